//! `glrt run -- wine PROGRAM.exe`: what Wine needs to draw a Windows OpenGL program with glrt.
//!
//! Wine's `opengl32` hands OpenGL to its X11 driver, which loads the host's `libGL.so.1` (so
//! `glrt run`'s search path reaches glrt) as long as it uses GLX. From Wine 10.17 on, the X11
//! driver uses EGL by default and never loads `libGL.so.1`; its registry value
//! `HKEY_CURRENT_USER\Software\Wine\X11 Driver` `UseEGL` = `N` (read by `winex11.drv`'s
//! `x11drv_main.c`) turns GLX back on, and older versions ignore it. So when the program is
//! Wine, the value is set in the program's Wine prefix (`WINEPREFIX`, else `~/.wine`) unless
//! the prefix's `user.reg` already has it, with `wine reg add`, saying so once on stderr.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The registry key Wine's X11 driver reads its settings from (`HKEY_CURRENT_USER`).
const X11_DRIVER_KEY: &str = r"HKCU\Software\Wine\X11 Driver";

/// Whether `program` is Wine's launcher (`wine`, `wine64`, `wine-stable`, `wine-development`...).
pub fn is_wine(program: &OsStr) -> bool {
    let name = Path::new(program).file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    name == "wine" || name == "wine64" || name.starts_with("wine-")
}

/// Makes sure the Wine prefix the program will use has `UseEGL` = `N`: runs `wine reg add` (the
/// launcher `wine` given) when its `user.reg` does not say so already.
pub fn use_glx(wine: &OsStr) -> Result<(), String> {
    let prefix = prefix();
    if prefix.as_ref().is_some_and(|p| has_use_egl_off(&std::fs::read_to_string(p.join("user.reg")).unwrap_or_default())) {
        return Ok(());
    }
    let shown = prefix.as_ref().map_or_else(|| "the Wine prefix".to_owned(), |p| p.display().to_string());
    eprintln!("glrt: Wine: setting {X11_DRIVER_KEY} UseEGL=N in {shown}, so that Wine draws OpenGL through GLX and libGL.so.1 (Wine 10.17 and later use EGL otherwise)");
    let status = Command::new(wine)
        .args(["reg", "add", X11_DRIVER_KEY, "/v", "UseEGL", "/t", "REG_SZ", "/d", "N", "/f"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .status()
        .map_err(|e| format!("cannot run {} reg add: {e}", Path::new(wine).display()))?;
    if !status.success() {
        return Err(format!("{} reg add {X11_DRIVER_KEY} /v UseEGL failed ({status})", Path::new(wine).display()));
    }
    Ok(())
}

/// The prefix Wine will use: `WINEPREFIX`, else `~/.wine`.
fn prefix() -> Option<PathBuf> {
    let from = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    from("WINEPREFIX").or_else(|| from("HOME").map(|home| home.join(".wine")))
}

/// Whether a `user.reg` (Wine's text form of the registry) has `"UseEGL"="N"` in its
/// `Software\Wine\X11 Driver` key.
fn has_use_egl_off(user_reg: &str) -> bool {
    let mut in_key = false;
    for line in user_reg.lines() {
        if line.starts_with('[') {
            in_key = line.to_ascii_lowercase().starts_with(r"[software\\wine\\x11 driver]");
        } else if in_key && line.trim().eq_ignore_ascii_case(r#""UseEGL"="N""#) {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::{has_use_egl_off, is_wine};
    use std::ffi::OsStr;

    #[test]
    fn wine_is_known_by_its_launcher_name() {
        for wine in ["wine", "/usr/bin/wine", "wine64", "/opt/wine-stable/bin/wine-stable", "wine-development"] {
            assert!(is_wine(OsStr::new(wine)), "{wine}");
        }
        for other in ["/usr/bin/glxgears", "wineserver", "winecfg", "/home/u/wine/game"] {
            assert!(!is_wine(OsStr::new(other)), "{other}");
        }
    }

    #[test]
    fn the_value_is_read_from_the_x11_driver_key_only() {
        let set = "[Software\\\\Wine\\\\X11 Driver] 1795756515\n#time=1dd7e2e4944e452\n\"UseEGL\"=\"N\"\n";
        assert!(has_use_egl_off(set));
        assert!(!has_use_egl_off(&set.replace("\"N\"", "\"Y\"")));
        assert!(!has_use_egl_off("[Software\\\\Wine\\\\Direct3D] 1\n\"UseEGL\"=\"N\"\n"));
        assert!(!has_use_egl_off(""));
    }
}

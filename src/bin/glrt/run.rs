//! `glrt run [OPTIONS] -- PROGRAM ARGS...`: runs a program on glrt, as a wrapper command
//! (`glrt run -- %command%` in a Steam game's launch options, like `mangohud %command%`).
//!
//! How the program finds glrt, whatever it would have loaded:
//! - a directory holding `libGL.so.1` → glrt's library goes first in `LD_LIBRARY_PATH`: programs
//!   linked with `libGL.so.1`, and those that `dlopen("libGL.so.1")` (old games, SDL 1.2, Wine's
//!   `opengl32`), load glrt instead of the system's;
//! - the same directory holds `libGLX_glrt.so.0` → the library, and
//!   `__GLX_VENDOR_LIBRARY_NAME=glrt`: programs linked with glvnd's `libGLX.so.0` and
//!   `libOpenGL.so.0` (GLFW, SDL 2) get glrt as their GLX vendor.
//!
//! The directory is `glrt/lib-HASH` in the user's cache directory (`$XDG_CACHE_HOME`, else
//! `~/.cache`, else the temporary directory), HASH naming the library's path, so it stays valid
//! for the program's whole life: the command then becomes the program (`exec`), and Steam,
//! shells and signals see the program itself. The library is the `libglrt.so` beside the
//! `glrt` command (where `cargo build` puts both).
//!
//! The options become glrt's variables (`GLRT_MODE`, `GLRT_CONFIG`, `GLRT_CAPTURE`,
//! `GLRT_TRACE`, `GLRT_DEVICE`, `GLRT_HUD`); the command says once on stderr which device and
//! mode the program's frames will get ([`glrt::render::devices`]). When the program is Wine,
//! its prefix gets the registry value that keeps Wine on GLX ([`crate::wine`]).

use std::ffi::OsString;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};

use crate::wine;
use glrt::render::devices;

/// The arguments of `glrt run`.
#[derive(clap::Args)]
pub struct Args {
    /// How frames are rendered (GLRT_MODE; unset: path traced on a GPU, rasterized on a CPU).
    #[arg(long, value_enum)]
    mode: Option<Mode>,
    /// The glrt.toml to use (GLRT_CONFIG; default: glrt.toml beside the program).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Records every GL call to FILE, for `glrt replay` (GLRT_CAPTURE).
    #[arg(long, value_name = "FILE")]
    capture: Option<PathBuf>,
    /// Writes the call log to FILE (GLRT_TRACE).
    #[arg(long, value_name = "FILE")]
    trace: Option<PathBuf>,
    /// The Vulkan device: its index or a part of its name, as `glrt info` lists them
    /// (GLRT_DEVICE).
    #[arg(long, value_name = "DEVICE")]
    device: Option<String>,
    /// Draws frame times, a frame-time graph, frames per second, mode, device, draws per class
    /// and rays per second over the image (GLRT_HUD=1).
    #[arg(long)]
    hud: bool,
    /// The program and its arguments (after `--`, so that its options are not taken for
    /// glrt's).
    #[arg(required = true, trailing_var_arg = true, value_name = "PROGRAM ARGS")]
    command: Vec<OsString>,
}

/// `--mode`.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Mode {
    /// Everything rasterized: a faithful OpenGL 1.x on Vulkan.
    Raster,
    /// Opaque geometry path traced, the sky, translucent and 2D draws rasterized around it.
    Pathtrace,
}

/// Sets up the environment and becomes the program; returns only when it cannot be run.
pub fn run(args: &Args) -> Result<(), String> {
    let library = library()?;
    let dir = link_dir(&library)?;
    let mut variables: Vec<(&str, OsString)> = vec![
        ("LD_LIBRARY_PATH", prepend_path(&dir, std::env::var_os("LD_LIBRARY_PATH"))),
        ("__GLX_VENDOR_LIBRARY_NAME", "glrt".into()),
    ];
    if let Some(mode) = args.mode {
        variables.push(("GLRT_MODE", if matches!(mode, Mode::Raster) { "raster" } else { "pathtrace" }.into()));
    }
    if let Some(config) = &args.config {
        let config = config.canonicalize().map_err(|e| format!("--config {}: {e}", config.display()))?;
        variables.push(("GLRT_CONFIG", config.into()));
    }
    for (flag, variable, file) in [("--capture", "GLRT_CAPTURE", &args.capture), ("--trace", "GLRT_TRACE", &args.trace)] {
        if let Some(file) = file {
            // Absolute: the program may change its working directory.
            let file = std::path::absolute(file).map_err(|e| format!("{flag} {}: {e}", file.display()))?;
            variables.push((variable, file.into()));
        }
    }
    if let Some(device) = &args.device {
        variables.push(("GLRT_DEVICE", device.into()));
    }
    if args.hud {
        variables.push(("GLRT_HUD", "1".into()));
    }
    let (program, program_args) = args.command.split_first().ok_or("no program given")?;
    if wine::is_wine(program) {
        wine::use_glx(program)?;
    }
    for (name, value) in &variables {
        // Safety: single-threaded; the survey below and the program read them.
        unsafe { std::env::set_var(name, value) };
    }
    eprintln!("glrt: {} {}", Path::new(program).display(), rendering());
    let error = std::process::Command::new(program).args(program_args).exec();
    Err(format!("cannot run {}: {error}", Path::new(program).display()))
}

/// `on DEVICE, mode M`, or why frames will not be drawn.
fn rendering() -> String {
    match devices::survey() {
        Ok(list) => match list.iter().find(|d| d.chosen) {
            Some(d) if d.unusable.is_none() => format!("on {} ({}), mode {}", d.name, d.kind, d.rendering),
            Some(d) => format!("on {}: not usable by glrt ({}): frames will not be drawn", d.name, d.unusable.as_deref().unwrap_or_default()),
            None => "on no Vulkan device (none, or GLRT_DEVICE matches none: see `glrt info`): frames will not be drawn".to_owned(),
        },
        Err(e) => format!("without Vulkan ({e}): frames will not be drawn"),
    }
}

/// glrt's library: `libglrt.so` beside this command.
fn library() -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find the glrt command's own path: {e}"))?;
    let library = exe.with_file_name("libglrt.so");
    library.canonicalize().map_err(|e| {
        format!("{}: {e} (glrt run uses the libglrt.so built beside the glrt command: `cargo build` puts both in target/<profile>/)", library.display())
    })
}

/// The directory of `libGL.so.1` and `libGLX_glrt.so.0`, both links to `library` (made if
/// missing or pointing elsewhere; each link is made under a temporary name and renamed over,
/// so programs started at the same time never see a missing or half-made one).
fn link_dir(library: &Path) -> Result<PathBuf, String> {
    let cache = glrt::config::cache_dir();
    let hash = xxhash_rust::xxh3::xxh3_64(library.as_os_str().as_encoded_bytes());
    let dir = cache.join("glrt").join(format!("lib-{hash:016x}"));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for name in ["libGL.so.1", "libGLX_glrt.so.0"] {
        let link = dir.join(name);
        if std::fs::read_link(&link).is_ok_and(|target| target == library) {
            continue;
        }
        let temporary = dir.join(format!(".{name}.{}", std::process::id()));
        let _ = std::fs::remove_file(&temporary);
        std::os::unix::fs::symlink(library, &temporary)
            .and_then(|()| std::fs::rename(&temporary, &link))
            .map_err(|e| format!("{}: {e}", link.display()))?;
    }
    Ok(dir)
}

/// `dir` in front of the search path `old` (colon-separated; empty entries dropped: they mean
/// the working directory).
fn prepend_path(dir: &Path, old: Option<OsString>) -> OsString {
    let old = old.unwrap_or_default();
    let mut paths = vec![dir.to_path_buf()];
    paths.extend(std::env::split_paths(&old).filter(|p| !p.as_os_str().is_empty() && p != dir));
    std::env::join_paths(paths).unwrap_or_else(|_| dir.as_os_str().to_owned())
}

#[cfg(test)]
mod tests {
    use super::prepend_path;
    use std::path::Path;

    #[test]
    fn glrt_goes_first_in_the_search_path_once() {
        let dir = Path::new("/c/glrt/lib-1");
        assert_eq!(prepend_path(dir, None), "/c/glrt/lib-1");
        assert_eq!(prepend_path(dir, Some("/opt/lib::/c/glrt/lib-1:/usr/lib".into())), "/c/glrt/lib-1:/opt/lib:/usr/lib");
    }
}

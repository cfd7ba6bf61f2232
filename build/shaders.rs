//! Compiles every GLSL shader in `shaders/` (`*.vert`, `*.frag`, `*.comp`, `*.geom`) to SPIR-V
//! with `glslangValidator` (Debian's `glslang-tools`, installed by `scripts/setup.sh`), into
//! `OUT_DIR/shaders/<file name>.spv`; the renderer embeds them with
//! `include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.vert.spv"))`. Files included by others
//! end in `.glsl` and are not compiled on their own.

use std::path::Path;
use std::process::Command;

/// Stages compiled, by file extension.
const STAGES: &[&str] = &["vert", "frag", "comp", "geom"];

/// Compiles `shaders/*` into `out/shaders/`; panics with the compiler's message (the build
/// fails) when a shader does not compile or the compiler is missing.
pub fn compile_all(out: &Path) {
    println!("cargo:rerun-if-changed=shaders");
    let dest = out.join("shaders");
    std::fs::create_dir_all(&dest).expect("creating OUT_DIR/shaders");
    let mut sources: Vec<_> = std::fs::read_dir("shaders")
        .expect("reading shaders/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().and_then(|e| e.to_str()).is_some_and(|e| STAGES.contains(&e)))
        .collect();
    sources.sort();
    for src in sources {
        let name = src.file_name().and_then(|n| n.to_str()).expect("shader file name");
        let spv = dest.join(format!("{name}.spv"));
        let output = Command::new("glslangValidator")
            .args(["-V", "--target-env", "vulkan1.1", "-Ishaders", "-o"])
            .arg(&spv)
            .arg(&src)
            .output()
            .unwrap_or_else(|e| {
                panic!("glslangValidator not found ({e}): install it with `apt-get install glslang-tools` (scripts/setup.sh does)")
            });
        if !output.status.success() {
            panic!(
                "shader {} does not compile:\n{}{}",
                src.display(),
                String::from_utf8_lossy(&output.stdout),
                String::from_utf8_lossy(&output.stderr)
            );
        }
    }
}

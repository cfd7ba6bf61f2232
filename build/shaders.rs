//! Compiles every GLSL shader in `shaders/` and its folders (`*.vert`, `*.frag`, `*.comp`,
//! `*.geom`, and the ray-tracing stages `*.rgen`, `*.rchit`, `*.rahit`, `*.rmiss`) to SPIR-V
//! with `glslangValidator` (Debian's `glslang-tools`, installed by `scripts/setup.sh`), into
//! `OUT_DIR/shaders/<path under shaders/>.spv` (`OUT_DIR/shaders/denoise/atrous.comp.spv`);
//! the renderer embeds them with
//! `include_bytes!(concat!(env!("OUT_DIR"), "/shaders/ff.vert.spv"))`. Files included by others
//! end in `.glsl` and are not compiled on their own; the generated headers of
//! `glsl_constants.rs` are on the include path.
//!
//! Then checks the Rust mirrors of [`LAYOUTS`] against the compiled SPIR-V
//! (`spirv_layout.rs`): each entry becomes `OUT_DIR/layouts/<name>.rs`, `const` assertions
//! that the module holding the mirrors includes.

use std::path::Path;
use std::process::Command;

use crate::spirv_layout::{self, Mirror, Rust};

/// Stages compiled, by file extension.
const STAGES: &[&str] = &["vert", "frag", "comp", "geom", "rgen", "rchit", "rahit", "rmiss"];
/// The ray-tracing stages, compiled for Vulkan 1.2 (SPIR-V 1.4, which `GL_EXT_ray_tracing`
/// needs); the others for Vulkan 1.1.
const RAY_TRACING_STAGES: &[&str] = &["rgen", "rchit", "rahit", "rmiss"];

/// A generated file of layout assertions: its name and, per shader, the mirrors checked
/// against that shader's SPIR-V.
struct LayoutFile {
    name: &'static str,
    shaders: &'static [(&'static str, &'static [Mirror])],
}

const fn mirror(glsl: &'static str, rust: Rust) -> Mirror {
    Mirror { glsl, rust }
}

/// The fixed-function uniform block and its structs (both stages declare them).
const FF_UNIFORMS: &[Mirror] = &[
    mirror("FF", Rust::Struct("FfBlock")),
    mirror("Material", Rust::Struct("FfMaterial")),
    mirror("Light", Rust::Struct("FfLight")),
    mirror("HeightFog", Rust::Struct("GpuHeightFog")),
];

/// Every struct Rust shares with the shaders, by the module that includes its assertions.
const LAYOUTS: &[LayoutFile] = &[
    // render::trace::gpu_types
    LayoutFile {
        name: "trace_gpu_types",
        shaders: &[
            (
                "pathtrace.comp",
                &[
                    mirror("TraceFrameBlock", Rust::Struct("GpuFrame")),
                    mirror("Corner", Rust::Struct("GpuCorner")),
                    mirror("TriangleAttributes", Rust::Struct("GpuTriangleAttributes")),
                    mirror("Layer", Rust::Struct("GpuLayer")),
                    mirror("LayerCorners", Rust::Struct("GpuLayerCorners")),
                    mirror("Material", Rust::Struct("GpuMaterial")),
                    mirror("Emitter", Rust::Struct("GpuEmitter")),
                    mirror("RadiosityTriangle", Rust::Struct("GpuRadiosityTriangle")),
                    mirror("Light", Rust::Struct("GpuLight")),
                    mirror("Instance", Rust::Struct("GpuInstance")),
                    mirror("Counters", Rust::Struct("GpuCounters")),
                    mirror("GSample", Rust::SizeConstant("GSAMPLE_BYTES")),
                ],
            ),
            ("trace_resolve.comp", &[mirror("AccumSample", Rust::SizeConstant("ACCUM_SAMPLE_BYTES")), mirror("OutputSample", Rust::SizeConstant("OUTPUT_SAMPLE_BYTES"))]),
        ],
    },
    // render::trace::texels
    LayoutFile { name: "trace_texels", shaders: &[("pathtrace.comp", &[mirror("GpuTexture", Rust::Struct("GpuTexture"))])] },
    // render::trace::bvh
    LayoutFile {
        name: "trace_bvh",
        shaders: &[(
            "pathtrace_binary.comp",
            &[mirror("BvhNode", Rust::Struct("GpuNode")), mirror("BvhChild", Rust::Struct("GpuChild")), mirror("BvhTriangle", Rust::Struct("GpuTriangle"))],
        )],
    },
    // render::trace::bvh::wide
    LayoutFile { name: "trace_bvh_wide", shaders: &[("pathtrace.comp", &[mirror("BvhWideNode", Rust::Struct("GpuWideNode"))])] },
    // render::trace::pipelines
    LayoutFile {
        name: "trace_push_constants",
        shaders: &[
            ("pathtrace.comp", &[mirror("Pass", Rust::SizeConstant("TRACE_PUSH_BYTES"))]),
        ],
    },
    // render::denoise::pipelines and render::denoise
    LayoutFile {
        name: "denoise_gpu_types",
        shaders: &[
            (
                "denoise/temporal.comp",
                &[
                    mirror("DenoisePass", Rust::Struct("DenoisePass")),
                    mirror("HistoryLight", Rust::SizeConstant("HISTORY_LIGHT_BYTES")),
                    mirror("HistoryMoments", Rust::SizeConstant("HISTORY_MOMENTS_BYTES")),
                    mirror("Guide", Rust::SizeConstant("GUIDE_BYTES")),
                    mirror("HistorySpecular", Rust::SizeConstant("HISTORY_SPECULAR_BYTES")),
                ],
            ),
            ("denoise/atrous.comp", &[mirror("Signal", Rust::SizeConstant("SIGNAL_BYTES")), mirror("SpecularSignal", Rust::SizeConstant("SPECULAR_SIGNAL_BYTES"))]),
            ("denoise/gradient.comp", &[mirror("Gradient", Rust::SizeConstant("GRADIENT_BYTES"))]),
        ],
    },
    // render::radiosity::gpu::scene
    LayoutFile {
        name: "radiosity_scene_types",
        shaders: &[
            ("radiosity/form_factors.comp", &[mirror("Patch", Rust::Struct("GpuPatch")), mirror("PatchTriangle", Rust::Struct("GpuPatchTriangle"))]),
            ("radiosity/direct.comp", &[mirror("Patch", Rust::Struct("GpuPatch")), mirror("PatchTriangle", Rust::Struct("GpuPatchTriangle"))]),
        ],
    },
    // render::radiosity::gpu::form_factors
    LayoutFile { name: "radiosity_gpu_types", shaders: &[("radiosity/form_factors.comp", &[mirror("FormFactorPass", Rust::Struct("GpuPass"))])] },
    // render::radiosity::gpu::direct
    LayoutFile {
        name: "radiosity_direct_types",
        shaders: &[(
            "radiosity/direct.comp",
            &[
                mirror("Light", Rust::Struct("GpuLight")),
                mirror("PatchSurface", Rust::Struct("GpuPatchSurface")),
                mirror("PatchLight", Rust::Struct("GpuPatchLight")),
                mirror("DirectPass", Rust::Struct("GpuDirectPass")),
            ],
        )],
    },
    // render::radiosity::gpu::product
    LayoutFile { name: "radiosity_product_types", shaders: &[("radiosity/product.comp", &[mirror("ProductPass", Rust::Struct("GpuProductPass"))])] },
    // render::radiosity::gpu::gather
    LayoutFile {
        name: "radiosity_gather_types",
        shaders: &[("radiosity/gather.comp", &[mirror("SparseEntry", Rust::Struct("GpuSparseEntry")), mirror("GatherPass", Rust::Struct("GpuGatherPass"))])],
    },
    // render::trace::composite
    LayoutFile {
        name: "trace_composite",
        shaders: &[("trace_composite.frag", &[mirror("Sizes", Rust::SizeConstant("PUSH_BYTES")), mirror("HeightFog", Rust::Struct("GpuHeightFog"))])],
    },
    // render::ao
    LayoutFile { name: "ao_gpu_types", shaders: &[("ao/ssao.comp", &[mirror("AoParams", Rust::Struct("GpuAoParams"))])] },
    // render::raster::ff::uniforms
    LayoutFile { name: "ff_uniforms", shaders: &[("ff.vert", FF_UNIFORMS), ("ff.frag", FF_UNIFORMS)] },
];

/// The shaders under `dir` and its folders (`shaders/denoise/*.comp`), by extension.
fn collect_sources(dir: &Path, sources: &mut Vec<std::path::PathBuf>) {
    for path in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display())).filter_map(|e| e.ok().map(|e| e.path())) {
        if path.is_dir() {
            collect_sources(&path, sources);
        } else if path.extension().and_then(|e| e.to_str()).is_some_and(|e| STAGES.contains(&e)) {
            sources.push(path);
        }
    }
}

/// Compiles `shaders/*` (and its folders) into `out/shaders/` with `include` (the generated headers) on the
/// include path, then writes the layout assertions into `out/layouts/`; panics with the
/// compiler's or the checker's message (the build fails) when a shader does not compile, the
/// compiler is missing or a mirrored struct cannot be found or mirrored.
pub fn compile_all(out: &Path, include: &Path) {
    println!("cargo:rerun-if-changed=shaders");
    let dest = out.join("shaders");
    std::fs::create_dir_all(&dest).expect("creating OUT_DIR/shaders");
    let mut sources = Vec::new();
    collect_sources(Path::new("shaders"), &mut sources);
    sources.sort();
    for src in sources {
        let name = src.strip_prefix("shaders").expect("a shader under shaders/").to_str().expect("shader file name");
        let spv = dest.join(format!("{name}.spv"));
        let ray_tracing = src.extension().and_then(|e| e.to_str()).is_some_and(|e| RAY_TRACING_STAGES.contains(&e));
        if let Some(dir) = spv.parent() {
            std::fs::create_dir_all(dir).expect("creating a folder of OUT_DIR/shaders");
        }
        let output = Command::new("glslangValidator")
            .args(["-V", "--target-env", if ray_tracing { "vulkan1.2" } else { "vulkan1.1" }, "-Ishaders"])
            .arg(format!("-I{}", include.display()))
            .arg("-o")
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
    let layouts = out.join("layouts");
    std::fs::create_dir_all(&layouts).expect("creating OUT_DIR/layouts");
    for file in LAYOUTS {
        let mut text = String::from("// Generated by build/shaders.rs from the compiled SPIR-V: the layouts Rust mirrors.\n");
        for (shader, mirrors) in file.shaders {
            let spirv = std::fs::read(dest.join(format!("{shader}.spv"))).expect("reading compiled SPIR-V");
            let module = spirv_layout::Module::decode(&spirv).unwrap_or_else(|e| panic!("{shader}.spv: {e}"));
            text += &spirv_layout::assertions(&module, shader, mirrors).unwrap_or_else(|e| panic!("layouts {}: {e}", file.name));
        }
        std::fs::write(layouts.join(format!("{}.rs", file.name)), text).expect("writing layout assertions");
    }
}

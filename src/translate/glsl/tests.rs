//! Compiling and linking real GLSL 1.10/1.20 programs: what the link reports and that the
//! rewrite compiles to SPIR-V laid out as reported.

use std::collections::HashMap;

use super::*;
use crate::frame::program::SamplerKind;
use crate::render::shader_abi::spirv_layout::Module;

fn compiled(stage: Stage, src: &str) -> CompiledShader {
    let c = compile(stage, src);
    assert!(c.ok, "{stage:?} shader does not compile:\n{}", c.log);
    c
}

fn linked(shaders: &[&CompiledShader]) -> LinkedProgram {
    let p = link(shaders, &HashMap::new());
    assert!(p.ok, "link failed:\n{}", p.log);
    p
}

/// `member name → Offset` of the block type `block` in SPIR-V words.
fn block_offsets(words: &[u32], block: &str) -> HashMap<String, u32> {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let layout = Module::decode(&bytes).and_then(|m| m.layout(block)).unwrap_or_else(|e| panic!("{block}: {e}"));
    layout.members.into_iter().map(|m| (m.name, m.offset)).collect()
}

#[test]
fn piglit_teximage_colors_fragment_shaders_link() {
    for src in [
        "uniform sampler2D tex; \nvoid main() \n{ \n\tgl_FragColor = texture2D(tex, gl_TexCoord[0].xy);\n} \n",
        "uniform sampler2D tex; \nvoid main() \n{ \n\tgl_FragColor = 0.5 + 0.5 * texture2D(tex, gl_TexCoord[0].xy);\n} \n",
    ] {
        let fs = compiled(Stage::Fragment, src);
        let p = linked(&[&fs]);
        let exe = p.executable.unwrap();
        assert!(exe.vertex.is_none());
        assert_eq!(exe.fragment.as_ref().unwrap()[0], 0x0723_0203);
        assert_eq!(exe.samplers, vec![SamplerKind::D2]);
        assert_eq!(p.uniforms.len(), 1);
        assert_eq!((p.uniforms[0].name.as_str(), p.uniforms[0].ty), ("tex", 0x8B5E));
        assert_eq!(p.uniforms[0].storage, UniformStorage::Sampler { first_slot: 0 });
    }
}

const LIT_VS: &str = "
struct Material { vec4 tint; float gain[2]; };
uniform Material material;
uniform mat3 warp;
uniform float texture;     // a 4.50 built-in function's name, legal in 1.10
attribute vec3 tangent;
attribute mat2 shear;
varying vec3 light_dir;
varying vec2 uv[2];
void main() {
    gl_Position = ftransform();
    vec3 n = gl_NormalMatrix * gl_Normal;
    light_dir = normalize(gl_LightSource[0].position.xyz) + tangent * texture + vec3(shear[1], 0.0);
    uv[0] = gl_MultiTexCoord0.st;
    uv[1] = (warp * vec3(gl_MultiTexCoord1.st, 1.0)).xy;
    gl_FrontColor = gl_Color * material.tint * material.gain[1] * max(dot(n, light_dir), 0.0);
    gl_TexCoord[0] = gl_TextureMatrix[0] * gl_MultiTexCoord0;
}
";

const LIT_FS: &str = "
uniform sampler2D base;
uniform sampler2DShadow shadow;
uniform samplerCube sky;
uniform vec4 fog_tint;
varying vec3 light_dir;
varying vec2 uv[2];
void main() {
    vec4 lit = gl_Color * texture2D(base, uv[0]) * shadow2DProj(shadow, gl_TexCoord[0]);
    lit += textureCube(sky, light_dir) * fog_tint + texture2D(base, uv[1], 1.0);
    gl_FragColor = mix(gl_Fog.color, lit, clamp((gl_Fog.end - gl_FogFragCoord) * gl_Fog.scale, 0.0, 1.0));
}
";

#[test]
fn a_lit_program_links_with_its_interface() {
    let vs = compiled(Stage::Vertex, LIT_VS);
    let fs = compiled(Stage::Fragment, LIT_FS);
    let mut bindings = HashMap::new();
    bindings.insert("shear".to_string(), 6);
    let p = link(&[&vs, &fs], &bindings);
    assert!(p.ok, "{}", p.log);
    let exe = p.executable.as_ref().unwrap();
    assert_eq!(exe.samplers, vec![SamplerKind::D2, SamplerKind::D2Shadow, SamplerKind::Cube]);
    // tangent takes the lowest free index; shear its binding and the next index for column 1.
    let attrs: Vec<_> = p.attributes.iter().map(|a| (a.name.as_str(), a.ty, a.index)).collect();
    assert_eq!(attrs, vec![("tangent", 0x8B51, 1), ("shear", 0x8B5A, 6)]);
    assert_eq!(exe.attributes, vec![1, 6, 7]);
    // The reported block offsets are the ones glslang laid out.
    for words in [exe.vertex.as_ref().unwrap(), exe.fragment.as_ref().unwrap()] {
        let offsets = block_offsets(words, "GlrtUniforms");
        let material = offsets["u_material"];
        for u in &p.uniforms {
            let UniformStorage::Block { offset, .. } = u.storage else { continue };
            let expected = match u.name.as_str() {
                "material.tint" => material,
                "material.gain" => material + 16,
                name => offsets[&format!("u_{name}")],
            };
            assert_eq!(offset, expected, "{}", u.name);
        }
    }
    let names: Vec<_> = p.uniforms.iter().map(|u| u.name.as_str()).collect();
    assert_eq!(names, vec!["material.tint", "material.gain", "warp", "texture", "base", "shadow", "sky", "fog_tint"]);
}

#[test]
fn link_errors_are_reported_in_the_log() {
    let fs = compiled(Stage::Fragment, "varying vec3 n;\nvoid main() { gl_FragColor = vec4(n, 1.0); }\n");
    let p = link(&[&fs], &HashMap::new());
    assert!(!p.ok && p.log.contains("'n' is not written"), "{}", p.log);
    let vs = compiled(Stage::Vertex, "varying vec2 n;\nvoid main() { gl_Position = ftransform(); n = vec2(1.0); }\n");
    let p = link(&[&vs, &fs], &HashMap::new());
    assert!(!p.ok && p.log.contains("different types"), "{}", p.log);
    let no_main = compiled(Stage::Vertex, "float f(float x) { return x; }\n");
    assert!(link(&[&no_main], &HashMap::new()).log.contains("no main"));
    let bad = compile(Stage::Fragment, "void main() { gl_FragColor = vec4(undeclared); }\n");
    assert!(!bad.ok && bad.log.contains("undeclared"), "{}", bad.log);
}

//! The built-in uniform state block of programs (`shaders/glsl_builtins.glsl`, std430),
//! packed from the context state of a draw as section 7.5 of the GLSL 1.10 specification
//! defines each `gl_` value: matrices and their inverses and transposes, the normal matrix
//! and scale, depth range, clip planes (eye space, by index, enabled or not), point
//! parameters, materials, lights (by index, enabled or not) and their products with the
//! materials, texture environment colours, texture coordinate generation planes, fog; then
//! glrt's own per-sampler-slot depth comparison words.

use glam::{Mat3, Mat4, Vec3, Vec4};

use crate::frame::program::MAX_SAMPLERS;
use crate::frame::state::{Light, Material};
use crate::translate::Context;
use crate::translate::gl::{self, GLenum};
use crate::translate::limits::{MAX_CLIP_PLANES, MAX_LIGHTS, MAX_TEXTURE_UNITS};

/// Texture coordinate sets of the block (`glrt_MaxTextureCoords`, one per texture unit).
const MAX_TEXTURE_COORDS: usize = MAX_TEXTURE_UNITS;

/// A std430 block being written member by member: each member at the next offset its
/// alignment allows.
#[derive(Default)]
pub(crate) struct Std430 {
    /// The bytes so far.
    pub bytes: Vec<u8>,
}

impl Std430 {
    /// Pads to a multiple of `align` bytes (a struct's start and end, a vector's start).
    pub fn align(&mut self, align: usize) {
        let len = self.bytes.len().next_multiple_of(align);
        self.bytes.resize(len, 0);
    }
    /// A `float`.
    pub fn float(&mut self, v: f32) {
        self.align(4);
        self.bytes.extend_from_slice(&v.to_ne_bytes());
    }
    /// A `uint`.
    pub fn uint(&mut self, v: u32) {
        self.align(4);
        self.bytes.extend_from_slice(&v.to_ne_bytes());
    }
    /// A `vec3` (16-byte aligned, 12 bytes).
    pub fn vec3(&mut self, v: [f32; 3]) {
        self.align(16);
        v.iter().for_each(|&x| self.float(x));
    }
    /// A `vec4`.
    pub fn vec4(&mut self, v: [f32; 4]) {
        self.align(16);
        v.iter().for_each(|&x| self.float(x));
    }
    /// A `uvec4`.
    pub fn uvec4(&mut self, v: [u32; 4]) {
        self.align(16);
        v.iter().for_each(|&x| self.uint(x));
    }
    /// A `mat4`, column by column.
    pub fn mat4(&mut self, m: Mat4) {
        m.to_cols_array_2d().iter().for_each(|&c| self.vec4(c));
    }
    /// A `mat3`: three `vec3` columns, each 16 bytes apart.
    pub fn mat3(&mut self, m: Mat3) {
        m.to_cols_array_2d().iter().for_each(|&c| self.vec3(c));
        self.align(16);
    }
}

/// A double-precision plane as `vec4`.
fn plane(p: [f64; 4]) -> [f32; 4] {
    p.map(|x| x as f32)
}

/// Component-wise product of two colours (alpha: the material's, section 7.5's products).
fn product(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
    (Vec4::from(a) * Vec4::from(b)).to_array()
}

/// The comparison word of `glrt_SamplerDepth.x`: the order NEVER, LESS, EQUAL, LEQUAL,
/// GREATER, NOTEQUAL, GEQUAL, ALWAYS; 8 when the texture does not compare.
fn compare_word(mode: GLenum, func: GLenum) -> u32 {
    if mode == gl::GL_NONE { 8 } else { func.wrapping_sub(gl::GL_NEVER).min(8) }
}

/// The depth-texture mode word of `glrt_SamplerDepth.y`.
fn depth_mode_word(mode: GLenum) -> u32 {
    match mode {
        gl::GL_INTENSITY => 1,
        gl::GL_ALPHA => 2,
        _ => 0,
    }
}

/// `glrt_SamplerDepth` of one sampler slot: `(compare, depth mode, is depth, 0)` of the
/// texture it samples.
pub(crate) type SamplerDepth = [u32; 4];

/// The depth words of a texture with these parameters and base format.
pub(crate) fn sampler_depth(compare_mode: GLenum, compare_func: GLenum, depth_mode: GLenum, depth: bool) -> SamplerDepth {
    [compare_word(compare_mode, compare_func), depth_mode_word(depth_mode), u32::from(depth), 0]
}

impl Context {
    /// The built-in state block for a draw now, with the depth words of its sampler slots.
    pub(crate) fn pack_builtins(&self, sampler_depth: &[SamplerDepth]) -> Vec<u8> {
        let point_size_from_shader = self.enables.is_on(gl::GL_VERTEX_PROGRAM_POINT_SIZE);
        let mut b = Std430::default();
        let t = &self.transform;
        let (mv, p) = (t.modelview(), t.projection());
        let mvp = p * mv;
        for m in [mv, p, mvp] {
            b.mat4(m);
        }
        for m in [mv, p, mvp] {
            b.mat4(m.inverse());
        }
        for m in [mv, p, mvp] {
            b.mat4(m.transpose());
        }
        for m in [mv, p, mvp] {
            b.mat4(m.inverse().transpose());
        }
        let tex: [Mat4; MAX_TEXTURE_COORDS] = std::array::from_fn(|u| if u < MAX_TEXTURE_UNITS { t.texture_matrix(u) } else { Mat4::IDENTITY });
        for f in [|m: Mat4| m, |m: Mat4| m.inverse(), |m: Mat4| m.transpose(), |m: Mat4| m.inverse().transpose()] {
            tex.iter().for_each(|&m| b.mat4(f(m)));
        }
        // gl_NormalMatrix: the upper 3x3 of the modelview's inverse, transposed (section
        // 2.11.3 transforms normals by the inverse of the whole matrix, as Mesa does).
        let inverse = mv.inverse();
        b.mat3(Mat3::from_mat4(inverse).transpose());
        // gl_NormalScale: the rescale factor of section 2.11.3, from the inverse's third row.
        b.float(1.0 / Vec3::new(inverse.x_axis.z, inverse.y_axis.z, inverse.z_axis.z).length());
        let [near, far] = self.viewport.depth_range.map(|v| v as f32);
        b.align(4);
        [near, far, far - near].iter().for_each(|&x| b.float(x));
        b.align(4);
        for i in 0..MAX_CLIP_PLANES {
            b.vec4(plane(self.fixed.clip_planes[i]));
        }
        let pt = &self.fixed.raster.point;
        for x in [pt.size, pt.size_min, pt.size_max, pt.fade_threshold, pt.attenuation[0], pt.attenuation[1], pt.attenuation[2]] {
            b.float(x);
        }
        let lighting = &self.fixed.lighting;
        for m in &lighting.materials {
            pack_material(&mut b, m);
        }
        for l in &lighting.lights {
            pack_light(&mut b, l);
        }
        b.vec4(lighting.model.ambient);
        b.align(16);
        for m in &lighting.materials {
            let scene = Vec4::from(m.emission) + Vec4::from(m.ambient) * Vec4::from(lighting.model.ambient);
            b.vec4([scene.x, scene.y, scene.z, m.diffuse[3]]);
        }
        for m in &lighting.materials {
            for l in lighting.lights.iter().take(MAX_LIGHTS) {
                b.vec4(product(l.ambient, m.ambient));
                b.vec4(product(l.diffuse, m.diffuse));
                b.vec4(product(l.specular, m.specular));
            }
        }
        let texture = &self.texture;
        for u in 0..MAX_TEXTURE_UNITS {
            b.vec4(texture.env[u].color);
        }
        for eye in [true, false] {
            for c in 0..4 {
                for u in 0..MAX_TEXTURE_COORDS {
                    let g = texture.texgen[u].coords[c];
                    b.vec4(plane(if eye { g.eye_plane } else { g.object_plane }));
                }
            }
        }
        let fog = &self.fixed.fog.fog;
        b.vec4(fog.color);
        for x in [fog.density, fog.start, fog.end, 1.0 / (fog.end - fog.start)] {
            b.float(x);
        }
        b.align(16);
        for i in 0..MAX_SAMPLERS {
            b.uvec4(sampler_depth.get(i).copied().unwrap_or([8, 0, 0, 0]));
        }
        b.uvec4([u32::from(point_size_from_shader), 0, 0, 0]);
        b.bytes
    }
}

/// One `glrt_MaterialParameters`.
fn pack_material(b: &mut Std430, m: &Material) {
    b.align(16);
    for c in [m.emission, m.ambient, m.diffuse, m.specular] {
        b.vec4(c);
    }
    b.float(m.shininess);
    b.align(16);
}

/// One `glrt_LightSourceParameters` (eye-space position and direction, as stored).
fn pack_light(b: &mut Std430, l: &Light) {
    b.align(16);
    for c in [l.ambient, l.diffuse, l.specular, l.position] {
        b.vec4(c);
    }
    let pos = Vec4::from(l.position);
    let half = if pos.w == 0.0 { (pos.truncate().normalize_or_zero() + Vec3::Z).normalize_or_zero() } else { Vec3::Z };
    b.vec4([half.x, half.y, half.z, 1.0]);
    b.vec3(l.spot_direction);
    b.float(l.spot_exponent);
    b.float(l.spot_cutoff);
    b.float(if l.spot_cutoff >= 180.0 { -1.0 } else { l.spot_cutoff.to_radians().cos() });
    l.attenuation.iter().for_each(|&a| b.float(a));
    b.align(16);
}

#[cfg(test)]
mod tests {
    use crate::render::shader_abi::spirv_layout::Module;
    use crate::translate::glsl::{Stage, compiler};
    use crate::translate::{Context, dispatch, gl};

    /// A fragment shader reading every member of the block, so that glslang keeps them all.
    fn block_spirv() -> Vec<u8> {
        let source = format!(
            "#version 450\n{}\nlayout(location = 0) out vec4 o;\nvoid main() {{ o = glrt_ModelViewMatrix[0] + vec4(glrt_NormalScale, \
             glrt_DepthRange.diff, glrt_Point.distanceQuadraticAttenuation, glrt_FrontMaterial.shininess) + glrt_ClipPlane[5] + \
             vec4(glrt_LightSource[7].quadraticAttenuation, glrt_LightSource[3].spotCosCutoff, glrt_Fog.scale, \
             float(glrt_SamplerDepth[7].z + glrt_Flags.x)) + glrt_BackLightProduct[7].specular + glrt_ObjectPlaneQ[3] + \
             glrt_TextureEnvColor[3] + glrt_BackLightModelProduct.sceneColor + glrt_LightModel.ambient + \
             vec4(glrt_NormalMatrix[2], 1.0) + glrt_TextureMatrixInverseTranspose[3][3]; }}\n",
            include_str!("../../../shaders/glsl_builtins.glsl")
        );
        let words = compiler::spirv(Stage::Fragment, &source).expect("the block compiles");
        words.iter().flat_map(|w| w.to_le_bytes()).collect()
    }

    #[test]
    fn limits_are_the_constants_of_the_block() {
        let (mut ctx, _) = Context::with_recording();
        let text = include_str!("../../../shaders/glsl_builtins.glsl");
        let constant = |name: &str| -> i32 {
            let line = text.lines().find(|l| l.starts_with(&format!("const int glrt_{name} "))).unwrap_or_else(|| panic!("{name}"));
            line.split('=').nth(1).unwrap().trim().trim_end_matches(';').parse().unwrap()
        };
        for (name, pname) in [
            ("MaxLights", gl::GL_MAX_LIGHTS),
            ("MaxClipPlanes", gl::GL_MAX_CLIP_PLANES),
            ("MaxTextureUnits", gl::GL_MAX_TEXTURE_UNITS),
            ("MaxTextureCoords", gl::GL_MAX_TEXTURE_COORDS),
            ("MaxVertexAttribs", gl::GL_MAX_VERTEX_ATTRIBS),
            ("MaxVertexUniformComponents", gl::GL_MAX_VERTEX_UNIFORM_COMPONENTS),
            ("MaxVaryingFloats", gl::GL_MAX_VARYING_FLOATS),
            ("MaxVertexTextureImageUnits", gl::GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS),
            ("MaxCombinedTextureImageUnits", gl::GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS),
            ("MaxTextureImageUnits", gl::GL_MAX_TEXTURE_IMAGE_UNITS),
            ("MaxFragmentUniformComponents", gl::GL_MAX_FRAGMENT_UNIFORM_COMPONENTS),
            ("MaxDrawBuffers", gl::GL_MAX_DRAW_BUFFERS),
        ] {
            let mut v = -1;
            unsafe { dispatch::glGetIntegerv(&mut ctx, pname, &mut v) };
            assert_eq!(v, constant(name), "{name}");
        }
    }

    fn f32_at(b: &[u8], at: usize) -> f32 {
        f32::from_ne_bytes(b[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn packed_values_sit_at_the_offsets_of_the_compiled_block() {
        let module = Module::decode(&block_spirv()).expect("SPIR-V");
        let at = |s: &str, m: &str| {
            let layout = module.layout(s).unwrap_or_else(|e| panic!("{s}: {e}"));
            layout.members.iter().find(|x| x.name == m).map(|x| x.offset as usize).unwrap_or_else(|| panic!("{s}.{m}: {layout:?}"))
        };
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glDepthRange(&mut ctx, 0.25, 0.75);
            dispatch::glClipPlane(&mut ctx, gl::GL_CLIP_PLANE5, [1.0, 2.0, 3.0, 4.0].as_ptr());
            dispatch::glPointSize(&mut ctx, 5.0);
            dispatch::glMaterialf(&mut ctx, gl::GL_FRONT, gl::GL_SHININESS, 7.0);
            dispatch::glLightf(&mut ctx, gl::GL_LIGHT7, gl::GL_QUADRATIC_ATTENUATION, 9.0);
            dispatch::glLightf(&mut ctx, gl::GL_LIGHT3, gl::GL_SPOT_CUTOFF, 60.0);
            dispatch::glFogf(&mut ctx, gl::GL_FOG_END, 3.0);
            dispatch::glFogf(&mut ctx, gl::GL_FOG_START, 1.0);
            dispatch::glActiveTexture(&mut ctx, gl::GL_TEXTURE3);
            dispatch::glTexEnvfv(&mut ctx, gl::GL_TEXTURE_ENV, gl::GL_TEXTURE_ENV_COLOR, [0.5, 0.25, 0.125, 1.0].as_ptr());
            dispatch::glEnable(&mut ctx, gl::GL_VERTEX_PROGRAM_POINT_SIZE);
            dispatch::glScalef(&mut ctx, 2.0, 2.0, 2.0);
        }
        let depth = [[1, 2, 1, 0]; 8];
        let b = ctx.pack_builtins(&depth);
        let top = |m: &str| at("GlrtBuiltins", m);
        assert_eq!(b.len(), top("glrt_Flags") + 16, "the block's size");
        assert_eq!(u32::from_ne_bytes(b[top("glrt_Flags")..][..4].try_into().unwrap()), 1, "GL_VERTEX_PROGRAM_POINT_SIZE");
        assert_eq!(f32_at(&b, top("glrt_DepthRange") + at("glrt_DepthRangeParameters", "diff")), 0.5);
        assert_eq!(f32_at(&b, top("glrt_ClipPlane") + 5 * 16 + 12), 4.0, "planes by index, enabled or not");
        assert_eq!(f32_at(&b, top("glrt_Point") + at("glrt_PointParameters", "size")), 5.0);
        assert_eq!(f32_at(&b, top("glrt_FrontMaterial") + at("glrt_MaterialParameters", "shininess")), 7.0);
        let light = |i: usize, m: &str| top("glrt_LightSource") + i * 128 + at("glrt_LightSourceParameters", m);
        assert_eq!(f32_at(&b, light(7, "quadraticAttenuation")), 9.0, "lights by index, enabled or not");
        assert!((f32_at(&b, light(3, "spotCosCutoff")) - 0.5).abs() < 1e-6);
        assert_eq!(f32_at(&b, light(3, "spotCutoff")), 60.0);
        assert_eq!(f32_at(&b, top("glrt_Fog") + at("glrt_FogParameters", "scale")), 0.5);
        assert_eq!(f32_at(&b, top("glrt_TextureEnvColor") + 3 * 16 + 4), 0.25);
        assert_eq!(f32_at(&b, top("glrt_NormalScale")), 2.0, "undoes the scale the normal matrix gives");
        let mat3 = top("glrt_NormalMatrix");
        assert_eq!([f32_at(&b, mat3), f32_at(&b, mat3 + 16 + 4), f32_at(&b, mat3 + 32 + 8)], [0.5; 3]);
        assert_eq!(f32_at(&b, top("glrt_ModelViewMatrixInverse") + 16 + 4), 0.5);
        assert_eq!(f32_at(&b, top("glrt_ModelViewProjectionMatrix")), 2.0);
        let scene = top("glrt_FrontLightModelProduct") + at("glrt_LightModelProducts", "sceneColor");
        assert!((f32_at(&b, scene) - 0.04).abs() < 1e-6, "emission + ambient * model ambient (0.2 * 0.2)");
        for m in ["glrt_LightModel", "glrt_BackLightProduct", "glrt_ObjectPlaneQ", "glrt_TextureMatrixInverseTranspose"] {
            assert!(top(m) < b.len(), "{m}");
        }
        assert_eq!(u32::from_ne_bytes(b[top("glrt_SamplerDepth") + 7 * 16..][..4].try_into().unwrap()), 1);
    }
}

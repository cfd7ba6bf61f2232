//! The std140 uniform block `FF` of `shaders/ff_uniforms.glsl`, packed from a draw's state.
//!
//! [`MEMBERS`] lists every member with its byte offset; a test reads the member offsets of the
//! compiled SPIR-V (its `Offset` decorations) and compares them with that table, so the GLSL
//! declaration and this packing cannot drift apart. Everything is in the draw's eye space
//! (lights, clip planes, eye-linear planes are stored in eye space by `translate`).

use glam::{Mat3, Mat4, Vec4};

use super::MAX_UNITS;
use crate::frame::Draw;
use crate::frame::state::{Light, Material, RasterState, MAX_POINT_SIZE};
use crate::frame::texture::TexGenMode;

/// Lights the block holds (`GL_MAX_LIGHTS`).
pub const MAX_LIGHTS: usize = 8;
/// Clip planes the block holds (`GL_MAX_CLIP_PLANES`).
pub const MAX_CLIP_PLANES: usize = 6;

/// Byte offsets of the members of `FF` (std140).
pub mod offset {
    use super::{MAX_CLIP_PLANES, MAX_LIGHTS, MAX_UNITS};

    /// `mat4 modelview`.
    pub const MODELVIEW: usize = 0;
    /// `mat4 projection`.
    pub const PROJECTION: usize = 64;
    /// `mat4 normal_matrix`: inverse transpose of the modelview (upper 3×3 used).
    pub const NORMAL_MATRIX: usize = 128;
    /// `mat4 texture_matrix[MAX_UNITS]`.
    pub const TEXTURE_MATRIX: usize = 192;
    /// `vec4 texgen_plane[4 * MAX_UNITS]`: plane of coordinate `c` of unit `u` at `4 u + c`.
    pub const TEXGEN_PLANE: usize = TEXTURE_MATRIX + 64 * MAX_UNITS;
    /// `vec4 env_color[MAX_UNITS]`.
    pub const ENV_COLOR: usize = TEXGEN_PLANE + 16 * 4 * MAX_UNITS;
    /// `vec4 lod_bias`: component `u` for unit `u`.
    pub const LOD_BIAS: usize = ENV_COLOR + 16 * MAX_UNITS;
    /// `vec4 scene_ambient`.
    pub const SCENE_AMBIENT: usize = LOD_BIAS + 16;
    /// `Material material[2]` (front, back).
    pub const MATERIAL: usize = SCENE_AMBIENT + 16;
    /// Bytes of a `Material`.
    pub const MATERIAL_STRIDE: usize = 80;
    /// `Light light[MAX_LIGHTS]`: the enabled lights, packed first.
    pub const LIGHT: usize = MATERIAL + 2 * MATERIAL_STRIDE;
    /// Bytes of a `Light`.
    pub const LIGHT_STRIDE: usize = 96;
    /// `vec4 fog_color`.
    pub const FOG_COLOR: usize = LIGHT + MAX_LIGHTS * LIGHT_STRIDE;
    /// `vec4 fog_params`: start, end, density, `1 / (end − start)` (0 when equal).
    pub const FOG_PARAMS: usize = FOG_COLOR + 16;
    /// `vec4 clip_plane[MAX_CLIP_PLANES]`: the enabled planes, packed first.
    pub const CLIP_PLANE: usize = FOG_PARAMS + 16;
    /// `vec4 point`: size, minimum, maximum, fade threshold.
    pub const POINT: usize = CLIP_PLANE + 16 * MAX_CLIP_PLANES;
    /// `vec4 point_attenuation`: constant, linear, quadratic, unused.
    pub const POINT_ATTENUATION: usize = POINT + 16;
    /// `vec4 raster`: alpha test reference, line width, line stipple factor, normal rescale
    /// factor.
    pub const RASTER: usize = POINT_ATTENUATION + 16;
    /// `vec4 viewport`: x, y, width, height in window pixels.
    pub const VIEWPORT: usize = RASTER + 16;
    /// `uvec4 stipple`: line stipple pattern, framebuffer height (see
    /// [`super::set_framebuffer_height`]), unused, unused.
    pub const STIPPLE: usize = VIEWPORT + 16;
    /// `uvec4 polygon_stipple[8]`: row `r` (bottom first) is component `r % 4` of `r / 4`.
    pub const POLYGON_STIPPLE: usize = STIPPLE + 16;
    /// Size of the block.
    pub const END: usize = POLYGON_STIPPLE + 16 * 8;

    /// Offsets within a `Light`.
    pub mod light {
        /// `vec4 ambient`.
        pub const AMBIENT: usize = 0;
        /// `vec4 diffuse`.
        pub const DIFFUSE: usize = 16;
        /// `vec4 specular`.
        pub const SPECULAR: usize = 32;
        /// `vec4 position` (eye space, homogeneous).
        pub const POSITION: usize = 48;
        /// `vec4 spot`: direction (normalized), exponent.
        pub const SPOT: usize = 64;
        /// `vec4 params`: cosine of the cutoff (−2 for no spot), attenuation k0, k1, k2.
        pub const PARAMS: usize = 80;
    }

    /// Offsets within a `Material`.
    pub mod material {
        /// `vec4 ambient`.
        pub const AMBIENT: usize = 0;
        /// `vec4 diffuse`.
        pub const DIFFUSE: usize = 16;
        /// `vec4 specular`.
        pub const SPECULAR: usize = 32;
        /// `vec4 emission`.
        pub const EMISSION: usize = 48;
        /// `vec4 shininess` (x).
        pub const SHININESS: usize = 64;
    }
}

/// Every member of `FF` with its offset, as named in `ff_uniforms.glsl`, followed by the
/// members of `Light` and `Material` (checked against the SPIR-V).
pub const MEMBERS: &[(&str, &str, usize)] = &[
    ("FF", "modelview", offset::MODELVIEW),
    ("FF", "projection", offset::PROJECTION),
    ("FF", "normal_matrix", offset::NORMAL_MATRIX),
    ("FF", "texture_matrix", offset::TEXTURE_MATRIX),
    ("FF", "texgen_plane", offset::TEXGEN_PLANE),
    ("FF", "env_color", offset::ENV_COLOR),
    ("FF", "lod_bias", offset::LOD_BIAS),
    ("FF", "scene_ambient", offset::SCENE_AMBIENT),
    ("FF", "material", offset::MATERIAL),
    ("FF", "light", offset::LIGHT),
    ("FF", "fog_color", offset::FOG_COLOR),
    ("FF", "fog_params", offset::FOG_PARAMS),
    ("FF", "clip_plane", offset::CLIP_PLANE),
    ("FF", "point", offset::POINT),
    ("FF", "point_attenuation", offset::POINT_ATTENUATION),
    ("FF", "raster", offset::RASTER),
    ("FF", "viewport", offset::VIEWPORT),
    ("FF", "stipple", offset::STIPPLE),
    ("FF", "polygon_stipple", offset::POLYGON_STIPPLE),
    ("Light", "ambient", offset::light::AMBIENT),
    ("Light", "diffuse", offset::light::DIFFUSE),
    ("Light", "specular", offset::light::SPECULAR),
    ("Light", "position", offset::light::POSITION),
    ("Light", "spot", offset::light::SPOT),
    ("Light", "params", offset::light::PARAMS),
    ("Material", "ambient", offset::material::AMBIENT),
    ("Material", "diffuse", offset::material::DIFFUSE),
    ("Material", "specular", offset::material::SPECULAR),
    ("Material", "emission", offset::material::EMISSION),
    ("Material", "shininess", offset::material::SHININESS),
];

/// The uniform block being filled.
struct Block(Vec<u8>);

impl Block {
    fn floats(&mut self, at: usize, values: &[f32]) {
        for (i, v) in values.iter().enumerate() {
            self.0[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
        }
    }

    fn words(&mut self, at: usize, values: &[u32]) {
        for (i, v) in values.iter().enumerate() {
            self.0[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
        }
    }

    fn mat4(&mut self, at: usize, m: &Mat4) {
        self.floats(at, &m.to_cols_array());
    }
}

/// Writes the framebuffer height (pixels) into a batch's uniform block: the fragment stage
/// needs it for the polygon stipple, whose rows count from the bottom of the window while
/// Vulkan's `gl_FragCoord.y` counts from the top. The Vulkan side calls this once per batch
/// (or per render target) before uploading [`super::Batch::uniforms`].
pub fn set_framebuffer_height(uniforms: &mut [u8], height: u32) {
    let at = offset::STIPPLE + 4;
    if let Some(bytes) = uniforms.get_mut(at..at + 4) {
        bytes.copy_from_slice(&height.to_le_bytes());
    }
}

/// The uniform block of `draw` (the framebuffer height left 0).
pub fn pack(draw: &Draw) -> Vec<u8> {
    let s: &RasterState = &draw.state;
    let mut b = Block(vec![0; offset::END]);
    b.mat4(offset::MODELVIEW, &draw.modelview);
    b.mat4(offset::PROJECTION, &draw.projection);
    let normal = Mat4::from_mat3(Mat3::from_mat4(draw.modelview).inverse().transpose());
    b.mat4(offset::NORMAL_MATRIX, &normal);
    for u in 0..MAX_UNITS {
        let matrix = draw.texture_matrices.get(u).copied().flatten().unwrap_or(Mat4::IDENTITY);
        b.mat4(offset::TEXTURE_MATRIX + 64 * u, &matrix);
        let Some(unit) = draw.texture_units.get(u).copied().flatten() else { continue };
        for (c, mode) in unit.texgen.iter().enumerate() {
            if let Some(TexGenMode::ObjectLinear(p) | TexGenMode::EyeLinear(p)) = mode {
                b.floats(offset::TEXGEN_PLANE + 16 * (4 * u + c), p);
            }
        }
        b.floats(offset::ENV_COLOR + 16 * u, &unit.env.color);
        b.floats(offset::LOD_BIAS + 4 * u, &[unit.env.lod_bias]);
    }
    if let Some(l) = &s.lighting {
        b.floats(offset::SCENE_AMBIENT, &l.model.ambient);
        for (i, m) in [&l.front, &l.back].into_iter().enumerate() {
            material(&mut b, offset::MATERIAL + i * offset::MATERIAL_STRIDE, m);
        }
        for (i, (_, light)) in l.lights.iter().take(MAX_LIGHTS).enumerate() {
            pack_light(&mut b, offset::LIGHT + i * offset::LIGHT_STRIDE, light);
        }
    }
    if let Some(fog) = &s.fog {
        b.floats(offset::FOG_COLOR, &fog.color);
        let scale = if fog.end != fog.start { 1.0 / (fog.end - fog.start) } else { 0.0 };
        b.floats(offset::FOG_PARAMS, &[fog.start, fog.end, fog.density, scale]);
    }
    for (i, (_, plane)) in s.clip_planes.iter().take(MAX_CLIP_PLANES).enumerate() {
        b.floats(offset::CLIP_PLANE + 16 * i, &plane.map(|x| x as f32));
    }
    let p = &s.point;
    b.floats(offset::POINT, &[p.size, p.size_min, p.size_max.min(MAX_POINT_SIZE), p.fade_threshold]);
    b.floats(offset::POINT_ATTENUATION, &p.attenuation);
    let alpha_ref = s.alpha_test.map_or(0.0, |(_, r)| r);
    let stipple_factor = s.line.stipple.map_or(1, |(f, _)| f.clamp(1, 256));
    b.floats(offset::RASTER, &[alpha_ref, s.line.width, stipple_factor as f32, rescale_factor(&draw.modelview)]);
    b.floats(offset::VIEWPORT, &s.viewport.map(|v| v as f32));
    b.words(offset::STIPPLE, &[s.line.stipple.map_or(0xffff, |(_, p)| p as u32)]);
    if let Some(rows) = &s.polygon_stipple {
        b.words(offset::POLYGON_STIPPLE, rows);
    }
    b.0
}

/// `GL_RESCALE_NORMAL`'s factor (section 2.11.3): one over the length of the third row of the
/// inverse modelview's upper 3×3, as `translate::Context::eye_normal` computes it.
pub fn rescale_factor(modelview: &Mat4) -> f32 {
    let row = modelview.inverse().row(2).truncate().length();
    if row > 0.0 { 1.0 / row } else { 1.0 }
}

fn material(b: &mut Block, at: usize, m: &Material) {
    use offset::material as o;
    b.floats(at + o::AMBIENT, &m.ambient);
    b.floats(at + o::DIFFUSE, &m.diffuse);
    b.floats(at + o::SPECULAR, &m.specular);
    b.floats(at + o::EMISSION, &m.emission);
    b.floats(at + o::SHININESS, &[m.shininess]);
}

fn pack_light(b: &mut Block, at: usize, l: &Light) {
    use offset::light as o;
    b.floats(at + o::AMBIENT, &l.ambient);
    b.floats(at + o::DIFFUSE, &l.diffuse);
    b.floats(at + o::SPECULAR, &l.specular);
    b.floats(at + o::POSITION, &l.position);
    let dir = Vec4::from((glam::Vec3::from(l.spot_direction).normalize_or_zero(), l.spot_exponent));
    b.floats(at + o::SPOT, &dir.to_array());
    let cutoff = if l.spot_cutoff >= 180.0 { -2.0 } else { l.spot_cutoff.to_radians().cos() };
    b.floats(at + o::PARAMS, &[cutoff, l.attenuation[0], l.attenuation[1], l.attenuation[2]]);
}

#[cfg(test)]
pub(crate) mod tests {
    use std::collections::HashMap;
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{Fog, Lighting};

    /// `(struct name, member name) → Offset` from the SPIR-V of a shader.
    pub(crate) fn spirv_offsets(spirv: &[u8]) -> HashMap<(String, String), usize> {
        let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        let string = |w: &[u32]| -> String {
            let bytes: Vec<u8> = w.iter().flat_map(|x| x.to_le_bytes()).take_while(|&b| b != 0).collect();
            String::from_utf8(bytes).expect("utf-8 name")
        };
        let (mut names, mut members, mut offsets) = (HashMap::new(), HashMap::new(), HashMap::new());
        let mut i = 5;
        while i < words.len() {
            let (count, op) = ((words[i] >> 16) as usize, words[i] & 0xffff);
            let args = &words[i + 1..i + count];
            match op {
                5 => drop(names.insert(args[0], string(&args[1..]))),
                6 => drop(members.insert((args[0], args[1]), string(&args[2..]))),
                72 if args[2] == 35 => drop(offsets.insert((args[0], args[1]), args[3] as usize)),
                _ => {}
            }
            i += count.max(1);
        }
        offsets
            .into_iter()
            .filter_map(|((ty, m), off)| Some(((names.get(&ty)?.clone(), members.get(&(ty, m))?.clone()), off)))
            .collect()
    }

    #[test]
    fn offsets_match_the_compiled_shaders() {
        for spirv in [super::super::vertex_spirv(), super::super::fragment_spirv()] {
            let found = spirv_offsets(spirv);
            for &(ty, member, off) in MEMBERS {
                // A member the stage never reads may be stripped from the SPIR-V.
                if let Some(&actual) = found.get(&(ty.to_string(), member.to_string())) {
                    assert_eq!(actual, off, "{ty}.{member}");
                }
            }
        }
        let vert = spirv_offsets(super::super::vertex_spirv());
        assert!(vert.len() >= 20, "the vertex shader declares the block: {vert:?}");
        assert_eq!(offset::END, super::super::UNIFORM_SIZE);
    }

    fn float_at(bytes: &[u8], at: usize) -> f32 {
        f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"))
    }

    #[test]
    fn packs_lights_fog_and_stipples_where_the_shader_reads_them() {
        let mut spot = Light::initial(1);
        spot.spot_cutoff = 60.0;
        spot.spot_direction = [0.0, 0.0, -2.0];
        spot.attenuation = [1.0, 0.5, 0.25];
        let state = RasterState {
            lighting: Some(Lighting { lights: vec![(0, Light::initial(0)), (5, spot)], ..Lighting::default() }),
            fog: Some(Fog { start: 2.0, end: 6.0, ..Fog::default() }),
            polygon_stipple: Some(std::array::from_fn(|r| r as u32 * 3)),
            line: crate::frame::state::Line { stipple: Some((3, 0xf0f0)), ..Default::default() },
            viewport: [0, 0, 640, 480],
            ..RasterState::default()
        };
        let draw = Draw { state: Arc::new(state), ..Draw::default() };
        let mut u = pack(&draw);
        let second = offset::LIGHT + offset::LIGHT_STRIDE;
        assert!((float_at(&u, second + offset::light::PARAMS) - 0.5).abs() < 1e-6, "cos 60°");
        assert_eq!(float_at(&u, second + offset::light::PARAMS + 8), 0.5);
        assert_eq!(float_at(&u, second + offset::light::SPOT + 8), -1.0, "normalized direction");
        assert_eq!(float_at(&u, offset::LIGHT + offset::light::PARAMS), -2.0, "no spot: cutoff 180");
        assert_eq!(float_at(&u, offset::FOG_PARAMS + 12), 0.25);
        assert_eq!(float_at(&u, offset::MATERIAL + offset::material::DIFFUSE), 0.8);
        assert_eq!(float_at(&u, offset::VIEWPORT + 8), 640.0);
        assert_eq!(float_at(&u, offset::RASTER + 8), 3.0);
        assert_eq!(u32::from_le_bytes(u[offset::STIPPLE..][..4].try_into().unwrap()), 0xf0f0);
        let row = |u: &[u8], r: usize| u32::from_le_bytes(u[offset::POLYGON_STIPPLE + 4 * r..][..4].try_into().unwrap());
        assert_eq!(row(&u, 31), 93);
        set_framebuffer_height(&mut u, 480);
        assert_eq!(u32::from_le_bytes(u[offset::STIPPLE + 4..][..4].try_into().unwrap()), 480);
    }

    fn mat4_at(bytes: &[u8], at: usize) -> Mat4 {
        Mat4::from_cols_array(&std::array::from_fn(|i| float_at(bytes, at + 4 * i)))
    }

    /// A draw recorded through the GL commands: its uniforms, with the normal transform
    /// `ff.vert` applies (normal matrix, then normalize or rescale as the key says), give the
    /// eye normal of the CPU lighting (`Context::eye_normal`), and its lights are the ones the
    /// CPU lighting evaluates.
    #[test]
    fn uniforms_reproduce_the_cpu_lighting_inputs() {
        use crate::translate::{Context, dispatch, gl};
        for scaling in [None, Some(gl::GL_NORMALIZE), Some(gl::GL_RESCALE_NORMAL)] {
            let (mut ctx, _) = Context::with_recording();
            let normal = [0.3f32, -0.5, 0.8];
            unsafe {
                dispatch::glRotatef(&mut ctx, 30.0, 1.0, 2.0, 0.5);
                dispatch::glEnable(&mut ctx, gl::GL_LIGHTING);
                dispatch::glEnable(&mut ctx, gl::GL_LIGHT2);
                dispatch::glLightfv(&mut ctx, gl::GL_LIGHT2, gl::GL_POSITION, [1.0f32, 2.0, 3.0, 1.0].as_ptr());
                // A uniform scale after the light was placed: rescaling can undo it.
                dispatch::glScalef(&mut ctx, 3.0, 3.0, 3.0);
                if let Some(cap) = scaling {
                    dispatch::glEnable(&mut ctx, cap);
                }
                dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
                dispatch::glNormal3f(&mut ctx, normal[0], normal[1], normal[2]);
                for v in [[0.0f32, 0.0], [1.0, 0.0], [0.0, 1.0]] {
                    dispatch::glVertex2f(&mut ctx, v[0], v[1]);
                }
                dispatch::glEnd(&mut ctx);
            }
            let draw = ctx.frame.draws.last().expect("a draw").clone();
            let u = pack(&draw);
            let key = super::super::key::shader_key(&draw, super::super::key::Primitive::Triangle, super::super::key::Facing::Rasterizer);
            let mut n = glam::Mat3::from_mat4(mat4_at(&u, offset::NORMAL_MATRIX)) * glam::Vec3::from(normal);
            match super::super::key::NORMAL_SCALING.get(key.words[super::super::key::GENERAL]) {
                1 => n = n.normalize(),
                2 => n *= float_at(&u, offset::RASTER + 12),
                _ => {}
            }
            let expected = ctx.eye_normal(normal);
            assert!((n - expected).length() < 1e-5, "{scaling:?}: {n} != {expected}");
            let position: [f32; 4] = std::array::from_fn(|i| float_at(&u, offset::LIGHT + offset::light::POSITION + 4 * i));
            assert_eq!(position, ctx.fixed.lighting.lights[2].position);
            assert_eq!(mat4_at(&u, offset::MODELVIEW), draw.modelview);
        }
    }

    #[test]
    fn rescale_factor_undoes_a_uniform_scale() {
        let m = Mat4::from_rotation_z(1.0) * Mat4::from_scale(glam::Vec3::splat(4.0));
        assert!((rescale_factor(&m) - 4.0).abs() < 1e-5);
    }
}

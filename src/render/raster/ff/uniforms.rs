//! The std140 uniform block `FF` of `shaders/ff_uniforms.glsl` as [`FfBlock`], packed from a
//! draw's state.
//!
//! [`FfBlock`], [`FfMaterial`] and [`FfLight`] mirror the GLSL block and structs member for
//! member; the build checks their sizes, offsets and field types against the compiled
//! `ff.vert` and `ff.frag` (`OUT_DIR/layouts/ff_uniforms.rs`, see
//! [`crate::render::shader_abi`]). Everything is in the draw's eye space (lights, clip planes,
//! eye-linear planes are stored in eye space by `translate`).

use bytemuck::{Pod, Zeroable};
use glam::{Mat3, Mat4, Vec4};

use super::shader_interface::{MAX_CLIP_PLANES, MAX_LIGHTS};
use crate::frame::Draw;
use crate::frame::state::{Light, Material, RasterState, MAX_POINT_SIZE};
use crate::frame::texture::TexGenMode;
use crate::render::fog::GpuHeightFog;
use crate::render::texenv::codes::MAX_UNITS;

/// `Material` of `ff_uniforms.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FfMaterial {
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// `GL_EMISSION`.
    pub emission: [f32; 4],
    /// `GL_SHININESS` in x.
    pub shininess: [f32; 4],
}

/// `Light` of `ff_uniforms.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FfLight {
    /// `GL_AMBIENT`.
    pub ambient: [f32; 4],
    /// `GL_DIFFUSE`.
    pub diffuse: [f32; 4],
    /// `GL_SPECULAR`.
    pub specular: [f32; 4],
    /// Eye space, homogeneous.
    pub position: [f32; 4],
    /// Spot direction (normalized), spot exponent.
    pub spot: [f32; 4],
    /// Cosine of the cutoff (−2 for no spot), attenuation k0, k1, k2.
    pub params: [f32; 4],
}

/// The block `FF` of `ff_uniforms.glsl` (std140).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FfBlock {
    /// The modelview matrix (column-major).
    pub modelview: [[f32; 4]; 4],
    /// The projection matrix.
    pub projection: [[f32; 4]; 4],
    /// Inverse transpose of the modelview (upper 3×3 used).
    pub normal_matrix: [[f32; 4]; 4],
    /// Each unit's texture matrix.
    pub texture_matrix: [[[f32; 4]; 4]; MAX_UNITS],
    /// Plane of coordinate `c` of unit `u` at `4 u + c` (object or eye linear).
    pub texgen_plane: [[f32; 4]; 4 * MAX_UNITS],
    /// Each unit's `GL_TEXTURE_ENV_COLOR`.
    pub env_color: [[f32; 4]; MAX_UNITS],
    /// Component `u`: unit `u`'s LOD bias.
    pub lod_bias: [f32; 4],
    /// `GL_LIGHT_MODEL_AMBIENT`.
    pub scene_ambient: [f32; 4],
    /// Front and back material.
    pub material: [FfMaterial; 2],
    /// The enabled lights, packed first.
    pub light: [FfLight; MAX_LIGHTS],
    /// `GL_FOG_COLOR`.
    pub fog_color: [f32; 4],
    /// Start, end, density, `1 / (end − start)` (0 when equal).
    pub fog_params: [f32; 4],
    /// The enabled clip planes (eye space), packed first.
    pub clip_plane: [[f32; 4]; MAX_CLIP_PLANES],
    /// Point size, minimum, maximum, fade threshold.
    pub point: [f32; 4],
    /// Point attenuation: constant, linear, quadratic, unused.
    pub point_attenuation: [f32; 4],
    /// Alpha test reference, line width, line stipple factor, normal rescale factor.
    pub raster: [f32; 4],
    /// Viewport x, y, width, height in window pixels.
    pub viewport: [f32; 4],
    /// Line stipple pattern, framebuffer height (see [`set_framebuffer_height`]), unused,
    /// unused.
    pub stipple: [u32; 4],
    /// Polygon stipple row `r` (bottom first) is component `r % 4` of `r / 4`.
    pub polygon_stipple: [[u32; 4]; 8],
    /// The renderer's height fog (see [`set_height_fog`]); zero (off) as packed.
    pub height_fog: GpuHeightFog,
}

include!(concat!(env!("OUT_DIR"), "/layouts/ff_uniforms.rs"));

/// Writes the framebuffer height (pixels) into a draw's uniform block: the fragment stage
/// needs it for the polygon stipple, whose rows count from the bottom of the window while
/// Vulkan's `gl_FragCoord.y` counts from the top. The Vulkan side calls this once per draw
/// where it uploads the block ([`block`]).
pub fn set_framebuffer_height(uniforms: &mut [u8], height: u32) {
    let at = std::mem::offset_of!(FfBlock, stipple) + 4;
    if let Some(bytes) = uniforms.get_mut(at..at + 4) {
        bytes.copy_from_slice(&height.to_le_bytes());
    }
}

/// Writes the height fog of a draw into its uniform block: the Vulkan side calls this per
/// draw drawn into the window's framebuffer while the fog is on
/// ([`crate::render::fog::FrameFog::for_draw`]).
pub fn set_height_fog(uniforms: &mut [u8], fog: &GpuHeightFog) {
    let at = std::mem::offset_of!(FfBlock, height_fog);
    if let Some(bytes) = uniforms.get_mut(at..at + size_of::<GpuHeightFog>()) {
        bytes.copy_from_slice(bytemuck::bytes_of(fog));
    }
}

/// The uniform block of `draw` (the framebuffer height left 0).
pub fn block(draw: &Draw) -> FfBlock {
    let s: &RasterState = &draw.state;
    let mut b = FfBlock::zeroed();
    b.modelview = draw.modelview.to_cols_array_2d();
    b.projection = draw.projection.to_cols_array_2d();
    b.normal_matrix = Mat4::from_mat3(Mat3::from_mat4(draw.modelview).inverse().transpose()).to_cols_array_2d();
    for u in 0..MAX_UNITS {
        let matrix = draw.texture_matrices.get(u).copied().flatten().unwrap_or(Mat4::IDENTITY);
        b.texture_matrix[u] = matrix.to_cols_array_2d();
        let Some(unit) = draw.texture_units.get(u).copied().flatten() else { continue };
        for (c, mode) in unit.texgen.iter().enumerate() {
            if let Some(TexGenMode::ObjectLinear(p) | TexGenMode::EyeLinear(p)) = mode {
                b.texgen_plane[4 * u + c] = *p;
            }
        }
        b.env_color[u] = unit.env.color;
        b.lod_bias[u] = unit.env.lod_bias;
    }
    if let Some(l) = &s.lighting {
        b.scene_ambient = l.model.ambient;
        b.material = [material(&l.front), material(&l.back)];
        for (i, (_, light)) in l.lights.iter().take(MAX_LIGHTS).enumerate() {
            b.light[i] = pack_light(light);
        }
    }
    if let Some(fog) = &s.fog {
        b.fog_color = fog.color;
        let scale = if fog.end != fog.start { 1.0 / (fog.end - fog.start) } else { 0.0 };
        b.fog_params = [fog.start, fog.end, fog.density, scale];
    }
    for (i, (_, plane)) in s.clip_planes.iter().take(MAX_CLIP_PLANES).enumerate() {
        b.clip_plane[i] = plane.map(|x| x as f32);
    }
    let p = &s.point;
    b.point = [p.size, p.size_min, p.size_max.min(MAX_POINT_SIZE), p.fade_threshold];
    b.point_attenuation[..3].copy_from_slice(&p.attenuation);
    let alpha_ref = s.alpha_test.map_or(0.0, |(_, r)| r);
    let stipple_factor = s.line.stipple.map_or(1, |(f, _)| f.clamp(1, 256));
    b.raster = [alpha_ref, s.line.width, stipple_factor as f32, rescale_factor(&draw.modelview)];
    b.viewport = s.viewport.map(|v| v as f32);
    b.stipple[0] = s.line.stipple.map_or(0xffff, |(_, p)| p as u32);
    if let Some(rows) = &s.polygon_stipple {
        for (r, row) in rows.iter().enumerate() {
            b.polygon_stipple[r / 4][r % 4] = *row;
        }
    }
    b
}

/// `GL_RESCALE_NORMAL`'s factor (section 2.11.3): one over the length of the third row of the
/// inverse modelview's upper 3×3, as `translate::Context::eye_normal` computes it.
pub fn rescale_factor(modelview: &Mat4) -> f32 {
    let row = modelview.inverse().row(2).truncate().length();
    if row > 0.0 { 1.0 / row } else { 1.0 }
}

fn material(m: &Material) -> FfMaterial {
    FfMaterial { ambient: m.ambient, diffuse: m.diffuse, specular: m.specular, emission: m.emission, shininess: [m.shininess, 0.0, 0.0, 0.0] }
}

fn pack_light(l: &Light) -> FfLight {
    let dir = Vec4::from((glam::Vec3::from(l.spot_direction).normalize_or_zero(), l.spot_exponent));
    let cutoff = if l.spot_cutoff >= 180.0 { -2.0 } else { l.spot_cutoff.to_radians().cos() };
    FfLight {
        ambient: l.ambient,
        diffuse: l.diffuse,
        specular: l.specular,
        position: l.position,
        spot: dir.to_array(),
        params: [cutoff, l.attenuation[0], l.attenuation[1], l.attenuation[2]],
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{Fog, Lighting};

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
        let b = block(&draw);
        assert!((b.light[1].params[0] - 0.5).abs() < 1e-6, "cos 60°");
        assert_eq!(b.light[1].params[2], 0.5);
        assert_eq!(b.light[1].spot[2], -1.0, "normalized direction");
        assert_eq!(b.light[0].params[0], -2.0, "no spot: cutoff 180");
        assert_eq!(b.fog_params[3], 0.25);
        assert_eq!(b.material[0].diffuse[0], 0.8);
        assert_eq!(b.viewport[2], 640.0);
        assert_eq!(b.raster[2], 3.0);
        assert_eq!(b.stipple[0], 0xf0f0);
        assert_eq!(b.polygon_stipple[7][3], 93, "row 31");
        let mut u = bytemuck::bytes_of(&b).to_vec();
        assert_eq!(u.len(), super::super::UNIFORM_SIZE);
        set_framebuffer_height(&mut u, 480);
        let fog = GpuHeightFog { eye: [1.0, 2.0, 3.0, 1.0], density: [0.5, 0.1, 0.0, 0.0], ..GpuHeightFog::default() };
        set_height_fog(&mut u, &fog);
        let read = bytemuck::pod_read_unaligned::<FfBlock>(&u);
        assert_eq!((read.stipple[1], read.height_fog), (480, fog));
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
            let b = block(&draw);
            let key = super::super::key::shader_key(&draw, super::super::key::Primitive::Triangle, super::super::key::Facing::Rasterizer);
            let mut n = Mat3::from_mat4(Mat4::from_cols_array_2d(&b.normal_matrix)) * glam::Vec3::from(normal);
            match super::super::shader_interface::NORMAL_SCALING.get(key.words[super::super::key::GENERAL]) {
                1 => n = n.normalize(),
                2 => n *= b.raster[3],
                _ => {}
            }
            let expected = ctx.eye_normal(normal);
            assert!((n - expected).length() < 1e-5, "{scaling:?}: {n} != {expected}");
            assert_eq!(b.light[0].position, ctx.fixed.lighting.lights[2].position);
            assert_eq!(Mat4::from_cols_array_2d(&b.modelview), draw.modelview);
        }
    }

    #[test]
    fn rescale_factor_undoes_a_uniform_scale() {
        let m = Mat4::from_rotation_z(1.0) * Mat4::from_scale(glam::Vec3::splat(4.0));
        assert!((rescale_factor(&m) - 4.0).abs() < 1e-5);
    }
}

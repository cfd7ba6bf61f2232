//! The structures the tracing shaders read, as `#[repr(C)]` mirrors of `shaders/trace/`
//! (`scene.glsl`, `instance.glsl`, `gbuffer.glsl`); the build checks their sizes, field offsets
//! and field types against the compiled `pathtrace.comp` and `trace_resolve.comp`
//! (`OUT_DIR/layouts/trace_gpu_types.rs`, see [`crate::render::shader_abi`]). Their flag bits
//! are [`super::shader_constants`].

use bytemuck::{Pod, Zeroable};

use super::shader_constants::{GRADIENT_STRATUM, MATERIAL_LAYERS, MAX_PASSES, TRACED_UNITS};

/// `TraceFrameBlock` of `scene.glsl`: camera, settings and counts of one frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    /// Eye to clip, this frame (column-major).
    pub projection: [[f32; 4]; 4],
    /// Its inverse.
    pub inverse_projection: [[f32; 4]; 4],
    /// Eye to clip, last frame.
    pub previous_projection: [[f32; 4]; 4],
    /// Linear radiance of missed rays (rgb) when the frame has no sky draws.
    pub environment: [f32; 4],
    /// The GL viewport: x, y, width, height in window pixels.
    pub viewport: [f32; 4],
    /// `glDepthRange` near, far; two unused.
    pub depth_range: [f32; 4],
    /// Exposure multiplier, history cap in frames, knee of the knee tone curve
    /// ([`super::settings::Tonemap::Knee`]), ray-cone spread of one traced pixel.
    pub params: [f32; 4],
    /// Traced width and height, window width and height.
    pub size: [u32; 4],
    /// Frame index (random seed), samples per pixel, bounces, light count.
    pub counts: [u32; 4],
    /// `FRAME_*` bits, instance count, emitter count ([`GpuEmitter`]), unused.
    pub flags: [u32; 4],
    /// The probability that a path vertex samples the sky ([`super::sky_selection`]), last
    /// frame's (0 where the sky distribution holds no cells of last frame's); two unused.
    pub sampling: [f32; 4],
}

/// `Corner` of `scene.glsl`: the shading attributes of one triangle corner.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCorner {
    /// Texture coordinates of each traced unit (zero when the unit is not enabled).
    pub uv: [[f32; 2]; TRACED_UNITS],
    /// Object-space normal, octahedral snorm16x2; 0 when the geometric normal is used.
    pub normal: u32,
    /// Base colour, display-encoded unorm8 RGBA.
    pub color: u32,
}

/// `TriangleAttributes` of `scene.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangleAttributes {
    /// The three corners, in the triangle's vertex order.
    pub corner: [GpuCorner; 3],
}

/// `Layer` of `scene.glsl`: one traced texture unit or pass of a material (see
/// [`super::material`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLayer {
    /// `GL_TEXTURE_ENV_COLOR`.
    pub env_color: [f32; 4],
    /// A pass's `glBlendColor`.
    pub blend_color: [f32; 4],
    /// Texel pool index of the unit's texture, or `NO_TEXTURE`.
    pub texture: u32,
    /// The unit word's `FORMAT` and `ENV` fields ([`crate::render::texenv::unit_bits`]).
    pub env: u32,
    /// The RGB combiner word ([`crate::render::texenv::combine_words`]).
    pub combine_rgb: u32,
    /// The alpha combiner word.
    pub combine_alpha: u32,
    /// `LAYER_*` of [`super::shader_constants`].
    pub role: u32,
    /// A pass's blend function (`BLEND_*` fields of [`super::shader_constants`]).
    pub blend: u32,
    /// A pass's alpha test compare function, `gl_compare.glsl` order (7: always).
    pub alpha_func: u32,
    /// A pass's alpha test reference.
    pub alpha_ref: f32,
}

/// `LayerCorners` of `scene.glsl`: what one triangle's corners carry for one pass of its
/// surface (the pass's vertex attributes at the base triangle's corners). 40 bytes per
/// triangle and pass; a surface of [`MAX_PASSES`] passes adds 160 bytes per triangle
/// (53⅓ per corner) to the 72 of [`GpuTriangleAttributes`].
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLayerCorners {
    /// Texture coordinates of the pass's unit 0 at each corner (after its texture matrix).
    pub uv: [[f32; 2]; 3],
    /// The pass's primary colour at each corner, display-encoded unorm8 RGBA.
    pub color: [u32; 3],
    /// 1 when the pass covers the triangle; 0: the pass leaves it as it is.
    pub covered: u32,
}

/// `Material` of `scene.glsl`: one per instance, 464 bytes (six layers of 64).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Linear emitted radiance (rgb); a: emissive scale applied to the raster colour.
    pub emission: [f32; 4],
    /// A vertex-lit model's ambient light ([`super::vertex_light::ModelLight::ambient`]):
    /// linear radiance from every direction (rgb), which its continuation rays take when they
    /// meet nothing within `a`, the model's width; a = 0: none (traced light lights it).
    pub ambient: [f32; 4],
    /// Layer `u < TRACED_UNITS`: texture unit `u`; then pass `k` at `TRACED_UNITS + k`.
    pub layer: [GpuLayer; MATERIAL_LAYERS],
    /// Roughness (GGX alpha = roughness²).
    pub roughness: f32,
    /// Metalness.
    pub metalness: f32,
    /// Dielectric reflectance at normal incidence.
    pub specular: f32,
    /// Alpha test compare function, `gl_compare.glsl` order (7: always).
    pub alpha_func: u32,
    /// Alpha test reference.
    pub alpha_ref: f32,
    /// `MATERIAL_*` bits.
    pub flags: u32,
    /// The instance's first record in the layer-corner buffer ([`GpuLayerCorners`]: its
    /// geometry's, `passes` per triangle, triangle after triangle in BVH order).
    pub layer_corners: u32,
    /// Passes of the surface (layers `TRACED_UNITS..TRACED_UNITS + passes`).
    pub passes: u32,
    /// The instance's first entry in the emitter list (one per triangle, in BVH order), or
    /// `NO_EMITTER`.
    pub emitters: u32,
    /// A hash of what the material shows ([`super::material::key`]): the temporal pass keeps
    /// a pixel's history only while its material's key stays.
    pub key: u32,
    /// The RGB (display-encoded, packed as `packUnorm4x8`) that replaces the primary
    /// colours' in the albedo with `MATERIAL_TINT_PRIMARY` ([`super::material`]).
    pub tint: u32,
    /// The instance's first record in the radiosity buffer ([`GpuRadiosityTriangle`], one
    /// per triangle in BVH order), or `NO_RADIOSITY`: the path's first diffuse bounce on it
    /// reads radiosity's indirect light and ends ([`super::radiosity`]).
    pub radiosity: u32,
}

/// `RadiosityTriangle` of `scene.glsl`: radiosity's indirect light at the three corners of a
/// static-world triangle ([`super::radiosity`]), irradiance / π (linear RGB per corner, the
/// corners in the triangle's order).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuRadiosityTriangle {
    /// Corner `k`'s red, green and blue at `3k..3k + 3`.
    pub corner: [f32; 9],
}

/// `Emitter` of `scene.glsl`: one emissive triangle of the frame, an entry of the alias table
/// that next-event estimation picks triangles from in proportion to their power
/// ([`super::emitters`]).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuEmitter {
    /// Its instance (index into the frame's instances).
    pub instance: u32,
    /// Its triangle (global index into the triangle buffers).
    pub triangle: u32,
    /// The entry taken instead when the draw exceeds `threshold`.
    pub alias: u32,
    /// Probability of keeping this entry once it is drawn (alias method).
    pub threshold: f32,
    /// Probability that a sample picks this triangle.
    pub probability: f32,
}

/// `Light` of `trace/light.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// Eye space; w = 0: directional (xyz: unit direction towards the light).
    pub position: [f32; 4],
    /// Directional: irradiance at normal incidence; point: intensity (rgb); a: radius.
    pub radiance: [f32; 4],
    /// Unit spot direction; w: cos(cutoff), or −2 without a spot.
    pub spot: [f32; 4],
    /// x: spot exponent; y: cosine of a directional light's angular radius; z: directional:
    /// length of its shadow rays (0: to the light); point: its reach, where it has faded to
    /// nothing (0: unlimited); w: 0, or 1 + the only instance it lights (a light
    /// recovered from a model's vertex colours, [`super::vertex_light`]), or −1: a dynamic
    /// light, which baked surfaces reflect too ([`super::lights::dynamic`]).
    pub params: [f32; 4],
}

/// `Instance` of `instance.glsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuInstance {
    /// Rows of the affine object-to-eye matrix.
    pub object_to_eye: [[f32; 4]; 3],
    /// Rows of its inverse.
    pub eye_to_object: [[f32; 4]; 3],
    /// Last frame's object-to-eye rows (the same when unknown).
    pub previous_object_to_eye: [[f32; 4]; 3],
    /// Root of its geometry in the BLAS node buffer.
    pub blas_root: u32,
    /// First triangle of its geometry in the triangle buffers.
    pub first_triangle: u32,
    /// `INSTANCE_*` bits.
    pub flags: u32,
    /// Index into the material buffer.
    pub material: u32,
    /// First of its geometry's last-frame triangles in the previous-triangle buffer (a
    /// deforming mesh's last shape, in its BVH order; [`super::resident::Resident::previous`]),
    /// or `NO_PREVIOUS_TRIANGLES` (its shape did not change, or it is new).
    pub previous_triangles: u32,
    /// With `INSTANCE_MERGED` (a merged region of chunks, [`super::regions`]): the record of
    /// its first chunk, which its triangles' `member` counts from; 0 elsewhere.
    pub first_member: u32,
    /// Padding to the GLSL struct's 16-byte multiple.
    pub pad1: u32,
    /// Padding.
    pub pad2: u32,
}

/// Bytes of a G-buffer record (`GSample` of `gbuffer.glsl`).
pub const GSAMPLE_BYTES: u64 = 96;
/// Per-pixel bytes of the accumulation buffers (`AccumSample`).
pub const ACCUM_SAMPLE_BYTES: u64 = 32;
/// Per-pixel bytes of the composite's input (`OutputSample`).
pub const OUTPUT_SAMPLE_BYTES: u64 = 8;

/// `Counters` of `gbuffer.glsl`: rays traced and traversal work, summed over a frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuCounters {
    /// Primary (camera) rays.
    pub primary_rays: u32,
    /// Shadow rays of next-event estimation.
    pub shadow_rays: u32,
    /// Indirect rays of the diffuse lobe.
    pub diffuse_rays: u32,
    /// Indirect rays of the specular lobe.
    pub specular_rays: u32,
    /// BVH nodes (TLAS and BLAS) visited by all rays.
    pub nodes_visited: u32,
    /// Ray-triangle tests of all rays.
    pub triangles_tested: u32,
    /// Shadow rays towards the sky (counted in `shadow_rays` too).
    pub sky_rays: u32,
    /// Those of them that found the sky unoccluded.
    pub sky_unoccluded: u32,
}

/// Bytes of the ray counters.
pub const COUNTER_BYTES: u64 = size_of::<GpuCounters>() as u64;

include!(concat!(env!("OUT_DIR"), "/layouts/trace_gpu_types.rs"));

const _: () = assert!(size_of::<GpuMaterial>() == 464 && size_of::<GpuLayerCorners>() == 40, "the sizes the docs give");

const _: () = assert!(MAX_PASSES == crate::frame::class::MAX_LAYERS, "a material traces every layer a surface may have");

/// Temporal gradient strata per side of a traced image of `size` (`gradient_strata` of
/// `trace/gradient.glsl`; those at the far edges may be partial).
pub fn gradient_strata(size: [u32; 2]) -> [u32; 2] {
    size.map(|s| s.div_ceil(GRADIENT_STRATUM))
}

/// The G-buffer's records for a traced image of `size`: one per pixel, then one per gradient
/// stratum, the tracer's gradient pass's samples (`gradient_record` of `trace/gradient.glsl`).
pub fn gbuffer_records(size: [u32; 2]) -> u64 {
    let strata = gradient_strata(size);
    u64::from(size[0]) * u64::from(size[1]) + u64::from(strata[0]) * u64::from(strata[1])
}

/// The rows of the affine part of `m` (its last row is taken as 0, 0, 0, 1).
pub fn rows(m: &glam::Mat4) -> [[f32; 4]; 3] {
    let t = m.transpose();
    [t.x_axis.to_array(), t.y_axis.to_array(), t.z_axis.to_array()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gbuffer_holds_a_record_per_pixel_and_per_stratum() {
        assert_eq!(gradient_strata([80, 60]), [27, 20]);
        assert_eq!(gbuffer_records([80, 60]), 80 * 60 + 27 * 20);
        assert_eq!(gbuffer_records([3, 3]), 10);
    }

    #[test]
    fn rows_are_the_affine_rows() {
        let m = glam::Mat4::from_translation(glam::Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(rows(&m), [[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 2.0], [0.0, 0.0, 1.0, 3.0]]);
    }
}

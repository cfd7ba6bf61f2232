//! The environment of missed rays: the frame's [`DrawClass::Sky`] draws rendered into a cube
//! map around the eye, which `shaders/trace/environment.glsl` samples for every ray that
//! leaves the scene (radiance = the sRGB-decoded texel, linear; filtered linearly).
//!
//! GL programs draw their sky around the eye (a box or dome whose modelview has no
//! translation, or one small against its size), so each sky draw is rendered with its own
//! modelview into the six faces of an eye-space cube, one 90° perspective view per face
//! ([`face_projection`]: the face transform applied after the modelview, no far plane),
//! cleared first to the frame's clear colour (what a missed ray saw before), then the sky
//! draws in program order with their fixed-function shading (textures, colours, blending,
//! fog as drawn). The raster renderer records them ([`Recorder::with_target`]), so the faces
//! are shaded by the same pipelines as the window. Draws whose sky is not a direction around
//! the eye are left out: orthographic backdrops, GLSL programs (their own matrices),
//! framebuffer objects.
//!
//! Cube maps are left-handed (the Vulkan specification's table of major axes and face
//! coordinates), so each face transform is a rotation composed with a mirror: the faces are
//! drawn with the front-face winding flipped, which keeps culling and `gl_FrontFacing` as
//! GL has them. The faces are drawn into an RGBA8 [`Target`] and copied into the layers of
//! an sRGB cube image (same bits: the sampler decodes them).
//!
//! The cube is drawn again only when the sky draws, the clear colour or the window's alpha
//! change (compared with those it holds, draw by draw: geometry, matrices, state, texture
//! versions); [`Sky::update`] returns a version that changes with its content, which the
//! tracer puts into its frame signature (temporal accumulation restarts when the sky
//! changes). The cube is what rays see; the visible sky stays the rasterized one (the
//! composite keeps the framebuffer where the primary ray missed).
//!
//! Each time the cube is drawn its faces are also copied into a host-readable buffer of the
//! frame slot; when that slot comes round again (its frame finished) the faces are read and
//! become the sky's distribution of directions for next-event estimation
//! ([`super::sky_distribution`], [`Sky::distribution`]). That distribution may describe an
//! earlier content of the cube (a frame slot late; the cube is redrawn every frame while the
//! camera turns, since it is in eye space): that changes which directions are sampled, never
//! the expected image, because the shaders weigh each sample by the density of the same
//! distribution it was drawn from and every cell keeps a share of uniform sampling.

use std::sync::Arc;

use ash::vk;
use glam::{Mat3, Mat4};

use crate::frame::class::{DrawClass, orthographic};
use crate::frame::state::Winding;
use crate::frame::{Clear, Draw, Frame, Framebuffer, RasterState};
use gpu_allocator::MemoryLocation;

use super::sky_distribution::SkyDistribution;
use crate::render::raster::device::{Buffer, Check, Device, Image, Result};
use crate::render::raster::renderer::Recorder;
use crate::render::raster::target::{Plane, Target};
use crate::render::raster::textures::image_barrier;

/// The format of the cube: the faces' RGBA8 bits, decoded from sRGB by the sampler.
const CUBE_FORMAT: vk::Format = vk::Format::R8G8B8A8_SRGB;

/// The near plane of a sky draw whose projection gives none.
const FALLBACK_NEAR: f32 = 0.01;

/// Eye-space direction to face view space, per cube face in Vulkan's layer order (+X, −X,
/// +Y, −Y, +Z, −Z), as rows: the view looks down −z at the face's major axis, its x and y are
/// the face's s and −t coordinates (Vulkan specification, "Cube Map Face Selection").
const FACE_ROWS: [[[f32; 3]; 3]; 6] = [
    [[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
    [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
    [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, -1.0, 0.0]],
    [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]],
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]],
    [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
];

/// The transform from eye space to the view of cube face `face` (0..6, Vulkan's order): a
/// rotation and a mirror (see the module doc).
pub fn face_transform(face: usize) -> Mat4 {
    Mat4::from_mat3(Mat3::from_cols_array_2d(&FACE_ROWS[face % 6]).transpose())
}

/// Eye space to GL clip space of cube face `face`: [`face_transform`], then a 90° square
/// perspective with its near plane at `near` and no far plane (a sky is drawn whatever its
/// distance). A face rendered with it into an image whose row 0 is the top (the raster
/// target's orientation) is the cube layer of that face.
pub fn face_projection(face: usize, near: f32) -> Mat4 {
    let perspective = Mat4::from_cols(glam::Vec4::X, glam::Vec4::Y, glam::Vec4::new(0.0, 0.0, -1.0, -1.0), glam::Vec4::new(0.0, 0.0, -2.0 * near, 0.0));
    perspective * face_transform(face)
}

/// The near-plane distance of the GL perspective `projection` (`glFrustum`,
/// `gluPerspective`), or [`FALLBACK_NEAR`] when it gives none.
fn near_plane(projection: &Mat4) -> f32 {
    let near = projection.w_axis.z / (projection.z_axis.z - 1.0);
    if near.is_finite() && near > 0.0 { near } else { FALLBACK_NEAR }
}

/// Whether `draw` is part of the environment: a sky draw into the window, run by the
/// fixed-function pipeline, with a perspective projection.
pub fn is_environment(draw: &Draw) -> bool {
    draw.class == DrawClass::Sky && draw.program.is_none() && draw.state.framebuffer == Framebuffer::default() && !orthographic(&draw.projection)
}

/// What the cube holds.
struct Drawn {
    /// The colour the faces were cleared to (GL values).
    clear: [f32; 4],
    /// The sky draws, as the frame had them.
    draws: Vec<Draw>,
}

/// The environment cube map and the target its faces are drawn in.
pub struct Sky {
    /// Face size in pixels.
    size: u32,
    /// The cube (six layers, [`CUBE_FORMAT`]).
    cube: Image,
    /// Linear filtering, clamped to the edges.
    sampler: vk::Sampler,
    /// The cube's layout after the commands recorded so far.
    layout: vk::ImageLayout,
    /// Where faces are drawn (created at the first sky, with the window's alpha).
    faces: Option<Target>,
    /// What the cube holds (`None`: nothing drawn yet).
    drawn: Option<Drawn>,
    /// Times the cube was drawn: the version [`Sky::update`] returns.
    version: u64,
    /// Per frame slot, the faces copied when the slot last drew the cube (host-readable, six
    /// faces of `size`² RGBA8 texels in layer order), and whether they are waiting to be read.
    readback: Vec<(Buffer, bool)>,
    /// The distribution of the faces read back last (`None`: none yet, or a black sky).
    distribution: Option<SkyDistribution>,
}

impl Sky {
    /// Creates the cube with faces of `size` pixels, its sampler and the read-back buffers of
    /// `slots` frames in flight (none: the sky is not sampled, [`Sky::distribution`] is
    /// `None`).
    pub fn new(device: &Device, size: u32, slots: usize) -> Result<Sky> {
        let size = size.clamp(1, device.properties.limits.max_image_dimension_cube);
        let info = vk::ImageCreateInfo::default()
            .flags(vk::ImageCreateFlags::CUBE_COMPATIBLE)
            .image_type(vk::ImageType::TYPE_2D)
            .format(CUBE_FORMAT)
            .extent(vk::Extent3D { width: size, height: size, depth: 1 })
            .mip_levels(1)
            .array_layers(6)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST);
        let cube = device.create_image("glrt sky cube", &info, vk::ImageViewType::CUBE, vk::ImageAspectFlags::COLOR)?;
        let sampler_info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE);
        // Safety: valid create info; destroyed in `destroy`.
        let sampler = match unsafe { device.raw.create_sampler(&sampler_info, None) }.check("vkCreateSampler") {
            Ok(s) => s,
            Err(e) => {
                device.destroy_image(cube);
                return Err(e);
            }
        };
        let mut sky = Sky { size, cube, sampler, layout: vk::ImageLayout::UNDEFINED, faces: None, drawn: None, version: 0, readback: Vec::new(), distribution: None };
        let bytes = u64::from(size) * u64::from(size) * 4 * 6;
        for _ in 0..slots {
            match device.create_buffer("glrt sky read-back", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu) {
                Ok(b) => sky.readback.push((b, false)),
                Err(e) => {
                    sky.destroy(device);
                    return Err(e);
                }
            }
        }
        Ok(sky)
    }

    /// The distribution of directions of the cube's content as last read back (the current
    /// content or an earlier one; `None` before the first read-back, or for a black sky).
    pub fn distribution(&self) -> Option<&SkyDistribution> {
        self.distribution.as_ref()
    }

    /// Reads the faces frame slot `slot` copied (its frame has finished) into the
    /// distribution.
    fn read_back(&mut self, slot: usize) {
        let size = self.size as usize;
        let Some((buffer, pending)) = self.readback.get_mut(slot) else { return };
        if !std::mem::take(pending) {
            return;
        }
        let bytes = buffer.mapped();
        let face = size * size * 4;
        let faces: [&[u8]; 6] = std::array::from_fn(|f| &bytes[f * face..(f + 1) * face]);
        self.distribution = SkyDistribution::build(&faces, size);
    }

    /// The descriptor of the cube, for the tracing pass (after [`Sky::update`]).
    pub fn descriptor(&self) -> vk::DescriptorImageInfo {
        vk::DescriptorImageInfo { sampler: self.sampler, image_view: self.cube.view, image_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL }
    }

    /// Makes the cube hold the environment of `frame`, drawing it into `rec`'s command buffer
    /// when it changed, and leaves it readable by shaders. Returns the version of the content
    /// (from 1, changes whenever the cube is drawn again), or `None` when the frame has no sky
    /// draws: the environment is then the clear colour alone.
    pub fn update(&mut self, rec: &mut Recorder<'_>, frame: &Frame) -> Result<Option<u64>> {
        self.read_back(rec.slot());
        if self.layout == vk::ImageLayout::UNDEFINED {
            transition(rec, self.cube.raw, &mut self.layout, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
        }
        let draws: Vec<&Draw> = frame.draws.iter().filter(|d| is_environment(d)).collect();
        if draws.is_empty() {
            return Ok(None);
        }
        let clear = super::scene::clear_color(frame).unwrap_or([0.0, 0.0, 0.0, 1.0]);
        let alpha = rec.target.alpha;
        if self.faces.as_ref().is_some_and(|t| t.alpha != alpha) {
            rec.device.wait_idle()?;
            self.faces.take().into_iter().for_each(|t| t.destroy(rec.device));
            self.drawn = None;
        }
        let same = self.drawn.as_ref().is_some_and(|d| d.clear == clear && d.draws.iter().eq(draws.iter().copied()));
        if !same {
            self.draw(rec, &draws, clear, alpha)?;
            self.drawn = Some(Drawn { clear, draws: draws.into_iter().cloned().collect() });
            self.version += 1;
            if let Some((_, pending)) = self.readback.get_mut(rec.slot()) {
                *pending = true;
            }
        }
        Ok(Some(self.version))
    }

    /// Records drawing `draws` into the six faces, each cleared to `clear` first, and copying
    /// them into the cube and into the frame slot's read-back buffer.
    fn draw(&mut self, rec: &mut Recorder<'_>, draws: &[&Draw], clear: [f32; 4], alpha: bool) -> Result<()> {
        let size = self.size;
        let faces = match &mut self.faces {
            Some(t) => t,
            None => self.faces.insert(Target::new(rec.device, [size; 2], 1, alpha)?),
        };
        let clear = Clear { color: Some(clear), depth: Some(1.0), stencil: Some(0), color_mask: [true; 4], depth_mask: true, stencil_mask: 0xff, ..Clear::default() };
        let side = size as i32;
        let mut face_draws: Vec<(Draw, f32)> = draws
            .iter()
            .map(|d| {
                let front_face = match d.state.front_face {
                    Winding::Ccw => Winding::Cw,
                    Winding::Cw => Winding::Ccw,
                };
                let state = Arc::new(RasterState { viewport: [0, 0, side, side], scissor: None, front_face, ..(*d.state).clone() });
                (Draw { state, ..(*d).clone() }, near_plane(&d.projection))
            })
            .collect();
        let cube = self.cube.raw;
        let readback = self.readback.get(rec.slot()).map(|(b, _)| b.raw);
        transition(rec, cube, &mut self.layout, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        let layers = |layer| vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: layer, layer_count: 1 };
        for face in 0..6 {
            for (draw, near) in &mut face_draws {
                draw.projection = face_projection(face, *near);
            }
            rec.with_target(faces, |r| {
                r.clear(&clear);
                face_draws.iter().try_for_each(|(draw, _)| r.draw(draw))
            })?;
            faces.transition(rec.device, rec.cmd, Plane::Color, vk::ImageLayout::TRANSFER_SRC_OPTIMAL);
            let region = vk::ImageCopy {
                src_subresource: layers(0),
                src_offset: vk::Offset3D::default(),
                dst_subresource: layers(face as u32),
                dst_offset: vk::Offset3D::default(),
                extent: vk::Extent3D { width: size, height: size, depth: 1 },
            };
            // Safety: both images are in the layouts named, outside a rendering pass; their
            // formats are size-compatible (RGBA8 bits copied as they are).
            unsafe {
                rec.device.raw.cmd_copy_image(rec.cmd, faces.color.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, cube, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[region])
            };
            if let Some(buffer) = readback {
                let copy = vk::BufferImageCopy {
                    buffer_offset: face as u64 * u64::from(size) * u64::from(size) * 4,
                    buffer_row_length: 0,
                    buffer_image_height: 0,
                    image_subresource: layers(0),
                    image_offset: vk::Offset3D::default(),
                    image_extent: vk::Extent3D { width: size, height: size, depth: 1 },
                };
                // Safety: the face is in the layout named, outside a rendering pass; the
                // buffer holds six faces and lives until the slot's frame is read back.
                unsafe { rec.device.raw.cmd_copy_image_to_buffer(rec.cmd, faces.color.raw, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, buffer, &[copy]) };
            }
        }
        // Safety: outside a rendering pass.
        unsafe { super::compute::barrier(&rec.device.raw, rec.cmd, vk::PipelineStageFlags2::TRANSFER, vk::PipelineStageFlags2::HOST) };
        transition(rec, cube, &mut self.layout, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
        Ok(())
    }

    /// Frees the images, the sampler and the read-back buffers (the GPU must be idle).
    pub fn destroy(self, device: &Device) {
        for (buffer, _) in self.readback {
            device.destroy_buffer(buffer);
        }
        device.destroy_image(self.cube);
        if let Some(t) = self.faces {
            t.destroy(device);
        }
        // Safety: the GPU is done with it.
        unsafe { device.raw.destroy_sampler(self.sampler, None) };
    }
}

/// Records the barrier moving the six layers of `cube` from `layout` to `new`.
fn transition(rec: &Recorder<'_>, cube: vk::Image, layout: &mut vk::ImageLayout, new: vk::ImageLayout) {
    let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 6 };
    image_barrier(rec.device, rec.cmd, cube, range, *layout, new);
    *layout = new;
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec3, Vec4};

    /// Vulkan's cube map face selection and face coordinates (specification, "Cube Map Face
    /// Selection" and "Cube Map Face Coordinates"): the layer and (s, t) in 0..=1 that
    /// direction `d` samples.
    fn vulkan_cube_lookup(d: Vec3) -> (usize, f32, f32) {
        let (face, s, t) = crate::render::trace::sky_distribution::face_coordinates(d);
        (face, 0.5 * (s + 1.0), 0.5 * (t + 1.0))
    }

    /// Where direction `d` lands in the image of face `face` drawn with [`face_projection`]:
    /// (s, t) with s from the left, t from the top row (the raster target's row 0), or `None`
    /// behind the face's view.
    fn rendered_at(face: usize, d: Vec3) -> Option<(f32, f32)> {
        let clip = face_projection(face, 0.1) * (d * 10.0).extend(1.0);
        (clip.w > 0.0).then(|| (0.5 * (clip.x / clip.w + 1.0), 0.5 * (1.0 - clip.y / clip.w)))
    }

    #[test]
    fn face_centres_are_the_cube_axes_in_vulkan_order() {
        let axes = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];
        for (face, axis) in axes.into_iter().enumerate() {
            // The centre of the face's view is the direction its view looks down (−z).
            let centre = face_transform(face).inverse().transform_vector3(Vec3::NEG_Z);
            assert!(centre.abs_diff_eq(axis, 1e-6), "face {face}: centre {centre} against {axis}");
            let clip = face_projection(face, 0.1) * (axis * 5.0).extend(1.0);
            assert!(clip.x.abs() < 1e-6 && clip.y.abs() < 1e-6 && clip.w > 0.0, "face {face}: the axis projects to the face's centre");
            assert!(face_transform(face).determinant() < 0.0, "face {face}: a mirror (cube maps are left-handed)");
        }
    }

    #[test]
    fn every_direction_lands_where_vulkan_samples_it() {
        let mut checked = [0; 6];
        for i in 0..400 {
            // Directions spread over the sphere (a Fibonacci lattice).
            let y = 1.0 - 2.0 * (i as f32 + 0.5) / 400.0;
            let phi = i as f32 * 2.399_963;
            let r = (1.0 - y * y).sqrt();
            let d = Vec3::new(r * phi.cos(), y, r * phi.sin());
            let (face, s, t) = vulkan_cube_lookup(d);
            let (rs, rt) = rendered_at(face, d).expect("in front of its face");
            assert!((rs - s).abs() < 1e-5 && (rt - t).abs() < 1e-5, "{d}: face {face} samples ({s}, {t}), drawn at ({rs}, {rt})");
            assert!((0.0..=1.0).contains(&rs) && (0.0..=1.0).contains(&rt));
            checked[face] += 1;
        }
        assert!(checked.iter().all(|&n| n > 30), "every face is checked: {checked:?}");
    }

    #[test]
    fn the_near_plane_comes_from_the_draws_projection() {
        // glFrustum(-0.1, 0.1, -0.1, 0.1, 0.25, 500).
        let (n, f) = (0.25f32, 500.0f32);
        let frustum = Mat4::from_cols(Vec4::new(2.5, 0.0, 0.0, 0.0), Vec4::new(0.0, 2.5, 0.0, 0.0), Vec4::new(0.0, 0.0, -(f + n) / (f - n), -1.0), Vec4::new(0.0, 0.0, -2.0 * f * n / (f - n), 0.0));
        assert!((near_plane(&frustum) - 0.25).abs() < 1e-5);
        assert_eq!(near_plane(&Mat4::IDENTITY), FALLBACK_NEAR);
        // Depth grows with distance and stays below the far end however far the sky is.
        let depth = |z: f32| {
            let c = face_projection(4, 0.25) * Vec4::new(0.0, 0.0, z, 1.0);
            c.z / c.w
        };
        assert!((depth(0.25) + 1.0).abs() < 1e-6 && depth(10.0) < depth(1000.0) && depth(1e6) < 1.0);
    }
}

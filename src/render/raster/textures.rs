//! Textures on the GPU: the image of each [`TextureRef`] content version, uploaded once and
//! kept while draws use it (dropped after [`KEEP_FRAMES`] presented frames without use, or at
//! once when asked and `translate` holds the version no more: [`Textures::release_unreferenced`]),
//! samplers cached by their state, the 1×1 white textures that fill unused fixed-function
//! bindings (see the `ff` module doc) and the 1×1 black opaque ones that fill a program's
//! sampler slots without a complete texture (which sample as (0, 0, 0, 1) in a shader,
//! OpenGL 2.0 section 3.11.2).
//!
//! Images:
//! - colour formats: the canonical RGBA8 texels of [`crate::frame::texture`] (every
//!   [`TexelFormat`] is already expanded to RGBA there, so one Vulkan format serves all),
//!   as `R8G8B8A8_SRGB` for [`Precision::Srgb8`] levels (sampling decodes sRGB to linear), and
//!   the `f32` values of [`Precision::Float`] levels as `R32G32B32A32_SFLOAT` (where the device
//!   filters it linearly; else their RGBA8 texels);
//! - depth formats: `R32_SFLOAT` from [`TexImage::depth_values`] at full precision, swizzled
//!   to `DEPTH_TEXTURE_MODE` ((D, D, D, 1), (D, D, D, D), (0, 0, 0, D)); with a comparison
//!   (`GL_COMPARE_R_TO_TEXTURE`) the swizzle is (D, D, D, D) and the fragment shader compares
//!   and expands (a sampler with `compareEnable` needs a shadow sampler in GLSL, which the
//!   `ff` contract does not have). Without linear filtering of `R32_SFLOAT` the RGBA8 texels
//!   are used. A program's sampler slot reads the depth in red whatever the mode (the shader
//!   expands it): a depth image whose swizzle moves red elsewhere gets a second, unswizzled
//!   view for programs;
//! - 1D textures are 2D images one texel high, 3D textures 3D images, cube maps 6-layer cube
//!   images; rows bottom to top as OpenGL gives them, so `t = 0` is image row 0;
//! - mip levels from the base level (`GL_TEXTURE_BASE_LEVEL`) to the max level or the 1×1
//!   level, as long as each halves the one above (translate only passes complete textures);
//! - borders (`glTexImage` with border 1) are cut off: the interior is uploaded and the border
//!   colour of `GL_CLAMP_TO_BORDER` comes from the sampler.
//!
//! Samplers: filters, wrap modes (`GL_CLAMP` with a linear filter: clamp-to-border plus a
//! coordinate clamp in the shader; with nearest filters: clamp-to-edge),
//! border colour (custom with `VK_EXT_custom_border_color`, else the closest of Vulkan's three),
//! LOD range and the unit's LOD bias; mipmapping off = `maxLod` 0.

use std::sync::{Arc, Weak};

use ash::vk;
use rustc_hash::FxHashMap;

use super::device::{Check, Device, Image, Result};
use crate::render::texenv::codes::MAX_UNITS;
use super::ff::shader_interface::BINDING_COUNT;
use super::pipelines::{SamplerKind, sampler_binding};
use super::upload::Ring;
use crate::frame::program::{self, MAX_SAMPLERS};
use crate::frame::texture::{DepthMode, Filter, Precision, Sampler, TexImage, TexelFormat, TextureContent, TextureKind, TextureRef, Wrap};

/// Presented frames a texture version stays on the GPU without being used (more than the
/// frames in flight, so the GPU is done with it when it goes).
pub const KEEP_FRAMES: u64 = 8;

/// Image view and sampler of each sampler binding (bindings 1..).
pub type Bindings = [(vk::ImageView, vk::Sampler); BINDING_COUNT as usize - 1];

/// Image view and sampler of each sampler slot of a program (set 1).
pub type SlotBindings = [(vk::ImageView, vk::Sampler); MAX_SAMPLERS];

/// One uploaded content version.
struct Entry {
    image: Image,
    /// The unswizzled view of a depth image whose view moves red elsewhere (for programs).
    red_view: Option<vk::ImageView>,
    kind: SamplerKind,
    /// Frame counter of the last use.
    used: u64,
    /// The version's content, held by `translate` while the texture object has this version
    /// or a frame draws with it: once dead, no draw can use the version again.
    content: Weak<TextureContent>,
}

/// Everything a sampler is created from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct SamplerKey {
    mag: Filter,
    min: Filter,
    mip: Option<Filter>,
    wrap: [Wrap; 3],
    /// Bits of border colour, LOD range and LOD bias.
    bits: [u32; 7],
}

/// Textures and samplers.
pub struct Textures {
    white: Option<[Image; 3]>,
    /// The opaque black 2D, 3D and cube textures.
    black: Option<[Image; 3]>,
    entries: FxHashMap<(u32, u64), Entry>,
    /// Versions that could not be created (too large, out of memory): sampled as white.
    failed: rustc_hash::FxHashSet<(u32, u64)>,
    samplers: FxHashMap<SamplerKey, vk::Sampler>,
    /// Presented frames so far.
    frame: u64,
    /// Whether `R32_SFLOAT` can be sampled with linear filtering.
    float_depth: bool,
    /// Whether `R32G32B32A32_SFLOAT` can be sampled with linear filtering.
    float_color: bool,
}

/// What the texels of an uploaded image are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Upload {
    /// RGBA8 texels (linear or sRGB).
    Rgba8,
    /// RGBA `f32` values.
    Float,
    /// `f32` depth values.
    Depth,
}

impl Textures {
    /// An empty cache (the white images are made on first use, in a frame).
    pub fn new(device: &Device) -> Textures {
        let filters = |format| {
            // Safety: valid physical device.
            let props = unsafe { device.instance.get_physical_device_format_properties(device.physical, format) };
            props.optimal_tiling_features.contains(vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR | vk::FormatFeatureFlags::TRANSFER_DST)
        };
        let (float_depth, float_color) = (filters(vk::Format::R32_SFLOAT), filters(vk::Format::R32G32B32A32_SFLOAT));
        Textures { white: None, black: None, entries: FxHashMap::default(), failed: Default::default(), samplers: FxHashMap::default(), frame: 0, float_depth, float_color }
    }

    /// Whether [`Textures::upload`] would record commands for `textures` (then the caller
    /// ends the rendering pass first).
    pub fn needs_upload<'a>(&self, mut textures: impl Iterator<Item = &'a Option<TextureRef>>) -> bool {
        self.white.is_none() || self.black.is_none() || textures.any(|t| t.as_ref().is_some_and(|t| !self.known(t)))
    }

    /// Records the upload of the white and black textures and of every texture of `textures`
    /// not on the GPU yet (outside a rendering pass), staging through `ring`.
    pub fn upload<'a>(&mut self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, textures: impl Iterator<Item = &'a Option<TextureRef>>) -> Result<()> {
        if self.white.is_none() {
            self.white = Some(create_filled(device, cmd, "white", [1.0; 4])?);
        }
        if self.black.is_none() {
            self.black = Some(create_filled(device, cmd, "black", [0.0, 0.0, 0.0, 1.0])?);
        }
        for t in textures.flatten() {
            if !self.known(t) {
                match self.create(device, cmd, ring, t) {
                    Ok((image, red_view, kind)) => {
                        let content = Arc::downgrade(&t.content);
                        self.entries.insert((t.id, t.version), Entry { image, red_view, kind, used: self.frame, content });
                    }
                    Err(e) => {
                        eprintln!("glrt: texture {} (version {}) cannot be used: {e}; it samples as white", t.id, t.version);
                        self.failed.insert((t.id, t.version));
                    }
                }
            }
        }
        Ok(())
    }

    /// Whether `t` is on the GPU or known to fail.
    fn known(&self, t: &TextureRef) -> bool {
        let key = (t.id, t.version);
        self.entries.contains_key(&key) || self.failed.contains(&key)
    }

    /// Views and samplers of bindings 1.. for a draw with `textures` (per unit) and the
    /// units' LOD biases; uploads must have been recorded ([`Textures::upload`]).
    pub fn bindings(&mut self, device: &Device, textures: &[Option<TextureRef>], lod_bias: [f32; MAX_UNITS]) -> Result<Bindings> {
        let white = self.white.as_ref().map(|w| [w[0].view, w[1].view, w[2].view]).unwrap_or_default();
        let default_sampler = self.sampler(device, &Sampler::default(), 0.0)?;
        let mut out: Bindings = std::array::from_fn(|i| (white[i / MAX_UNITS], default_sampler));
        for (unit, t) in textures.iter().enumerate().take(MAX_UNITS) {
            let Some(t) = t else { continue };
            let frame = self.frame;
            let Some(entry) = self.entries.get_mut(&(t.id, t.version)) else { continue };
            entry.used = frame;
            let (view, kind) = (entry.image.view, entry.kind);
            let sampler = self.sampler(device, &t.content.sampler, lod_bias[unit])?;
            out[sampler_binding(kind, unit) as usize - 1] = (view, sampler);
        }
        Ok(out)
    }

    /// Views and samplers of a program's sampler slots: slot `i` of kind `kinds[i]` samples
    /// `textures[i]` (the black texture of its kind when `None`, not on the GPU, or of another
    /// kind); uploads must have been recorded ([`Textures::upload`]).
    pub fn slot_bindings(&mut self, device: &Device, kinds: &[program::SamplerKind], textures: &[Option<TextureRef>]) -> Result<SlotBindings> {
        let black = self.black.as_ref().map(|b| [b[0].view, b[1].view, b[2].view]).unwrap_or_default();
        let default_sampler = self.sampler(device, &Sampler::default(), 0.0)?;
        let mut out: SlotBindings = [(black[0], default_sampler); MAX_SAMPLERS];
        for (slot, kind) in kinds.iter().enumerate().take(MAX_SAMPLERS) {
            let kind = match kind {
                program::SamplerKind::D2 | program::SamplerKind::D2Shadow => SamplerKind::D2,
                program::SamplerKind::D3 => SamplerKind::D3,
                program::SamplerKind::Cube => SamplerKind::Cube,
            };
            out[slot].0 = black[kind as usize];
            let Some(t) = textures.get(slot).and_then(Option::as_ref) else { continue };
            let frame = self.frame;
            let Some(entry) = self.entries.get_mut(&(t.id, t.version)).filter(|e| e.kind == kind) else { continue };
            entry.used = frame;
            let view = entry.red_view.unwrap_or(entry.image.view);
            out[slot] = (view, self.sampler(device, &t.content.sampler, 0.0)?);
        }
        Ok(out)
    }

    /// Counts a presented frame and frees the versions unused for [`KEEP_FRAMES`] frames.
    pub fn end_frame(&mut self, device: &Device) {
        self.frame += 1;
        let frame = self.frame;
        let old: Vec<_> = self.entries.iter().filter(|(_, e)| e.used + KEEP_FRAMES < frame).map(|(k, _)| *k).collect();
        for key in old {
            if let Some(e) = self.entries.remove(&key) {
                destroy_entry(device, e);
            }
        }
    }

    /// Whether a version on the GPU is referenced by `translate` no more.
    pub fn has_unreferenced(&self) -> bool {
        self.entries.values().any(|e| e.content.strong_count() == 0)
    }

    /// Frees the versions `translate` references no more (the GPU must be done with them).
    pub fn release_unreferenced(&mut self, device: &Device) {
        let dead: Vec<_> = self.entries.iter().filter(|(_, e)| e.content.strong_count() == 0).map(|(k, _)| *k).collect();
        for key in dead {
            if let Some(e) = self.entries.remove(&key) {
                destroy_entry(device, e);
            }
        }
    }

    /// Texture versions on the GPU.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether no texture is on the GPU.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Frees everything (the GPU must be idle).
    pub fn destroy(&mut self, device: &Device) {
        for image in self.white.take().into_iter().chain(self.black.take()).flatten() {
            device.destroy_image(image);
        }
        for (_, e) in self.entries.drain() {
            destroy_entry(device, e);
        }
        for (_, s) in self.samplers.drain() {
            // Safety: the GPU is idle.
            unsafe { device.raw.destroy_sampler(s, None) };
        }
    }

    fn sampler(&mut self, device: &Device, s: &Sampler, lod_bias: f32) -> Result<vk::Sampler> {
        let [b0, b1, b2, b3] = s.border_color.map(f32::to_bits);
        let key = SamplerKey {
            mag: s.mag_filter,
            min: s.min_filter.texel,
            mip: s.min_filter.mipmap,
            wrap: s.wrap,
            bits: [b0, b1, b2, b3, s.lod[0].to_bits(), s.lod[1].to_bits(), lod_bias.to_bits()],
        };
        if let Some(&sampler) = self.samplers.get(&key) {
            return Ok(sampler);
        }
        let filter = |f| match f {
            Filter::Nearest => vk::Filter::NEAREST,
            Filter::Linear => vk::Filter::LINEAR,
        };
        // GL_CLAMP with a linear filter: the shader clamps the coordinate to [0, 1] (key
        // field `CLAMP`) and the sampler supplies the border (`Sampler::clamp_blends_border`).
        let blends = s.clamp_blends_border();
        let wrap = |axis: usize| match s.wrap[axis] {
            Wrap::Repeat => vk::SamplerAddressMode::REPEAT,
            Wrap::Clamp if blends[axis] => vk::SamplerAddressMode::CLAMP_TO_BORDER,
            Wrap::Clamp | Wrap::ClampToEdge => vk::SamplerAddressMode::CLAMP_TO_EDGE,
            Wrap::ClampToBorder => vk::SamplerAddressMode::CLAMP_TO_BORDER,
            Wrap::MirroredRepeat => vk::SamplerAddressMode::MIRRORED_REPEAT,
        };
        let limit = device.properties.limits.max_sampler_lod_bias;
        let (min_lod, max_lod) = match s.min_filter.mipmap {
            Some(_) => (s.lod[0].max(0.0), s.lod[1].max(s.lod[0]).max(0.0)),
            None => (0.0, 0.0),
        };
        let mut custom = vk::SamplerCustomBorderColorCreateInfoEXT::default()
            .custom_border_color(vk::ClearColorValue { float32: s.border_color })
            .format(vk::Format::UNDEFINED);
        let use_custom = device.custom_border_color && (s.wrap.contains(&Wrap::ClampToBorder) || blends.contains(&true));
        let mut info = vk::SamplerCreateInfo::default()
            .mag_filter(filter(s.mag_filter))
            .min_filter(filter(s.min_filter.texel))
            .mipmap_mode(match s.min_filter.mipmap {
                Some(Filter::Linear) => vk::SamplerMipmapMode::LINEAR,
                _ => vk::SamplerMipmapMode::NEAREST,
            })
            .address_mode_u(wrap(0))
            .address_mode_v(wrap(1))
            .address_mode_w(wrap(2))
            .mip_lod_bias(lod_bias.clamp(-limit, limit))
            .min_lod(min_lod)
            .max_lod(max_lod)
            .border_color(if use_custom { vk::BorderColor::FLOAT_CUSTOM_EXT } else { nearest_border(s.border_color) });
        if use_custom {
            info = info.push_next(&mut custom);
        }
        // Safety: valid create info; the custom border colour extension is enabled when used.
        let sampler = unsafe { device.raw.create_sampler(&info, None) }.check("vkCreateSampler")?;
        self.samplers.insert(key, sampler);
        Ok(sampler)
    }

    /// Creates the image of `t` (with its unswizzled view for programs, when it needs one) and
    /// records its upload.
    fn create(&self, device: &Device, cmd: vk::CommandBuffer, ring: &mut Ring, t: &TextureRef) -> Result<(Image, Option<vk::ImageView>, SamplerKind)> {
        let content = &t.content;
        let base = content.sampler.levels[0] as usize;
        let chain = level_chain(&content.faces, base, content.sampler.levels[1] as usize, content.kind);
        let Some(top) = chain.first() else {
            return Err(super::device::Error::Memory(format!("texture {} has no base level", t.id)));
        };
        let [w, h, d] = interior(top);
        let limits = &device.properties.limits;
        let max = match content.kind {
            TextureKind::D3 => limits.max_image_dimension3_d,
            TextureKind::Cube => limits.max_image_dimension_cube,
            _ => limits.max_image_dimension2_d,
        };
        if w.max(h).max(d) > max {
            return Err(super::device::Error::Memory(format!("{w}×{h}×{d} exceeds the device's {max}")));
        }
        let depth = content.format == TexelFormat::Depth && self.float_depth && !top.depth_values.is_empty();
        let (upload, format) = match top.precision {
            _ if depth => (Upload::Depth, vk::Format::R32_SFLOAT),
            Precision::Float if self.float_color => (Upload::Float, vk::Format::R32G32B32A32_SFLOAT),
            Precision::Srgb8 => (Upload::Rgba8, vk::Format::R8G8B8A8_SRGB),
            _ => (Upload::Rgba8, vk::Format::R8G8B8A8_UNORM),
        };
        let (image_type, view_type, layers, flags, kind) = match content.kind {
            TextureKind::D1 | TextureKind::D2 | TextureKind::Rect => (vk::ImageType::TYPE_2D, vk::ImageViewType::TYPE_2D, 1, vk::ImageCreateFlags::empty(), SamplerKind::D2),
            TextureKind::D3 => (vk::ImageType::TYPE_3D, vk::ImageViewType::TYPE_3D, 1, vk::ImageCreateFlags::empty(), SamplerKind::D3),
            TextureKind::Cube => (vk::ImageType::TYPE_2D, vk::ImageViewType::CUBE, 6, vk::ImageCreateFlags::CUBE_COMPATIBLE, SamplerKind::Cube),
        };
        let levels = chain.len() as u32;
        let info = vk::ImageCreateInfo::default()
            .flags(flags)
            .image_type(image_type)
            .format(format)
            .extent(vk::Extent3D { width: w, height: h, depth: d })
            .mip_levels(levels)
            .array_layers(layers)
            .samples(vk::SampleCountFlags::TYPE_1)
            .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC);
        let swizzle = if depth { depth_swizzle(content.sampler.depth_mode, content.sampler.compare.is_some()) } else { vk::ComponentMapping::default() };
        let image = device.create_image_swizzled("glrt texture", &info, view_type, vk::ImageAspectFlags::COLOR, swizzle)?;
        let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: levels, base_array_layer: 0, layer_count: layers };
        let red_view = if swizzle.r == vk::ComponentSwizzle::R || swizzle.r == vk::ComponentSwizzle::IDENTITY {
            None
        } else {
            let view_info = vk::ImageViewCreateInfo::default().image(image.raw).view_type(view_type).format(format).subresource_range(range);
            // Safety: a view of the live image just created.
            match unsafe { device.raw.create_image_view(&view_info, None) }.check("vkCreateImageView") {
                Ok(view) => Some(view),
                Err(e) => {
                    device.destroy_image(image);
                    return Err(e);
                }
            }
        };
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::UNDEFINED, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        let mut copies = Vec::new();
        for face in 0..layers as usize {
            for (level, _) in chain.iter().enumerate() {
                let Some(img) = content.faces.get(face).and_then(|f| f.get(base + level)).and_then(Option::as_ref) else { continue };
                let bytes = texel_bytes(img, upload);
                let slice = ring.push(device, &bytes, 16)?;
                let [lw, lh, ld] = interior(img);
                copies.push((
                    slice.buffer,
                    vk::BufferImageCopy {
                        buffer_offset: slice.offset,
                        buffer_row_length: 0,
                        buffer_image_height: 0,
                        image_subresource: vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: level as u32, base_array_layer: face as u32, layer_count: 1 },
                        image_offset: vk::Offset3D::default(),
                        image_extent: vk::Extent3D { width: lw, height: lh, depth: ld },
                    },
                ));
            }
        }
        for (buffer, copy) in copies {
            // Safety: the image is in TRANSFER_DST_OPTIMAL; the region matches the staged bytes.
            unsafe { device.raw.cmd_copy_buffer_to_image(cmd, buffer, image.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[copy]) };
        }
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
        Ok((image, red_view, kind))
    }
}

/// Frees an uploaded version (the GPU must be done with it).
fn destroy_entry(device: &Device, e: Entry) {
    if let Some(view) = e.red_view {
        // Safety: the GPU is done with the view; destroyed once, before its image.
        unsafe { device.raw.destroy_image_view(view, None) };
    }
    device.destroy_image(e.image);
}

/// The levels uploaded: from `base`, while each exists and halves the one above, up to `max`.
pub(crate) fn level_chain(faces: &[Vec<Option<std::sync::Arc<TexImage>>>], base: usize, max: usize, kind: TextureKind) -> Vec<std::sync::Arc<TexImage>> {
    let Some(levels) = faces.first() else { return Vec::new() };
    let mut chain: Vec<std::sync::Arc<TexImage>> = Vec::new();
    for level in base..=max.max(base) {
        let Some(Some(img)) = levels.get(level) else { break };
        let size = interior(img);
        if let Some(prev) = chain.last() {
            let mut want = interior(prev).map(|s| (s / 2).max(1));
            if kind != TextureKind::D3 {
                want[2] = 1;
            }
            if size != want || interior(prev) == [1, 1, 1] {
                break;
            }
        }
        if size.contains(&0) {
            break;
        }
        chain.push(img.clone());
    }
    chain
}

/// Width, height and depth without the border.
pub(crate) fn interior(img: &TexImage) -> [u32; 3] {
    let b = img.border;
    let h_border = if img.height > 1 { b } else { 0 };
    let d_border = if img.depth > 1 { b } else { 0 };
    [img.width.saturating_sub(2 * b), img.height.saturating_sub(2 * h_border), img.depth.saturating_sub(2 * d_border)].map(|s| s.max(1))
}

/// The texel bytes of the interior of `img` as `upload` says (a float upload of a level
/// without values converts its RGBA8 texels).
pub(crate) fn texel_bytes(img: &TexImage, upload: Upload) -> Vec<u8> {
    let [w, h, d] = interior(img).map(|v| v as usize);
    let b = img.border as usize;
    let (bx, by, bz) = (b, if img.height > 1 { b } else { 0 }, if img.depth > 1 { b } else { 0 });
    let (fw, fh) = (img.width as usize, img.height as usize);
    let texel = if upload == Upload::Float { 16 } else { 4 };
    let mut out = Vec::with_capacity(w * h * d * texel);
    for z in 0..d {
        for y in 0..h {
            let row = ((z + bz) * fh + y + by) * fw + bx;
            match upload {
                Upload::Depth => {
                    let values = img.depth_values.get(row..row + w).unwrap_or(&[]);
                    out.extend(values.iter().flat_map(|v| v.to_le_bytes()));
                }
                Upload::Float if !img.values.is_empty() => {
                    let values = img.values.get(row * 4..(row + w) * 4).unwrap_or(&[]);
                    out.extend(values.iter().flat_map(|v| v.to_le_bytes()));
                }
                Upload::Float => {
                    let texels = img.texels.get(row * 4..(row + w) * 4).unwrap_or(&[]);
                    out.extend(texels.iter().flat_map(|&v| (f32::from(v) / 255.0).to_le_bytes()));
                }
                Upload::Rgba8 => out.extend_from_slice(img.texels.get(row * 4..(row + w) * 4).unwrap_or(&[])),
            }
        }
    }
    out.resize(w * h * d * texel, 0);
    out
}

/// The view swizzle of a depth texture (see the module doc).
fn depth_swizzle(mode: DepthMode, compare: bool) -> vk::ComponentMapping {
    let (r, one, zero) = (vk::ComponentSwizzle::R, vk::ComponentSwizzle::ONE, vk::ComponentSwizzle::ZERO);
    let [cr, cg, cb, ca] = match (compare, mode) {
        (true, _) | (false, DepthMode::Intensity) => [r, r, r, r],
        (false, DepthMode::Luminance) => [r, r, r, one],
        (false, DepthMode::Alpha) => [zero, zero, zero, r],
    };
    vk::ComponentMapping { r: cr, g: cg, b: cb, a: ca }
}

/// The Vulkan border colour closest to `c`.
fn nearest_border(c: [f32; 4]) -> vk::BorderColor {
    if c[3] < 0.5 {
        vk::BorderColor::FLOAT_TRANSPARENT_BLACK
    } else if c[0] + c[1] + c[2] > 1.5 {
        vk::BorderColor::FLOAT_OPAQUE_WHITE
    } else {
        vk::BorderColor::FLOAT_OPAQUE_BLACK
    }
}

/// 1×1 2D, 3D and cube textures of `color` (white, black; `name` says which), cleared in
/// `cmd` and left shader-readable.
fn create_filled(device: &Device, cmd: vk::CommandBuffer, name: &str, color: [f32; 4]) -> Result<[Image; 3]> {
    let base = vk::ImageCreateInfo::default()
        .format(vk::Format::R8G8B8A8_UNORM)
        .extent(vk::Extent3D { width: 1, height: 1, depth: 1 })
        .mip_levels(1)
        .array_layers(1)
        .samples(vk::SampleCountFlags::TYPE_1)
        .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST);
    let d2 = device.create_image(&format!("glrt {name} 2D"), &base.image_type(vk::ImageType::TYPE_2D), vk::ImageViewType::TYPE_2D, vk::ImageAspectFlags::COLOR)?;
    let d3 = device.create_image(&format!("glrt {name} 3D"), &base.image_type(vk::ImageType::TYPE_3D), vk::ImageViewType::TYPE_3D, vk::ImageAspectFlags::COLOR)?;
    let cube_info = base.image_type(vk::ImageType::TYPE_2D).array_layers(6).flags(vk::ImageCreateFlags::CUBE_COMPATIBLE);
    let cube = device.create_image(&format!("glrt {name} cube"), &cube_info, vk::ImageViewType::CUBE, vk::ImageAspectFlags::COLOR)?;
    for (image, layers) in [(&d2, 1), (&d3, 1), (&cube, 6)] {
        let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: layers };
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::UNDEFINED, vk::ImageLayout::TRANSFER_DST_OPTIMAL);
        // Safety: the image is in TRANSFER_DST_OPTIMAL.
        unsafe {
            device.raw.cmd_clear_color_image(cmd, image.raw, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &vk::ClearColorValue { float32: color }, &[range])
        };
        image_barrier(device, cmd, image.raw, range, vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    }
    Ok([d2, d3, cube])
}

/// Records a full barrier moving `range` of `image` between layouts.
pub fn image_barrier(device: &Device, cmd: vk::CommandBuffer, image: vk::Image, range: vk::ImageSubresourceRange, old: vk::ImageLayout, new: vk::ImageLayout) {
    let barrier = [vk::ImageMemoryBarrier2::default()
        .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
        .src_access_mask(vk::AccessFlags2::MEMORY_WRITE)
        .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
        .dst_access_mask(vk::AccessFlags2::MEMORY_READ | vk::AccessFlags2::MEMORY_WRITE)
        .old_layout(old)
        .new_layout(new)
        .image(image)
        .subresource_range(range)];
    // Safety: cmd is recording; the image is alive.
    unsafe { device.raw.cmd_pipeline_barrier2(cmd, &vk::DependencyInfo::default().image_memory_barriers(&barrier)) };
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn level(w: u32, h: u32, border: u32) -> Option<Arc<TexImage>> {
        let texels = (0..w * h * 4).map(|i| i as u8).collect();
        Some(Arc::new(TexImage { width: w, height: h, depth: 1, border, texels, ..TexImage::default() }))
    }

    #[test]
    fn chains_stop_at_a_level_that_does_not_halve() {
        let faces = vec![vec![level(8, 4, 0), level(4, 2, 0), level(2, 1, 0), level(1, 1, 0), level(1, 1, 0)]];
        assert_eq!(level_chain(&faces, 0, 1000, TextureKind::D2).len(), 4);
        assert_eq!(level_chain(&faces, 0, 1, TextureKind::D2).len(), 2);
        assert_eq!(level_chain(&faces, 1, 1000, TextureKind::D2).len(), 3);
        let broken = vec![vec![level(8, 8, 0), level(2, 2, 0)]];
        assert_eq!(level_chain(&broken, 0, 1000, TextureKind::D2).len(), 1);
    }

    #[test]
    fn borders_are_cut_off() {
        let img = level(4, 3, 1).unwrap();
        assert_eq!(interior(&img), [2, 1, 1]);
        let bytes = texel_bytes(&img, Upload::Rgba8);
        // Row 1, texels 1 and 2 of the 4-wide bordered image.
        let start = (4 + 1) * 4;
        assert_eq!(bytes, img.texels[start..start + 8].to_vec());
    }

    #[test]
    fn depth_modes_swizzle() {
        let s = depth_swizzle(DepthMode::Alpha, false);
        assert_eq!((s.r, s.a), (vk::ComponentSwizzle::ZERO, vk::ComponentSwizzle::R));
        assert_eq!(depth_swizzle(DepthMode::Luminance, true).a, vk::ComponentSwizzle::R);
        assert_eq!(nearest_border([1.0, 1.0, 1.0, 1.0]), vk::BorderColor::FLOAT_OPAQUE_WHITE);
        assert_eq!(nearest_border([0.0, 0.0, 0.0, 0.0]), vk::BorderColor::FLOAT_TRANSPARENT_BLACK);
    }
}

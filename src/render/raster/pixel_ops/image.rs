//! `glDrawPixels` (OpenGL 1.5 section 3.6.4–3.6.5) and the drawing half of `glCopyPixels`
//! (section 4.3.3): colour and depth images become fragments that are textured, summed and
//! fogged with the raster position's data ([`super::quads::raster_fragments`]) and go
//! through every per-fragment operation of the state; stencil images write the stencil buffer directly,
//! through the scissor test and the stencil write mask only, and depth/stencil images
//! (EXT_packed_depth_stencil section 4.3.1) write their depths too, through the depth mask,
//! whatever the depth test.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use super::super::device::Result;
use super::super::renderer::Recorder;
use super::quads::{fragment_state, push_image, raster_fragments, Quads};
use crate::frame::TextureUnit;
use crate::frame::pixels::{PixelData, RasterFragment};
use crate::frame::texture::{EnvMode, Filter, MinFilter, Sampler, TexImage, TextureContent, TextureEnv, TextureRef, Wrap};
use crate::frame::state::{CompareFunc, RasterState, Stencil, StencilOp};

/// Where and how an image is drawn.
pub struct Placement<'a> {
    /// Lower-left corner (the raster position) and depth.
    pub window_pos: [f32; 3],
    /// `glPixelZoom` factors.
    pub zoom: [f32; 2],
    /// Width of the image in pixels.
    pub width: usize,
    /// The current raster colour (the colour of depth-image fragments).
    pub color: [f32; 4],
    /// The state at the time of the operation.
    pub state: &'a RasterState,
    /// What the fragments take from the raster position.
    pub raster: &'a RasterFragment,
}

/// Colour images that need more rectangles than this (one per run of equal pixels) are drawn
/// as one rectangle textured with the image instead, unless texturing applies to the
/// fragments: the image would then need a texture unit of its own ahead of the program's, and
/// environments that read the primary colour would see the rectangle's instead of the
/// pixel's, so such images are always drawn as rectangles (slower, exact).
const MAX_RECTANGLES: usize = 1024;

/// Texture name of images drawn as textures (never a program's: the texture cache keys on
/// name and version, and these versions come from [`NEXT_IMAGE_VERSION`]).
const IMAGE_TEXTURE: u32 = u32::MAX;

/// Content versions of images drawn as textures: above every version translate hands out.
static NEXT_IMAGE_VERSION: AtomicU64 = AtomicU64::new(1 << 63);

/// A texture holding an RGBA8 image (rows bottom to top), sampled at the nearest texel
/// without mipmaps or wrapping, so each fragment takes the colour of its pixel (the texture
/// cache frees it a few frames after its last use).
fn image_texture(width: u32, height: u32, texels: Vec<u8>) -> TextureRef {
    let image = TexImage { width, height, depth: 1, border: 0, texels, ..TexImage::default() };
    let sampler = Sampler {
        min_filter: MinFilter { texel: Filter::Nearest, mipmap: None },
        mag_filter: Filter::Nearest,
        wrap: [Wrap::ClampToEdge; 3],
        levels: [0, 0],
        ..Sampler::default()
    };
    let content = TextureContent { faces: vec![vec![Some(Arc::new(image))]], sampler, ..TextureContent::default() };
    TextureRef { id: IMAGE_TEXTURE, version: NEXT_IMAGE_VERSION.fetch_add(1, Ordering::Relaxed), content: Arc::new(content) }
}

/// Records the fragments of an image.
pub fn record(rec: &mut Recorder<'_>, at: &Placement<'_>, data: &PixelData) -> Result<()> {
    let size = rec.target.size;
    let origin = [at.window_pos[0], at.window_pos[1]];
    let z = at.window_pos[2].clamp(0.0, 1.0);
    match data {
        PixelData::Rgba8(bytes) => {
            let pixels: Vec<[u8; 4]> = bytes.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
            let mut quads = Quads::default();
            push_image(&mut quads, origin, at.zoom, at.width, &pixels, |p| Some((z, p.map(|v| v as f32 / 255.0))));
            if quads.len() <= MAX_RECTANGLES || at.raster.textured() {
                return draw_fragments(rec, quads, at);
            }
            let height = pixels.len() / at.width.max(1);
            let mut textured = Quads::default();
            let far = [origin[0] + at.zoom[0] * at.width as f32, origin[1] + at.zoom[1] * height as f32];
            textured.push_textured([origin[0], origin[1], far[0], far[1]], z, [0.0, 0.0, 1.0, 1.0]);
            let mut draw = raster_fragments(textured, size, at.state, at.raster);
            let texels = bytes.get(..at.width * height * 4).unwrap_or_default().to_vec();
            draw.textures = vec![Some(image_texture(at.width as u32, height as u32, texels))];
            draw.texture_units = vec![Some(TextureUnit { env: TextureEnv { mode: EnvMode::Replace, ..TextureEnv::default() }, texgen: [None; 4] })];
            draw.texture_matrices = vec![Some(glam::Mat4::IDENTITY)];
            rec.draw(&draw)
        }
        PixelData::Depth(depths) => {
            let mut quads = Quads::default();
            let bits: Vec<u32> = depths.iter().map(|d| d.clamp(0.0, 1.0).to_bits()).collect();
            push_image(&mut quads, origin, at.zoom, at.width, &bits, |d| Some((f32::from_bits(d), at.color)));
            draw_fragments(rec, quads, at)
        }
        PixelData::Stencil(values) => write_stencil(rec, at, values, None),
        PixelData::DepthStencil(depths, values) => write_stencil(rec, at, values, Some(depths)),
    }
}

/// Writes the stencil indices `values` of an image (their low 8 bits) and, when `depths` are
/// given, the depths, bypassing every per-fragment operation but the scissor test: one draw
/// per distinct index replaces the stencil of its pixels through the stencil write mask and,
/// with depths, writes each pixel's depth through the depth mask with the depth test
/// passing always (EXT_packed_depth_stencil section 4.3.1: "the setting of DepthTest is
/// ignored"). Without depths nothing but the stencil is written.
fn write_stencil(rec: &mut Recorder<'_>, at: &Placement<'_>, values: &[u32], depths: Option<&[f32]>) -> Result<()> {
    let size = rec.target.size;
    let depth_bits = |i: usize| depths.and_then(|d| d.get(i)).map_or(0, |d| d.clamp(0.0, 1.0).to_bits());
    let pixels: Vec<(u8, u32)> = values.iter().enumerate().map(|(i, &v)| (v as u8, depth_bits(i))).collect();
    let indices: std::collections::BTreeSet<u8> = pixels.iter().map(|p| p.0).collect();
    for index in indices {
        let mut quads = Quads::default();
        let origin = [at.window_pos[0], at.window_pos[1]];
        push_image(&mut quads, origin, at.zoom, at.width, &pixels, |(v, d)| (v == index).then_some((f32::from_bits(d), [0.0; 4])));
        let mut state = stencil_write_state(at.state, size, index);
        if depths.is_some() {
            state.depth_test = Some(CompareFunc::Always);
            state.depth_write = at.state.depth_write;
        }
        draw(rec, quads, state)?;
    }
    Ok(())
}

/// Draws `quads` as fragments of the operation `at` places (nothing when empty).
pub fn draw_fragments(rec: &mut Recorder<'_>, quads: Quads, at: &Placement<'_>) -> Result<()> {
    if quads.is_empty() {
        return Ok(());
    }
    let size = rec.target.size;
    rec.draw(&raster_fragments(quads, size, at.state, at.raster))
}

/// Draws `quads` (nothing when empty).
pub fn draw(rec: &mut Recorder<'_>, quads: Quads, state: RasterState) -> Result<()> {
    if quads.is_empty() {
        return Ok(());
    }
    let size = rec.target.size;
    rec.draw(&quads.into_draw(size, state))
}

/// A state that writes `value` into the stencil buffer through the scissor test and the
/// stencil write mask (all bits when the stencil test is off, as the frame's state carries the
/// mask only with the test), and nothing else.
pub fn stencil_write_state(base: &RasterState, size: [u32; 2], value: u8) -> RasterState {
    let write_mask = base.stencil.map_or(0xff, |s| s.write_mask);
    let mut state = RasterState { scissor: base.scissor, ..fragment_state(&RasterState::default(), size) };
    state.color_mask = [false; 4];
    state.stencil = Some(Stencil {
        func: CompareFunc::Always,
        reference: value as i32,
        value_mask: 0xff,
        fail: StencilOp::Replace,
        depth_fail: StencilOp::Replace,
        depth_pass: StencilOp::Replace,
        write_mask,
    });
    state
}

//! Pixel operations on the GPU framebuffer (OpenGL 1.5 sections 3.6–3.7, 4.2.3–4.2.4, 4.3):
//! one module per operation. Fragments of bitmaps, images and copies are drawn as
//! window-aligned rectangles through the fixed-function pipelines with the state of the
//! operation ([`quads`]), so every per-fragment operation applies to them.
//!
//! Operations that read the framebuffer (`glCopyPixels`, `glAccum(GL_LOAD/GL_ACCUM)`) name the
//! rectangle they read through [`source`]; the renderer submits the frame so far, reads it
//! back and passes the pixels to [`record`] (the copy is therefore taken before any of it is
//! drawn: overlapping source and destination rectangles behave as the specification says).
//!
//! `glCopyTexImage*`/`glCopyTexSubImage*` ([`PixelKind::TextureCopy`]) need nothing here:
//! translate reads the pixels back at the copy and writes them into the texture's texels, so
//! the content version the operation names already holds them and the texture cache uploads
//! it like any other version.

pub mod accum;
pub mod bitmap;
pub mod clear;
pub mod image;
pub mod quads;

use super::device::Result;
use super::renderer::Recorder;
use crate::frame::pixels::{AccumOp, PixelBuffer, PixelData, PixelKind, PixelOp, clip_to_window};

/// The buffer and window rectangle `op` reads, when it reads the framebuffer; `size` is the
/// target's.
pub fn source(op: &PixelOp, size: [u32; 2]) -> Option<(PixelBuffer, [i32; 4])> {
    match op.kind {
        PixelKind::Copy { src, buffer, .. } => clip_to_window(src, size).map(|(rect, _)| (buffer, rect)),
        PixelKind::Accum { op: AccumOp::Load | AccumOp::Accum, .. } => {
            Some((PixelBuffer::Color, accum::Accum::area(size, op.state.scissor))).filter(|(_, r)| r[2] > 0 && r[3] > 0)
        }
        _ => None,
    }
}

/// Whether `op` writes colour fragments (everything but accumulation-buffer updates and
/// texture copies): the renderer records it once per draw buffer.
pub fn writes_color(op: &PixelOp) -> bool {
    !matches!(op.kind, PixelKind::TextureCopy { .. } | PixelKind::Accum { op: AccumOp::Load | AccumOp::Accum | AccumOp::Mult | AccumOp::Add, .. })
}

/// Records `op`; `read` holds the pixels of [`source`]'s rectangle when it names one (as
/// [`crate::frame::FrameSink::read_pixels`] returns them).
pub fn record(rec: &mut Recorder<'_>, accum: &mut accum::Accum, op: &PixelOp, read: Option<&[[f32; 4]]>) -> Result<()> {
    match &op.kind {
        PixelKind::Bitmap { window_pos, size, color, mask } => bitmap::record(rec, &op.state, &op.raster, *window_pos, size[0] as usize, *color, mask),
        PixelKind::Image { window_pos, zoom, size, color, data } => {
            let at = image::Placement { window_pos: *window_pos, zoom: *zoom, width: size[0] as usize, color: *color, state: &op.state, raster: &op.raster };
            image::record(rec, &at, data)
        }
        PixelKind::Copy { src, window_pos, zoom, buffer, color } => {
            let (Some(read), Some((rect, skipped))) = (read, clip_to_window(*src, rec.target.size)) else { return Ok(()) };
            let data = match buffer {
                PixelBuffer::Color => PixelData::Rgba8(read.iter().flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect()),
                PixelBuffer::Depth => PixelData::Depth(read.iter().map(|c| c[0]).collect()),
                PixelBuffer::Stencil => PixelData::Stencil(read.iter().map(|c| c[0] as u32).collect()),
            };
            // Source pixels outside the window produce no fragments: the copy starts that many
            // zoomed pixels further.
            let corner = [window_pos[0] + skipped[0] as f32 * zoom[0], window_pos[1] + skipped[1] as f32 * zoom[1], window_pos[2]];
            let at = image::Placement { window_pos: corner, zoom: *zoom, width: rect[2] as usize, color: *color, state: &op.state, raster: &op.raster };
            image::record(rec, &at, &data)
        }
        PixelKind::Accum { op: kind, value } => accum.apply(rec, &op.state, *kind, *value, read),
        PixelKind::TextureCopy { .. } => Ok(()),
    }
}

//! `glBitmap` (OpenGL 1.5 section 3.7): each set bit produces a fragment at its pixel with
//! the raster colour and depth and the raster position's other data (texture coordinates,
//! secondary colour, distance); the fragments go through texturing, colour sum, fog and every
//! per-fragment operation. Zoom does not apply to bitmaps.

use super::super::device::Result;
use super::super::renderer::Recorder;
use super::image::{draw_fragments, Placement};
use super::quads::{push_image, Quads};
use crate::frame::pixels::RasterFragment;
use crate::frame::state::RasterState;

/// Records a bitmap with lower-left corner `window_pos`, `width` pixels per row, coverage
/// `mask` (0 or 255 per pixel, rows bottom to top) and colour `color`, under `state` with the
/// raster position's `raster` data.
pub fn record(rec: &mut Recorder<'_>, state: &RasterState, raster: &RasterFragment, window_pos: [f32; 3], width: usize, color: [f32; 4], mask: &[u8]) -> Result<()> {
    let z = window_pos[2].clamp(0.0, 1.0);
    let mut quads = Quads::default();
    push_image(&mut quads, [window_pos[0], window_pos[1]], [1.0, 1.0], width, mask, |m| (m != 0).then_some((z, color)));
    let at = Placement { window_pos, zoom: [1.0, 1.0], width, color, state, raster };
    draw_fragments(rec, quads, &at)
}

//! `glClear` with masks (OpenGL 1.5 section 4.2.3): the cleared buffers and the parts the
//! write masks leave out. Buffers cleared whole (all colour channels, every stencil bit) use
//! the renderer's attachment clear; a partial colour mask or stencil write mask is honoured by
//! drawing a rectangle over the cleared area with those write masks.

use super::super::device::Result;
use super::super::renderer::Recorder;
use super::image::draw;
use super::quads::{fragment_state, Quads};
use crate::frame::state::{CompareFunc, RasterState, Stencil, StencilFaces, StencilOp};
use crate::frame::Clear;

/// Stencil bits of the framebuffer.
const STENCIL_BITS: u32 = 0xff;

/// Records `clear`.
pub fn record(rec: &mut Recorder<'_>, clear: &Clear) -> Result<()> {
    let full_color = clear.color_mask == [true; 4];
    let full_stencil = clear.stencil_mask & STENCIL_BITS == STENCIL_BITS;
    rec.clear(&Clear {
        color: clear.color.filter(|_| full_color),
        stencil: clear.stencil.filter(|_| full_stencil),
        stencil_mask: STENCIL_BITS,
        color_mask: [true; 4],
        ..clear.clone()
    });
    let color = clear.color.filter(|_| !full_color && clear.color_mask.iter().any(|&m| m));
    let stencil = clear.stencil.filter(|_| !full_stencil && clear.stencil_mask & STENCIL_BITS != 0);
    if color.is_none() && stencil.is_none() {
        return Ok(());
    }
    let size = rec.target.size;
    let mut state = fragment_state(&RasterState::default(), size);
    state.scissor = clear.scissor;
    state.dither = false;
    state.color_mask = if color.is_some() { clear.color_mask } else { [false; 4] };
    state.stencil = stencil.map(|value| StencilFaces::both(Stencil {
        func: CompareFunc::Always,
        reference: value & STENCIL_BITS as i32,
        value_mask: STENCIL_BITS,
        fail: StencilOp::Replace,
        depth_fail: StencilOp::Replace,
        depth_pass: StencilOp::Replace,
        write_mask: clear.stencil_mask & STENCIL_BITS,
    }));
    let mut quads = Quads::default();
    let rgba = color.unwrap_or_default().map(|v| v.clamp(0.0, 1.0));
    quads.push([0.0, 0.0, size[0] as f32, size[1] as f32], 0.0, rgba);
    draw(rec, quads, state)
}

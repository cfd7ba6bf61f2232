//! `glDrawPixels` (OpenGL 1.5 section 3.6.4–3.6.5) and the drawing half of `glCopyPixels`
//! (section 4.3.3): colour and depth images become fragments that go through every
//! per-fragment operation of the state; stencil images write the stencil buffer directly,
//! through the scissor test and the stencil write mask only.

use std::collections::BTreeMap;

use super::super::device::Result;
use super::super::renderer::Recorder;
use super::quads::{fragment_state, push_image, Quads};
use crate::frame::pixels::PixelData;
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
            draw(rec, quads, fragment_state(at.state, size))
        }
        PixelData::Depth(depths) => {
            let mut quads = Quads::default();
            let bits: Vec<u32> = depths.iter().map(|d| d.clamp(0.0, 1.0).to_bits()).collect();
            push_image(&mut quads, origin, at.zoom, at.width, &bits, |d| Some((f32::from_bits(d), at.color)));
            draw(rec, quads, fragment_state(at.state, size))
        }
        PixelData::Stencil(values) => {
            let mut groups: BTreeMap<u8, Quads> = BTreeMap::new();
            let values: Vec<u8> = values.iter().map(|&v| v as u8).collect();
            for &value in values.iter().collect::<std::collections::BTreeSet<_>>() {
                let quads = groups.entry(value).or_default();
                push_image(quads, origin, at.zoom, at.width, &values, |v| (v == value).then_some((0.0, [0.0; 4])));
            }
            for (value, quads) in groups {
                draw(rec, quads, stencil_write_state(at.state, size, value))?;
            }
            Ok(())
        }
    }
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

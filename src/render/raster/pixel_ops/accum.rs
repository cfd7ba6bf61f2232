//! The accumulation buffer (OpenGL 1.5 section 4.2.4), RGBA with `f32` components, kept in
//! host memory: `GL_LOAD` and `GL_ACCUM` read the colour buffer back (the renderer submits the
//! frame so far and waits), `GL_MULT` and `GL_ADD` work on the stored values, and `GL_RETURN`
//! draws `value × accum`, clamped to [0, 1], into the colour buffer through the scissor test
//! and the colour mask only. Every operation is limited to the scissor box when the scissor
//! test is on, like clears.
//!
//! Host memory keeps the buffer simple and exact; it costs a read-back per load or
//! accumulation, which suits the multi-pass effects (motion blur, depth of field,
//! antialiasing) that use it a few times per frame at small sizes.

use super::super::device::Result;
use super::super::renderer::Recorder;
use super::image::{self, Placement};
use super::quads::fragment_state;
use crate::frame::pixels::{AccumOp, PixelData, RasterFragment};
use crate::frame::state::RasterState;

/// The accumulation buffer: one RGBA value per pixel, rows bottom to top.
#[derive(Default)]
pub struct Accum {
    size: [u32; 2],
    values: Vec<[f32; 4]>,
}

impl Accum {
    /// Makes the buffer `size` (contents become zero when it changes: undefined in OpenGL).
    fn fit(&mut self, size: [u32; 2]) {
        if self.size != size {
            self.size = size;
            self.values = vec![[0.0; 4]; size[0] as usize * size[1] as usize];
        }
    }

    /// The window rectangle `[x, y, w, h]` an operation covers: the window, cut by `scissor`.
    pub fn area(size: [u32; 2], scissor: Option<[i32; 4]>) -> [i32; 4] {
        let [w, h] = [size[0] as i64, size[1] as i64];
        let [x, y, sw, sh] = scissor.map_or([0, 0, w, h], |s| s.map(|v| v as i64));
        let (x0, y0) = (x.clamp(0, w), y.clamp(0, h));
        let (x1, y1) = ((x + sw.max(0)).clamp(0, w), (y + sh.max(0)).clamp(0, h));
        [x0, y0, (x1 - x0).max(0), (y1 - y0).max(0)].map(|v| v as i32)
    }

    /// Sets `area` to `value` (`glClear` with `GL_ACCUM_BUFFER_BIT`).
    pub fn clear(&mut self, size: [u32; 2], scissor: Option<[i32; 4]>, value: [f32; 4]) {
        self.fit(size);
        let area = Self::area(size, scissor);
        self.update(area, None, |_, _| value);
    }

    /// Applies `f(accum, colour)` to each pixel of `area`; `colors` holds the colour buffer's
    /// pixels of `area` (rows bottom to top), or is `None` for operations that do not read it.
    fn update(&mut self, [x, y, w, h]: [i32; 4], colors: Option<&[[f32; 4]]>, f: impl Fn([f32; 4], [f32; 4]) -> [f32; 4]) {
        let width = self.size[0] as usize;
        for j in 0..h.max(0) as usize {
            for i in 0..w.max(0) as usize {
                let color = colors.and_then(|c| c.get(j * w as usize + i)).copied().unwrap_or_default();
                let index = (y as usize + j) * width + x as usize + i;
                if let Some(a) = self.values.get_mut(index) {
                    *a = f(*a, color);
                }
            }
        }
    }

    /// Records `op` with `value` for a target of the recorder's size under `state`; `colors`
    /// are the colour-buffer pixels of [`Accum::area`] for `GL_LOAD` and `GL_ACCUM`.
    pub fn apply(&mut self, rec: &mut Recorder<'_>, state: &RasterState, op: AccumOp, value: f32, colors: Option<&[[f32; 4]]>) -> Result<()> {
        let size = rec.target.size;
        self.fit(size);
        let area = Self::area(size, state.scissor);
        match op {
            AccumOp::Load => self.update(area, colors, |_, c| c.map(|v| v * value)),
            AccumOp::Accum => self.update(area, colors, |a, c| std::array::from_fn(|k| a[k] + c[k] * value)),
            AccumOp::Mult => self.update(area, None, |a, _| a.map(|v| v * value)),
            AccumOp::Add => self.update(area, None, |a, _| a.map(|v| v + value)),
            AccumOp::Return => return self.draw_return(rec, state, area, value),
        }
        Ok(())
    }

    /// `GL_RETURN`: draws `value × accum` over `area` with the colour mask of `state`.
    fn draw_return(&self, rec: &mut Recorder<'_>, state: &RasterState, [x, y, w, h]: [i32; 4], value: f32) -> Result<()> {
        if w <= 0 || h <= 0 {
            return Ok(());
        }
        let width = self.size[0] as usize;
        let mut bytes = Vec::with_capacity(w as usize * h as usize * 4);
        for j in 0..h as usize {
            let row = (y as usize + j) * width + x as usize;
            bytes.extend(self.values.get(row..row + w as usize).unwrap_or_default().iter().flat_map(|a| a.map(|v| quantize(v * value))));
        }
        let mut returned = fragment_state(&RasterState::default(), rec.target.size);
        returned.scissor = state.scissor;
        returned.color_mask = state.color_mask;
        // Returned values are colours, neither textured nor fogged.
        let untextured = RasterFragment::default();
        let at = Placement { window_pos: [x as f32, y as f32, 0.0], zoom: [1.0, 1.0], width: w as usize, color: [1.0; 4], state: &returned, raster: &untextured };
        image::record(rec, &at, &PixelData::Rgba8(bytes.into()))
    }

    /// The current values of `area` (tests).
    #[cfg(test)]
    fn read(&self, [x, y, w, h]: [i32; 4]) -> Vec<[f32; 4]> {
        let width = self.size[0] as usize;
        (0..h as usize).flat_map(|j| (0..w as usize).map(move |i| self.values[(y as usize + j) * width + x as usize + i])).collect()
    }
}

/// A returned component as the 8-bit colour buffer stores it (clamped to [0, 1]).
fn quantize(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_is_the_window_cut_by_the_scissor_box() {
        assert_eq!(Accum::area([8, 4], None), [0, 0, 8, 4]);
        assert_eq!(Accum::area([8, 4], Some([-2, 1, 5, 10])), [0, 1, 3, 3]);
        assert_eq!(Accum::area([8, 4], Some([9, 0, 5, 5]))[2], 0);
    }

    #[test]
    fn clear_mult_add_within_the_scissor_box() {
        let mut a = Accum::default();
        a.clear([4, 4], None, [0.5; 4]);
        a.clear([4, 4], Some([1, 1, 2, 2]), [0.25, 0.5, 0.75, 1.0]);
        a.update(Accum::area([4, 4], Some([1, 1, 1, 1])), None, |a, _| a.map(|v| v * 2.0));
        assert_eq!(a.read([0, 0, 1, 1]), vec![[0.5; 4]]);
        assert_eq!(a.read([1, 1, 2, 1]), vec![[0.5, 1.0, 1.5, 2.0], [0.25, 0.5, 0.75, 1.0]]);
        assert_eq!(quantize(1.5), 255);
        assert_eq!(quantize(-0.5), 0);
    }
}

//! `glBlitFramebufferEXT` (`GL_EXT_framebuffer_blit`): a rectangle of the read framebuffer
//! copied, scaled and possibly mirrored, into a rectangle of the draw framebuffer.
//!
//! The source is read back through the renderer now (as `glCopyPixels` across framebuffers
//! is), resampled on the CPU with the filter, and written as an image whose fragments bypass
//! every per-fragment operation but the pixel ownership and scissor tests (section 4.3.2 of
//! the extension).

use std::sync::Arc;

use super::super::Context;
use super::super::gl::{self, GLbitfield, GLenum, GLint};
use crate::frame::Framebuffer;
use crate::frame::pixels::{PixelBuffer, PixelData, PixelKind, PixelOp};
use crate::frame::state::CompareFunc;
use crate::frame::RasterState;

/// The buffers a blit can copy.
const BUFFER_BITS: GLbitfield = gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT;

/// Which images a framebuffer has: colour, depth, stencil (the window has all three).
fn images(framebuffer: &Framebuffer) -> [bool; 3] {
    match framebuffer {
        Framebuffer::Window => [true; 3],
        Framebuffer::Object(fbo) => [fbo.color.is_some(), fbo.depth.is_some(), fbo.stencil.is_some()],
    }
}

/// The source coordinate (continuous) that the centre of destination pixel `d` maps to.
fn source_at(d: i64, src: [GLint; 2], dst: [GLint; 2]) -> f64 {
    let (s0, s1, d0, d1) = (src[0] as f64, src[1] as f64, dst[0] as f64, dst[1] as f64);
    s0 + (d as f64 + 0.5 - d0) * (s1 - s0) / (d1 - d0)
}

/// A source image read back: `size` pixels from `origin`, rows bottom to top.
struct Source {
    origin: [i64; 2],
    size: [i64; 2],
    pixels: Vec<[f32; 4]>,
}

impl Source {
    /// The pixel at source coordinates (clamped into the image).
    fn at(&self, x: i64, y: i64) -> [f32; 4] {
        let x = (x - self.origin[0]).clamp(0, self.size[0] - 1);
        let y = (y - self.origin[1]).clamp(0, self.size[1] - 1);
        self.pixels[(y * self.size[0] + x) as usize]
    }

    /// The value at continuous source coordinates: the nearest pixel, or the bilinear blend
    /// of the four around it.
    fn sample(&self, x: f64, y: f64, linear: bool) -> [f32; 4] {
        if !linear {
            return self.at(x.floor() as i64, y.floor() as i64);
        }
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor() as i64, fy.floor() as i64);
        let (tx, ty) = ((fx - fx.floor()) as f32, (fy - fy.floor()) as f32);
        let mix = |a: [f32; 4], b: [f32; 4], t: f32| [0, 1, 2, 3].map(|i| a[i] + (b[i] - a[i]) * t);
        let bottom = mix(self.at(x0, y0), self.at(x0 + 1, y0), tx);
        let top = mix(self.at(x0, y0 + 1), self.at(x0 + 1, y0 + 1), tx);
        mix(bottom, top, ty)
    }
}

impl Context {
    /// `glBlitFramebufferEXT`: `GL_INVALID_VALUE` for mask bits other than the colour, depth
    /// and stencil buffers, `GL_INVALID_ENUM` for a filter other than `GL_NEAREST` and
    /// `GL_LINEAR`, `GL_INVALID_OPERATION` for depth or stencil with `GL_LINEAR`,
    /// `GL_INVALID_FRAMEBUFFER_OPERATION_EXT` when the read or draw framebuffer is incomplete.
    /// A buffer that either framebuffer lacks is not copied. glrt's depth and stencil images
    /// all have the same formats, so the format-match error cannot arise.
    #[allow(clippy::too_many_arguments)]
    pub fn glBlitFramebufferEXT(
        &mut self,
        srcX0: GLint,
        srcY0: GLint,
        srcX1: GLint,
        srcY1: GLint,
        dstX0: GLint,
        dstY0: GLint,
        dstX1: GLint,
        dstY1: GLint,
        mask: GLbitfield,
        filter: GLenum,
    ) {
        const CMD: &str = "glBlitFramebufferEXT";
        if mask & !BUFFER_BITS != 0 {
            return self.set_error_in(gl::GL_INVALID_VALUE, CMD);
        }
        let linear = match filter {
            gl::GL_NEAREST => false,
            gl::GL_LINEAR => true,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, CMD),
        };
        if linear && mask & (gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT) != 0 {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        }
        let (Ok(read), Ok(draw)) = (self.read_framebuffer_object(), self.draw_framebuffer()) else {
            return self.set_error_in(gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT, CMD);
        };
        let (has_read, has_draw) = (images(&read), images(&draw));
        let wanted = [gl::GL_COLOR_BUFFER_BIT, gl::GL_DEPTH_BUFFER_BIT, gl::GL_STENCIL_BUFFER_BIT].map(|b| mask & b != 0);
        let [color, depth, stencil] = [0, 1, 2].map(|i| wanted[i] && has_read[i] && has_draw[i]);
        if srcX0 == srcX1 || srcY0 == srcY1 || dstX0 == dstX1 || dstY0 == dstY1 {
            return;
        }
        let draw_size = match &draw {
            Framebuffer::Object(fbo) => fbo.size,
            Framebuffer::Window => self.frame.size,
        };
        let read_size = match &read {
            Framebuffer::Object(fbo) => fbo.size,
            Framebuffer::Window => self.frame.size,
        };
        // Destination pixels inside the draw framebuffer whose source pixel lies inside the read
        // framebuffer (the others are not written, as Mesa does; the specification leaves their
        // values undefined).
        let inside = |src: [GLint; 2], dst: [GLint; 2], draw: u32, read: u32| {
            let all = dst[0].min(dst[1]).max(0) as i64..dst[0].max(dst[1]).min(draw as GLint) as i64;
            let reads = |d: i64| (0..read as i64).contains(&(source_at(d, src, dst).floor() as i64));
            let first = all.clone().find(|&d| reads(d));
            let last = all.rev().find(|&d| reads(d));
            match (first, last) {
                (Some(a), Some(b)) => a..b + 1,
                _ => 0..0,
            }
        };
        let x_range = inside([srcX0, srcX1], [dstX0, dstX1], draw_size[0], read_size[0]);
        let y_range = inside([srcY0, srcY1], [dstY0, dstY1], draw_size[1], read_size[1]);
        if x_range.is_empty() || y_range.is_empty() {
            return;
        }
        // The source rectangle those pixels read, with one pixel around it for the filter.
        let (sx_a, sx_b) = (source_at(x_range.start, [srcX0, srcX1], [dstX0, dstX1]), source_at(x_range.end - 1, [srcX0, srcX1], [dstX0, dstX1]));
        let (sy_a, sy_b) = (source_at(y_range.start, [srcY0, srcY1], [dstY0, dstY1]), source_at(y_range.end - 1, [srcY0, srcY1], [dstY0, dstY1]));
        let x0 = (sx_a.min(sx_b).floor() as i64 - 1).clamp(0, read_size[0] as i64);
        let x1 = (sx_a.max(sx_b).floor() as i64 + 2).clamp(0, read_size[0] as i64);
        let y0 = (sy_a.min(sy_b).floor() as i64 - 1).clamp(0, read_size[1] as i64);
        let y1 = (sy_a.max(sy_b).floor() as i64 + 2).clamp(0, read_size[1] as i64);
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let rect = [x0 as i32, y0 as i32, (x1 - x0) as i32, (y1 - y0) as i32];
        let read_back = |ctx: &mut Context, buffer| {
            ctx.read_framebuffer(buffer, rect).map(|pixels| Source { origin: [x0, y0], size: [x1 - x0, y1 - y0], pixels })
        };
        let resample = |source: &Source, linear: bool| -> Vec<[f32; 4]> {
            let mut out = Vec::with_capacity(x_range.clone().count() * y_range.clone().count());
            for y in y_range.clone() {
                let sy = source_at(y, [srcY0, srcY1], [dstY0, dstY1]);
                for x in x_range.clone() {
                    out.push(source.sample(source_at(x, [srcX0, srcX1], [dstX0, dstX1]), sy, linear));
                }
            }
            out
        };
        let mut images = Vec::new();
        if color
            && let Some(source) = read_back(self, PixelBuffer::Color) {
                let bytes: Vec<u8> = resample(&source, linear).iter().flat_map(|c| c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)).collect();
                images.push((PixelData::Rgba8(bytes.into()), false));
            }
        let depths = if depth { read_back(self, PixelBuffer::Depth).map(|s| resample(&s, false).iter().map(|p| p[0]).collect::<Vec<f32>>()) } else { None };
        let stencils = if stencil { read_back(self, PixelBuffer::Stencil).map(|s| resample(&s, false).iter().map(|p| p[0] as u32).collect::<Vec<u32>>()) } else { None };
        match (depths, stencils) {
            (Some(d), Some(s)) => images.push((PixelData::DepthStencil(d.into(), s.into()), true)),
            (Some(d), None) => images.push((PixelData::Depth(d.into()), true)),
            (None, Some(s)) => images.push((PixelData::Stencil(s.into()), true)),
            (None, None) => {}
        }
        let base = self.raster_snapshot();
        self.enter_framebuffer(&base.framebuffer);
        for (data, depth_stencil) in images {
            let state = RasterState {
                viewport: base.viewport,
                scissor: base.scissor,
                color_mask: [!depth_stencil; 4],
                depth_test: depth_stencil.then_some(CompareFunc::Always),
                depth_write: depth_stencil,
                draw_buffers: base.draw_buffers,
                read_buffer: base.read_buffer,
                framebuffer: base.framebuffer.clone(),
                ..RasterState::default()
            };
            let kind = PixelKind::Image {
                window_pos: [x_range.start as f32, y_range.start as f32, 0.0],
                zoom: [1.0; 2],
                size: [(x_range.end - x_range.start) as u32, (y_range.end - y_range.start) as u32],
                color: [1.0; 4],
                data,
            };
            let (before_draw, after_clears) = (self.frame.draws.len(), self.frame.clears.len());
            self.frame.pixels.push(PixelOp { before_draw, after_clears, kind, state: Arc::new(state), raster: Arc::default() });
        }
        self.keep_frame_in_budget();
    }
}

//! Texture images attached to framebuffer objects: `translate`'s texture levels stay the one
//! truth, the renderer's framebuffer images follow them.
//!
//! - **Entering**: before the first draw, clear or pixel operation that goes to a framebuffer
//!   object after it was bound (or after its attachments changed), the texels of each texture
//!   level attached are drawn into the renderer's image as a pixel operation that bypasses
//!   every fragment operation (the colour image as an RGBA image, a depth level as depth
//!   values). The renderer's image then holds what the texture holds, whatever was drawn
//!   into it through another framebuffer object or uploaded since.
//! - **Writing back**: when drawing moves away from that framebuffer object (another binding,
//!   a changed attachment, deleting it) or a texture command reads or changes texture images
//!   (`glGetTexImage`, `glGenerateMipmapEXT`), the attached levels are read back through the
//!   renderer ([`crate::frame::FrameSink::read_pixels`]) and written into the textures, which
//!   get a new content version; draws that sample them afterwards see what was rendered.
//!
//! A write-back waits for the GPU, so a program that renders to a texture every frame pays one
//! read-back per frame: correct first, a GPU-side copy can replace it later without changing
//! this contract.

use std::sync::Arc;

use crate::frame::framebuffer::{Attachment, FramebufferObject};
use crate::frame::pixels::{PixelBuffer, PixelData, PixelKind, PixelOp};
use crate::frame::state::CompareFunc;
use crate::frame::{DrawBuffers, Framebuffer, RasterState};
use crate::translate::Context;
use crate::translate::pixels::transfer::Unpacked;
use crate::translate::texture::formats;

/// Which framebuffer object's texture images are in the renderer's images.
#[derive(Clone, Debug, Default)]
pub struct SyncState {
    /// The framebuffer object drawn into since it was bound (its texture levels were loaded
    /// into the renderer and are written back when drawing moves elsewhere).
    entered: Option<Arc<FramebufferObject>>,
}

impl Context {
    /// Called before a draw, clear or pixel operation going to `framebuffer` enters the frame:
    /// loads the texture images of a framebuffer object entered now (see the module doc).
    pub(crate) fn enter_framebuffer(&mut self, framebuffer: &Framebuffer) {
        let Framebuffer::Object(fbo) = framebuffer else { return };
        if self.framebuffers.sync.entered.as_ref() == Some(fbo) {
            return;
        }
        // The attachments changed under the binding without a write-back point (a texture
        // level respecified): what was drawn into the old images is obsolete.
        self.framebuffers.sync.entered = Some(fbo.clone());
        for (attachment, depth) in [(fbo.color, false), (fbo.depth, true)] {
            let Some(Attachment::Texture { name, face, level, slice }) = attachment else { continue };
            let Some(data) = self.attached_texels(name, face, level, slice, depth) else { continue };
            let state = RasterState {
                viewport: [0, 0, fbo.size[0] as i32, fbo.size[1] as i32],
                color_mask: [!depth; 4],
                depth_test: depth.then_some(CompareFunc::Always),
                depth_write: depth,
                draw_buffers: DrawBuffers { front: false, back: true },
                framebuffer: framebuffer.clone(),
                ..RasterState::default()
            };
            let kind = PixelKind::Image { window_pos: [0.0; 3], zoom: [1.0; 2], size: fbo.size, color: [1.0; 4], data };
            let (before_draw, after_clears) = (self.frame.draws.len(), self.frame.clears.len());
            self.frame.pixels.push(PixelOp { before_draw, after_clears, kind, state: Arc::new(state), raster: Arc::default() });
        }
    }

    /// The texels of slice `slice` of a texture level, as colour or depth pixel data.
    fn attached_texels(&self, name: u32, face: u32, level: u32, slice: u32, depth: bool) -> Option<PixelData> {
        let shared = self.shared.lock();
        let lvl = shared.textures.get(name)?.level(face as usize, level as usize)?;
        let [w, h, _] = lvl.size;
        let texels = w * h;
        let first = slice as usize * texels;
        Some(if depth {
            PixelData::Depth(lvl.image.depth_values.get(first..first + texels)?.into())
        } else {
            PixelData::Rgba8(lvl.image.texels.get(first * 4..(first + texels) * 4)?.into())
        })
    }

    /// Reads the texture images of the framebuffer object entered last back into their
    /// textures (see the module doc); nothing when none was entered.
    pub(crate) fn write_back_framebuffer(&mut self) {
        let Some(fbo) = self.framebuffers.sync.entered.take() else { return };
        let rect = [0, 0, fbo.size[0] as i32, fbo.size[1] as i32];
        for (attachment, depth) in [(fbo.color, false), (fbo.depth, true)] {
            let Some(Attachment::Texture { name, face, level, slice }) = attachment else { continue };
            self.frame.read_framebuffer = Framebuffer::Object(fbo.clone());
            let data = if !depth {
                self.sink.read_pixels(&self.frame, PixelBuffer::Color, rect).map(Unpacked::Rgba)
            } else {
                let read = |ctx: &mut Context, buffer| ctx.sink.read_pixels(&ctx.frame, buffer, rect).map(|v| v.into_iter().map(|p| p[0]));
                let Some(values) = read(self, PixelBuffer::Depth) else { continue };
                let depths: Vec<f32> = values.collect();
                let internal = self.shared.lock().textures.get(name).and_then(|t| t.level(face as usize, level as usize)).map(|l| l.internal_format);
                if internal.is_some_and(|i| formats::stencil_bits(i) > 0) {
                    read(self, PixelBuffer::Stencil).map(|s| Unpacked::DepthStencil(depths, s.map(|v| v as i64).collect()))
                } else {
                    Some(Unpacked::Depth(depths))
                }
            };
            if let Some(data) = data {
                self.write_texture_region(name, face as usize, level as usize, [0, 0, slice as usize], [fbo.size[0] as usize, fbo.size[1] as usize, 1], data);
            }
        }
        self.frame.read_framebuffer = Framebuffer::Window;
    }
}

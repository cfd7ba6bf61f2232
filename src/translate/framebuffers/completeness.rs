//! Framebuffer completeness (EXT_framebuffer_object section 4.4.4) and the description of a
//! complete framebuffer object that the frame carries ([`crate::frame::framebuffer`]).

use std::sync::Arc;

use super::objects::{Attached, FramebufferObject, Holds, Point, renders_exactly, texture_holds};
use crate::frame::framebuffer::{self, Attachment};
use crate::translate::context::SharedObjects;
use crate::translate::gl::{self, GLenum};
use crate::translate::texture::Target;

/// One attachment resolved against the share group's objects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Image {
    /// Its identity for the renderer.
    pub attachment: Attachment,
    /// Width and height.
    pub size: [u32; 2],
    /// What it holds.
    pub holds: Holds,
    /// Border width of a texture level (glrt renders only to levels without one).
    pub border: usize,
    /// Whether its format keeps more than glrt's 8-bit colour buffers render
    /// ([`super::objects::renders_exactly`]).
    pub beyond_8_bits: bool,
}

/// The image attached as `attached`, if it exists (a renderbuffer with storage, a texture
/// level that is specified); `None` when the name or level no longer exists or holds nothing
/// renderable.
pub fn resolve(shared: &SharedObjects, attached: Attached) -> Option<Image> {
    match attached {
        Attached::Renderbuffer(name) => {
            let rb = shared.fbos.renderbuffers.get(name)?;
            let holds = rb.holds?;
            if rb.size.contains(&0) {
                return None;
            }
            let beyond_8_bits = !renders_exactly(rb.internal_format);
            Some(Image { attachment: Attachment::Renderbuffer { name, storage: rb.storage }, size: rb.size, holds, border: 0, beyond_8_bits })
        }
        Attached::Texture { name, kind, face, level, slice } => {
            let obj = shared.textures.get(name)?;
            let lvl = obj.level(face as usize, level as usize)?;
            let holds = texture_holds(lvl.base, lvl.internal_format)?;
            let [w, h, d] = lvl.size;
            if w == 0 || h == 0 || (kind == Target::D3 && slice as usize >= d) {
                return None;
            }
            Some(Image {
                attachment: Attachment::Texture { name, face, level, slice },
                size: [w as u32, h as u32],
                holds,
                border: lvl.border,
                beyond_8_bits: !renders_exactly(lvl.internal_format),
            })
        }
    }
}

/// The status `glCheckFramebufferStatusEXT` reports for `fbo`, and on completeness the
/// description the frame carries.
pub fn check(shared: &SharedObjects, fbo: &FramebufferObject) -> Result<Arc<framebuffer::FramebufferObject>, GLenum> {
    let mut images = [None; 3];
    for point in [Point::Color, Point::Depth, Point::Stencil] {
        let Some(attached) = fbo.attached[point.index()] else { continue };
        let image = resolve(shared, attached).ok_or(gl::GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT_EXT)?;
        let fits = match point {
            Point::Color => matches!(image.holds, Holds::Color { .. }),
            Point::Depth => image.holds.depth(),
            Point::Stencil => image.holds.stencil(),
        };
        if !fits {
            return Err(gl::GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT_EXT);
        }
        images[point.index()] = Some(image);
    }
    let present: Vec<&Image> = images.iter().flatten().collect();
    let Some(first) = present.first() else { return Err(gl::GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT_EXT) };
    if present.iter().any(|i| i.size != first.size) {
        return Err(gl::GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS_EXT);
    }
    let [color, depth, stencil] = images;
    if fbo.draw_buffer != gl::GL_NONE && color.is_none() {
        return Err(gl::GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER_EXT);
    }
    if fbo.read_buffer != gl::GL_NONE && color.is_none() {
        return Err(gl::GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER_EXT);
    }
    // glrt's renderer keeps depth and stencil in one image: separate depth and stencil images
    // are a combination it does not support (section 4.4.4 allows refusing any), and so are
    // texture levels with a border, and formats with more than 8 bits, signed or floating-point
    // colour (rendering to them at 8 bits would lose what they keep).
    let separate = matches!((depth, stencil), (Some(d), Some(s)) if d.attachment != s.attachment);
    if separate || present.iter().any(|i| i.border != 0 || i.beyond_8_bits) {
        return Err(gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT);
    }
    Ok(Arc::new(framebuffer::FramebufferObject {
        size: first.size,
        color: color.map(|i| i.attachment),
        depth: depth.map(|i| i.attachment),
        stencil: stencil.map(|i| i.attachment),
        alpha: color.is_none_or(|i| i.holds == Holds::Color { alpha: true }),
    }))
}

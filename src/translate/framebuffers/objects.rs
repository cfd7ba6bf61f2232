//! Renderbuffer and framebuffer objects of a share group (EXT_framebuffer_object sections
//! 4.4.1–4.4.2): names, storage, attachment points.

use std::collections::HashMap;

use crate::translate::gl::{self, GLenum, GLuint};
use crate::translate::texture::Target;
use crate::translate::texture::formats::{self, Base};
use crate::frame::texture::{Precision, TexelFormat};

/// What a renderbuffer's internal format holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Holds {
    /// Colour; `alpha` when the base format is RGBA.
    Color {
        /// The base format has alpha.
        alpha: bool,
    },
    /// Depth values.
    Depth,
    /// Stencil indices.
    Stencil,
    /// Both (`GL_DEPTH_STENCIL_EXT` formats).
    DepthStencil,
}

impl Holds {
    /// Whether depth values are held.
    pub fn depth(self) -> bool {
        matches!(self, Holds::Depth | Holds::DepthStencil)
    }
    /// Whether stencil indices are held.
    pub fn stencil(self) -> bool {
        matches!(self, Holds::Stencil | Holds::DepthStencil)
    }
}

/// What `internal` holds as a renderbuffer format (colour-, depth- or stencil-renderable, as
/// EXT_framebuffer_object section 4.4.2.1 and EXT_packed_depth_stencil list them), or `None`.
pub fn renderbuffer_format(internal: GLenum) -> Option<Holds> {
    match internal {
        gl::GL_STENCIL_INDEX | gl::GL_STENCIL_INDEX1_EXT | gl::GL_STENCIL_INDEX4_EXT | gl::GL_STENCIL_INDEX8_EXT | gl::GL_STENCIL_INDEX16_EXT => {
            Some(Holds::Stencil)
        }
        // Unsized and numbered formats of glTexImage are not renderbuffer formats but RGB/RGBA.
        1..=4 => None,
        _ => match formats::internal_format(internal)? {
            _ if is_compressed(internal) => None,
            f => match f.base {
                Base::Texel(TexelFormat::Rgb | TexelFormat::Red | TexelFormat::Rg) => Some(Holds::Color { alpha: false }),
                Base::Texel(TexelFormat::Rgba) => Some(Holds::Color { alpha: true }),
                Base::Texel(TexelFormat::Depth) if formats::stencil_bits(internal) > 0 => Some(Holds::DepthStencil),
                Base::Texel(TexelFormat::Depth) => Some(Holds::Depth),
                _ => None,
            },
        },
    }
}

/// Whether glrt renders to an image of `internal` without loss: colour formats of at most 8
/// unsigned-normalized (or sRGB) bits a component, and depth/stencil formats. Others, integer
/// formats (EXT_texture_integer allows this) included, are `GL_FRAMEBUFFER_UNSUPPORTED_EXT`
/// when attached.
pub fn renders_exactly(internal: GLenum) -> bool {
    formats::internal_format(internal).is_none_or(|i| i.base == Base::Texel(TexelFormat::Depth) || matches!(i.storage.precision(), Precision::Unorm8 | Precision::Srgb8))
}

/// Whether `internal` is a compressed format (never renderable).
fn is_compressed(internal: GLenum) -> bool {
    matches!(internal, gl::GL_COMPRESSED_ALPHA..=gl::GL_COMPRESSED_RGBA)
        || matches!(internal, gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT..=gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT)
        || matches!(internal, gl::GL_COMPRESSED_SRGB..=gl::GL_COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT | gl::GL_COMPRESSED_RED | gl::GL_COMPRESSED_RG)
}

/// What a texture level of `base` and `internal` format holds when attached, if renderable
/// (EXT_framebuffer_object: RGB and RGBA colour, depth; never compressed).
pub fn texture_holds(base: Base, internal: GLenum) -> Option<Holds> {
    if is_compressed(internal) {
        return None;
    }
    match base {
        Base::Texel(TexelFormat::Rgb | TexelFormat::Red | TexelFormat::Rg) => Some(Holds::Color { alpha: false }),
        Base::Texel(TexelFormat::Rgba) => Some(Holds::Color { alpha: true }),
        Base::Texel(TexelFormat::Depth) if formats::stencil_bits(internal) > 0 => Some(Holds::DepthStencil),
        Base::Texel(TexelFormat::Depth) => Some(Holds::Depth),
        _ => None,
    }
}

/// A renderbuffer object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Renderbuffer {
    /// Width and height (0 until storage is allocated).
    pub size: [u32; 2],
    /// `GL_RENDERBUFFER_INTERNAL_FORMAT_EXT` (initially `GL_RGBA`).
    pub internal_format: GLenum,
    /// What the storage holds (`None` before `glRenderbufferStorageEXT`).
    pub holds: Option<Holds>,
    /// Storage version, unique in the process (see [`crate::frame::framebuffer::Attachment`]).
    pub storage: u64,
}

impl Default for Renderbuffer {
    fn default() -> Renderbuffer {
        Renderbuffer { size: [0, 0], internal_format: gl::GL_RGBA, holds: None, storage: crate::translate::texture::objects::next_version() }
    }
}

/// What is attached at one attachment point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Attached {
    /// A renderbuffer, by name.
    Renderbuffer(GLuint),
    /// A texture image: name, kind, cube face, level and 3D slice.
    Texture {
        /// Texture name.
        name: GLuint,
        /// The texture's kind (the attaching command's target).
        kind: Target,
        /// Cube face (0 unless a cube map).
        face: u32,
        /// Level.
        level: u32,
        /// Slice of a 3D texture.
        slice: u32,
    },
}

/// The attachment points glrt has: one colour attachment (`GL_MAX_COLOR_ATTACHMENTS_EXT` is
/// 1), depth and stencil.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Point {
    /// `GL_COLOR_ATTACHMENT0_EXT`.
    Color,
    /// `GL_DEPTH_ATTACHMENT_EXT`.
    Depth,
    /// `GL_STENCIL_ATTACHMENT_EXT`.
    Stencil,
}

impl Point {
    /// The point `attachment` names: `Err(GL_INVALID_ENUM)` for anything else (colour
    /// attachments past the first included).
    pub fn from_gl(attachment: GLenum) -> Result<Point, GLenum> {
        match attachment {
            gl::GL_COLOR_ATTACHMENT0_EXT => Ok(Point::Color),
            gl::GL_DEPTH_ATTACHMENT_EXT => Ok(Point::Depth),
            gl::GL_STENCIL_ATTACHMENT_EXT => Ok(Point::Stencil),
            _ => Err(gl::GL_INVALID_ENUM),
        }
    }

    /// Index into [`FramebufferObject::attached`].
    pub fn index(self) -> usize {
        self as usize
    }
}

/// A framebuffer object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramebufferObject {
    /// Attachments at colour, depth and stencil ([`Point::index`]).
    pub attached: [Option<Attached>; 3],
    /// `GL_DRAW_BUFFER` while bound (initially `GL_COLOR_ATTACHMENT0_EXT`).
    pub draw_buffer: GLenum,
    /// `GL_READ_BUFFER` while bound.
    pub read_buffer: GLenum,
}

impl Default for FramebufferObject {
    fn default() -> FramebufferObject {
        FramebufferObject { attached: [None; 3], draw_buffer: gl::GL_COLOR_ATTACHMENT0_EXT, read_buffer: gl::GL_COLOR_ATTACHMENT0_EXT }
    }
}

/// Objects by name; a name is reserved by `glGen*` (`None`) and becomes an object when first
/// bound.
#[derive(Debug)]
pub struct Table<T> {
    objects: HashMap<GLuint, Option<T>>,
}

impl<T> Default for Table<T> {
    fn default() -> Table<T> {
        Table { objects: HashMap::new() }
    }
}

impl<T: Default> Table<T> {
    /// Reserves `count` unused names.
    pub fn generate(&mut self, count: usize) -> Vec<GLuint> {
        let mut names = Vec::with_capacity(count.min(1 << 16));
        let mut candidate: GLuint = 1;
        while names.len() < count {
            if let std::collections::hash_map::Entry::Vacant(slot) = self.objects.entry(candidate) {
                slot.insert(None);
                names.push(candidate);
            }
            candidate = candidate.wrapping_add(1).max(1);
        }
        names
    }

    /// The object `name` (created if the name is unused or only reserved).
    pub fn bind(&mut self, name: GLuint) -> &mut T {
        self.objects.entry(name).or_default().get_or_insert_with(T::default)
    }

    /// Whether `name` is an object (bound at least once).
    pub fn is_object(&self, name: GLuint) -> bool {
        matches!(self.objects.get(&name), Some(Some(_)))
    }

    /// The object `name`.
    pub fn get(&self, name: GLuint) -> Option<&T> {
        self.objects.get(&name)?.as_ref()
    }

    /// The object `name`, mutable.
    pub fn get_mut(&mut self, name: GLuint) -> Option<&mut T> {
        self.objects.get_mut(&name)?.as_mut()
    }

    /// Frees `name`; returns the object it was.
    pub fn delete(&mut self, name: GLuint) -> Option<T> {
        self.objects.remove(&name).flatten()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renderable_formats() {
        assert_eq!(renderbuffer_format(gl::GL_RGBA8), Some(Holds::Color { alpha: true }));
        assert_eq!(renderbuffer_format(gl::GL_RGB5), Some(Holds::Color { alpha: false }));
        assert_eq!(renderbuffer_format(gl::GL_DEPTH_COMPONENT24), Some(Holds::Depth));
        assert_eq!(renderbuffer_format(gl::GL_DEPTH24_STENCIL8), Some(Holds::DepthStencil));
        assert_eq!(renderbuffer_format(gl::GL_STENCIL_INDEX8_EXT), Some(Holds::Stencil));
        for not in [gl::GL_LUMINANCE8, gl::GL_ALPHA, 3, gl::GL_COMPRESSED_RGB, gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, gl::GL_COLOR_INDEX8_EXT, gl::GL_TEXTURE_2D] {
            assert_eq!(renderbuffer_format(not), None, "{not:#x}");
        }
        assert_eq!(texture_holds(Base::Texel(TexelFormat::Luminance), gl::GL_LUMINANCE8), None);
        assert_eq!(texture_holds(Base::Texel(TexelFormat::Rgb), gl::GL_RGB8), Some(Holds::Color { alpha: false }));
    }

    #[test]
    fn names_are_reserved_then_created_by_binding() {
        let mut t: Table<Renderbuffer> = Table::default();
        let names = t.generate(2);
        assert_eq!(names, [1, 2]);
        assert!(!t.is_object(1));
        t.bind(1);
        assert!(t.is_object(1));
        t.bind(7);
        assert_eq!(t.generate(1), [3]);
        assert!(t.delete(1).is_some());
        assert!(!t.is_object(1));
    }
}

//! Where draws, clears and pixel operations go: the window's framebuffer or a framebuffer
//! object (`EXT_framebuffer_object`), as the renderer sees it.
//!
//! A framebuffer object is described by the images attached to it. The renderer keeps one
//! set of images per distinct description ([`FramebufferObject::key`]) for as long as the
//! attachments live ([`crate::frame::Frame::released`] names those that died). Texture
//! attachments are kept in sync by `translate`: when drawing starts on a framebuffer object,
//! it draws the attached texture levels' texels into the renderer's image first (a pixel
//! operation that bypasses every fragment operation), and when drawing moves elsewhere it
//! reads the rendered pixels back into the texture level (`translate::framebuffers`). So
//! the texture's content in `translate` stays the one truth and the renderer needs no notion
//! of images shared between textures and framebuffers.

use std::sync::Arc;

/// The framebuffer an operation draws into or reads from.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum Framebuffer {
    /// The window-system-provided framebuffer of the drawable (name 0).
    #[default]
    Window,
    /// A framebuffer object.
    Object(Arc<FramebufferObject>),
}

impl Framebuffer {
    /// The framebuffer object, if any.
    pub fn object(&self) -> Option<&FramebufferObject> {
        match self {
            Framebuffer::Window => None,
            Framebuffer::Object(fbo) => Some(fbo),
        }
    }
}

/// A complete framebuffer object: its size and the images attached.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct FramebufferObject {
    /// Width and height in pixels (all attachments have this size).
    pub size: [u32; 2],
    /// The image at `GL_COLOR_ATTACHMENT0_EXT`.
    pub color: Option<Attachment>,
    /// The image at `GL_DEPTH_ATTACHMENT_EXT`.
    pub depth: Option<Attachment>,
    /// The image at `GL_STENCIL_ATTACHMENT_EXT` (the same as `depth` for a packed
    /// depth/stencil renderbuffer attached at both points).
    pub stencil: Option<Attachment>,
    /// Whether the colour image has alpha (false for RGB formats: alpha then reads 1).
    pub alpha: bool,
}

/// The renderer's identity of a framebuffer object's images: equal keys share images.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FramebufferKey {
    /// Width and height.
    pub size: [u32; 2],
    /// Colour image.
    pub color: Option<Attachment>,
    /// Depth/stencil image (the depth attachment, else the stencil attachment).
    pub depth_stencil: Option<Attachment>,
    /// Whether the colour image has alpha.
    pub alpha: bool,
}

impl Attachment {
    /// Whether `self` is an image of the object `released` names (for textures any image of
    /// the texture, see [`crate::frame::Frame::released`]).
    pub fn same_object(&self, released: &Attachment) -> bool {
        match (self, released) {
            (Attachment::Texture { name: a, .. }, Attachment::Texture { name: b, .. }) => a == b,
            (a, b) => a == b,
        }
    }
}

impl FramebufferKey {
    /// Whether one of the images is of the object `released` names.
    pub fn uses(&self, released: &Attachment) -> bool {
        [self.color, self.depth_stencil].iter().flatten().any(|a| a.same_object(released))
    }
}

impl FramebufferObject {
    /// The key the renderer keeps this framebuffer's images under.
    pub fn key(&self) -> FramebufferKey {
        FramebufferKey { size: self.size, color: self.color, depth_stencil: self.depth.or(self.stencil), alpha: self.alpha }
    }
}

/// One attached image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Attachment {
    /// A renderbuffer: its name and the version of its storage (each
    /// `glRenderbufferStorageEXT` gives a new one, unique in the process).
    Renderbuffer {
        /// Renderbuffer name.
        name: u32,
        /// Storage version.
        storage: u64,
    },
    /// A level of a texture: its name, cube face (0 unless a cube map), level, and the slice
    /// of a 3D texture.
    Texture {
        /// Texture name.
        name: u32,
        /// Cube face.
        face: u32,
        /// Mipmap level.
        level: u32,
        /// Slice of a 3D texture (0 otherwise).
        slice: u32,
    },
}

//! Framebuffer objects (`GL_EXT_framebuffer_object`): renderbuffers, framebuffer objects,
//! their attachments and completeness, the framebuffer-dependent state while one is bound,
//! and `glGenerateMipmapEXT`.
//!
//! Draws, clears and pixel operations go to the framebuffer bound when they are issued
//! ([`crate::frame::RasterState::framebuffer`], [`crate::frame::Clear::framebuffer`]); reads
//! come from it ([`crate::frame::Frame::read_framebuffer`]). Texture images attached to a
//! framebuffer object are kept in `translate` as the one truth (see [`sync`]).
//!
//! Choices where the specification leaves room: one colour attachment
//! (`GL_MAX_COLOR_ATTACHMENTS_EXT` is 1); colour images are stored with 8 bits per component,
//! depth with 24 bits and stencil with 8, whatever the internal format; separate depth and
//! stencil images, and texture levels with a border, are `GL_FRAMEBUFFER_UNSUPPORTED_EXT`.
//! Framebuffer and renderbuffer objects are shared by the share group, as textures are.

pub mod blit;
pub mod completeness;
pub mod objects;
pub mod sync;

use objects::{Attached, FramebufferObject, Holds, Point, Renderbuffer};
use super::Context;
use super::convert::{read_slice, write_slice};
use super::get::Value;
use super::gl::{self, GLboolean, GLenum, GLint, GLsizei, GLuint};
use super::limits::{MAX_3D_TEXTURE_SIZE, MAX_TEXTURE_SIZE};
use super::texture::Target;
use crate::frame::Framebuffer;

/// Framebuffer-object state of a context.
#[derive(Clone, Debug, Default)]
pub struct FramebufferState {
    /// `GL_FRAMEBUFFER_BINDING_EXT`, the draw framebuffer (0: the window).
    pub bound: GLuint,
    /// `GL_READ_FRAMEBUFFER_BINDING_EXT` (`GL_EXT_framebuffer_blit`): the framebuffer reads
    /// come from (0: the window).
    pub read_bound: GLuint,
    /// `GL_RENDERBUFFER_BINDING_EXT`.
    pub renderbuffer: GLuint,
    /// Texture attachments drawn into and not read back yet ([`sync`]).
    pub(crate) sync: sync::SyncState,
}

/// Renderbuffer and framebuffer objects of a share group.
#[derive(Debug, Default)]
pub struct FramebufferTables {
    /// Renderbuffers by name.
    pub renderbuffers: objects::Table<Renderbuffer>,
    /// Framebuffer objects by name.
    pub framebuffers: objects::Table<FramebufferObject>,
}

impl Context {
    /// The framebuffer draws go to now: the window, the bound framebuffer object when it is
    /// complete, `Err(status)` when it is not.
    pub(crate) fn draw_framebuffer(&self) -> Result<Framebuffer, GLenum> {
        self.framebuffer_named(self.framebuffers.bound)
    }

    /// The framebuffer reads come from now, as [`Context::draw_framebuffer`] says.
    pub(crate) fn read_framebuffer_object(&self) -> Result<Framebuffer, GLenum> {
        self.framebuffer_named(self.framebuffers.read_bound)
    }

    /// The window for 0, else framebuffer object `name` when it is complete.
    fn framebuffer_named(&self, name: GLuint) -> Result<Framebuffer, GLenum> {
        if name == 0 {
            return Ok(Framebuffer::Window);
        }
        let shared = self.shared.lock();
        let fbo = shared.fbos.framebuffers.get(name).cloned().unwrap_or_default();
        completeness::check(&shared, &fbo).map(Framebuffer::Object)
    }

    /// The binding a `glFramebuffer*EXT`/`glCheckFramebufferStatusEXT` target names:
    /// `GL_FRAMEBUFFER_EXT` and `GL_DRAW_FRAMEBUFFER_EXT` the draw framebuffer,
    /// `GL_READ_FRAMEBUFFER_EXT` the read framebuffer; `GL_INVALID_ENUM` for others.
    fn binding_of(&self, target: GLenum) -> Result<GLuint, GLenum> {
        match target {
            gl::GL_FRAMEBUFFER_EXT | gl::GL_DRAW_FRAMEBUFFER_EXT => Ok(self.framebuffers.bound),
            gl::GL_READ_FRAMEBUFFER_EXT => Ok(self.framebuffers.read_bound),
            _ => Err(gl::GL_INVALID_ENUM),
        }
    }

    /// Raises `GL_INVALID_FRAMEBUFFER_OPERATION_EXT` in `command` and returns true when the
    /// bound framebuffer object is not complete (commands that draw or read then do nothing).
    pub(crate) fn framebuffer_incomplete(&mut self, command: &'static str) -> bool {
        if self.framebuffers.bound != 0 && self.draw_framebuffer().is_err() {
            self.set_error_in(gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT, command);
            return true;
        }
        false
    }

    /// The draw framebuffer object's `GL_DRAW_BUFFER`, if one is bound.
    pub(crate) fn object_draw_buffer(&self) -> Option<GLenum> {
        self.object_buffer(self.framebuffers.bound, false)
    }

    /// The read framebuffer object's `GL_READ_BUFFER`, if one is bound.
    pub(crate) fn object_read_buffer(&self) -> Option<GLenum> {
        self.object_buffer(self.framebuffers.read_bound, true)
    }

    /// `GL_READ_BUFFER` (`read`) or `GL_DRAW_BUFFER` of framebuffer object `name`; `None` for
    /// the window.
    fn object_buffer(&self, name: GLuint, read: bool) -> Option<GLenum> {
        if name == 0 {
            return None;
        }
        let shared = self.shared.lock();
        let fbo = shared.fbos.framebuffers.get(name).cloned().unwrap_or_default();
        Some(if read { fbo.read_buffer } else { fbo.draw_buffer })
    }

    /// `glDrawBuffer`/`glReadBuffer` while a framebuffer object is bound: `GL_NONE` or
    /// `GL_COLOR_ATTACHMENT0_EXT`; other colour attachments are `GL_INVALID_VALUE` (there is
    /// one), window buffers `GL_INVALID_OPERATION`. Returns false when no object is bound.
    pub(crate) fn set_object_buffer(&mut self, buf: GLenum, read: bool, command: &'static str) -> bool {
        let bound = if read { self.framebuffers.read_bound } else { self.framebuffers.bound };
        if bound == 0 {
            return false;
        }
        let result = match buf {
            gl::GL_NONE if read => Ok(()),
            gl::GL_NONE | gl::GL_COLOR_ATTACHMENT0_EXT => Ok(()),
            b if (gl::GL_COLOR_ATTACHMENT1_EXT..=gl::GL_COLOR_ATTACHMENT15_EXT).contains(&b) => Err(gl::GL_INVALID_VALUE),
            gl::GL_FRONT_LEFT | gl::GL_FRONT_RIGHT | gl::GL_BACK_LEFT | gl::GL_BACK_RIGHT | gl::GL_FRONT | gl::GL_BACK | gl::GL_LEFT
            | gl::GL_RIGHT | gl::GL_FRONT_AND_BACK | gl::GL_AUX0 | gl::GL_AUX1 | gl::GL_AUX2 | gl::GL_AUX3 => Err(gl::GL_INVALID_OPERATION),
            _ => Err(gl::GL_INVALID_ENUM),
        };
        match result {
            Ok(()) => {
                {
                    let mut shared = self.shared.lock();
                    let fbo = shared.fbos.framebuffers.bind(bound);
                    if read { fbo.read_buffer = buf } else { fbo.draw_buffer = buf }
                }
                self.framebuffer_changed();
            }
            Err(e) => self.set_error_in(e, command),
        }
        true
    }

    /// Something the draw framebuffer's description depends on changed: texture levels drawn
    /// so far are read back and the raster snapshot is rebuilt.
    fn framebuffer_changed(&mut self) {
        self.write_back_framebuffer();
        self.fixed_mut();
    }

    /// `glGenRenderbuffersEXT`: `GL_INVALID_VALUE` for a negative count.
    ///
    /// # Safety
    /// `renderbuffers` must have room for `n` names.
    pub unsafe fn glGenRenderbuffersEXT(&mut self, n: GLsizei, renderbuffers: *mut GLuint) {
        // Safety: as this function's.
        unsafe { self.generate_names(n, renderbuffers, "glGenRenderbuffersEXT", |t, count| t.renderbuffers.generate(count)) }
    }

    /// `glGenFramebuffersEXT`: `GL_INVALID_VALUE` for a negative count.
    ///
    /// # Safety
    /// `framebuffers` must have room for `n` names.
    pub unsafe fn glGenFramebuffersEXT(&mut self, n: GLsizei, framebuffers: *mut GLuint) {
        // Safety: as this function's.
        unsafe { self.generate_names(n, framebuffers, "glGenFramebuffersEXT", |t, count| t.framebuffers.generate(count)) }
    }

    /// Writes `n` names reserved by `generate` to `names`.
    ///
    /// # Safety
    /// `names` must have room for `n` names.
    unsafe fn generate_names(&mut self, n: GLsizei, names: *mut GLuint, command: &'static str, generate: impl FnOnce(&mut FramebufferTables, usize) -> Vec<GLuint>) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, command) };
        if names.is_null() {
            return self.null_pointer(command);
        }
        let reserved = generate(&mut self.shared.lock().fbos, count);
        // Safety: the caller guarantees room for n names.
        unsafe { write_slice(names, &reserved) };
    }

    /// `glBindRenderbufferEXT`: `GL_INVALID_ENUM` unless `target` is `GL_RENDERBUFFER_EXT`;
    /// binding an unused name creates the object.
    pub fn glBindRenderbufferEXT(&mut self, target: GLenum, renderbuffer: GLuint) {
        if target != gl::GL_RENDERBUFFER_EXT {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glBindRenderbufferEXT");
        }
        if renderbuffer != 0 {
            self.shared.lock().fbos.renderbuffers.bind(renderbuffer);
        }
        self.framebuffers.renderbuffer = renderbuffer;
    }

    /// `glBindFramebufferEXT`: `GL_FRAMEBUFFER_EXT` binds the draw and the read framebuffer,
    /// `GL_DRAW_FRAMEBUFFER_EXT` and `GL_READ_FRAMEBUFFER_EXT` (`GL_EXT_framebuffer_blit`) one
    /// of them, other targets are `GL_INVALID_ENUM`; binding an unused name creates the
    /// object. Texture images drawn into through the previous draw binding are read back into
    /// their textures first.
    pub fn glBindFramebufferEXT(&mut self, target: GLenum, framebuffer: GLuint) {
        let (draw, read) = match target {
            gl::GL_FRAMEBUFFER_EXT => (true, true),
            gl::GL_DRAW_FRAMEBUFFER_EXT => (true, false),
            gl::GL_READ_FRAMEBUFFER_EXT => (false, true),
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, "glBindFramebufferEXT"),
        };
        if framebuffer != 0 {
            self.shared.lock().fbos.framebuffers.bind(framebuffer);
        }
        if read {
            self.framebuffers.read_bound = framebuffer;
        }
        if draw && self.framebuffers.bound != framebuffer {
            self.framebuffer_changed();
            self.framebuffers.bound = framebuffer;
        }
    }

    /// `glIsRenderbufferEXT`.
    pub fn glIsRenderbufferEXT(&mut self, renderbuffer: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().fbos.renderbuffers.is_object(renderbuffer))
    }

    /// `glIsFramebufferEXT`.
    pub fn glIsFramebufferEXT(&mut self, framebuffer: GLuint) -> GLboolean {
        GLboolean::from(self.shared.lock().fbos.framebuffers.is_object(framebuffer))
    }

    /// `glDeleteRenderbuffersEXT`: a deleted renderbuffer is unbound, and detached from the
    /// bound framebuffer object (section 4.4.2.1); its image is released in the renderer.
    ///
    /// # Safety
    /// `renderbuffers` must point to `n` names.
    pub unsafe fn glDeleteRenderbuffersEXT(&mut self, n: GLsizei, renderbuffers: *const GLuint) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteRenderbuffersEXT") };
        // Safety: the caller guarantees n readable names.
        let Some(names) = (unsafe { read_slice(renderbuffers, count) }) else { return self.null_pointer("glDeleteRenderbuffersEXT") };
        for name in names.into_iter().filter(|&n| n != 0) {
            self.detach_everywhere(|a| a == Attached::Renderbuffer(name));
            if let Some(rb) = self.shared.lock().fbos.renderbuffers.delete(name) {
                self.frame.released.push(crate::frame::framebuffer::Attachment::Renderbuffer { name, storage: rb.storage });
            }
            if self.framebuffers.renderbuffer == name {
                self.framebuffers.renderbuffer = 0;
            }
        }
    }

    /// `glDeleteFramebuffersEXT`: deleting the bound one binds the window's framebuffer.
    ///
    /// # Safety
    /// `framebuffers` must point to `n` names.
    pub unsafe fn glDeleteFramebuffersEXT(&mut self, n: GLsizei, framebuffers: *const GLuint) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteFramebuffersEXT") };
        // Safety: the caller guarantees n readable names.
        let Some(names) = (unsafe { read_slice(framebuffers, count) }) else { return self.null_pointer("glDeleteFramebuffersEXT") };
        for name in names.into_iter().filter(|&n| n != 0) {
            if self.framebuffers.bound == name {
                self.glBindFramebufferEXT(gl::GL_DRAW_FRAMEBUFFER_EXT, 0);
            }
            if self.framebuffers.read_bound == name {
                self.framebuffers.read_bound = 0;
            }
            self.shared.lock().fbos.framebuffers.delete(name);
        }
    }

    /// Removes attachments matching `which` from the bound framebuffer object (deleting a
    /// texture or renderbuffer detaches it from the bound framebuffer only, section 4.4.2.1).
    pub(crate) fn detach_everywhere(&mut self, which: impl Fn(Attached) -> bool) {
        let bound = self.framebuffers.bound;
        if bound == 0 {
            return;
        }
        let changed = {
            let mut shared = self.shared.lock();
            let Some(fbo) = shared.fbos.framebuffers.get_mut(bound) else { return };
            let mut changed = false;
            for slot in &mut fbo.attached {
                if slot.is_some_and(&which) {
                    *slot = None;
                    changed = true;
                }
            }
            changed
        };
        if changed {
            self.framebuffer_changed();
        }
    }

    /// `glRenderbufferStorageEXT`: `GL_INVALID_ENUM` for another target or a format that is
    /// not colour-, depth- or stencil-renderable, `GL_INVALID_VALUE` for a size outside
    /// [0, `GL_MAX_RENDERBUFFER_SIZE_EXT`], `GL_INVALID_OPERATION` with no renderbuffer bound.
    pub fn glRenderbufferStorageEXT(&mut self, target: GLenum, internalformat: GLenum, width: GLsizei, height: GLsizei) {
        const CMD: &str = "glRenderbufferStorageEXT";
        if target != gl::GL_RENDERBUFFER_EXT {
            return self.set_error_in(gl::GL_INVALID_ENUM, CMD);
        }
        let Some(holds) = objects::renderbuffer_format(internalformat) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let max = MAX_TEXTURE_SIZE as GLsizei;
        if !(0..=max).contains(&width) || !(0..=max).contains(&height) {
            return self.set_error_in(gl::GL_INVALID_VALUE, CMD);
        }
        let name = self.framebuffers.renderbuffer;
        if name == 0 {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        }
        let old = {
            let mut shared = self.shared.lock();
            let rb = shared.fbos.renderbuffers.bind(name);
            let old = rb.storage;
            *rb = Renderbuffer { size: [width as u32, height as u32], internal_format: internalformat, holds: Some(holds), ..Renderbuffer::default() };
            old
        };
        self.frame.released.push(crate::frame::framebuffer::Attachment::Renderbuffer { name, storage: old });
        self.framebuffer_changed();
    }

    /// `glGetRenderbufferParameterivEXT`: width, height, internal format and component sizes
    /// of the bound renderbuffer; `GL_INVALID_ENUM` for another target or parameter,
    /// `GL_INVALID_OPERATION` with none bound.
    ///
    /// # Safety
    /// `params` must have room for one integer.
    pub unsafe fn glGetRenderbufferParameterivEXT(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        const CMD: &str = "glGetRenderbufferParameterivEXT";
        if target != gl::GL_RENDERBUFFER_EXT {
            return self.set_error_in(gl::GL_INVALID_ENUM, CMD);
        }
        let name = self.framebuffers.renderbuffer;
        if name == 0 {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        }
        let rb = self.shared.lock().fbos.renderbuffers.get(name).cloned().unwrap_or_default();
        let bits = |on: bool, n: i64| if on { n } else { 0 };
        let value = match pname {
            gl::GL_RENDERBUFFER_WIDTH_EXT => i64::from(rb.size[0]),
            gl::GL_RENDERBUFFER_HEIGHT_EXT => i64::from(rb.size[1]),
            gl::GL_RENDERBUFFER_INTERNAL_FORMAT_EXT => i64::from(rb.internal_format),
            gl::GL_RENDERBUFFER_RED_SIZE_EXT | gl::GL_RENDERBUFFER_GREEN_SIZE_EXT | gl::GL_RENDERBUFFER_BLUE_SIZE_EXT => {
                bits(matches!(rb.holds, Some(Holds::Color { .. })), 8)
            }
            gl::GL_RENDERBUFFER_ALPHA_SIZE_EXT => bits(rb.holds == Some(Holds::Color { alpha: true }), 8),
            gl::GL_RENDERBUFFER_DEPTH_SIZE_EXT => bits(rb.holds.is_some_and(Holds::depth), 24),
            gl::GL_RENDERBUFFER_STENCIL_SIZE_EXT => bits(rb.holds.is_some_and(Holds::stencil), 8),
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, CMD),
        };
        if params.is_null() {
            return self.null_pointer(CMD);
        }
        // Safety: the caller guarantees room for one integer.
        unsafe { write_slice(params, &[value as GLint]) };
    }

    /// `glCheckFramebufferStatusEXT`: the completeness of the framebuffer bound to `target`
    /// (`GL_FRAMEBUFFER_COMPLETE_EXT` for the window's); 0 and `GL_INVALID_ENUM` for a target
    /// that is not a framebuffer target.
    pub fn glCheckFramebufferStatusEXT(&mut self, target: GLenum) -> GLenum {
        let name = match self.binding_of(target) {
            Ok(name) => name,
            Err(e) => {
                self.set_error_in(e, "glCheckFramebufferStatusEXT");
                return 0;
            }
        };
        match self.framebuffer_named(name) {
            Ok(_) => gl::GL_FRAMEBUFFER_COMPLETE_EXT,
            Err(status) => status,
        }
    }

    /// `glFramebufferRenderbufferEXT`: attaches `renderbuffer` (0 detaches).
    /// `GL_INVALID_ENUM` for a bad target, attachment point or renderbuffer target,
    /// `GL_INVALID_OPERATION` with no framebuffer object bound or for a name that is not a
    /// renderbuffer.
    pub fn glFramebufferRenderbufferEXT(&mut self, target: GLenum, attachment: GLenum, renderbuffertarget: GLenum, renderbuffer: GLuint) {
        const CMD: &str = "glFramebufferRenderbufferEXT";
        let point = match self.attachment_point(target, attachment) {
            Ok(p) => p,
            Err(e) => return self.set_error_in(e, CMD),
        };
        if renderbuffertarget != gl::GL_RENDERBUFFER_EXT {
            return self.set_error_in(gl::GL_INVALID_ENUM, CMD);
        }
        if renderbuffer != 0 && !self.shared.lock().fbos.renderbuffers.is_object(renderbuffer) {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        }
        self.attach(point, (renderbuffer != 0).then_some(Attached::Renderbuffer(renderbuffer)));
    }

    /// `glFramebufferTexture1DEXT`.
    pub fn glFramebufferTexture1DEXT(&mut self, target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint) {
        self.framebuffer_texture(1, target, attachment, textarget, texture, level, 0, "glFramebufferTexture1DEXT");
    }

    /// `glFramebufferTexture2DEXT` (2D textures and cube-map faces).
    pub fn glFramebufferTexture2DEXT(&mut self, target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint) {
        self.framebuffer_texture(2, target, attachment, textarget, texture, level, 0, "glFramebufferTexture2DEXT");
    }

    /// `glFramebufferTexture3DEXT`: slice `zoffset` of a 3D texture.
    pub fn glFramebufferTexture3DEXT(&mut self, target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint, zoffset: GLint) {
        self.framebuffer_texture(3, target, attachment, textarget, texture, level, zoffset, "glFramebufferTexture3DEXT");
    }

    /// The `glFramebufferTexture*DEXT` commands (section 4.4.2.2): texture 0 detaches;
    /// otherwise `GL_INVALID_OPERATION` when `texture` is not a texture of the kind
    /// `textarget` names, `GL_INVALID_ENUM` for a `textarget` the command does not take,
    /// `GL_INVALID_VALUE` for a level or slice out of range.
    #[allow(clippy::too_many_arguments)]
    fn framebuffer_texture(&mut self, dims: usize, target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint, zoffset: GLint, command: &'static str) {
        let point = match self.attachment_point(target, attachment) {
            Ok(p) => p,
            Err(e) => return self.set_error_in(e, command),
        };
        if texture == 0 {
            return self.attach(point, None);
        }
        let cube_face = (gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X..=gl::GL_TEXTURE_CUBE_MAP_NEGATIVE_Z).contains(&textarget);
        let (kind, face) = match (dims, textarget) {
            (1, gl::GL_TEXTURE_1D) => (Target::D1, 0),
            (2, gl::GL_TEXTURE_2D) => (Target::D2, 0),
            (2, gl::GL_TEXTURE_RECTANGLE_ARB) => (Target::Rect, 0),
            (2, _) if cube_face => (Target::Cube, textarget - gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X),
            (3, gl::GL_TEXTURE_3D) => (Target::D3, 0),
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, command),
        };
        // Rectangle textures have level 0 only (ARB_texture_rectangle with EXT_framebuffer_object).
        let max_level = kind.max_levels() as GLint - 1;
        if !(0..=max_level).contains(&level) || !(0..MAX_3D_TEXTURE_SIZE as GLint).contains(&zoffset) {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let is_kind = self.shared.lock().textures.get(texture).is_some_and(|t| t.target == Some(kind));
        if !is_kind {
            return self.set_error_in(gl::GL_INVALID_OPERATION, command);
        }
        self.attach(point, Some(Attached::Texture { name: texture, kind, face, level: level as u32, slice: zoffset as u32 }));
    }

    /// The framebuffer object and attachment point of a `glFramebuffer*EXT` command, after
    /// checking `target` and that a framebuffer object is bound to it.
    fn attachment_point(&self, target: GLenum, attachment: GLenum) -> Result<(GLuint, Point), GLenum> {
        let bound = self.binding_of(target)?;
        if bound == 0 {
            return Err(gl::GL_INVALID_OPERATION);
        }
        Ok((bound, Point::from_gl(attachment)?))
    }

    /// Sets what framebuffer object `bound` has at `point`.
    fn attach(&mut self, (bound, point): (GLuint, Point), what: Option<Attached>) {
        self.write_back_framebuffer();
        self.shared.lock().fbos.framebuffers.bind(bound).attached[point.index()] = what;
        self.fixed_mut();
    }

    /// `glGetFramebufferAttachmentParameterivEXT` (section 6.1.3 of the extension):
    /// `GL_INVALID_ENUM` for a bad target, attachment or parameter (texture parameters of a
    /// renderbuffer or an empty point included), `GL_INVALID_OPERATION` with no framebuffer
    /// object bound.
    ///
    /// # Safety
    /// `params` must have room for one integer.
    pub unsafe fn glGetFramebufferAttachmentParameterivEXT(&mut self, target: GLenum, attachment: GLenum, pname: GLenum, params: *mut GLint) {
        const CMD: &str = "glGetFramebufferAttachmentParameterivEXT";
        let (bound, point) = match self.attachment_point(target, attachment) {
            Ok(p) => p,
            Err(e) => return self.set_error_in(e, CMD),
        };
        let attached = self.shared.lock().fbos.framebuffers.get(bound).and_then(|f| f.attached[point.index()]);
        let value = match (pname, attached) {
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_EXT, None) => i64::from(gl::GL_NONE),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_EXT, Some(Attached::Renderbuffer(_))) => i64::from(gl::GL_RENDERBUFFER_EXT),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_EXT, Some(Attached::Texture { .. })) => i64::from(gl::GL_TEXTURE),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME_EXT, Some(Attached::Renderbuffer(name) | Attached::Texture { name, .. })) => i64::from(name),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL_EXT, Some(Attached::Texture { level, .. })) => i64::from(level),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE_EXT, Some(Attached::Texture { kind, face, .. })) => {
                if kind == Target::Cube { i64::from(gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X + face) } else { 0 }
            }
            (gl::GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_3D_ZOFFSET_EXT, Some(Attached::Texture { slice, .. })) => i64::from(slice),
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, CMD),
        };
        if params.is_null() {
            return self.null_pointer(CMD);
        }
        // Safety: the caller guarantees room for one integer.
        unsafe { write_slice(params, &[value as GLint]) };
    }

    /// `glGenerateMipmapEXT`: the levels below the base level of the texture bound to
    /// `target`, from the base level (as `GL_GENERATE_MIPMAP` makes them). `GL_INVALID_ENUM`
    /// for a target that is not 1D, 2D, 3D or a cube map; `GL_INVALID_OPERATION` for a cube
    /// map whose base levels are not cube complete.
    pub fn glGenerateMipmapEXT(&mut self, target: GLenum) {
        let Some(kind) = Target::from_gl(target).filter(|&t| t != Target::Rect) else {
            return self.set_error_in(gl::GL_INVALID_ENUM, "glGenerateMipmapEXT");
        };
        self.write_back_framebuffer();
        let generated = self.with_bound_texture(kind, |obj| {
            let base = obj.params.levels[0].max(0) as usize;
            let faces = kind.faces();
            let sizes: Vec<Option<[usize; 3]>> = (0..faces).map(|f| obj.level(f, base).map(|l| l.size)).collect();
            if kind == Target::Cube && (sizes.iter().any(Option::is_none) || sizes.windows(2).any(|w| w[0] != w[1])) {
                return false;
            }
            for face in 0..faces {
                if obj.level(face, base).is_some() {
                    super::texture::mipmap::generate(obj, face, base);
                }
            }
            obj.touch();
            true
        });
        if !generated {
            self.set_error_in(gl::GL_INVALID_OPERATION, "glGenerateMipmapEXT");
        }
    }

    /// Framebuffer-object queries: the bindings and limits, and, while a framebuffer object
    /// is bound, the framebuffer-dependent values of tables 6.31–6.33 (bit depths of its
    /// images, no multisampling, no accumulation buffer, single-buffered).
    pub(crate) fn query_framebuffers(&self, pname: GLenum) -> Option<Value> {
        match pname {
            gl::GL_FRAMEBUFFER_BINDING_EXT => return Some(Value::int(self.framebuffers.bound)),
            gl::GL_READ_FRAMEBUFFER_BINDING_EXT => return Some(Value::int(self.framebuffers.read_bound)),
            gl::GL_RENDERBUFFER_BINDING_EXT => return Some(Value::int(self.framebuffers.renderbuffer)),
            gl::GL_MAX_RENDERBUFFER_SIZE_EXT => return Some(Value::int(MAX_TEXTURE_SIZE as i64)),
            gl::GL_MAX_COLOR_ATTACHMENTS_EXT => return Some(Value::int(1)),
            gl::GL_READ_BUFFER => return self.object_read_buffer().map(Value::int),
            _ => {}
        }
        let draw = self.object_draw_buffer()?;
        let holds = |point: Point| {
            let shared = self.shared.lock();
            let attached = shared.fbos.framebuffers.get(self.framebuffers.bound)?.attached[point.index()]?;
            completeness::resolve(&shared, attached).map(|i| i.holds)
        };
        let bits = |on: bool, n: i64| Value::int(if on { n } else { 0 });
        Some(match pname {
            gl::GL_RED_BITS | gl::GL_GREEN_BITS | gl::GL_BLUE_BITS => bits(matches!(holds(Point::Color), Some(Holds::Color { .. })), 8),
            gl::GL_ALPHA_BITS => bits(holds(Point::Color) == Some(Holds::Color { alpha: true }), 8),
            gl::GL_DEPTH_BITS => bits(holds(Point::Depth).is_some_and(Holds::depth), 24),
            gl::GL_STENCIL_BITS => bits(holds(Point::Stencil).is_some_and(Holds::stencil), 8),
            gl::GL_ACCUM_RED_BITS | gl::GL_ACCUM_GREEN_BITS | gl::GL_ACCUM_BLUE_BITS | gl::GL_ACCUM_ALPHA_BITS => Value::int(0),
            gl::GL_SAMPLE_BUFFERS | gl::GL_SAMPLES => Value::int(0),
            gl::GL_DOUBLEBUFFER => Value::bool(false),
            gl::GL_DRAW_BUFFER => Value::int(draw),
            _ => return None,
        })
    }
}

/// Whether a framebuffer-object description has what a raster state needs: the depth and
/// stencil tests act as if disabled without a depth or stencil image (EXT_framebuffer_object
/// sections 4.1.5–4.1.6), and colour writes as if masked without a colour image.
pub fn restrict_state(state: &mut crate::frame::RasterState) {
    let Framebuffer::Object(fbo) = &state.framebuffer else { return };
    let (depth, stencil, color) = (fbo.depth.is_some(), fbo.stencil.is_some(), fbo.color.is_some());
    if !depth {
        state.depth_test = None;
        state.depth_write = false;
    }
    if !stencil {
        state.stencil = None;
    }
    if !color {
        state.color_mask = [false; 4];
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::Framebuffer;
    use crate::translate::{Context, gl};

    /// A context with framebuffer object 1 bound.
    fn bound() -> Context {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindFramebufferEXT(gl::GL_FRAMEBUFFER_EXT, 1);
        ctx
    }

    /// Renderbuffer `name` with storage of `format`, `w` × `h`.
    fn storage(ctx: &mut Context, name: u32, format: gl::GLenum, w: i32, h: i32) {
        ctx.glBindRenderbufferEXT(gl::GL_RENDERBUFFER_EXT, name);
        ctx.glRenderbufferStorageEXT(gl::GL_RENDERBUFFER_EXT, format, w, h);
    }

    fn status(ctx: &mut Context) -> gl::GLenum {
        ctx.glCheckFramebufferStatusEXT(gl::GL_FRAMEBUFFER_EXT)
    }

    #[test]
    fn formats_beyond_8_bits_are_unsupported_attachments() {
        let mut ctx = bound();
        for (format, want) in [
            (gl::GL_RGBA16F, gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT),
            (gl::GL_RGB16, gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT),
            (gl::GL_RG8_SNORM, gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT),
            (gl::GL_RG8, gl::GL_FRAMEBUFFER_COMPLETE_EXT),
            (gl::GL_SRGB8_ALPHA8, gl::GL_FRAMEBUFFER_COMPLETE_EXT),
            // EXT_texture_integer allows integer attachments to be unsupported.
            (gl::GL_RGBA8UI_EXT, gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT),
            (gl::GL_RGB32I_EXT, gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT),
        ] {
            let integer = matches!(format, gl::GL_RGBA8UI_EXT | gl::GL_RGB32I_EXT);
            let (pixels, type_) = if integer { (gl::GL_RGBA_INTEGER_EXT, gl::GL_INT) } else { (gl::GL_RGBA, gl::GL_FLOAT) };
            storage(&mut ctx, 1, format, 16, 16);
            ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_RENDERBUFFER_EXT, 1);
            assert_eq!((ctx.glGetError(), status(&mut ctx)), (gl::GL_NO_ERROR, want), "renderbuffer {format:#x}");
            ctx.glBindTexture(gl::GL_TEXTURE_2D, 5);
            unsafe { ctx.glTexImage2D(gl::GL_TEXTURE_2D, 0, format as i32, 16, 16, 0, pixels, type_, std::ptr::null()) };
            ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_2D, 5, 0);
            assert_eq!((ctx.glGetError(), status(&mut ctx)), (gl::GL_NO_ERROR, want), "texture {format:#x}");
        }
    }

    #[test]
    fn completeness_follows_section_4_4_4() {
        let mut ctx = bound();
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT_EXT);
        storage(&mut ctx, 1, gl::GL_RGBA8, 16, 16);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_RENDERBUFFER_EXT, 1);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
        storage(&mut ctx, 2, gl::GL_DEPTH_COMPONENT24, 8, 16);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_DEPTH_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 2);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_DIMENSIONS_EXT);
        storage(&mut ctx, 2, gl::GL_DEPTH_COMPONENT24, 16, 16);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
        // A colour renderbuffer at the depth point.
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_DEPTH_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 1);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT_EXT);
        // Separate depth and stencil images: refused as unsupported.
        storage(&mut ctx, 3, gl::GL_STENCIL_INDEX8_EXT, 16, 16);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_DEPTH_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 2);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_STENCIL_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 3);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_UNSUPPORTED_EXT);
        // A packed depth/stencil renderbuffer at both points is supported.
        storage(&mut ctx, 4, gl::GL_DEPTH24_STENCIL8, 16, 16);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_DEPTH_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 4);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_STENCIL_ATTACHMENT_EXT, gl::GL_RENDERBUFFER_EXT, 4);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
        let Ok(Framebuffer::Object(fbo)) = ctx.draw_framebuffer() else { panic!("complete") };
        assert_eq!(fbo.size, [16, 16]);
        assert_eq!(fbo.depth, fbo.stencil);
        // Without a colour image the draw buffer must be GL_NONE.
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_RENDERBUFFER_EXT, 0);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER_EXT);
        ctx.glDrawBuffer(gl::GL_NONE);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER_EXT);
        ctx.glReadBuffer(gl::GL_NONE);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_COMPLETE_EXT);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn incomplete_framebuffers_refuse_drawing_and_reading() {
        let mut ctx = bound();
        ctx.glClear(gl::GL_COLOR_BUFFER_BIT);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT);
        assert!(ctx.frame.clears.is_empty());
        ctx.glBegin(gl::GL_TRIANGLES);
        for v in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]] {
            ctx.glVertex4f(v[0], v[1], 0.0, 1.0);
        }
        ctx.glEnd();
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_FRAMEBUFFER_OPERATION_EXT);
        assert!(ctx.frame.draws.is_empty());
        ctx.glAccum(gl::GL_LOAD, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "a framebuffer object has no accumulation buffer");
    }

    #[test]
    fn errors_of_the_entry_points() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindFramebufferEXT(gl::GL_TEXTURE_2D, 1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glFramebufferRenderbufferEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_RENDERBUFFER_EXT, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "no framebuffer object bound");
        ctx.glRenderbufferStorageEXT(gl::GL_RENDERBUFFER_EXT, gl::GL_RGBA8, 4, 4);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "no renderbuffer bound");
        ctx.glBindRenderbufferEXT(gl::GL_RENDERBUFFER_EXT, 5);
        ctx.glRenderbufferStorageEXT(gl::GL_RENDERBUFFER_EXT, gl::GL_LUMINANCE8, 4, 4);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM, "not colour-renderable");
        ctx.glRenderbufferStorageEXT(gl::GL_RENDERBUFFER_EXT, gl::GL_RGB8, -1, 4);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glRenderbufferStorageEXT(gl::GL_RENDERBUFFER_EXT, gl::GL_RGB8, 4, 6);
        let mut v = 0;
        for (pname, want) in [
            (gl::GL_RENDERBUFFER_WIDTH_EXT, 4),
            (gl::GL_RENDERBUFFER_HEIGHT_EXT, 6),
            (gl::GL_RENDERBUFFER_INTERNAL_FORMAT_EXT, gl::GL_RGB8 as i32),
            (gl::GL_RENDERBUFFER_GREEN_SIZE_EXT, 8),
            (gl::GL_RENDERBUFFER_ALPHA_SIZE_EXT, 0),
            (gl::GL_RENDERBUFFER_DEPTH_SIZE_EXT, 0),
        ] {
            unsafe { ctx.glGetRenderbufferParameterivEXT(gl::GL_RENDERBUFFER_EXT, pname, &mut v) };
            assert_eq!(v, want, "{pname:#x}");
        }
        ctx.glBindFramebufferEXT(gl::GL_FRAMEBUFFER_EXT, 2);
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_2D, 9, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "9 is not a texture");
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 9);
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X, 9, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "not a cube map");
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT1_EXT, gl::GL_TEXTURE_2D, 9, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM, "one colour attachment");
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_2D, 9, -1);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glFramebufferTexture2DEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_TEXTURE_2D, 9, 2);
        for (pname, want) in [
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_EXT, gl::GL_TEXTURE as i32),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME_EXT, 9),
            (gl::GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL_EXT, 2),
        ] {
            unsafe { ctx.glGetFramebufferAttachmentParameterivEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, pname, &mut v) };
            assert_eq!(v, want, "{pname:#x}");
        }
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(status(&mut ctx), gl::GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT_EXT, "level 2 has no image");
        // Deleting the texture detaches it from the bound framebuffer.
        unsafe { ctx.glDeleteTextures(1, &9) };
        unsafe { ctx.glGetFramebufferAttachmentParameterivEXT(gl::GL_FRAMEBUFFER_EXT, gl::GL_COLOR_ATTACHMENT0_EXT, gl::GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE_EXT, &mut v) };
        assert_eq!(v, gl::GL_NONE as i32);
        ctx.glDrawBuffer(gl::GL_BACK);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "window buffers while an object is bound");
        let ints = |ctx: &Context, p| ctx.query(p).unwrap().to_ints()[0];
        assert_eq!(ints(&ctx, gl::GL_FRAMEBUFFER_BINDING_EXT), 2);
        assert_eq!(ints(&ctx, gl::GL_DRAW_BUFFER), gl::GL_COLOR_ATTACHMENT0_EXT as i32);
        assert_eq!(ints(&ctx, gl::GL_DOUBLEBUFFER), 0);
        unsafe { ctx.glDeleteFramebuffersEXT(1, &2) };
        assert_eq!(ints(&ctx, gl::GL_FRAMEBUFFER_BINDING_EXT), 0, "deleting the bound framebuffer binds the window's");
        assert_eq!(ints(&ctx, gl::GL_DRAW_BUFFER), gl::GL_BACK as i32);
    }
}

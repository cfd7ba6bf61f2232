//! Texture objects (OpenGL 1.5 section 3.8.12): names, targets, their images and parameters,
//! `glGenTextures`, `glDeleteTextures`, `glBindTexture`, `glIsTexture`,
//! `glAreTexturesResident`, `glPrioritizeTextures`. Named objects live in the share group;
//! each context has its own default texture (name 0) per target.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use super::super::Context;
use super::super::convert::{read_slice, write_slice};
use super::super::gl::{self, GLboolean, GLenum, GLfloat, GLsizei, GLuint};
use super::super::limits::{MAX_3D_TEXTURE_SIZE, MAX_CUBE_MAP_TEXTURE_SIZE, MAX_TEXTURE_SIZE};
use super::super::lists::ListOp;
use super::formats::Base;
use super::palette::Palette;
use super::params::TexParams;
use crate::frame::texture::{TexImage, TextureRef};

/// Mipmap levels per face: enough for `GL_MAX_TEXTURE_SIZE`.
pub const MAX_LEVELS: usize = MAX_TEXTURE_SIZE.trailing_zeros() as usize + 1;

static NEXT_VERSION: AtomicU64 = AtomicU64::new(1);

/// A content version never handed out before in this process.
pub fn next_version() -> u64 {
    NEXT_VERSION.fetch_add(1, Ordering::Relaxed)
}

/// A texture target (the kind of a texture object).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// `GL_TEXTURE_1D`.
    D1,
    /// `GL_TEXTURE_2D`.
    D2,
    /// `GL_TEXTURE_3D`.
    D3,
    /// `GL_TEXTURE_CUBE_MAP`.
    Cube,
    /// `GL_TEXTURE_RECTANGLE_ARB` (`GL_ARB_texture_rectangle`): one level, no border,
    /// coordinates in texels.
    Rect,
}

impl Target {
    /// Every target, in index order.
    pub const ALL: [Target; 5] = [Target::D1, Target::D2, Target::D3, Target::Cube, Target::Rect];

    /// The target of a bind target enum.
    pub fn from_gl(target: GLenum) -> Option<Target> {
        Some(match target {
            gl::GL_TEXTURE_1D => Target::D1,
            gl::GL_TEXTURE_2D => Target::D2,
            gl::GL_TEXTURE_3D => Target::D3,
            gl::GL_TEXTURE_CUBE_MAP => Target::Cube,
            gl::GL_TEXTURE_RECTANGLE_ARB => Target::Rect,
            _ => return None,
        })
    }

    /// Index in per-target arrays.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The bind target enum.
    pub fn gl(self) -> GLenum {
        [gl::GL_TEXTURE_1D, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_3D, gl::GL_TEXTURE_CUBE_MAP, gl::GL_TEXTURE_RECTANGLE_ARB][self.index()]
    }

    /// The binding query enum (`GL_TEXTURE_BINDING_2D`...).
    pub fn binding_gl(self) -> GLenum {
        [
            gl::GL_TEXTURE_BINDING_1D,
            gl::GL_TEXTURE_BINDING_2D,
            gl::GL_TEXTURE_BINDING_3D,
            gl::GL_TEXTURE_BINDING_CUBE_MAP,
            gl::GL_TEXTURE_BINDING_RECTANGLE_ARB,
        ][self.index()]
    }

    /// Number of faces.
    pub fn faces(self) -> usize {
        if self == Target::Cube { 6 } else { 1 }
    }

    /// Number of dimensions of its images.
    pub fn dims(self) -> usize {
        match self {
            Target::D1 => 1,
            Target::D2 | Target::Cube | Target::Rect => 2,
            Target::D3 => 3,
        }
    }

    /// Largest image size (without border).
    pub fn max_size(self) -> usize {
        match self {
            Target::D1 | Target::D2 | Target::Rect => MAX_TEXTURE_SIZE,
            Target::D3 => MAX_3D_TEXTURE_SIZE,
            Target::Cube => MAX_CUBE_MAP_TEXTURE_SIZE,
        }
    }

    /// Number of levels its largest image has.
    pub fn max_levels(self) -> usize {
        if self == Target::Rect { 1 } else { self.max_size().trailing_zeros() as usize + 1 }
    }
}

/// One image of a texture object.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Canonical texels (empty for proxy levels).
    pub image: Arc<TexImage>,
    /// Size including border: width, height, depth.
    pub size: [usize; 3],
    /// Border width.
    pub border: usize,
    /// `GL_TEXTURE_INTERNAL_FORMAT`.
    pub internal_format: GLenum,
    /// Base format.
    pub base: Base,
    /// The compressed bytes as given (`glGetCompressedTexImage`).
    pub compressed: Option<Arc<[u8]>>,
    /// Colour indices of paletted images, one per texel.
    pub indices: Option<Arc<Vec<u16>>>,
    /// Stencil indices of depth/stencil images, one per texel (`glGetTexImage`; sampling
    /// ignores them).
    pub stencil: Option<Arc<Vec<u8>>>,
}

/// A texture object.
#[derive(Clone, Debug)]
pub struct TextureObject {
    /// The target it was first bound to; `None` for a name from `glGenTextures` not bound yet.
    pub target: Option<Target>,
    /// Parameters (`glTexParameter`).
    pub params: TexParams,
    /// `faces[face][level]`: empty until the first image, then 6 × [`MAX_LEVELS`].
    pub faces: Vec<Vec<Option<Level>>>,
    /// Its palette (EXT_paletted_texture).
    pub palette: Palette,
    /// Content version: a fresh [`next_version`] after every change.
    pub version: u64,
    /// The last snapshot and the key it was built for.
    pub(crate) snapshot: Option<(u64, TextureRef)>,
}

impl Default for TextureObject {
    fn default() -> TextureObject {
        TextureObject {
            target: None,
            params: TexParams::default(),
            faces: Vec::new(),
            palette: Palette::default(),
            version: next_version(),
            snapshot: None,
        }
    }
}

impl TextureObject {
    /// A new object with the initial state of table 6.16 (no images) and a fresh version.
    pub fn new() -> TextureObject {
        TextureObject::default()
    }

    /// Marks a change of images, parameters or palette. The cached snapshot is dropped, so
    /// images held only by it are changed in place by the next update instead of copied.
    pub fn touch(&mut self) {
        self.version = next_version();
        self.snapshot = None;
    }

    /// The slot of level `level` of `face` (allocated on first use). Both must be in range
    /// (`face` < 6, `level` < [`MAX_LEVELS`]).
    pub fn level_slot(&mut self, face: usize, level: usize) -> &mut Option<Level> {
        if self.faces.is_empty() {
            self.faces = vec![vec![None; MAX_LEVELS]; 6];
        }
        &mut self.faces[face][level]
    }

    /// The level `level` of `face`, if specified.
    pub fn level(&self, face: usize, level: usize) -> Option<&Level> {
        self.faces.get(face)?.get(level)?.as_ref()
    }
}

/// The named texture objects of a share group.
#[derive(Default)]
pub struct TextureTable {
    objects: HashMap<GLuint, TextureObject>,
}

impl TextureTable {
    /// The object named `name`.
    pub fn get(&self, name: GLuint) -> Option<&TextureObject> {
        self.objects.get(&name)
    }

    /// The object named `name`, mutable.
    pub fn get_mut(&mut self, name: GLuint) -> Option<&mut TextureObject> {
        self.objects.get_mut(&name)
    }
}

impl Context {
    /// The name bound to `target` on the active unit.
    pub(crate) fn bound_texture(&self, target: Target) -> GLuint {
        self.texture.bindings[self.active_texture_unit()][target.index()]
    }

    /// Runs `f` on the texture object named `name` of kind `target` (the context's default
    /// texture for name 0, or when the object was deleted by another context).
    pub(crate) fn with_object<R>(&mut self, target: Target, name: GLuint, f: impl FnOnce(&mut TextureObject) -> R) -> R {
        if name != 0 {
            let shared = self.shared.clone();
            let mut shared = shared.lock();
            if let Some(obj) = shared.textures.get_mut(name) {
                return f(obj);
            }
        }
        f(&mut self.texture.defaults[target.index()])
    }

    /// Runs `f` on the texture bound to `target` on the active unit.
    pub(crate) fn with_bound_texture<R>(&mut self, target: Target, f: impl FnOnce(&mut TextureObject) -> R) -> R {
        let name = self.bound_texture(target);
        self.with_object(target, name, f)
    }

    /// `glGenTextures`: `GL_INVALID_VALUE` for a negative count.
    ///
    /// # Safety
    /// `textures` must have room for `n` names.
    pub unsafe fn glGenTextures(&mut self, n: GLsizei, textures: *mut GLuint) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, "glGenTextures") };
        if textures.is_null() {
            return self.null_pointer("glGenTextures");
        }
        let shared = self.shared.clone();
        let mut shared = shared.lock();
        let objects = &mut shared.textures.objects;
        let mut names = Vec::with_capacity(count.min(1 << 16));
        let mut candidate: GLuint = 1;
        while names.len() < count {
            if let std::collections::hash_map::Entry::Vacant(slot) = objects.entry(candidate) {
                slot.insert(TextureObject::new());
                names.push(candidate);
            }
            let Some(next) = candidate.checked_add(1) else { break };
            candidate = next;
        }
        drop(shared);
        unsafe { write_slice(textures, &names) }
    }

    /// `glDeleteTextures`: deleted textures bound in this context revert to the default
    /// texture; unknown names and 0 are ignored.
    ///
    /// # Safety
    /// `textures` must point to `n` names.
    pub unsafe fn glDeleteTextures(&mut self, n: GLsizei, textures: *const GLuint) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, "glDeleteTextures") };
        let Some(names) = (unsafe { read_slice(textures, count) }) else { return self.null_pointer("glDeleteTextures") };
        for &name in names.iter().filter(|&&n| n != 0) {
            self.detach_everywhere(|a| matches!(a, crate::translate::framebuffers::objects::Attached::Texture { name: n, .. } if n == name));
            self.frame.released.push(crate::frame::framebuffer::Attachment::Texture { name, face: 0, level: 0, slice: 0 });
        }
        let shared = self.shared.clone();
        let mut shared = shared.lock();
        for name in names.into_iter().filter(|&n| n != 0) {
            if shared.textures.objects.remove(&name).is_some() {
                for unit in &mut self.texture.bindings {
                    unit.iter_mut().filter(|b| **b == name).for_each(|b| *b = 0);
                }
            }
        }
    }

    /// `glBindTexture`: `GL_INVALID_ENUM` for an unknown target, `GL_INVALID_OPERATION` when
    /// the object already has another target. Binding an unused name creates the object.
    pub fn glBindTexture(&mut self, target: GLenum, texture: GLuint) {
        let Some(t) = Target::from_gl(target) else { return self.set_error_in(gl::GL_INVALID_ENUM, "glBindTexture") };
        if texture != 0 {
            let shared = self.shared.clone();
            let mut shared = shared.lock();
            let obj = shared.textures.objects.entry(texture).or_default();
            match obj.target {
                Some(existing) if existing != t => {
                    drop(shared);
                    return self.set_error_in(gl::GL_INVALID_OPERATION, "glBindTexture");
                }
                Some(_) => {}
                None => {
                    obj.target = Some(t);
                    obj.params = TexParams::initial(t);
                }
            }
        }
        let unit = self.active_texture_unit();
        self.texture.bindings[unit][t.index()] = texture;
    }

    /// `glIsTexture`: true for the name of an object that has been bound.
    pub fn glIsTexture(&mut self, texture: GLuint) -> GLboolean {
        let shared = self.shared.lock();
        GLboolean::from(texture != 0 && shared.textures.get(texture).is_some_and(|o| o.target.is_some()))
    }

    /// `glAreTexturesResident`: every texture is resident, so `GL_TRUE` and `residences` is
    /// left untouched; `GL_INVALID_VALUE` for a negative count, 0 or an unknown name.
    ///
    /// # Safety
    /// `textures` must point to `n` names.
    pub unsafe fn glAreTexturesResident(&mut self, n: GLsizei, textures: *const GLuint, _residences: *mut GLboolean) -> GLboolean {
        let Ok(count) = usize::try_from(n) else {
            self.set_error_in(gl::GL_INVALID_VALUE, "glAreTexturesResident");
            return gl::GL_FALSE;
        };
        let Some(names) = (unsafe { read_slice(textures, count) }) else {
            self.null_pointer("glAreTexturesResident");
            return gl::GL_FALSE;
        };
        let all_known = {
            let shared = self.shared.lock();
            names.iter().all(|&n| n != 0 && shared.textures.get(n).is_some_and(|o| o.target.is_some()))
        };
        if !all_known {
            self.set_error_in(gl::GL_INVALID_VALUE, "glAreTexturesResident");
            return gl::GL_FALSE;
        }
        gl::GL_TRUE
    }

    /// `glPrioritizeTextures`: priorities are clamped to [0, 1]; names 0 and unknown names are
    /// ignored; `GL_INVALID_VALUE` for a negative count.
    ///
    /// # Safety
    /// `textures` and `priorities` must point to `n` values each.
    pub unsafe fn glPrioritizeTextures(&mut self, n: GLsizei, textures: *const GLuint, priorities: *const GLfloat) {
        let Ok(count) = usize::try_from(n) else { return self.set_error_in(gl::GL_INVALID_VALUE, "glPrioritizeTextures") };
        let (Some(names), Some(prios)) = (unsafe { read_slice(textures, count) }, unsafe { read_slice(priorities, count) }) else {
            return self.null_pointer("glPrioritizeTextures");
        };
        let shared = self.shared.clone();
        let mut shared = shared.lock();
        for (name, p) in names.into_iter().zip(prios) {
            if let Some(obj) = shared.textures.get_mut(name).filter(|_| name != 0) {
                obj.params.priority = p.clamp(0.0, 1.0);
            }
        }
    }

    /// `glPrioritizeTextures` in a display list.
    ///
    /// # Safety
    /// As [`Context::glPrioritizeTextures`].
    pub unsafe fn compile_glPrioritizeTextures(&mut self, n: GLsizei, textures: *const GLuint, priorities: *const GLfloat) {
        let count = usize::try_from(n).unwrap_or(0);
        let names = unsafe { read_slice(textures, count) }.unwrap_or_default();
        let prios = unsafe { read_slice(priorities, count) }.unwrap_or_default();
        self.lists.record(ListOp::Deferred(Box::new(move |ctx| unsafe {
            ctx.glPrioritizeTextures(n, names.as_ptr(), prios.as_ptr())
        })));
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn gen_bind_delete_and_is() {
        let (mut ctx, _) = Context::with_recording();
        let mut names = [0u32; 3];
        unsafe { dispatch::glGenTextures(&mut ctx, 3, names.as_mut_ptr()) };
        assert_eq!(names, [1, 2, 3]);
        assert_eq!(ctx.glIsTexture(2), 0);
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 2);
        assert_eq!(ctx.glIsTexture(2), 1);
        ctx.glBindTexture(gl::GL_TEXTURE_1D, 2);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        ctx.glBindTexture(gl::GL_TEXTURE_2D_ARRAY, 2);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 2);
        let mut bound = 0;
        unsafe { ctx.glGetIntegerv(gl::GL_TEXTURE_BINDING_2D, &mut bound) };
        assert_eq!(bound, 2);
        unsafe { dispatch::glDeleteTextures(&mut ctx, 1, [2u32].as_ptr()) };
        unsafe { ctx.glGetIntegerv(gl::GL_TEXTURE_BINDING_2D, &mut bound) };
        assert_eq!((bound, ctx.texture.bindings[0][1], ctx.glIsTexture(2)), (0, 0, 0));
        let mut again = [0u32; 2];
        unsafe { dispatch::glGenTextures(&mut ctx, 2, again.as_mut_ptr()) };
        assert_eq!(again, [2, 4]);
        ctx.glBindTexture(gl::GL_TEXTURE_3D, 4);
        let prio = [0.25f32];
        unsafe { dispatch::glPrioritizeTextures(&mut ctx, 1, [4u32].as_ptr(), prio.as_ptr()) };
        let mut p = 0.0f32;
        unsafe { ctx.glGetTexParameterfv(gl::GL_TEXTURE_3D, gl::GL_TEXTURE_PRIORITY, &mut p) };
        assert_eq!(p, 0.25);
        let mut res = [0u8; 1];
        assert_eq!(unsafe { ctx.glAreTexturesResident(1, [4u32].as_ptr(), res.as_mut_ptr()) }, 1);
        assert_eq!(unsafe { ctx.glAreTexturesResident(1, [99u32].as_ptr(), res.as_mut_ptr()) }, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }
}

#[cfg(test)]
mod share_tests {
    use crate::frame::NullSink;
    use crate::translate::context::ContextConfig;
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn share_group_sees_objects_but_not_bindings() {
        let (mut a, _) = Context::with_recording();
        let mut b = Context::new(ContextConfig { share: Some(a.shared.clone()), sink: Box::new(NullSink::default()) });
        a.glBindTexture(gl::GL_TEXTURE_2D, 5);
        let px = [1u8, 2, 3, 4];
        unsafe { dispatch::glTexImage2D(&mut a, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        assert_eq!(b.glIsTexture(5), 1);
        assert_eq!(b.texture.bindings[0][1], 0);
        b.glBindTexture(gl::GL_TEXTURE_2D, 5);
        let mut out = [0u8; 4];
        unsafe { b.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(out, px);
        // The default texture is per context.
        b.glBindTexture(gl::GL_TEXTURE_2D, 0);
        unsafe { dispatch::glTexImage2D(&mut b, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        a.glBindTexture(gl::GL_TEXTURE_2D, 0);
        let mut w = 0;
        unsafe { a.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_WIDTH, &mut w) };
        assert_eq!(w, 0);
    }
}

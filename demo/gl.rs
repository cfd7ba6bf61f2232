//! The OpenGL 1.x functions and constants the demo uses. Core functions come from `dlsym` on
//! the loaded library (as Quake 3's `qgl` does); extension functions
//! (`GL_ARB_multitexture`, `GL_EXT_compiled_vertex_array`) from `glXGetProcAddressARB` after a
//! context is current, and only when the extension string lists them.

use std::ffi::{CStr, c_char, c_void};

use crate::loader::{GlLibrary, fn_table};

pub type GLenum = u32;
pub type GLint = i32;
pub type GLuint = u32;
pub type GLsizei = i32;
pub type GLfloat = f32;
pub type GLdouble = f64;
pub type GLboolean = u8;
pub type GLbitfield = u32;

pub const GL_FALSE: GLboolean = 0;
pub const GL_TRUE: GLboolean = 1;
pub const GL_NO_ERROR: GLenum = 0x0000;
pub const GL_ZERO: GLenum = 0x0000;
pub const GL_ONE: GLenum = 0x0001;
pub const GL_TRIANGLES: GLenum = 0x0004;
pub const GL_TRIANGLE_STRIP: GLenum = 0x0005;
pub const GL_QUADS: GLenum = 0x0007;
pub const GL_DEPTH_BUFFER_BIT: GLbitfield = 0x0100;
pub const GL_EQUAL: GLenum = 0x0202;
pub const GL_LEQUAL: GLenum = 0x0203;
pub const GL_SRC_COLOR: GLenum = 0x0300;
pub const GL_SRC_ALPHA: GLenum = 0x0302;
pub const GL_ONE_MINUS_SRC_ALPHA: GLenum = 0x0303;
pub const GL_DST_COLOR: GLenum = 0x0306;
pub const GL_FRONT: GLenum = 0x0404;
pub const GL_BACK: GLenum = 0x0405;
pub const GL_FRONT_AND_BACK: GLenum = 0x0408;
pub const GL_CULL_FACE: GLenum = 0x0B44;
pub const GL_LIGHTING: GLenum = 0x0B50;
pub const GL_LIGHT_MODEL_AMBIENT: GLenum = 0x0B53;
pub const GL_FOG: GLenum = 0x0B60;
pub const GL_FOG_START: GLenum = 0x0B63;
pub const GL_FOG_END: GLenum = 0x0B64;
pub const GL_FOG_MODE: GLenum = 0x0B65;
pub const GL_FOG_COLOR: GLenum = 0x0B66;
pub const GL_DEPTH_TEST: GLenum = 0x0B71;
pub const GL_NORMALIZE: GLenum = 0x0BA1;
pub const GL_BLEND: GLenum = 0x0BE2;
pub const GL_SCISSOR_TEST: GLenum = 0x0C11;
pub const GL_PERSPECTIVE_CORRECTION_HINT: GLenum = 0x0C50;
pub const GL_UNPACK_ALIGNMENT: GLenum = 0x0CF5;
pub const GL_PACK_ALIGNMENT: GLenum = 0x0D05;
pub const GL_TEXTURE_2D: GLenum = 0x0DE1;
pub const GL_NICEST: GLenum = 0x1102;
pub const GL_DIFFUSE: GLenum = 0x1201;
pub const GL_SPECULAR: GLenum = 0x1202;
pub const GL_POSITION: GLenum = 0x1203;
pub const GL_CONSTANT_ATTENUATION: GLenum = 0x1207;
pub const GL_LINEAR_ATTENUATION: GLenum = 0x1208;
pub const GL_COMPILE: GLenum = 0x1300;
pub const GL_UNSIGNED_BYTE: GLenum = 0x1401;
pub const GL_UNSIGNED_SHORT: GLenum = 0x1403;
pub const GL_UNSIGNED_INT: GLenum = 0x1405;
pub const GL_FLOAT: GLenum = 0x1406;
pub const GL_SHININESS: GLenum = 0x1601;
pub const GL_AMBIENT_AND_DIFFUSE: GLenum = 0x1602;
pub const GL_MODELVIEW: GLenum = 0x1700;
pub const GL_PROJECTION: GLenum = 0x1701;
pub const GL_RGB: GLenum = 0x1907;
pub const GL_RGBA: GLenum = 0x1908;
pub const GL_SMOOTH: GLenum = 0x1D01;
pub const GL_VENDOR: GLenum = 0x1F00;
pub const GL_RENDERER: GLenum = 0x1F01;
pub const GL_VERSION: GLenum = 0x1F02;
pub const GL_EXTENSIONS: GLenum = 0x1F03;
pub const GL_MODULATE: GLenum = 0x2100;
pub const GL_TEXTURE_ENV_MODE: GLenum = 0x2200;
pub const GL_TEXTURE_ENV: GLenum = 0x2300;
pub const GL_LINEAR: GLenum = 0x2601;
pub const GL_LINEAR_MIPMAP_NEAREST: GLenum = 0x2701;
pub const GL_TEXTURE_MAG_FILTER: GLenum = 0x2800;
pub const GL_TEXTURE_MIN_FILTER: GLenum = 0x2801;
pub const GL_TEXTURE_WRAP_S: GLenum = 0x2802;
pub const GL_TEXTURE_WRAP_T: GLenum = 0x2803;
pub const GL_REPEAT: GLenum = 0x2901;
pub const GL_COLOR_BUFFER_BIT: GLbitfield = 0x4000;
pub const GL_CLIP_PLANE0: GLenum = 0x3000;
pub const GL_LIGHT0: GLenum = 0x4000;
pub const GL_LIGHT1: GLenum = 0x4001;
pub const GL_RGB8: GLenum = 0x8051;
pub const GL_RGBA8: GLenum = 0x8058;
pub const GL_VERTEX_ARRAY: GLenum = 0x8074;
pub const GL_NORMAL_ARRAY: GLenum = 0x8075;
pub const GL_COLOR_ARRAY: GLenum = 0x8076;
pub const GL_TEXTURE_COORD_ARRAY: GLenum = 0x8078;
pub const GL_CLAMP_TO_EDGE: GLenum = 0x812F;
pub const GL_TEXTURE0_ARB: GLenum = 0x84C0;
pub const GL_TEXTURE1_ARB: GLenum = 0x84C1;

fn_table!(
    /// OpenGL 1.1 functions, resolved with `dlsym` (the Linux ABI requires libGL to export them).
    Gl {
        fn glGetString(name: GLenum) -> *const u8;
        fn glViewport(x: GLint, y: GLint, w: GLsizei, h: GLsizei);
        fn glClearColor(r: GLfloat, g: GLfloat, b: GLfloat, a: GLfloat);
        fn glClear(mask: GLbitfield);
        fn glEnable(cap: GLenum);
        fn glDisable(cap: GLenum);
        fn glHint(target: GLenum, mode: GLenum);
        fn glShadeModel(mode: GLenum);
        fn glDepthFunc(func: GLenum);
        fn glDepthMask(flag: GLboolean);
        fn glDepthRange(near: GLdouble, far: GLdouble);
        fn glScissor(x: GLint, y: GLint, w: GLsizei, h: GLsizei);
        fn glCullFace(mode: GLenum);
        fn glDrawBuffer(mode: GLenum);
        fn glGetError() -> GLenum;
        fn glBlendFunc(s: GLenum, d: GLenum);
        fn glMatrixMode(mode: GLenum);
        fn glLoadIdentity();
        fn glLoadMatrixf(m: *const GLfloat);
        fn glFrustum(l: GLdouble, r: GLdouble, b: GLdouble, t: GLdouble, n: GLdouble, f: GLdouble);
        fn glOrtho(l: GLdouble, r: GLdouble, b: GLdouble, t: GLdouble, n: GLdouble, f: GLdouble);
        fn glPushMatrix();
        fn glPopMatrix();
        fn glTranslatef(x: GLfloat, y: GLfloat, z: GLfloat);
        fn glRotatef(angle: GLfloat, x: GLfloat, y: GLfloat, z: GLfloat);
        fn glBegin(mode: GLenum);
        fn glEnd();
        fn glVertex2f(x: GLfloat, y: GLfloat);
        fn glVertex3f(x: GLfloat, y: GLfloat, z: GLfloat);
        fn glNormal3f(x: GLfloat, y: GLfloat, z: GLfloat);
        fn glTexCoord2f(s: GLfloat, t: GLfloat);
        fn glColor3f(r: GLfloat, g: GLfloat, b: GLfloat);
        fn glColor4f(r: GLfloat, g: GLfloat, b: GLfloat, a: GLfloat);
        fn glGenTextures(n: GLsizei, textures: *mut GLuint);
        fn glDeleteTextures(n: GLsizei, textures: *const GLuint);
        fn glBindTexture(target: GLenum, texture: GLuint);
        fn glTexParameteri(target: GLenum, pname: GLenum, param: GLint);
        fn glTexImage2D(target: GLenum, level: GLint, internal: GLint, w: GLsizei, h: GLsizei, border: GLint, format: GLenum, ty: GLenum, pixels: *const c_void);
        fn glTexEnvi(target: GLenum, pname: GLenum, param: GLint);
        fn glPixelStorei(pname: GLenum, param: GLint);
        fn glLightfv(light: GLenum, pname: GLenum, params: *const GLfloat);
        fn glLightf(light: GLenum, pname: GLenum, param: GLfloat);
        fn glLightModelfv(pname: GLenum, params: *const GLfloat);
        fn glMaterialfv(face: GLenum, pname: GLenum, params: *const GLfloat);
        fn glMaterialf(face: GLenum, pname: GLenum, param: GLfloat);
        fn glFogi(pname: GLenum, param: GLint);
        fn glFogf(pname: GLenum, param: GLfloat);
        fn glFogfv(pname: GLenum, params: *const GLfloat);
        fn glGenLists(range: GLsizei) -> GLuint;
        fn glNewList(list: GLuint, mode: GLenum);
        fn glEndList();
        fn glCallList(list: GLuint);
        fn glDeleteLists(list: GLuint, range: GLsizei);
        fn glEnableClientState(array: GLenum);
        fn glDisableClientState(array: GLenum);
        fn glVertexPointer(size: GLint, ty: GLenum, stride: GLsizei, ptr: *const c_void);
        fn glNormalPointer(ty: GLenum, stride: GLsizei, ptr: *const c_void);
        fn glTexCoordPointer(size: GLint, ty: GLenum, stride: GLsizei, ptr: *const c_void);
        fn glColorPointer(size: GLint, ty: GLenum, stride: GLsizei, ptr: *const c_void);
        fn glDrawElements(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void);
        fn glRasterPos2i(x: GLint, y: GLint);
        fn glBitmap(w: GLsizei, h: GLsizei, xorig: GLfloat, yorig: GLfloat, xmove: GLfloat, ymove: GLfloat, bitmap: *const u8);
        fn glReadPixels(x: GLint, y: GLint, w: GLsizei, h: GLsizei, format: GLenum, ty: GLenum, pixels: *mut c_void);
        fn glFinish();
    }
);

fn_table!(
    /// `GL_ARB_multitexture` (resolved with `glXGetProcAddressARB`).
    #[derive(Clone, Copy)]
    Multitexture {
        fn glActiveTextureARB(texture: GLenum);
        fn glClientActiveTextureARB(texture: GLenum);
        fn glMultiTexCoord2fARB(target: GLenum, s: GLfloat, t: GLfloat);
    }
);

fn_table!(
    /// `GL_EXT_compiled_vertex_array` (resolved with `glXGetProcAddressARB`).
    #[derive(Clone, Copy)]
    LockArrays {
        fn glLockArraysEXT(first: GLint, count: GLsizei);
        fn glUnlockArraysEXT();
    }
);

/// The GL entry points of a current context: core functions and the extensions the
/// implementation lists.
pub struct GlApi {
    /// Core OpenGL 1.1.
    pub gl: Gl,
    /// `GL_ARB_multitexture`, when listed.
    pub multitexture: Option<Multitexture>,
    /// `GL_EXT_compiled_vertex_array`, when listed.
    pub lock_arrays: Option<LockArrays>,
}

/// `glXGetProcAddressARB`.
type GetProcAddress = unsafe extern "C" fn(*const c_char) -> *mut c_void;

impl GlApi {
    /// Resolves the core functions, then (with a context current) the extensions listed in
    /// `GL_EXTENSIONS` through `glXGetProcAddressARB`, or `dlsym` when the library has no
    /// `glXGetProcAddressARB`.
    pub fn load(lib: &GlLibrary) -> Result<Self, String> {
        let gl = Gl::load(|name| lib.symbol(name))?;
        let gpa = lib.symbol("glXGetProcAddressARB");
        let resolve = |name: &str| -> *mut c_void {
            if gpa.is_null() {
                return lib.symbol(name);
            }
            // Safety: glXGetProcAddressARB has this signature in every libGL.
            let gpa: GetProcAddress = unsafe { std::mem::transmute(gpa) };
            let cname = std::ffi::CString::new(name).unwrap_or_default();
            // Safety: cname is a NUL-terminated string.
            unsafe { gpa(cname.as_ptr()) }
        };
        let extensions = gl_string(&gl, GL_EXTENSIONS);
        let listed = |ext: &str| extensions.split_ascii_whitespace().any(|e| e == ext);
        let multitexture =
            if listed("GL_ARB_multitexture") { Multitexture::load(resolve).ok() } else { None };
        let lock_arrays = if listed("GL_EXT_compiled_vertex_array") {
            LockArrays::load(resolve).ok()
        } else {
            None
        };
        Ok(Self { gl, multitexture, lock_arrays })
    }
}

/// `glGetString(name)` as text ("" when null).
pub fn gl_string(gl: &Gl, name: GLenum) -> String {
    // Safety: a context is current; glGetString returns null or a static NUL-terminated string.
    let ptr = unsafe { gl.glGetString(name) };
    if ptr.is_null() {
        return String::new();
    }
    // Safety: non-null, NUL-terminated, owned by the implementation.
    unsafe { CStr::from_ptr(ptr.cast()) }.to_string_lossy().into_owned()
}

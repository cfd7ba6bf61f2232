//! Texture images (OpenGL 1.5 sections 3.8.1–3.8.3, 6.1.4): `glTexImage{1,2,3}D`,
//! `glTexSubImage{1,2,3}D`, `glCopyTexImage{1,2}D`, `glCopyTexSubImage{1,2,3}D`,
//! `glGetTexImage`, `glGetTexLevelParameter{if}v`, with the argument checks of the
//! specification, proxy targets and `GL_GENERATE_MIPMAP`.

// GL commands keep the parameter lists of their C functions.
#![allow(clippy::too_many_arguments)]

use std::ffi::c_void;
use std::sync::Arc;

use super::super::Context;
use super::super::convert::write_slice;
use super::super::get::Value;
use super::super::gl::{self, GLenum, GLfloat, GLint, GLsizei, GLuint};
use super::super::pixels::Unpacked;
use super::super::pixels::codec::{self, Format, Kind, Luminance};
use super::formats::{self, Base, Internal, S3tc};
use super::objects::{Level, Target, TextureObject};
use super::palette::Palette;
use crate::frame::pixels::{PixelBuffer, PixelKind};
use crate::frame::texture::{Precision, TexImage, TexelFormat};

/// Where an image command writes: the kind of texture, the cube face, and whether it is a
/// proxy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dest {
    /// Kind of texture.
    pub target: Target,
    /// Cube face (0 otherwise).
    pub face: usize,
    /// A proxy target.
    pub proxy: bool,
}

/// The destination of an image target enum for `dims`-dimensional commands.
pub fn image_target(dims: usize, target: GLenum) -> Option<Dest> {
    let plain = |target, proxy| Some(Dest { target, face: 0, proxy });
    match (dims, target) {
        (1, gl::GL_TEXTURE_1D) => plain(Target::D1, false),
        (1, gl::GL_PROXY_TEXTURE_1D) => plain(Target::D1, true),
        (2, gl::GL_TEXTURE_2D) => plain(Target::D2, false),
        (2, gl::GL_PROXY_TEXTURE_2D) => plain(Target::D2, true),
        (2, gl::GL_PROXY_TEXTURE_CUBE_MAP) => plain(Target::Cube, true),
        (2, gl::GL_TEXTURE_RECTANGLE_ARB) => plain(Target::Rect, false),
        (2, gl::GL_PROXY_TEXTURE_RECTANGLE_ARB) => plain(Target::Rect, true),
        (2, gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X..=gl::GL_TEXTURE_CUBE_MAP_NEGATIVE_Z) => {
            Some(Dest { target: Target::Cube, face: (target - gl::GL_TEXTURE_CUBE_MAP_POSITIVE_X) as usize, proxy: false })
        }
        (3, gl::GL_TEXTURE_3D) => plain(Target::D3, false),
        (3, gl::GL_PROXY_TEXTURE_3D) => plain(Target::D3, true),
        _ => None,
    }
}

/// The destination of any image target (for queries): 1D, 2D, 3D, cube faces and proxies.
pub fn any_image_target(target: GLenum) -> Option<Dest> {
    (1..=3).find_map(|d| image_target(d, target))
}

/// A checked sub-image region: destination, level, offset (border included), size, and the
/// level's base format.
pub type SubImage = (Dest, usize, [usize; 3], [usize; 3], Base);

/// The outcome of the size checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SizeCheck {
    /// Sizes including border, each ≥ 1 in unused dimensions.
    Fits([usize; 3]),
    /// Valid but larger than the implementation supports at that level.
    TooLarge,
    /// Valid, but more texels than glrt stores in one image ([`MAX_IMAGE_TEXELS`]).
    OutOfMemory,
}

/// Most texels one image may have (1 GiB of canonical RGBA8).
pub const MAX_IMAGE_TEXELS: usize = 1 << 28;

/// Checks a level number: `GL_INVALID_VALUE` when negative or beyond the largest image.
pub fn check_level(target: Target, level: GLint) -> Result<usize, GLenum> {
    usize::try_from(level).ok().filter(|&l| l < target.max_levels()).ok_or(gl::GL_INVALID_VALUE)
}

/// Checks border and sizes (section 3.8.1): `GL_INVALID_VALUE` for a border other than 0 or 1
/// (other than 0 for rectangle textures),
/// or a negative size (or one smaller than 2 × border); cube faces must be square. Sizes need
/// not be 2^n + 2 × border: glrt implements ARB_texture_non_power_of_two (the renderer's images
/// take any size; mipmap levels halve with the floor, as completeness in `snapshot` checks).
pub fn check_size(target: Target, level: usize, size: [GLsizei; 3], border: GLint) -> Result<SizeCheck, GLenum> {
    let border_max = if target == Target::Rect { 0 } else { 1 };
    let border = usize::try_from(border).ok().filter(|&b| b <= border_max).ok_or(gl::GL_INVALID_VALUE)?;
    let dims = target.dims();
    let mut out = [1usize; 3];
    let mut too_large = false;
    for (i, &s) in size.iter().enumerate().take(dims) {
        let s = usize::try_from(s).map_err(|_| gl::GL_INVALID_VALUE)?;
        let inner = s.checked_sub(2 * border).ok_or(gl::GL_INVALID_VALUE)?;
        too_large |= inner > target.max_size() >> level;
        out[i] = s;
    }
    if target == Target::Cube && size[0] != size[1] {
        return Err(gl::GL_INVALID_VALUE);
    }
    Ok(if too_large {
        SizeCheck::TooLarge
    } else if out[0] * out[1] * out[2] > MAX_IMAGE_TEXELS {
        SizeCheck::OutOfMemory
    } else {
        SizeCheck::Fits(out)
    })
}

/// Resolves colour indices to canonical texels with `palette`.
pub fn resolve_indices(indices: &[u16], palette: &Palette) -> Vec<u8> {
    indices.iter().flat_map(|&i| palette.texel(i)).collect()
}

/// Pixels converted for storage in a level.
#[derive(Default)]
struct Converted {
    /// Canonical RGBA8 texels.
    texels: Vec<u8>,
    /// RGBA `f32` texels of [`Precision::Float`] levels (empty otherwise).
    values: Vec<f32>,
    /// RGBA integer texels of [`Precision::Integer`] levels (empty otherwise).
    integers: Vec<i64>,
    /// Depth values at the internal format's precision (depth formats only).
    depth: Vec<f32>,
    /// Colour indices (paletted formats only).
    indices: Option<Arc<Vec<u16>>>,
    /// Stencil indices (depth/stencil formats only).
    stencil: Option<Arc<Vec<u8>>>,
}

/// Converts unpacked pixels (zeros when `None`) for a level of internal format `internal`
/// (the reported enum) and base `base`. Indices keep the low bits of the paletted format,
/// depth values are rounded to the bits of the depth format, and depth/stencil formats keep
/// the stencil indices masked by 2^8 − 1 (EXT_packed_depth_stencil section 3.8.1; zeros when
/// the pixels have none, where the spec leaves them undefined).
/// Writes `data` into a region of a level of `obj` (given as `base`, or as the level's own base
/// format when `None`), recompresses it, regenerates mipmaps when the base level changed with
/// `GL_GENERATE_MIPMAP` on, and gives the object a new content version.
#[allow(clippy::too_many_arguments)]
fn write_object_region(obj: &mut TextureObject, palette: &Palette, face: usize, level: usize, offset: [usize; 3], size: [usize; 3], base: Option<Base>, data: Unpacked) {
    if let Some(l) = obj.level_slot(face, level).as_mut() {
        let converted = convert(base.unwrap_or(l.base), l.internal_format, Some(data), size[0] * size[1] * size[2], palette);
        let blocks = l.compressed.clone();
        write_region(l, offset, size, &converted);
        super::compressed::recompress_region(l, blocks, offset, size);
    }
    let base_level = obj.params.levels[0].max(0) as usize;
    if obj.params.generate_mipmap && level == base_level {
        super::mipmap::generate(obj, face, level);
    }
    obj.touch();
}

fn convert(base: Base, internal: GLenum, data: Option<Unpacked>, count: usize, palette: &Palette) -> Converted {
    match (base, data) {
        (Base::ColorIndex, data) => {
            let mask = (1i64 << formats::index_bits(internal)) - 1;
            let indices: Vec<u16> = match data {
                Some(Unpacked::Index(ix)) => ix.iter().map(|&i| (i & mask) as u16).collect(),
                _ => vec![0; count],
            };
            Converted { texels: resolve_indices(&indices, palette), indices: Some(Arc::new(indices)), ..Converted::default() }
        }
        (Base::Texel(TexelFormat::Depth), data) => {
            let bits = formats::depth_bits(internal);
            let (depth, stencil) = match data {
                Some(Unpacked::Depth(d)) => (d, Vec::new()),
                Some(Unpacked::DepthStencil(d, s)) => (d, s),
                _ => (vec![0.0; count], Vec::new()),
            };
            let depth: Vec<f32> = depth.iter().map(|&v| formats::stored_depth(v, bits)).collect();
            let stencil = (formats::stencil_bits(internal) > 0).then(|| {
                let mask = (1i64 << formats::stencil_bits(internal)) - 1;
                Arc::new((0..depth.len()).map(|i| stencil.get(i).map_or(0, |&s| (s & mask) as u8)).collect())
            });
            let texels = depth.iter().flat_map(|&d| formats::texel(TexelFormat::Depth, [d, d, d, 1.0])).collect();
            Converted { texels, depth, stencil, ..Converted::default() }
        }
        (Base::Texel(f), data) if formats::level_storage(base, internal).is_integer() => {
            // Integer formats keep the components clamped to their range (EXT_texture_integer
            // section 3.8.1); their 8-bit texels stay zero (see `crate::frame::texture`).
            let storage = formats::level_storage(base, internal);
            let integers: Vec<i64> = match data {
                Some(Unpacked::Integer(c)) => c.iter().flat_map(|&c| formats::expand(f, storage.clamp_integers(c))).collect(),
                _ => (0..count).flat_map(|_| formats::expand(f, [0; 4])).collect(),
            };
            Converted { texels: vec![0; integers.len()], integers, ..Converted::default() }
        }
        (Base::Texel(f), data) => {
            let storage = formats::level_storage(base, internal);
            let colours = match data {
                Some(Unpacked::Rgba(c)) => c.iter().map(|&c| formats::expand(f, storage.round(c))).collect(),
                _ => vec![[0.0; 4]; count],
            };
            let texels = colours.iter().flat_map(|&c| formats::texel(TexelFormat::Rgba, c)).collect();
            let values = if storage.precision() == Precision::Float { colours.into_iter().flatten().collect() } else { Vec::new() };
            Converted { texels, values, ..Converted::default() }
        }
    }
}

/// Builds a level of `size` (border included) from unpacked pixels (zeros when `None`).
fn build_level(internal: Internal, size: [usize; 3], border: usize, data: Option<Unpacked>, palette: &Palette) -> Level {
    let count = size[0] * size[1] * size[2];
    level_of(internal, size, border, convert(internal.base, internal.reported, data, count, palette))
}

/// A level of `size` (border included) holding `converted`.
fn level_of(internal: Internal, size: [usize; 3], border: usize, converted: Converted) -> Level {
    let Converted { texels, values, integers, depth, indices, stencil } = converted;
    let [w, h, d] = size.map(|v| v as u32);
    let precision = internal.storage.precision();
    let mut level = Level {
        image: Arc::new(TexImage { width: w, height: h, depth: d, border: border as u32, texels, precision, values, integers, depth_values: depth }),
        size,
        border,
        internal_format: internal.reported,
        base: internal.base,
        compressed: None,
        indices,
        stencil,
    };
    super::compressed::recompress(&mut level);
    level
}

/// S3TC internal formats need 2D images (`GL_INVALID_ENUM`) without border
/// (`GL_INVALID_OPERATION`).
fn check_compressed_internal(internal: GLenum, dims: usize, border: GLint) -> Result<(), GLenum> {
    match S3tc::of(internal) {
        Some(_) if dims != 2 => Err(gl::GL_INVALID_ENUM),
        Some(_) if border != 0 => Err(gl::GL_INVALID_OPERATION),
        _ => Ok(()),
    }
}

/// Writes a region of converted pixels into a level; `offset` includes the border.
fn write_region(level: &mut Level, offset: [usize; 3], size: [usize; 3], src: &Converted) {
    let [lw, lh, _] = level.size;
    let image = Arc::make_mut(&mut level.image);
    let mut level_indices = level.indices.as_mut().map(Arc::make_mut);
    let mut level_stencil = level.stencil.as_mut().map(Arc::make_mut);
    let mut i = 0;
    for z in 0..size[2] {
        for y in 0..size[1] {
            for x in 0..size[0] {
                let dst = ((offset[2] + z) * lh + offset[1] + y) * lw + offset[0] + x;
                if let (Some(d), Some(s)) = (image.texels.get_mut(dst * 4..dst * 4 + 4), src.texels.get(i * 4..i * 4 + 4)) {
                    d.copy_from_slice(s);
                }
                if let (Some(d), Some(s)) = (image.values.get_mut(dst * 4..dst * 4 + 4), src.values.get(i * 4..i * 4 + 4)) {
                    d.copy_from_slice(s);
                }
                if let (Some(d), Some(s)) = (image.integers.get_mut(dst * 4..dst * 4 + 4), src.integers.get(i * 4..i * 4 + 4)) {
                    d.copy_from_slice(s);
                }
                if let (Some(d), Some(&s)) = (image.depth_values.get_mut(dst), src.depth.get(i)) {
                    *d = s;
                }
                if let (Some(d), Some(&s)) = (level_indices.as_deref_mut().and_then(|li| li.get_mut(dst)), src.indices.as_ref().and_then(|si| si.get(i))) {
                    *d = s;
                }
                if let (Some(d), Some(&s)) = (level_stencil.as_deref_mut().and_then(|ls| ls.get_mut(dst)), src.stencil.as_ref().and_then(|ss| ss.get(i))) {
                    *d = s;
                }
                i += 1;
            }
        }
    }
    level.compressed = None;
}

/// Checks that an image format suits the internal format: depth and depth/stencil pixels go
/// with depth and depth/stencil internal formats, in any pairing, and no other pixels do
/// (`GL_INVALID_OPERATION`; EXT_packed_depth_stencil section 3.8.1, which Mesa applies to
/// `GL_STENCIL_INDEX` too), paletted internal formats need `GL_COLOR_INDEX`, and
/// `GL_STENCIL_INDEX` is no colour texture format (`GL_INVALID_ENUM`). Integer internal formats
/// (`integer`) need the `*_INTEGER` formats and other formats refuse them
/// (`GL_INVALID_OPERATION`; EXT_texture_integer section 3.8.1).
fn check_format_pair(format: Format, base: Base, integer: bool) -> Result<(), GLenum> {
    let depth_base = base == Base::Texel(TexelFormat::Depth);
    match format.kind {
        Kind::Depth | Kind::DepthStencil if !depth_base => Err(gl::GL_INVALID_OPERATION),
        Kind::Color | Kind::Index | Kind::Stencil | Kind::Integer if depth_base => Err(gl::GL_INVALID_OPERATION),
        Kind::Stencil => Err(gl::GL_INVALID_ENUM),
        Kind::Integer if !integer => Err(gl::GL_INVALID_OPERATION),
        kind if integer && kind != Kind::Integer => Err(gl::GL_INVALID_OPERATION),
        Kind::Color if base == Base::ColorIndex => Err(gl::GL_INVALID_OPERATION),
        _ => Ok(()),
    }
}

/// Depth and depth/stencil images may not be 3D (`GL_INVALID_OPERATION`; ARB_depth_texture
/// and EXT_packed_depth_stencil section 3.8.1 name 1D and 2D targets; cube maps, allowed from
/// OpenGL 3.0 on, are accepted).
fn check_depth_target(target: Target, base: Base) -> Result<(), GLenum> {
    if target == Target::D3 && base == Base::Texel(TexelFormat::Depth) { Err(gl::GL_INVALID_OPERATION) } else { Ok(()) }
}

impl Context {
    /// Runs `f` on the object a destination names: the bound texture, or the proxy.
    pub(crate) fn with_dest<R>(&mut self, dest: Dest, f: impl FnOnce(&mut TextureObject, &Palette) -> R) -> R {
        let shared_palette = self.texture.shared_palette.clone();
        if dest.proxy {
            return f(&mut self.texture.proxies[dest.target.index()], &shared_palette);
        }
        self.with_bound_texture(dest.target, |obj| {
            let palette = obj.palette.clone();
            let palette = if palette.entries.is_empty() { &shared_palette } else { &palette };
            f(obj, palette)
        })
    }

    /// Stores `level` (or clears it) and regenerates mipmaps when asked.
    pub(crate) fn store_level(&mut self, dest: Dest, level: usize, image: Option<Level>) {
        self.with_dest(dest, |obj, _| {
            let regenerate = !dest.proxy && obj.params.generate_mipmap && level == obj.params.levels[0].max(0) as usize && image.is_some();
            *obj.level_slot(dest.face, level) = image;
            if regenerate {
                super::mipmap::generate(obj, dest.face, level);
            }
            obj.touch();
        });
    }

    /// `glTexImage1D/2D/3D`.
    unsafe fn tex_image(
        &mut self,
        dims: usize,
        target: GLenum,
        level: GLint,
        internalformat: GLint,
        size: [GLsizei; 3],
        border: GLint,
        format: GLenum,
        type_: GLenum,
        pixels: *const c_void,
        command: &'static str,
    ) {
        self.write_back_framebuffer();
        let Some(dest) = image_target(dims, target) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let Some(ft) = self.parse_pixel_format(format, type_, command) else { return };
        let Some(internal) = u32::try_from(internalformat).ok().and_then(formats::internal_format) else {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        };
        let checked = check_level(dest.target, level)
            .and_then(|l| Ok((l, check_size(dest.target, l, size, border)?)))
            .and_then(|v| check_format_pair(ft.0, internal.base, internal.storage.is_integer()).map(|()| v))
            .and_then(|v| check_depth_target(dest.target, internal.base).map(|()| v))
            .and_then(|v| check_compressed_internal(internalformat as GLenum, dims, border).map(|()| v));
        let (level, fit) = match checked {
            Ok(v) => v,
            Err(e) => return self.set_error_in(e, command),
        };
        let border = border as usize;
        let size = match fit {
            SizeCheck::Fits(s) => s,
            SizeCheck::TooLarge | SizeCheck::OutOfMemory if dest.proxy => return self.store_level(dest, level, None),
            SizeCheck::TooLarge => return self.set_error_in(gl::GL_INVALID_VALUE, command),
            SizeCheck::OutOfMemory => return self.set_error_in(gl::GL_OUT_OF_MEMORY, command),
        };
        if dest.proxy {
            let proxy = Level { image: Arc::default(), size, border, internal_format: internal.reported, base: internal.base, compressed: None, indices: None, stencil: None };
            return self.store_level(dest, level, Some(proxy));
        }
        let Ok(direct) = (unsafe { self.direct_texels(ft, internal, size, pixels, command) }) else { return };
        let image = if let Some(texels) = direct {
            level_of(internal, size, border, Converted { texels, ..Converted::default() })
        } else {
            let keep_index = internal.base == Base::ColorIndex;
            let Ok(data) = (unsafe { self.unpack_client(ft, size, pixels, keep_index, !internal.storage.unclamped(), command) }) else { return };
            self.with_dest(dest, |_, palette| build_level(internal, size, border, data, palette))
        };
        self.store_level(dest, level, Some(image));
    }

    /// `glTexImage1D`: see [`Context::glTexImage2D`].
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexImage1D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_image(1, target, level, internalformat, [width, 1, 1], border, format, type_, pixels, "glTexImage1D") }
    }

    /// `glTexImage2D`: `GL_INVALID_ENUM` for a bad target, format or type;
    /// `GL_INVALID_VALUE` for a bad internal format, level, border or size (at least
    /// 2 × border, at most `GL_MAX_TEXTURE_SIZE` >> level + 2 × border); `GL_INVALID_OPERATION` for a
    /// packed type that does not match the format or a depth/colour mismatch. Proxy targets
    /// only record the sizes (all zero when too large). A null `pixels` allocates the level.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexImage2D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, height: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_image(2, target, level, internalformat, [width, height, 1], border, format, type_, pixels, "glTexImage2D") }
    }

    /// `glTexImage3D`: see [`Context::glTexImage2D`].
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexImage3D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_image(3, target, level, internalformat, [width, height, depth], border, format, type_, pixels, "glTexImage3D") }
    }

    /// Records an image command with a copy of its pixels, unless its target is a proxy (those
    /// run at once, section 5.4).
    unsafe fn compile_tex_image(&mut self, dims: usize, target: GLenum, format: GLenum, type_: GLenum, size: [GLsizei; 3], pixels: *const c_void, command: &'static str, run: impl Fn(&mut Context, *const c_void) + Send + Sync + 'static) {
        if image_target(dims, target).is_some_and(|d| d.proxy) {
            return run(self, pixels);
        }
        unsafe { self.compile_image_command(format, type_, size, pixels, command, run) }
    }

    /// `glTexImage1D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexImage1D`].
    pub unsafe fn compile_glTexImage1D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexImage1D(target, level, internalformat, width, border, format, type_, p) };
        unsafe { self.compile_tex_image(1, target, format, type_, [width, 1, 1], pixels, "glTexImage1D", run) }
    }

    /// `glTexImage2D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexImage2D`].
    pub unsafe fn compile_glTexImage2D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, height: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexImage2D(target, level, internalformat, width, height, border, format, type_, p) };
        unsafe { self.compile_tex_image(2, target, format, type_, [width, height, 1], pixels, "glTexImage2D", run) }
    }

    /// `glTexImage3D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexImage3D`].
    pub unsafe fn compile_glTexImage3D(&mut self, target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexImage3D(target, level, internalformat, width, height, depth, border, format, type_, p) };
        unsafe { self.compile_tex_image(3, target, format, type_, [width, height, depth], pixels, "glTexImage3D", run) }
    }

    /// Checks a sub-image region against the existing level: `GL_INVALID_ENUM` for a bad or
    /// proxy target, `GL_INVALID_VALUE` for a bad level, negative size or a region outside the
    /// image (border included), `GL_INVALID_OPERATION` when the level was never specified.
    /// Returns the destination, level, the region's offset (border included) and size, and
    /// the level's base format.
    pub(crate) fn check_sub_image(&mut self, dims: usize, target: GLenum, level: GLint, offset: [GLint; 3], size: [GLsizei; 3], command: &'static str) -> Option<SubImage> {
        let result = (|| {
            let dest = image_target(dims, target).filter(|d| !d.proxy).ok_or(gl::GL_INVALID_ENUM)?;
            let level = check_level(dest.target, level)?;
            let existing = self.with_dest(dest, |obj, _| obj.level(dest.face, level).map(|l| (l.size, l.border, l.base)));
            let (lsize, border, base) = existing.ok_or(gl::GL_INVALID_OPERATION)?;
            let mut off = [0usize; 3];
            let mut sz = [1usize; 3];
            for i in 0..dims {
                let s = usize::try_from(size[i]).map_err(|_| gl::GL_INVALID_VALUE)?;
                let o = i64::from(offset[i]) + border as i64;
                if o < 0 || o as usize + s > lsize[i] {
                    return Err(gl::GL_INVALID_VALUE);
                }
                off[i] = o as usize;
                sz[i] = s;
            }
            Ok((dest, level, off, sz, base))
        })();
        result.map_err(|e| self.set_error_in(e, command)).ok()
    }

    /// `glTexSubImage1D/2D/3D`.
    unsafe fn tex_sub_image(&mut self, dims: usize, target: GLenum, level: GLint, offset: [GLint; 3], size: [GLsizei; 3], format: GLenum, type_: GLenum, pixels: *const c_void, command: &'static str) {
        self.write_back_framebuffer();
        let Some((dest, level, off, sz, base)) = self.check_sub_image(dims, target, level, offset, size, command) else { return };
        let Some(ft) = self.parse_pixel_format(format, type_, command) else { return };
        let internal = self.with_dest(dest, |obj, _| obj.level(dest.face, level).map_or(gl::GL_NONE, |l| l.internal_format));
        let storage = formats::level_storage(base, internal);
        if let Err(e) = check_format_pair(ft.0, base, storage.is_integer()) {
            return self.set_error_in(e, command);
        }
        let clamp = !storage.unclamped();
        let Ok(data) = (unsafe { self.unpack_client(ft, sz, pixels, base == Base::ColorIndex, clamp, command) }) else { return };
        let Some(data) = data else { return self.null_pointer(command) };
        self.write_sub_image(dest, level, off, sz, base, data);
    }

    /// Writes `data` (`size` pixels) into `level` of `dest` at `offset` (border included),
    /// regenerates mipmaps when `GL_GENERATE_MIPMAP` asks, and changes the content version.
    fn write_sub_image(&mut self, dest: Dest, level: usize, offset: [usize; 3], size: [usize; 3], base: Base, data: Unpacked) {
        self.with_dest(dest, |obj, palette| write_object_region(obj, palette, dest.face, level, offset, size, Some(base), data));
    }

    /// Writes `data` (pixels after transfer) into the region `offset`/`size` of `level` of
    /// `face` of the texture named `name`, converted to the level's internal format (what
    /// framebuffer-object texture attachments are read back with). Nothing happens when the
    /// texture or level no longer exists.
    pub(crate) fn write_texture_region(&mut self, name: GLuint, face: usize, level: usize, offset: [usize; 3], size: [usize; 3], data: Unpacked) {
        let shared_palette = self.texture.shared_palette.clone();
        let shared = self.shared.clone();
        let mut shared = shared.lock();
        let Some(obj) = shared.textures.get_mut(name) else { return };
        if obj.level(face, level).is_none() {
            return;
        }
        let palette = if obj.palette.entries.is_empty() { shared_palette } else { obj.palette.clone() };
        write_object_region(obj, &palette, face, level, offset, size, None, data);
    }

    /// `glTexSubImage1D`.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexSubImage1D(&mut self, target: GLenum, level: GLint, xoffset: GLint, width: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_sub_image(1, target, level, [xoffset, 0, 0], [width, 1, 1], format, type_, pixels, "glTexSubImage1D") }
    }

    /// `glTexSubImage2D`: replaces a region of an existing level (errors as
    /// `Context::check_sub_image` and the format checks of `glTexImage2D`).
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexSubImage2D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_sub_image(2, target, level, [xoffset, yoffset, 0], [width, height, 1], format, type_, pixels, "glTexSubImage2D") }
    }

    /// `glTexSubImage3D`.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the image the unpack modes describe.
    pub unsafe fn glTexSubImage3D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        unsafe { self.tex_sub_image(3, target, level, [xoffset, yoffset, zoffset], [width, height, depth], format, type_, pixels, "glTexSubImage3D") }
    }

    /// `glTexSubImage1D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexSubImage1D`].
    pub unsafe fn compile_glTexSubImage1D(&mut self, target: GLenum, level: GLint, xoffset: GLint, width: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexSubImage1D(target, level, xoffset, width, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [width, 1, 1], pixels, "glTexSubImage1D", run) }
    }

    /// `glTexSubImage2D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexSubImage2D`].
    pub unsafe fn compile_glTexSubImage2D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexSubImage2D(target, level, xoffset, yoffset, width, height, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [width, height, 1], pixels, "glTexSubImage2D", run) }
    }

    /// `glTexSubImage3D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexSubImage3D`].
    pub unsafe fn compile_glTexSubImage3D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glTexSubImage3D(target, level, xoffset, yoffset, zoffset, width, height, depth, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [width, height, depth], pixels, "glTexSubImage3D", run) }
    }

    /// The framebuffer copy of a `glCopyTex*` command (section 3.8.2): the renderer reads
    /// `src` of the colour (or, for depth textures, depth; for depth/stencil textures depth
    /// and stencil) buffer back, the pixels go through pixel transfer and are written into the
    /// level at `offset` (border included), and the content version changes, so draws that use
    /// the texture afterwards sample the copied pixels. Without a renderer that reads back the
    /// texels stay as they were (logged once). The copy is also recorded in the frame.
    fn record_texture_copy(&mut self, dest: Dest, level: usize, offset: [usize; 3], src: [i32; 4], base: Base) {
        let internal = self.with_dest(dest, |obj, _| obj.level(dest.face, level).map(|l| l.internal_format)).unwrap_or(gl::GL_NONE);
        let (buffer, format) = match base {
            Base::Texel(TexelFormat::Depth) if formats::stencil_bits(internal) > 0 => (PixelBuffer::Depth, gl::GL_DEPTH_STENCIL),
            Base::Texel(TexelFormat::Depth) => (PixelBuffer::Depth, gl::GL_DEPTH_COMPONENT),
            _ => (PixelBuffer::Color, gl::GL_RGBA),
        };
        let size = [src[2].max(0) as usize, src[3].max(0) as usize, 1];
        if let Some(format) = codec::format(format).filter(|_| size[0] * size[1] > 0)
            && let Some(data) = self.read_transferred(format, src, "glCopyTexImage")
        {
            self.write_sub_image(dest, level, offset, size, base, data);
        }
        let texture = self.bound_texture(dest.target);
        let version = self.with_dest(dest, |obj, _| obj.version);
        self.push_pixel_op(PixelKind::TextureCopy {
            texture,
            version,
            face: dest.face as u32,
            level: level as u32,
            offset: offset.map(|v| v as i32),
            src,
            buffer,
        });
    }

    /// `glCopyTexImage1D/2D`: like `glTexImage`, with the pixels from the framebuffer. An
    /// internal format outside tables 3.15–3.16, one of 1–4 (section 3.8.2: "may not be
    /// specified as 1, 2, 3, or 4") or a colour index raises `GL_INVALID_ENUM`, as in Mesa
    /// (the spec names no error). Depth/stencil formats copy depth and stencil
    /// (EXT_packed_depth_stencil section 3.8.2; glrt's visuals have both buffers, so its
    /// `GL_INVALID_OPERATION` for a missing one never applies). An integer internal format
    /// is `GL_INVALID_OPERATION`, glrt's colour buffers not being integer (EXT_texture_integer
    /// section 3.8.2). The level is allocated zero-filled and the copy is recorded in the
    /// frame.
    fn copy_tex_image(&mut self, dims: usize, target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, size: [GLsizei; 2], border: GLint, command: &'static str) {
        self.write_back_framebuffer();
        let Some(dest) = image_target(dims, target).filter(|d| !d.proxy) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let internal = formats::internal_format(internalformat).filter(|i| !(1..=4).contains(&internalformat) && i.base != Base::ColorIndex);
        let Some(internal) = internal else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let checked = check_level(dest.target, level)
            .and_then(|l| Ok((l, check_size(dest.target, l, [size[0], size[1], 1], border)?)))
            .and_then(|v| check_compressed_internal(internalformat, dims, border).map(|()| v))
            .and_then(|v| if internal.storage.is_integer() { Err(gl::GL_INVALID_OPERATION) } else { Ok(v) });
        let (level, size3) = match checked {
            Ok((l, SizeCheck::Fits(s))) => (l, s),
            Ok((_, SizeCheck::TooLarge)) => return self.set_error_in(gl::GL_INVALID_VALUE, command),
            Ok((_, SizeCheck::OutOfMemory)) => return self.set_error_in(gl::GL_OUT_OF_MEMORY, command),
            Err(e) => return self.set_error_in(e, command),
        };
        let image = build_level(internal, size3, border as usize, None, &Palette::default());
        self.store_level(dest, level, Some(image));
        self.record_texture_copy(dest, level, [0; 3], [x, y, size3[0] as i32, size3[1] as i32], internal.base);
    }

    /// `glCopyTexImage1D`.
    pub fn glCopyTexImage1D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, width: GLsizei, border: GLint) {
        self.copy_tex_image(1, target, level, internalformat, x, y, [width, 1], border, "glCopyTexImage1D");
    }

    /// `glCopyTexImage2D`.
    pub fn glCopyTexImage2D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, width: GLsizei, height: GLsizei, border: GLint) {
        self.copy_tex_image(2, target, level, internalformat, x, y, [width, height], border, "glCopyTexImage2D");
    }

    /// `glCopyTexSubImage1D/2D/3D`: the region checks of `glTexSubImage`, and
    /// `GL_INVALID_OPERATION` for an integer level (as `glCopyTexImage2D`); the copy is
    /// recorded in the frame and the content version changes.
    fn copy_tex_sub_image(&mut self, dims: usize, target: GLenum, level: GLint, offset: [GLint; 3], src: [i32; 4], command: &'static str) {
        self.write_back_framebuffer();
        let size = [src[2], if dims >= 2 { src[3] } else { 1 }, 1];
        let Some((dest, level, off, _, base)) = self.check_sub_image(dims, target, level, offset, size, command) else { return };
        let internal = self.with_dest(dest, |obj, _| obj.level(dest.face, level).map_or(gl::GL_NONE, |l| l.internal_format));
        if formats::level_storage(base, internal).is_integer() {
            return self.set_error_in(gl::GL_INVALID_OPERATION, command);
        }
        self.with_dest(dest, |obj, _| obj.touch());
        self.record_texture_copy(dest, level, off, [src[0], src[1], size[0], size[1]], base);
    }

    /// `glCopyTexSubImage1D`.
    pub fn glCopyTexSubImage1D(&mut self, target: GLenum, level: GLint, xoffset: GLint, x: GLint, y: GLint, width: GLsizei) {
        self.copy_tex_sub_image(1, target, level, [xoffset, 0, 0], [x, y, width, 1], "glCopyTexSubImage1D");
    }

    /// `glCopyTexSubImage2D`.
    pub fn glCopyTexSubImage2D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei) {
        self.copy_tex_sub_image(2, target, level, [xoffset, yoffset, 0], [x, y, width, height], "glCopyTexSubImage2D");
    }

    /// `glCopyTexSubImage3D`: copies into slice `zoffset`.
    pub fn glCopyTexSubImage3D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei) {
        self.copy_tex_sub_image(3, target, level, [xoffset, yoffset, zoffset], [x, y, width, height], "glCopyTexSubImage3D");
    }

    /// `glGetTexImage` (section 6.1.4): the level's texels as RGBA (table 6.1), through pixel
    /// transfer and the pack modes. `GL_INVALID_ENUM` for a bad or proxy target, format or
    /// type (`GL_COLOR_INDEX` and `GL_STENCIL_INDEX` included), `GL_INVALID_VALUE` for a bad
    /// level, `GL_INVALID_OPERATION` for a colour format from a depth level, `GL_DEPTH_COMPONENT`
    /// from a colour level, or `GL_DEPTH_STENCIL` from a level without stencil
    /// (EXT_packed_depth_stencil section 6.1.4), or an integer format from a non-integer level
    /// and the reverse (EXT_texture_integer; integer levels are packed without pixel transfer,
    /// luminance from R, each component clamped to the type). Unspecified levels write nothing.
    ///
    /// # Safety
    /// A non-null `pixels` must point to writable memory as the pack modes describe.
    pub unsafe fn glGetTexImage(&mut self, target: GLenum, level: GLint, format: GLenum, type_: GLenum, pixels: *mut c_void) {
        const CMD: &str = "glGetTexImage";
        self.write_back_framebuffer();
        let Some(dest) = any_image_target(target).filter(|d| !d.proxy) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let Some((f, t)) = self.parse_pixel_format(format, type_, CMD) else { return };
        if matches!(f.kind, Kind::Index | Kind::Stencil) {
            return self.set_error_in(gl::GL_INVALID_ENUM, CMD);
        }
        let level = match check_level(dest.target, level) {
            Ok(l) => l,
            Err(e) => return self.set_error_in(e, CMD),
        };
        let Some(lvl) = self.with_dest(dest, |obj, _| obj.level(dest.face, level).cloned()) else { return };
        let texel_format = match lvl.base {
            Base::Texel(tf) => tf,
            Base::ColorIndex => TexelFormat::Rgba,
        };
        let depth_level = texel_format == TexelFormat::Depth;
        let integer_level = lvl.image.precision == Precision::Integer;
        let mismatch = match f.kind {
            Kind::DepthStencil => formats::stencil_bits(lvl.internal_format) == 0,
            Kind::Depth => !depth_level,
            Kind::Integer => !integer_level,
            _ => depth_level || integer_level,
        };
        if mismatch {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        }
        if integer_level {
            let mut values = Vec::with_capacity(lvl.image.integers.len());
            for c in lvl.image.integers.chunks_exact(4) {
                codec::from_integer_rgba(f.gl, formats::texel_to_rgba(texel_format, [c[0], c[1], c[2], c[3]]), &mut values);
            }
            return unsafe { self.pack_client_integers((f, t), lvl.size, pixels, &values, CMD) };
        }
        // Depth levels answer from their full-precision values, with the stencil index in
        // the second component.
        let rgba: Vec<[f32; 4]> = if depth_level {
            let stencil = |i: usize| lvl.stencil.as_ref().and_then(|s| s.get(i)).map_or(0.0, |&s| f32::from(s));
            lvl.image.depth_values.iter().enumerate().map(|(i, &d)| [d, stencil(i), 0.0, 1.0]).collect()
        } else if lvl.image.precision == Precision::Float {
            lvl.image.values.chunks_exact(4).map(|c| formats::texel_to_rgba(texel_format, [c[0], c[1], c[2], c[3]])).collect()
        } else {
            lvl.image.texels.chunks_exact(4).map(|c| formats::texel_to_rgba(texel_format, [c[0], c[1], c[2], c[3]].map(|v| f32::from(v) / 255.0))).collect()
        };
        let clamp = !formats::level_storage(lvl.base, lvl.internal_format).unclamped();
        let values = self.transfer_for_pack(f, &rgba, Luminance::Red, clamp);
        unsafe { self.pack_client((f, t), lvl.size, pixels, &values, CMD) }
    }

    /// The value of a level parameter (table 6.17); `Err` with the error to raise.
    fn level_parameter(&mut self, target: GLenum, level: GLint, pname: GLenum) -> Result<Value, GLenum> {
        let dest = any_image_target(target).ok_or(gl::GL_INVALID_ENUM)?;
        let level = check_level(dest.target, level)?;
        let lvl = self.with_dest(dest, |obj, _| obj.level(dest.face, level).cloned());
        let size = |i: usize| Value::int(lvl.as_ref().map_or(0, |l| l.size[i] as i64));
        let s3tc = lvl.as_ref().and_then(|l| S3tc::of(l.internal_format));
        Ok(match pname {
            gl::GL_TEXTURE_WIDTH => size(0),
            gl::GL_TEXTURE_HEIGHT => size(1),
            gl::GL_TEXTURE_DEPTH => size(2),
            gl::GL_TEXTURE_BORDER => Value::int(lvl.as_ref().map_or(0, |l| l.border as i64)),
            gl::GL_TEXTURE_INTERNAL_FORMAT => Value::int(lvl.as_ref().map_or(1, |l| l.internal_format)),
            gl::GL_TEXTURE_COMPRESSED => Value::bool(s3tc.is_some()),
            gl::GL_TEXTURE_INDEX_SIZE_EXT => {
                let paletted = lvl.as_ref().filter(|l| l.base == Base::ColorIndex);
                Value::int(paletted.map_or(0, |l| i64::from(formats::index_bits(l.internal_format))))
            }
            gl::GL_TEXTURE_RED_TYPE..=gl::GL_TEXTURE_DEPTH_TYPE => {
                let ty = lvl.as_ref().map_or(gl::GL_NONE, |l| formats::component_type(l.base, l.internal_format, pname).unwrap_or(gl::GL_NONE));
                Value::int(i64::from(ty))
            }
            gl::GL_TEXTURE_COMPRESSED_IMAGE_SIZE => {
                let (Some(l), Some(fmt)) = (lvl.as_ref(), s3tc) else { return Err(gl::GL_INVALID_OPERATION) };
                Value::int((super::compressed::image_size(fmt, l.size) as i64).min(i64::from(i32::MAX)))
            }
            _ => Value::int(match &lvl {
                Some(l) => formats::component_bits(l.base, l.internal_format, pname).ok_or(gl::GL_INVALID_ENUM)?,
                None => formats::component_bits(Base::Texel(TexelFormat::Rgba), gl::GL_RGBA, pname).map(|_| 0).ok_or(gl::GL_INVALID_ENUM)?,
            }),
        })
    }

    /// `glGetTexLevelParameterfv`.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetTexLevelParameterfv(&mut self, target: GLenum, level: GLint, pname: GLenum, params: *mut GLfloat) {
        match self.level_parameter(target, level, pname) {
            Ok(v) => unsafe { write_slice(params, &v.to_doubles().iter().map(|&x| x as f32).collect::<Vec<_>>()) },
            Err(e) => self.set_error_in(e, "glGetTexLevelParameterfv"),
        }
    }

    /// `glGetTexLevelParameteriv`: `GL_INVALID_ENUM` for a bad target or name,
    /// `GL_INVALID_VALUE` for a bad level; proxies answer too.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetTexLevelParameteriv(&mut self, target: GLenum, level: GLint, pname: GLenum, params: *mut GLint) {
        match self.level_parameter(target, level, pname) {
            Ok(v) => unsafe { write_slice(params, &v.to_ints()) },
            Err(e) => self.set_error_in(e, "glGetTexLevelParameteriv"),
        }
    }
}

impl Context {
    /// `glTexImage3DEXT` (EXT_texture3D): `glTexImage3D` with a `GLenum` internal format.
    ///
    /// # Safety
    /// As [`Context::glTexImage3D`].
    pub unsafe fn glTexImage3DEXT(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let internal = GLint::try_from(internalformat).unwrap_or(-1);
        unsafe { self.glTexImage3D(target, level, internal, width, height, depth, border, format, type_, pixels) }
    }

    /// `glTexImage3DEXT` in a display list.
    ///
    /// # Safety
    /// As [`Context::glTexImage3D`].
    pub unsafe fn compile_glTexImage3DEXT(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, type_: GLenum, pixels: *const c_void) {
        let internal = GLint::try_from(internalformat).unwrap_or(-1);
        unsafe { self.compile_glTexImage3D(target, level, internal, width, height, depth, border, format, type_, pixels) }
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::pixels::PixelKind;
    use crate::translate::{Context, dispatch, gl};

    fn level_param(ctx: &mut Context, target: u32, level: i32, pname: u32) -> i32 {
        let mut v = -7;
        unsafe { ctx.glGetTexLevelParameteriv(target, level, pname, &mut v) };
        v
    }

    #[test]
    fn packed_formats_round_trip_through_get_tex_image() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        // Values every packed field represents exactly after an 8-bit round trip.
        for (format, type_, words) in [
            (gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_4_4_4_4, vec![0x1234u32, 0xfedc]),
            (gl::GL_BGRA, gl::GL_UNSIGNED_SHORT_4_4_4_4_REV, vec![0x1234, 0xfedc]),
            (gl::GL_RGBA, gl::GL_UNSIGNED_SHORT_5_5_5_1, vec![0x8421, 0xffff]),
            (gl::GL_BGRA, gl::GL_UNSIGNED_SHORT_1_5_5_5_REV, vec![0x8421, 0x7fff]),
            (gl::GL_RGB, gl::GL_UNSIGNED_SHORT_5_6_5, vec![0xf81f, 0x07e0]),
            (gl::GL_RGB, gl::GL_UNSIGNED_SHORT_5_6_5_REV, vec![0x1234, 0xabcd]),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_8_8_8_8, vec![0x11223344, 0xaabbccdd]),
            (gl::GL_BGRA, gl::GL_UNSIGNED_INT_8_8_8_8_REV, vec![0x11223344, 0xaabbccdd]),
            (gl::GL_RGB, gl::GL_UNSIGNED_BYTE_3_3_2, vec![0xa5, 0x3c]),
            (gl::GL_RGB, gl::GL_UNSIGNED_BYTE_2_3_3_REV, vec![0xa5, 0x3c]),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_2_10_10_10_REV, vec![0xc0000000, 0x3ff]),
            (gl::GL_RGBA, gl::GL_UNSIGNED_INT_10_10_10_2, vec![0xffc00003, 0x0]),
        ] {
            let size = match type_ {
                gl::GL_UNSIGNED_BYTE_3_3_2 | gl::GL_UNSIGNED_BYTE_2_3_3_REV => 1,
                gl::GL_UNSIGNED_INT_8_8_8_8 | gl::GL_UNSIGNED_INT_8_8_8_8_REV | gl::GL_UNSIGNED_INT_2_10_10_10_REV | gl::GL_UNSIGNED_INT_10_10_10_2 => 4,
                _ => 2,
            };
            let bytes: Vec<u8> = words.iter().flat_map(|&w| w.to_ne_bytes()[..size].to_vec()).collect();
            let bytes: Vec<u8> = match size {
                2 => words.iter().flat_map(|&w| (w as u16).to_ne_bytes()).collect(),
                4 => words.iter().flat_map(|&w| w.to_ne_bytes()).collect(),
                _ => bytes,
            };
            let internal = if format == gl::GL_RGB { gl::GL_RGB8 } else { gl::GL_RGBA8 } as i32;
            unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, internal, 2, 1, 0, format, type_, bytes.as_ptr().cast()) };
            assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "{type_:#x}");
            let mut back = vec![0u8; bytes.len()];
            unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, format, type_, back.as_mut_ptr().cast()) };
            assert_eq!(back, bytes, "{type_:#x}");
        }
    }

    #[test]
    fn unpack_modes_select_the_texels() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        // A 4×3 image of big-endian shorts; the texture is its 2×2 corner at (1, 1).
        let src: Vec<u16> = (0..12u16).map(|i| i * 0x1111).collect();
        let bytes: Vec<u8> = src.iter().flat_map(|v| v.to_be_bytes()).collect();
        ctx.glPixelStorei(gl::GL_UNPACK_SWAP_BYTES, i32::from(cfg!(target_endian = "little")));
        ctx.glPixelStorei(gl::GL_UNPACK_ROW_LENGTH, 4);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_PIXELS, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_ROWS, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 8);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE as i32, 2, 2, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_SHORT, bytes.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let mut out = [0u8; 4];
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        // Source values 5, 6, 9, 10 × 0x1111 → 0x55, 0x66, 0x99, 0xaa as bytes.
        assert_eq!(out, [0x55, 0x66, 0x99, 0xaa]);
        // Pack: skip pixels and row length on the way out, padding left as it was.
        ctx.glPixelStorei(gl::GL_PACK_ROW_LENGTH, 3);
        ctx.glPixelStorei(gl::GL_PACK_SKIP_PIXELS, 1);
        let mut wide = [0xeeu8; 6];
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, wide.as_mut_ptr().cast()) };
        assert_eq!(wide, [0xee, 0x55, 0x66, 0xee, 0x99, 0xaa]);
    }

    #[test]
    fn image_errors() {
        let (mut ctx, _) = Context::with_recording();
        let px = [0u8; 256];
        let tex = |ctx: &mut Context, target, level, internal: u32, w, h, border, format, type_| {
            unsafe { dispatch::glTexImage2D(ctx, target, level, internal as i32, w, h, border, format, type_, px.as_ptr().cast()) };
            ctx.glGetError()
        };
        let (t2, rgba, ub) = (gl::GL_TEXTURE_2D, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE);
        // ARB_texture_non_power_of_two: any size of at least 2 × border.
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 3, 4, 0, rgba, ub), gl::GL_NO_ERROR);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 5, 4, 1, rgba, ub), gl::GL_NO_ERROR);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 1, 4, 1, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 6, 4, 1, rgba, ub), gl::GL_NO_ERROR);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, -2, 4, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 4, 4, 2, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, -1, rgba, 4, 4, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 14, rgba, 1, 1, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 13, rgba, 2, 2, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 13, rgba, 1, 1, 0, rgba, ub), gl::GL_NO_ERROR);
        assert_eq!(tex(&mut ctx, gl::GL_TEXTURE_3D, 0, rgba, 4, 4, 0, rgba, ub), gl::GL_INVALID_ENUM);
        assert_eq!(tex(&mut ctx, t2, 0, 5, 4, 4, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 4, 4, 0, gl::GL_STENCIL_INDEX, ub), gl::GL_INVALID_ENUM);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 4, 4, 0, rgba, gl::GL_UNSIGNED_SHORT_5_6_5), gl::GL_INVALID_OPERATION);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 4, 4, 0, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT), gl::GL_INVALID_OPERATION);
        assert_eq!(tex(&mut ctx, t2, 0, gl::GL_DEPTH_COMPONENT, 2, 2, 0, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT), gl::GL_NO_ERROR);
        assert_eq!(tex(&mut ctx, gl::GL_TEXTURE_CUBE_MAP_NEGATIVE_Y, 0, rgba, 4, 2, 0, rgba, ub), gl::GL_INVALID_VALUE);
        assert_eq!(tex(&mut ctx, gl::GL_TEXTURE_2D, 0, rgba, 16384, 1, 0, rgba, ub), gl::GL_INVALID_VALUE);
        unsafe { dispatch::glTexImage3D(&mut ctx, gl::GL_TEXTURE_3D, 0, rgba as i32, 2048, 2048, 2048, 0, rgba, ub, std::ptr::null()) };
        assert_eq!(ctx.glGetError(), gl::GL_OUT_OF_MEMORY);
        // Sub-images: outside the level, or into a level never specified.
        ctx.glBindTexture(t2, 2);
        assert_eq!(tex(&mut ctx, t2, 0, rgba, 2, 2, 0, rgba, ub), gl::GL_NO_ERROR);
        unsafe { dispatch::glTexSubImage2D(&mut ctx, t2, 0, 1, 1, 2, 1, rgba, ub, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { dispatch::glTexSubImage2D(&mut ctx, t2, 1, 0, 0, 1, 1, rgba, ub, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_PROXY_TEXTURE_2D, 0, 0, 0, 1, 1, rgba, ub, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let mut out = [0u8; 4];
        unsafe { ctx.glGetTexImage(t2, 0, gl::GL_COLOR_INDEX, ub, out.as_mut_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        assert_eq!(level_param(&mut ctx, t2, 0, gl::GL_TEXTURE_COMPRESSED_IMAGE_SIZE), -7);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }

    #[test]
    fn proxies_record_sizes_only() {
        let (mut ctx, _) = Context::with_recording();
        let p = gl::GL_PROXY_TEXTURE_2D;
        unsafe { dispatch::glTexImage2D(&mut ctx, p, 0, gl::GL_RGB5 as i32, 64, 32, 0, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert_eq!((level_param(&mut ctx, p, 0, gl::GL_TEXTURE_WIDTH), level_param(&mut ctx, p, 0, gl::GL_TEXTURE_HEIGHT)), (64, 32));
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_INTERNAL_FORMAT) as u32, gl::GL_RGB5);
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_GREEN_SIZE), 8);
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_ALPHA_SIZE), 0);
        // Too large: every parameter becomes 0, without an error.
        unsafe { dispatch::glTexImage2D(&mut ctx, p, 0, gl::GL_RGBA as i32, 16384, 16384, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_WIDTH), 0);
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_RED_SIZE), 0);
        let p3 = gl::GL_PROXY_TEXTURE_3D;
        unsafe { dispatch::glTexImage3D(&mut ctx, p3, 1, gl::GL_ALPHA as i32, 1024, 1024, 2, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert_eq!((level_param(&mut ctx, p3, 1, gl::GL_TEXTURE_DEPTH), level_param(&mut ctx, p3, 1, gl::GL_TEXTURE_WIDTH)), (2, 1024));
        unsafe { dispatch::glTexImage3D(&mut ctx, p3, 1, gl::GL_ALPHA as i32, 2048, 2, 2, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert_eq!(level_param(&mut ctx, p3, 1, gl::GL_TEXTURE_WIDTH), 0);
        // Proxies do not touch the bound texture; unspecified levels read as zero.
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_WIDTH), 0);
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_INTERNAL_FORMAT), 1);
        // Proxy commands in display lists run at once.
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glTexImage2D(&mut ctx, p, 0, gl::GL_RGBA as i32, 8, 8, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null());
            dispatch::glEndList(&mut ctx);
        }
        assert_eq!(level_param(&mut ctx, p, 0, gl::GL_TEXTURE_WIDTH), 8);
    }

    #[test]
    fn generated_mipmaps_box_filter_the_base() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_GENERATE_MIPMAP, 1);
        let px: [u8; 16] = [0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120, 130, 140, 250];
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE as i32, 4, 4, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        let mut l1 = [0u8; 4];
        let mut l2 = [0u8; 1];
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        unsafe {
            ctx.glGetTexImage(gl::GL_TEXTURE_2D, 1, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, l1.as_mut_ptr().cast());
            ctx.glGetTexImage(gl::GL_TEXTURE_2D, 2, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, l2.as_mut_ptr().cast());
        }
        // (0 + 10 + 40 + 50) / 4 = 25, (20 + 30 + 60 + 70) / 4 = 45, (80 + 90 + 120 + 130) / 4 = 105,
        // (100 + 110 + 140 + 250) / 4 = 150; then (25 + 45 + 105 + 150) / 4 = 81.25 → 81.
        assert_eq!(l1, [25, 45, 105, 150]);
        assert_eq!(l2, [81]);
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_2D, 2, gl::GL_TEXTURE_WIDTH), 1);
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_2D, 3, gl::GL_TEXTURE_WIDTH), 0);
    }

    #[test]
    fn copy_tex_image_records_framebuffer_copy() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 9);
        ctx.glCopyTexImage2D(gl::GL_TEXTURE_2D, 0, gl::GL_RGB, 10, 20, 16, 8, 0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        for bad in [3, gl::GL_COLOR_INDEX8_EXT, gl::GL_STENCIL_INDEX8] {
            ctx.glCopyTexImage2D(gl::GL_TEXTURE_2D, 0, bad, 10, 20, 16, 8, 0);
            assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM, "{bad:#x}");
        }
        ctx.glCopyTexImage2D(gl::GL_PROXY_TEXTURE_2D, 0, gl::GL_RGB, 0, 0, 16, 8, 0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glCopyTexSubImage2D(gl::GL_TEXTURE_2D, 0, 8, 4, 1, 2, 8, 4);
        ctx.glCopyTexSubImage2D(gl::GL_TEXTURE_2D, 0, 9, 4, 1, 2, 8, 4);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        assert_eq!(level_param(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_WIDTH), 16);
        let version = ctx.with_bound_texture(super::Target::D2, |o| o.version);
        let ops: Vec<_> = ctx.frame.pixels.iter().map(|p| p.kind.clone()).collect();
        assert_eq!(ops.len(), 2);
        let PixelKind::TextureCopy { texture, offset, src, version: v, .. } = &ops[1] else { panic!("not a copy") };
        assert_eq!((*texture, *offset, *src, *v), (9, [8, 4, 0], [1, 2, 8, 4], version));
    }
}

#[cfg(test)]
mod more_tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn display_lists_keep_the_image_unpacked_at_compile_time() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_1D, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_PIXELS, 1);
        let mut px = vec![1u8, 2, 3];
        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glTexImage1D(&mut ctx, gl::GL_TEXTURE_1D, 0, gl::GL_ALPHA as i32, 2, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast());
            dispatch::glEndList(&mut ctx);
        }
        px[1] = 99;
        drop(px);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_PIXELS, 0);
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        let mut out = [0u8; 2];
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_1D, 0, gl::GL_ALPHA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(out, [2, 3]);
        assert_eq!(ctx.pixels.store.unpack.skip_pixels, 0);
    }

    #[test]
    fn three_d_images_use_image_height_and_skip_images() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_3D, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_IMAGE_HEIGHT, 3);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_IMAGES, 1);
        // Images of 2×3 bytes; the texture is 2×2×2 from image 1 on, rows 0–1 of each.
        let src: Vec<u8> = (0..18).collect();
        unsafe { dispatch::glTexImage3D(&mut ctx, gl::GL_TEXTURE_3D, 0, gl::GL_LUMINANCE as i32, 2, 2, 2, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, src.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let mut out = [0u8; 8];
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_3D, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(out, [6, 7, 8, 9, 12, 13, 14, 15]);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_IMAGES, 0);
        ctx.glPixelStorei(gl::GL_UNPACK_IMAGE_HEIGHT, 0);
        let one = [200u8];
        unsafe { dispatch::glTexSubImage3D(&mut ctx, gl::GL_TEXTURE_3D, 0, 1, 0, 1, 1, 1, 1, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, one.as_ptr().cast()) };
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_3D, 0, gl::GL_LUMINANCE, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(out, [6, 7, 8, 9, 12, 200, 14, 15]);
    }

    #[test]
    fn rgba_texels_read_as_luminance_give_red() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        let texel = [128u8, 64, 32, 255];
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 1, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texel.as_ptr().cast()) };
        let mut out = [0u8; 4];
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_LUMINANCE_ALPHA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
        assert_eq!(out[..2], [128, 255]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn bordered_textures_are_complete_and_sampled() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_LINEAR as i32);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 4, 3, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        ctx.glEnable(gl::GL_TEXTURE_2D);
        let r = ctx.texture_snapshot()[0].clone().expect("complete");
        let image = r.content.faces[0][0].clone().unwrap();
        assert_eq!((image.width, image.height, image.border, image.texels.len()), (4, 3, 1, 48));
    }

    #[test]
    fn non_power_of_two_mipmaps_halve_with_the_floor() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        let sizes: [(i32, i32); 6] = [(60, 13), (30, 6), (15, 3), (7, 1), (3, 1), (1, 1)];
        for (level, (w, h)) in sizes.into_iter().enumerate() {
            assert!(ctx.texture_snapshot()[0].is_none(), "incomplete before level {level}");
            unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, level as i32, gl::GL_RGBA as i32, w, h, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
            assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        }
        let r = ctx.texture_snapshot()[0].clone().expect("complete with floor-halved levels");
        let image = r.content.faces[0][0].clone().unwrap();
        assert_eq!((image.width, image.height), (60, 13));
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 2);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 5, 3, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 1, gl::GL_RGBA as i32, 3, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        ctx.glTexParameteri(gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAX_LEVEL, 1);
        assert!(ctx.texture_snapshot()[0].is_none(), "level 1 of 5×3 must be 2×1");
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 1, gl::GL_RGBA as i32, 2, 1, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, std::ptr::null()) };
        assert!(ctx.texture_snapshot()[0].is_some(), "5×3 and 2×1 with max level 1");
    }
}

//! Compressed texture images (ARB_texture_compression with EXT_texture_compression_s3tc's
//! DXT1/3/5 formats): `glCompressedTexImage{1,2,3}D`, `glCompressedTexSubImage{1,2,3}D`,
//! `glGetCompressedTexImage`. The blocks are kept for read-back and decoded to canonical
//! texels. S3TC formats exist for 2D images only, so the 1D and 3D commands accept no format.

// GL commands keep the parameter lists of their C functions.
#![allow(clippy::too_many_arguments)]

use std::ffi::c_void;
use std::sync::Arc;

use super::super::Context;
use super::super::gl::{self, GLenum, GLint, GLsizei};
use super::formats::{self, Base, S3tc};
use super::image::{SizeCheck, check_level, check_size, image_target};
use super::objects::Level;
use super::s3tc;
use crate::frame::texture::{Precision, TexImage, TexelFormat};

/// Bytes of a compressed image of `size` (width, height, depth).
pub fn image_size(format: S3tc, size: [usize; 3]) -> usize {
    size[0].div_ceil(4) * size[1].div_ceil(4) * size[2] * format.block_bytes()
}

/// Compresses a level whose internal format is S3TC from its texels, and replaces the texels
/// with the decoded blocks (2D levels with texels only; others are left as they are).
pub fn recompress(level: &mut Level) {
    let Some(format) = S3tc::of(level.internal_format) else { return };
    let [w, h, d] = level.size;
    if d != 1 || level.image.texels.len() != w * h * 4 {
        return;
    }
    let blocks = s3tc::encode(format, w, h, &level.image.texels);
    if let Some(texels) = s3tc::decode(format, w, h, &blocks) {
        Arc::make_mut(&mut level.image).texels = texels;
    }
    level.compressed = Some(blocks.into());
}

/// Like [`recompress`] after the texels of the region `offset`/`size` changed: the blocks the
/// region does not touch keep their bytes from `old`, the level's blocks before the change
/// (encoding decoded texels again is lossy, so a `glTexSubImage` must not alter the rest of
/// the image).
pub fn recompress_region(level: &mut Level, old: Option<Arc<[u8]>>, offset: [usize; 3], size: [usize; 3]) {
    let Some(format) = S3tc::of(level.internal_format) else { return };
    if size.contains(&0) && old.is_some() {
        // Nothing was written.
        level.compressed = old;
        return;
    }
    recompress(level);
    let (Some(old), Some(new)) = (old, level.compressed.clone()) else { return };
    let [w, h, _] = level.size;
    if old.len() != new.len() {
        return;
    }
    let (columns, bytes) = (w.div_ceil(4), format.block_bytes());
    let mut merged = old.to_vec();
    for by in offset[1] / 4..(offset[1] + size[1]).div_ceil(4) {
        for bx in offset[0] / 4..(offset[0] + size[0]).div_ceil(4) {
            let at = (by * columns + bx) * bytes;
            if let (Some(dst), Some(src)) = (merged.get_mut(at..at + bytes), new.get(at..at + bytes)) {
                dst.copy_from_slice(src);
            }
        }
    }
    if let Some(texels) = s3tc::decode(format, w, h, &merged) {
        Arc::make_mut(&mut level.image).texels = texels;
        level.compressed = Some(merged.into());
    }
}

/// The S3TC format of a compressed command, which needs a 2D image target.
fn s3tc_for(dims: usize, internal: GLenum) -> Option<S3tc> {
    S3tc::of(internal).filter(|_| dims == 2)
}

impl Context {
    /// `glCompressedTexImage*`: `GL_INVALID_ENUM` for a bad target or a format that is not a
    /// compressed format of that dimensionality, `GL_INVALID_VALUE` for bad level or sizes or
    /// an `imageSize` that does not match, `GL_INVALID_OPERATION` for a non-zero border.
    unsafe fn compressed_tex_image(&mut self, dims: usize, target: GLenum, level: GLint, internalformat: GLenum, size: [GLsizei; 3], border: GLint, image_size_: GLsizei, data: *const c_void, command: &'static str) {
        let Some(dest) = image_target(dims, target) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let Some(format) = s3tc_for(dims, internalformat) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        if border != 0 {
            return self.set_error_in(gl::GL_INVALID_OPERATION, command);
        }
        let checked = check_level(dest.target, level).and_then(|l| Ok((l, check_size(dest.target, l, size, border)?)));
        let (level, fit) = match checked {
            Ok(v) => v,
            Err(e) => return self.set_error_in(e, command),
        };
        let size = match fit {
            SizeCheck::Fits(s) => s,
            SizeCheck::TooLarge | SizeCheck::OutOfMemory if dest.proxy => return self.store_level(dest, level, None),
            SizeCheck::TooLarge => return self.set_error_in(gl::GL_INVALID_VALUE, command),
            SizeCheck::OutOfMemory => return self.set_error_in(gl::GL_OUT_OF_MEMORY, command),
        };
        let expected = image_size(format, size);
        if usize::try_from(image_size_).ok() != Some(expected) {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let base = Base::Texel(if format == S3tc::Dxt1Rgb { TexelFormat::Rgb } else { TexelFormat::Rgba });
        let mut lvl = Level { image: Arc::default(), size, border: 0, internal_format: internalformat, base, compressed: None, indices: None, stencil: None };
        if !dest.proxy {
            let Ok(bytes) = (unsafe { self.unpack_bytes(data, expected, 1, command) }) else { return };
            let Some(bytes) = bytes else { return self.null_pointer(command) };
            let texels = s3tc::decode(format, size[0], size[1], &bytes).unwrap_or_default();
            let precision = formats::internal_format(internalformat).map_or(Precision::Unorm8, |i| i.storage.precision());
            lvl.image = Arc::new(TexImage { width: size[0] as u32, height: size[1] as u32, depth: 1, border: 0, texels, precision, ..TexImage::default() });
            lvl.compressed = Some(bytes.into_owned().into());
        }
        self.store_level(dest, level, Some(lvl));
    }

    /// `glCompressedTexImage1D` (no 1D compressed format exists: `GL_INVALID_ENUM` after the
    /// target check).
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexImage1D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_image(1, target, level, internalformat, [width, 1, 1], border, imageSize, data, "glCompressedTexImage1D") }
    }

    /// `glCompressedTexImage2D` with a DXT1/3/5 format.
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexImage2D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_image(2, target, level, internalformat, [width, height, 1], border, imageSize, data, "glCompressedTexImage2D") }
    }

    /// `glCompressedTexImage3D` (no 3D compressed format exists).
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexImage3D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_image(3, target, level, internalformat, [width, height, depth], border, imageSize, data, "glCompressedTexImage3D") }
    }

    /// `glCompressedTexSubImage*`: the region checks of `glTexSubImage`; `GL_INVALID_ENUM` for
    /// a format that is not S3TC, `GL_INVALID_OPERATION` when it differs from the level's or
    /// the region is not made of whole blocks, `GL_INVALID_VALUE` for a wrong `imageSize`.
    unsafe fn compressed_tex_sub_image(&mut self, dims: usize, target: GLenum, level: GLint, offset: [GLint; 3], size: [GLsizei; 3], format: GLenum, image_size_: GLsizei, data: *const c_void, command: &'static str) {
        let Some((dest, level, off, sz, _)) = self.check_sub_image(dims, target, level, offset, size, command) else { return };
        let Some(fmt) = s3tc_for(dims, format) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let Some(lvl) = self.with_dest(dest, |obj, _| obj.level(dest.face, level).cloned()) else { return };
        let whole = |i: usize| off[i] % 4 == 0 && (sz[i] % 4 == 0 || off[i] + sz[i] == lvl.size[i]);
        if lvl.internal_format != format || lvl.compressed.is_none() || !whole(0) || !whole(1) {
            return self.set_error_in(gl::GL_INVALID_OPERATION, command);
        }
        let expected = image_size(fmt, sz);
        if usize::try_from(image_size_).ok() != Some(expected) {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let Ok(bytes) = (unsafe { self.unpack_bytes(data, expected, 1, command) }) else { return };
        let Some(bytes) = bytes else { return self.null_pointer(command) };
        let Some(texels) = s3tc::decode(fmt, sz[0], sz[1], &bytes) else { return };
        let mut blocks = lvl.compressed.as_deref().map(<[u8]>::to_vec).unwrap_or_default();
        let (level_bw, bb) = (lvl.size[0].div_ceil(4), fmt.block_bytes());
        for by in 0..sz[1].div_ceil(4) {
            for bx in 0..sz[0].div_ceil(4) {
                let dst = ((off[1] / 4 + by) * level_bw + off[0] / 4 + bx) * bb;
                let src = (by * sz[0].div_ceil(4) + bx) * bb;
                if let (Some(d), Some(s)) = (blocks.get_mut(dst..dst + bb), bytes.get(src..src + bb)) {
                    d.copy_from_slice(s);
                }
            }
        }
        self.with_dest(dest, |obj, _| {
            if let Some(l) = obj.level_slot(dest.face, level).as_mut() {
                let image = Arc::make_mut(&mut l.image);
                for y in 0..sz[1] {
                    let d = ((off[1] + y) * l.size[0] + off[0]) * 4;
                    if let (Some(dst), Some(src)) = (image.texels.get_mut(d..d + sz[0] * 4), texels.get(y * sz[0] * 4..(y + 1) * sz[0] * 4)) {
                        dst.copy_from_slice(src);
                    }
                }
                l.compressed = Some(blocks.into());
            }
            obj.touch();
        });
    }

    /// `glCompressedTexSubImage1D`.
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexSubImage1D(&mut self, target: GLenum, level: GLint, xoffset: GLint, width: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_sub_image(1, target, level, [xoffset, 0, 0], [width, 1, 1], format, imageSize, data, "glCompressedTexSubImage1D") }
    }

    /// `glCompressedTexSubImage2D`.
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexSubImage2D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_sub_image(2, target, level, [xoffset, yoffset, 0], [width, height, 1], format, imageSize, data, "glCompressedTexSubImage2D") }
    }

    /// `glCompressedTexSubImage3D`.
    ///
    /// # Safety
    /// `data` must point to `imageSize` bytes.
    pub unsafe fn glCompressedTexSubImage3D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        unsafe { self.compressed_tex_sub_image(3, target, level, [xoffset, yoffset, zoffset], [width, height, depth], format, imageSize, data, "glCompressedTexSubImage3D") }
    }

    /// Records a compressed-image command with a copy of its `image_size_` bytes of data
    /// ([`Context::compile_unpack`]; proxies run at once).
    unsafe fn compile_compressed(&mut self, proxy: bool, image_size_: GLsizei, data: *const c_void, command: &'static str, run: impl Fn(&mut Context, *const c_void) + Send + Sync + 'static) {
        if proxy {
            return run(self, data);
        }
        let size = usize::try_from(image_size_).ok().filter(|&n| n as u64 <= super::super::pixels::store::MAX_CLIENT_IMAGE_BYTES);
        unsafe { self.compile_unpack(data, size.map(|n| (n, 1)), command, run) }
    }

    /// `glCompressedTexImage1D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexImage1D`].
    pub unsafe fn compile_glCompressedTexImage1D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        let proxy = image_target(1, target).is_some_and(|d| d.proxy);
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexImage1D(target, level, internalformat, width, border, imageSize, p) };
        unsafe { self.compile_compressed(proxy, imageSize, data, "glCompressedTexImage1D", run) }
    }

    /// `glCompressedTexImage2D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexImage2D`].
    pub unsafe fn compile_glCompressedTexImage2D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        let proxy = image_target(2, target).is_some_and(|d| d.proxy);
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexImage2D(target, level, internalformat, width, height, border, imageSize, p) };
        unsafe { self.compile_compressed(proxy, imageSize, data, "glCompressedTexImage2D", run) }
    }

    /// `glCompressedTexImage3D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexImage3D`].
    pub unsafe fn compile_glCompressedTexImage3D(&mut self, target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, imageSize: GLsizei, data: *const c_void) {
        let proxy = image_target(3, target).is_some_and(|d| d.proxy);
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexImage3D(target, level, internalformat, width, height, depth, border, imageSize, p) };
        unsafe { self.compile_compressed(proxy, imageSize, data, "glCompressedTexImage3D", run) }
    }

    /// `glCompressedTexSubImage1D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexSubImage1D`].
    pub unsafe fn compile_glCompressedTexSubImage1D(&mut self, target: GLenum, level: GLint, xoffset: GLint, width: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexSubImage1D(target, level, xoffset, width, format, imageSize, p) };
        unsafe { self.compile_compressed(false, imageSize, data, "glCompressedTexSubImage1D", run) }
    }

    /// `glCompressedTexSubImage2D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexSubImage2D`].
    pub unsafe fn compile_glCompressedTexSubImage2D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexSubImage2D(target, level, xoffset, yoffset, width, height, format, imageSize, p) };
        unsafe { self.compile_compressed(false, imageSize, data, "glCompressedTexSubImage2D", run) }
    }

    /// `glCompressedTexSubImage3D` in a display list.
    ///
    /// # Safety
    /// As [`Context::glCompressedTexSubImage3D`].
    pub unsafe fn compile_glCompressedTexSubImage3D(&mut self, target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, imageSize: GLsizei, data: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glCompressedTexSubImage3D(target, level, xoffset, yoffset, zoffset, width, height, depth, format, imageSize, p) };
        unsafe { self.compile_compressed(false, imageSize, data, "glCompressedTexSubImage3D", run) }
    }

    /// `glGetCompressedTexImage`: the level's blocks as given. `GL_INVALID_ENUM` for a bad or
    /// proxy target, `GL_INVALID_VALUE` for a bad level, `GL_INVALID_OPERATION` when the level
    /// is not compressed.
    ///
    /// # Safety
    /// `img` must have room for `GL_TEXTURE_COMPRESSED_IMAGE_SIZE` bytes.
    pub unsafe fn glGetCompressedTexImage(&mut self, target: GLenum, level: GLint, img: *mut c_void) {
        const CMD: &str = "glGetCompressedTexImage";
        let Some(dest) = super::image::any_image_target(target).filter(|d| !d.proxy) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let level = match check_level(dest.target, level) {
            Ok(l) => l,
            Err(e) => return self.set_error_in(e, CMD),
        };
        let Some(bytes) = self.with_dest(dest, |obj, _| obj.level(dest.face, level).and_then(|l| l.compressed.clone())) else {
            return self.set_error_in(gl::GL_INVALID_OPERATION, CMD);
        };
        unsafe { self.pack_bytes(img, bytes.len(), 1, CMD, |out| out.copy_from_slice(&bytes)) }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn compressed_upload_decodes_and_reads_back() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 3);
        let red_blue = [0x00u8, 0xf8, 0x1f, 0x00, 0b11_10_01_00, 0, 0, 0];
        let two: Vec<u8> = red_blue.iter().chain(red_blue.iter()).copied().collect();
        let f = gl::GL_COMPRESSED_RGB_S3TC_DXT1_EXT;
        unsafe { dispatch::glCompressedTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f, 8, 4, 0, 15, two.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        unsafe { dispatch::glCompressedTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f, 8, 4, 1, 16, two.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe { dispatch::glCompressedTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f, 8, 4, 0, 16, two.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let (mut compressed, mut size, mut internal) = (0, 0, 0);
        unsafe {
            ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_COMPRESSED, &mut compressed);
            ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &mut size);
            ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_INTERNAL_FORMAT, &mut internal);
        }
        assert_eq!((compressed, size, internal as u32), (1, 16, f));
        let mut px = [0u8; 8 * 4 * 4];
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
        assert_eq!(px[..16], [255, 0, 0, 255, 0, 0, 255, 255, 170, 0, 85, 255, 85, 0, 170, 255]);
        // Replace the second block with an all-index-1 (blue) block.
        let blue = [0x00u8, 0xf8, 0x1f, 0x00, 0x55, 0x55, 0x55, 0x55];
        unsafe { dispatch::glCompressedTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 2, 0, 4, 4, f, 8, blue.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
        unsafe { dispatch::glCompressedTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 4, 0, 4, 4, f, 8, blue.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let mut back = [0u8; 16];
        unsafe { ctx.glGetCompressedTexImage(gl::GL_TEXTURE_2D, 0, back.as_mut_ptr().cast()) };
        assert_eq!(back[..8], red_blue);
        assert_eq!(back[8..], blue);
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
        assert_eq!(px[4 * 3..5 * 3], [0, 0, 255]);
        unsafe { dispatch::glCompressedTexImage1D(&mut ctx, gl::GL_TEXTURE_1D, 0, f, 4, 0, 8, blue.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let mut n = 0;
        unsafe { ctx.glGetIntegerv(gl::GL_NUM_COMPRESSED_TEXTURE_FORMATS, &mut n) };
        assert_eq!(n, 4);
    }

    #[test]
    fn uncompressed_images_with_s3tc_formats_are_compressed() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        // 4×4: left half red, right half blue (exact in 565).
        let px: Vec<u8> = (0..16).flat_map(|i| if i % 4 < 2 { [255u8, 0, 0] } else { [0, 0, 255] }).collect();
        let f = gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f as i32, 4, 4, 0, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let (mut compressed, mut size) = (0, 0);
        unsafe {
            ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_COMPRESSED, &mut compressed);
            ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &mut size);
        }
        assert_eq!((compressed, size), (1, 16));
        let mut blocks = [0u8; 16];
        unsafe { ctx.glGetCompressedTexImage(gl::GL_TEXTURE_2D, 0, blocks.as_mut_ptr().cast()) };
        let decoded = super::s3tc::decode(super::S3tc::Dxt5, 4, 4, &blocks).unwrap();
        let mut back = [0u8; 48];
        ctx.glPixelStorei(gl::GL_PACK_ALIGNMENT, 1);
        unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, back.as_mut_ptr().cast()) };
        assert_eq!(back.to_vec(), px);
        assert_eq!(decoded.chunks(4).flat_map(|c| c[..3].to_vec()).collect::<Vec<_>>(), px);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f as i32, 6, 6, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, px.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION);
    }

    /// piglit's `texsubimage` case: a gradient whose blocks change when their decoded texels
    /// are encoded again; a sub-image must leave the blocks outside it as they were.
    #[test]
    fn tex_sub_image_leaves_untouched_blocks_as_they_were() {
        let (w, h) = (128usize, 64usize);
        let orig: Vec<u8> = (0..h).flat_map(|j| (0..w).flat_map(move |k| [(j * 4) as u8, (k * 2) as u8, 0, 255])).collect();
        let upd: Vec<u8> = orig.chunks(4).flat_map(|p| [p[1], p[2], p[0], p[3]]).collect();
        let f = gl::GL_COMPRESSED_RGBA_S3TC_DXT5_EXT;
        let get = |ctx: &mut Context| {
            let mut back = vec![0u8; w * h * 4];
            unsafe { ctx.glGetTexImage(gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, back.as_mut_ptr().cast()) };
            back
        };
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f as i32, w as i32, h as i32, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, orig.as_ptr().cast()) };
        let reference = get(&mut ctx);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_PIXELS, 0);
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_ROWS, 8);
        unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 8, 72, 44, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, upd.as_ptr().cast()) };
        let test = get(&mut ctx);
        for (row, same) in [(0, true), (7, true), (8, false), (51, false), (52, true), (58, true)] {
            let at = row * w * 4;
            assert_eq!(test[at..at + 72 * 4] == reference[at..at + 72 * 4], same, "row {row}");
        }
        assert_eq!(test[(58 * w + 2) * 4..][..4], reference[(58 * w + 2) * 4..][..4], "the texel piglit probes");
        // An empty region writes nothing and re-encodes nothing.
        ctx.glPixelStorei(gl::GL_UNPACK_SKIP_ROWS, 0);
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, f as i32, w as i32, h as i32, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, orig.as_ptr().cast()) };
        unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 64, 8, 0, 52, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, upd.as_ptr().cast()) };
        assert_eq!(get(&mut ctx), reference);
    }
}

//! Texture images that need no conversion: tightly packed `GL_UNSIGNED_BYTE` RGB or RGBA
//! pixels, pixel transfer at its initial state, stored in an RGB or RGBA texture of 8-bit
//! (or sRGB 8-bit) storage. Unpacking
//! (OpenGL 1.5 section 3.6.4: c / 255, scale 1, bias 0, no colour map) then storing as 8-bit
//! texels (round(c · 255)) gives back the client's bytes, so they are copied (alpha 255 for
//! RGB) instead of going through the general path's conversion to floating point, which is
//! what large or frequent uploads (piglit's `streaming-texture-leak`) spend their time on.

use std::ffi::c_void;

use super::super::Context;
use super::super::gl;
use super::super::pixels::codec::{Format, Type};
use super::formats::{Base, Internal};
use crate::frame::texture::{Precision, TexelFormat};

impl Context {
    /// The canonical RGBA8 texels of a `w` × `h` × `d` image at `pixels` (client memory or the
    /// unpack buffer, [`Context::unpack_bytes`]), or `Ok(None)` when the image needs the
    /// general path (other formats or types, unpack modes that skip or pad, pixel transfer in
    /// use, a null client pointer). `Err(())` after the unpack buffer's error.
    ///
    /// # Safety
    /// A non-null `pixels` must point to the memory the unpack modes describe.
    pub(crate) unsafe fn direct_texels(
        &mut self,
        (format, ty): (Format, Type),
        internal: Internal,
        [w, h, d]: [usize; 3],
        pixels: *const c_void,
        command: &'static str,
    ) -> Result<Option<Vec<u8>>, ()> {
        let n = match format.gl {
            gl::GL_RGBA => 4,
            gl::GL_RGB => 3,
            _ => return Ok(None),
        };
        let t = &self.pixels.transfer;
        let identity = !t.map_color && t.scale == [1.0; 4] && t.bias == [0.0; 4];
        let base = internal.base;
        let stored = matches!(base, Base::Texel(TexelFormat::Rgba | TexelFormat::Rgb)) && matches!(internal.storage.precision(), Precision::Unorm8 | Precision::Srgb8);
        if ty != Type::U8 || !identity || !stored {
            return Ok(None);
        }
        let Some(layout) = ty.layout(format, &self.pixels.store.unpack, w, h, d) else { return Ok(None) };
        let Some(len) = w.checked_mul(h).and_then(|v| v.checked_mul(d)).and_then(|v| v.checked_mul(n)) else { return Ok(None) };
        let tight = layout.start == 0 && layout.row_stride == w * n && layout.image_stride == w * n * h && layout.span == len;
        if !tight {
            return Ok(None);
        }
        let Some(bytes) = (unsafe { self.unpack_bytes(pixels, len, ty.datum_size(), command) })? else { return Ok(None) };
        Ok(Some(if n == 4 && base == Base::Texel(TexelFormat::Rgba) {
            bytes.into_owned()
        } else {
            bytes.chunks_exact(n).flat_map(|p| [p[0], p[1], p[2], 255]).collect()
        }))
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::dispatch;
    use crate::translate::gl;

    /// Uploads a 2×2 image with `format` into `internal` and reads it back as RGBA bytes.
    fn round_trip(ctx: &mut Context, internal: gl::GLenum, format: gl::GLenum, pixels: &[u8]) -> Vec<u8> {
        let mut out = vec![0u8; 16];
        unsafe {
            dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, internal as i32, 2, 2, 0, format, gl::GL_UNSIGNED_BYTE, pixels.as_ptr().cast());
            dispatch::glGetTexImage(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast());
        }
        out
    }

    #[test]
    fn direct_uploads_match_the_general_path() {
        let (mut ctx, _) = Context::with_recording();
        let rgba: Vec<u8> = (0..16).map(|i| i * 16 + 3).collect();
        let rgb: Vec<u8> = (0..12).map(|i| i * 20 + 1).collect();
        unsafe { dispatch::glPixelStorei(&mut ctx, gl::GL_UNPACK_ALIGNMENT, 1) };
        let direct = [
            round_trip(&mut ctx, gl::GL_RGBA, gl::GL_RGBA, &rgba),
            round_trip(&mut ctx, gl::GL_RGB, gl::GL_RGBA, &rgba),
            round_trip(&mut ctx, gl::GL_RGBA, gl::GL_RGB, &rgb),
        ];
        assert_eq!(direct[0], rgba, "RGBA bytes are kept");
        assert_eq!(&direct[1][..8], &[3, 19, 35, 255, 67, 83, 99, 255], "an RGB texture drops alpha");
        assert_eq!(&direct[2][..8], &[1, 21, 41, 255, 61, 81, 101, 255], "RGB pixels get alpha 255");
        // A red scale of 1.0 written explicitly keeps the direct path; 0.5 takes the general one.
        unsafe { dispatch::glPixelTransferf(&mut ctx, gl::GL_RED_SCALE, 0.5) };
        let scaled = round_trip(&mut ctx, gl::GL_RGBA, gl::GL_RGBA, &rgba);
        assert_eq!(&scaled[..4], &[1, 19, 35, 51], "pixel transfer still applies");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}

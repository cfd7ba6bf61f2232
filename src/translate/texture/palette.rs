//! Palettes of colour-index textures (EXT_paletted_texture, EXT_shared_texture_palette):
//! `glColorTableEXT`, `glColorSubTableEXT`, `glGetColorTableEXT`,
//! `glGetColorTableParameter{if}vEXT`. A palette change re-resolves the texels of the
//! texture's paletted levels, which changes its content version.

use std::ffi::c_void;
use std::sync::Arc;

use super::super::Context;
use super::super::convert::write_slice;
use super::super::get::Value;
use super::super::gl::{self, GLenum, GLfloat, GLint, GLsizei};
use super::super::pixels::Unpacked;
use super::super::pixels::codec::{Kind, Luminance};
use super::formats::{self, Base};
use super::image::resolve_indices;
use super::objects::{Target, TextureObject};
use crate::frame::texture::TexelFormat;

/// Largest palette (`GL_MAX_PIXEL_MAP_TABLE`-sized, enough for 8-bit indices).
pub const MAX_PALETTE: usize = 256;

/// A palette: canonical texels and the internal format they were given with.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Palette {
    /// Entries as canonical RGBA8 texels.
    pub entries: Vec<[u8; 4]>,
    /// `GL_COLOR_TABLE_FORMAT`.
    pub internal_format: GLenum,
    /// Base format of the entries.
    pub base: Option<TexelFormat>,
}

impl Palette {
    /// The texel of index `i` (indices wrap at the palette size; black without a palette).
    pub fn texel(&self, i: u16) -> [u8; 4] {
        if self.entries.is_empty() {
            return [0, 0, 0, 255];
        }
        self.entries[usize::from(i) % self.entries.len()]
    }
}

/// Where a palette command goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum PaletteTarget {
    Texture(Target),
    Proxy(Target),
    Shared,
}

fn palette_target(target: GLenum) -> Option<PaletteTarget> {
    Some(match target {
        gl::GL_SHARED_TEXTURE_PALETTE_EXT => PaletteTarget::Shared,
        gl::GL_PROXY_TEXTURE_1D => PaletteTarget::Proxy(Target::D1),
        gl::GL_PROXY_TEXTURE_2D => PaletteTarget::Proxy(Target::D2),
        gl::GL_PROXY_TEXTURE_3D => PaletteTarget::Proxy(Target::D3),
        gl::GL_PROXY_TEXTURE_CUBE_MAP => PaletteTarget::Proxy(Target::Cube),
        t => PaletteTarget::Texture(Target::from_gl(t)?),
    })
}

/// Re-resolves every paletted level of `obj` with its palette (or `fallback` when it has
/// none) and bumps its version.
pub fn reresolve(obj: &mut TextureObject, fallback: &Palette) {
    let palette = if obj.palette.entries.is_empty() { fallback.clone() } else { obj.palette.clone() };
    for level in obj.faces.iter_mut().flatten().flatten() {
        if let Some(indices) = &level.indices {
            Arc::make_mut(&mut level.image).texels = resolve_indices(indices, &palette);
        }
    }
    obj.touch();
}

impl Context {
    /// Runs `f` on the palette of `target`, re-resolving the texture afterwards when it
    /// changed.
    fn with_palette<R>(&mut self, target: PaletteTarget, f: impl FnOnce(&mut Palette) -> R) -> R {
        match target {
            PaletteTarget::Shared => {
                let before = self.texture.shared_palette.clone();
                let r = f(&mut self.texture.shared_palette);
                if self.texture.shared_palette != before {
                    self.texture.shared_palette_version = super::objects::next_version();
                }
                r
            }
            PaletteTarget::Proxy(t) => f(&mut self.texture.proxies[t.index()].palette),
            PaletteTarget::Texture(t) => {
                let shared = self.texture.shared_palette.clone();
                self.with_bound_texture(t, |obj| {
                    let before = obj.palette.clone();
                    let r = f(&mut obj.palette);
                    if obj.palette != before {
                        reresolve(obj, &shared);
                    }
                    r
                })
            }
        }
    }

    /// Unpacks palette entries as canonical texels of `base`.
    unsafe fn palette_entries(&mut self, base: TexelFormat, count: usize, format: GLenum, type_: GLenum, data: *const c_void, command: &'static str) -> Option<Vec<[u8; 4]>> {
        let ft = self.parse_pixel_format(format, type_, command)?;
        if ft.0.kind != Kind::Color {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
            return None;
        }
        match unsafe { self.unpack_client(ft, [count, 1, 1], data, false, true, command) } {
            Ok(Some(Unpacked::Rgba(c))) => Some(c.iter().map(|&c| formats::texel(base, c)).collect()),
            Ok(_) => {
                self.null_pointer(command);
                None
            }
            Err(()) => None,
        }
    }

    /// `glColorTableEXT`: `GL_INVALID_ENUM` for a bad target, internal format, format or
    /// type; `GL_INVALID_VALUE` for a width that is not a power of two or is larger than 256
    /// (a proxy then gets an empty palette instead).
    ///
    /// # Safety
    /// A non-null `table` must point to `width` entries as the unpack modes describe.
    pub unsafe fn glColorTableEXT(&mut self, target: GLenum, internalFormat: GLenum, width: GLsizei, format: GLenum, type_: GLenum, table: *const c_void) {
        const CMD: &str = "glColorTableEXT";
        let Some(pt) = palette_target(target) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let base = match formats::internal_format(internalFormat).map(|i| i.base) {
            Some(Base::Texel(b)) if b != TexelFormat::Depth => b,
            _ => return self.set_error_in(gl::GL_INVALID_ENUM, CMD),
        };
        let Some(count) = usize::try_from(width).ok().filter(|w| w.is_power_of_two()) else { return self.set_error_in(gl::GL_INVALID_VALUE, CMD) };
        if count > MAX_PALETTE {
            if matches!(pt, PaletteTarget::Proxy(_)) {
                return self.with_palette(pt, |p| *p = Palette::default());
            }
            return self.set_error_in(gl::GL_INVALID_VALUE, CMD);
        }
        let entries = if matches!(pt, PaletteTarget::Proxy(_)) {
            vec![[0; 4]; count]
        } else {
            match unsafe { self.palette_entries(base, count, format, type_, table, CMD) } {
                Some(e) => e,
                None => return,
            }
        };
        self.with_palette(pt, |p| *p = Palette { entries, internal_format: internalFormat, base: Some(base) });
    }

    /// `glColorSubTableEXT`: replaces `count` entries from `start`; `GL_INVALID_VALUE` when
    /// they do not fit the palette.
    ///
    /// # Safety
    /// A non-null `data` must point to `count` entries as the unpack modes describe.
    pub unsafe fn glColorSubTableEXT(&mut self, target: GLenum, start: GLsizei, count: GLsizei, format: GLenum, type_: GLenum, data: *const c_void) {
        const CMD: &str = "glColorSubTableEXT";
        let Some(pt) = palette_target(target).filter(|t| !matches!(t, PaletteTarget::Proxy(_))) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let (len, base) = self.with_palette(pt, |p| (p.entries.len(), p.base));
        let (Ok(start), Ok(n)) = (usize::try_from(start), usize::try_from(count)) else { return self.set_error_in(gl::GL_INVALID_VALUE, CMD) };
        if start + n > len {
            return self.set_error_in(gl::GL_INVALID_VALUE, CMD);
        }
        let Some(entries) = (unsafe { self.palette_entries(base.unwrap_or(TexelFormat::Rgba), n, format, type_, data, CMD) }) else { return };
        self.with_palette(pt, |p| p.entries[start..start + n].copy_from_slice(&entries));
    }

    /// `glColorTableEXT` in a display list.
    ///
    /// # Safety
    /// As [`Context::glColorTableEXT`].
    pub unsafe fn compile_glColorTableEXT(&mut self, target: GLenum, internalFormat: GLenum, width: GLsizei, format: GLenum, type_: GLenum, table: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glColorTableEXT(target, internalFormat, width, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [width, 1, 1], table, "glColorTableEXT", run) }
    }

    /// `glColorSubTableEXT` in a display list.
    ///
    /// # Safety
    /// As [`Context::glColorSubTableEXT`].
    pub unsafe fn compile_glColorSubTableEXT(&mut self, target: GLenum, start: GLsizei, count: GLsizei, format: GLenum, type_: GLenum, data: *const c_void) {
        let run = move |ctx: &mut Context, p| unsafe { ctx.glColorSubTableEXT(target, start, count, format, type_, p) };
        unsafe { self.compile_image_command(format, type_, [count, 1, 1], data, "glColorSubTableEXT", run) }
    }

    /// `glGetColorTableEXT`: the entries as RGBA (table 6.1) packed with the pack modes.
    ///
    /// # Safety
    /// A non-null `data` must have room for the palette as the pack modes describe.
    pub unsafe fn glGetColorTableEXT(&mut self, target: GLenum, format: GLenum, type_: GLenum, data: *mut c_void) {
        const CMD: &str = "glGetColorTableEXT";
        let Some(pt) = palette_target(target).filter(|t| !matches!(t, PaletteTarget::Proxy(_))) else { return self.set_error_in(gl::GL_INVALID_ENUM, CMD) };
        let Some((f, t)) = self.parse_pixel_format(format, type_, CMD) else { return };
        if f.kind != Kind::Color {
            return self.set_error_in(gl::GL_INVALID_ENUM, CMD);
        }
        let palette = self.with_palette(pt, |p| p.clone());
        let base = palette.base.unwrap_or(TexelFormat::Rgba);
        let rgba: Vec<[f32; 4]> = palette.entries.iter().map(|&e| formats::texel_to_rgba(base, e.map(|v| f32::from(v) / 255.0))).collect();
        let values = self.transfer_for_pack(f, &rgba, Luminance::Red, true);
        unsafe { self.pack_client((f, t), [rgba.len(), 1, 1], data, &values, CMD) }
    }

    /// A palette parameter (`GL_COLOR_TABLE_FORMAT`, `_WIDTH`, `_*_SIZE`).
    fn color_table_parameter(&mut self, target: GLenum, pname: GLenum) -> Option<Value> {
        let palette = self.with_palette(palette_target(target)?, |p| p.clone());
        let base = Base::Texel(palette.base.unwrap_or(TexelFormat::Rgba));
        let bits = |tex_pname| formats::component_bits(base, palette.internal_format, tex_pname).map(|b| if palette.entries.is_empty() { 0 } else { b });
        Some(Value::int(match pname {
            gl::GL_COLOR_TABLE_FORMAT => i64::from(if palette.internal_format == 0 { gl::GL_RGBA } else { palette.internal_format }),
            gl::GL_COLOR_TABLE_WIDTH => palette.entries.len() as i64,
            gl::GL_COLOR_TABLE_RED_SIZE => bits(gl::GL_TEXTURE_RED_SIZE)?,
            gl::GL_COLOR_TABLE_GREEN_SIZE => bits(gl::GL_TEXTURE_GREEN_SIZE)?,
            gl::GL_COLOR_TABLE_BLUE_SIZE => bits(gl::GL_TEXTURE_BLUE_SIZE)?,
            gl::GL_COLOR_TABLE_ALPHA_SIZE => bits(gl::GL_TEXTURE_ALPHA_SIZE)?,
            gl::GL_COLOR_TABLE_LUMINANCE_SIZE => bits(gl::GL_TEXTURE_LUMINANCE_SIZE)?,
            gl::GL_COLOR_TABLE_INTENSITY_SIZE => bits(gl::GL_TEXTURE_INTENSITY_SIZE)?,
            _ => return None,
        }))
    }

    /// `glGetColorTableParameterivEXT`: `GL_INVALID_ENUM` for a bad target or name.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetColorTableParameterivEXT(&mut self, target: GLenum, pname: GLenum, params: *mut GLint) {
        match self.color_table_parameter(target, pname) {
            Some(v) => unsafe { write_slice(params, &v.to_ints()) },
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glGetColorTableParameterivEXT"),
        }
    }

    /// `glGetColorTableParameterfvEXT`.
    ///
    /// # Safety
    /// `params` must have room for one value.
    pub unsafe fn glGetColorTableParameterfvEXT(&mut self, target: GLenum, pname: GLenum, params: *mut GLfloat) {
        match self.color_table_parameter(target, pname) {
            Some(v) => unsafe { write_slice(params, &v.to_doubles().iter().map(|&x| x as f32).collect::<Vec<_>>()) },
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glGetColorTableParameterfvEXT"),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::{Context, dispatch, gl};

    #[test]
    fn paletted_texture_resolves_and_follows_palette_changes() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glBindTexture(gl::GL_TEXTURE_2D, 1);
        ctx.glPixelStorei(gl::GL_UNPACK_ALIGNMENT, 1);
        let palette: Vec<u8> = (0..256u32).flat_map(|i| [i as u8, 0, 255 - i as u8]).collect();
        unsafe {
            dispatch::glColorTableEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_RGB, 256, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, palette.as_ptr().cast());
            let idx = [0u8, 1, 2, 255];
            dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_COLOR_INDEX8_EXT as i32, 2, 2, 0, gl::GL_COLOR_INDEX, gl::GL_UNSIGNED_BYTE, idx.as_ptr().cast());
        }
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        let (texels, v1) = ctx.with_bound_texture(super::Target::D2, |o| (o.level(0, 0).unwrap().image.texels.clone(), o.version));
        assert_eq!(texels[12..16], [255, 0, 0, 255]);
        assert_eq!(texels[4..8], [1, 0, 254, 255]);
        let red = [9u8, 8, 7];
        unsafe { ctx.glColorSubTableEXT(gl::GL_TEXTURE_2D, 1, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, red.as_ptr().cast()) };
        let (texels, v2) = ctx.with_bound_texture(super::Target::D2, |o| (o.level(0, 0).unwrap().image.texels.clone(), o.version));
        assert_eq!(texels[4..8], [9, 8, 7, 255]);
        assert!(v2 > v1);
        let mut width = 0;
        unsafe { ctx.glGetColorTableParameterivEXT(gl::GL_TEXTURE_2D, gl::GL_COLOR_TABLE_WIDTH, &mut width) };
        assert_eq!(width, 256);
        let mut back = [0u8; 256 * 4];
        unsafe { ctx.glGetColorTableEXT(gl::GL_TEXTURE_2D, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, back.as_mut_ptr().cast()) };
        assert_eq!(back[4..8], [9, 8, 7, 255]);
        let mut size = 0;
        unsafe { ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 0, gl::GL_TEXTURE_INDEX_SIZE_EXT, &mut size) };
        assert_eq!(size, 8);
        // COLOR_INDEX4: indices keep their low four bits.
        let idx = [0x13u8];
        unsafe { dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 1, gl::GL_COLOR_INDEX4_EXT as i32, 1, 1, 0, gl::GL_COLOR_INDEX, gl::GL_UNSIGNED_BYTE, idx.as_ptr().cast()) };
        unsafe { ctx.glGetTexLevelParameteriv(gl::GL_TEXTURE_2D, 1, gl::GL_TEXTURE_INDEX_SIZE_EXT, &mut size) };
        let texel = ctx.with_bound_texture(super::Target::D2, |o| o.level(0, 1).unwrap().image.texels.clone());
        assert_eq!((size, texel[0]), (4, 3));
        unsafe { dispatch::glColorTableEXT(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_RGB, 100, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, palette.as_ptr().cast()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    }
}

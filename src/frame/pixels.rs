//! Pixel operations of the frame, in program order with the draws: bitmaps (HUD text),
//! `glDrawPixels` images, `glCopyPixels`, copies from the framebuffer into textures and
//! accumulation-buffer operations. Positions are window coordinates (OpenGL 1.5 sections
//! 3.6–3.7, 4.2.4, 4.3).

use std::sync::Arc;

use super::{RasterState, TextureRef, TextureUnit};

/// One pixel operation and where it falls among the draws.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelOp {
    /// Index in [`super::Frame::draws`] of the first draw after the operation.
    pub before_draw: usize,
    /// Number of [`super::Frame::clears`] issued before the operation (orders it among clears
    /// placed before the same draw).
    pub after_clears: usize,
    /// What to do.
    pub kind: PixelKind,
    /// The raster state when the operation was issued: the per-fragment operations (scissor,
    /// alpha, stencil and depth tests, blending, logic op, masks) that apply to the fragments
    /// of bitmaps, images and copies (OpenGL 1.5 sections 3.6.5, 3.7 and 4.3.3), and the
    /// scissor box and colour mask of accumulation returns (section 4.2.4).
    pub state: Arc<RasterState>,
    /// What the fragments of bitmaps, images and copies take from the current raster position
    /// besides their colour and depth.
    pub raster: Arc<RasterFragment>,
}

/// The data of the current raster position that the fragments of `glBitmap`, `glDrawPixels`
/// and `glCopyPixels` carry into texturing, colour sum and fog (OpenGL 1.5 sections 3.6.5,
/// 3.7 and 4.3.3: they take "the texture coordinates ... associated with the current raster
/// position"; section 3.10 fogs them with the raster distance).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RasterFragment {
    /// Texture coordinates of each unit, with coordinate generation and the texture matrix
    /// already applied (as the raster position holds them).
    pub texcoords: Vec<[f32; 4]>,
    /// Bound texture of each unit that texturing uses (empty when no unit textures).
    pub textures: Vec<Option<TextureRef>>,
    /// Texture environment of each unit with a texture target enabled (`None` for the
    /// others); coordinate generation is off, since `texcoords` are final.
    pub texture_units: Vec<Option<TextureUnit>>,
    /// The raster secondary colour (colour sum, section 3.9).
    pub secondary: [f32; 4],
    /// The raster distance: the fog coordinate of the fragments.
    pub fog_coord: f32,
}

impl RasterFragment {
    /// Whether some unit textures the fragments.
    pub fn textured(&self) -> bool {
        self.texture_units.iter().any(Option::is_some)
    }
}

/// Which framebuffer contents an operation reads or writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PixelBuffer {
    /// The colour buffer.
    #[default]
    Color,
    /// The depth buffer (values in [0, 1]).
    Depth,
    /// The stencil buffer.
    Stencil,
}

/// Data of a `glDrawPixels` image, rows bottom to top.
#[derive(Clone, PartialEq)]
pub enum PixelData {
    /// Colours after pixel transfer, RGBA8.
    Rgba8(Arc<[u8]>),
    /// Depth values after scale and bias.
    Depth(Arc<[f32]>),
    /// Stencil indices after shift, offset and map.
    Stencil(Arc<[u32]>),
    /// Depth values and stencil indices (`GL_DEPTH_STENCIL`, one of each per pixel), after
    /// their pixel transfer. They bypass every per-fragment operation but the pixel ownership
    /// and scissor tests: each pixel's stencil index is written through the stencil write
    /// mask and its depth through the depth mask, whatever the depth and stencil tests
    /// (EXT_packed_depth_stencil section 4.3.1).
    DepthStencil(Arc<[f32]>, Arc<[u32]>),
}

impl std::fmt::Debug for PixelData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PixelData::Rgba8(d) => write!(f, "Rgba8({} bytes)", d.len()),
            PixelData::Depth(d) => write!(f, "Depth({} values)", d.len()),
            PixelData::Stencil(d) => write!(f, "Stencil({} values)", d.len()),
            PixelData::DepthStencil(d, _) => write!(f, "DepthStencil({} values)", d.len()),
        }
    }
}

/// Accumulation-buffer operation (`glAccum`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AccumOp {
    /// accum = colour × value.
    Load,
    /// accum += colour × value.
    Accum,
    /// colour = accum × value.
    Return,
    /// accum ×= value.
    Mult,
    /// accum += value.
    Add,
}

/// A pixel operation.
#[derive(Clone, Debug, PartialEq)]
pub enum PixelKind {
    /// `glBitmap`: set pixels take `color`; `mask` has one byte per pixel (0 or 255), rows
    /// bottom to top; the lower-left corner is at `window_pos` (raster position − origin).
    Bitmap {
        /// Lower-left corner and depth.
        window_pos: [f32; 3],
        /// Width and height in pixels.
        size: [u32; 2],
        /// Current raster colour.
        color: [f32; 4],
        /// Coverage, 0 or 255 per pixel.
        mask: Arc<[u8]>,
    },
    /// `glDrawPixels`.
    Image {
        /// Lower-left corner (the raster position) and depth.
        window_pos: [f32; 3],
        /// `glPixelZoom` factors.
        zoom: [f32; 2],
        /// Width and height in pixels.
        size: [u32; 2],
        /// Current raster colour (used for depth and stencil images).
        color: [f32; 4],
        /// The pixels.
        data: PixelData,
    },
    /// `glCopyPixels`: the rectangle `src` (x, y, width, height) of `buffer` is drawn at
    /// `window_pos` with `zoom`.
    Copy {
        /// Source rectangle.
        src: [i32; 4],
        /// Destination lower-left corner and depth.
        window_pos: [f32; 3],
        /// Zoom factors.
        zoom: [f32; 2],
        /// Which buffer is copied.
        buffer: PixelBuffer,
        /// Current raster colour (the colour of depth-copy fragments).
        color: [f32; 4],
    },
    /// `glCopyTexImage*`/`glCopyTexSubImage*`: the renderer copies `src` (x, y, width, height)
    /// of the colour (or depth, for depth textures) buffer into the texture `texture`, whose
    /// content version became `version` with this copy, at `face`, `level`, `offset`.
    TextureCopy {
        /// Texture object name.
        texture: u32,
        /// Content version the copy produces.
        version: u64,
        /// Cube face (0 for other kinds).
        face: u32,
        /// Mipmap level.
        level: u32,
        /// Destination texel offset (x, y, z), border included.
        offset: [i32; 3],
        /// Source rectangle.
        src: [i32; 4],
        /// Which buffer is read.
        buffer: PixelBuffer,
    },
    /// `glAccum`.
    Accum {
        /// The operation.
        op: AccumOp,
        /// Its value.
        value: f32,
    },
}

/// The part of the window rectangle `src` inside a window of `size`, and how many columns and
/// rows of `src` lie left of and below it; `None` when nothing is inside.
pub fn clip_to_window(src: [i32; 4], size: [u32; 2]) -> Option<([i32; 4], [i32; 2])> {
    let [x, y, w, h] = src.map(|v| v as i64);
    let x0 = x.clamp(0, size[0] as i64);
    let y0 = y.clamp(0, size[1] as i64);
    let x1 = (x + w.max(0)).clamp(0, size[0] as i64);
    let y1 = (y + h.max(0)).clamp(0, size[1] as i64);
    (x1 > x0 && y1 > y0).then(|| ([x0, y0, x1 - x0, y1 - y0].map(|v| v as i32), [(x0 - x) as i32, (y0 - y) as i32]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_are_clipped_to_the_window() {
        assert_eq!(clip_to_window([-2, 3, 10, 10], [8, 8]), Some(([0, 3, 8, 5], [2, 0])));
        assert_eq!(clip_to_window([0, 0, 4, 4], [8, 8]), Some(([0, 0, 4, 4], [0, 0])));
        assert_eq!(clip_to_window([9, 0, 4, 4], [8, 8]), None);
        assert_eq!(clip_to_window([0, 0, -1, 4], [8, 8]), None);
    }
}

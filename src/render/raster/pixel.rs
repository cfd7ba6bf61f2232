//! Pixel operations of a frame (`glBitmap`, `glDrawPixels`, `glCopyPixels`, copies into
//! textures, `glAccum`) on the GPU framebuffer. This is the seam where the pixel path records
//! its commands through the [`Recorder`]; until an operation is implemented it is skipped
//! and reported once by kind.

use super::device::Result;
use super::renderer::Recorder;
use crate::frame::pixels::{PixelKind, PixelOp};

/// Records `op` into the frame.
pub fn record(_rec: &mut Recorder<'_>, op: &PixelOp) -> Result<()> {
    let kind = match op.kind {
        PixelKind::Bitmap { .. } => "glBitmap",
        PixelKind::Image { .. } => "glDrawPixels",
        PixelKind::Copy { .. } => "glCopyPixels",
        PixelKind::TextureCopy { .. } => "glCopyTexImage",
        PixelKind::Accum { .. } => "glAccum",
    };
    super::renderer::log_once(kind);
    Ok(())
}

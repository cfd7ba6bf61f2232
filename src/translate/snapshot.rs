//! Texture snapshot taken when a draw is emitted (placeholder until the texture module
//! provides it). The raster-state snapshot is `Context::raster_snapshot` in `fixed.rs`.

use super::Context;
use crate::frame::TextureRef;

impl Context {
    /// The texture each unit would sample for the next draw.
    pub fn texture_snapshot(&mut self) -> Vec<Option<TextureRef>> {
        Vec::new()
    }
}

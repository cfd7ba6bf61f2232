//! Snapshots of the context state taken when a draw is emitted (placeholders until the
//! fixed-function state and texture modules provide them).

use std::sync::Arc;

use super::Context;
use crate::frame::{RasterState, TextureRef};

impl Context {
    /// The raster state for the next draw.
    pub fn raster_snapshot(&mut self) -> Arc<RasterState> {
        Arc::default()
    }

    /// The texture each unit would sample for the next draw.
    pub fn texture_snapshot(&mut self) -> Vec<Option<TextureRef>> {
        Vec::new()
    }
}

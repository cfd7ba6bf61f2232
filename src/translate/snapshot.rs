//! Snapshots of the context state taken when a draw is emitted (placeholder until the
//! fixed-function state module provides it; textures: `texture::snapshot`).

use std::sync::Arc;

use super::Context;
use crate::frame::RasterState;

impl Context {
    /// The raster state for the next draw.
    pub fn raster_snapshot(&mut self) -> Arc<RasterState> {
        Arc::default()
    }
}

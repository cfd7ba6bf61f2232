//! The raster state of a draw, as plain Rust values (placeholder until the fixed-function
//! state snapshot lands).

/// Snapshot of the state a draw is rasterized or traced with.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RasterState {}

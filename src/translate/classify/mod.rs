//! Hash tracking (DESIGN.md, "Hash tracking"): which geometry is static, movable or dynamic,
//! matched across frames, and the persistent static world built below the draw level.

pub mod static_world;

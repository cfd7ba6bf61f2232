//! The generated layer between the C exports and [`super::Context`]: for each command,
//! display-list recording (OpenGL 1.5 section 5.4), the `glBegin`/`glEnd` rule (section 2.6.3),
//! attribute-family conversions (`glColor3ub` → `glColor4f`, table 2.9) and aliases
//! (`glActiveTextureARB` → `glActiveTexture`). See `build/` for the rules.

#![allow(non_snake_case, clippy::too_many_arguments, clippy::missing_safety_doc)]

include!(concat!(env!("OUT_DIR"), "/dispatch.rs"));

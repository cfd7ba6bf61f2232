//! `glEnable`, `glDisable`, `glIsEnabled` (OpenGL 1.5 section 2.13 and table 6.x): every
//! server-side capability, global or per texture unit. The modules that use a capability read
//! it here (`ctx.enables.is_on(gl::GL_FOG)`).

use super::Context;
use super::get::Value;
use super::gl::{self, GLboolean, GLenum};
use super::limits::{MAX_CLIP_PLANES, MAX_LIGHTS, MAX_TEXTURE_UNITS};

/// Capabilities that are not per texture unit. `GL_LIGHTi` and `GL_CLIP_PLANEi` are added
/// from their ranges.
const GLOBAL_CAPS: &[GLenum] = &[
    gl::GL_ALPHA_TEST,
    gl::GL_AUTO_NORMAL,
    gl::GL_BLEND,
    gl::GL_COLOR_LOGIC_OP,
    gl::GL_COLOR_MATERIAL,
    gl::GL_COLOR_SUM,
    gl::GL_CULL_FACE,
    gl::GL_DEPTH_TEST,
    gl::GL_DITHER,
    gl::GL_FOG,
    gl::GL_INDEX_LOGIC_OP,
    gl::GL_LIGHTING,
    gl::GL_LINE_SMOOTH,
    gl::GL_LINE_STIPPLE,
    gl::GL_MAP1_COLOR_4,
    gl::GL_MAP1_INDEX,
    gl::GL_MAP1_NORMAL,
    gl::GL_MAP1_TEXTURE_COORD_1,
    gl::GL_MAP1_TEXTURE_COORD_2,
    gl::GL_MAP1_TEXTURE_COORD_3,
    gl::GL_MAP1_TEXTURE_COORD_4,
    gl::GL_MAP1_VERTEX_3,
    gl::GL_MAP1_VERTEX_4,
    gl::GL_MAP2_COLOR_4,
    gl::GL_MAP2_INDEX,
    gl::GL_MAP2_NORMAL,
    gl::GL_MAP2_TEXTURE_COORD_1,
    gl::GL_MAP2_TEXTURE_COORD_2,
    gl::GL_MAP2_TEXTURE_COORD_3,
    gl::GL_MAP2_TEXTURE_COORD_4,
    gl::GL_MAP2_VERTEX_3,
    gl::GL_MAP2_VERTEX_4,
    gl::GL_MULTISAMPLE,
    gl::GL_NORMALIZE,
    gl::GL_POINT_SMOOTH,
    gl::GL_POINT_SPRITE,
    gl::GL_POLYGON_OFFSET_FILL,
    gl::GL_POLYGON_OFFSET_LINE,
    gl::GL_POLYGON_OFFSET_POINT,
    gl::GL_POLYGON_SMOOTH,
    gl::GL_POLYGON_STIPPLE,
    gl::GL_RESCALE_NORMAL,
    gl::GL_SAMPLE_ALPHA_TO_COVERAGE,
    gl::GL_SAMPLE_ALPHA_TO_ONE,
    gl::GL_SAMPLE_COVERAGE,
    gl::GL_SCISSOR_TEST,
    gl::GL_SHARED_TEXTURE_PALETTE_EXT,
    gl::GL_STENCIL_TEST,
    gl::GL_VERTEX_PROGRAM_POINT_SIZE,
    gl::GL_VERTEX_PROGRAM_TWO_SIDE,
    gl::GL_STENCIL_TEST_TWO_SIDE_EXT,
];

/// Capabilities of the active texture unit.
pub(crate) const UNIT_CAPS: [GLenum; 9] = [
    gl::GL_TEXTURE_1D,
    gl::GL_TEXTURE_2D,
    gl::GL_TEXTURE_3D,
    gl::GL_TEXTURE_CUBE_MAP,
    gl::GL_TEXTURE_RECTANGLE_ARB,
    gl::GL_TEXTURE_GEN_S,
    gl::GL_TEXTURE_GEN_T,
    gl::GL_TEXTURE_GEN_R,
    gl::GL_TEXTURE_GEN_Q,
];

/// Client-side capabilities: `glIsEnabled` answers them, `glEnable` does not take them.
const CLIENT_CAPS: &[GLenum] = &[
    gl::GL_VERTEX_ARRAY,
    gl::GL_NORMAL_ARRAY,
    gl::GL_COLOR_ARRAY,
    gl::GL_INDEX_ARRAY,
    gl::GL_TEXTURE_COORD_ARRAY,
    gl::GL_EDGE_FLAG_ARRAY,
    gl::GL_FOG_COORD_ARRAY,
    gl::GL_SECONDARY_COLOR_ARRAY,
];

/// Where a capability lives.
enum Slot {
    Global(usize),
    Unit(usize),
}

fn slot(cap: GLenum) -> Option<Slot> {
    match global_slot(cap) {
        Some(i) => Some(Slot::Global(i)),
        None => UNIT_CAPS.iter().position(|&c| c == cap).map(Slot::Unit),
    }
}

/// The index of a global capability in [`EnableState`]; a `const fn`, so that
/// [`EnableState::is_on_const`] finds it at compile time.
const fn global_slot(cap: GLenum) -> Option<usize> {
    let mut i = 0;
    while i < GLOBAL_CAPS.len() {
        if GLOBAL_CAPS[i] == cap {
            return Some(i);
        }
        i += 1;
    }
    let light = cap.wrapping_sub(gl::GL_LIGHT0) as usize;
    if light < MAX_LIGHTS {
        return Some(GLOBAL_CAPS.len() + light);
    }
    let plane = cap.wrapping_sub(gl::GL_CLIP_PLANE0) as usize;
    if plane < MAX_CLIP_PLANES {
        return Some(GLOBAL_CAPS.len() + MAX_LIGHTS + plane);
    }
    None
}

const GLOBAL_COUNT: usize = GLOBAL_CAPS.len() + MAX_LIGHTS + MAX_CLIP_PLANES;

/// Every server-side capability's state.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnableState {
    global: [bool; GLOBAL_COUNT],
    units: [[bool; UNIT_CAPS.len()]; MAX_TEXTURE_UNITS],
    /// Bumped on every change, so snapshots of the raster state can be cached.
    pub version: u64,
}

impl Default for EnableState {
    /// Everything off but `GL_DITHER` and `GL_MULTISAMPLE` (table 6.x initial values).
    fn default() -> EnableState {
        let mut e = EnableState { global: [false; GLOBAL_COUNT], units: Default::default(), version: 0 };
        e.set(gl::GL_DITHER, 0, true);
        e.set(gl::GL_MULTISAMPLE, 0, true);
        e
    }
}

impl EnableState {
    /// Whether a global capability (`GL_FOG`, `GL_LIGHT3`...) is on; false for others.
    pub fn is_on(&self, cap: GLenum) -> bool {
        global_slot(cap).is_some_and(|i| self.global[i])
    }

    /// [`EnableState::is_on`] of a capability named at compile time (a load instead of a
    /// search, for the per-vertex and per-draw paths); not compiling for a per-unit one.
    #[inline(always)]
    pub fn is_on_const<const CAP: GLenum>(&self) -> bool {
        let slot = const {
            match global_slot(CAP) {
                Some(i) => i,
                None => panic!("not a global capability"),
            }
        };
        self.global[slot]
    }

    /// Whether a per-unit capability (`GL_TEXTURE_2D`, `GL_TEXTURE_GEN_S`...) is on for `unit`.
    pub fn unit_on(&self, unit: usize, cap: GLenum) -> bool {
        UNIT_CAPS.iter().position(|&c| c == cap).is_some_and(|i| self.units[unit][i])
    }

    /// Sets a capability (per-unit ones on `unit`); false if `cap` is not one.
    pub fn set(&mut self, cap: GLenum, unit: usize, on: bool) -> bool {
        match slot(cap) {
            Some(Slot::Global(i)) => self.global[i] = on,
            Some(Slot::Unit(i)) => self.units[unit][i] = on,
            None => return false,
        }
        self.version += 1;
        true
    }

    fn get(&self, cap: GLenum, unit: usize) -> Option<bool> {
        Some(match slot(cap)? {
            Slot::Global(i) => self.global[i],
            Slot::Unit(i) => self.units[unit][i],
        })
    }
}

impl Context {
    /// Sets a server capability. The client array enables (`GL_VERTEX_ARRAY`...) are also
    /// taken here, as `glEnableClientState` would take them: OpenGL 1.5 names only
    /// `glEnableClientState` for them, but Mesa's and NVIDIA's compatibility contexts accept
    /// them in `glEnable`/`glDisable` and old programs (piglit's `color-material-array`
    /// among them) rely on it.
    fn set_cap(&mut self, cap: GLenum, on: bool, command: &'static str) {
        if CLIENT_CAPS.contains(&cap) {
            return self.set_client_state(cap, on, command);
        }
        let unit = self.active_texture_unit();
        if !self.enables.set(cap, unit, on) {
            self.set_error_in(gl::GL_INVALID_ENUM, command);
        }
    }

    /// `glEnable`; enabling `GL_COLOR_MATERIAL` gives the material the current colour at once
    /// (section 2.14.3).
    pub fn glEnable(&mut self, cap: GLenum) {
        self.set_cap(cap, true, "glEnable");
        if cap == gl::GL_COLOR_MATERIAL {
            self.apply_color_material(self.immediate.current().color);
        }
    }

    /// `glDisable`.
    pub fn glDisable(&mut self, cap: GLenum) {
        self.set_cap(cap, false, "glDisable");
    }

    /// `glIsEnabled`: server capabilities, and the client array enables.
    pub fn glIsEnabled(&mut self, cap: GLenum) -> GLboolean {
        if let Some(on) = self.enables.get(cap, self.active_texture_unit()) {
            return GLboolean::from(on);
        }
        if CLIENT_CAPS.contains(&cap)
            && let Some(v) = self.query(cap) {
                return v.to_bools()[0];
            }
        self.set_error_in(gl::GL_INVALID_ENUM, "glIsEnabled");
        0
    }

    /// Every server capability is also a `glGet` parameter.
    pub(crate) fn query_enables(&self, pname: GLenum) -> Option<Value> {
        self.enables.get(pname, self.active_texture_unit()).map(Value::bool)
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    #[test]
    fn caps_per_unit_and_errors() {
        let (mut ctx, _) = Context::with_recording();
        assert_eq!(ctx.glIsEnabled(gl::GL_DITHER), 1);
        ctx.glEnable(gl::GL_LIGHT7);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        assert_eq!(ctx.glIsEnabled(gl::GL_TEXTURE_2D), 0);
        assert_eq!(ctx.glIsEnabled(gl::GL_LIGHT7), 1);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glEnable(gl::GL_LIGHT0 + 8);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn client_array_caps_in_enable_set_client_state() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_COLOR_ARRAY);
        assert_eq!(ctx.glIsEnabled(gl::GL_COLOR_ARRAY), 1);
        assert_eq!(ctx.glIsEnabled(gl::GL_VERTEX_ARRAY), 0);
        ctx.glDisable(gl::GL_COLOR_ARRAY);
        assert_eq!(ctx.glIsEnabled(gl::GL_COLOR_ARRAY), 0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}

//! The user clip-plane test of a single point (OpenGL 1.5 section 2.12), for the raster
//! position (section 2.13), which is invalid when any enabled plane rejects it.

use glam::{DVec4, Vec4};

use super::Context;
use super::gl::{self, GLenum};
use super::limits::MAX_CLIP_PLANES;

impl Context {
    /// Whether the eye-space point `eye_pos` lies in the half-space `p · eye_pos ≥ 0` of every
    /// enabled `GL_CLIP_PLANEi`, the planes being stored in eye space by `glClipPlane`.
    pub fn inside_user_clip_planes(&self, eye_pos: Vec4) -> bool {
        let v = eye_pos.as_dvec4();
        (0..MAX_CLIP_PLANES)
            .filter(|&i| self.enables.is_on(gl::GL_CLIP_PLANE0 + i as GLenum))
            .all(|i| DVec4::from_array(self.fixed.clip_planes[i]).dot(v) >= 0.0)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use crate::translate::{Context, gl};

    #[test]
    fn enabled_planes_accept_and_reject_points() {
        let (mut ctx, _) = Context::with_recording();
        // Object plane x ≤ 1 (−x + 1 ≥ 0) under a translation by 2 along x: eye x ≤ 3.
        ctx.glTranslatef(2.0, 0.0, 0.0);
        unsafe { ctx.glClipPlane(gl::GL_CLIP_PLANE3, [-1.0, 0.0, 0.0, 1.0].as_ptr()) };
        let outside = Vec4::new(3.5, 0.0, 0.0, 1.0);
        assert!(ctx.inside_user_clip_planes(outside), "plane disabled: everything passes");
        ctx.glEnable(gl::GL_CLIP_PLANE3);
        assert!(!ctx.inside_user_clip_planes(outside));
        assert!(ctx.inside_user_clip_planes(Vec4::new(2.5, 9.0, -4.0, 1.0)));
        assert!(ctx.inside_user_clip_planes(Vec4::new(3.0, 0.0, 0.0, 1.0)), "on the plane is inside");
        // Homogeneous: (7, 0, 0, 2) is x = 3.5.
        assert!(!ctx.inside_user_clip_planes(Vec4::new(7.0, 0.0, 0.0, 2.0)));
        // A second plane y ≥ 0 rejects what the first accepts.
        ctx.glLoadIdentity();
        unsafe { ctx.glClipPlane(gl::GL_CLIP_PLANE0, [0.0, 1.0, 0.0, 0.0].as_ptr()) };
        ctx.glEnable(gl::GL_CLIP_PLANE0);
        assert!(ctx.inside_user_clip_planes(Vec4::new(0.0, 1.0, 0.0, 1.0)));
        assert!(!ctx.inside_user_clip_planes(Vec4::new(0.0, -1.0, 0.0, 1.0)));
    }
}

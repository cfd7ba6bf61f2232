//! Early face culling (OpenGL 1.5 section 3.5.1): a batch of triangles that the renderer
//! would cull entirely is dropped before it enters the frame, so that a frame of culled
//! geometry costs its GL calls and a facing test, not vertex copies, snapshots and uploads.
//!
//! Only when the sink does not keep culled triangles ([`crate::frame::FrameSink::keeps_culled_triangles`]:
//! a rasterizer does not, the path tracer's world and the frame log do), only for the
//! fixed-function transform (a program's vertex shader places vertices where the CPU cannot
//! see), and only for triangles whose facing is certain: every vertex in front of the eye
//! (`w > 0`, where the sign of the homogeneous determinant is the sign of the window-space
//! area) and an area clearly away from zero. Everything else counts as drawn.

use glam::{Mat4, Vec4};

use crate::frame::state::{Face, Winding};

/// Relative size of the smallest determinant whose sign is taken as the facing: below it, the
/// triangle is too thin for float rounding to decide (and a zero-area triangle still draws
/// lines and points in polygon modes `GL_LINE` and `GL_POINT`).
const CERTAIN: f32 = 1e-5;

/// Whether every triangle of `indices` (three per triangle, into `positions`, object space)
/// is culled when drawn with `mvp` (object to clip space) under `cull` with front faces
/// winding `front`. Stops at the first triangle that may be drawn.
pub fn all_culled(cull: Face, front: Winding, mvp: &Mat4, positions: &[[f32; 4]], indices: &[u32]) -> bool {
    if cull == Face::FrontAndBack {
        return true;
    }
    // The sign of the counter-clockwise (positive) area of a triangle that is culled.
    let culled_sign = match (cull, front) {
        (Face::Back, Winding::Ccw) | (Face::Front, Winding::Cw) => -1.0,
        _ => 1.0,
    };
    let clip = |i: u32| positions.get(i as usize).map(|&p| *mvp * Vec4::from_array(p));
    indices.chunks_exact(3).all(|t| {
        let (Some(a), Some(b), Some(c)) = (clip(t[0]), clip(t[1]), clip(t[2])) else { return false };
        if a.w <= 0.0 || b.w <= 0.0 || c.w <= 0.0 {
            return false;
        }
        // det [a.xyw; b.xyw; c.xyw] = a.w b.w c.w × (twice the signed area in normalized
        // device coordinates), so with every w positive it has the area's sign.
        let terms = [a.x * (b.y * c.w - c.y * b.w), a.y * (c.x * b.w - b.x * c.w), a.w * (b.x * c.y - c.x * b.y)];
        let det: f32 = terms.iter().sum();
        let scale: f32 = terms.iter().map(|t| t.abs()).sum();
        det * culled_sign > CERTAIN * scale
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A counter-clockwise triangle at depth `z` (eye space, so `w = -z` in front of the eye).
    const CCW: [[f32; 4]; 3] = [[0.0, 0.0, -1.0, 1.0], [1.0, 0.0, -1.0, 1.0], [0.0, 1.0, -1.0, 1.0]];

    /// `glFrustum(-0.1, 0.1, -0.1, 0.1, 0.1, 10.0)`.
    fn perspective() -> Mat4 {
        let (n, f) = (0.1, 10.0);
        Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -(f + n) / (f - n), -1.0, 0.0, 0.0, -2.0 * f * n / (f - n), 0.0])
    }

    #[test]
    fn facing_follows_winding_front_face_and_cull_face() {
        let m = perspective();
        let ccw = [0, 1, 2];
        let cw = [0, 2, 1];
        assert!(!all_culled(Face::Back, Winding::Ccw, &m, &CCW, &ccw), "front face kept");
        assert!(all_culled(Face::Back, Winding::Ccw, &m, &CCW, &cw), "back face culled");
        assert!(all_culled(Face::Front, Winding::Ccw, &m, &CCW, &ccw));
        assert!(!all_culled(Face::Front, Winding::Ccw, &m, &CCW, &cw));
        assert!(all_culled(Face::Back, Winding::Cw, &m, &CCW, &ccw), "glFrontFace(GL_CW) turns it around");
        assert!(all_culled(Face::FrontAndBack, Winding::Ccw, &m, &CCW, &ccw));
        // A mirroring transform flips the facing.
        let mirror = m * Mat4::from_scale(glam::Vec3::new(-1.0, 1.0, 1.0));
        assert!(all_culled(Face::Back, Winding::Ccw, &mirror, &CCW, &ccw));
    }

    #[test]
    fn one_drawn_triangle_keeps_the_batch() {
        let m = perspective();
        assert!(all_culled(Face::Back, Winding::Ccw, &m, &CCW, &[0, 2, 1, 1, 0, 2]));
        assert!(!all_culled(Face::Back, Winding::Ccw, &m, &CCW, &[0, 2, 1, 0, 1, 2]));
    }

    #[test]
    fn uncertain_triangles_count_as_drawn() {
        let m = perspective();
        // A vertex behind the eye: clipping decides, not the CPU.
        let behind = [CCW[0], CCW[1], [0.0, 1.0, 1.0, 1.0]];
        assert!(!all_culled(Face::Back, Winding::Ccw, &m, &behind, &[0, 2, 1]));
        // Zero area (it still draws lines in polygon mode GL_LINE).
        let flat = [CCW[0], CCW[1], [2.0, 0.0, -1.0, 1.0]];
        assert!(!all_culled(Face::Back, Winding::Ccw, &m, &flat, &[0, 2, 1]));
        // An index past the vertices.
        assert!(!all_culled(Face::Back, Winding::Ccw, &m, &CCW, &[0, 2, 7]));
    }
}

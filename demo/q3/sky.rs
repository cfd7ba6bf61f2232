//! The sky (`tr_sky.c`): a box around the eye, [`SKY_SUBDIVISIONS`] rows and columns per
//! side, each row a `glBegin(GL_TRIANGLE_STRIP)` with texture coordinates and vertices in
//! immediate mode (`DrawSkySide`), sides mapped from (s, t) as Q3's `MakeSkyVec` maps them;
//! then the cloud layer as vertices and indexes in the batch (`FillCloudBox`), drawn by the
//! generic iterator. Q3 draws only the part of each side that the visible sky surfaces cover;
//! here the opening is always above the eye, so the upper half of the four sides and the top
//! are drawn whenever the opening is in view.

use glam::Vec3;

use super::gl_state::{Api, GlState};
use super::tess::Tess;
use crate::gl::GLuint;

/// Rows and columns per side.
const SKY_SUBDIVISIONS: i32 = 8;
const HALF: i32 = SKY_SUBDIVISIONS / 2;
/// Q3's `st_to_vec`: per side, which of (s, t, 1) · box size (1-based, negative: negated)
/// becomes x, y and z. Sides 0..4 go around, 4 is the top, 5 the bottom.
const ST_TO_VEC: [[i32; 3]; 6] = [[3, -1, 2], [-3, 1, 2], [1, 3, 2], [-1, -3, 2], [-2, -1, 3], [2, -1, -3]];
/// Sides drawn: around and the top.
const SIDES: usize = 5;

/// The direction (times the box size) and the texture coordinates of point (s, t) in -1..=1 of
/// `side` (`MakeSkyVec`).
fn sky_vec(s: f32, t: f32, side: usize, box_size: f32) -> (Vec3, [f32; 2]) {
    let b = [s * box_size, t * box_size, box_size];
    let v = ST_TO_VEC[side].map(|k| if k < 0 { -b[(-k - 1) as usize] } else { b[(k - 1) as usize] });
    (Vec3::from(v), [((s + 1.0) * 0.5).clamp(0.0, 1.0), (1.0 - (t + 1.0) * 0.5).clamp(0.0, 1.0)])
}

/// Rows of `side` drawn (in subdivisions from the centre): the upper half of the sides
/// around, all of the top.
fn rows(side: usize) -> std::ops::Range<i32> {
    if side == 4 { -HALF..HALF } else { 0..HALF }
}

/// Box size for a far plane (Q3: `zFar / 1.75`, so the corners stay inside the far plane).
fn box_size(z_far: f32) -> f32 {
    z_far / 1.75
}

/// Draws the sky box around the origin with `sides` as images; returns the number of
/// `glBegin`/`glEnd` pairs.
pub fn draw_box(api: Api, state: &mut GlState, sides: &[GLuint; 6], z_far: f32) -> usize {
    let size = box_size(z_far);
    let mut begins = 0;
    for (side, &image) in sides.iter().enumerate().take(SIDES) {
        state.bind(api, image);
        for t in rows(side) {
            // Safety: a context is current; only vertex calls inside glBegin/glEnd.
            unsafe {
                api.gl.glBegin(crate::gl::GL_TRIANGLE_STRIP);
                for s in -HALF..=HALF {
                    for row in [t, t + 1] {
                        let (v, st) = sky_vec(s as f32 / HALF as f32, row as f32 / HALF as f32, side, size);
                        api.gl.glTexCoord2f(st[0], st[1]);
                        api.gl.glVertex3f(v.x, v.y, v.z);
                    }
                }
                api.gl.glEnd();
            }
            begins += 1;
        }
    }
    begins
}

/// Replaces the batch with the cloud layer around `origin`: the same grid as the box, at the
/// box's distance, texture coordinates from where each direction would meet a flat cloud
/// ceiling (`R_BuildCloudData`).
pub fn fill_clouds(tess: &mut Tess, origin: Vec3, z_far: f32) {
    tess.num_vertexes = 0;
    tess.num_indexes = 0;
    let size = box_size(z_far);
    for side in 0..SIDES {
        let r = rows(side);
        let width = (2 * HALF + 1) as u32;
        let mut vertices = Vec::new();
        for t in r.start..=r.end {
            for s in -HALF..=HALF {
                let (v, _) = sky_vec(s as f32 / HALF as f32, t as f32 / HALF as f32, side, size);
                let d = v.normalize();
                let st = [d.x / (d.z + 0.25) * 0.6, d.y / (d.z + 0.25) * 0.6];
                vertices.push((origin + v, st));
            }
        }
        let mut indexes = Vec::new();
        for t in 0..(r.end - r.start) as u32 {
            for s in 0..width - 1 {
                let (a, b) = (t * width + s, (t + 1) * width + s);
                // The strip's winding: (s, t), (s, t + 1), (s + 1, t), then its odd triangle.
                indexes.extend_from_slice(&[a, b, a + 1, a + 1, b, b + 1]);
            }
        }
        tess.add_vertices(&vertices, &indexes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_face_their_axes_and_the_top_is_up() {
        let centre = |side| sky_vec(0.0, 0.0, side, 1.0).0;
        assert_eq!([centre(0), centre(1), centre(2), centre(3), centre(4), centre(5)], [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z]);
        // t = 1 is the top edge of the sides around (z up), texture row 0.
        for side in 0..4 {
            let (v, st) = sky_vec(0.0, 1.0, side, 1.0);
            assert_eq!((v.z, st[1]), (1.0, 0.0), "side {side}");
        }
    }

    #[test]
    fn strips_are_clockwise_seen_from_inside() {
        for side in 0..SIDES {
            let p = |s: i32, t: i32| sky_vec(s as f32 / 4.0, t as f32 / 4.0, side, 1.0).0;
            // The strip's first triangle: (s, t), (s, t + 1), (s + 1, t).
            let (a, b, c) = (p(0, 0), p(0, 1), p(1, 0));
            let normal = (b - a).cross(c - a);
            // Seen from the centre (looking along a), clockwise: the normal points away.
            assert!(normal.dot(a) > 0.0, "side {side}");
        }
    }

    #[test]
    fn clouds_cover_the_sides_drawn() {
        let mut tess = Tess::new();
        fill_clouds(&mut tess, Vec3::new(1.0, 2.0, 3.0), 4096.0);
        assert_eq!(tess.num_vertexes, 4 * 9 * 5 + 9 * 9);
        assert_eq!(tess.num_indexes, (4 * 8 * 4 + 8 * 8) * 6);
        assert!(tess.xyz[..tess.num_vertexes].iter().all(|p| p[2] >= 3.0 - 1e-3));
    }
}

//! The models of `--q3`, built at start-up as Quake 3's MD3 models are stored: every frame of
//! the animation as its own vertex positions and normals, shared texture coordinates and
//! triangles (clockwise seen from outside). The back end blends two frames per draw on the CPU
//! (`Tess::add_mesh`). A player is a figure of boxes with a walk cycle of [`WALK_FRAMES`]
//! frames; the armour, the HUD's head and the others have one frame.

use glam::{Mat3, Vec3};

/// Frames of a player's walk cycle.
pub const WALK_FRAMES: usize = 8;

/// A model: frames of (position, normal) per vertex, texture coordinates, triangles.
pub struct Mesh {
    pub frames: Vec<Vec<(Vec3, Vec3)>>,
    pub st: Vec<[f32; 2]>,
    pub indexes: Vec<u32>,
}

/// One frame under construction.
#[derive(Default)]
struct Builder {
    vertices: Vec<(Vec3, Vec3)>,
    st: Vec<[f32; 2]>,
    indexes: Vec<u32>,
}

impl Builder {
    /// A box of centre `c` and half sizes `h`, each vertex moved by `pose` (a rotation about
    /// a pivot); texture coordinates repeat every 32 units.
    fn cuboid(&mut self, c: Vec3, h: Vec3, pose: impl Fn(Vec3) -> Vec3, turn: Mat3) {
        for n in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            let t1 = if n.x.abs() > 0.5 { Vec3::Y } else { Vec3::X };
            let t2 = n.cross(t1);
            let (e1, e2) = ((t1 * h).length(), (t2 * h).length());
            let base = self.vertices.len() as u32;
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let p = c + n * h + t1 * h * a + t2 * h * b;
                self.vertices.push((pose(p), turn * n));
                self.st.push([(a + 1.0) * e1 / 32.0, (1.0 - b) * e2 / 32.0]);
            }
            // Corners run counter-clockwise seen from outside: triangles clockwise.
            self.indexes.extend([0, 2, 1, 0, 3, 2].map(|i| base + i));
        }
    }

    /// An ellipsoid of radii `r` around the origin, `rings` × `segments` quads.
    fn ellipsoid(&mut self, r: Vec3, rings: usize, segments: usize) {
        let row = segments as u32 + 1;
        for ring in 0..=rings {
            for seg in 0..=segments {
                let phi = std::f32::consts::PI * ring as f32 / rings as f32;
                let theta = std::f32::consts::TAU * seg as f32 / segments as f32;
                let unit = Vec3::new(phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos());
                self.vertices.push((unit * r, (unit / r).normalize()));
                self.st.push([seg as f32 / segments as f32, ring as f32 / rings as f32]);
            }
        }
        for ring in 0..rings as u32 {
            for seg in 0..segments as u32 {
                let a = ring * row + seg;
                self.indexes.extend([a, a + 1, a + row + 1, a, a + row + 1, a + row]);
            }
        }
    }

    fn mesh(self) -> Mesh {
        Mesh { frames: vec![self.vertices], st: self.st, indexes: self.indexes }
    }
}

/// A rotation by `angle` about `axis` through `pivot`, as a point map.
fn swing(pivot: Vec3, axis: Vec3, angle: f32) -> (impl Fn(Vec3) -> Vec3, Mat3) {
    let m = Mat3::from_axis_angle(axis, angle);
    (move |p: Vec3| pivot + m * (p - pivot), m)
}

/// A player: legs, torso, arms and head, feet at z = 0, facing +x; frame k of the walk cycle
/// swings legs and arms by 0.5 rad · sin(2πk / 8) about their hips and shoulders and bobs the
/// upper body.
pub fn player() -> Mesh {
    let mut frames = Vec::new();
    let mut first = None;
    for k in 0..WALK_FRAMES {
        let phase = std::f32::consts::TAU * k as f32 / WALK_FRAMES as f32;
        let (swing_angle, bob) = (0.5 * phase.sin(), 1.5 * phase.cos().abs());
        let up = Vec3::Z * bob;
        let mut b = Builder::default();
        for (side, sign) in [(6.0, 1.0), (-6.0, -1.0)] {
            let (leg, leg_turn) = swing(Vec3::new(0.0, side, 28.0), Vec3::Y, sign * swing_angle);
            b.cuboid(Vec3::new(0.0, side, 14.0), Vec3::new(4.0, 4.0, 14.0), leg, leg_turn);
            let (arm, arm_turn) = swing(Vec3::new(0.0, 2.5 * side, 50.0) + up, Vec3::Y, -sign * 0.8 * swing_angle);
            b.cuboid(Vec3::new(0.0, 2.5 * side, 38.0) + up, Vec3::new(3.5, 3.5, 12.0), arm, arm_turn);
        }
        b.cuboid(Vec3::new(0.0, 0.0, 40.0) + up, Vec3::new(6.0, 11.0, 12.0), |p| p, Mat3::IDENTITY);
        b.cuboid(Vec3::new(0.0, 0.0, 59.0) + up, Vec3::new(6.0, 6.0, 7.0), |p| p, Mat3::IDENTITY);
        frames.push(std::mem::take(&mut b.vertices));
        first.get_or_insert((b.st, b.indexes));
    }
    let (st, indexes) = first.unwrap_or_default();
    Mesh { frames, st, indexes }
}

/// The armour pickup: a flattened ellipsoid (radius 12, 8 high), 6 × 12 quads.
pub fn armour() -> Mesh {
    let mut b = Builder::default();
    b.ellipsoid(Vec3::new(12.0, 12.0, 8.0), 6, 12);
    b.mesh()
}

/// A head for the HUD: a sphere of radius 10 (the face texture wraps once around it).
pub fn head() -> Mesh {
    let mut b = Builder::default();
    b.ellipsoid(Vec3::splat(10.0), 8, 12);
    b.mesh()
}

/// The rocket: a 32-unit body along +x.
pub fn rocket() -> Mesh {
    let mut b = Builder::default();
    b.cuboid(Vec3::ZERO, Vec3::new(16.0, 3.0, 3.0), |p| p, Mat3::IDENTITY);
    b.mesh()
}

/// The view weapon: a body and a barrel along +x, in the view's axes, held low and to the
/// right (-y) of the eye.
pub fn weapon() -> Mesh {
    let mut b = Builder::default();
    b.cuboid(Vec3::new(16.0, -8.0, -10.0), Vec3::new(5.0, 1.6, 2.0), |p| p, Mat3::IDENTITY);
    b.cuboid(Vec3::new(25.0, -8.0, -9.5), Vec3::new(5.0, 0.8, 0.8), |p| p, Mat3::IDENTITY);
    b.mesh()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle of every frame is clockwise seen from outside (its right-hand normal
    /// points inwards, against the vertex normals).
    fn clockwise_from_outside(mesh: &Mesh) {
        for frame in &mesh.frames {
            for t in mesh.indexes.chunks(3) {
                let v = |i: usize| frame[t[i] as usize];
                let n = (v(1).0 - v(0).0).cross(v(2).0 - v(0).0);
                if n.length() > 1e-4 {
                    assert!(n.dot(v(0).1 + v(1).1 + v(2).1) < 0.0, "{t:?}");
                }
            }
        }
    }

    #[test]
    fn models_are_wound_clockwise_from_outside() {
        for mesh in [player(), armour(), head(), rocket(), weapon()] {
            clockwise_from_outside(&mesh);
            assert!(mesh.frames.iter().all(|f| f.len() == mesh.st.len()));
            assert!(mesh.indexes.iter().all(|&i| (i as usize) < mesh.st.len()));
        }
    }

    #[test]
    fn the_walk_cycle_moves_the_legs() {
        let p = player();
        assert_eq!(p.frames.len(), WALK_FRAMES);
        // Vertex 0 is on the left leg: it moves between frames 0 and 2, feet stay above z -1.
        assert!(p.frames[0][0].0.distance(p.frames[2][0].0) > 4.0);
        assert!(p.frames.iter().flatten().all(|v| v.0.z > -1.0 && v.0.z < 70.0));
        assert_eq!(p.indexes.len(), 6 * 6 * 6);
    }
}

//! Recovering the camera. OpenGL 1.x gives only modelview = view · model. The world frame is
//! the object space of a reference static draw (Quake-like engines draw the world with
//! modelview = view, so their world is that object space): each frame, every traced draw that
//! matched a static instance of the previous frame exactly proposes a view, its modelview
//! times the inverse of its previous model matrix. The previous reference and the three
//! largest such draws are tried; the view that puts the most triangles back where they were
//! wins (ties: the previous reference), so the view survives the reference leaving the screen
//! (the other static draws chain it) and a reference that starts moving.
//!
//! When no draw matched a static instance (Quake 3 re-batches its world surfaces every frame,
//! so hardly any draw matches exactly), the world frame is taken to be the object space of the
//! largest perspective draw (model = identity, as Quake-like engines draw their world): the
//! frame is continuous with the previous one unless that puts the camera far away.
//!
//! A camera cut (teleport, level change) is declared when the camera moved more than half the
//! scale of the scene (the largest reference draw since the last cut) in one frame, or when the
//! view was lost (no perspective draw); the world frame is then re-established on the largest
//! perspective draw and the persistent static world is cleared.

use glam::{Mat4, Vec3};

use crate::frame::class::{View, orthographic};

/// What view recovery needs of a traced draw.
#[derive(Clone, Copy, Debug)]
pub struct ViewInput<'a> {
    /// Instance id.
    pub id: u64,
    /// Modelview.
    pub modelview: Mat4,
    /// Projection.
    pub projection: Mat4,
    /// Triangle count.
    pub triangles: usize,
    /// Model matrix of the static instance it matched exactly in the previous frame.
    pub previous_model: Option<Mat4>,
    /// Object-space positions (for its size, when it becomes the reference).
    pub positions: &'a [[f32; 4]],
}

/// Whether `a` and `b` place geometry alike: each column within 1e-5 relative.
pub fn same_place(a: &Mat4, b: &Mat4) -> bool {
    (0..4).all(|c| {
        let (x, y) = (a.col(c), b.col(c));
        (x - y).abs().max_element() <= 1e-5 * (1.0 + y.abs().max_element())
    })
}

/// Whether `model` is the identity (geometry already in the world frame).
pub fn is_identity(model: &Mat4) -> bool {
    same_place(model, &Mat4::IDENTITY)
}

/// The reference draw.
#[derive(Clone, Copy, Debug)]
struct Reference {
    id: u64,
    /// Diagonal of its bounding box.
    size: f32,
}

/// The view of a frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct Recovered {
    /// The camera, when a perspective traced draw exists.
    pub view: Option<View>,
    /// The world frame was re-established.
    pub cut: bool,
}

/// The reference and the last view, across frames.
#[derive(Default)]
pub struct ViewTracker {
    reference: Option<Reference>,
    last: Option<Mat4>,
    /// The largest reference size since the world frame was established: the scale of a
    /// "large jump".
    scale: f32,
}

/// Diagonal of the bounding box of `positions`.
fn size_of(positions: &[[f32; 4]]) -> f32 {
    let (lo, hi) = positions.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), p| {
        let v = Vec3::new(p[0], p[1], p[2]);
        (lo.min(v), hi.max(v))
    });
    if positions.is_empty() { 0.0 } else { (hi - lo).length() }
}

impl ViewTracker {
    /// The view of a frame whose traced draws are `inputs`.
    pub fn recover(&mut self, inputs: &[ViewInput<'_>]) -> Recovered {
        let had_view = self.last.is_some();
        let eye = |v: &Mat4| v.inverse().w_axis.truncate();
        let jump = |view: &Mat4, scale: f32| self.last.is_some_and(|last| eye(view).distance(eye(&last)) > 0.5 * scale);
        let chained = self.chain(inputs).filter(|(view, _)| !jump(view, self.scale));
        let (view, (reference, projection), cut) = match chained {
            Some((view, reference)) => (view, reference, false),
            None => {
                // A flattening modelview (planar shadows) cannot be a view.
                let perspective = |i: &&ViewInput| !orthographic(&i.projection) && i.modelview.determinant().abs() > 1e-12;
                let Some(largest) = inputs.iter().filter(perspective).max_by_key(|i| i.triangles) else {
                    (self.reference, self.last, self.scale) = (None, None, 0.0);
                    return Recovered { view: None, cut: had_view };
                };
                let reference = Reference { id: largest.id, size: size_of(largest.positions) };
                let cut = had_view && jump(&largest.modelview, self.scale.max(reference.size));
                (largest.modelview, (reference, largest.projection), cut)
            }
        };
        self.scale = if cut || !had_view { reference.size } else { self.scale.max(reference.size) };
        (self.reference, self.last) = (Some(reference), Some(view));
        Recovered { view: Some(describe(view, projection, reference.id)), cut }
    }

    /// The view chained from the static draws matched again, with the reference (kept, or a
    /// new one among the draws that agree with the view) and its projection.
    fn chain(&self, inputs: &[ViewInput<'_>]) -> Option<(Mat4, (Reference, Mat4))> {
        let invertible = |m: &Mat4| m.determinant().abs() > 1e-12;
        let known = || {
            inputs.iter().filter(move |i| i.previous_model.is_some_and(|m| invertible(&m)) && !orthographic(&i.projection))
        };
        let previous = self.reference.and_then(|r| known().find(|i| i.id == r.id));
        let mut largest: Vec<&ViewInput> = known().collect();
        largest.sort_by_key(|i| std::cmp::Reverse(i.triangles));
        let candidates = previous.into_iter().chain(largest.iter().copied().take(3));
        let view_of = |i: &ViewInput| i.modelview * i.previous_model.unwrap_or_default().inverse();
        let agrees = |view: &Mat4, i: &ViewInput| i.previous_model.is_some_and(|m| same_place(&(*view * m), &i.modelview));
        let score = |view: &Mat4| known().filter(|i| agrees(view, i)).map(|i| i.triangles).sum::<usize>();
        // The first best wins ties: the previous reference comes first.
        let mut best: Option<(Mat4, usize)> = None;
        for candidate in candidates {
            let view = view_of(candidate);
            let s = score(&view);
            if best.is_none_or(|(_, b)| s > b) {
                best = Some((view, s));
            }
        }
        let (view, _) = best?;
        let reference = match previous.filter(|p| agrees(&view, p)) {
            Some(p) => (self.reference?, p.projection),
            None => {
                let r = largest.iter().find(|i| agrees(&view, i))?;
                (Reference { id: r.id, size: size_of(r.positions) }, r.projection)
            }
        };
        Some((view, reference))
    }
}

/// The camera of `view` seen through `projection` (OpenGL conventions: `glFrustum`,
/// `glOrtho`).
pub fn describe(view: Mat4, projection: Mat4, reference: u64) -> View {
    let p = projection;
    let (c, d) = (p.z_axis.z, p.w_axis.z);
    let perspective = !orthographic(&p);
    let (near, far, fov_y) = if perspective {
        (d / (c - 1.0), d / (c + 1.0), 2.0 * (1.0 / p.y_axis.y).atan())
    } else {
        ((d + 1.0) / c, (d - 1.0) / c, 0.0)
    };
    let aspect = if p.x_axis.x != 0.0 { p.y_axis.y / p.x_axis.x } else { 0.0 };
    View { view, projection, perspective, near, far, fov_y, aspect, reference }
}

/// `gluPerspective` (`fov_y` in radians), for tests.
#[cfg(test)]
pub fn perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let f = 1.0 / (fov_y / 2.0).tan();
    let (c, d) = (-(far + near) / (far - near), -2.0 * far * near / (far - near));
    Mat4::from_cols_array(&[f / aspect, 0.0, 0.0, 0.0, 0.0, f, 0.0, 0.0, 0.0, 0.0, c, -1.0, 0.0, 0.0, d, 0.0])
}

/// `glOrtho`, for tests.
#[cfg(test)]
pub fn ortho(l: f32, r: f32, b: f32, t: f32, n: f32, f: f32) -> Mat4 {
    let (sx, sy, sz) = (2.0 / (r - l), 2.0 / (t - b), -2.0 / (f - n));
    let (tx, ty, tz) = (-(r + l) / (r - l), -(t + b) / (t - b), -(f + n) / (f - n));
    Mat4::from_cols_array(&[sx, 0.0, 0.0, 0.0, 0.0, sy, 0.0, 0.0, 0.0, 0.0, sz, 0.0, tx, ty, tz, 1.0])
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUAD: [[f32; 4]; 3] = [[0.0, 0.0, 0.0, 1.0], [10.0, 0.0, 0.0, 1.0], [0.0, 10.0, 0.0, 1.0]];

    fn input(id: u64, modelview: Mat4, previous_model: Option<Mat4>, triangles: usize) -> ViewInput<'static> {
        let projection = perspective(1.2, 1.5, 0.1, 100.0);
        ViewInput { id, modelview, projection, triangles, previous_model, positions: &QUAD }
    }

    #[test]
    fn projection_parameters_are_recovered() {
        let v = describe(Mat4::IDENTITY, perspective(1.2, 1.5, 0.1, 100.0), 1);
        assert!(v.perspective && (v.fov_y - 1.2).abs() < 1e-5 && (v.aspect - 1.5).abs() < 1e-5);
        assert!((v.near - 0.1).abs() < 1e-5 && (v.far - 100.0).abs() < 0.05, "{} {}", v.near, v.far);
        let o = describe(Mat4::IDENTITY, ortho(0.0, 640.0, 0.0, 480.0, -1.0, 5.0), 1);
        assert!(!o.perspective && (o.near + 1.0).abs() < 1e-5 && (o.far - 5.0).abs() < 1e-4);
    }

    #[test]
    fn view_chains_when_the_reference_leaves_and_cuts_on_a_jump() {
        let mut t = ViewTracker::default();
        let placed = Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0));
        let v0 = Mat4::from_rotation_y(0.1) * Mat4::from_translation(Vec3::new(0.0, -2.0, -5.0));
        let r = t.recover(&[input(1, v0, None, 100), input(2, v0 * placed, None, 10)]);
        assert_eq!((r.view.unwrap().view, r.view.unwrap().reference, r.cut), (v0, 1, false));
        // The camera turns; the reference (1) is no longer drawn: draw 2 chains the view.
        let v1 = Mat4::from_rotation_y(0.15) * Mat4::from_translation(Vec3::new(0.0, -2.0, -5.0));
        let r = t.recover(&[input(2, v1 * placed, Some(placed), 10)]);
        let view = r.view.unwrap();
        assert!(same_place(&view.view, &v1) && !r.cut && view.reference == 2);
        // A moving draw does not drag the view: the static majority wins.
        let moved = Mat4::from_translation(Vec3::new(0.0, 1.0, 0.0));
        let r = t.recover(&[input(3, v1 * moved, Some(Mat4::IDENTITY), 50), input(2, v1 * placed, Some(placed), 10), input(4, v1, Some(Mat4::IDENTITY), 60)]);
        assert!(same_place(&r.view.unwrap().view, &v1) && !r.cut);
        // A teleport far away (more than half the reference's size): a cut.
        let far = Mat4::from_translation(Vec3::new(0.0, 0.0, -500.0)) * v1;
        let r = t.recover(&[input(4, far, Some(Mat4::IDENTITY), 60)]);
        assert!(r.cut && r.view.unwrap().view == far);
        // No perspective draw: no view, and the loss is a cut.
        assert!(t.recover(&[]).cut);
        assert!(!t.recover(&[]).cut);
    }
}

//! Bernstein polynomial evaluation for the evaluators (OpenGL 1.5 section 5.1, equations 5.1
//! to 5.3): de Casteljau's algorithm on the control points, with the first derivative, for
//! curves and tensor-product surfaces. Pure functions of the control points.

/// A curve's value and its derivative with respect to the normalized parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePoint {
    /// p(t).
    pub value: Vec<f64>,
    /// dp/dt.
    pub derivative: Vec<f64>,
}

/// Evaluates the Bernstein curve of `order` control points of `k` components each (stored one
/// after the other in `points`) at `t` (0 at the first point, 1 at the last).
pub fn curve(points: &[f64], k: usize, order: usize, t: f64) -> CurvePoint {
    let mut work: Vec<f64> = points[..order * k].to_vec();
    if order == 1 {
        return CurvePoint { value: work, derivative: vec![0.0; k] };
    }
    // de Casteljau: reduce to two points; their difference gives the derivative.
    for level in (2..order).rev() {
        for i in 0..level {
            for c in 0..k {
                work[i * k + c] = (1.0 - t) * work[i * k + c] + t * work[(i + 1) * k + c];
            }
        }
    }
    let n = (order - 1) as f64;
    let value = (0..k).map(|c| (1.0 - t) * work[c] + t * work[k + c]).collect();
    let derivative = (0..k).map(|c| n * (work[k + c] - work[c])).collect();
    CurvePoint { value, derivative }
}

/// A surface's value and partial derivatives with respect to the normalized parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfacePoint {
    /// p(u, v).
    pub value: Vec<f64>,
    /// ∂p/∂u.
    pub du: Vec<f64>,
    /// ∂p/∂v.
    pub dv: Vec<f64>,
}

/// Evaluates the tensor-product Bernstein surface of `uorder` × `vorder` control points of `k`
/// components (point (i, j) at `(i * vorder + j) * k`) at (`u`, `v`).
pub fn surface(points: &[f64], k: usize, uorder: usize, vorder: usize, u: f64, v: f64) -> SurfacePoint {
    // Each row i (fixed u index) is a curve in v; its value and v-derivative are control
    // points of curves in u.
    let mut along_v = Vec::with_capacity(uorder * k);
    let mut along_v_dv = Vec::with_capacity(uorder * k);
    for i in 0..uorder {
        let row = curve(&points[i * vorder * k..(i + 1) * vorder * k], k, vorder, v);
        along_v.extend(row.value);
        along_v_dv.extend(row.derivative);
    }
    let p = curve(&along_v, k, uorder, u);
    let dv = curve(&along_v_dv, k, uorder, u).value;
    SurfacePoint { value: p.value, du: p.derivative, dv }
}

/// The analytic normal of `AUTO_NORMAL` (section 5.1): ∂p/∂u × ∂p/∂v, normalized; for a
/// four-component map the partials of the projected point (x/w, y/w, z/w) are used, scaled by
/// w² (which the normalization removes). A degenerate patch gives the zero vector.
pub fn auto_normal(p: &SurfacePoint) -> [f64; 3] {
    let (du, dv) = if p.value.len() == 4 {
        let w = p.value[3];
        let proj = |d: &[f64]| -> [f64; 3] { std::array::from_fn(|c| d[c] * w - d[3] * p.value[c]) };
        (proj(&p.du), proj(&p.dv))
    } else {
        (std::array::from_fn(|c| p.du[c]), std::array::from_fn(|c| p.dv[c]))
    };
    let n = [du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len == 0.0 { [0.0; 3] } else { n.map(|c| c / len) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn cubic_matches_bernstein_polynomials() {
        // 1D cubic with scalar control points 0, 1, 3, 2 at t = 0.25:
        // B0 = 0.421875, B1 = 0.421875, B2 = 0.140625, B3 = 0.015625.
        let pts = [0.0, 1.0, 3.0, 2.0];
        let p = curve(&pts, 1, 4, 0.25);
        let expected = 0.421875 + 3.0 * 0.140625 + 2.0 * 0.015625;
        assert!(close(&p.value, &[expected]), "{:?}", p.value);
        // Derivative: 3 * sum of B_i^2(t) * (P_{i+1} - P_i), B^2 at 0.25 = 0.5625, 0.375, 0.0625.
        let d = 3.0 * (0.5625 * 1.0 + 0.375 * 2.0 - 0.0625 * 1.0);
        assert!(close(&p.derivative, &[d]), "{:?}", p.derivative);
        assert!(close(&curve(&pts, 1, 4, 0.0).value, &[0.0]));
        assert!(close(&curve(&pts, 1, 4, 1.0).value, &[2.0]));
    }

    #[test]
    fn bilinear_patch_interpolates_corners() {
        // Corners (i, j): (0,0)=0, (0,1)=10, (1,0)=20, (1,1)=40 (one component).
        let pts = [0.0, 10.0, 20.0, 40.0];
        let p = surface(&pts, 1, 2, 2, 0.5, 0.25);
        // (1-u)(1-v)*0 + (1-u)v*10 + u(1-v)*20 + uv*40
        let expected = 0.5 * 0.25 * 10.0 + 0.5 * 0.75 * 20.0 + 0.5 * 0.25 * 40.0;
        assert!(close(&p.value, &[expected]));
        assert!(close(&p.du, &[(1.0 - 0.25) * 20.0 + 0.25 * 30.0]));
        assert!(close(&p.dv, &[0.5 * 10.0 + 0.5 * 20.0]));
    }

    #[test]
    fn plane_normal_is_unit_cross_product() {
        // Plane z = 0 spanned by u along +x (scaled 2) and v along +y: normal +z.
        let pts = [0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 2.0, 1.0, 0.0];
        let n = auto_normal(&surface(&pts, 3, 2, 2, 0.3, 0.7));
        assert!(close(&n, &[0.0, 0.0, 1.0]), "{n:?}");
        // Same plane with homogeneous w = 2 everywhere: the projected normal is unchanged.
        let pts4: Vec<f64> = pts.chunks(3).flat_map(|c| [c[0] * 2.0, c[1] * 2.0, c[2] * 2.0, 2.0]).collect();
        let n4 = auto_normal(&surface(&pts4, 4, 2, 2, 0.3, 0.7));
        assert!(close(&n4, &[0.0, 0.0, 1.0]), "{n4:?}");
    }
}

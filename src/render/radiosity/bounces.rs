//! Light bounced between patches (seed 004, eqs. 1–7): the colour matrix
//! `F^C_ij = F_ij · colour_i`, the k-bounce matrix `F^k = Σ_{h=1..k} (F^C)^h` that gives the
//! secondary light of `k` bounces in one product, the classic gathering step it replaces, and
//! the Neumann series summed to convergence (every bounce), the reference for both.
//!
//! Notation as in the seed: `incident⁽⁰⁾` is the primary light leaving each patch (emission,
//! and per frame the direct light it reflects), `incident⁽ʰ⁺¹⁾ = colours ∘ (F · incident⁽ʰ⁾)`,
//! and the secondary light after `k` bounces is `Σ_{h=1..k} incident⁽ʰ⁾ = F^k · incident⁽⁰⁾`.
//! The radiosity of a patch is its primary light plus its secondary light.

use glam::Vec3;

use super::form_factors::FormFactors;
use super::matrix::ColourMatrix;
use super::progress::Progress;

/// The colour matrix: `F_ij` times receiver `i`'s albedo, per channel (eq. 4).
pub fn colour_matrix(f: &FormFactors, albedo: &[Vec3]) -> ColourMatrix {
    let n = f.n;
    let mut m = ColourMatrix::zeros(n);
    for c in 0..3 {
        for (i, row) in m.channels[c].chunks_mut(n.max(1)).enumerate().take(n) {
            for (x, &fij) in row.iter_mut().zip(f.row(i)) {
                *x = fij * albedo[i][c];
            }
        }
    }
    m
}

/// The k-bounce matrix `Σ_{h=1..k} (F^C)^h` (eq. 7), by Horner's rule:
/// `S_1 = F^C`, `S_{h+1} = F^C + F^C · S_h` (`k − 1` products, their rows counted on
/// `progress`). `k = 0` gives the zero matrix.
pub fn k_bounce(colour: &ColourMatrix, k: u32, progress: Progress) -> ColourMatrix {
    if k == 0 {
        return ColourMatrix::zeros(colour.n);
    }
    let stage = progress.stage(&format!("k-bounce matrix (k = {k})"), u64::from(k - 1) * 3 * colour.n as u64, "rows");
    let mut sum = colour.clone();
    for _ in 1..k {
        sum = colour.multiply(&sum, &|rows| stage.add(rows));
        sum.add(colour);
    }
    stage.finish();
    sum
}

/// One bounce of classic gathering radiosity (eqs. 2–3): `colours ∘ (F · incident)`.
pub fn gather(f: &FormFactors, albedo: &[Vec3], incident: &[Vec3]) -> Vec<Vec3> {
    (0..f.n)
        .map(|i| {
            let mut sum = [0.0f64; 3];
            for (&fij, x) in f.row(i).iter().zip(incident) {
                for (c, s) in sum.iter_mut().enumerate() {
                    *s += f64::from(fij) * f64::from(x[c]);
                }
            }
            Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32) * albedo[i]
        })
        .collect()
}

/// The secondary light of every bounce: the Neumann series `Σ_{h≥1} incident⁽ʰ⁾`, summed by
/// [`gather`] until a bounce adds less than `tolerance` times the sum on every patch and
/// channel (or `max_bounces` were summed); or the same fixed point by [`gauss_seidel`].
#[derive(Clone, Debug, PartialEq)]
pub struct Converged {
    /// The secondary light per patch.
    pub secondary: Vec<Vec3>,
    /// Bounces summed (Jacobi gathering), or sweeps made ([`gauss_seidel`]).
    pub bounces: u32,
}

/// See [`Converged`].
pub fn neumann(f: &FormFactors, albedo: &[Vec3], primary: &[Vec3], tolerance: f32, max_bounces: u32) -> Converged {
    let mut incident = primary.to_vec();
    let mut secondary = vec![Vec3::ZERO; f.n];
    for bounce in 1..=max_bounces {
        incident = gather(f, albedo, &incident);
        let mut settled = true;
        for (s, x) in secondary.iter_mut().zip(&incident) {
            *s += *x;
            settled &= x.cmple(s.abs() * tolerance).all();
        }
        if settled {
            return Converged { secondary, bounces: bounce };
        }
    }
    Converged { secondary, bounces: max_bounces }
}

/// The secondary light of every bounce by Gauss–Seidel gathering: sweeps over the patches in
/// order, each setting its radiosity `B_i = primary_i + colour_i ∘ Σ_j F_ij B_j` from the
/// newest values (this sweep's for the patches before it), until a sweep changes no patch's
/// secondary light `B_i − primary_i` by more than `tolerance` times itself on any channel (or
/// `max_sweeps` were made). It converges to [`neumann`]'s fixed point in fewer sweeps than
/// Jacobi's bounces, each sweep costing one bounce's `n²` multiply-adds per channel.
pub fn gauss_seidel(f: &FormFactors, albedo: &[Vec3], primary: &[Vec3], tolerance: f32, max_sweeps: u32) -> Converged {
    let mut b: Vec<[f64; 3]> = primary.iter().map(|p| [p.x, p.y, p.z].map(f64::from)).collect();
    for sweep in 1..=max_sweeps {
        let mut settled = true;
        for i in 0..f.n {
            let mut sum = [0.0f64; 3];
            for (&fij, x) in f.row(i).iter().zip(&b) {
                for (c, s) in sum.iter_mut().enumerate() {
                    *s += f64::from(fij) * x[c];
                }
            }
            for c in 0..3 {
                let new = f64::from(primary[i][c]) + f64::from(albedo[i][c]) * sum[c];
                let secondary = new - f64::from(primary[i][c]);
                settled &= (new - b[i][c]).abs() <= secondary.abs() * f64::from(tolerance);
                b[i][c] = new;
            }
        }
        if settled {
            return Converged { secondary: secondary_of(&b, primary), bounces: sweep };
        }
    }
    Converged { secondary: secondary_of(&b, primary), bounces: max_sweeps }
}

/// `b − primary`, per patch.
fn secondary_of(b: &[[f64; 3]], primary: &[Vec3]) -> Vec<Vec3> {
    b.iter().zip(primary).map(|(b, p)| Vec3::new(b[0] as f32, b[1] as f32, b[2] as f32) - *p).collect()
}

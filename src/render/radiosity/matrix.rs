//! A dense colour matrix: one `n × n` matrix per colour channel (seed 004 eq. 4: the colour
//! matrix holds the light reflected per channel), with the products radiosity needs.

use glam::Vec3;
use rayon::prelude::*;

/// Result rows of one task of [`ColourMatrix::multiply`].
const ROWS: usize = 16;
/// Inner indices of one block: with [`COLUMNS`], 512 KiB of the right factor, kept in L2.
const INNER: usize = 128;
/// Columns of one block.
const COLUMNS: usize = 1024;

/// Three row-major `n × n` matrices, red, green and blue: entry `(i, j)` of channel `c` is
/// `channels[c][i * n + j]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ColourMatrix {
    /// Rows and columns.
    pub n: usize,
    /// The channels.
    pub channels: [Vec<f32>; 3],
}

impl ColourMatrix {
    /// The zero matrix.
    pub fn zeros(n: usize) -> ColourMatrix {
        ColourMatrix { n, channels: std::array::from_fn(|_| vec![0.0; n * n]) }
    }

    /// Entry `(i, j)` of the three channels.
    pub fn get(&self, i: usize, j: usize) -> Vec3 {
        let k = i * self.n + j;
        Vec3::new(self.channels[0][k], self.channels[1][k], self.channels[2][k])
    }

    /// Sets entry `(i, j)` of the three channels.
    pub fn set(&mut self, i: usize, j: usize, v: Vec3) {
        let k = i * self.n + j;
        for c in 0..3 {
            self.channels[c][k] = v[c];
        }
    }

    /// The matrix with rows and columns both permuted by `order`: entry `(a, b)` is
    /// `self`'s `(order[a], order[b])`.
    pub fn permuted(&self, order: &[u32]) -> ColourMatrix {
        ColourMatrix { n: self.n, channels: std::array::from_fn(|c| super::reorder::permute_square(&self.channels[c], self.n, order)) }
    }

    /// `self · v`, channel by channel (f64 sums).
    pub fn apply(&self, v: &[Vec3]) -> Vec<Vec3> {
        let n = self.n;
        (0..n)
            .map(|i| {
                let mut sum = [0.0f64; 3];
                for (c, s) in sum.iter_mut().enumerate() {
                    let row = &self.channels[c][i * n..(i + 1) * n];
                    *s = row.iter().zip(v).map(|(&m, x)| f64::from(m) * f64::from(x[c])).sum();
                }
                Vec3::new(sum[0] as f32, sum[1] as f32, sum[2] as f32)
            })
            .collect()
    }

    /// `self · other`, channel by channel, on every core; `rows_done` is told of each block
    /// of result rows finished (`3 n` rows in all). Cache-blocked ([`ROWS`] result rows,
    /// [`INNER`] inner indices, [`COLUMNS`] columns a block); each entry's sum still runs over
    /// the inner index in order, so the result is the plain i-k-j product's, bit for bit.
    pub fn multiply(&self, other: &ColourMatrix, rows_done: &(dyn Fn(u64) + Sync)) -> ColourMatrix {
        let n = self.n;
        let mut out = ColourMatrix::zeros(n);
        if n == 0 {
            return out;
        }
        for c in 0..3 {
            let (a, b) = (&self.channels[c], &other.channels[c]);
            out.channels[c].par_chunks_mut(ROWS * n).enumerate().for_each(|(t, rows)| {
                block_rows(a, b, n, t * ROWS, rows);
                rows_done((rows.len() / n) as u64);
            });
        }
        out
    }

    /// Adds `other` entry by entry.
    pub fn add(&mut self, other: &ColourMatrix) {
        for (a, b) in self.channels.iter_mut().zip(&other.channels) {
            for (x, y) in a.iter_mut().zip(b) {
                *x += y;
            }
        }
    }

    /// Bytes of the three dense f32 matrices.
    pub fn bytes(&self) -> usize {
        3 * self.n * self.n * size_of::<f32>()
    }
}

/// Rows `first..` of `a · b` (`n × n` each) into `rows` (zeroed, whole rows), block by block:
/// with AVX2 where the CPU has it (the same operations, 8 lanes instead of 4: the same sums).
fn block_rows(a: &[f32], b: &[f32], n: usize, first: usize, rows: &mut [f32]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // Safety: the CPU has AVX2.
        return unsafe { block_rows_avx2(a, b, n, first, rows) };
    }
    block_rows_portable(a, b, n, first, rows);
}

/// [`block_rows_portable`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn block_rows_avx2(a: &[f32], b: &[f32], n: usize, first: usize, rows: &mut [f32]) {
    block_rows_portable(a, b, n, first, rows);
}

/// See [`block_rows`]: per block of columns and inner indices, each row adds `a[i][k] · b[k]`
/// for `k` in order (the i-k-j product's order for every entry).
#[inline(always)]
fn block_rows_portable(a: &[f32], b: &[f32], n: usize, first: usize, rows: &mut [f32]) {
    let height = rows.len() / n;
    for j0 in (0..n).step_by(COLUMNS) {
        let j1 = (j0 + COLUMNS).min(n);
        for k0 in (0..n).step_by(INNER) {
            let k1 = (k0 + INNER).min(n);
            for r in 0..height {
                let i = first + r;
                let row = &mut rows[r * n + j0..r * n + j1];
                for k in k0..k1 {
                    let x = a[i * n + k];
                    if x != 0.0 {
                        for (o, &y) in row.iter_mut().zip(&b[k * n + j0..k * n + j1]) {
                            *o += x * y;
                        }
                    }
                }
            }
        }
    }
}

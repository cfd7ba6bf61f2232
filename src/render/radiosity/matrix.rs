//! A dense colour matrix: one `n × n` matrix per colour channel (seed 004 eq. 4: the colour
//! matrix holds the light reflected per channel), with the products radiosity needs.

use glam::Vec3;

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

    /// `self · other`, channel by channel (rows on every available core).
    pub fn multiply(&self, other: &ColourMatrix) -> ColourMatrix {
        let n = self.n;
        let mut out = ColourMatrix::zeros(n);
        let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
        let rows_per_thread = n.div_ceil(threads).max(1);
        for c in 0..3 {
            let (a, b) = (&self.channels[c], &other.channels[c]);
            std::thread::scope(|s| {
                for (t, rows) in out.channels[c].chunks_mut(rows_per_thread * n.max(1)).enumerate() {
                    s.spawn(move || {
                        for (k, row) in rows.chunks_mut(n).enumerate() {
                            let i = t * rows_per_thread + k;
                            // i-k-j order: rows of `b` are read contiguously.
                            for (m, &x) in a[i * n..(i + 1) * n].iter().enumerate() {
                                if x != 0.0 {
                                    for (r, &y) in row.iter_mut().zip(&b[m * n..(m + 1) * n]) {
                                        *r += x * y;
                                    }
                                }
                            }
                        }
                    });
                }
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

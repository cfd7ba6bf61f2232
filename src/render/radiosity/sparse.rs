//! The exact part of a compressed matrix (seed 004, §4.2): the top share of its entries by
//! size, the few large form factors whose errors would show, kept as they are in compressed
//! sparse rows; the rest of the matrix is quantised.

use glam::Vec3;
use rayon::prelude::*;

use super::matrix::ColourMatrix;

/// Entries of a colour matrix by row: row `i`'s entries are `offsets[i]..offsets[i + 1]` of
/// `columns` and `values`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SparseRows {
    /// Start of each row, and the end of the last.
    pub offsets: Vec<u32>,
    /// Column of each entry.
    pub columns: Vec<u32>,
    /// Value of each entry, per channel.
    pub values: Vec<[f32; 3]>,
}

impl SparseRows {
    /// Entry count.
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Whether no entry is kept.
    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }

    /// Bytes of the three arrays.
    pub fn bytes(&self) -> usize {
        self.offsets.len() * 4 + self.columns.len() * 4 + self.values.len() * 12
    }

    /// Adds every entry into `m`.
    pub fn add_to(&self, m: &mut ColourMatrix) {
        for i in 0..self.offsets.len().saturating_sub(1) {
            for k in self.offsets[i] as usize..self.offsets[i + 1] as usize {
                let (j, v) = (self.columns[k] as usize, Vec3::from(self.values[k]));
                m.set(i, j, m.get(i, j) + v);
            }
        }
    }
}

/// Splits `m` into its largest `share` (0..=1) of entries, ranked by their largest channel
/// (ties by position, zeros never kept), and the rest (those entries zeroed). The cut is found
/// from histograms of the sizes ([`threshold`]), so no ranking of the `n²` entries is held and
/// the positions never wrap (`n` past 65,535).
pub fn split_top(m: &ColourMatrix, share: f32) -> (SparseRows, ColourMatrix) {
    let n = m.n;
    let size = |k: usize| m.channels[0][k].max(m.channels[1][k]).max(m.channels[2][k]);
    let keep = ((share.clamp(0.0, 1.0) as f64) * (n * n) as f64).round() as usize;
    let mut rest = m.clone();
    let mut sparse = SparseRows { offsets: vec![0; n + 1], ..SparseRows::default() };
    if let Some((cut, mut ties)) = threshold(n * n, keep, &size) {
        for k in 0..n * n {
            let s = size(k);
            let kept = s > 0.0 && (s.to_bits() > cut || (s.to_bits() == cut && ties > 0));
            if !kept {
                continue;
            }
            if s.to_bits() == cut {
                ties -= 1;
            }
            let (i, j) = (k / n, k % n);
            sparse.offsets[i + 1] += 1;
            sparse.columns.push(j as u32);
            sparse.values.push(m.get(i, j).to_array());
            rest.set(i, j, Vec3::ZERO);
        }
    }
    for i in 0..n {
        sparse.offsets[i + 1] += sparse.offsets[i];
    }
    (sparse, rest)
}

/// Of the positive sizes `size(k)`, `k < count`, the `keep` largest (ties to the smaller `k`;
/// all of them when fewer are positive): the bits of the smallest size kept, and how many of
/// the sizes equal to it are kept (the first ones). `None` when none is kept.
///
/// Positive `f32`s order as their bits, so a histogram of the high 16 bits finds the bucket
/// that holds the cut, and one of the low 16 bits of that bucket's sizes finds the cut exactly:
/// two passes over the sizes, on every core, and counts that can be summed band by band.
pub fn threshold(count: usize, keep: usize, size: &(dyn Fn(usize) -> f32 + Sync)) -> Option<(u32, usize)> {
    let histogram = |bucket: &(dyn Fn(u32) -> Option<u32> + Sync)| {
        (0..count)
            .into_par_iter()
            .with_min_len(1 << 16)
            .fold(
                || vec![0usize; 1 << 16],
                |mut h, k| {
                    let s = size(k);
                    if let Some(b) = (s > 0.0).then(|| bucket(s.to_bits())).flatten() {
                        h[b as usize] += 1;
                    }
                    h
                },
            )
            .reduce(|| vec![0usize; 1 << 16], |mut a, b| {
                a.iter_mut().zip(b).for_each(|(x, y)| *x += y);
                a
            })
    };
    let high = histogram(&|bits| Some(bits >> 16));
    let keep = keep.min(high.iter().sum());
    let (bucket, above) = cut(&high, keep)?;
    let low = histogram(&|bits| (bits >> 16 == bucket).then_some(bits & 0xffff));
    let (bits, above_in_bucket) = cut(&low, keep - above)?;
    Some((bucket << 16 | bits, keep - above - above_in_bucket))
}

/// The bucket of `h` (counted from the top) that holds the `keep`-th largest entry, and the
/// entries in the buckets above it; `None` when `keep` is 0 or past the count.
fn cut(h: &[usize], keep: usize) -> Option<(u32, usize)> {
    let mut above = 0;
    for (b, &c) in h.iter().enumerate().rev() {
        if keep > 0 && above + c >= keep {
            return Some((b as u32, above));
        }
        above += c;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_top_share_is_kept_exactly_and_the_rest_is_zeroed_there() {
        let mut m = ColourMatrix::zeros(4);
        for k in 0..16 {
            m.set(k / 4, k % 4, Vec3::new(k as f32, 0.5 * k as f32, 0.0));
        }
        let (sparse, rest) = split_top(&m, 0.25);
        assert_eq!(sparse.len(), 4);
        assert_eq!(sparse.offsets, [0, 0, 0, 0, 4]);
        assert_eq!(sparse.columns, [0, 1, 2, 3]);
        assert_eq!(sparse.values[3], [15.0, 7.5, 0.0]);
        assert_eq!(rest.get(3, 3), Vec3::ZERO);
        assert_eq!(rest.get(2, 3), m.get(2, 3));
        let mut back = rest.clone();
        sparse.add_to(&mut back);
        assert_eq!(back, m);
        // Zeros are never kept: entry 0 is zero.
        let (all, _) = split_top(&m, 1.0);
        assert_eq!(all.len(), 15);
        assert_eq!(all.bytes(), 5 * 4 + 15 * 16);
    }

    /// The ranking `split_top` made before its histograms: every positive entry sorted by
    /// (size, descending; position), the first `share` of the matrix kept.
    fn split_by_ranking(m: &ColourMatrix, share: f32) -> (SparseRows, ColourMatrix) {
        let n = m.n;
        let size = |k: usize| m.channels[0][k].max(m.channels[1][k]).max(m.channels[2][k]);
        let keep = ((share as f64) * (n * n) as f64).round() as usize;
        let mut ranked: Vec<usize> = (0..n * n).filter(|&k| size(k) > 0.0).collect();
        ranked.sort_by(|&a, &b| size(b).total_cmp(&size(a)).then(a.cmp(&b)));
        ranked.truncate(keep);
        ranked.sort_unstable();
        let mut rest = m.clone();
        let mut sparse = SparseRows { offsets: vec![0; n + 1], ..SparseRows::default() };
        for &k in &ranked {
            sparse.offsets[k / n + 1] += 1;
            sparse.columns.push((k % n) as u32);
            sparse.values.push(m.get(k / n, k % n).to_array());
            rest.set(k / n, k % n, Vec3::ZERO);
        }
        for i in 0..n {
            sparse.offsets[i + 1] += sparse.offsets[i];
        }
        (sparse, rest)
    }

    #[test]
    fn the_histogram_cut_keeps_what_a_full_ranking_keeps() {
        // Sizes from a few values (many ties at every cut, sizes in one high bucket and in
        // many), zeros, a channel other than the first the largest.
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for (n, values) in [(37, 5u64), (64, 400), (50, 100_000)] {
            let mut m = ColourMatrix::zeros(n);
            for k in 0..n * n {
                let r = next();
                let v = if r % 7 == 0 { 0.0 } else { ((r >> 8) % values) as f32 * 1.0e-4 };
                m.set(k / n, k % n, Vec3::new(v, v * 0.5, if r % 3 == 0 { v * 1.5 } else { 0.0 }));
            }
            for share in [0.0, 0.001, 0.04, 0.3, 0.9, 1.0] {
                assert_eq!(split_top(&m, share), split_by_ranking(&m, share), "n = {n}, {values} values, share {share}");
            }
        }
    }
}

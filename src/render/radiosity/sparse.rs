//! The exact part of a compressed matrix (seed 004, §4.2): the top share of its entries by
//! size, the few large form factors whose errors would show, kept as they are in compressed
//! sparse rows; the rest of the matrix is quantised.

use glam::Vec3;

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
/// (ties by position, zeros never kept), and the rest (those entries zeroed).
pub fn split_top(m: &ColourMatrix, share: f32) -> (SparseRows, ColourMatrix) {
    let n = m.n;
    let size = |k: usize| m.channels[0][k].max(m.channels[1][k]).max(m.channels[2][k]);
    let keep = ((share.clamp(0.0, 1.0) as f64) * (n * n) as f64).round() as usize;
    let mut ranked: Vec<u32> = (0..(n * n) as u32).filter(|&k| size(k as usize) > 0.0).collect();
    let keep = keep.min(ranked.len());
    if keep < ranked.len() {
        ranked.select_nth_unstable_by(keep, |&a, &b| size(b as usize).total_cmp(&size(a as usize)).then(a.cmp(&b)));
    }
    ranked.truncate(keep);
    ranked.sort_unstable();
    let mut rest = m.clone();
    let mut sparse = SparseRows { offsets: vec![0; n + 1], ..SparseRows::default() };
    for &k in &ranked {
        let (i, j) = (k as usize / n, k as usize % n);
        sparse.offsets[i + 1] += 1;
        sparse.columns.push(j as u32);
        sparse.values.push(m.get(i, j).to_array());
        rest.set(i, j, Vec3::ZERO);
    }
    for i in 0..n {
        sparse.offsets[i + 1] += sparse.offsets[i];
    }
    (sparse, rest)
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
}

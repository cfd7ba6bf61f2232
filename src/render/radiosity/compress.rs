//! The seed's compressed k-bounce matrix (seed 004, §4.2): the top share of entries exact
//! ([`sparse`](super::sparse)), the rest log-quantised ([`quantise`](super::quantise): over
//! the seed's fixed range or one fitted to the values, [`LogRange`]),
//! reordered by greedy passes ([`reorder`](super::reorder), [`Reorder`]) and stored as BC1 blocks
//! ([`bc1`](super::bc1)); and the error of the round trip, as the seed's table reports it
//! (mean, max and summed absolute error over every entry and channel). The kept entries come
//! back exact: the sparse part stores them minus what their texels decode to.

use glam::Vec3;
use rayon::prelude::*;

use super::bc1::Bc1Matrix;
use super::matrix::ColourMatrix;
use super::progress::Progress;
use super::quantise;
use super::reorder::{self, Codes, Search};
use super::sparse::{self, SparseRows};

/// The seed's share of entries kept exactly.
pub const TOP_SHARE: f32 = 0.04;
/// The seed's reordering passes (rows, then columns).
pub const REORDER_PASSES: u32 = 2;

/// How the quantised part is reordered: greedy passes (alternately rows and columns, from
/// rows), each finding the nearest line by `search`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reorder {
    /// Passes.
    pub passes: u32,
    /// How a pass finds the nearest line.
    pub search: Search,
}

impl Reorder {
    /// The seed's two passes, searched by `search`.
    pub const fn seed(search: Search) -> Reorder {
        Reorder { passes: REORDER_PASSES, search }
    }
}

/// How the quantised part is log-scaled ([`quantise`](super::quantise)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogRange {
    /// The seed's: shifted by 25.
    Seed,
    /// Shifted by the span of the values present.
    Fitted,
}

/// A compressed colour matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct CompressedMatrix {
    /// `order[a]`: the patch at row and column `a` of the texture.
    pub order: Vec<u32>,
    /// The largest value of the quantised part (its three channels share it).
    pub max: f32,
    /// The log shift of the quantised part.
    pub shift: f32,
    /// The quantised part, reordered, as BC1.
    pub texture: Bc1Matrix,
    /// The exact part, in patch order: each kept entry minus what its texel decodes to.
    pub sparse: SparseRows,
}

/// Compresses `m`: the `top_share` largest entries exact, the rest quantised over `range`,
/// reordered by `reorder` and BC1-encoded; the passes and the blocks are stages on
/// `progress`.
pub fn compress(m: &ColourMatrix, top_share: f32, reorder: Reorder, range: LogRange, progress: Progress) -> CompressedMatrix {
    let passes = reorder.passes;
    let n = m.n;
    let (sparse, rest) = sparse::split_top(m, top_share);
    let max = rest.channels.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
    let shift = match range {
        LogRange::Seed => quantise::LOG_SHIFT,
        LogRange::Fitted => quantise::fitted_shift(rest.channels.iter().flatten().copied()),
    };
    let mut codes: Codes = std::array::from_fn(|c| rest.channels[c].par_iter().map(|&x| quantise::encode(x, max, shift)).collect());
    let mut order: Vec<u32> = (0..n as u32).collect();
    for pass in 0..passes {
        let by_columns = pass % 2 == 1;
        let search = match reorder.search {
            Search::Exact => "exact search",
            Search::Sketch { .. } => "sketched search",
        };
        let stage = progress.stage(&format!("reordering pass {} of {passes} ({}, {search})", pass + 1, if by_columns { "columns" } else { "rows" }), n as u64, "lines");
        let step = reorder::greedy_order(&codes, n, by_columns, reorder.search, &stage);
        stage.finish();
        codes = reorder::permute(&codes, n, &step);
        order = step.iter().map(|&k| order[k as usize]).collect();
    }
    let stage = progress.stage("BC1 blocks", n.div_ceil(4) as u64, "rows of blocks");
    let texture = Bc1Matrix::encode(&codes, n, &stage);
    stage.finish();
    // The kept entries' texels (zeroed, then blurred by BC1 among large neighbours) decode to
    // something: the sparse part stores the exact value minus it, so the sum is exact.
    let decoded = texture.decode();
    let mut at = vec![0usize; n];
    for (a, &i) in order.iter().enumerate() {
        at[i as usize] = a;
    }
    let mut sparse = sparse;
    for i in 0..n {
        for k in sparse.offsets[i] as usize..sparse.offsets[i + 1] as usize {
            let texel = at[i] * n + at[sparse.columns[k] as usize];
            for c in 0..3 {
                sparse.values[k][c] -= quantise::decode(decoded[c][texel], max, shift);
            }
        }
    }
    CompressedMatrix { order, max, shift, texture, sparse }
}

impl CompressedMatrix {
    /// The matrix the compressed form stands for, in patch order.
    pub fn decompress(&self) -> ColourMatrix {
        let n = self.texture.n;
        let codes = self.texture.decode();
        let mut m = ColourMatrix::zeros(n);
        for (a, &i) in self.order.iter().enumerate() {
            for (b, &j) in self.order.iter().enumerate() {
                let k = a * n + b;
                let v = Vec3::from_array(std::array::from_fn(|c| quantise::decode(codes[c][k], self.max, self.shift)));
                m.set(i as usize, j as usize, v);
            }
        }
        self.sparse.add_to(&mut m);
        m
    }

    /// Bytes: BC1 blocks, the sparse rows and the order.
    pub fn bytes(&self) -> usize {
        self.texture.bytes() + self.sparse.bytes() + self.order.len() * 4
    }
}

/// Absolute errors of an approximation over every entry and channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// Mean.
    pub mean: f64,
    /// Largest.
    pub max: f64,
    /// Sum.
    pub sum: f64,
}

/// The errors of `approx` against `exact` (same size).
pub fn errors(exact: &ColourMatrix, approx: &ColourMatrix) -> Errors {
    let (mut sum, mut max, mut count) = (0.0f64, 0.0f64, 0usize);
    for (a, b) in exact.channels.iter().zip(&approx.channels) {
        for (&x, &y) in a.iter().zip(b) {
            let e = f64::from((x - y).abs());
            sum += e;
            max = max.max(e);
            count += 1;
        }
    }
    Errors { mean: if count == 0 { 0.0 } else { sum / count as f64 }, max, sum }
}

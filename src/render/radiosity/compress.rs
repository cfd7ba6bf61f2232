//! The seed's compressed k-bounce matrix (seed 004, §4.2): the top share of entries exact
//! ([`sparse`](super::sparse)), the rest log-quantised ([`quantise`](super::quantise)),
//! reordered by greedy passes ([`reorder`](super::reorder)) and stored as BC1 blocks
//! ([`bc1`](super::bc1)); and the error of the round trip, as the seed's table reports it
//! (mean, max and summed absolute error over every entry and channel).

use glam::Vec3;

use super::bc1::Bc1Matrix;
use super::matrix::ColourMatrix;
use super::quantise;
use super::reorder::{self, Codes};
use super::sparse::{self, SparseRows};

/// The seed's share of entries kept exactly.
pub const TOP_SHARE: f32 = 0.04;
/// The seed's reordering passes (rows, then columns).
pub const REORDER_PASSES: u32 = 2;

/// A compressed colour matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct CompressedMatrix {
    /// `order[a]`: the patch at row and column `a` of the texture.
    pub order: Vec<u32>,
    /// The largest value of the quantised part (per channel entries share it).
    pub max: f32,
    /// The quantised part, reordered, as BC1.
    pub texture: Bc1Matrix,
    /// The exact part, in patch order.
    pub sparse: SparseRows,
}

/// Compresses `m`: the `top_share` largest entries exact, the rest quantised, reordered by
/// `passes` greedy passes (alternately rows and columns, from rows) and BC1-encoded.
pub fn compress(m: &ColourMatrix, top_share: f32, passes: u32) -> CompressedMatrix {
    let n = m.n;
    let (sparse, rest) = sparse::split_top(m, top_share);
    let max = rest.channels.iter().flatten().fold(0.0f32, |a, &b| a.max(b));
    let mut codes: Codes = std::array::from_fn(|c| rest.channels[c].iter().map(|&x| quantise::encode(x, max)).collect());
    let mut order: Vec<u32> = (0..n as u32).collect();
    for pass in 0..passes {
        let step = reorder::greedy_order(&codes, n, pass % 2 == 1);
        codes = reorder::permute(&codes, n, &step);
        order = step.iter().map(|&k| order[k as usize]).collect();
    }
    CompressedMatrix { order, max, texture: Bc1Matrix::encode(&codes, n), sparse }
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
                let v = Vec3::new(quantise::decode(codes[0][k], self.max), quantise::decode(codes[1][k], self.max), quantise::decode(codes[2][k], self.max));
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

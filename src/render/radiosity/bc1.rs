//! BC1 (DXT1) blocks of a matrix of RGB codes, through `texpresso` (a pure-Rust port of
//! libsquish's encoder): the form the GPU samples the compressed matrix in. Each 4 × 4 block
//! keeps two RGB565 end points and a 2-bit index per texel: 8 bytes for 16 texels. The side is
//! padded to a multiple of 4 with zero codes. Channels are weighted equally (the three
//! channels of a colour matrix matter alike; texpresso defaults to perceptual weights) and
//! fitted by cluster fit, texpresso's default quality.

use rayon::prelude::*;
use texpresso::{Algorithm, COLOUR_WEIGHTS_UNIFORM, Format, Params};

use super::progress::Stage;
use super::reorder::Codes;

/// A BC1 image of an `n × n` matrix of codes.
#[derive(Clone, Debug, PartialEq)]
pub struct Bc1Matrix {
    /// Rows and columns of the matrix.
    pub n: usize,
    /// Side of the encoded image (`n` rounded up to a multiple of 4).
    pub side: usize,
    /// The blocks, row of blocks after row of blocks.
    pub blocks: Vec<u8>,
}

impl Bc1Matrix {
    /// Encodes `codes` (`n × n`), a row of blocks a task on every core, each counted on
    /// `progress` (`side / 4` in all).
    pub fn encode(codes: &Codes, n: usize, progress: &Stage) -> Bc1Matrix {
        let side = n.div_ceil(4) * 4;
        let params = Params { algorithm: Algorithm::ClusterFit, weights: COLOUR_WEIGHTS_UNIFORM, weigh_colour_by_alpha: false };
        let row_bytes = Format::Bc1.compressed_size(side, 4);
        let mut blocks = vec![0u8; Format::Bc1.compressed_size(side, side)];
        blocks.par_chunks_mut(row_bytes.max(1)).enumerate().for_each(|(r, out)| {
            let mut rgba = vec![0u8; side * 4 * 4];
            for y in 0..4 {
                let i = 4 * r + y;
                if i >= n {
                    break;
                }
                for j in 0..n {
                    let at = (y * side + j) * 4;
                    rgba[at..at + 4].copy_from_slice(&[codes[0][i * n + j], codes[1][i * n + j], codes[2][i * n + j], 255]);
                }
            }
            Format::Bc1.compress(&rgba, side, 4, params, out);
            progress.add(1);
        });
        Bc1Matrix { n, side, blocks }
    }

    /// The codes the blocks decode to (`n × n`).
    pub fn decode(&self) -> Codes {
        let (n, side) = (self.n, self.side);
        if side == 0 {
            return std::array::from_fn(|_| Vec::new());
        }
        let mut rgba = vec![0u8; side * side * 4];
        Format::Bc1.decompress(&self.blocks, side, side, &mut rgba);
        std::array::from_fn(|c| (0..n * n).map(|k| rgba[((k / n) * side + k % n) * 4 + c]).collect())
    }

    /// Bytes of the blocks.
    pub fn bytes(&self) -> usize {
        self.blocks.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::progress::Progress;

    #[test]
    fn blocks_are_half_a_byte_a_texel_and_smooth_codes_survive() {
        let n = 6;
        // Ramps along each row, 3 codes a column: a block spans 9 codes per channel.
        let codes: Codes = std::array::from_fn(|c| (0..n * n).map(|k| (100 + 3 * (k % n) + 40 * c) as u8).collect());
        let quiet = || Progress::Quiet.stage("BC1 blocks", 2, "rows of blocks");
        let bc1 = Bc1Matrix::encode(&codes, n, &quiet());
        assert_eq!((bc1.side, bc1.bytes()), (8, 4 * 8));
        let back = bc1.decode();
        for c in 0..3 {
            for k in 0..n * n {
                // Within RGB565 rounding (8 levels in red and blue) and the 4-colour palette.
                assert!(back[c][k].abs_diff(codes[c][k]) <= 6, "{c} {k}: {} vs {}", back[c][k], codes[c][k]);
            }
        }
        // A uniform block is exact up to RGB565 (8 levels in red and blue, 4 in green).
        let flat: Codes = [vec![200; 16], vec![100; 16], vec![40; 16]];
        let back = Bc1Matrix::encode(&flat, 4, &quiet()).decode();
        assert!(back[0].iter().all(|&x| x.abs_diff(200) <= 4) && back[1].iter().all(|&x| x.abs_diff(100) <= 2) && back[2].iter().all(|&x| x.abs_diff(40) <= 4));
    }
}

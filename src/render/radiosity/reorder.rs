//! The seed's greedy reordering (seed 004, §4.2): rows and columns of the quantised matrix
//! are permuted (the same permutation on both, so the matrix still maps patches to patches)
//! so that similar rows, then similar columns, sit together and BC1's 4 × 4 blocks hold
//! similar texels. Finding the best order is a travelling-salesman problem; one greedy pass
//! starts at the first row (column) and repeatedly puts next the nearest one not placed yet,
//! by the sum of absolute differences of their codes over all channels. The seed runs two
//! passes: rows, then columns. Each pass compares every pair: O(n³) byte operations.

use rayon::prelude::*;

use super::progress::Stage;

/// Codes of an `n × n` RGB matrix, row-major.
pub type Codes = [Vec<u8>; 3];

/// The order of one greedy pass over `codes` (`n × n`), by rows or by columns: `order[new]` is
/// the old index placed at `new` (ties to the smaller index). Each line's codes of the three
/// channels are first laid out one after the other, so a distance reads two contiguous runs
/// of `3 n` bytes; each step's search for the nearest line runs on every core, its steps
/// counted on `progress`.
pub fn greedy_order(codes: &Codes, n: usize, by_columns: bool, progress: &Stage) -> Vec<u32> {
    let lines = lines(codes, n, by_columns);
    let line = |a: usize| &lines[a * 3 * n..(a + 1) * 3 * n];
    let mut placed = vec![false; n];
    let mut order = Vec::with_capacity(n);
    let mut current = 0;
    for _ in 0..n {
        placed[current] = true;
        order.push(current as u32);
        progress.add(1);
        let from = line(current);
        let next = (0..n).into_par_iter().with_min_len(SEARCH_GRAIN).filter(|&b| !placed[b]).map(|b| (distance(from, line(b)), b)).min();
        match next {
            Some((_, b)) => current = b,
            None => break,
        }
    }
    order
}

/// The sum of absolute differences of two lines, with AVX2 where the CPU has it.
fn distance(a: &[u8], b: &[u8]) -> u32 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // Safety: the CPU has AVX2.
        return unsafe { distance_avx2(a, b) };
    }
    distance_portable(a, b)
}

/// [`distance`] with AVX2's `vpsadbw`: 32 bytes a step into four 64-bit sums, the tail by
/// [`distance_portable`]; integer sums, so the same distance.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn distance_avx2(a: &[u8], b: &[u8]) -> u32 {
    use std::arch::x86_64::{__m256i, _mm256_add_epi64, _mm256_loadu_si256, _mm256_sad_epu8, _mm256_setzero_si256, _mm256_storeu_si256};
    let len = a.len().min(b.len());
    let whole = len / 32 * 32;
    let mut sums = _mm256_setzero_si256();
    for at in (0..whole).step_by(32) {
        // Safety: `at + 32 <= len`, within both slices; unaligned loads.
        let (x, y) = unsafe { (_mm256_loadu_si256(a[at..].as_ptr().cast::<__m256i>()), _mm256_loadu_si256(b[at..].as_ptr().cast::<__m256i>())) };
        sums = _mm256_add_epi64(sums, _mm256_sad_epu8(x, y));
    }
    let mut lanes = [0u64; 4];
    // Safety: 32 bytes written into 32 bytes.
    unsafe { _mm256_storeu_si256(lanes.as_mut_ptr().cast::<__m256i>(), sums) };
    lanes.iter().sum::<u64>() as u32 + distance_portable(&a[whole..len], &b[whole..len])
}

/// See [`distance`]: u32 sums (vectorised); 3 n · 255 fits below n = 5.6 million.
fn distance_portable(a: &[u8], b: &[u8]) -> u32 {
    a.iter().zip(b).map(|(&x, &y)| u32::from(x.abs_diff(y))).sum()
}

/// Candidates one task of a greedy step compares.
const SEARCH_GRAIN: usize = 64;

/// Row (or column) `a` of every channel, one after the other: `3 n` bytes a line.
fn lines(codes: &Codes, n: usize, by_columns: bool) -> Vec<u8> {
    let mut out = vec![0u8; 3 * n * n];
    out.par_chunks_mut(3 * n.max(1)).enumerate().for_each(|(a, line)| {
        for (c, part) in line.chunks_mut(n).enumerate() {
            if by_columns {
                for (k, x) in part.iter_mut().enumerate() {
                    *x = codes[c][k * n + a];
                }
            } else {
                part.copy_from_slice(&codes[c][a * n..(a + 1) * n]);
            }
        }
    });
    out
}

/// `codes` with rows and columns both permuted by `order` (`order[new]` = old).
pub fn permute(codes: &Codes, n: usize, order: &[u32]) -> Codes {
    std::array::from_fn(|c| {
        let mut out = vec![0u8; n * n];
        out.par_chunks_mut(n.max(1)).zip(order).for_each(|(row, &i)| {
            let from = &codes[c][i as usize * n..(i as usize + 1) * n];
            for (x, &j) in row.iter_mut().zip(order) {
                *x = from[j as usize];
            }
        });
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::radiosity::progress::Progress;

    #[test]
    fn similar_rows_end_up_together() {
        // Rows 0 and 2 are alike, so are 1 and 3: the pass gives 0, 2, then 1 or 3.
        let n = 4;
        let rows: [[u8; 4]; 4] = [[10, 10, 10, 10], [200, 200, 200, 200], [12, 10, 10, 10], [200, 190, 200, 200]];
        let codes: Codes = std::array::from_fn(|_| rows.iter().flatten().copied().collect());
        let quiet = || Progress::Quiet.stage("reordering", 4, "lines");
        let order = greedy_order(&codes, n, false, &quiet());
        assert_eq!(order, [0, 2, 3, 1]);
        let p = permute(&codes, n, &order);
        // Row 1 of the result is old row 2 with its columns permuted the same way.
        assert_eq!(&p[0][4..8], &[12, 10, 10, 10]);
        assert_eq!(&p[1][12..16], &[200, 200, 200, 200]);
        let by_columns = greedy_order(&codes, n, true, &quiet());
        let mut sorted = by_columns.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, [0, 1, 2, 3]);
    }

    #[test]
    fn the_parallel_pass_picks_what_the_plain_pass_picks() {
        // The plain pass, entry by entry: the nearest line not placed, ties to the smaller index.
        let plain = |codes: &Codes, n: usize, by_columns: bool| -> Vec<u32> {
            let at = |a: usize, k: usize, c: usize| if by_columns { codes[c][k * n + a] } else { codes[c][a * n + k] };
            let distance = |a: usize, b: usize| -> u64 { (0..3).map(|c| (0..n).map(|k| u64::from(at(a, k, c).abs_diff(at(b, k, c)))).sum::<u64>()).sum() };
            let (mut placed, mut order, mut current) = (vec![false; n], vec![], 0);
            for _ in 0..n {
                placed[current] = true;
                order.push(current as u32);
                match (0..n).filter(|&b| !placed[b]).min_by_key(|&b| (distance(current, b), b)) {
                    Some(b) => current = b,
                    None => break,
                }
            }
            order
        };
        // Rows repeat every 5 and columns every 7 (ties), a few entries off by one (not all);
        // lines of 3 · 150 bytes: 14 whole steps of 32 bytes and a tail.
        let n = 150;
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let table: Vec<u8> = (0..3 * 35)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state % 200) as u8
            })
            .collect();
        let codes: Codes = std::array::from_fn(|c| (0..n * n).map(|k| table[c * 35 + (k / n % 5) * 7 + k % n % 7] + u8::from((k / n) * (k % n) % 11 == 0)).collect());
        let quiet = Progress::Quiet.stage("reordering", n as u64, "lines");
        for by_columns in [false, true] {
            assert_eq!(greedy_order(&codes, n, by_columns, &quiet), plain(&codes, n, by_columns), "by columns: {by_columns}");
        }
    }
}

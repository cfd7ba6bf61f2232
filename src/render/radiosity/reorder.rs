//! The seed's greedy reordering (seed 004, §4.2): rows and columns of the quantised matrix
//! are permuted (the same permutation on both, so the matrix still maps patches to patches)
//! so that similar rows, then similar columns, sit together and BC1's 4 × 4 blocks hold
//! similar texels. Finding the best order is a travelling-salesman problem; one greedy pass
//! starts at the first row (column) and repeatedly puts next the nearest one not placed yet,
//! by the sum of absolute differences of their codes over all channels. The seed runs two
//! passes: rows, then columns.
//!
//! Two searches for the nearest line ([`Search`]): the seed's exact one compares whole lines,
//! every pair: O(n³) byte operations a pass (75 s a pass at 16k patches on 16 cores); the
//! sketched one (the default) compares sketches of the lines (their codes at a few hundred
//! evenly spaced positions) to find the nearest few candidates, then picks among those by
//! the whole lines: O(n² · samples), the sketches staying in cache (`bench/radiosity.md`
//! compares their orders' errors).

use rayon::prelude::*;

use super::progress::Stage;

/// Codes of an `n × n` RGB matrix, row-major.
pub type Codes = [Vec<u8>; 3];

/// How a greedy pass finds the line nearest to the last one placed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Search {
    /// The seed's: by whole lines, among every line not placed.
    Exact,
    /// By sketches: the `candidates` lines not placed whose codes at `samples` evenly spaced
    /// positions (per channel) are nearest, then the nearest of those by whole lines.
    Sketch {
        /// Positions per channel.
        samples: u32,
        /// Lines compared whole.
        candidates: u32,
    },
}

impl Search {
    /// The renderer's default sketch.
    pub const SKETCH: Search = Search::Sketch { samples: 256, candidates: 16 };
}

/// The order of one greedy pass over `codes` (`n × n`), by rows or by columns, searching by
/// `search`: `order[new]` is the old index placed at `new` (ties to the smaller index). Each
/// line's codes of the three channels are first laid out one after the other, so a distance
/// reads two contiguous runs of `3 n` bytes; each step's search for the nearest line runs on
/// every core, its steps counted on `progress`.
pub fn greedy_order(codes: &Codes, n: usize, by_columns: bool, search: Search, progress: &Stage) -> Vec<u32> {
    let lines = lines(codes, n, by_columns);
    let line = |a: usize| &lines[a * 3 * n..(a + 1) * 3 * n];
    let sketches = match search {
        Search::Exact => None,
        Search::Sketch { samples, candidates } => Some((sketches(&lines, n, samples as usize), (samples as usize).min(n) * 3, candidates.max(1) as usize)),
    };
    // The lines not placed (in any order: every choice is by distance, then index).
    let mut remaining: Vec<u32> = (0..n as u32).collect();
    let mut at: Vec<u32> = (0..n as u32).collect();
    let mut order = Vec::with_capacity(n);
    let mut current = 0usize;
    for _ in 0..n {
        // `current` is among them: it leaves, the last one takes its slot.
        let Some(last) = remaining.pop() else { break };
        if last as usize != current {
            let k = at[current] as usize;
            remaining[k] = last;
            at[last as usize] = k as u32;
        }
        order.push(current as u32);
        progress.add(1);
        let from = line(current);
        let whole = |b: u32| (distance(from, line(b as usize)), b);
        let next = match &sketches {
            None => remaining.par_iter().with_min_len(SEARCH_GRAIN).map(|&b| whole(b)).min(),
            Some((sketch, width, candidates)) => {
                let of = |a: usize| &sketch[a * width..(a + 1) * width];
                let near = nearest(&remaining, *candidates, |b| distance(of(current), of(b as usize)));
                near.into_par_iter().map(|(_, b)| whole(b)).min()
            }
        };
        match next {
            Some((_, b)) => current = b as usize,
            None => break,
        }
    }
    order
}

/// The `count` entries of `among` nearest by `distance` (ties to the smaller index), nearest
/// first, searched on every core.
fn nearest(among: &[u32], count: usize, distance: impl Fn(u32) -> u32 + Sync) -> Vec<(u32, u32)> {
    let keep = |mut best: Vec<(u32, u32)>, x: (u32, u32)| {
        if best.len() < count || x < best[best.len() - 1] {
            let k = best.partition_point(|y| *y < x);
            best.insert(k, x);
            best.truncate(count);
        }
        best
    };
    among
        .par_iter()
        .with_min_len(SEARCH_GRAIN)
        .fold(Vec::new, |best, &b| keep(best, (distance(b), b)))
        .reduce(Vec::new, |a, b| b.into_iter().fold(a, &keep))
}

/// The sketch of every line of `lines` (`n` lines of three channels of `n` codes): each
/// channel's codes at `samples` evenly spaced positions (all of them when `n` is smaller),
/// `3 · min(samples, n)` bytes a line.
fn sketches(lines: &[u8], n: usize, samples: usize) -> Vec<u8> {
    let s = samples.min(n);
    let positions: Vec<usize> = (0..s).map(|k| (2 * k + 1) * n / (2 * s)).collect();
    let mut out = vec![0u8; 3 * s * n];
    out.par_chunks_mut(3 * s.max(1)).enumerate().for_each(|(a, sketch)| {
        for (c, part) in sketch.chunks_mut(s.max(1)).enumerate() {
            let channel = &lines[(3 * a + c) * n..(3 * a + c + 1) * n];
            for (x, &p) in part.iter_mut().zip(&positions) {
                *x = channel[p];
            }
        }
    });
    out
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
    std::array::from_fn(|c| permute_square(&codes[c], n, order))
}

/// `values` (`n × n`, row-major) with rows and columns both permuted by `order` (`order[new]`
/// = old), on every core.
pub fn permute_square<T: Copy + Default + Send + Sync>(values: &[T], n: usize, order: &[u32]) -> Vec<T> {
    let mut out = vec![T::default(); n * n];
    out.par_chunks_mut(n.max(1)).zip(order).for_each(|(row, &i)| {
        let from = &values[i as usize * n..(i as usize + 1) * n];
        for (x, &j) in row.iter_mut().zip(order) {
            *x = from[j as usize];
        }
    });
    out
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
        let order = greedy_order(&codes, n, false, Search::Exact, &quiet());
        assert_eq!(order, [0, 2, 3, 1]);
        let p = permute(&codes, n, &order);
        // Row 1 of the result is old row 2 with its columns permuted the same way.
        assert_eq!(&p[0][4..8], &[12, 10, 10, 10]);
        assert_eq!(&p[1][12..16], &[200, 200, 200, 200]);
        let by_columns = greedy_order(&codes, n, true, Search::Exact, &quiet());
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
            let exact = greedy_order(&codes, n, by_columns, Search::Exact, &quiet);
            assert_eq!(exact, plain(&codes, n, by_columns), "by columns: {by_columns}");
            // A sketch of every position is the whole line: the same order, however many
            // candidates.
            for candidates in [1, 7] {
                assert_eq!(greedy_order(&codes, n, by_columns, Search::Sketch { samples: n as u32, candidates }, &quiet), exact, "by columns: {by_columns}");
            }
        }
    }

    #[test]
    fn a_sketched_pass_is_a_permutation_the_same_every_run_and_near_the_exact_one() {
        // Lines of 300 codes, smooth in both indices (a patch's row is like its neighbours'),
        // in a shuffled order for the passes to undo; sketches of 24 positions of 300.
        let n = 300;
        let order = crate::render::radiosity::test_scenes::shuffled_order(n, 7);
        let smooth = |i: usize, j: usize, c: usize| (128.0 + 100.0 * ((i as f32 * 0.05 + c as f32).sin() * (j as f32 * 0.03).cos())) as u8;
        let codes: Codes = std::array::from_fn(|c| (0..n * n).map(|k| smooth(order[k / n] as usize, order[k % n] as usize, c)).collect());
        let quiet = Progress::Quiet.stage("reordering", n as u64, "lines");
        // The summed distance between neighbouring lines of an order.
        let path = |o: &[u32]| -> u64 {
            let lines = lines(&codes, n, false);
            o.windows(2).map(|w| u64::from(distance(&lines[w[0] as usize * 3 * n..][..3 * n], &lines[w[1] as usize * 3 * n..][..3 * n]))).sum()
        };
        let sketch = Search::Sketch { samples: 24, candidates: 4 };
        let a = greedy_order(&codes, n, false, sketch, &quiet);
        assert_eq!(a, greedy_order(&codes, n, false, sketch, &quiet));
        let mut sorted = a.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n as u32).collect::<Vec<_>>());
        let exact = greedy_order(&codes, n, false, Search::Exact, &quiet);
        let identity: Vec<u32> = (0..n as u32).collect();
        let (a, exact, shuffled) = (path(&a), path(&exact), path(&identity));
        eprintln!("summed distance between neighbours: sketched {a}, exact {exact}, shuffled {shuffled}");
        assert!(a as f64 <= 1.1 * exact as f64 && a * 5 < shuffled, "sketched {a}, exact {exact}, shuffled {shuffled}");
    }
}

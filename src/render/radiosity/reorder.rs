//! The seed's greedy reordering (seed 004, §4.2): rows and columns of the quantised matrix
//! are permuted (the same permutation on both, so the matrix still maps patches to patches)
//! so that similar rows, then similar columns, sit together and BC1's 4 × 4 blocks hold
//! similar texels. Finding the best order is a travelling-salesman problem; one greedy pass
//! starts at the first row (column) and repeatedly puts next the nearest one not placed yet,
//! by the sum of absolute differences of their codes over all channels. The seed runs two
//! passes: rows, then columns. Each pass compares every pair: O(n³) byte operations.

/// Codes of an `n × n` RGB matrix, row-major.
pub type Codes = [Vec<u8>; 3];

/// The order of one greedy pass over `codes` (`n × n`), by rows or by columns: `order[new]` is
/// the old index placed at `new`.
pub fn greedy_order(codes: &Codes, n: usize, by_columns: bool) -> Vec<u32> {
    let line = |a: usize, k: usize, c: usize| if by_columns { codes[c][k * n + a] } else { codes[c][a * n + k] };
    let distance = |a: usize, b: usize| -> u64 { (0..3).map(|c| (0..n).map(|k| u64::from(line(a, k, c).abs_diff(line(b, k, c)))).sum::<u64>()).sum() };
    let mut placed = vec![false; n];
    let mut order = Vec::with_capacity(n);
    let mut current = 0;
    for _ in 0..n {
        placed[current] = true;
        order.push(current as u32);
        let next = (0..n).filter(|&b| !placed[b]).min_by_key(|&b| (distance(current, b), b));
        match next {
            Some(b) => current = b,
            None => break,
        }
    }
    order
}

/// `codes` with rows and columns both permuted by `order` (`order[new]` = old).
pub fn permute(codes: &Codes, n: usize, order: &[u32]) -> Codes {
    std::array::from_fn(|c| {
        let mut out = vec![0u8; n * n];
        for (a, &i) in order.iter().enumerate() {
            for (b, &j) in order.iter().enumerate() {
                out[a * n + b] = codes[c][i as usize * n + j as usize];
            }
        }
        out
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn similar_rows_end_up_together() {
        // Rows 0 and 2 are alike, so are 1 and 3: the pass gives 0, 2, then 1 or 3.
        let n = 4;
        let rows: [[u8; 4]; 4] = [[10, 10, 10, 10], [200, 200, 200, 200], [12, 10, 10, 10], [200, 190, 200, 200]];
        let codes: Codes = std::array::from_fn(|_| rows.iter().flatten().copied().collect());
        let order = greedy_order(&codes, n, false);
        assert_eq!(order, [0, 2, 3, 1]);
        let p = permute(&codes, n, &order);
        // Row 1 of the result is old row 2 with its columns permuted the same way.
        assert_eq!(&p[0][4..8], &[12, 10, 10, 10]);
        assert_eq!(&p[1][12..16], &[200, 200, 200, 200]);
        let by_columns = greedy_order(&codes, n, true);
        let mut sorted = by_columns.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, [0, 1, 2, 3]);
    }
}

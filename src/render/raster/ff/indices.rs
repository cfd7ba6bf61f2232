//! The indices of a [`super::Batch`]: the draw's own primitives, rotated so that the provoking
//! vertex comes first (Vulkan's default) as they are written into upload memory, or a list
//! built on the CPU (expanded primitives, filtered indices).

use crate::frame::Draw;

/// A batch's indices.
#[derive(Clone, Debug, PartialEq)]
pub enum BatchIndices {
    /// The draw's primitives of `per` vertices ([`Draw::indices`], every index in range; a
    /// last, partial primitive left out), each rotated so that its provoking vertex (the
    /// last) comes first.
    Draw {
        /// Vertices per primitive (1 to 3).
        per: usize,
    },
    /// Indices into the batch's vertices, provoking vertex first.
    List(Vec<u32>),
}

impl BatchIndices {
    /// The draw's primitives of `per` vertices, each rotated: [`BatchIndices::Draw`] when
    /// every index is below the draw's vertex count, else a list of the primitives whose
    /// indices all are.
    pub fn rotated(draw: &Draw, per: usize) -> BatchIndices {
        let count = draw.vertices.len();
        // A fold without early exit, so the test of every index is vectorised.
        let in_range = u32::try_from(count).map_or(true, |count| draw.indices.iter().fold(0u32, |out, &i| out | u32::from(i >= count)) == 0);
        if in_range {
            return BatchIndices::Draw { per };
        }
        let valid: Vec<u32> = draw.indices.chunks_exact(per).filter(|p| p.iter().all(|&i| (i as usize) < count)).flatten().copied().collect();
        let mut list = vec![0; valid.len()];
        rotate(&valid, per, &mut list);
        BatchIndices::List(list)
    }

    /// Number of indices.
    pub fn len(&self, draw: &Draw) -> usize {
        match self {
            BatchIndices::Draw { per } => draw.indices.len() / per * per,
            BatchIndices::List(list) => list.len(),
        }
    }

    /// Writes the indices into `out` (as many as both hold).
    pub fn write(&self, draw: &Draw, out: &mut [u32]) {
        match self {
            BatchIndices::Draw { per } => rotate(&draw.indices, *per, out),
            BatchIndices::List(list) => {
                let n = list.len().min(out.len());
                out[..n].copy_from_slice(&list[..n]);
            }
        }
    }
}

/// `indices`' primitives of `per` vertices into `out`, each with its last index first.
fn rotate(indices: &[u32], per: usize, out: &mut [u32]) {
    match per {
        3 => rotate_by::<3>(indices, out),
        2 => rotate_by::<2>(indices, out),
        _ => rotate_by::<1>(indices, out),
    }
}

fn rotate_by<const N: usize>(indices: &[u32], out: &mut [u32]) {
    for (o, p) in out.as_chunks_mut::<N>().0.iter_mut().zip(indices.as_chunks::<N>().0) {
        *o = std::array::from_fn(|k| p[(k + N - 1) % N]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draw(vertices: usize, indices: &[u32]) -> Draw {
        let mut d = Draw { indices: indices.to_vec(), ..Draw::default() };
        d.vertices.position = vec![[0.0; 4]; vertices];
        d
    }

    fn written(indices: &BatchIndices, d: &Draw) -> Vec<u32> {
        let mut out = vec![u32::MAX; indices.len(d)];
        indices.write(d, &mut out);
        out
    }

    #[test]
    fn primitives_are_rotated_as_written_and_partial_ones_left_out() {
        let d = draw(5, &[0, 1, 2, 2, 3, 4, 0, 1]);
        let triangles = BatchIndices::rotated(&d, 3);
        assert_eq!(triangles, BatchIndices::Draw { per: 3 });
        assert_eq!(written(&triangles, &d), vec![2, 0, 1, 4, 2, 3]);
        assert_eq!(written(&BatchIndices::rotated(&d, 2), &d), vec![1, 0, 2, 2, 4, 3, 1, 0]);
        assert_eq!(written(&BatchIndices::rotated(&d, 1), &d), d.indices);
    }

    #[test]
    fn primitives_with_an_index_out_of_range_are_dropped() {
        let d = draw(3, &[0, 1, 2, 0, 1, 9, 2, 1, 0]);
        let triangles = BatchIndices::rotated(&d, 3);
        assert_eq!(triangles, BatchIndices::List(vec![2, 0, 1, 0, 2, 1]));
        assert_eq!(written(&triangles, &d), vec![2, 0, 1, 0, 2, 1]);
    }
}

//! `EXT_compiled_vertex_array`: while arrays are locked, each element of the vertex array
//! (positions) in client memory is converted once, and the later draws of the lock copy it
//! from that conversion. The conversion grows to the smallest range holding the elements the
//! lock's draws used (inside the locked range), so a program that locks more than it draws
//! reads no more than it draws.
//!
//! Only positions are kept: the extension makes changing locked arrays undefined, but Quake
//! III locks its positions and then rewrites the colours and texture coordinates it points at
//! between the draws of one lock (one draw per shader stage), as drivers let it; those arrays
//! are read at each draw.

use super::array_convert::Span;
use super::array_fetch::Source;

/// The locked vertex array's conversion.
#[derive(Default)]
pub(crate) struct LockedPositions {
    /// The array `values` was converted from, and the elements `start..end` it holds.
    from: Option<(Source, usize, usize)>,
    /// Elements `start..end` of the array.
    values: Vec<[f32; 4]>,
}

impl LockedPositions {
    /// Forgets the conversion (`glLockArraysEXT`, `glUnlockArraysEXT`).
    pub(crate) fn forget(&mut self) {
        self.from = None;
    }

    /// Appends the positions of `span` to `out` from the conversion of `source`, converting
    /// (more of) it first if needed; false (read the array instead) when the array is not in
    /// client memory or `span` reaches outside the locked range `(first, count)`.
    pub(crate) fn positions(
        &mut self,
        source: &Source,
        (first, count): (usize, usize),
        span: Span<'_>,
        out: &mut Vec<[f32; 4]>,
    ) -> bool {
        let (lo, hi) = match span {
            Span::Range(a, n) => (a, a.saturating_add(n)),
            Span::Gather(indices) => {
                let lo = indices.iter().copied().min().unwrap_or(0) as usize;
                (lo, indices.iter().copied().max().map_or(lo, |m| m as usize + 1))
            }
        };
        if !source.is_client() || lo < first || hi > first.saturating_add(count) || lo >= hi {
            return false;
        }
        let (start, end) = match self.from {
            Some((s, start, end)) if s == *source => {
                // Elements not converted yet: before and after those that are.
                if lo < start {
                    let mut before = Vec::with_capacity(end - lo);
                    source.convert_into(Span::Range(lo, start - lo), &mut before);
                    before.extend_from_slice(&self.values);
                    self.values = before;
                }
                if hi > end {
                    source.convert_into(Span::Range(end, hi - end), &mut self.values);
                }
                (start.min(lo), end.max(hi))
            }
            _ => {
                self.values.clear();
                source.convert_into(Span::Range(lo, hi - lo), &mut self.values);
                (lo, hi)
            }
        };
        self.from = Some((*source, start, end));
        // A capture records the elements each draw uses, converted now or not.
        source.note_reads(span);
        match span {
            Span::Range(a, n) => out.extend_from_slice(&self.values[a - start..a - start + n]),
            Span::Gather(indices) => out.extend(indices.iter().map(|&i| self.values[i as usize - start])),
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::LockedPositions;
    use crate::translate::array_convert::Span;
    use crate::translate::array_fetch::Source;
    use crate::translate::gl;

    #[test]
    fn converted_once_then_copied_until_forgotten() {
        let mut xyz: Vec<f32> = (0..30).map(|i| i as f32).collect();
        let data = xyz.as_mut_ptr();
        let src = Source::client(data.cast_const().cast(), 12, 3, gl::GL_FLOAT, false);
        let mut locked = LockedPositions::default();
        let mut out = Vec::new();
        assert!(locked.positions(&src, (0, 10), Span::Range(2, 2), &mut out));
        assert_eq!(out, [[6.0, 7.0, 8.0, 1.0], [9.0, 10.0, 11.0, 1.0]]);
        // Changing locked data is undefined: the copy is what the lock's draws see.
        unsafe { data.add(6).write(-1.0) };
        out.clear();
        assert!(locked.positions(&src, (0, 10), Span::Gather(&[3, 2, 1]), &mut out));
        assert_eq!(out[1], [6.0, 7.0, 8.0, 1.0], "element 2 comes from the conversion");
        assert_eq!(out[2], [3.0, 4.0, 5.0, 1.0], "element 1 extends it");
        out.clear();
        assert!(!locked.positions(&src, (0, 10), Span::Range(9, 2), &mut out), "outside the locked range");
        assert!(out.is_empty());
        locked.forget();
        assert!(locked.positions(&src, (0, 10), Span::Range(2, 1), &mut out));
        assert_eq!(out, [[-1.0, 7.0, 8.0, 1.0]], "a new lock reads the array again");
    }
}

//! Converting vertex-array elements to floats (OpenGL 1.5 table 2.9), one element or a whole
//! run of them at once: the component type and count are resolved once per array and draw,
//! then a loop specialised for them converts every element the draw uses (a slice copy for
//! the float arrays games use, a tight conversion loop for bytes and shorts).

use super::array_fetch::Source;
use super::convert::{norm_i8, norm_i16, norm_i32, norm_u8, norm_u16, norm_u32};
use super::gl;

/// A component type of an array, converted to float as table 2.9 says.
trait Component: Copy {
    /// The value; integer types map to [-1, 1] / [0, 1] when `normalized`.
    fn float(self, normalized: bool) -> f32;
}

macro_rules! integer_component {
    ($t:ty, $norm:ident) => {
        impl Component for $t {
            #[inline(always)]
            fn float(self, normalized: bool) -> f32 {
                if normalized { $norm(self) } else { self as f32 }
            }
        }
    };
}
integer_component!(i8, norm_i8);
integer_component!(u8, norm_u8);
integer_component!(i16, norm_i16);
integer_component!(u16, norm_u16);
integer_component!(i32, norm_i32);
integer_component!(u32, norm_u32);

impl Component for f32 {
    #[inline(always)]
    fn float(self, _: bool) -> f32 {
        self
    }
}

impl Component for f64 {
    #[inline(always)]
    fn float(self, _: bool) -> f32 {
        self as f32
    }
}

/// The element at `p`: `S` components of `T`, the missing ones from `(0, 0, 0, 1)`.
///
/// # Safety
/// `p` must point to `S` readable components of `T`.
#[inline(always)]
unsafe fn load<T: Component, const S: usize>(p: *const u8, normalized: bool) -> [f32; 4] {
    let mut out = [0.0, 0.0, 0.0, 1.0];
    for (k, slot) in out.iter_mut().enumerate().take(S) {
        // Safety: the caller guarantees S readable components.
        *slot = unsafe { p.cast::<T>().add(k).read_unaligned() }.float(normalized);
    }
    out
}

/// Which elements of an array to convert, in order.
#[derive(Clone, Copy)]
pub(crate) enum Span<'a> {
    /// `first..first + count`.
    Range(usize, usize),
    /// These elements (repeats allowed).
    Gather(&'a [u32]),
}

impl Span<'_> {
    /// How many elements.
    pub(crate) fn len(&self) -> usize {
        match self {
            Span::Range(_, count) => *count,
            Span::Gather(indices) => indices.len(),
        }
    }
}

/// Appends the elements of `span` to `out`, converted with `S` components of `T`; elements
/// past the end of a buffer store read as zero.
///
/// # Safety
/// Client-memory elements of `span` must be readable (the program vouches for them).
unsafe fn convert<T: Component, const S: usize>(src: &Source, span: Span<'_>, out: &mut Vec<[f32; 4]>) {
    // Safety: as the caller's.
    unsafe {
        if src.normalized { convert_as::<T, S, true>(src, span, out) } else { convert_as::<T, S, false>(src, span, out) }
    }
}

/// [`convert`] with `normalized` known at compile time (no test per component).
///
/// # Safety
/// As [`convert`].
#[inline(always)]
unsafe fn convert_as<T: Component, const S: usize, const NORMALIZED: bool>(src: &Source, span: Span<'_>, out: &mut Vec<[f32; 4]>) {
    let (base, stride, normalized, valid) = (src.base, src.stride, NORMALIZED, src.len());
    match span {
        Span::Range(first, count) => {
            let readable = count.min(valid.saturating_sub(first));
            src.note_reads(Span::Range(first, readable));
            let start = base.wrapping_add(first.wrapping_mul(stride));
            out.reserve(count);
            let spare = &mut out.spare_capacity_mut()[..readable];
            for (j, slot) in spare.iter_mut().enumerate() {
                // Safety: within a buffer store (checked by `valid`), or client memory.
                slot.write(unsafe { load::<T, S>(start.wrapping_add(j * stride), normalized) });
            }
            // Safety: the `readable` elements after the length were just written.
            unsafe { out.set_len(out.len() + readable) };
            out.resize(out.len() + (count - readable), [0.0; 4]);
        }
        Span::Gather(indices) => {
            let noted = src.is_client() && super::capture::reads::enabled();
            out.extend(indices.iter().map(|&i| {
                let i = i as usize;
                if i >= valid {
                    return [0.0; 4];
                }
                let p = base.wrapping_add(i.wrapping_mul(stride));
                if noted {
                    super::capture::reads::note(p, src.element_bytes());
                }
                // Safety: within a buffer store (checked by `valid`), or client memory.
                unsafe { load::<T, S>(p, normalized) }
            }));
        }
    }
}

/// Calls `$f::<T, S>($args)` with the component type `T` and count `S` of `$src`.
macro_rules! specialised {
    ($src:expr, $f:ident($($args:expr),*)) => {{
        macro_rules! sized {
            ($t:ty) => {
                match $src.size {
                    1 => $f::<$t, 1>($($args),*),
                    2 => $f::<$t, 2>($($args),*),
                    3 => $f::<$t, 3>($($args),*),
                    _ => $f::<$t, 4>($($args),*),
                }
            };
        }
        match $src.type_ {
            gl::GL_BYTE => sized!(i8),
            gl::GL_UNSIGNED_BYTE => sized!(u8),
            gl::GL_SHORT => sized!(i16),
            gl::GL_UNSIGNED_SHORT => sized!(u16),
            gl::GL_INT => sized!(i32),
            gl::GL_UNSIGNED_INT => sized!(u32),
            gl::GL_DOUBLE => sized!(f64),
            _ => sized!(f32),
        }
    }};
}

impl Source {
    /// Reports the bytes of each element of `span` as read (client memory only: a capture
    /// holds exactly what the draw read, element by element).
    pub(crate) fn note_reads(&self, span: Span<'_>) {
        if !self.is_client() || !super::capture::reads::enabled() {
            return;
        }
        let (base, stride, elem) = (self.base, self.stride, self.element_bytes());
        let note = |i: usize| super::capture::reads::note(base.wrapping_add(i.wrapping_mul(stride)), elem);
        match span {
            Span::Range(first, count) => (first..first + count).for_each(note),
            Span::Gather(indices) => indices.iter().for_each(|&i| note(i as usize)),
        }
    }

    /// Appends the elements of `span`, converted, to `out` (missing components from
    /// `(0, 0, 0, 1)`, elements past the end of a buffer store zero).
    pub(crate) fn convert_into(&self, span: Span<'_>, out: &mut Vec<[f32; 4]>) {
        // Safety: client memory the program vouches for; buffer reads are bounds-checked.
        unsafe { specialised!(self, convert(self, span, out)) }
    }

    /// Element `i`, converted (as [`Source::convert_into`] would).
    pub(crate) fn read(&self, i: usize) -> [f32; 4] {
        /// One element, or zero past the end of a buffer store.
        unsafe fn one<T: Component, const S: usize>(src: &Source, i: usize) -> [f32; 4] {
            if i >= src.len() {
                return [0.0; 4];
            }
            let p = src.base.wrapping_add(i.wrapping_mul(src.stride));
            if src.is_client() {
                super::capture::reads::note(p, src.element_bytes());
            }
            // Safety: within a buffer store, or client memory the program vouches for.
            unsafe { load::<T, S>(p, src.normalized) }
        }
        // Safety: as above.
        unsafe { specialised!(self, one(self, i)) }
    }
}

#[cfg(test)]
mod tests {
    use super::Span;
    use crate::translate::array_fetch::Source;
    use crate::translate::gl;

    #[test]
    fn every_type_and_size_converts_as_one_element_does() {
        // Three elements of up to 4 doubles, at a stride of 8 bytes per component.
        let bytes: Vec<u8> = (0..96u8).map(|b| b.wrapping_mul(37)).collect();
        let bits = |v: &[[f32; 4]]| v.iter().map(|e| e.map(f32::to_bits)).collect::<Vec<_>>();
        for &type_ in crate::translate::arrays::COLOR_TYPES {
            for size in 1..=4 {
                for normalized in [false, true] {
                    let src = Source::client(bytes.as_ptr(), 8 * size, size, type_, normalized);
                    let mut range = Vec::new();
                    src.convert_into(Span::Range(1, 2), &mut range);
                    let mut gathered = Vec::new();
                    src.convert_into(Span::Gather(&[2, 0, 2]), &mut gathered);
                    assert_eq!(bits(&range), bits(&[src.read(1), src.read(2)]), "{type_:#x} x{size}");
                    assert_eq!(bits(&gathered), bits(&[src.read(2), src.read(0), src.read(2)]), "{type_:#x} x{size}");
                    assert!(range.iter().all(|e| e[size..].iter().zip(&[0.0, 0.0, 0.0, 1.0][size..]).all(|(a, b)| a == b)));
                }
            }
        }
        let ub = Source::client(bytes.as_ptr(), 4, 4, gl::GL_UNSIGNED_BYTE, true);
        assert_eq!(ub.read(0), [0.0, 37.0 / 255.0, 74.0 / 255.0, 111.0 / 255.0]);
        let pair = [1.5f32, -2.0];
        let f = Source::client(pair.as_ptr().cast(), 8, 2, gl::GL_FLOAT, false);
        assert_eq!(f.read(0), [1.5, -2.0, 0.0, 1.0]);
    }
}

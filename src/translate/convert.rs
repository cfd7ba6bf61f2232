//! Conversions used by the generated dispatch: integer components to floats (OpenGL 1.5,
//! table 2.9), reads of small client arrays, and the value a command returns when it fails.

/// `ubyte` c → c / (2^8 − 1).
pub fn norm_u8(c: u8) -> f32 {
    UNORM8[usize::from(c)]
}

/// [`norm_u8`] of every byte, computed once (colour arrays convert four bytes a vertex).
static UNORM8: [f32; 256] = {
    let mut table = [0.0; 256];
    let mut c = 0;
    while c < 256 {
        table[c] = c as f32 / 255.0;
        c += 1;
    }
    table
};
/// `byte` c → (2c + 1) / (2^8 − 1).
pub fn norm_i8(c: i8) -> f32 {
    (2.0 * f32::from(c) + 1.0) / 255.0
}
/// `ushort` c → c / (2^16 − 1).
pub fn norm_u16(c: u16) -> f32 {
    f32::from(c) / 65535.0
}
/// `short` c → (2c + 1) / (2^16 − 1).
pub fn norm_i16(c: i16) -> f32 {
    (2.0 * f32::from(c) + 1.0) / 65535.0
}
/// `uint` c → c / (2^32 − 1).
pub fn norm_u32(c: u32) -> f32 {
    (f64::from(c) / 4294967295.0) as f32
}
/// `int` c → (2c + 1) / (2^32 − 1).
pub fn norm_i32(c: i32) -> f32 {
    ((2.0 * f64::from(c) + 1.0) / 4294967295.0) as f32
}

/// Copies `N` values from a client pointer; `None` for a null pointer.
///
/// # Safety
/// A non-null `ptr` must point to `N` readable values of `T`, as the GL command requires.
pub unsafe fn read_array<T: Copy, const N: usize>(ptr: *const T) -> Option<[T; N]> {
    if ptr.is_null() {
        return None;
    }
    super::capture::reads::note(ptr, N * size_of::<T>());
    // Safety: non-null, and the caller guarantees N readable values.
    Some(unsafe { std::ptr::read_unaligned(ptr.cast::<[T; N]>()) })
}

/// Copies `n` values from a client pointer; `None` for a null pointer.
///
/// # Safety
/// A non-null `ptr` must point to `n` readable values of `T`.
pub unsafe fn read_slice<T: Copy>(ptr: *const T, n: usize) -> Option<Vec<T>> {
    if ptr.is_null() {
        return None;
    }
    super::capture::reads::note(ptr, n.saturating_mul(size_of::<T>()));
    // Safety: non-null, and the caller guarantees n readable values.
    Some((0..n).map(|i| unsafe { std::ptr::read_unaligned(ptr.add(i)) }).collect())
}

/// Writes `values` to a client pointer; does nothing for a null pointer.
///
/// # Safety
/// A non-null `ptr` must point to room for `values.len()` values of `T`.
pub unsafe fn write_slice<T: Copy>(ptr: *mut T, values: &[T]) {
    if ptr.is_null() {
        return;
    }
    for (i, v) in values.iter().enumerate() {
        // Safety: non-null, and the caller guarantees room for every value.
        unsafe { std::ptr::write_unaligned(ptr.add(i), *v) };
    }
}

/// The values a scalar command (`glTexParameterf`, `glTexGenf`) gives a name that takes `count`
/// values: `param`, then zeros. OpenGL 1.5 defines no error for a vector name given to the
/// scalar form; Mesa reads (param, 0, 0, 0), which piglit's `gl-1.0-beginend-coverage` expects.
pub fn scalar_as_vector(param: f64, count: usize) -> Vec<f64> {
    let mut v = vec![0.0; count.max(1)];
    v[0] = param;
    v
}

/// The value a command returns when it raises an error or has no current context:
/// zero, `GL_FALSE` or null.
pub trait ReturnDefault {
    /// Zero of the type.
    fn return_default() -> Self;
}

macro_rules! zero_default {
    ($($t:ty),*) => { $(impl ReturnDefault for $t { fn return_default() -> Self { 0 as $t } })* };
}
zero_default!(u8, i8, u16, i16, u32, i32, u64, i64, usize, isize, f32, f64);

impl<T> ReturnDefault for *const T {
    fn return_default() -> Self {
        std::ptr::null()
    }
}
impl<T> ReturnDefault for *mut T {
    fn return_default() -> Self {
        std::ptr::null_mut()
    }
}
impl ReturnDefault for () {
    fn return_default() -> Self {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalization_matches_table_2_9() {
        assert_eq!(norm_u8(255), 1.0);
        assert_eq!(norm_u8(0), 0.0);
        assert_eq!(norm_i8(127), 1.0);
        assert_eq!(norm_i8(-128), -1.0);
        assert_eq!(norm_i16(32767), 1.0);
        assert_eq!(norm_u32(u32::MAX), 1.0);
        assert_eq!(norm_i32(i32::MIN), -1.0);
    }
}

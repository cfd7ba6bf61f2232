//! The replay's copy of the captured program's address space: one reserved region
//! (`MAP_NORESERVE`: pages cost memory only once written) holding one 4 GiB slot per window
//! of captured addresses (`address >> 32`), in address order, so that windows that follow
//! each other stay contiguous, plus one spare slot at the end for writes that run past the
//! last window. Addresses below 4 GiB are not translated: there they are buffer offsets and
//! null, which pass through unchanged.

use std::collections::BTreeSet;
use std::ffi::{c_int, c_void};

/// Bytes per window.
const WINDOW: u64 = 1 << 32;
/// Most windows a capture may use (the region is `(windows + 1) × 4 GiB` of address space).
pub const MAX_WINDOWS: usize = 256;

unsafe extern "C" {
    fn mmap(addr: *mut c_void, len: usize, prot: c_int, flags: c_int, fd: c_int, offset: i64) -> *mut c_void;
    fn munmap(addr: *mut c_void, len: usize) -> c_int;
}

const PROT_READ: c_int = 1;
const PROT_WRITE: c_int = 2;
const MAP_PRIVATE: c_int = 0x02;
const MAP_ANONYMOUS: c_int = 0x20;
const MAP_NORESERVE: c_int = 0x4000;

/// The reserved region and which window each slot mirrors.
pub struct Shadow {
    base: usize,
    len: usize,
    /// Window numbers (`address >> 32`, never 0), sorted; slot `i` mirrors `windows[i]`.
    windows: Vec<u64>,
}

// Safety: the region is plain memory owned by the `Shadow`; it is only written through
// `write` (by the replaying thread) and by the GL calls it makes.
unsafe impl Send for Shadow {}
unsafe impl Sync for Shadow {}

impl Shadow {
    /// Reserves slots for `windows` (window numbers; 0 is ignored).
    pub fn new(windows: &BTreeSet<u64>) -> Result<Shadow, String> {
        let windows: Vec<u64> = windows.iter().copied().filter(|&w| w != 0).collect();
        if windows.len() > MAX_WINDOWS {
            return Err(format!("the capture uses {} windows of 4 GiB, at most {MAX_WINDOWS} are replayed", windows.len()));
        }
        let len = usize::try_from((windows.len() as u64 + 1) * WINDOW).map_err(|_| "address space too small")?;
        // Safety: a fresh anonymous private mapping; no existing memory is touched.
        let base = unsafe {
            mmap(std::ptr::null_mut(), len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0)
        };
        if base as isize == -1 {
            return Err(format!("cannot reserve {} GiB of address space for the replay", len >> 30));
        }
        Ok(Shadow { base: base as usize, len, windows })
    }

    /// Where captured `address` is in the shadow; values below 4 GiB and in windows the
    /// capture does not use are returned unchanged.
    pub fn translate(&self, address: u64) -> u64 {
        match self.windows.binary_search(&(address >> 32)) {
            Ok(slot) => self.base as u64 + slot as u64 * WINDOW + (address & (WINDOW - 1)),
            Err(_) => address,
        }
    }

    /// The captured address of shadow `address` (inverse of [`Shadow::translate`]); other
    /// addresses are returned unchanged.
    pub fn original(&self, address: u64) -> u64 {
        let offset = address.wrapping_sub(self.base as u64);
        match self.windows.get((offset / WINDOW) as usize) {
            Some(window) if address >= self.base as u64 => (window << 32) | (offset & (WINDOW - 1)),
            _ => address,
        }
    }

    /// Writes `bytes` that the program had at captured `address`.
    pub fn write(&self, address: u64, bytes: &[u8]) -> Result<(), String> {
        let start = self.translate(address);
        let inside = start >= self.base as u64
            && start.checked_add(bytes.len() as u64).is_some_and(|end| end <= (self.base + self.len) as u64);
        if !inside || address < WINDOW {
            return Err(format!("{} bytes at {address:#x}: outside the captured address windows", bytes.len()));
        }
        // Safety: the range lies inside the region, which this `Shadow` owns.
        unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), start as *mut u8, bytes.len()) };
        Ok(())
    }

    /// The window numbers a read of `len` bytes at `address` touches.
    pub fn windows_of(address: u64, len: u64) -> impl Iterator<Item = u64> {
        let last = address.saturating_add(len.saturating_sub(1));
        (address >> 32)..=(last >> 32)
    }
}

impl Drop for Shadow {
    fn drop(&mut self) {
        // Safety: the region was mapped by `new` with this length.
        unsafe { munmap(self.base as *mut c_void, self.len) };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_translate_into_slots_and_back() {
        let windows: BTreeSet<u64> = [0x5555, 0x7ffc, 0x7ffd].into_iter().collect();
        let shadow = Shadow::new(&windows).unwrap();
        let a = 0x7ffc_ffff_fff0u64;
        let t = shadow.translate(a);
        assert_ne!(t, a);
        assert_eq!(shadow.original(t), a);
        assert_eq!(shadow.translate(a + 0x20), t + 0x20, "consecutive windows are contiguous");
        assert_eq!(shadow.translate(0x40), 0x40, "offsets pass unchanged");
        assert_eq!(shadow.original(0x40), 0x40);
        shadow.write(a, &[1, 2, 3, 4]).unwrap();
        assert_eq!(unsafe { std::slice::from_raw_parts(t as *const u8, 4) }, &[1, 2, 3, 4]);
        assert!(shadow.write(0x1000, &[1]).is_err(), "below 4 GiB");
        assert!(shadow.write(0x1234_0000_0000, &[1]).is_err(), "unknown window");
        assert_eq!(Shadow::windows_of(0x1_ffff_fffe, 4).collect::<Vec<_>>(), vec![1, 2]);
    }
}

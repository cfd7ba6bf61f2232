//! The replay's copy of the captured program's address space: one reserved region
//! (`MAP_NORESERVE`: pages cost memory only once written) holding one 4 GiB slot per window
//! of captured addresses (`address >> 32`), in address order, so that windows that follow
//! each other stay contiguous, plus one spare slot at the end for writes that run past the
//! last window. Addresses below 4 GiB are not translated: there they are buffer offsets and
//! null, which pass through unchanged, or the data of a program that is not position
//! independent: the pages of those the capture read (and, where free, those pointer
//! arguments point into) are mapped at their own addresses.

use std::collections::BTreeSet;
use std::ffi::{c_int, c_void};

use crate::translate::capture::AddressMap;

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
const MAP_FIXED_NOREPLACE: c_int = 0x10_0000;
/// Page size used for the identity-mapped low pages.
const PAGE: u64 = 4096;

/// Maps `pages` pages at page number `first` at their own address; false when the range is
/// not free in this process.
fn map_fixed(first: u64, pages: u64) -> bool {
    let (address, len) = ((first * PAGE) as usize, (pages * PAGE) as usize);
    // Safety: MAP_FIXED_NOREPLACE never replaces an existing mapping.
    let got = unsafe {
        mmap(address as *mut c_void, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED_NOREPLACE, -1, 0)
    };
    if got as usize == address {
        return true;
    }
    if got as isize != -1 {
        // An old kernel took the address as a hint and mapped elsewhere.
        // Safety: the mapping was just made, with this length.
        unsafe { munmap(got, len) };
    }
    false
}

/// Runs of consecutive page numbers: `(first, count)`.
fn runs(pages: &BTreeSet<u64>) -> Vec<(u64, u64)> {
    let mut out: Vec<(u64, u64)> = Vec::new();
    for &p in pages {
        match out.last_mut() {
            Some((first, n)) if *first + *n == p => *n += 1,
            _ => out.push((p, 1)),
        }
    }
    out
}

/// The reserved region and which window each slot mirrors.
pub struct Shadow {
    base: usize,
    len: usize,
    /// Window numbers (`address >> 32`, never 0), sorted; slot `i` mirrors `windows[i]`.
    windows: Vec<u64>,
    /// Runs of pages below 4 GiB mapped at their own address: `(first page, count)`.
    low: Vec<(u64, u64)>,
}

// Safety: the region is plain memory owned by the `Shadow`; it is only written through
// `write` (by the replaying thread) and by the GL calls it makes.
unsafe impl Send for Shadow {}
unsafe impl Sync for Shadow {}

impl Shadow {
    /// Reserves slots for `windows` (window numbers; 0 is ignored), and maps below 4 GiB the
    /// pages `read` (page numbers; an error when one is not free here) and those of `pointed`
    /// that are free.
    pub fn new(windows: &BTreeSet<u64>, read: &BTreeSet<u64>, pointed: &BTreeSet<u64>) -> Result<Shadow, String> {
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
        let mut shadow = Shadow { base: base as usize, len, windows, low: Vec::new() };
        for (first, n) in runs(read) {
            if !map_fixed(first, n) {
                return Err(format!(
                    "the capture read memory at {:#x}..{:#x}, which is in use in this process",
                    first * PAGE,
                    (first + n) * PAGE
                ));
            }
            shadow.low.push((first, n));
        }
        for (first, n) in runs(&pointed.difference(read).copied().collect()) {
            for page in first..first + n {
                if map_fixed(page, 1) {
                    shadow.low.push((page, 1));
                }
            }
        }
        Ok(shadow)
    }

    /// Page numbers below 4 GiB of a range of `len` bytes at `address` (none above).
    pub fn low_pages_of(address: u64, len: u64) -> impl Iterator<Item = u64> {
        let end = address.saturating_add(len).min(WINDOW);
        let first = address / PAGE;
        let last = if end > address { end.div_ceil(PAGE) } else { first };
        first..last
    }

    /// Writes `bytes` that the program had at captured `address`.
    pub fn write(&self, address: u64, bytes: &[u8]) -> Result<(), String> {
        let start = self.translate(address);
        let end = start.checked_add(bytes.len() as u64);
        let in_region = start >= self.base as u64 && end.is_some_and(|end| end <= (self.base + self.len) as u64);
        // Every page of a low range is mapped (possibly by adjacent runs).
        let in_low = end.is_some_and(|end| end <= WINDOW)
            && Shadow::low_pages_of(address, bytes.len() as u64).all(|p| self.low.iter().any(|&(f, n)| (f..f + n).contains(&p)));
        let inside = if address < WINDOW { in_low } else { in_region };
        if !inside {
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

impl AddressMap for Shadow {
    /// Where captured `address` is in the shadow; values below 4 GiB and in windows the
    /// capture does not use are returned unchanged.
    fn translate(&self, address: u64) -> u64 {
        match self.windows.binary_search(&(address >> 32)) {
            Ok(slot) => self.base as u64 + slot as u64 * WINDOW + (address & (WINDOW - 1)),
            Err(_) => address,
        }
    }

    /// The captured address of shadow `address` (inverse of [`AddressMap::translate`]);
    /// other addresses are returned unchanged.
    fn original(&self, address: u64) -> u64 {
        let offset = address.wrapping_sub(self.base as u64);
        match self.windows.get((offset / WINDOW) as usize) {
            Some(window) if address >= self.base as u64 => (window << 32) | (offset & (WINDOW - 1)),
            _ => address,
        }
    }
}

impl Drop for Shadow {
    fn drop(&mut self) {
        // Safety: the region was mapped by `new` with this length.
        unsafe { munmap(self.base as *mut c_void, self.len) };
        for &(first, n) in &self.low {
            // Safety: mapped by `new` at this address with this length.
            unsafe { munmap((first * PAGE) as *mut c_void, (n * PAGE) as usize) };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn addresses_translate_into_slots_and_back() {
        let windows: BTreeSet<u64> = [0x5555, 0x7ffc, 0x7ffd].into_iter().collect();
        let shadow = Shadow::new(&windows, &BTreeSet::new(), &BTreeSet::new()).unwrap();
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

    #[test]
    fn memory_below_4_gib_is_mapped_at_its_own_address() {
        // A non-PIE program's data (0x600000 in the program): here a free range at 3 GiB.
        let at = 0xc000_0ff0u64;
        let read: BTreeSet<u64> = Shadow::low_pages_of(at, 32).collect();
        assert_eq!(read.len(), 2, "the range crosses a page boundary");
        let pointed: BTreeSet<u64> = [at / PAGE + 5].into_iter().collect();
        let shadow = Shadow::new(&BTreeSet::new(), &read, &pointed).unwrap();
        assert_eq!(shadow.translate(at), at, "identity below 4 GiB");
        shadow.write(at, &[7; 32]).unwrap();
        assert_eq!(unsafe { std::slice::from_raw_parts(at as *const u8, 32) }, &[7; 32]);
        shadow.write(at + 5 * PAGE, &[1]).unwrap();
        assert!(shadow.write(at + 9 * PAGE, &[1]).is_err(), "a page neither read nor pointed to");
        assert!(shadow.write(at + 30, &[1; 4]).is_ok() && shadow.write(at + 2 * PAGE, &[1]).is_err());
        assert!(Shadow::new(&BTreeSet::new(), &read, &BTreeSet::new()).is_err(), "pages in use are refused");
    }
}

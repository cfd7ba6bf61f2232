//! A client array the GL writes into later (the selection and feedback buffers): its address
//! is kept as an integer so the context stays `Send`; writes are bounds-checked and counted,
//! so an overflow is detected as sections 5.2 and 5.3 require.

/// A client buffer of `size` values of `T`, filled from the start.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClientBuffer {
    address: usize,
    size: usize,
    /// Values produced since the last reset, written or not.
    count: usize,
}

impl ClientBuffer {
    /// A buffer at `ptr` of `size` values; a null pointer holds nothing.
    pub fn new<T>(ptr: *mut T, size: usize) -> ClientBuffer {
        ClientBuffer { address: ptr as usize, size: if ptr.is_null() { 0 } else { size }, count: 0 }
    }

    /// The buffer's address, for `glGetPointerv`.
    pub fn pointer(&self) -> *mut std::ffi::c_void {
        self.address as *mut std::ffi::c_void
    }

    /// Its size in values.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Values produced so far (more than [`Self::size`] after an overflow).
    pub fn count(&self) -> usize {
        self.count
    }

    /// Whether more values were produced than fit.
    pub fn overflowed(&self) -> bool {
        self.count > self.size
    }

    /// Starts again at the beginning of the buffer.
    pub fn reset(&mut self) {
        self.count = 0;
    }

    /// Appends `value` if there is room; counts it either way.
    ///
    /// # Safety
    /// The buffer must have been given as `size` writable values of `T` and still be valid, as
    /// `glSelectBuffer`/`glFeedbackBuffer` require of the program.
    pub unsafe fn push<T: Copy>(&mut self, value: T) {
        if self.count < self.size {
            // Safety: in bounds of the client buffer, which the caller guarantees is valid.
            unsafe { std::ptr::write_unaligned((self.address as *mut T).add(self.count), value) };
        }
        self.count = self.count.saturating_add(1);
    }
}

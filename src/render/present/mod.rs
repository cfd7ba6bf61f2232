//! Presentation: putting rendered frames on the application's X drawable.
//!
//! - [`presenter`]: [`Presenter`], what a renderer owns per target: picks the path and shows
//!   each frame ([`presenter::FrameImage`] is what it needs of the rendered frame).
//! - [`pixel_format`]: RGBA8 to the pixel layout of an X visual.
//! - [`swapchain`]: a Vulkan swapchain on the window (the normal path).
//! - [`window_output`]: the raster renderer's output that presents its frames.
//! - [`xlib`]: the fallback presenter, `XShmPutImage` (MIT-SHM) or `XPutImage` of a read-back.
//! - [`x_errors`]: the X error trap of the whole library (the GLX layer's requests too).
//!
//! What a context draws to ([`crate::frame::Target`]) reaches the renderer through
//! [`crate::frame::FrameSink::set_target`].
//!
//! Xlib requests go to the application's own `Display`, on the application's thread, inside
//! its `glXSwapBuffers`/`glFinish` (synchronously), so no display lock is needed beyond what
//! Xlib itself requires of a multi-threaded program (`XInitThreads`).

pub mod pixel_format;
pub mod presenter;
pub mod swapchain;
pub mod window_output;
pub mod x_errors;
pub mod xlib;

use std::collections::HashMap;

use parking_lot::Mutex;

pub use presenter::{FrameImage, Presenter};

/// How many times each display address was closed (see [`display_closed`]).
static CLOSES: Mutex<Option<HashMap<usize, u64>>> = Mutex::new(None);

/// Records that the application closed `display` (called from the window-system layer's
/// `XCloseDisplay` hook): presenters made for it stop issuing requests, and a display opened
/// later at the same address is told apart by its new [`display_epoch`].
pub fn display_closed(display: usize) {
    *CLOSES.lock().get_or_insert_with(HashMap::new).entry(display).or_default() += 1;
}

/// How many times `display`'s address was closed: a presenter remembers the value it was made
/// with and uses the display only while it is unchanged.
pub fn display_epoch(display: usize) -> u64 {
    CLOSES.lock().as_ref().and_then(|m| m.get(&display).copied()).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closing_a_display_changes_its_epoch_only() {
        let (a, b) = (0x1000_usize, 0x2000_usize);
        let (ea, eb) = (display_epoch(a), display_epoch(b));
        display_closed(a);
        assert_eq!(display_epoch(a), ea + 1);
        assert_eq!(display_epoch(b), eb);
    }
}

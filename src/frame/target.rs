//! Where a context's frames are shown: the size of its drawable and, for X drawables, the
//! application's display and the X drawable behind the GLX drawable.

use std::ffi::c_void;

/// An X window or pixmap of the application.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct XDrawable {
    /// The application's Xlib `Display*`.
    pub display: *mut c_void,
    /// The X window or pixmap (for a GLX window or pixmap, the X drawable it was made from,
    /// not the GLX name).
    pub drawable: u64,
}

// Safety: the display pointer is only dereferenced by Xlib, on the thread that calls the
// sink (the application's, inside its GLX call), as Xlib requires of its callers; a sink
// moving between threads with the context carries the pointer, not a use of it.
unsafe impl Send for XDrawable {}

/// What receives a context's frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// Nothing visible: pbuffers and headless contexts render off-screen.
    Offscreen,
    /// An X window: each presented frame is shown on it.
    Window(XDrawable),
    /// An X pixmap: receives each presented frame (GLX pixmaps are single-buffered, so frames
    /// end at `glFlush`/`glFinish`) with `XPutImage`.
    Pixmap(XDrawable),
}

impl Surface {
    /// The X drawable, for windows and pixmaps.
    pub fn x_drawable(&self) -> Option<XDrawable> {
        match *self {
            Surface::Offscreen => None,
            Surface::Window(d) | Surface::Pixmap(d) => Some(d),
        }
    }
}

/// Where frames go and how large they are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    /// Width and height of the drawable in pixels.
    pub size: [u32; 2],
    /// What shows the frames.
    pub surface: Surface,
    /// Swap interval of the drawable (GLX_EXT_swap_control and its MESA/SGI variants): 0 shows
    /// frames at once, 1 or more waits for vertical blank.
    pub swap_interval: u32,
    /// Samples per pixel of the drawable's configuration (`GLX_SAMPLES`, 1 when it is not
    /// multisampled).
    pub samples: u32,
    /// Whether the drawable's configuration has destination alpha (`GLX_ALPHA_SIZE` > 0).
    /// Without it `GL_ALPHA_BITS` is 0 and destination alpha is 1 wherever it is read
    /// (blending, read-back, copies, accumulation, presentation), whatever is drawn.
    pub alpha: bool,
}

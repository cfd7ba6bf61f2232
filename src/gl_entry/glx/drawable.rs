//! GLX drawables (GLX 1.4 section 3.3.5): GLX windows, GLX pixmaps and pbuffers, and the
//! per-drawable state of plain X windows used as drawables (GLX 1.2 style).
//!
//! Each GLX drawable gets a real XID: a 1×1 depth-1 X pixmap that glrt creates as its name
//! (depth 1 exists on every screen) and frees when the drawable is destroyed. glrt renders
//! into its own buffers, so a pbuffer is only its size and flags.

use std::collections::HashMap;
use std::ffi::{c_int, c_uint, c_ulong};

use parking_lot::Mutex;
use x11_dl::xlib::{self, Xlib};

use super::XDisplay;
use crate::frame::{Surface, Target, XDrawable};
use crate::render::present::x_errors;

/// What a drawable is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `glXCreateWindow` on this X window.
    Window(xlib::Window),
    /// `glXCreatePixmap`/`glXCreateGLXPixmap` on this X pixmap.
    Pixmap(xlib::Pixmap),
    /// `glXCreatePbuffer`.
    Pbuffer {
        /// Width in pixels.
        width: c_int,
        /// Height in pixels.
        height: c_int,
        /// `GLX_PRESERVED_CONTENTS`.
        preserved: bool,
        /// `GLX_LARGEST_PBUFFER`.
        largest: bool,
    },
    /// A plain X window or pixmap given directly to `glXMakeCurrent`.
    X,
}

/// A drawable's GLX state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drawable {
    /// What it is.
    pub kind: Kind,
    /// `GLX_FBCONFIG_ID` of its configuration (0 for plain X drawables).
    pub config_id: c_int,
    /// `glXSelectEvent` mask.
    pub event_mask: c_ulong,
    /// `GLX_SWAP_INTERVAL_EXT` (GLX_EXT_swap_control: 1 by default).
    pub swap_interval: c_int,
}

impl Drawable {
    /// A drawable of `kind` with default state.
    pub fn new(kind: Kind, config_id: c_int) -> Drawable {
        Drawable { kind, config_id, event_mask: 0, swap_interval: 1 }
    }
}

type Key = (usize, xlib::XID);

static DRAWABLES: Mutex<Option<HashMap<Key, Drawable>>> = Mutex::new(None);

fn with_table<R>(f: impl FnOnce(&mut HashMap<Key, Drawable>) -> R) -> R {
    f(DRAWABLES.lock().get_or_insert_with(HashMap::new))
}

/// The state of drawable `xid` of `dpy`, if it is a GLX drawable or has state.
pub fn get(dpy: *mut XDisplay, xid: xlib::XID) -> Option<Drawable> {
    with_table(|t| t.get(&(dpy as usize, xid)).copied())
}

/// Records a drawable.
pub fn insert(dpy: *mut XDisplay, xid: xlib::XID, drawable: Drawable) {
    with_table(|t| t.insert((dpy as usize, xid), drawable));
}

/// Updates the state of `xid`, creating it as a plain X drawable if it has none.
pub fn update(dpy: *mut XDisplay, xid: xlib::XID, f: impl FnOnce(&mut Drawable)) {
    with_table(|t| f(t.entry((dpy as usize, xid)).or_insert_with(|| Drawable::new(Kind::X, 0))));
}

/// Forgets every drawable of a closed display (their XIDs died with the connection).
pub fn forget_display(dpy: usize) {
    with_table(|t| t.retain(|&(d, _), _| d != dpy));
}

/// Whether some GLX drawable of `dpy` is already made from the X drawable `target`.
pub fn wraps(dpy: *mut XDisplay, target: xlib::XID) -> bool {
    with_table(|t| {
        t.iter().any(|(&(d, _), v)| d == dpy as usize && matches!(v.kind, Kind::Window(w) | Kind::Pixmap(w) if w == target))
    })
}

/// Removes the drawable `xid` when `accept` says its kind is the one being destroyed, and
/// frees its name. Returns false when there is no such drawable.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn destroy(x: &Xlib, dpy: *mut XDisplay, xid: xlib::XID, accept: impl Fn(&Kind) -> bool) -> bool {
    let removed = with_table(|t| {
        let key = (dpy as usize, xid);
        let ok = t.get(&key).is_some_and(|d| accept(&d.kind));
        ok.then(|| t.remove(&key)).flatten()
    });
    if removed.is_some() {
        // Safety: the name is a pixmap glrt created on this display.
        let _ = unsafe { x_errors::trapped(x, dpy, || (x.XFreePixmap)(dpy, xid)) };
    }
    removed.is_some()
}

/// A new XID naming a GLX drawable on `screen` (see the module documentation); `None` when
/// the server refuses.
///
/// # Safety
/// `dpy` is a live display and `screen` one of its screens.
pub unsafe fn new_name(x: &Xlib, dpy: *mut XDisplay, screen: c_int) -> Option<xlib::XID> {
    // Safety: as documented; errors are trapped.
    unsafe {
        let root = (x.XRootWindow)(dpy, screen);
        x_errors::trapped(x, dpy, || (x.XCreatePixmap)(dpy, root, 1, 1, 1)).ok().filter(|&p| p != 0)
    }
}

/// Geometry of an X drawable: `(width, height, depth)`, `None` when it does not exist.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn x_geometry(x: &Xlib, dpy: *mut XDisplay, xid: xlib::XID) -> Option<(c_int, c_int, c_uint)> {
    let (mut root, mut px, mut py, mut w, mut h, mut border, mut depth) = (0, 0, 0, 0, 0, 0, 0);
    // Safety: the out-pointers are valid; a bad drawable is an error that is trapped.
    let status = unsafe {
        x_errors::trapped_reply(x, dpy, || {
            (x.XGetGeometry)(dpy, xid, &mut root, &mut px, &mut py, &mut w, &mut h, &mut border, &mut depth)
        })
    };
    matches!(status, Ok(s) if s != 0).then_some((w as c_int, h as c_int, depth))
}

/// The visual of X window `window`, `None` when it does not exist.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn window_visual(x: &Xlib, dpy: *mut XDisplay, window: xlib::Window) -> Option<c_ulong> {
    // Safety: a zeroed XWindowAttributes is a valid out-parameter; errors are trapped.
    unsafe {
        let mut attrs: xlib::XWindowAttributes = std::mem::zeroed();
        let status = x_errors::trapped(x, dpy, || (x.XGetWindowAttributes)(dpy, window, &mut attrs));
        match status {
            Ok(s) if s != 0 && !attrs.visual.is_null() => Some((x.XVisualIDFromVisual)(attrs.visual)),
            _ => None,
        }
    }
}

/// Size of a drawable (a GLX drawable or a plain X window or pixmap); `None` when it does not
/// exist (`GLXBadDrawable`).
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn size(x: &Xlib, dpy: *mut XDisplay, xid: xlib::XID) -> Option<(c_int, c_int)> {
    let target = match get(dpy, xid).map(|d| d.kind) {
        Some(Kind::Pbuffer { width, height, .. }) => return Some((width, height)),
        Some(Kind::Window(w)) => w,
        Some(Kind::Pixmap(p)) => p,
        Some(Kind::X) | None => xid,
    };
    // Safety: forwarded.
    unsafe { x_geometry(x, dpy, target) }.map(|(w, h, _)| (w, h))
}

/// Where frames drawn to `xid` (of `width` × `height`) go: the X window or pixmap behind it
/// (pbuffers render off-screen), with the drawable's swap interval and the `samples` and
/// destination `alpha` of the context's configuration. A plain X drawable is a window when it
/// has window attributes.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn target(x: &Xlib, dpy: *mut XDisplay, xid: xlib::XID, [width, height]: [c_int; 2], samples: u32, alpha: bool) -> Target {
    let on = |drawable| XDrawable { display: dpy.cast(), drawable };
    let surface = match get(dpy, xid).map(|d| d.kind) {
        Some(Kind::Pbuffer { .. }) => Surface::Offscreen,
        Some(Kind::Window(w)) => Surface::Window(on(w)),
        Some(Kind::Pixmap(p)) => Surface::Pixmap(on(p)),
        // Safety: forwarded.
        Some(Kind::X) | None if unsafe { window_visual(x, dpy, xid) }.is_some() => Surface::Window(on(xid)),
        Some(Kind::X) | None => Surface::Pixmap(on(xid)),
    };
    let swap_interval = get(dpy, xid).map_or(1, |d| d.swap_interval.max(0) as u32);
    Target { size: [width.max(0) as u32, height.max(0) as u32], surface, swap_interval, samples, alpha }
}

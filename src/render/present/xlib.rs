//! The Xlib presenter: puts a read-back RGBA8 image on the application's X window or pixmap,
//! converted to the drawable's visual ([`super::pixel_format`]). It is the path when no Vulkan
//! swapchain can present to the window (an NVIDIA GPU with Xvfb, a remote display) and for
//! pixmaps.
//!
//! Transport: MIT-SHM (`XShmPutImage` from a shared segment: no copy through the socket) when
//! the server has the extension and accepts the segment (it refuses it from a remote client,
//! which glrt sees as an error of `XShmAttach`); otherwise `XPutImage` (Xlib splits large
//! images into several requests). The segment is not rewritten until the server finished
//! reading it: the previous put is waited for (one `XSync`) just before the next frame is
//! written, so the server's copy overlaps the program's next frame.

use std::ffi::{c_int, c_uint, c_void};
use std::sync::OnceLock;

use x11_dl::xlib::{self, Xlib};
use x11_dl::xshm::{XShmSegmentInfo, Xext};

use super::display_epoch;
use super::x_errors::trapped;
use super::pixel_format::PixelFormat;
use crate::frame::{Surface, XDrawable};

/// Xlib, loaded once (the application's `libX11.so.6` is already in the process).
fn xlib_fns() -> Option<&'static Xlib> {
    static XLIB: OnceLock<Option<Xlib>> = OnceLock::new();
    XLIB.get_or_init(|| Xlib::open().map_err(|e| log::error!("present: cannot load Xlib: {e}")).ok()).as_ref()
}

/// `libXext` (MIT-SHM), loaded once; `None` when absent (`XPutImage` is used).
fn xext_fns() -> Option<&'static Xext> {
    static XEXT: OnceLock<Option<Xext>> = OnceLock::new();
    XEXT.get_or_init(|| Xext::open().map_err(|e| log::info!("present: no libXext, no MIT-SHM: {e}")).ok()).as_ref()
}

unsafe extern "C" {
    fn shmget(key: c_int, size: usize, flags: c_int) -> c_int;
    fn shmat(id: c_int, addr: *const c_void, flags: c_int) -> *mut c_void;
    fn shmdt(addr: *const c_void) -> c_int;
    fn shmctl(id: c_int, cmd: c_int, buf: *mut c_void) -> c_int;
}
const IPC_PRIVATE: c_int = 0;
const IPC_CREAT: c_int = 0o1000;
const IPC_RMID: c_int = 0;

/// Where an image's pixels live.
enum Pixels {
    /// A shared memory segment attached by the server. Boxed: the `XImage` keeps a pointer to
    /// it (`obdata`, read by `XShmPutImage`), so it must not move.
    Shared(Box<XShmSegmentInfo>),
    /// Client memory sent with `XPutImage`.
    Owned(Vec<u8>),
}

/// An image of the drawable's visual, filled by glrt.
struct Image {
    ximage: *mut xlib::XImage,
    pixels: Pixels,
    format: PixelFormat,
    size: [u32; 2],
}

/// Shows RGBA8 frames on one X drawable with Xlib.
pub struct XlibPresenter {
    x: &'static Xlib,
    target: XDrawable,
    /// [`display_epoch`] of the display when this presenter was made.
    epoch: u64,
    visual: *mut xlib::Visual,
    depth: c_uint,
    gc: xlib::GC,
    /// MIT-SHM, while the server has it and accepts glrt's segments.
    shm: Option<&'static Xext>,
    image: Option<Image>,
    /// An `XShmPutImage` of the segment may still be running.
    in_flight: bool,
}

// Safety: the raw pointers are Xlib objects of the application's display, used only by the
// thread presenting (see the module documentation of `present`).
unsafe impl Send for XlibPresenter {}

impl XlibPresenter {
    /// A presenter for the window or pixmap of `surface`; `None` for an off-screen surface,
    /// without Xlib, or when the drawable is gone or its visual is not TrueColor.
    ///
    /// # Safety
    /// The surface's display is the application's live display.
    pub unsafe fn new(surface: Surface) -> Option<XlibPresenter> {
        let x = xlib_fns()?;
        let target = surface.x_drawable()?;
        let dpy = target.display.cast::<xlib::Display>();
        // Safety: as documented.
        let (visual, depth) = unsafe { visual_of(x, dpy, surface)? };
        // Safety: `dpy` is live; a bad drawable is trapped.
        let gc = unsafe { trapped(x, dpy, || (x.XCreateGC)(dpy, target.drawable, 0, std::ptr::null_mut())) }.ok()?;
        // Safety: `dpy` is live.
        let shm = xext_fns().filter(|e| unsafe { (e.XShmQueryExtension)(dpy) } != 0);
        let epoch = display_epoch(target.display as usize);
        Some(XlibPresenter { x, target, epoch, visual, depth, gc, shm, image: None, in_flight: false })
    }

    /// Whether frames go through MIT-SHM (for logs and tests; false before the first frame
    /// when the server lacks the extension, or once it refused a segment).
    pub fn uses_shm(&self) -> bool {
        self.shm.is_some() && self.image.as_ref().is_none_or(|i| matches!(i.pixels, Pixels::Shared(_)))
    }

    /// Stops using MIT-SHM: later frames go through `XPutImage`.
    pub fn disable_shm(&mut self) {
        // The segment is detached while MIT-SHM is still known.
        self.release_image();
        self.shm = None;
    }

    /// Puts `rgba` (`size[0]` × `size[1]` RGBA8 pixels, rows bottom to top when `bottom_up`,
    /// else top to bottom) on the drawable,
    /// its top-left corner at the drawable's. Returns false when nothing could be shown: the
    /// display was closed, the buffer is too small, or no image could be made.
    pub fn present(&mut self, size: [u32; 2], rgba: &[u8], bottom_up: bool) -> bool {
        if !self.display_open() {
            self.release_image();
            return false;
        }
        let [w, h] = size;
        if w == 0 || h == 0 {
            return true;
        }
        if rgba.len() < w as usize * h as usize * 4 {
            return false;
        }
        if self.image.as_ref().is_none_or(|i| i.size != size) {
            self.release_image();
            self.image = self.make_image(size);
        }
        let dpy = self.display();
        let x = self.x;
        if std::mem::take(&mut self.in_flight) {
            // Safety: the display is open.
            unsafe { (x.XSync)(dpy, xlib::False) };
        }
        let Some(image) = self.image.as_mut() else { return false };
        // Safety: `ximage` is live; its data holds `bytes_per_line * height` bytes.
        let stride = unsafe { (*image.ximage).bytes_per_line } as usize;
        let data = match &mut image.pixels {
            // Safety: the segment was created with `stride * h` bytes.
            Pixels::Shared(info) => unsafe { std::slice::from_raw_parts_mut(info.shmaddr.cast::<u8>(), stride * h as usize) },
            Pixels::Owned(v) => v.as_mut_slice(),
        };
        if !image.format.convert(rgba, w as usize, h as usize, bottom_up, data, stride) {
            return false;
        }
        // Safety: the display is open; the GC and the image belong to it.
        unsafe {
            match (&image.pixels, self.shm) {
                (Pixels::Shared(_), Some(ext)) => {
                    (ext.XShmPutImage)(dpy, self.target.drawable, self.gc, image.ximage, 0, 0, 0, 0, w, h, xlib::False);
                    self.in_flight = true;
                }
                _ => {
                    (x.XPutImage)(dpy, self.target.drawable, self.gc, image.ximage, 0, 0, 0, 0, w, h);
                }
            }
            (x.XFlush)(dpy);
        }
        true
    }

    fn display(&self) -> *mut xlib::Display {
        self.target.display.cast()
    }

    /// Whether the display this presenter was made for is still open.
    fn display_open(&self) -> bool {
        display_epoch(self.target.display as usize) == self.epoch
    }

    /// A new image of `size`: shared when MIT-SHM works, else owned (and MIT-SHM is given up
    /// when the server refused the segment).
    fn make_image(&mut self, size: [u32; 2]) -> Option<Image> {
        if let Some(ext) = self.shm {
            // Safety: the display is open.
            match unsafe { self.shared_image(ext, size) } {
                Some(image) => return Some(image),
                None => {
                    log::info!("present: MIT-SHM unavailable for this display, using XPutImage");
                    self.shm = None;
                }
            }
        }
        // Safety: the display is open.
        unsafe { self.owned_image(size) }
    }

    /// # Safety
    /// The display is open.
    unsafe fn shared_image(&self, ext: &Xext, [w, h]: [u32; 2]) -> Option<Image> {
        let (x, dpy) = (self.x, self.display());
        // Safety (all): the display is open; every object made here is freed on failure.
        unsafe {
            let mut info: Box<XShmSegmentInfo> = Box::new(std::mem::zeroed());
            let ximage = (ext.XShmCreateImage)(dpy, self.visual, self.depth, xlib::ZPixmap, std::ptr::null_mut(), &mut *info, w, h);
            if ximage.is_null() {
                return None;
            }
            // `XDestroyImage` frees `obdata`, which points to the boxed `info`: it is cleared
            // before every `XDestroyImage` of this image.
            (*ximage).obdata = std::ptr::null_mut();
            let Some(format) = image_format(ximage) else {
                (x.XDestroyImage)(ximage);
                return None;
            };
            let bytes = (*ximage).bytes_per_line as usize * h as usize;
            info.shmid = shmget(IPC_PRIVATE, bytes, IPC_CREAT | 0o600);
            let addr = if info.shmid >= 0 { shmat(info.shmid, std::ptr::null(), 0) } else { usize::MAX as *mut c_void };
            if addr as usize == usize::MAX {
                if info.shmid >= 0 {
                    shmctl(info.shmid, IPC_RMID, std::ptr::null_mut());
                }
                (x.XDestroyImage)(ximage);
                return None;
            }
            info.shmaddr = addr.cast();
            info.readOnly = xlib::False;
            (*ximage).data = info.shmaddr;
            (*ximage).obdata = (&mut *info as *mut XShmSegmentInfo).cast();
            let attached = matches!(trapped(x, dpy, || (ext.XShmAttach)(dpy, &mut *info)), Ok(ok) if ok != 0);
            // Marked for removal now: the kernel frees it once both sides detached (also
            // when the program exits without cleaning up).
            shmctl(info.shmid, IPC_RMID, std::ptr::null_mut());
            if !attached {
                (*ximage).data = std::ptr::null_mut();
                (*ximage).obdata = std::ptr::null_mut();
                (x.XDestroyImage)(ximage);
                shmdt(addr);
                return None;
            }
            Some(Image { ximage, pixels: Pixels::Shared(info), format, size: [w, h] })
        }
    }

    /// # Safety
    /// The display is open.
    unsafe fn owned_image(&self, [w, h]: [u32; 2]) -> Option<Image> {
        let (x, dpy) = (self.x, self.display());
        // Safety: the display is open; the image's data is pointed at memory it does not own
        // and reset before `XDestroyImage`.
        unsafe {
            let ximage = (x.XCreateImage)(dpy, self.visual, self.depth, xlib::ZPixmap, 0, std::ptr::null_mut(), w, h, 32, 0);
            if ximage.is_null() {
                return None;
            }
            let Some(format) = image_format(ximage) else {
                (x.XDestroyImage)(ximage);
                return None;
            };
            let mut data = vec![0u8; (*ximage).bytes_per_line as usize * h as usize];
            (*ximage).data = data.as_mut_ptr().cast();
            Some(Image { ximage, pixels: Pixels::Owned(data), format, size: [w, h] })
        }
    }

    /// Frees the current image; server-side state only while the display is open.
    fn release_image(&mut self) {
        let Some(image) = self.image.take() else { return };
        let open = self.display_open();
        // Safety: the image was made by this presenter; its data and segment information are
        // detached from the XImage before `XDestroyImage`, which would free them.
        unsafe {
            (*image.ximage).data = std::ptr::null_mut();
            (*image.ximage).obdata = std::ptr::null_mut();
            (self.x.XDestroyImage)(image.ximage);
            if let Pixels::Shared(mut info) = image.pixels {
                if let (true, Some(ext)) = (open, self.shm) {
                    (ext.XShmDetach)(self.display(), &mut *info);
                    (self.x.XSync)(self.display(), xlib::False);
                }
                shmdt(info.shmaddr.cast());
            }
        }
        self.in_flight = false;
    }
}

impl Drop for XlibPresenter {
    fn drop(&mut self) {
        self.release_image();
        if self.display_open() {
            // Safety: the GC was created on this open display.
            unsafe { (self.x.XFreeGC)(self.display(), self.gc) };
        }
    }
}

/// The pixel layout of an image, from its masks, depth, bits per pixel and byte order.
///
/// # Safety
/// `ximage` is a live image.
unsafe fn image_format(ximage: *const xlib::XImage) -> Option<PixelFormat> {
    // Safety: as documented.
    let i = unsafe { &*ximage };
    let masks = [i.red_mask as u32, i.green_mask as u32, i.blue_mask as u32];
    let format = PixelFormat::new(masks, i.depth as u32, i.bits_per_pixel as u32, i.byte_order == xlib::MSBFirst);
    if format.is_none() {
        log::warn!("present: unsupported X image layout (depth {}, {} bits per pixel, masks {masks:x?})", i.depth, i.bits_per_pixel);
    }
    format
}

/// The visual and depth to draw into `surface` with: a window's own; for a pixmap, a
/// TrueColor visual of its depth on its screen.
///
/// # Safety
/// `dpy` is a live display.
unsafe fn visual_of(x: &Xlib, dpy: *mut xlib::Display, surface: Surface) -> Option<(*mut xlib::Visual, c_uint)> {
    // Safety (all): `dpy` is live; requests on a missing drawable are trapped.
    unsafe {
        match surface {
            Surface::Offscreen => None,
            Surface::Window(d) => {
                let mut attrs: xlib::XWindowAttributes = std::mem::zeroed();
                let ok = trapped(x, dpy, || (x.XGetWindowAttributes)(dpy, d.drawable, &mut attrs));
                (matches!(ok, Ok(s) if s != 0) && !attrs.visual.is_null()).then_some((attrs.visual, attrs.depth as c_uint))
            }
            Surface::Pixmap(d) => {
                let (mut root, mut px, mut py, mut w, mut h, mut border, mut depth) = (0, 0, 0, 0, 0, 0, 0);
                let ok = trapped(x, dpy, || {
                    (x.XGetGeometry)(dpy, d.drawable, &mut root, &mut px, &mut py, &mut w, &mut h, &mut border, &mut depth)
                });
                if !matches!(ok, Ok(s) if s != 0) {
                    return None;
                }
                let screen = (0..(x.XScreenCount)(dpy)).find(|&s| (x.XRootWindow)(dpy, s) == root)?;
                let mut info: xlib::XVisualInfo = std::mem::zeroed();
                let found = (x.XMatchVisualInfo)(dpy, screen, depth as c_int, xlib::TrueColor, &mut info) != 0;
                found.then_some((info.visual, depth))
            }
        }
    }
}

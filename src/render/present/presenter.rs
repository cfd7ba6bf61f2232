//! Chooses how a renderer's frames reach its [`Target`] and shows them: the Vulkan swapchain
//! when the device can present to the window, else the Xlib presenter with a read-back
//! (also for pixmaps, and after the swapchain failed), nothing for off-screen targets.
//!
//! `GLRT_PRESENT=xlib` forces the Xlib path on windows (`auto`, the default, prefers Vulkan;
//! `vulkan` is the same as `auto`: without a usable swapchain there is no other way to show
//! a frame).

use super::display_epoch;
use super::swapchain::{Gpu, Presented, Source, SwapchainPresenter};
use super::xlib::XlibPresenter;
use crate::frame::{Surface, Target};

/// The rendered frame as a presenter needs it: the GPU image for a swapchain, or its pixels.
pub trait FrameImage {
    /// The colour image and its layout, for a swapchain blit.
    fn source(&self) -> Source;
    /// The image read back: `size[0] * size[1]` RGBA8 pixels, rows in the order
    /// [`Source::bottom_up`] says; `None` when it cannot be read.
    fn read_rgba(&mut self) -> Option<Vec<u8>>;
}

/// How frames are shown now.
enum Path {
    /// Off-screen: nothing to show.
    Offscreen,
    /// A Vulkan swapchain on the window.
    Swapchain(Box<SwapchainPresenter>),
    /// Xlib, from a read-back.
    Xlib(XlibPresenter),
    /// The drawable cannot be shown (gone, or an unsupported visual): frames are dropped.
    Nowhere,
}

/// Shows frames on one target.
pub struct Presenter {
    target: Target,
    path: Path,
    /// [`display_epoch`] of the target's display when the presenter was made.
    epoch: u64,
}

/// Whether `GLRT_PRESENT` asks for the Xlib path.
fn xlib_forced() -> bool {
    static FORCED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *FORCED.get_or_init(|| match std::env::var("GLRT_PRESENT").as_deref() {
        Ok("xlib") => true,
        Ok("auto" | "vulkan") | Err(_) => false,
        Ok(other) => {
            log::warn!("GLRT_PRESENT={other} is not auto, vulkan or xlib: using auto");
            false
        }
    })
}

impl Presenter {
    /// A presenter for `target`; `gpu` is the renderer's device when its instance and device
    /// have the presentation extensions ([`super::swapchain::INSTANCE_EXTENSIONS`]).
    ///
    /// # Safety
    /// The target's display (if any) is the application's live display; `gpu` outlives the
    /// presenter.
    pub unsafe fn new(target: Target, gpu: Option<&Gpu>) -> Presenter {
        let path = match target.surface {
            Surface::Offscreen => Path::Offscreen,
            Surface::Window(window) => {
                // Safety: as documented.
                let chain = gpu.filter(|_| !xlib_forced()).map(|gpu| unsafe {
                    SwapchainPresenter::new(gpu, window, target.size, target.swap_interval)
                });
                match chain {
                    Some(Ok(chain)) => Path::Swapchain(Box::new(chain)),
                    Some(Err(why)) => {
                        log::info!("present: no Vulkan swapchain on window {:#x} ({why:?}): using Xlib", window.drawable);
                        // Safety: as documented.
                        unsafe { xlib_path(target.surface) }
                    }
                    // Safety: as documented.
                    None => unsafe { xlib_path(target.surface) },
                }
            }
            // Safety: as documented.
            Surface::Pixmap(_) => unsafe { xlib_path(target.surface) },
        };
        log::info!("present: {:?} through {}", target.surface, path_name(&path));
        Presenter { target, path, epoch: epoch_of(&target) }
    }

    /// `"vulkan"`, `"xlib"`, `"offscreen"` or `"none"`: the path in use (for logs and tests).
    pub fn path(&self) -> &'static str {
        path_name(&self.path)
    }

    /// Whether frames reach a drawable (not off-screen, not a drawable that cannot be shown).
    pub fn shows_frames(&self) -> bool {
        matches!(self.path, Path::Swapchain(_) | Path::Xlib(_))
    }

    /// Whether frames must be read back for this path (the renderer may skip rendering to
    /// host memory otherwise).
    pub fn needs_pixels(&self) -> bool {
        matches!(self.path, Path::Xlib(_))
    }

    /// Follows a new target: a new size or swap interval keeps the path (the swapchain is
    /// recreated), another drawable gets a new presenter.
    ///
    /// # Safety
    /// As for [`Presenter::new`].
    pub unsafe fn retarget(&mut self, target: Target, gpu: Option<&Gpu>) {
        if target.surface != self.target.surface {
            // The old presenter goes first: it may use the same window.
            self.path = Path::Nowhere;
            // Safety: as documented.
            *self = unsafe { Presenter::new(target, gpu) };
            return;
        }
        self.target = target;
        if let Path::Swapchain(chain) = &mut self.path {
            chain.resize(target.size, target.swap_interval);
        }
    }

    /// Shows `frame`. A swapchain that fails for good is replaced by the Xlib path, which
    /// shows this frame. Returns whether the frame reached the drawable.
    ///
    /// # Safety
    /// `frame`'s image satisfies [`SwapchainPresenter::present`]; the display is live.
    pub unsafe fn show(&mut self, frame: &mut dyn FrameImage) -> bool {
        if epoch_of(&self.target) != self.epoch {
            // The application closed the display: nothing may use it any more.
            self.path = Path::Nowhere;
        }
        match &mut self.path {
            Path::Offscreen | Path::Nowhere => false,
            // Safety: as documented.
            Path::Swapchain(chain) => match unsafe { chain.present(&frame.source()) } {
                Ok(Presented::Shown) => true,
                Ok(Presented::Skipped) => false,
                Err(why) => {
                    log::warn!("present: the swapchain failed ({why:?}): using Xlib from now on");
                    self.path = Path::Nowhere;
                    // Safety: as documented.
                    self.path = unsafe { xlib_path(self.target.surface) };
                    // Safety: as documented.
                    unsafe { self.show(frame) }
                }
            },
            Path::Xlib(xlib) => {
                let Source { size, bottom_up, .. } = frame.source();
                frame.read_rgba().is_some_and(|rgba| xlib.present(size, &rgba, bottom_up))
            }
        }
    }
}

/// The Xlib presenter for `surface`, or [`Path::Nowhere`].
///
/// # Safety
/// The surface's display is live.
unsafe fn xlib_path(surface: Surface) -> Path {
    // Safety: as documented.
    match unsafe { XlibPresenter::new(surface) } {
        Some(p) => Path::Xlib(p),
        None => {
            log::warn!("present: cannot show frames on {surface:?}");
            Path::Nowhere
        }
    }
}

/// The [`display_epoch`] of the target's display (0 off-screen).
fn epoch_of(target: &Target) -> u64 {
    target.surface.x_drawable().map_or(0, |d| display_epoch(d.display as usize))
}

fn path_name(path: &Path) -> &'static str {
    match path {
        Path::Offscreen => "offscreen",
        Path::Swapchain(_) => "vulkan",
        Path::Xlib(_) => "xlib",
        Path::Nowhere => "none",
    }
}

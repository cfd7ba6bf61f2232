//! glrt as a glvnd GLX vendor library: the same shared object, installed as
//! `libGLX_glrt.so.0`, is loaded by glvnd's `libGLX.so.0` when `__GLX_VENDOR_LIBRARY_NAME=glrt`.
//!
//! The vendor ABI is libglvnd's `include/glvnd/libglxabi.h` (ABI 1.x; Debian's libglvnd 1.6 passes
//! 1.0): libGLX calls the exported [`__glx_Main`], which fills in the [`GlxApiImports`] callbacks.
//! libGLX then fetches the GLX 1.4 functions and every GL function through `getProcAddress`
//! (libGLdispatch builds the vendor's GL table from it and switches to it on make-current). GLX
//! extension functions that libGLX does not know get vendor-neutral dispatch functions here,
//! which find the right vendor through libGLX's [`GlxApiExports`] (`src/GLX/libglxmapping.c`).

use std::ffi::{CStr, c_char, c_int, c_uint, c_ulong, c_void};
use std::sync::atomic::{AtomicI32, AtomicPtr, Ordering};

use x11_dl::glx::GLX_BAD_CONTEXT;

use super::exports::proc_address;
use super::glx::guard;
use super::shim::Proc;

/// Xlib `Bool`.
pub type Bool = c_int;
/// Opaque `Display`.
type Display = c_void;
/// Opaque `__GLXvendorInfo`: libGLX's handle for one vendor.
type VendorInfo = c_void;
/// `GLXDrawable` (an XID).
type GlxDrawable = c_ulong;
/// `GLXContext` and `GLXFBConfig` as libGLX passes them through.
type Handle = *mut c_void;
/// `__GLXextFuncPtr`: any function pointer, null when absent.
type ExtFuncPtr = *const c_void;

/// `GLX_VENDOR_ABI_MAJOR_VERSION`: a vendor built for major version 1 works with any 1.x libGLX.
pub const ABI_MAJOR_VERSION: u32 = 1;
/// `GLX_VENDOR_ABI_MINOR_VERSION` of the header glrt follows.
pub const ABI_MINOR_VERSION: u32 = 0;

/// `__GLXapiExports`: the functions libGLX gives a vendor's dispatch functions (field order and
/// types exactly as in `libglxabi.h`; fields glrt does not call are still declared for layout).
#[repr(C)]
#[allow(non_snake_case)]
pub struct GlxApiExports {
    /// `getDynDispatch(dpy, screen)`: the vendor of a screen.
    pub getDynDispatch: Option<unsafe extern "C" fn(*mut Display, c_int) -> *mut VendorInfo>,
    /// `getCurrentDynDispatch()`: the vendor of the current context, or null.
    pub getCurrentDynDispatch: Option<unsafe extern "C" fn() -> *mut VendorInfo>,
    /// `fetchDispatchEntry(vendor, index)`: a vendor's function for a dispatch index.
    pub fetchDispatchEntry: Option<unsafe extern "C" fn(*mut VendorInfo, c_int) -> ExtFuncPtr>,
    /// `getCurrentContext()`.
    pub getCurrentContext: Option<unsafe extern "C" fn() -> Handle>,
    /// `addVendorContextMapping(dpy, context, vendor)`.
    pub addVendorContextMapping: Option<unsafe extern "C" fn(*mut Display, Handle, *mut VendorInfo) -> c_int>,
    /// `removeVendorContextMapping(dpy, context)`.
    pub removeVendorContextMapping: Option<unsafe extern "C" fn(*mut Display, Handle)>,
    /// `vendorFromContext(context)`.
    pub vendorFromContext: Option<unsafe extern "C" fn(Handle) -> *mut VendorInfo>,
    /// `addVendorFBConfigMapping(dpy, config, vendor)`.
    pub addVendorFBConfigMapping: Option<unsafe extern "C" fn(*mut Display, Handle, *mut VendorInfo) -> c_int>,
    /// `removeVendorFBConfigMapping(dpy, config)`.
    pub removeVendorFBConfigMapping: Option<unsafe extern "C" fn(*mut Display, Handle)>,
    /// `vendorFromFBConfig(dpy, config)`.
    pub vendorFromFBConfig: Option<unsafe extern "C" fn(*mut Display, Handle) -> *mut VendorInfo>,
    /// `addVendorDrawableMapping(dpy, drawable, vendor)`.
    pub addVendorDrawableMapping: Option<unsafe extern "C" fn(*mut Display, GlxDrawable, *mut VendorInfo) -> c_int>,
    /// `removeVendorDrawableMapping(dpy, drawable)`.
    pub removeVendorDrawableMapping: Option<unsafe extern "C" fn(*mut Display, GlxDrawable)>,
    /// `vendorFromDrawable(dpy, drawable)`: the vendor of a drawable.
    pub vendorFromDrawable: Option<unsafe extern "C" fn(*mut Display, GlxDrawable) -> *mut VendorInfo>,
}

/// `__GLXapiImports`: the callbacks a vendor fills in (layout exactly as in `libglxabi.h`).
#[repr(C)]
#[allow(non_snake_case)]
pub struct GlxApiImports {
    /// `isScreenSupported(dpy, screen)` (required).
    pub isScreenSupported: Option<unsafe extern "C" fn(*mut Display, c_int) -> Bool>,
    /// `getProcAddress(procName)`: a GLX or GL function (required).
    pub getProcAddress: Option<unsafe extern "C" fn(*const u8) -> *mut c_void>,
    /// `getDispatchAddress(procName)`: a vendor-neutral GLX extension dispatcher (required).
    pub getDispatchAddress: Option<unsafe extern "C" fn(*const u8) -> *mut c_void>,
    /// `setDispatchIndex(procName, index)` (required).
    pub setDispatchIndex: Option<unsafe extern "C" fn(*const u8, c_int)>,
    /// `notifyError(dpy, error, resid, opcode, coreX11error)` (optional).
    pub notifyError: Option<unsafe extern "C" fn(*mut Display, u8, c_ulong, u8, Bool) -> Bool>,
    /// `isPatchSupported(type, stubSize)` (optional).
    pub isPatchSupported: Option<unsafe extern "C" fn(c_int, c_int) -> u8>,
    /// `initiatePatch(type, stubSize, lookupStubOffset)` (optional).
    pub initiatePatch: Option<unsafe extern "C" fn(c_int, c_int, *const c_void) -> u8>,
    /// `releasePatch()` (optional).
    pub releasePatch: Option<unsafe extern "C" fn()>,
    /// `patchThreadAttach()` (optional).
    pub patchThreadAttach: Option<unsafe extern "C" fn()>,
}

/// The GLX functions libGLX fetches from a vendor at load time (`LookupVendorEntrypoints` in
/// `libglxmapping.c`): the 32 required GLX 1.4 functions, then the optional
/// `glXCreateContextAttribsARB` (glrt does not offer `glXImportContextEXT`/`glXFreeContextEXT`).
const STATIC_GLX: [&str; 33] = [
    "glXChooseFBConfig",
    "glXChooseVisual",
    "glXCopyContext",
    "glXCreateContext",
    "glXCreateContextAttribsARB",
    "glXCreateGLXPixmap",
    "glXCreateNewContext",
    "glXCreatePbuffer",
    "glXCreatePixmap",
    "glXCreateWindow",
    "glXDestroyContext",
    "glXDestroyGLXPixmap",
    "glXDestroyPbuffer",
    "glXDestroyPixmap",
    "glXDestroyWindow",
    "glXGetClientString",
    "glXGetConfig",
    "glXGetFBConfigAttrib",
    "glXGetFBConfigs",
    "glXGetSelectedEvent",
    "glXGetVisualFromFBConfig",
    "glXIsDirect",
    "glXMakeContextCurrent",
    "glXMakeCurrent",
    "glXQueryContext",
    "glXQueryDrawable",
    "glXQueryExtensionsString",
    "glXQueryServerString",
    "glXSelectEvent",
    "glXSwapBuffers",
    "glXUseXFont",
    "glXWaitGL",
    "glXWaitX",
];

/// A GLX extension function libGLX does not know: its name, glrt's dispatcher, and the dispatch
/// index libGLX assigned to it (-1 until `setDispatchIndex`).
struct Extension {
    name: &'static str,
    dispatcher: Proc,
    index: AtomicI32,
}

impl Extension {
    const fn new(name: &'static str, dispatcher: Proc) -> Self {
        Extension {
            name,
            dispatcher,
            index: AtomicI32::new(-1),
        }
    }
}

/// The GLX extension functions glrt implements beyond libGLX's own (the swap-interval
/// extensions glrt advertises), each with its dispatcher.
static EXTENSIONS: [Extension; 4] = [
    Extension::new(
        "glXGetSwapIntervalMESA",
        Proc(dispatch_get_swap_interval_mesa as *const ()),
    ),
    Extension::new("glXSwapIntervalEXT", Proc(dispatch_swap_interval_ext as *const ())),
    Extension::new("glXSwapIntervalMESA", Proc(dispatch_swap_interval_mesa as *const ())),
    Extension::new("glXSwapIntervalSGI", Proc(dispatch_swap_interval_sgi as *const ())),
];

/// Indices into [`EXTENSIONS`], used by the dispatchers.
const GET_SWAP_INTERVAL_MESA: usize = 0;
const SWAP_INTERVAL_EXT: usize = 1;
const SWAP_INTERVAL_MESA: usize = 2;
const SWAP_INTERVAL_SGI: usize = 3;

/// libGLX's exports, valid for as long as the vendor is loaded (set by [`__glx_Main`]).
static API_EXPORTS: AtomicPtr<GlxApiExports> = AtomicPtr::new(std::ptr::null_mut());

/// The extension called `name`, if glrt dispatches it.
fn extension(name: &[u8]) -> Option<&'static Extension> {
    EXTENSIONS.iter().find(|e| e.name.as_bytes() == name)
}

/// What the vendor's `getProcAddress` returns for `name`: glrt's GL functions, and its GLX
/// functions that libGLX fetches from vendors (static ones and dispatched extensions). Other
/// `glX*` names are null, so libGLX does not mistake an unimplemented GLX function for GL.
pub fn vendor_proc_address(name: &[u8]) -> *const () {
    let glx_known = STATIC_GLX.iter().any(|n| n.as_bytes() == name) || extension(name).is_some();
    if name.starts_with(b"glX") && !glx_known {
        return std::ptr::null();
    }
    proc_address(name)
}

/// The name a C caller passed, or `None` for null.
///
/// # Safety
/// `name` is null or a NUL-terminated string.
unsafe fn c_name<'a>(name: *const u8) -> Option<&'a [u8]> {
    // Safety: as documented.
    (!name.is_null()).then(|| unsafe { CStr::from_ptr(name.cast::<c_char>()) }.to_bytes())
}

/// `isScreenSupported`: glrt renders on any X screen.
unsafe extern "C" fn is_screen_supported(_dpy: *mut Display, _screen: c_int) -> Bool {
    1
}

/// `getProcAddress`: see [`vendor_proc_address`].
unsafe extern "C" fn get_proc_address(name: *const u8) -> *mut c_void {
    guard("glvnd getProcAddress", || {
        // Safety: libGLX passes a function name.
        unsafe { c_name(name) }.map_or(std::ptr::null_mut(), |n| vendor_proc_address(n).cast_mut().cast())
    })
}

/// `getDispatchAddress`: glrt's dispatcher for a GLX extension function, or null (libGLX then
/// treats the name as a GL function if `getProcAddress` knows it).
unsafe extern "C" fn get_dispatch_address(name: *const u8) -> *mut c_void {
    guard("glvnd getDispatchAddress", || {
        // Safety: libGLX passes a function name.
        let ext = unsafe { c_name(name) }.and_then(extension);
        ext.map_or(std::ptr::null_mut(), |e| e.dispatcher.0.cast_mut().cast())
    })
}

/// `setDispatchIndex`: remembers the index libGLX assigned to one of glrt's dispatchers.
unsafe extern "C" fn set_dispatch_index(name: *const u8, index: c_int) {
    guard("glvnd setDispatchIndex", || {
        // Safety: libGLX passes a function name.
        if let Some(e) = unsafe { c_name(name) }.and_then(extension) {
            e.index.store(index, Ordering::Relaxed);
        }
    })
}

/// The implementation of extension `EXTENSIONS[which]` offered by the vendor that `vendor`
/// picks from libGLX's exports, or `None` (not loaded yet, no vendor, vendor lacks it).
fn vendor_function(which: usize, vendor: impl FnOnce(&GlxApiExports) -> *mut VendorInfo) -> Option<ExtFuncPtr> {
    // Safety: libGLX keeps its exports alive while the vendor is loaded.
    let exports = unsafe { API_EXPORTS.load(Ordering::Acquire).as_ref() }?;
    let index = EXTENSIONS.get(which)?.index.load(Ordering::Relaxed);
    let vendor = Some(vendor(exports)).filter(|v| index >= 0 && !v.is_null())?;
    // Safety: a vendor libGLX returned, an index it assigned.
    let f = unsafe { (exports.fetchDispatchEntry?)(vendor, index) };
    (!f.is_null()).then_some(f)
}

/// The vendor of the current context.
fn current_vendor(e: &GlxApiExports) -> *mut VendorInfo {
    // Safety: a libGLX export without arguments.
    e.getCurrentDynDispatch.map_or(std::ptr::null_mut(), |f| unsafe { f() })
}

/// Dispatches `glXSwapIntervalEXT` to the vendor owning `drawable`.
unsafe extern "C" fn dispatch_swap_interval_ext(dpy: *mut Display, drawable: GlxDrawable, interval: c_int) {
    // Safety: the application's display and drawable.
    let vendor = |e: &GlxApiExports| {
        e.vendorFromDrawable
            .map_or(std::ptr::null_mut(), |f| unsafe { f(dpy, drawable) })
    };
    if let Some(f) = vendor_function(SWAP_INTERVAL_EXT, vendor) {
        // Safety: the vendor's glXSwapIntervalEXT, which has this signature.
        let f: unsafe extern "C" fn(*mut Display, GlxDrawable, c_int) = unsafe { std::mem::transmute(f) };
        unsafe { f(dpy, drawable, interval) }
    }
}

/// Dispatches a `glXSwapInterval{MESA,SGI}`-like setter of extension `which` to the current vendor;
/// without one, `GLX_BAD_CONTEXT` (GLX_SGI_swap_control, GLX_MESA_swap_control), as glrt's own
/// setters answer.
fn dispatch_current_setter(which: usize, interval: c_int) -> c_int {
    match vendor_function(which, current_vendor) {
        Some(f) => {
            // Safety: the vendor's setter: `int f(int)` (MESA's `unsigned int` has the same ABI).
            let f: unsafe extern "C" fn(c_int) -> c_int = unsafe { std::mem::transmute(f) };
            unsafe { f(interval) }
        }
        None => GLX_BAD_CONTEXT,
    }
}

/// Dispatches `glXSwapIntervalMESA` to the current vendor.
extern "C" fn dispatch_swap_interval_mesa(interval: c_uint) -> c_int {
    dispatch_current_setter(SWAP_INTERVAL_MESA, interval as c_int)
}

/// Dispatches `glXSwapIntervalSGI` to the current vendor.
extern "C" fn dispatch_swap_interval_sgi(interval: c_int) -> c_int {
    dispatch_current_setter(SWAP_INTERVAL_SGI, interval)
}

/// Dispatches `glXGetSwapIntervalMESA` to the current vendor; 0 without one.
extern "C" fn dispatch_get_swap_interval_mesa() -> c_int {
    vendor_function(GET_SWAP_INTERVAL_MESA, current_vendor).map_or(0, |f| {
        // Safety: the vendor's glXGetSwapIntervalMESA.
        let f: unsafe extern "C" fn() -> c_int = unsafe { std::mem::transmute(f) };
        unsafe { f() }
    })
}

/// The vendor entry point libGLX calls once after loading `libGLX_glrt.so.0`: checks the ABI
/// major version (a mismatch is logged and refused), keeps `exports`, fills in `imports`.
///
/// # Safety
/// `exports` lives while the library is loaded; `imports` is null or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn __glx_Main(
    version: u32,
    exports: *const GlxApiExports,
    _vendor: *mut VendorInfo,
    imports: *mut GlxApiImports,
) -> Bool {
    guard("__glx_Main", || {
        let major = version >> 16;
        if major != ABI_MAJOR_VERSION {
            log::error!(
                "glvnd GLX vendor ABI {major}.{} is not supported (glrt implements {ABI_MAJOR_VERSION}.{ABI_MINOR_VERSION})",
                version & 0xffff
            );
            return 0;
        }
        if exports.is_null() || imports.is_null() {
            log::error!("glvnd passed no exports or imports table");
            return 0;
        }
        API_EXPORTS.store(exports.cast_mut(), Ordering::Release);
        let table = GlxApiImports {
            isScreenSupported: Some(is_screen_supported),
            getProcAddress: Some(get_proc_address),
            getDispatchAddress: Some(get_dispatch_address),
            setDispatchIndex: Some(set_dispatch_index),
            notifyError: None,
            isPatchSupported: None,
            initiatePatch: None,
            releasePatch: None,
            patchThreadAttach: None,
        };
        // Safety: checked non-null; libGLX owns the writable table.
        unsafe { imports.write(table) };
        1
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicPtr as Ptr, AtomicUsize};

    /// The vendor handle the fake libGLX reports as current.
    static CURRENT_VENDOR: Ptr<c_void> = Ptr::new(std::ptr::null_mut());
    /// The last `(vendor, index)` the fake `fetchDispatchEntry` was asked for.
    static FETCHED: [AtomicUsize; 2] = [AtomicUsize::new(0), AtomicUsize::new(0)];
    /// The interval the fake vendor's `glXSwapIntervalSGI` received.
    static RECEIVED: AtomicI32 = AtomicI32::new(0);

    unsafe extern "C" fn fake_current_vendor() -> *mut VendorInfo {
        CURRENT_VENDOR.load(Ordering::SeqCst)
    }

    unsafe extern "C" fn fake_swap_interval_sgi(interval: c_int) -> c_int {
        RECEIVED.store(interval, Ordering::SeqCst);
        42
    }

    unsafe extern "C" fn fake_fetch(vendor: *mut VendorInfo, index: c_int) -> ExtFuncPtr {
        FETCHED[0].store(vendor as usize, Ordering::SeqCst);
        FETCHED[1].store(index as usize, Ordering::SeqCst);
        fake_swap_interval_sgi as *const c_void
    }

    /// A libGLX exports table with the entries the dispatchers use.
    static FAKE_EXPORTS: GlxApiExports = GlxApiExports {
        getDynDispatch: None,
        getCurrentDynDispatch: Some(fake_current_vendor),
        fetchDispatchEntry: Some(fake_fetch),
        getCurrentContext: None,
        addVendorContextMapping: None,
        removeVendorContextMapping: None,
        vendorFromContext: None,
        addVendorFBConfigMapping: None,
        removeVendorFBConfigMapping: None,
        vendorFromFBConfig: None,
        addVendorDrawableMapping: None,
        removeVendorDrawableMapping: None,
        vendorFromDrawable: None,
    };

    fn empty_imports() -> GlxApiImports {
        GlxApiImports {
            isScreenSupported: None,
            getProcAddress: None,
            getDispatchAddress: None,
            setDispatchIndex: None,
            notifyError: None,
            isPatchSupported: None,
            initiatePatch: None,
            releasePatch: None,
            patchThreadAttach: None,
        }
    }

    fn glx_main(version: u32, imports: &mut GlxApiImports) -> Bool {
        // Safety: a static exports table and a writable imports table.
        unsafe { __glx_Main(version, &FAKE_EXPORTS, std::ptr::null_mut(), imports) }
    }

    #[test]
    fn layouts_match_the_header() {
        // 13 and 9 function pointers, in the header's order.
        let word = std::mem::size_of::<usize>();
        assert_eq!(std::mem::size_of::<GlxApiExports>(), 13 * word);
        assert_eq!(std::mem::size_of::<GlxApiImports>(), 9 * word);
        assert_eq!(std::mem::offset_of!(GlxApiExports, vendorFromDrawable), 12 * word);
        assert_eq!(std::mem::offset_of!(GlxApiImports, patchThreadAttach), 8 * word);
    }

    #[test]
    fn another_major_version_is_refused() {
        let mut imports = empty_imports();
        assert_eq!(glx_main(2 << 16, &mut imports), 0);
        assert_eq!(glx_main(0, &mut imports), 0);
        assert!(imports.getProcAddress.is_none() && imports.isScreenSupported.is_none());
        // Safety: a null imports table is refused, not written.
        assert_eq!(
            unsafe { __glx_Main(1 << 16, &FAKE_EXPORTS, std::ptr::null_mut(), std::ptr::null_mut()) },
            0
        );
    }

    #[test]
    fn imports_are_filled_for_any_1_x() {
        for version in [1 << 16, (1 << 16) | 7] {
            let mut imports = empty_imports();
            assert_eq!(glx_main(version, &mut imports), 1);
            let get = imports.getProcAddress.expect("getProcAddress");
            let dispatch = imports.getDispatchAddress.expect("getDispatchAddress");
            // Safety: NUL-terminated names; null display is not read.
            unsafe {
                assert_eq!(
                    imports.isScreenSupported.expect("isScreenSupported")(std::ptr::null_mut(), 0),
                    1
                );
                assert_eq!(get(c"glBegin".as_ptr().cast()) as *const (), proc_address(b"glBegin"));
                assert!(!get(c"glXCreateContext".as_ptr().cast()).is_null());
                assert!(get(c"glXImportContextEXT".as_ptr().cast()).is_null());
                assert!(get(c"glXCreateGLXPixmapMESA".as_ptr().cast()).is_null());
                assert!(get(c"glNoSuchFunction".as_ptr().cast()).is_null());
                assert!(get(std::ptr::null()).is_null());
                assert_eq!(
                    dispatch(c"glXSwapIntervalEXT".as_ptr().cast()) as *const (),
                    dispatch_swap_interval_ext as *const ()
                );
                assert!(dispatch(c"glBegin".as_ptr().cast()).is_null());
                assert!(dispatch(c"glXCreateContext".as_ptr().cast()).is_null());
            }
            assert!(imports.setDispatchIndex.is_some() && imports.notifyError.is_none());
            assert!(imports.isPatchSupported.is_none() && imports.initiatePatch.is_none());
        }
    }

    #[test]
    fn every_function_libglx_fetches_exists() {
        for name in STATIC_GLX.iter().chain(EXTENSIONS.iter().map(|e| &e.name)) {
            assert!(!vendor_proc_address(name.as_bytes()).is_null(), "{name}");
        }
    }

    #[test]
    fn extension_dispatch_reaches_the_current_vendor_at_its_index() {
        let mut imports = empty_imports();
        assert_eq!(glx_main(1 << 16, &mut imports), 1);
        // Safety: a NUL-terminated name.
        unsafe { imports.setDispatchIndex.expect("setDispatchIndex")(c"glXSwapIntervalSGI".as_ptr().cast(), 7) };
        CURRENT_VENDOR.store(std::ptr::null_mut(), Ordering::SeqCst);
        assert_eq!(dispatch_swap_interval_sgi(3), GLX_BAD_CONTEXT);
        let vendor = 0x1234usize as *mut c_void;
        CURRENT_VENDOR.store(vendor, Ordering::SeqCst);
        assert_eq!(dispatch_swap_interval_sgi(3), 42);
        assert_eq!(RECEIVED.load(Ordering::SeqCst), 3);
        assert_eq!(FETCHED[0].load(Ordering::SeqCst), 0x1234);
        assert_eq!(FETCHED[1].load(Ordering::SeqCst), 7);
    }
}

//! Frame capture (`GLRT_CAPTURE=path`): the recording side. Reading and replaying a capture
//! (`glrt replay|dump|info FILE`) is the `replay` module's, a client of the exported C API
//! above `gl_entry`, as apitrace keeps its retracer apart from its tracer.
//!
//! **Why recording lives here.** The GL commands of `translate` report the client memory they
//! read ([`reads::note`]: vertex arrays as their elements are fetched, pixels as the unpack
//! state lays them out) and map pointers found in client memory ([`client_pointer`]); only
//! they know those ranges, so the recorder must be reachable from `translate`, which names
//! nothing above itself. The generated C exports (`gl_entry`) open each call's record
//! ([`begin`]) and report the window-system events ([`context_created`], [`made_current`],
//! [`swapped`]); what a record needs from above is handed down at the call (whether the
//! current context is compiling a display list) or installed by the replay
//! ([`map_addresses`]).
//!
//! **What is recorded.** Every GL call the generated C exports receive (command id and raw
//! arguments: integer and float bits, pointers as addresses), with exactly the client memory
//! the call read ([`reads`]: vertex arrays as their elements are fetched at draw time, so
//! `glArrayElement`, locked and interleaved arrays are covered; pixel data as the unpack state
//! lays it out; `glCallLists` names; buffer data; vector arguments), and the window-system
//! events that matter: context creation with its share group, make-current with the drawable
//! size and buffering, and frame-ending swaps. Memory the GL writes (`glGet*`,
//! `glReadPixels`, feedback and selection buffers) is not recorded; replay gives it writable
//! memory at the same place. The file layout is in [`mod@format`]; records are written by a
//! background thread ([`writer`]).
//!
//! **Replay** creates headless contexts of the captured sizes and calls the same generated C
//! exports a program calls, so the call log and capture hooks work during a replay too. Client
//! memory lives in a *shadow* of the captured address space, which the replay installs here
//! as an [`AddressMap`] while it runs: a capture made during a replay maps addresses back
//! through it ([`captured_address`]), so replaying with `GLRT_CAPTURE` set writes a
//! byte-identical file.
//!
//! **Frame ranges.** `GLRT_CAPTURE_FRAMES=A..B` (frames count from 0, ended by swaps, `B`
//! excluded) records frames `A` to `B - 1` completely; before `A` it drops the commands that
//! only draw (the `glBegin`/`glEnd` pairs and vertices, `glDraw*`, `glClear`, evaluator
//! draws, `glRect`, pixel drawing) unless a display list is being compiled, keeping every
//! state, texture, buffer and list command so frame `A` starts from the same state; after
//! `B` the file is closed. (Current attributes a dropped `glDrawArrays` would have left
//! behind are not reproduced: OpenGL 1.5 section 2.8 leaves them indeterminate.)
//!
//! Pointers stored in client memory (`glMultiDrawElements`' index lists) are mapped with
//! [`client_pointer`]. Commands reading a buffer object (vertex arrays, pixels from a pixel
//! unpack buffer) record its offset and no memory. What a program writes through a mapping
//! (`glMapBuffer`, `glMapBufferRange`) is recorded when `glUnmapBuffer` ends a writable
//! mapping, as the `glBufferSubData` call that has the same effect, right after the unmap
//! ([`mapped_writes`]).
//!
//! Limits: one recording thread is assumed (the calls of all threads go to one stream);
//! a program killed before the capture is finished (at exit, or after the last frame of
//! `GLRT_CAPTURE_FRAMES`) leaves a file readers refuse. A full disk ends the capture with a
//! readable file of the frames written before ([`writer`]).

pub mod format;
pub mod reads;
pub mod writer;

use std::cell::RefCell;
use std::path::Path;
use std::sync::atomic::{AtomicU8, AtomicU32, AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};

use parking_lot::RwLock;

use format::{Event, SwapKind};
use writer::Writer;

/// The generated command table: every captured command's name and signature by capture id.
pub mod table {
    include!(concat!(env!("OUT_DIR"), "/capture_commands.rs"));
}

/// A GL argument as the 64 raw bits a capture stores, and back (lossless for its type).
pub trait Raw: Sized {
    /// The bits recorded.
    fn raw(self) -> u64;
    /// The value from recorded bits.
    fn from_raw(v: u64) -> Self;
}

macro_rules! raw_int {
    ($($t:ty => $u:ty),*) => {$(impl Raw for $t {
        fn raw(self) -> u64 { self as $u as u64 }
        fn from_raw(v: u64) -> Self { v as $u as $t }
    })*};
}
raw_int!(u8 => u8, i8 => u8, u16 => u16, i16 => u16, u32 => u32, i32 => u32, u64 => u64, i64 => u64, usize => u64, isize => u64);

impl Raw for f32 {
    fn raw(self) -> u64 {
        self.to_bits().into()
    }
    fn from_raw(v: u64) -> Self {
        f32::from_bits(v as u32)
    }
}

impl Raw for f64 {
    fn raw(self) -> u64 {
        self.to_bits()
    }
    fn from_raw(v: u64) -> Self {
        f64::from_bits(v)
    }
}

impl<T> Raw for *const T {
    fn raw(self) -> u64 {
        self as usize as u64
    }
    fn from_raw(v: u64) -> Self {
        v as usize as *const T
    }
}

impl<T> Raw for *mut T {
    fn raw(self) -> u64 {
        self as usize as u64
    }
    fn from_raw(v: u64) -> Self {
        v as usize as *mut T
    }
}

/// Capture state: the environment is not read yet, capture is off, or on.
const UNREAD: u8 = 0;
const OFF: u8 = 1;
const ON: u8 = 2;

static STATE: AtomicU8 = AtomicU8::new(UNREAD);

/// The open capture.
struct Session {
    writer: Writer,
    /// Frames `[first, end)` are recorded completely.
    first: u64,
    end: u64,
    /// Per command id: whether it only draws (dropped before `first`).
    draws_only: Vec<bool>,
}

static SESSION: OnceLock<Option<Session>> = OnceLock::new();

/// Frames ended so far (swaps recorded).
static FRAME: AtomicU64 = AtomicU64::new(0);

/// Context ids, counted from 1 in creation order (the same order in a replay).
static NEXT_CONTEXT: AtomicU32 = AtomicU32::new(1);

/// How the addresses of a replay relate to those of the captured program: the replay's copy
/// of the captured address space, installed with [`map_addresses`] while a replay runs.
pub trait AddressMap: Send + Sync {
    /// Where captured `address` is in this process; addresses outside the map are returned
    /// unchanged.
    fn translate(&self, address: u64) -> u64;
    /// The captured address of `address` of this process (the inverse of
    /// [`AddressMap::translate`]); addresses outside the map are returned unchanged.
    fn original(&self, address: u64) -> u64;
}

/// The address map of the replay that runs, if one does.
static CANONICAL: RwLock<Option<Arc<dyn AddressMap>>> = RwLock::new(None);

/// Installs the address map of a replay that starts (`None` when it ends): while one is
/// installed, pointers read from client memory are translated ([`client_pointer`]), recorded
/// addresses are mapped back ([`captured_address`]), and writes through buffer mappings are
/// not recorded again ([`mapped_writes`]: the replayed file holds them).
pub fn map_addresses(map: Option<Arc<dyn AddressMap>>) {
    *CANONICAL.write() = map;
}

/// The open session, opening it on first use from `GLRT_CAPTURE` and `GLRT_CAPTURE_FRAMES`.
fn session() -> Option<&'static Session> {
    SESSION
        .get_or_init(|| {
            let session = open_from_env();
            if session.is_some() {
                reads::enable();
            }
            STATE.store(if session.is_some() { ON } else { OFF }, Ordering::Relaxed);
            session
        })
        .as_ref()
        .filter(|_| STATE.load(Ordering::Relaxed) == ON)
}

fn open_from_env() -> Option<Session> {
    let path = std::env::var_os("GLRT_CAPTURE").filter(|p| !p.is_empty())?;
    let (first, end) = match std::env::var("GLRT_CAPTURE_FRAMES") {
        Ok(range) => match parse_frames(&range) {
            Some(r) => r,
            None => {
                log::error!("GLRT_CAPTURE_FRAMES={range:?} is not a range A..B; capturing every frame");
                (0, u64::MAX)
            }
        },
        Err(_) => (0, u64::MAX),
    };
    match Writer::create(Path::new(&path), table::COMMANDS) {
        Ok(writer) => {
            // Safety: `finish_at_exit` is a plain function that never unwinds.
            unsafe { atexit(finish_at_exit) };
            let draws_only = table::COMMANDS.iter().map(|(name, _)| draws_only(name)).collect();
            Some(Session { writer, first, end, draws_only })
        }
        Err(e) => {
            eprintln!("glrt: GLRT_CAPTURE: cannot create {}: {e}; capture is off", Path::new(&path).display());
            None
        }
    }
}

/// `A..B` (either bound may be left out: `..B`, `A..`) as `(A, B)`.
pub fn parse_frames(range: &str) -> Option<(u64, u64)> {
    let (a, b) = range.trim().split_once("..")?;
    let a = if a.is_empty() { 0 } else { a.parse().ok()? };
    let b = if b.is_empty() { u64::MAX } else { b.parse().ok()? };
    (a <= b).then_some((a, b))
}

/// Whether a command only draws (no state it changes outlives the frame): dropped before
/// the first captured frame.
fn draws_only(name: &str) -> bool {
    const PREFIXES: &[&str] = &[
        "glVertex", "glDrawArrays", "glDrawElements", "glDrawRangeElements", "glMultiDraw", "glRect", "glEvalCoord",
        "glEvalPoint", "glEvalMesh", "glDrawPixels", "glCopyPixels",
    ];
    let exact = ["glBegin", "glEnd", "glClear", "glAccum"];
    (PREFIXES.iter().any(|p| name.starts_with(p)) && !name.contains("Pointer")) || exact.contains(&name)
}

unsafe extern "C" {
    /// C library: runs `f` at `exit` (or when this library is unloaded).
    fn atexit(f: extern "C" fn()) -> std::ffi::c_int;
}

extern "C" fn finish_at_exit() {
    let _ = std::panic::catch_unwind(finish);
}

/// Completes and closes the capture file (also done at exit); later calls are not recorded.
pub fn finish() {
    if let Some(Some(session)) = SESSION.get() {
        STATE.store(OFF, Ordering::Relaxed);
        // A failed write was said by the writer when it happened.
        let _ = session.writer.finish();
    }
}

/// Whether capture is on (reads the environment the first time).
#[inline]
fn on() -> bool {
    STATE.load(Ordering::Relaxed) != OFF && session().is_some()
}

/// The captured address of `address`: during a replay, shadow addresses map back to the
/// addresses the captured program used; anything else is returned unchanged. (The call log
/// can print pointers through this so that `glrt dump` shows the program's addresses.)
pub fn captured_address(address: u64) -> u64 {
    CANONICAL.read().as_ref().map_or(address, |s| s.original(address))
}

/// A pointer a command read from client memory (`glMultiDrawElements`' index lists): in a
/// replay it holds a captured address, mapped here into the replay's shadow; otherwise it is
/// returned as it is.
pub fn client_pointer<T>(pointer: *const T) -> *const T {
    match CANONICAL.try_read().as_deref() {
        Some(Some(shadow)) => shadow.translate(pointer as u64) as usize as *const T,
        _ => pointer,
    }
}

/// A call recorded after the current call's own record: command id, raw arguments, and the
/// memory it reads (address, bytes).
type Follower = (usize, [u64; 4], (u64, Vec<u8>));

thread_local! {
    /// Calls to record after the current call's own record ([`mapped_writes`]).
    static FOLLOWERS: RefCell<Vec<Follower>> = const { RefCell::new(Vec::new()) };
}

/// Records that the call being made (`glUnmapBuffer`) ends a mapping through which the program
/// may have written `bytes`, which lie at offset `offset` of the buffer bound to `target`:
/// after the call's own record comes `glBufferSubData(target, offset, bytes.len(), bytes)`,
/// which puts the same contents into the buffer when replayed. Nothing is recorded when capture
/// is off, nor during a replay, whose file holds that call already.
pub fn mapped_writes(target: u32, offset: usize, bytes: &[u8]) {
    static BUFFER_SUB_DATA: OnceLock<Option<usize>> = OnceLock::new();
    if STATE.load(Ordering::Relaxed) != ON || CANONICAL.read().is_some() || bytes.is_empty() {
        return;
    }
    let Some(id) = *BUFFER_SUB_DATA.get_or_init(|| table::COMMANDS.iter().position(|c| c.0 == "glBufferSubData")) else { return };
    let address = bytes.as_ptr() as u64;
    let args = [target.raw(), (offset as isize).raw(), (bytes.len() as isize).raw(), address];
    let _ = FOLLOWERS.try_with(|f| f.borrow_mut().push((id, args, (address, bytes.to_vec()))));
}

/// A call being recorded; the record is written when it is dropped (after the call).
pub struct CallRecord<const N: usize> {
    id: usize,
    args: [u64; N],
}

/// Starts recording a call to command `id` (the generated exports call this first); `args`
/// gives the raw arguments; `compiling_list` says whether the calling thread's current context
/// is compiling a display list (whose drawing commands are state: they are kept before the
/// first captured frame). `None`, after one relaxed load, when capture is off.
#[inline]
pub fn begin<const N: usize>(id: usize, args: impl FnOnce() -> [u64; N], compiling_list: fn() -> bool) -> Option<CallRecord<N>> {
    if STATE.load(Ordering::Relaxed) == OFF {
        return None;
    }
    begin_slow(id, args(), compiling_list)
}

#[cold]
fn begin_slow<const N: usize>(id: usize, args: [u64; N], compiling_list: fn() -> bool) -> Option<CallRecord<N>> {
    let session = session()?;
    let frame = FRAME.load(Ordering::Relaxed);
    if frame < session.first && session.draws_only.get(id).copied().unwrap_or(false) && !compiling_list() {
        return None;
    }
    reads::open().then_some(CallRecord { id, args })
}

impl<const N: usize> Drop for CallRecord<N> {
    fn drop(&mut self) {
        let ranges = reads::close();
        let Some(session) = session() else { return };
        let signature = table::COMMANDS.get(self.id).map_or("", |c| c.1).as_bytes();
        let mut args = self.args;
        for (a, kind) in args.iter_mut().zip(signature) {
            if *kind == b'p' {
                *a = captured_address(*a);
            }
        }
        // Safety: each range was reported by the call as client memory it read, and the
        // program keeps that memory valid for the duration of the call, which has not
        // returned to it yet.
        let reads: Vec<(u64, &[u8])> = ranges
            .iter()
            .map(|&(address, len)| (captured_address(address as u64), unsafe { std::slice::from_raw_parts(address as *const u8, len) }))
            .collect();
        session.writer.record(|out| format::put_call(out, self.id, &args, &reads));
        for (id, args, (address, bytes)) in FOLLOWERS.try_with(|f| std::mem::take(&mut *f.borrow_mut())).unwrap_or_default() {
            session.writer.record(|out| format::put_call(out, id, &args, &[(address, &bytes)]));
        }
    }
}

/// Records a window-system event (no-op when capture is off).
fn event(event: Event) {
    if on()
        && let Some(session) = session()
    {
        session.writer.record(|out| format::put_event(out, event));
    }
}

/// A new context's id; records its creation with the id of a context of its share group
/// (`share`, 0: none).
pub fn context_created(share: u32) -> u32 {
    let id = NEXT_CONTEXT.fetch_add(1, Ordering::Relaxed);
    event(Event::Context { id, share });
    id
}

/// Records that context `id` (0: none) was made current on a `width` × `height` drawable.
pub fn made_current(id: u32, width: i32, height: i32, double: bool) {
    event(Event::MakeCurrent { id, width, height, double });
}

/// Records the end of a frame; closes the file after the last frame of the range.
pub fn swapped(kind: SwapKind) {
    if !on() {
        return;
    }
    event(Event::Swap(kind));
    let frame = FRAME.fetch_add(1, Ordering::Relaxed) + 1;
    match session() {
        Some(s) if frame >= s.end => finish(),
        Some(s) => s.writer.frame_ended(),
        None => {}
    }
}

//! Framebuffer configurations (GLX 1.4 sections 3.3.2 and 3.3.3) and the GLX attributes of X
//! visuals (section 3.4).
//!
//! The TrueColor and DirectColor visuals of depth 24 or 32 that the X server offers carry
//! RGBA8 configurations of four kinds: double- and single-buffered, each with (depth 24,
//! stencil 8, accumulation 16 per channel) or without ancillary buffers. Visuals of depth 24
//! also carry the same four as RGB8 configurations without destination alpha
//! (`GLX_ALPHA_SIZE` 0, `GLX_BUFFER_SIZE` 24), after the RGBA ones, as Mesa offers them: a
//! request that leaves `GLX_ALPHA_SIZE` at 0 gets an RGB configuration first (table 3.4: alpha
//! bits count only when asked for, then the smaller buffer wins), one asking for alpha gets only
//! RGBA ones. The renderer keeps alpha at 1 in the colour buffers of an RGB drawable
//! ([`crate::frame::Target::alpha`]). glrt renders into its own buffers, so every
//! configuration supports windows, pixmaps and pbuffers.
//!
//! The same kinds follow per sample count the Vulkan device renders multisampled
//! (`GLX_ARB_multisample`: `GLX_SAMPLE_BUFFERS` 1, `GLX_SAMPLES` n; the counts come from
//! [`crate::render::multisample_counts`], probed once per process), after every
//! single-sampled configuration in table order.
//!
//! As on a server with GLX, where each configuration has a visual of its own, the kinds of a
//! group of visuals (one class and depth) are dealt out over its visuals in turn: kind `i` of
//! `k` goes to visual `i mod n` of `n` and visual `j` gets kind `j mod k`, so the group has
//! `max(n, k)` configurations. A server with GLX (Xvfb, Xorg) has a visual for every kind,
//! and a visual then names exactly one configuration: programs that find the configuration of
//! their window by its visual (SFML: the first of `glXChooseFBConfig`'s list whose
//! `glXGetVisualFromFBConfig` is the window's visual, while that list puts single-buffered
//! configurations first) get the one whose attributes `glXGetConfig` reported for the visual.
//! The first visual of a group carries its first kind, double-buffered with every ancillary
//! buffer.
//!
//! A server with fewer visuals (no GLX extension) has several configurations per visual, and a
//! GLX 1.2 program sees only visuals: a visual takes the attributes of the configuration
//! `glXChooseVisual` last selected it for (by default its first one), so `glXGetConfig` and
//! `glXCreateContext` agree with what the program asked for.
//!
//! Tables are built per display and screen on first use and live for the program, so
//! `GLXFBConfig` handles (pointers to their entries) stay valid after `XCloseDisplay`.

use std::cmp::Ordering;
use std::collections::HashMap;
use std::ffi::{c_int, c_ulong, c_void};
use std::sync::atomic::{self, AtomicUsize};

use parking_lot::Mutex;
use x11_dl::glx::*;
use x11_dl::xlib::{self, Xlib};

use super::XDisplay;

/// Largest pbuffer side (`GLX_MAX_PBUFFER_WIDTH`/`HEIGHT`).
pub const MAX_PBUFFER_SIDE: c_int = 8192;

/// Every drawable type a configuration supports.
const DRAWABLE_TYPES: c_int = GLX_WINDOW_BIT | GLX_PIXMAP_BIT | GLX_PBUFFER_BIT;

/// One framebuffer configuration (`GLXFBConfig` points to one).
#[derive(Clone, Debug, PartialEq)]
pub struct FbConfig {
    /// `GLX_FBCONFIG_ID`.
    pub id: c_int,
    /// The X screen.
    pub screen: c_int,
    /// The X visual windows of this configuration use.
    pub visual_id: c_ulong,
    /// `GLX_X_VISUAL_TYPE`: `GLX_TRUE_COLOR` or `GLX_DIRECT_COLOR`.
    pub visual_type: c_int,
    /// Depth of the X visual (of windows and pixmaps drawn with this configuration).
    pub visual_depth: c_int,
    /// Red, green, blue and alpha bits.
    pub rgba: [c_int; 4],
    /// `GLX_DOUBLEBUFFER`.
    pub double_buffer: bool,
    /// `GLX_DEPTH_SIZE`.
    pub depth: c_int,
    /// `GLX_STENCIL_SIZE`.
    pub stencil: c_int,
    /// `GLX_ACCUM_*_SIZE` (each channel).
    pub accum: c_int,
    /// `GLX_SAMPLES`: 0, or the samples per pixel of a multisampled configuration.
    pub samples: c_int,
}

impl FbConfig {
    /// The value of a configuration attribute (GLX 1.4 table 3.1), `None` for other names.
    pub fn attrib(&self, attribute: c_int) -> Option<c_int> {
        let [r, g, b, a] = self.rgba;
        Some(match attribute {
            GLX_FBCONFIG_ID => self.id,
            GLX_BUFFER_SIZE => r + g + b + a,
            GLX_LEVEL | GLX_STEREO | GLX_AUX_BUFFERS => 0,
            GLX_SAMPLE_BUFFERS => c_int::from(self.samples > 0),
            GLX_SAMPLES => self.samples,
            GLX_DOUBLEBUFFER => c_int::from(self.double_buffer),
            GLX_RED_SIZE => r,
            GLX_GREEN_SIZE => g,
            GLX_BLUE_SIZE => b,
            GLX_ALPHA_SIZE => a,
            GLX_DEPTH_SIZE => self.depth,
            GLX_STENCIL_SIZE => self.stencil,
            GLX_ACCUM_RED_SIZE | GLX_ACCUM_GREEN_SIZE | GLX_ACCUM_BLUE_SIZE | GLX_ACCUM_ALPHA_SIZE => {
                self.accum
            }
            GLX_RENDER_TYPE => GLX_RGBA_BIT,
            GLX_DRAWABLE_TYPE => DRAWABLE_TYPES,
            GLX_X_RENDERABLE => xlib::True,
            GLX_X_VISUAL_TYPE => self.visual_type,
            // XIDs fit in 29 bits.
            GLX_VISUAL_ID => self.visual_id as c_int,
            GLX_SCREEN => self.screen,
            GLX_CONFIG_CAVEAT | GLX_TRANSPARENT_TYPE => GLX_NONE,
            GLX_TRANSPARENT_INDEX_VALUE
            | GLX_TRANSPARENT_RED_VALUE
            | GLX_TRANSPARENT_GREEN_VALUE
            | GLX_TRANSPARENT_BLUE_VALUE
            | GLX_TRANSPARENT_ALPHA_VALUE => 0,
            GLX_MAX_PBUFFER_WIDTH | GLX_MAX_PBUFFER_HEIGHT => MAX_PBUFFER_SIDE,
            GLX_MAX_PBUFFER_PIXELS => MAX_PBUFFER_SIDE * MAX_PBUFFER_SIDE,
            _ => return None,
        })
    }
}

/// The configurations of one screen of one display.
pub struct ScreenConfigs {
    /// The display's address; 0 once it is closed.
    display: AtomicUsize,
    screen: c_int,
    /// The configurations, in `glXGetFBConfigs` order.
    pub configs: Vec<FbConfig>,
    /// Per visual, the index of the configuration `glXChooseVisual` last selected it for.
    chosen: Mutex<HashMap<c_ulong, usize>>,
}

impl ScreenConfigs {
    /// Builds the configurations of the given visuals (`XGetVisualInfo` results), with
    /// multisampled ones for each of `sample_counts`: per group of usable visuals of one class
    /// and depth, its kinds of configuration ([`kinds`]) dealt out over its visuals in turn, as
    /// many configurations as the larger of the two counts (see the module documentation).
    fn build(display: usize, screen: c_int, visuals: &[xlib::XVisualInfo], sample_counts: &[u32]) -> ScreenConfigs {
        let usable: Vec<&xlib::XVisualInfo> = visuals
            .iter()
            .filter(|v| matches!(v.class, xlib::TrueColor | xlib::DirectColor) && matches!(v.depth, 24 | 32))
            .collect();
        let samples: Vec<c_int> =
            std::iter::once(0).chain(sample_counts.iter().filter_map(|&n| c_int::try_from(n).ok())).collect();
        // (kind index, visual index in `usable`, kind) of every configuration.
        let mut dealt = Vec::new();
        let mut groups: Vec<(c_int, c_int)> = Vec::new();
        for v in &usable {
            if !groups.contains(&(v.class, v.depth)) {
                groups.push((v.class, v.depth));
            }
        }
        for (class, depth) in groups {
            let members: Vec<usize> = (0..usable.len()).filter(|&i| (usable[i].class, usable[i].depth) == (class, depth)).collect();
            let kinds = kinds(depth, &samples);
            for i in 0..members.len().max(kinds.len()) {
                dealt.push((i % kinds.len(), members[i % members.len()], kinds[i % kinds.len()]));
            }
        }
        // Single-sampled first, then by visual, then by kind: a visual's first configuration is
        // its first kind (double-buffered with every ancillary buffer) where it has that kind.
        dealt.sort_by_key(|&(k, v, kind)| (kind.samples, v, k));
        let mut configs = Vec::with_capacity(dealt.len());
        for (_, v, kind) in dealt {
            let v = usable[v];
            let bits = |mask: c_ulong| mask.count_ones() as c_int;
            configs.push(FbConfig {
                id: (screen << 16) | (configs.len() as c_int + 1),
                screen,
                visual_id: v.visualid,
                visual_type: if v.class == xlib::TrueColor { GLX_TRUE_COLOR } else { GLX_DIRECT_COLOR },
                visual_depth: v.depth,
                rgba: [bits(v.red_mask), bits(v.green_mask), bits(v.blue_mask), kind.alpha],
                double_buffer: kind.double_buffer,
                depth: if kind.ancillary { 24 } else { 0 },
                stencil: if kind.ancillary { 8 } else { 0 },
                accum: if kind.ancillary { 16 } else { 0 },
                samples: kind.samples,
            });
        }
        ScreenConfigs { display: AtomicUsize::new(display), screen, configs, chosen: Mutex::new(HashMap::new()) }
    }

    /// The configuration a visual stands for (see the module documentation).
    pub fn of_visual(&self, visual_id: c_ulong) -> Option<&FbConfig> {
        if let Some(&i) = self.chosen.lock().get(&visual_id) {
            return self.configs.get(i);
        }
        self.configs.iter().find(|c| c.visual_id == visual_id)
    }

    /// Remembers that `glXChooseVisual` selected `config` (an entry of this table).
    pub fn remember_choice(&self, config: &FbConfig) {
        if let Some(i) = self.configs.iter().position(|c| std::ptr::eq(c, config)) {
            self.chosen.lock().insert(config.visual_id, i);
        }
    }
}

/// What tells configurations of one visual group apart.
#[derive(Clone, Copy)]
struct Kind {
    samples: c_int,
    alpha: c_int,
    ancillary: bool,
    double_buffer: bool,
}

/// The kinds of configuration of visuals of `depth`, in table order: per sample count, RGBA
/// then (depth 24 only) RGB, each double- and single-buffered with and without ancillary
/// buffers, double-buffered with every ancillary buffer first.
fn kinds(depth: c_int, samples: &[c_int]) -> Vec<Kind> {
    let alphas: &[c_int] = if depth == 24 { &[8, 0] } else { &[8] };
    let buffers = [(true, true), (true, false), (false, true), (false, false)];
    let mut out = Vec::new();
    for &samples in samples {
        for &alpha in alphas {
            for (ancillary, double_buffer) in buffers {
                out.push(Kind { samples, alpha, ancillary, double_buffer });
            }
        }
    }
    out
}

static SCREENS: Mutex<Vec<&'static ScreenConfigs>> = Mutex::new(Vec::new());

/// The configurations of `screen` of `dpy`, built on first use; `None` for a screen the
/// display does not have.
///
/// # Safety
/// `dpy` is a live display.
pub unsafe fn screen_configs(x: &Xlib, dpy: *mut XDisplay, screen: c_int) -> Option<&'static ScreenConfigs> {
    // Safety: `dpy` is live.
    if screen < 0 || screen >= unsafe { (x.XScreenCount)(dpy) } {
        return None;
    }
    let mut screens = SCREENS.lock();
    if let Some(found) = screens.iter().find(|s| s.display.load(atomic::Ordering::Relaxed) == dpy as usize && s.screen == screen) {
        return Some(found);
    }
    // Safety: a zeroed XVisualInfo is a valid template; Xlib allocates the result.
    let visuals = unsafe {
        let mut template: xlib::XVisualInfo = std::mem::zeroed();
        template.screen = screen;
        let mut count = 0;
        let list = (x.XGetVisualInfo)(dpy, xlib::VisualScreenMask, &mut template, &mut count);
        let visuals = if list.is_null() {
            Vec::new()
        } else {
            std::slice::from_raw_parts(list, count.max(0) as usize).to_vec()
        };
        if !list.is_null() {
            (x.XFree)(list.cast());
        }
        visuals
    };
    let counts = crate::render::multisample_counts();
    let table: &'static ScreenConfigs = Box::leak(Box::new(ScreenConfigs::build(dpy as usize, screen, &visuals, counts)));
    screens.push(table);
    Some(table)
}

/// Detaches the tables of a closed display (their entries stay valid for stale handles).
pub fn forget_display(dpy: usize) {
    for s in SCREENS.lock().iter() {
        let _ = s.display.compare_exchange(dpy, 0, atomic::Ordering::Relaxed, atomic::Ordering::Relaxed);
    }
}

/// The configuration a `GLXFBConfig` handle points to, `None` for anything else
/// (`GLXBadFBConfig`).
pub fn lookup(handle: *const c_void) -> Option<&'static FbConfig> {
    let screens = SCREENS.lock();
    screens.iter().find_map(|s| {
        let start = s.configs.as_ptr() as usize;
        let offset = (handle as usize).checked_sub(start)?;
        let size = std::mem::size_of::<FbConfig>();
        (offset % size == 0).then(|| s.configs.get(offset / size)).flatten()
    })
}

/// The table a configuration belongs to.
pub fn table_of(config: &FbConfig) -> Option<&'static ScreenConfigs> {
    SCREENS.lock().iter().copied().find(|s| s.configs.as_ptr_range().contains(&(config as *const FbConfig)))
}

/// How a requested attribute value selects configurations (GLX 1.4 table 3.4).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Rule {
    /// The configuration's value is at least the requested one.
    Minimum,
    /// Equal to the requested value.
    Exact,
    /// Has every requested bit.
    Mask,
    /// Not a selection criterion.
    Ignored,
}

fn rule(attribute: c_int) -> Option<Rule> {
    Some(match attribute {
        GLX_BUFFER_SIZE | GLX_AUX_BUFFERS | GLX_RED_SIZE | GLX_GREEN_SIZE | GLX_BLUE_SIZE | GLX_ALPHA_SIZE
        | GLX_DEPTH_SIZE | GLX_STENCIL_SIZE | GLX_ACCUM_RED_SIZE | GLX_ACCUM_GREEN_SIZE | GLX_ACCUM_BLUE_SIZE
        | GLX_ACCUM_ALPHA_SIZE | GLX_SAMPLE_BUFFERS | GLX_SAMPLES => Rule::Minimum,
        GLX_FBCONFIG_ID | GLX_LEVEL | GLX_DOUBLEBUFFER | GLX_STEREO | GLX_X_VISUAL_TYPE | GLX_CONFIG_CAVEAT
        | GLX_TRANSPARENT_TYPE | GLX_TRANSPARENT_INDEX_VALUE | GLX_TRANSPARENT_RED_VALUE
        | GLX_TRANSPARENT_GREEN_VALUE | GLX_TRANSPARENT_BLUE_VALUE | GLX_TRANSPARENT_ALPHA_VALUE
        | GLX_X_RENDERABLE => Rule::Exact,
        GLX_RENDER_TYPE | GLX_DRAWABLE_TYPE => Rule::Mask,
        GLX_MAX_PBUFFER_WIDTH | GLX_MAX_PBUFFER_HEIGHT | GLX_MAX_PBUFFER_PIXELS | GLX_VISUAL_ID => Rule::Ignored,
        _ => return None,
    })
}

/// The selection criteria of `glXChooseFBConfig` or `glXChooseVisual`.
#[derive(Clone, Debug, PartialEq)]
pub struct Request {
    /// Requested value per attribute (defaults first, later entries win).
    values: HashMap<c_int, c_int>,
    /// `glXChooseVisual`'s rule for depth: a request of zero prefers no depth buffer.
    visual_rules: bool,
}

/// Attribute lists longer than this many entries are treated as unterminated.
const MAX_LIST: usize = 4096;

/// Reads a `None`-terminated attribute list.
///
/// # Safety
/// `list` is null or points to a `None`-terminated list of ints.
unsafe fn read_list(list: *const c_int) -> Vec<c_int> {
    let mut out = Vec::new();
    if list.is_null() {
        return out;
    }
    // Safety: the list is terminated; MAX_LIST bounds the walk otherwise.
    while out.len() < MAX_LIST {
        let v = unsafe { *list.add(out.len()) };
        if v == 0 {
            break;
        }
        out.push(v);
    }
    out
}

/// Reads `(name, value)` pairs of a `None`-terminated list (`glXChooseFBConfig`,
/// `glXCreatePbuffer`, `glXCreateContextAttribsARB`).
///
/// # Safety
/// As `read_list`.
pub unsafe fn read_pairs(list: *const c_int) -> Vec<(c_int, c_int)> {
    let mut out = Vec::new();
    if list.is_null() {
        return out;
    }
    // Safety: as read_list; a value is read only after a non-zero name.
    for i in 0..MAX_LIST {
        let name = unsafe { *list.add(2 * i) };
        if name == 0 {
            break;
        }
        out.push((name, unsafe { *list.add(2 * i + 1) }));
    }
    out
}

impl Request {
    /// Parses a `glXChooseFBConfig` list, with the defaults of GLX 1.4 table 3.4. Unknown
    /// names are skipped (with a log) so extension attributes of newer programs do not fail
    /// the whole choice.
    ///
    /// # Safety
    /// `list` is null or a `None`-terminated list of pairs.
    pub unsafe fn fbconfig(list: *const c_int) -> Request {
        let mut values = HashMap::from([
            (GLX_DOUBLEBUFFER, GLX_DONT_CARE),
            (GLX_RENDER_TYPE, GLX_RGBA_BIT),
            (GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT),
            (GLX_X_RENDERABLE, GLX_DONT_CARE),
            (GLX_X_VISUAL_TYPE, GLX_DONT_CARE),
            (GLX_CONFIG_CAVEAT, GLX_DONT_CARE),
            (GLX_TRANSPARENT_TYPE, GLX_NONE),
            (GLX_FBCONFIG_ID, GLX_DONT_CARE),
        ]);
        // Safety: forwarded.
        for (name, value) in unsafe { read_pairs(list) } {
            if rule(name).is_some() {
                values.insert(name, value);
            } else {
                log::info!("glXChooseFBConfig: attribute {name:#x} ignored");
            }
        }
        Request { values, visual_rules: false }
    }

    /// Parses a `glXChooseVisual` list (GLX 1.4 section 3.4): `GLX_RGBA`, `GLX_DOUBLEBUFFER`
    /// and `GLX_STEREO` take no value and select; without `GLX_RGBA` only colour-index
    /// visuals match, without `GLX_DOUBLEBUFFER` only single-buffered ones. `None` for an
    /// unknown attribute.
    ///
    /// # Safety
    /// `list` is null or a `None`-terminated attribute list.
    pub unsafe fn visual(list: *const c_int) -> Option<Request> {
        let mut values = HashMap::from([
            (GLX_RENDER_TYPE, GLX_COLOR_INDEX_BIT),
            (GLX_DOUBLEBUFFER, 0),
            (GLX_STEREO, 0),
            (GLX_LEVEL, 0),
            (GLX_DRAWABLE_TYPE, GLX_WINDOW_BIT),
        ]);
        // Safety: forwarded.
        let items = unsafe { read_list(list) };
        let mut it = items.into_iter();
        while let Some(name) = it.next() {
            match name {
                GLX_USE_GL => {}
                GLX_RGBA => _ = values.insert(GLX_RENDER_TYPE, GLX_RGBA_BIT),
                GLX_DOUBLEBUFFER | GLX_STEREO => _ = values.insert(name, 1),
                _ if rule(name).is_some_and(|r| r != Rule::Ignored) => {
                    // A missing value (the terminator) reads as zero.
                    values.insert(name, it.next().unwrap_or(0));
                }
                _ => return None,
            }
        }
        Some(Request { values, visual_rules: true })
    }

    fn get(&self, attribute: c_int) -> c_int {
        self.values.get(&attribute).copied().unwrap_or(0)
    }

    /// Whether `config` satisfies every criterion. A `GLX_FBCONFIG_ID` other than
    /// `GLX_DONT_CARE` overrides every other attribute.
    pub fn matches(&self, config: &FbConfig) -> bool {
        let id = self.get(GLX_FBCONFIG_ID);
        if self.values.contains_key(&GLX_FBCONFIG_ID) && id != GLX_DONT_CARE {
            return config.id == id;
        }
        self.values.iter().all(|(&name, &wanted)| {
            let have = config.attrib(name).unwrap_or(0);
            match rule(name) {
                _ if wanted == GLX_DONT_CARE => true,
                Some(Rule::Minimum) => have >= wanted,
                Some(Rule::Exact) => have == wanted,
                Some(Rule::Mask) => have & wanted == wanted,
                Some(Rule::Ignored) | None => true,
            }
        })
    }

    /// Sum of the sizes of the listed components that the request asks for (a value above
    /// zero), the colour and accumulation sort keys of table 3.4.
    fn requested_bits(&self, config: &FbConfig, names: [c_int; 4]) -> c_int {
        names.iter().filter(|&&n| self.get(n) > 0).map(|&n| config.attrib(n).unwrap_or(0)).sum()
    }

    /// The order of GLX 1.4 section 3.3.3 (table 3.4 sort priorities): caveat, larger
    /// requested colour bits, smaller buffer size, single before double buffering, smaller
    /// auxiliary buffers and samples, larger depth, smaller stencil, larger requested
    /// accumulation bits, visual type; ties keep table order (`GLX_FBCONFIG_ID`).
    pub fn compare(&self, a: &FbConfig, b: &FbConfig) -> Ordering {
        let colour = [GLX_RED_SIZE, GLX_GREEN_SIZE, GLX_BLUE_SIZE, GLX_ALPHA_SIZE];
        let accum = [GLX_ACCUM_RED_SIZE, GLX_ACCUM_GREEN_SIZE, GLX_ACCUM_BLUE_SIZE, GLX_ACCUM_ALPHA_SIZE];
        let attr = |c: &FbConfig, n| c.attrib(n).unwrap_or(0);
        let smaller = |n| attr(a, n).cmp(&attr(b, n));
        let depth = if self.visual_rules && self.get(GLX_DEPTH_SIZE) == 0 {
            smaller(GLX_DEPTH_SIZE)
        } else {
            smaller(GLX_DEPTH_SIZE).reverse()
        };
        let visual_rank = |c: &FbConfig| {
            [GLX_TRUE_COLOR, GLX_DIRECT_COLOR, GLX_PSEUDO_COLOR, GLX_STATIC_COLOR, GLX_GRAY_SCALE, GLX_STATIC_GRAY]
                .iter()
                .position(|&t| t == c.visual_type)
        };
        smaller(GLX_CONFIG_CAVEAT)
            .then_with(|| self.requested_bits(b, colour).cmp(&self.requested_bits(a, colour)))
            .then_with(|| smaller(GLX_BUFFER_SIZE))
            .then_with(|| smaller(GLX_DOUBLEBUFFER))
            .then_with(|| smaller(GLX_AUX_BUFFERS))
            .then_with(|| smaller(GLX_SAMPLE_BUFFERS))
            .then_with(|| smaller(GLX_SAMPLES))
            .then_with(|| depth)
            .then_with(|| smaller(GLX_STENCIL_SIZE))
            .then_with(|| self.requested_bits(b, accum).cmp(&self.requested_bits(a, accum)))
            .then_with(|| visual_rank(a).cmp(&visual_rank(b)))
            .then_with(|| a.id.cmp(&b.id))
    }

    /// The matching configurations of `configs`, best first.
    pub fn choose<'a>(&self, configs: &'a [FbConfig]) -> Vec<&'a FbConfig> {
        let mut found: Vec<&FbConfig> = configs.iter().filter(|c| self.matches(c)).collect();
        found.sort_by(|a, b| self.compare(a, b));
        found
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> ScreenConfigs {
        let visual = |id, class, depth| xlib::XVisualInfo {
            visual: std::ptr::null_mut(),
            visualid: id,
            screen: 0,
            depth,
            class,
            red_mask: 0xff0000,
            green_mask: 0xff00,
            blue_mask: 0xff,
            colormap_size: 256,
            bits_per_rgb: 8,
        };
        let visuals =
            [visual(0x21, xlib::TrueColor, 24), visual(0x22, xlib::DirectColor, 24), visual(0x23, xlib::PseudoColor, 8)];
        ScreenConfigs::build(1, 0, &visuals, &[])
    }

    #[test]
    fn four_rgba_and_four_rgb_configurations_per_visual_of_depth_24() {
        let t = table();
        assert_eq!(t.configs.len(), 16);
        assert!(t.configs.iter().all(|c| c.visual_id != 0x23));
        let c = &t.configs[0];
        assert_eq!(c.attrib(GLX_RED_SIZE), Some(8));
        assert_eq!(c.attrib(GLX_BUFFER_SIZE), Some(32));
        assert_eq!(c.attrib(GLX_DEPTH_SIZE), Some(24));
        assert_eq!(c.attrib(GLX_X_VISUAL_TYPE), Some(GLX_TRUE_COLOR));
        let rgb = &t.configs[4];
        assert_eq!((rgb.attrib(GLX_ALPHA_SIZE), rgb.attrib(GLX_BUFFER_SIZE)), (Some(0), Some(24)));
        assert_eq!((rgb.visual_id, rgb.double_buffer, rgb.depth), (0x21, true, 24));
        assert_eq!(t.configs[8].attrib(GLX_X_VISUAL_TYPE), Some(GLX_DIRECT_COLOR));
        assert_eq!(c.attrib(0x7777), None);
        // A visual of depth 32 (composited windows) has alpha only.
        let argb = [xlib::XVisualInfo { visualid: 0x24, depth: 32, class: xlib::TrueColor, ..unsafe { std::mem::zeroed() } }];
        let t = ScreenConfigs::build(1, 0, &argb, &[]);
        assert_eq!(t.configs.len(), 4);
        assert!(t.configs.iter().all(|c| c.rgba[3] == 8));
    }

    #[test]
    fn rgb_configurations_come_first_unless_alpha_is_asked_for() {
        let t = table();
        for list in [[GLX_RED_SIZE, 1, GLX_DOUBLEBUFFER, 1, 0, 0], [GLX_ALPHA_SIZE, 0, GLX_DOUBLEBUFFER, 1, 0, 0]] {
            let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
            assert_eq!(got.len(), 8);
            assert_eq!(got[0].rgba[3], 0, "the smaller buffer wins when alpha is not asked for");
        }
        let list = [GLX_ALPHA_SIZE, 1, GLX_DOUBLEBUFFER, 1, 0];
        let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
        assert_eq!(got.len(), 4);
        assert!(got.iter().all(|c| c.rgba[3] == 8));
        let list = [GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 1, 0];
        let got = unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs);
        assert_eq!((got[0].rgba[3], got[0].depth), (0, 24));
        let list = [GLX_RGBA, GLX_DOUBLEBUFFER, GLX_ALPHA_SIZE, 1, 0];
        let got = unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs);
        assert!(!got.is_empty() && got.iter().all(|c| c.rgba[3] == 8));
    }

    #[test]
    fn kinds_are_dealt_over_the_visuals_of_a_group() {
        let visual = |id| xlib::XVisualInfo { visualid: id, depth: 32, class: xlib::TrueColor, ..unsafe { std::mem::zeroed() } };
        // Six visuals, four kinds: one configuration per visual, the kinds in turn.
        let visuals: Vec<_> = (0x40..0x46).map(visual).collect();
        let t = ScreenConfigs::build(1, 0, &visuals, &[]);
        let dealt: Vec<_> = t.configs.iter().map(|c| (c.visual_id, c.double_buffer, c.depth)).collect();
        let expected = [(0x40, true, 24), (0x41, false, 24), (0x42, true, 0), (0x43, false, 0), (0x44, true, 24), (0x45, false, 24)];
        assert_eq!(dealt, expected);
        // SFML finds its window's configuration as the first of glXChooseFBConfig's list (single-
        // buffered first) with the window's visual: the one glXGetConfig described.
        let window = t.configs.iter().find(|c| c.double_buffer && c.depth == 0).unwrap().visual_id;
        let all = unsafe { Request::fbconfig(std::ptr::null()) }.choose(&t.configs);
        let found = all.iter().find(|c| c.visual_id == window).unwrap();
        assert!(found.double_buffer && std::ptr::eq(*found, t.of_visual(window).unwrap()));
        // Two visuals, four kinds: each visual carries two, its first kind first.
        let t = ScreenConfigs::build(1, 0, &visuals[..2], &[]);
        let dealt: Vec<_> = t.configs.iter().map(|c| (c.visual_id, c.double_buffer, c.depth)).collect();
        assert_eq!(dealt, [(0x40, true, 24), (0x40, true, 0), (0x41, false, 24), (0x41, false, 0)]);
    }

    #[test]
    fn choose_fbconfig_sorts_single_buffered_first_and_deepest_depth() {
        let t = table();
        let list = [GLX_RED_SIZE, 1, 0];
        let req = unsafe { Request::fbconfig(list.as_ptr()) };
        let got = req.choose(&t.configs);
        assert_eq!(got.len(), 16);
        // Single-buffered before double (priority 4), depth 24 before none (priority 8),
        // TrueColor before DirectColor (priority 11).
        assert!(!got[0].double_buffer);
        assert_eq!(got[0].depth, 24);
        assert_eq!(got[0].visual_type, GLX_TRUE_COLOR);
        assert!(!got[1].double_buffer && got[1].depth == 24 && got[1].visual_type == GLX_DIRECT_COLOR);
        // RGB (buffer size 24) before RGBA (32): priority 3 comes before the others.
        assert!(got[..8].iter().all(|c| c.rgba[3] == 0) && got[8..].iter().all(|c| c.rgba[3] == 8));
    }

    #[test]
    fn choose_fbconfig_applies_minimum_exact_and_id_rules() {
        let t = table();
        let list = [GLX_DOUBLEBUFFER, 1, GLX_STENCIL_SIZE, 1, GLX_X_VISUAL_TYPE, GLX_DIRECT_COLOR, 0];
        let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
        assert_eq!(got.iter().map(|c| (c.visual_id, c.rgba[3])).collect::<Vec<_>>(), [(0x22, 0), (0x22, 8)]);
        let id = t.configs[3].id;
        let list = [GLX_FBCONFIG_ID, id, GLX_DOUBLEBUFFER, 1, 0];
        let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
        assert_eq!(got.iter().map(|c| c.id).collect::<Vec<_>>(), vec![id]);
        let list = [GLX_RENDER_TYPE, GLX_COLOR_INDEX_BIT, 0];
        assert!(unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs).is_empty());
        let list = [GLX_DEPTH_SIZE, 32, 0];
        assert!(unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs).is_empty());
    }

    #[test]
    fn choose_visual_rules() {
        let t = table();
        // Without GLX_RGBA only colour-index visuals match.
        let list = [GLX_DOUBLEBUFFER, 0];
        assert!(unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs).is_empty());
        // Without GLX_DOUBLEBUFFER only single-buffered; no depth request prefers no depth.
        let list = [GLX_RGBA, GLX_RED_SIZE, 1, 0];
        let got = unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs);
        assert!(got.iter().all(|c| !c.double_buffer));
        assert_eq!(got[0].depth, 0);
        let list = [GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 16, 0];
        let got = unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs);
        assert!(got[0].double_buffer && got[0].depth == 24);
        let list = [GLX_RGBA, 0x7777, 1, 0];
        assert!(unsafe { Request::visual(list.as_ptr()) }.is_none());
    }

    #[test]
    fn multisampled_configurations_follow_and_sort_after_single_sampled_ones() {
        let visuals = [xlib::XVisualInfo { visualid: 0x21, depth: 32, class: xlib::TrueColor, ..unsafe { std::mem::zeroed() } }];
        let t = ScreenConfigs::build(1, 0, &visuals, &[4]);
        assert_eq!(t.configs.len(), 8);
        assert_eq!(t.configs[..4].iter().map(|c| c.attrib(GLX_SAMPLE_BUFFERS)).collect::<Vec<_>>(), [Some(0); 4]);
        assert_eq!(t.configs[4].attrib(GLX_SAMPLE_BUFFERS), Some(1));
        assert_eq!(t.configs[4].attrib(GLX_SAMPLES), Some(4));
        assert_eq!(t.of_visual(0x21).map(|c| c.samples), Some(0), "a visual stands for a single-sampled configuration");
        let list = [GLX_DOUBLEBUFFER, 1, 0];
        let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
        assert_eq!(got.iter().map(|c| c.samples).collect::<Vec<_>>(), [0, 0, 4, 4], "fewer samples first (table 3.4)");
        let list = [GLX_SAMPLE_BUFFERS, 1, GLX_SAMPLES, 2, GLX_DEPTH_SIZE, 1, 0];
        let got = unsafe { Request::fbconfig(list.as_ptr()) }.choose(&t.configs);
        assert_eq!(got.iter().map(|c| (c.samples, c.double_buffer)).collect::<Vec<_>>(), [(4, false), (4, true)]);
        let list = [GLX_RGBA, GLX_SAMPLES, 8, 0];
        assert!(unsafe { Request::visual(list.as_ptr()) }.unwrap().choose(&t.configs).is_empty(), "no 8-sample configuration");
    }

    #[test]
    fn a_visual_stands_for_its_last_chosen_configuration() {
        let t = table();
        assert!(t.of_visual(0x21).unwrap().double_buffer);
        let single = &t.configs[1];
        t.remember_choice(single);
        assert_eq!(t.of_visual(0x21), Some(single));
        assert!(t.of_visual(0x99).is_none());
    }
}

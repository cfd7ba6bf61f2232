//! The HUD (`GLRT_HUD=1`, or `hud = true` under `[display]` in `glrt.toml`): a panel drawn over
//! the top-left corner of every presented frame, in raster and path-traced modes, with
//!
//! ```text
//! raster  llvmpipe (LLVM 15.0.6, 256 bits)     mode and device
//! 16.7 ms  59.9 fps                            the last frame's time, frames/s of the graph's
//! ▁▂▁▁▇▁▁▂ (frame-time graph, 33 ms high)        frames
//! static 3 movable 0 dynamic 1                 draws per class of this frame
//! transl 2 overlay 1 sky 1 layer 0
//! rays 12.3 M/s                                when tracing: rays of a frame / its time
//! ```
//!
//! Frame time is the wall time from one presented frame to the next, as the program sees it.
//! The panel is drawn on the CPU ([`canvas`], a built-in bitmap font) and copied into the
//! frame's front image at the present step, before the outputs (window, `GLRT_DUMP`) read it
//! ([`crate::render::raster::renderer::Raster::present`]); it is opaque (a copy, not a blend).
//! Multisampled drawables get no HUD (their images cannot be written by a copy).

pub mod canvas;

use std::collections::VecDeque;
use std::time::Instant;

use crate::config::{Key, Table, switch};
use crate::frame::class::{ClassCounts, DrawClass};
use canvas::{Canvas, GLYPH};

/// Frames the graph shows, one pixel column each.
const GRAPH_FRAMES: usize = 120;
/// Graph height in pixels.
const GRAPH_HEIGHT: u32 = 32;
/// Frame time at the graph's top, in ms (30 frames/s), unless a longer frame raises it.
const GRAPH_MS: f32 = 1000.0 / 30.0;
/// Characters per line at most.
const COLUMNS: usize = 40;
/// Line height and margin in pixels.
const LINE: u32 = GLYPH + 2;
/// Pixels between the panel's edge and its text.
pub const MARGIN: u32 = 4;
/// Colours: the panel, text, graph bars, and bars above [`GRAPH_MS`].
pub const BACKGROUND: [u8; 4] = [16, 16, 24, 255];
/// The colour of the HUD's text.
pub const TEXT: [u8; 4] = [255, 255, 255, 255];
const BAR: [u8; 4] = [64, 220, 96, 255];
const SLOW_BAR: [u8; 4] = [240, 80, 64, 255];

/// `[display]` of `glrt.toml`: what glrt shows besides the program's image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Display {
    /// `hud` (`GLRT_HUD`): true, false, 1 or 0.
    pub hud: bool,
}

impl Table for Display {
    const NAME: &'static str = "display";
    const KEYS: &'static [Key<Display>] = &[Key { name: "hud", set: |d, v| switch(v).map(|on| d.hud = on) }];
}

impl Display {
    /// The settings of this process, read at the first call ([`crate::config::Config::of_process`]);
    /// problems are reported then.
    pub fn of_process() -> Display {
        static DISPLAY: std::sync::OnceLock<Display> = std::sync::OnceLock::new();
        crate::config::process_table(&DISPLAY)
    }
}

/// What the HUD shows of one frame besides its times.
pub struct FrameInfo<'a> {
    /// `raster` or `pathtrace (compute)`.
    pub mode: &'a str,
    /// The Vulkan device's name.
    pub device: &'a str,
    /// Draws per class.
    pub classes: &'a ClassCounts,
    /// Rays of the last traced frame whose counters were read (`None`: not tracing).
    pub rays: Option<u64>,
}

/// The HUD of one renderer: the frame times so far.
#[derive(Default)]
pub struct Hud {
    /// Frame times in ms, oldest first, at most [`GRAPH_FRAMES`].
    times: VecDeque<f32>,
    /// When the last frame was presented.
    last: Option<Instant>,
}

impl Hud {
    /// Takes the time of the frame presented now and draws the panel of `info`.
    pub fn frame(&mut self, info: &FrameInfo<'_>) -> Canvas {
        let now = Instant::now();
        if let Some(last) = self.last.replace(now) {
            if self.times.len() == GRAPH_FRAMES {
                self.times.pop_front();
            }
            self.times.push_back(now.duration_since(last).as_secs_f32() * 1e3);
        }
        self.draw(info)
    }

    /// The panel: text lines, the graph after the second.
    fn draw(&self, info: &FrameInfo<'_>) -> Canvas {
        let lines = self.lines(info);
        let longest = lines.iter().map(|l| l.chars().count() as u32).max().unwrap_or(0);
        let width = MARGIN * 2 + (longest * GLYPH).max(GRAPH_FRAMES as u32);
        let height = MARGIN * 2 + lines.len() as u32 * LINE + GRAPH_HEIGHT + 2;
        let mut canvas = Canvas::new([width, height], BACKGROUND);
        for (n, line) in lines.iter().enumerate() {
            canvas.text(MARGIN, line_top(n as u32), line, TEXT);
        }
        self.graph(&mut canvas, line_top(2) - GRAPH_HEIGHT - 2);
        canvas
    }

    /// One bar per frame time, the newest on the right; the scale's top is [`GRAPH_MS`] or the
    /// longest frame shown.
    fn graph(&self, canvas: &mut Canvas, top: u32) {
        let scale = self.times.iter().copied().fold(GRAPH_MS, f32::max);
        let left = MARGIN + (GRAPH_FRAMES - self.times.len()) as u32;
        for (n, &ms) in self.times.iter().enumerate() {
            let bar = ((ms / scale * GRAPH_HEIGHT as f32).ceil() as u32).clamp(1, GRAPH_HEIGHT);
            let colour = if ms > GRAPH_MS { SLOW_BAR } else { BAR };
            canvas.fill([left + n as u32, top + GRAPH_HEIGHT - bar, 1, bar], colour);
        }
    }

    /// The text lines (at most [`COLUMNS`] characters each).
    fn lines(&self, info: &FrameInfo<'_>) -> Vec<String> {
        let count = |class| info.classes.get(class);
        let mut lines = vec![format!("{}  {}", info.mode, info.device)];
        lines.push(match self.times.back() {
            Some(&ms) => {
                let average = self.times.iter().sum::<f32>() / self.times.len() as f32;
                format!("{ms:.1} ms  {:.1} fps", 1e3 / average)
            }
            None => "first frame".to_owned(),
        });
        use DrawClass::*;
        lines.push(format!("static {} movable {} dynamic {}", count(Static), count(Movable), count(Dynamic)));
        lines.push(format!("transl {} overlay {} sky {} layer {}", count(Translucent), count(Overlay), count(Sky), count(Layer)));
        if let (Some(rays), Some(&ms)) = (info.rays, self.times.back()) {
            lines.push(format!("rays {}/s", rate(rays as f64 / (f64::from(ms) / 1e3))));
        }
        lines.iter().map(|l| l.chars().take(COLUMNS).collect()).collect()
    }
}

/// Top of text line `line` of the panel (the graph lies between lines 1 and 2).
pub fn line_top(line: u32) -> u32 {
    MARGIN + line * LINE + if line >= 2 { GRAPH_HEIGHT + 2 } else { 0 }
}

/// `per_second` with a unit prefix: `950`, `2.5 k`, `66.7 M`, `1.2 G`.
fn rate(per_second: f64) -> String {
    match per_second {
        x if x >= 1e9 => format!("{:.1} G", x / 1e9),
        x if x >= 1e6 => format!("{:.1} M", x / 1e6),
        x if x >= 1e3 => format!("{:.1} k", x / 1e3),
        x => format!("{x:.0}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info(rays: Option<u64>) -> (ClassCounts, Option<u64>) {
        let mut classes = ClassCounts::default();
        classes.add(DrawClass::Static, 3);
        classes.add(DrawClass::Overlay, 2);
        (classes, rays)
    }

    #[test]
    fn lines_say_mode_device_times_classes_and_rays() {
        let (classes, rays) = info(Some(2_000_000));
        let frame = FrameInfo { mode: "pathtrace (compute)", device: "llvmpipe", classes: &classes, rays };
        let mut hud = Hud::default();
        assert_eq!(hud.lines(&frame)[1], "first frame");
        hud.times.extend([10.0, 30.0]);
        let lines = hud.lines(&frame);
        assert_eq!(
            lines,
            [
                "pathtrace (compute)  llvmpipe",
                "30.0 ms  50.0 fps",
                "static 3 movable 0 dynamic 0",
                "transl 0 overlay 2 sky 0 layer 0",
                // 2 M rays in 30 ms.
                "rays 66.7 M/s"
            ]
        );
        let raster = FrameInfo { mode: "raster", rays: None, ..frame };
        assert_eq!(hud.lines(&raster).len(), 4, "no rays when not tracing");
    }

    #[test]
    fn the_graph_has_a_bar_per_frame_scaled_to_30_fps() {
        let (classes, _) = info(None);
        let frame = FrameInfo { mode: "raster", device: "d", classes: &classes, rays: None };
        let mut hud = Hud::default();
        hud.times.extend([GRAPH_MS, GRAPH_MS / 2.0, GRAPH_MS * 2.0]);
        let canvas = hud.draw(&frame);
        let top = MARGIN + 2 * LINE;
        let bar = |n: u32| (0..GRAPH_HEIGHT).filter(|&y| canvas.pixel(MARGIN + GRAPH_FRAMES as u32 - 3 + n, top + y) != BACKGROUND).count();
        // The 66.7 ms frame raises the scale: 16, 8 and 32 px of 32.
        assert_eq!([bar(0), bar(1), bar(2)], [16, 8, 32]);
        assert_eq!(canvas.pixel(MARGIN + GRAPH_FRAMES as u32 - 1, top + GRAPH_HEIGHT - 1), SLOW_BAR);
        assert_eq!(canvas.pixel(MARGIN + GRAPH_FRAMES as u32 - 4, top + GRAPH_HEIGHT - 1), BACKGROUND, "no bar before the first frame");
    }

    #[test]
    fn rates_take_a_unit_prefix() {
        assert_eq!([rate(950.4), rate(2500.0), rate(66.7e6), rate(1.24e9)], ["950", "2.5 k", "66.7 M", "1.2 G"]);
    }

    #[test]
    fn hud_switch_reads_booleans_and_0_or_1() {
        assert_eq!(switch(&toml::Value::Integer(1)), Ok(true));
        assert_eq!(switch(&toml::Value::Boolean(false)), Ok(false));
        assert!(switch(&toml::Value::Integer(2)).is_err());
    }
}

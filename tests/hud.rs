//! The HUD (`GLRT_HUD=1`, `render::hud`) read back from the frames glrt writes: captures are
//! replayed with `glrt replay --out` (the same frames every run), once with the HUD and once
//! without. The panel's text must be the mode and the device, then frame times, the graph,
//! draws per class and, when tracing, rays per second, in the built-in font; outside the panel
//! the frame must not change.

#[path = "images/mod.rs"]
mod images;

use std::path::{Path, PathBuf};
use std::process::Command;

use glrt::render::hud::canvas::{Canvas, GLYPH};
use glrt::render::hud::{BACKGROUND, MARGIN, TEXT, line_top};
use images::Image;

/// Frame `frame` of `glrt replay FIXTURE --out` in `mode` at `size`, with the HUD or without.
fn replayed(fixture: &str, mode: &str, size: &str, hud: bool, frame: u64) -> Image {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("hud-{fixture}-{mode}-{hud}"));
    let _ = std::fs::remove_dir_all(&dir);
    let capture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(format!("{fixture}.glrtcap"));
    let out = Command::new(env!("CARGO_BIN_EXE_glrt"))
        .args(["replay", capture.to_str().unwrap(), "--out", dir.to_str().unwrap(), "--size", size])
        .env("GLRT_MODE", mode)
        .env("GLRT_HUD", if hud { "1" } else { "0" })
        // The quickest traced frames: one sample, one bounce.
        .env("GLRT_SPP", "1")
        .env("GLRT_BOUNCES", "1")
        .output()
        .expect("run glrt replay");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    Image::load_png(&dir.join(format!("frame-{frame:05}.png")))
}

/// The name of the device glrt draws with here.
fn device() -> String {
    let devices = glrt::render::devices::survey().expect("a Vulkan device");
    devices.into_iter().find(|d| d.chosen).expect("the device glrt uses").name
}

/// Whether `text` is written in `image` at line `line` of the panel, glyph for glyph (as far as
/// the image is wide).
fn has_text(image: &Image, line: u32, text: &str) -> bool {
    let mut expected = Canvas::new([text.len() as u32 * GLYPH, GLYPH], BACKGROUND);
    expected.text(0, 0, text, TEXT);
    let top = line_top(line);
    (0..GLYPH).all(|y| {
        (0..expected.size[0]).filter(|x| MARGIN + x < image.width as u32).all(|x| {
            let [r, g, b, _] = expected.pixel(x, y);
            image.pixel((MARGIN + x) as usize, (top + y) as usize) == [r, g, b]
        })
    })
}

/// The panel's extent: the rows and columns from the top-left corner that hold its background.
fn panel_size(image: &Image) -> (usize, usize) {
    let bg = [BACKGROUND[0], BACKGROUND[1], BACKGROUND[2]];
    let width = (0..image.width).take_while(|&x| image.pixel(x, 0) == bg).count();
    let height = (0..image.height).take_while(|&y| image.pixel(0, y) == bg).count();
    (width, height)
}

#[test]
fn raster_hud_shows_mode_device_times_and_classes_over_an_unchanged_frame() {
    let with = replayed("demo", "raster", "320x240", true, 3);
    let without = replayed("demo", "raster", "320x240", false, 3);
    assert!(has_text(&with, 0, &format!("raster  {}", device())), "line 1: mode and device");
    let ink = (line_top(1)..line_top(1) + GLYPH).flat_map(|y| (0..with.width).map(move |x| (x, y as usize))).filter(|&(x, y)| with.pixel(x, y) == [255; 3]).count();
    assert!(ink > 50 && !has_text(&with, 1, "first frame"), "line 2: frame times after the first frame ({ink} text pixels)");
    assert!(has_text(&with, 2, "static ") && has_text(&with, 3, "transl "), "lines 3 and 4: draws per class");
    // The demo capture: 1 sky, 1 glass, 1 HUD bar each frame (tests/end_to_end/demo.rs).
    assert!(has_text(&with, 3, "transl 1 overlay 1 sky 1 "), "draws per class of the demo");
    assert!(!has_text(&with, 4, "rays "), "no rays when rasterizing");
    // The graph (between lines 2 and 3): a bar for each of frames 1 to 3.
    let graph_rows = line_top(1) + GLYPH..line_top(2);
    let bar_columns = (0..with.width)
        .filter(|&x| graph_rows.clone().any(|y| matches!(with.pixel(x, y as usize), [64, 220, 96] | [240, 80, 64])))
        .count();
    assert_eq!(bar_columns, 3, "one bar per timed frame");
    let (w, h) = panel_size(&with);
    assert!(w >= 120 && (50..120).contains(&h), "panel {w}x{h}");
    let outside = (0..with.height).flat_map(|y| (0..with.width).map(move |x| (x, y))).filter(|&(x, y)| x >= w || y >= h);
    let changed = outside.filter(|&(x, y)| with.pixel(x, y) != without.pixel(x, y)).count();
    assert_eq!(changed, 0, "pixels changed outside the {w}x{h} panel");
}

#[test]
fn path_traced_hud_shows_rays_per_second() {
    let with = replayed("glxgears", "pathtrace", "200x150", true, 3);
    assert!(has_text(&with, 0, &format!("pathtrace (compute)  {}", device())), "line 1: mode, tracer and device");
    assert!(has_text(&with, 4, "rays "), "line 5: rays per second");
    // A count of rays starts with a digit other than 0 (`rate` drops to the next unit).
    assert!(!has_text(&with, 4, "rays 0"), "rays were traced");
    assert!((1..=9).any(|d| has_text(&with, 4, &format!("rays {d}"))), "a number follows");
}

//! `glrt-demo --q3` (demo/q3/), the Quake-3-like workload: its capture fixture
//! `tests/fixtures/q3.glrtcap` (frames 409 to 412 of the camera's path at 320 × 240: in the
//! courtyard looking west at the doorway, the rocket flying away towards it) replayed in raster
//! mode against Mesa's image of the same frame (`tests/reference/q3-412-mesa.png`, llvmpipe
//! under Xvfb) and checked for light and shadow; the class hash tracking gives each draw of the
//! fixture's last frame, written down draw by draw; the fixture still being what the demo
//! draws; the demo's whole path through glrt without a GL error; and the fixture's last frame
//! path traced (issue 16's acceptance): the static world as raster shows it, region by region,
//! the models lit, the HUD's icons as drawn, and a glow lighting the surfaces beside it.
//! `tests/fixtures/make.sh`
//! remakes the fixture and the reference. Run `cargo build` first (the demo runs through
//! `target/<profile>/libglrt.so`).

mod images;
#[path = "lavapipe/mod.rs"]
mod lavapipe;
mod programs;

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;
use std::time::Duration;

use glrt::frame::class::{DrawClass, FrameStats, LayerRole, SurfaceLighting};
use glrt::frame::{Draw, Frame};
use glrt::frame::state::BlendFactor;
use glrt::frame::FrameSink;
use glrt::frame::pixels::PixelBuffer;
use glrt::render::frame::Renderer;
use glrt::render::trace::settings::{Lightmaps, Settings};
use glrt::replay::reader::Capture;
use glrt::replay;
use images::{Image, compare};
use parking_lot::Mutex;
use BlendFactor::{DstColor, One, OneMinusSrcAlpha, SrcAlpha, SrcColor, Zero};
use DrawClass::{Dynamic, Layer, Light, Movable, Overlay, Sky, Static, Translucent};
use LayerRole::{Albedo, BakedLight, Emission};
use SurfaceLighting::{Baked, VertexLit};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn fixture() -> PathBuf {
    repo("tests/fixtures/q3.glrtcap")
}

/// Frame 3 of the fixture replayed by `glrt replay --out` in raster mode on lavapipe.
fn raster_frame_3() -> Image {
    let dir = programs::scratch("q3_demo", "raster");
    let _ = std::fs::remove_dir_all(&dir);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt"));
    cmd.arg("replay").arg(fixture()).args(["--frames", "3..4", "--out"]).arg(&dir);
    for key in ["GLRT_CAPTURE", "GLRT_FRAME_LOG", "GLRT_DUMP", "GLRT_CONFIG"] {
        cmd.env_remove(key);
    }
    cmd.env("GLRT_MODE", "raster");
    let lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
    if Path::new(lavapipe).exists() {
        cmd.env("VK_DRIVER_FILES", lavapipe);
    }
    let out = cmd.output().expect("run glrt replay");
    assert!(out.status.success(), "glrt replay: {}", String::from_utf8_lossy(&out.stderr));
    Image::load_png(&dir.join("frame-00003.png"))
}

/// Rec. 709 luminance of a pixel.
fn luminance([r, g, b]: [u8; 3]) -> f64 {
    0.2126 * f64::from(r) + 0.7152 * f64::from(g) + 0.0722 * f64::from(b)
}

/// Mean luminance of the rectangle `[x0, y0, x1, y1)` (y from the top).
fn mean_luminance(image: &Image, [x0, y0, x1, y1]: [usize; 4]) -> f64 {
    let sum: f64 = (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).map(|(x, y)| luminance(image.pixel(x, y))).sum();
    sum / ((x1 - x0) * (y1 - y0)) as f64
}

/// Pixels of the rectangle that `f` accepts.
fn count(image: &Image, [x0, y0, x1, y1]: [usize; 4], f: impl Fn([u8; 3]) -> bool) -> usize {
    (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).filter(|&(x, y)| f(image.pixel(x, y))).count()
}

/// The replayed frame is Mesa's frame (the same metric as `tests/raster_vs_mesa.rs`: per
/// channel within 24, at most 1% of the pixels unmatched), lit, shadowed where the level is
/// shadowed, and shows the HUD's 3D icons.
#[test]
fn the_replayed_frame_is_mesas_lit_and_shadowed_with_its_hud_icons() {
    let frame = raster_frame_3();
    assert_eq!((frame.width, frame.height), (320, 240));
    let mesa = Image::load_png(&repo("tests/reference/q3-412-mesa.png"));
    let d = compare(&frame, &mesa, 24);
    eprintln!("against Mesa: {:.3}% mismatched, mean |difference| {:.4}", d.mismatched * 100.0, d.mean_abs);
    assert!(d.mismatched <= 0.01 && d.mean_abs <= 2.0, "glrt against Mesa: {d:?}");

    // Lit: the baked light makes a frame of mean luminance 68 (Mesa's), nowhere near black or
    // white.
    let mean = mean_luminance(&frame, [0, 0, 320, 240]);
    assert!((50.0..90.0).contains(&mean), "mean luminance {mean:.1}");
    // Regions of the lit level (demo/q3/level.rs), each well above black: the courtyard's west
    // wall in the sun above the doorway, its north wall in the sun, the courtyard floor in the
    // sun in front of the doorway, the hall seen through the doorway, the sky top left.
    let lit = [
        ("sunlit west wall", [160, 40, 220, 90], 60.0),
        ("north wall", [250, 20, 300, 120], 40.0),
        ("sunlit floor", [100, 150, 200, 165], 90.0),
        ("hall through the doorway", [130, 95, 150, 130], 30.0),
        ("sky", [0, 0, 10, 10], 60.0),
    ];
    for (what, rect, least) in lit {
        let l = mean_luminance(&frame, rect);
        eprintln!("{what} {rect:?}: mean luminance {l:.1}");
        assert!(l > least, "{what} {rect:?}: mean luminance {l:.1}");
    }
    // Shadowed: the same wall (same bricks, same lightmap page) below the diagonal edge of the
    // south wall's shadow is less than a third as bright as where the sun reaches it.
    let (sun, shade) = (mean_luminance(&frame, [160, 40, 220, 90]), mean_luminance(&frame, [70, 110, 110, 130]));
    eprintln!("west wall: {shade:.1} in the shadow, {sun:.1} in the sun");
    assert!(shade * 3.0 < sun, "west wall: {shade:.1} in the shadow, {sun:.1} in the sun");
    // The 3D icons of the status bar (GL viewports [143, 0, 24, 24] and [235, 0, 24, 24] in the
    // bottom row): the head's skin and the armour's yellow plates.
    let skin = count(&frame, [143, 216, 167, 240], |[r, g, b]| r > 120 && r > g + 15 && g > b + 15);
    let armour = count(&frame, [235, 216, 259, 240], |[r, g, b]| r > 110 && g > 90 && b < 60);
    eprintln!("icons: {skin} skin pixels, {armour} yellow pixels");
    assert!(skin > 300, "head icon: {skin} skin pixels");
    assert!(armour > 40, "armour icon: {armour} yellow pixels");
}

/// Blend factors (source, destination) of a draw that blends.
type Blending = Option<(BlendFactor, BlendFactor)>;

/// What a draw is to the surfaces of the traced scene.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Surface {
    /// Not traced.
    Raster,
    /// Traced: how it is lit and its texture units that hold baked light.
    Lit(SurfaceLighting, u8),
    /// A layer over the draw of this index, with this role.
    Over(usize, LayerRole),
}

/// What the tests need of a draw.
#[derive(Clone, Copy, Debug, PartialEq)]
struct DrawSummary {
    class: DrawClass,
    triangles: usize,
    blend: Blending,
    surface: Surface,
}

/// A raster draw.
const fn draw(class: DrawClass, triangles: usize, blend: Blending) -> DrawSummary {
    DrawSummary { class, triangles, blend, surface: Surface::Raster }
}

/// A traced draw, opaque, lit so.
const fn traced(class: DrawClass, triangles: usize, lighting: SurfaceLighting, light_units: u8) -> DrawSummary {
    DrawSummary { class, triangles, blend: None, surface: Surface::Lit(lighting, light_units) }
}

/// A layer over draw `base`.
const fn layer(triangles: usize, blend: (BlendFactor, BlendFactor), base: usize, role: LayerRole) -> DrawSummary {
    DrawSummary { class: Layer, triangles, blend: Some(blend), surface: Surface::Over(base, role) }
}

impl DrawSummary {
    fn of(d: &Draw) -> DrawSummary {
        let surface = match (d.instance, &d.layer) {
            (Some(i), _) => Surface::Lit(i.lighting, i.light_units),
            (None, Some(l)) => Surface::Over(l.base, l.role),
            (None, None) => Surface::Raster,
        };
        DrawSummary { class: d.class, triangles: d.indices.len() / 3, blend: d.state.blend.map(|b| (b.src_rgb, b.dst_rgb)), surface }
    }
}

#[derive(Clone, Debug)]
struct FrameSummary {
    draws: Vec<DrawSummary>,
    stats: FrameStats,
    frame: Frame,
}

#[derive(Clone, Default)]
struct Summaries(Arc<Mutex<Vec<FrameSummary>>>);

impl FrameSink for Summaries {
    fn present(&mut self, frame: Frame) {
        let draws = frame.draws.iter().map(DrawSummary::of).collect();
        self.0.lock().push(FrameSummary { draws, stats: frame.stats, frame });
    }
}

/// The fixture's frames, replayed and classified in this process.
fn classified_frames() -> Vec<FrameSummary> {
    let capture = Capture::open(&fixture()).expect("capture");
    let sink = Summaries::default();
    let keep = sink.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(keep.clone())))), ..Default::default() };
    let outcome = replay::run(&capture, &options).expect("replay");
    assert_eq!(outcome.frames, 4);
    sink.0.lock().clone()
}

/// The draws of the fixture's last frame (demo frame 412), in order, as glrt classifies them
/// today: class, triangles, blending, and how traced draws are lit (with their light units)
/// or which draw a layer lies on. glrt merges the sky's triangle strips per side.
const FRAME_3: [DrawSummary; 30] = [
    // The sky box (depth range 1..1): 4 sides around, 4 strips of 8 quads each, and the top,
    // then the cloud layer added over them.
    draw(Sky, 64, None),
    draw(Sky, 64, None),
    draw(Sky, 64, None),
    draw(Sky, 64, None),
    draw(Sky, 128, None),
    draw(Sky, 384, Some((One, One))),
    // Floor tiles, base × lightmap on two units (unit 1 holds baked light); every visible
    // floor surface is near the rocket, so the batch is followed by its dynamic light pass
    // over some of its triangles: the rocket's light, traced as a point light.
    traced(Static, 118, Baked, 0b10),
    draw(Light, 18, Some((One, One))),
    // Concrete, base × lightmap, and its dynamic light pass.
    traced(Static, 240, Baked, 0b10),
    draw(Light, 14, Some((One, One))),
    // Brick, base × lightmap, then the detail pass over the same triangles (2 × modulate).
    traced(Static, 404, Baked, 0b10),
    layer(404, (DstColor, SrcColor), 10, Albedo),
    // Metal (the doorway and the hall's east wall): base, then the lightmap as a second pass
    // (`GL_EQUAL` depth): baked light by its coarse texels.
    traced(Static, 26, Baked, 0),
    layer(26, (DstColor, Zero), 12, BakedLight),
    // The hall's light panel seen through the doorway, base × lightmap, then its glow.
    traced(Static, 2, Baked, 0b10),
    layer(2, (One, One), 14, Emission),
    // The two players: new vertices every frame (walk cycle blended on the CPU), colours from
    // the light grid.
    traced(Dynamic, 72, VertexLit, 0),
    traced(Dynamic, 72, VertexLit, 0),
    // The armour (spinning), the rocket (flying), lit from the light grid; the view weapon
    // (depth range 0..0.3) is drawn over the scene as it is.
    traced(Movable, 144, VertexLit, 0),
    traced(Movable, 12, VertexLit, 0),
    draw(Overlay, 24, None),
    // Blended shaders: the water, the armour's additive shell (its own deformed vertices),
    // three smoke puffs in one batch, the rocket's flame.
    draw(Translucent, 18, Some((SrcAlpha, OneMinusSrcAlpha))),
    draw(Translucent, 144, Some((One, One))),
    draw(Translucent, 6, Some((SrcAlpha, OneMinusSrcAlpha))),
    draw(Translucent, 2, Some((One, One))),
    // The HUD's 3D icons, head and armour, each in its own viewport after a depth clear:
    // drawn over the scene as they are.
    draw(Overlay, 192, None),
    draw(Overlay, 144, None),
    // 2D: the numbers (7 characters), the crosshair, "FRAME 00412" with its shadow.
    draw(Overlay, 14, Some((SrcAlpha, OneMinusSrcAlpha))),
    draw(Overlay, 2, Some((SrcAlpha, OneMinusSrcAlpha))),
    draw(Overlay, 40, Some((SrcAlpha, OneMinusSrcAlpha))),
];

/// Each draw of the last frame gets the class written down in [`FRAME_3`], and the per-class
/// counts of `Frame.stats` follow: 5 static (the world's first stages), 2 movable (armour,
/// rocket), 2 dynamic (the players), 4 translucent (the blended shaders), 6 overlay (the view
/// weapon, two HUD icons, 2D), 6 sky, 3 layers (detail, lightmap pass, glow), 2 lights (the
/// dynamic light passes), which make one light. In frame 0 nothing has moved yet: the 9 traced draws are all static (and the
/// models, whose colours vary, baked).
#[test]
fn each_draw_of_the_fixture_gets_the_class_written_down() {
    let frames = classified_frames();
    let actual = &frames[3].draws;
    for (i, (a, e)) in actual.iter().zip(&FRAME_3).enumerate() {
        assert_eq!(a, e, "draw {i}");
    }
    assert_eq!(actual.len(), FRAME_3.len(), "{actual:?}");
    let counts = |f: &FrameSummary| DrawClass::COUNTED.map(|c| f.stats.classes.get(c));
    // Order: static, movable, dynamic, translucent, overlay, sky, layer, light.
    assert_eq!(counts(&frames[0]), [9, 0, 0, 4, 6, 6, 3, 2], "frame 0");
    let lit = |f: &FrameSummary| f.draws.iter().filter_map(|d| if let Surface::Lit(l, _) = d.surface { Some(l) } else { None }).collect::<Vec<_>>();
    assert_eq!(lit(&frames[0]), [vec![Baked; 5], vec![Baked; 4]].concat(), "frame 0: the models before they moved");
    for (n, f) in frames.iter().enumerate().skip(1) {
        assert_eq!(counts(f), [5, 2, 2, 4, 6, 6, 3, 2], "frame {n}");
        assert_eq!(f.frame.lights.len(), 1, "frame {n}: one rocket, one light");
        assert_eq!(f.stats.matches_found, 9, "frame {n}: every traced draw found again");
    }
    let triangles = DrawClass::COUNTED.map(|c| frames[3].stats.triangles.get(c));
    assert_eq!(triangles, [790, 156, 144, 170, 416, 768, 432, 32]);
}

/// The corners of triangle `t` of `draw`, bit for bit.
fn corners(draw: &Draw, t: usize) -> [[u32; 4]; 3] {
    std::array::from_fn(|k| draw.vertices.position[draw.indices[3 * t + k] as usize].map(f32::to_bits))
}

/// No translucent draw is left for a stage that belongs to a traced surface: no triangle of a
/// `Translucent` draw is a triangle (the same corners) of a traced draw before it seen
/// through the same matrices; and each layer's triangles are its base's triangles, as its
/// `triangles` say.
#[test]
fn no_translucent_draw_is_a_pass_over_a_traced_surface() {
    let frames = classified_frames();
    for (n, f) in frames.iter().enumerate() {
        let draws = &f.frame.draws;
        for (i, d) in draws.iter().enumerate().filter(|(_, d)| d.class == Translucent) {
            let mine: HashSet<[[u32; 4]; 3]> = (0..d.indices.len() / 3).map(|t| corners(d, t)).collect();
            for (j, base) in draws[..i].iter().enumerate().filter(|(_, b)| b.class.is_traced() && b.modelview == d.modelview && b.projection == d.projection) {
                let shared = (0..base.indices.len() / 3).filter(|&t| mine.contains(&corners(base, t))).count();
                assert_eq!(shared, 0, "frame {n}: translucent draw {i} over {shared} triangles of traced draw {j}");
            }
        }
        let mut layers = 0;
        for (i, d) in draws.iter().enumerate().filter(|(_, d)| d.class == Layer) {
            let layer = d.layer.as_ref().unwrap_or_else(|| panic!("frame {n}: draw {i} is a layer without one"));
            let base = &draws[layer.base];
            assert!(layer.base < i && base.class.is_traced(), "frame {n}: draw {i} over draw {}", layer.base);
            assert_eq!(layer.triangles.len(), d.indices.len() / 3);
            for (t, &b) in layer.triangles.iter().enumerate() {
                assert_eq!(corners(d, t), corners(base, b as usize), "frame {n}: draw {i}, triangle {t}");
            }
            layers += 1;
        }
        assert_eq!(layers, 3, "frame {n}");
    }
}

/// The fixture is what the demo draws today: its frames 409 to 412 drawn live through glrt give
/// the frame log recorded with the fixture (draws, vertices, clears and content hash per frame).
/// When the demo changes, `tests/fixtures/make.sh` remakes the fixture and this file's numbers.
#[test]
fn the_fixture_is_what_the_demo_draws_today() {
    let log = programs::scratch("q3_demo", "live.frames");
    let _ = std::fs::remove_file(&log);
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    cmd.args(["--q3", "--headless", "--first-frame", "409", "--frames", "4", "--size", "320x240"]).env("LD_LIBRARY_PATH", programs::lib_dir()).env("GLRT_FRAME_LOG", &log).env("GLRT_MODE", "none");
    let (out, stopped) = programs::run_for(cmd, Duration::from_secs(120));
    assert!(!stopped && out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let recorded = std::fs::read_to_string(repo("tests/fixtures/q3.frames")).expect("q3.frames");
    assert_eq!(std::fs::read_to_string(&log).expect("frame log"), recorded, "the demo changed: run tests/fixtures/make.sh");
}

/// The whole camera path (480 frames at 160 × 120) through glrt without a renderer
/// (`GLRT_MODE=none`): no GL error (the demo checks `glGetError` every frame and fails on
/// one), and what is drawn changes with the view: the sky only when the courtyard's opening
/// is in view, the batches and draw calls with the surfaces in view and the rocket.
#[test]
fn the_whole_path_runs_through_glrt_without_a_gl_error() {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_glrt-demo"));
    cmd.args(["--q3", "--verbose", "--headless", "--frames", "480", "--size", "160x120"]).env("LD_LIBRARY_PATH", programs::lib_dir()).env("GLRT_MODE", "none");
    let (out, stopped) = programs::run_for(cmd, Duration::from_secs(300));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(!stopped && out.status.success(), "{:?}\n{stdout}\n{}", out.status, String::from_utf8_lossy(&out.stderr));
    // "q3 frame F: S surfaces, B batches, D glDrawElements, G glBegin"
    let frames: Vec<[usize; 4]> = stdout
        .lines()
        .filter_map(|l| l.strip_prefix("q3 frame "))
        .map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            [w[1], w[3], w[5], w[7]].map(|n| n.parse().unwrap_or_else(|_| panic!("{l}")))
        })
        .collect();
    assert_eq!(frames.len(), 480);
    let with_sky = frames.iter().filter(|f| f[3] == 24).count();
    assert!(frames.iter().all(|f| f[3] == 0 || f[3] == 24), "the sky box: 5 sides, 24 strips");
    assert!(with_sky > 400 && with_sky < 480, "the sky is drawn in {with_sky} frames");
    // Every batch makes at least one draw; second stages and dynamic light passes more.
    assert!(frames.iter().all(|f| f[2] >= f[1] && f[2] > f[1]));
    let mut batches: Vec<usize> = frames.iter().map(|f| f[1]).collect();
    batches.sort();
    batches.dedup();
    assert!(batches.len() >= 5, "batches per frame vary with the view: {batches:?}");
    assert!(stdout.contains("q3 shader textures/q3demo/metal: Generic, 2 stages\n"), "{stdout}");
    assert!(stdout.contains("q3 shader textures/q3demo/floor: LightmappedMultitexture, 1 stages, lightmap on unit 1\n"));
}

/// `frame` rendered by a renderer of its own on lavapipe: rasterized (`settings` `None`) or
/// path traced, presented `frames` times (a camera standing still: the tracer accumulates
/// every sample), then read back.
fn render(frame: &Frame, settings: Option<Settings>, frames: u64) -> Image {
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    if let Some(settings) = settings {
        renderer.enable_tracing(settings).expect("the tracer's pipelines");
    }
    let still = |k: u64| Frame { number: frame.number + k, ..frame.clone() };
    for k in 0..frames - 1 {
        renderer.present(still(k));
    }
    let [w, h] = frame.size;
    let pixels = renderer.read_pixels(&still(frames - 1), PixelBuffer::Color, [0, 0, w as i32, h as i32]).expect("pixels");
    let (w, h) = (w as usize, h as usize);
    // GL rows go bottom to top.
    let rgb = (0..h).rev().flat_map(|y| pixels[y * w..][..w].iter().flat_map(|p| [0, 1, 2].map(|c| (p[c].clamp(0.0, 1.0) * 255.0).round() as u8))).collect();
    Image { width: w, height: h, rgb }
}

/// `frame` without the draws `which` accepts (their triangles removed, so that layer indices
/// stay), with their layers.
fn without(frame: &Frame, which: impl Fn(&Draw) -> bool) -> Frame {
    let mut f = frame.clone();
    let gone: Vec<bool> = f.draws.iter().map(&which).collect();
    for d in &mut f.draws {
        if which(d) || d.layer.as_ref().is_some_and(|l| gone[l.base]) {
            d.indices.clear();
            if let Some(l) = &mut d.layer {
                l.triangles = Arc::from([]);
            }
        }
    }
    f
}

/// The pixels (x, y from the top) that differ between `a` and `b`: where the draws removed
/// from one of them show.
fn shown(a: &Image, b: &Image) -> Vec<(usize, usize)> {
    (0..a.height).flat_map(|y| (0..a.width).map(move |x| (x, y))).filter(|&(x, y)| a.pixel(x, y) != b.pixel(x, y)).collect()
}

/// Mean luminance of `pixels` of `image`.
fn mean_of(image: &Image, pixels: &[(usize, usize)]) -> f64 {
    pixels.iter().map(|&(x, y)| luminance(image.pixel(x, y))).sum::<f64>() / pixels.len().max(1) as f64
}

/// Whether `d` is a vertex-lit model (traced, lit by its vertex colours).
fn vertex_lit(d: &Draw) -> bool {
    d.instance.is_some_and(|i| i.lighting == VertexLit)
}

/// Whether `d` is a 3D icon of the HUD: a draw in one of the status bar's icon viewports.
fn hud_icon(d: &Draw) -> bool {
    [[143, 0, 24, 24], [235, 0, 24, 24]].contains(&d.state.viewport)
}

/// Where an image is written for a person to look at (`target/tmp/q3_demo/NAME.png`).
fn keep(image: &Image, name: &str) {
    image.save_png(&programs::scratch("q3_demo", &format!("{name}.png")));
}

/// Side of the square screen regions whose static-world luminance is compared.
const REGION: usize = 40;

/// The acceptance test of issue 16: the fixture's last frame (demo frame 412), path traced
/// with the default settings and converged (4 samples per pixel in each of 2 still frames),
/// against its raster frame (tone curve "knee", the identity up to display 231, so a surface
/// that shows its raster colour is traced as that colour), both without the rocket's light
/// (its two dynamic-light passes and `Frame::lights`: rasterized, the light is an additive
/// texture over the surfaces; traced, a light that they reflect by their albedo, out to its
/// radius: the two differ by design, and `the_rockets_light_lights_the_surfaces_near_it`
/// checks it):
///
/// - **the static world** (every draw of class `Static` with its layers: the lightmapped,
///   detailed, glowing and dynamically lit surfaces of the level, traced `Baked`, so that they
///   emit what the rasterizer shows): each 40 × 40 region of the 8 × 6 grid over the frame in
///   which the world shows in at least 3 pixels of 4 (the regions of the sky, the HUD and the
///   view weapon are left out: they are rasterized, or not the world) has the mean luminance
///   of its world pixels within 5 % of raster's, over every such region;
/// - **the models** (the `VertexLit` draws: two players, the armour, the rocket): their
///   pixels' mean luminance is at least 80 % of raster's: lit by traced light (the baked world
///   they see, the sky) and the direct light recovered from their vertex colours
///   (`render::trace::vertex_light`), never black;
/// - **the HUD's 3D icons** (the head and the armour, `Overlay`, rasterized as drawn over the
///   traced image): their pixels are raster's, bit for bit;
/// - **no pass of a traced surface is left translucent**: the frame has 3 layers, 2
///   dynamic-light passes (traced as the rocket's light, `Light`) and 4 translucent draws
///   (water, the armour's shell, smoke, the flame), none over a traced surface's triangles (`no_translucent_draw_is_a_pass_over_a_traced_surface` checks the
///   triangles; the renderer does not rasterize layers when it traces).
///
/// The images are written to `target/tmp/q3_demo/` (`raster.png`, `traced.png`).
#[test]
fn the_converged_traced_frame_matches_the_raster_frame() {
    let frames = classified_frames();
    let stats = &frames[3].stats;
    assert_eq!((stats.classes.get(Layer), stats.classes.get(Translucent), stats.classes.get(Light)), (3, 4, 2), "{stats:?}");
    let frame = &Frame { lights: Vec::new(), ..without(&frames[3].frame, |d| d.class == Light) };

    let raster = render(frame, None, 1);
    keep(&raster, "raster");
    let settings = Settings { spp: 4, ..Settings::default() };
    let traced = render(frame, Some(settings), 2);
    keep(&traced, "traced");
    assert!(mean_luminance(&traced, [0, 0, 320, 240]) > 50.0, "the traced frame is lit");

    // The static world, region by region.
    let world = shown(&raster, &render(&without(frame, |d| d.class == Static), None, 1));
    let mut compared = Vec::new();
    for (ry, rx) in (0..240 / REGION).flat_map(|ry| (0..320 / REGION).map(move |rx| (ry, rx))) {
        let inside = |&&(x, y): &&(usize, usize)| x / REGION == rx && y / REGION == ry;
        let pixels: Vec<(usize, usize)> = world.iter().filter(inside).copied().collect();
        if pixels.len() * 4 < REGION * REGION * 3 {
            continue;
        }
        let (r, t) = (mean_of(&raster, &pixels), mean_of(&traced, &pixels));
        eprintln!("world region ({}, {}): raster {r:.1}, traced {t:.1}, ratio {:.3}", rx * REGION, ry * REGION, t / r);
        compared.push(((rx, ry), r, t));
    }
    assert!(compared.len() >= 24, "regions of the world: {}", compared.len());
    for &((rx, ry), r, t) in &compared {
        assert!((t - r).abs() <= 0.05 * r, "world region ({}, {}): traced {t:.1} against raster {r:.1}", rx * REGION, ry * REGION);
    }

    // The models.
    let models = shown(&raster, &render(&without(frame, vertex_lit), None, 1));
    let (r, t) = (mean_of(&raster, &models), mean_of(&traced, &models));
    eprintln!("models: {} pixels, raster {r:.1}, traced {t:.1}, ratio {:.3}", models.len(), t / r);
    assert!(models.len() > 500, "model pixels: {}", models.len());
    assert!(t >= 0.8 * r, "models: traced {t:.1} against raster {r:.1}");

    // The HUD's 3D icons.
    let icons = shown(&raster, &render(&without(frame, hud_icon), None, 1));
    assert!(icons.len() > 300, "icon pixels: {}", icons.len());
    let differ = icons.iter().filter(|&&(x, y)| raster.pixel(x, y) != traced.pixel(x, y)).count();
    assert_eq!(differ, 0, "of {} icon pixels", icons.len());
}

/// The green share of `pixels` of `image`: the sum of their green over the sum of their
/// red, green and blue (their hue towards green, whatever their brightness).
fn green_share(image: &Image, pixels: &[(usize, usize)]) -> f64 {
    let sum = |c: usize| pixels.iter().map(|&(x, y)| f64::from(image.pixel(x, y)[c])).sum::<f64>();
    sum(1) / (sum(0) + sum(1) + sum(2)).max(1.0)
}

/// A vertex-lit model keeps the hue of its vertex colours when traced: games tint models
/// through them (OpenArena's green player coats), on top of the light the colours hold
/// (`render::trace::vertex_light`: the albedo keeps their common hue, the light recovered
/// from them lights the model). The fixture's last frame as in
/// `the_converged_traced_frame_matches_the_raster_frame`, with the vertex colours of its
/// `VertexLit` draws made green (times 0.35, 1, 0.35): the green share of the models' pixels
/// traced is within 0.06 of raster's (0.45; with white for the colours in the albedo it was
/// 0.34), and their brightness stays at least 80 % of raster's. What remains is light the
/// game's colours do not have: the blue sky's, and the untinted specular reflection of the
/// sky and the walls (the light recovered from the colours lights the diffuse lobe alone).
/// Images: `target/tmp/q3_demo/green-raster.png`, `green-traced.png`.
#[test]
fn a_tinted_model_keeps_its_hue_traced() {
    let frames = classified_frames();
    let mut frame = Frame { lights: Vec::new(), ..without(&frames[3].frame, |d| d.class == Light) };
    for d in frame.draws.iter_mut().filter(|d| vertex_lit(d)) {
        d.vertices.color.values.iter_mut().for_each(|c| *c = [c[0] * 0.35, c[1], c[2] * 0.35, c[3]]);
    }
    let raster = render(&frame, None, 1);
    keep(&raster, "green-raster");
    let traced = render(&frame, Some(Settings { spp: 4, ..Settings::default() }), 2);
    keep(&traced, "green-traced");
    let models = shown(&raster, &render(&without(&frame, vertex_lit), None, 1));
    assert!(models.len() > 500, "model pixels: {}", models.len());
    let (r, t) = (green_share(&raster, &models), green_share(&traced, &models));
    let (lr, lt) = (mean_of(&raster, &models), mean_of(&traced, &models));
    let rgb = |image: &Image| [0, 1, 2].map(|c| models.iter().map(|&(x, y)| f64::from(image.pixel(x, y)[c])).sum::<f64>() / models.len() as f64);
    eprintln!("green models: {} pixels, green share raster {r:.3}, traced {t:.3}; luminance raster {lr:.1}, traced {lt:.1}; RGB raster {:.1?}, traced {:.1?}", models.len(), rgb(&raster), rgb(&traced));
    assert!(r > 0.42, "the raster models are green: {r:.3}");
    assert!((t - r).abs() <= 0.06, "green share: traced {t:.3} against raster {r:.3}");
    assert!(lt >= 0.8 * lr, "models: traced {lt:.1} against raster {lr:.1}");
}

/// Whether `d` is the light panel's glow: an emission pass over every triangle of its base.
fn glow(frame: &Frame) -> impl Fn(&Draw) -> bool + '_ {
    |d: &Draw| d.layer.as_ref().is_some_and(|l| l.role == Emission && l.triangles.len() == frame.draws[l.base].indices.len() / 3)
}

/// The hall seen through the doorway (x0, y0, x1, y1 from the top left), where the light
/// panel on its ceiling shows.
const HALL: [usize; 4] = [122, 88, 160, 140];

/// A glow lights the surfaces beside it: the light panel's additive glow pass (an `Emission`
/// layer, sampled by next-event estimation) makes the hall around it brighter than the same
/// frame traced without it. With the default settings the hall's surfaces are baked (their
/// lightmaps hold the panel's light already, so they reflect no traced light), so the frame is
/// traced with `lightmaps = "ignore"`: every surface reflects traced light with its albedo.
/// Compared: the hall's pixels (`HALL`) that are neither the panel's nor a model's, direct
/// light only (`bounces = 0`: the emitters sampled by next-event estimation, the sky found by
/// the continuation ray), 8 samples per traced pixel, traced at a quarter of the window's
/// width and height (the mean over the hall is what is compared; the whole frame traced at
/// full size with bounces takes minutes on lavapipe). Images:
/// `target/tmp/q3_demo/ignore-glow.png`, `ignore-no-glow.png`.
#[test]
fn a_glow_lights_the_surfaces_beside_it() {
    let frames = classified_frames();
    let frame = &frames[3].frame;
    let no_glow = without(frame, glow(frame));
    let raster = render(frame, None, 1);
    let panel = shown(&raster, &render(&no_glow, None, 1));
    let models = shown(&raster, &render(&without(frame, vertex_lit), None, 1));
    let [x0, y0, x1, y1] = HALL;
    assert!(panel.iter().any(|&(x, y)| (x0..x1).contains(&x) && (y0..y1).contains(&y)), "the panel shows in the hall");
    let beside: Vec<(usize, usize)> =
        (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).filter(|p| !panel.contains(p) && !models.contains(p)).collect();

    let settings = Settings { spp: 8, bounces: 0, resolution_scale: 0.25, lightmaps: Lightmaps::Ignore, ..Settings::default() };
    let (lit, unlit) = (render(frame, Some(settings), 1), render(&no_glow, Some(settings), 1));
    keep(&lit, "ignore-glow");
    keep(&unlit, "ignore-no-glow");
    let (with, without_glow) = (mean_of(&lit, &beside), mean_of(&unlit, &beside));
    eprintln!("the hall beside the panel ({} pixels): {with:.2} with its glow, {without_glow:.2} without", beside.len());
    // Measured: 6.40 with, 5.16 without (+24 %).
    assert!(with >= 1.1 * without_glow && with - without_glow >= 0.5, "the hall: {with:.2} with the glow, {without_glow:.2} without");
}

/// The rocket's light: the fixture's last frame (demo frame 412, 12 frames into the rocket's
/// flight: `rocket_at` of demo/q3/script.rs puts it at (832.7, 212.7, 78.5), its light of
/// radius 200 and colour (1, 0.75, 0), demo/q3/mod.rs) has two dynamic-light passes, over the
/// floor and the concrete near the rocket; hash tracking makes them one point light
/// (`Frame::lights`) at the rocket, and the tracer samples it. The lit surfaces are baked:
/// there the light brings what the passes bring (`render::trace::lights`), so over the pixels
/// those passes cover in the raster frame, the light traced adds (traced with it, less traced
/// without it: `Frame::lights` emptied; the passes are not rasterized over the traced image
/// either way) a mean luminance within 20 % of what the passes add rasterized (raster with
/// them, less raster without them). Before, a point light reflected by the albedo in linear
/// units added a fifth of it (11.5 against 61.4). Direct light only (`bounces = 0`), 4
/// samples per traced pixel at a quarter of the window's width and height, default settings
/// otherwise. Images: `target/tmp/q3_demo/rocket-light.png`, `no-rocket-light.png`.
#[test]
fn the_rockets_light_lights_the_surfaces_near_it() {
    let frames = classified_frames();
    let frame = &frames[3].frame;
    let passes: Vec<usize> = frame.draws.iter().enumerate().filter(|(_, d)| d.class == Light).map(|(i, _)| i).collect();
    assert_eq!(passes, [7, 9]);
    let [light] = frame.lights[..] else { panic!("one light: {:?}", frame.lights) };
    let view = frame.view.expect("a view").view;
    let world = view.inverse().transform_point3(glam::Vec3::from_array(light.position));
    let rocket = glam::Vec3::new(1000.0 - 976.0 * 12.0 / 70.0, 205.0 + 45.0 * 12.0 / 70.0, 84.0 - 32.0 * 12.0 / 70.0);
    eprintln!("the rocket's light: {world:?} (the rocket at {rocket:?}), radius {:.3}, colour {:?}, falloff {:.1}", light.radius, light.color, light.falloff);
    assert!(world.truncate().distance(rocket.truncate()) < 0.5, "{world:?} against {rocket:?}");
    assert!((world.z - rocket.z).abs() < 100.0, "within half the radius of the rocket's height: {world:?}");
    assert!((light.radius - 200.0).abs() < 0.1, "{light:?}");
    assert!(glam::Vec3::from_array(light.color).abs_diff_eq(glam::Vec3::new(1.0, 0.75, 0.0), 0.01), "{light:?}");

    let (raster, raster_dark) = (render(frame, None, 1), render(&without(frame, |d| d.class == Light), None, 1));
    let lit = shown(&raster, &raster_dark);
    assert!(lit.len() > 500, "pixels the passes cover: {}", lit.len());
    let settings = Settings { spp: 4, bounces: 0, resolution_scale: 0.25, ..Settings::default() };
    let dark = Frame { lights: Vec::new(), ..frame.clone() };
    let (with, without_light) = (render(frame, Some(settings), 1), render(&dark, Some(settings), 1));
    keep(&with, "rocket-light");
    keep(&without_light, "no-rocket-light");
    let (r, w, wo) = (mean_of(&raster, &lit), mean_of(&with, &lit), mean_of(&without_light, &lit));
    let rd = mean_of(&raster_dark, &lit);
    eprintln!("near the rocket ({} pixels): raster {r:.2} with the passes, {rd:.2} without; traced {w:.2} with its light, {wo:.2} without", lit.len());
    assert!(w >= 1.15 * wo && w - wo >= 5.0, "near the rocket: {w:.2} with its light, {wo:.2} without");
    let (added_raster, added_traced) = (r - rd, w - wo);
    assert!((added_traced - added_raster).abs() <= 0.2 * added_raster, "the light adds {added_traced:.2} traced, the passes {added_raster:.2} rasterized");
    // The light reaches as far as its radius: the rest of the frame (the sky, the HUD and the
    // models aside: pixels the two traced frames differ in by less than noise) is as dark.
    let far: Vec<(usize, usize)> = (0..240).flat_map(|y| (0..320).map(move |x| (x, y))).filter(|p| !lit.contains(p)).collect();
    let (wf, wof) = (mean_of(&with, &far), mean_of(&without_light, &far));
    eprintln!("elsewhere ({} pixels): {wf:.2} with the light, {wof:.2} without", far.len());
    assert!((wf - wof).abs() <= 0.05 * wof, "elsewhere: {wf:.2} with the light, {wof:.2} without");
}

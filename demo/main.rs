//! glrt-demo: an OpenGL 1.x program written like an old game. It loads `libGL.so.1` by name
//! at run time and resolves every function with `dlsym` (extensions with
//! `glXGetProcAddressARB`), opens an Xlib window with GLX (or uses glrt's headless context),
//! and draws a room with pillars (display list), a swinging door, an animated mesh (client
//! arrays), glass, a sky, lights, fog and a HUD (`glBitmap` text). `--rebatch` draws a world
//! re-batched per texture every frame as Quake 3 does ([`rebatch`]); `--q3` draws a level
//! exactly as ioquake3's OpenGL 1 renderer draws one ([`q3`]: baked lightmaps, multi-pass
//! shaders, vertex-lit models, dynamic lights, sky, 3D HUD icons).
//!
//! Usage: `glrt-demo [--frames N] [--first-frame N] [--size WxH] [--headless] [--lib PATH]
//! [--screenshot PNG] [--bench-immediate [VERTICES] [--cull]] [--rebatch [--detail N] [--verbose]]
//! [--q3 [--verbose]]`. At the end it prints the frame count and frame times.

mod bench;
mod font;
mod gl;
mod loader;
mod q3;
mod rebatch;
mod scene;
mod screenshot;
mod window;

use std::process::ExitCode;
use std::time::Instant;

use loader::GlLibrary;
use window::{HeadlessContext, Surface, X11Window};

/// Command-line options.
struct Options {
    frames: u64,
    /// Scene frame number of the first frame drawn (to look at a given moment).
    first_frame: u64,
    width: i32,
    height: i32,
    headless: bool,
    lib: String,
    /// `--screenshot`: PNG file for the last frame.
    screenshot: Option<String>,
    /// `--bench-immediate`: vertex count of the throughput benchmark instead of the scene.
    bench_vertices: Option<u64>,
    /// `--cull`: the benchmark's triangles are all culled (`GL_CULL_FACE` on,
    /// `glCullFace(GL_FRONT_AND_BACK)`).
    cull: bool,
    /// `--rebatch`: the Quake-3-like world instead of the scene.
    rebatch: bool,
    /// `--q3`: the level drawn as ioquake3's renderer draws one, instead of the scene.
    q3: bool,
    /// `--detail`: quads along each side of a rebatch surface cell (1..=64).
    detail: u32,
    /// `--verbose`: one line per `--rebatch` or `--q3` frame (surfaces, batches, draws).
    verbose: bool,
}

const USAGE: &str = "usage: glrt-demo [--frames N] [--first-frame N] [--size WxH] [--headless] [--lib PATH] [--screenshot PNG] [--bench-immediate [VERTICES] [--cull]] [--rebatch [--detail N] [--verbose]] [--q3 [--verbose]]

  --bench-immediate  immediate-mode throughput: VERTICES vertices per frame (default 10
        million), 3 frames unless --frames says otherwise; --cull culls every triangle
        (GL_CULL_FACE on, glCullFace(GL_FRONT_AND_BACK))

  --q3  a Quake-3-like level drawn as ioquake3's OpenGL 1 renderer draws one: lightmaps baked
        at start-up on texture unit 1 or as a GL_DST_COLOR, GL_ZERO pass, detail and additive
        glow passes, vertex-lit animated models, a dynamic light pass, a sky box, water,
        sprites, 3D HUD icons and a 2D HUD, along a scripted camera path of 480 frames";

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        frames: u64::MAX,
        first_frame: 0,
        width: 640,
        height: 480,
        headless: false,
        lib: "libGL.so.1".into(),
        screenshot: None,
        bench_vertices: None,
        cull: false,
        rebatch: false,
        q3: false,
        detail: 1,
        verbose: false,
    };
    let mut it = args.iter().peekable();
    while let Some(arg) = it.next() {
        let mut value = |what: &str| it.next().cloned().ok_or(format!("{arg} needs {what}"));
        match arg.as_str() {
            "--frames" => {
                o.frames = value("a count")?.parse().map_err(|e| format!("--frames: {e}"))?
            }
            "--first-frame" => {
                o.first_frame =
                    value("a frame number")?.parse().map_err(|e| format!("--first-frame: {e}"))?
            }
            "--size" => {
                let v = value("WxH")?;
                let (w, h) = v.split_once(['x', 'X']).ok_or("--size: expected WxH")?;
                o.width = w.parse().map_err(|e| format!("--size: {e}"))?;
                o.height = h.parse().map_err(|e| format!("--size: {e}"))?;
                if !(1..=16384).contains(&o.width) || !(1..=16384).contains(&o.height) {
                    return Err("--size: each side must be 1..=16384".into());
                }
            }
            "--headless" => o.headless = true,
            "--lib" => o.lib = value("a path")?,
            "--screenshot" => o.screenshot = Some(value("a path")?),
            "--bench-immediate" => {
                let n = match it.peek() {
                    Some(n) if !n.starts_with("--") => {
                        let n = it.next().map(String::as_str).unwrap_or_default();
                        n.parse().map_err(|e| format!("--bench-immediate: {e}"))?
                    }
                    _ => 10_000_000,
                };
                o.bench_vertices = Some(n);
            }
            "--cull" => o.cull = true,
            "--rebatch" => o.rebatch = true,
            "--q3" => o.q3 = true,
            "--detail" => {
                o.detail = value("a count")?.parse().map_err(|e| format!("--detail: {e}"))?;
                if !(1..=64).contains(&o.detail) {
                    return Err("--detail: must be 1..=64".into());
                }
            }
            "--verbose" => o.verbose = true,
            "--help" | "-h" => return Err(USAGE.into()),
            other => return Err(format!("unknown argument '{other}'\n{USAGE}")),
        }
    }
    Ok(o)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let options = match parse_args(&args) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("glrt-demo: {e}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure { code, message }) => {
            eprintln!("glrt-demo: {message}");
            ExitCode::from(code)
        }
    }
}

/// Why the demo stopped: exit status and message.
struct Failure {
    code: u8,
    message: String,
}

impl From<String> for Failure {
    fn from(message: String) -> Self {
        Self { code: 1, message }
    }
}

fn run(o: &Options) -> Result<(), Failure> {
    let lib = GlLibrary::open(&o.lib)?;
    if o.headless && lib.symbol("glrtCreateContext").is_null() {
        let message = format!(
            "{} has no headless context API (glrtCreateContext): --headless needs glrt's libGL",
            lib.name
        );
        return Err(Failure { code: 2, message });
    }
    let surface = if o.headless {
        Surface::Headless(HeadlessContext::open(&lib, o.width, o.height)?)
    } else {
        Surface::X11(Box::new(X11Window::open(&lib, o.width, o.height, "glrt-demo")?))
    };
    let api = gl::GlApi::load(&lib)?;
    println!(
        "glrt-demo: {} | {} | {}",
        gl::gl_string(&api.gl, gl::GL_VENDOR),
        gl::gl_string(&api.gl, gl::GL_RENDERER),
        gl::gl_string(&api.gl, gl::GL_VERSION)
    );
    if let Some(vertices) = o.bench_vertices {
        let frames = if o.frames == u64::MAX { 3 } else { o.frames };
        let bench = bench::Bench { vertices, frames, cull: o.cull, width: o.width, height: o.height };
        bench.run(&api, &surface);
        return Ok(());
    }
    let mut program = if o.q3 {
        Program::Q3(Box::new(q3::Q3::new(&api, o.width, o.height, o.verbose)?))
    } else if o.rebatch {
        Program::Rebatch(rebatch::World::new(&api.gl, o.detail, o.width, o.height, o.verbose))
    } else {
        Program::Scene(scene::Scene::new(&api, o.width, o.height))
    };
    let mut times = FrameTimes::default();
    for n in 0..o.frames {
        let start = Instant::now();
        program.draw(&api, o.first_frame.saturating_add(n))?;
        if n + 1 == o.frames
            && let Some(path) = &o.screenshot
        {
            let rgb = screenshot::read(&api.gl, o.width, o.height);
            let png = screenshot::png(o.width as u32, o.height as u32, &rgb);
            std::fs::write(path, png).map_err(|e| format!("cannot write {path}: {e}"))?;
        }
        surface.swap();
        times.add(start.elapsed().as_secs_f64() * 1000.0);
    }
    program.delete(&api);
    times.print();
    Ok(())
}

/// What the demo draws.
enum Program {
    Scene(scene::Scene),
    Rebatch(rebatch::World),
    Q3(Box<q3::Q3>),
}

impl Program {
    /// Draws frame `frame`; fails when the program found a GL error.
    fn draw(&mut self, api: &gl::GlApi, frame: u64) -> Result<(), String> {
        match self {
            Program::Scene(scene) => scene.draw(api, frame),
            Program::Rebatch(world) => world.draw(&api.gl, frame),
            Program::Q3(q3) => return q3.draw(&api.gl, frame),
        }
        Ok(())
    }

    fn delete(&self, api: &gl::GlApi) {
        match self {
            Program::Scene(scene) => scene.delete(api),
            Program::Rebatch(world) => world.delete(&api.gl),
            Program::Q3(q3) => q3.delete(&api.gl),
        }
    }
}

/// Frame-time statistics in milliseconds.
#[derive(Default)]
struct FrameTimes {
    count: u64,
    sum: f64,
    min: f64,
    max: f64,
}

impl FrameTimes {
    fn add(&mut self, ms: f64) {
        self.min = if self.count == 0 { ms } else { self.min.min(ms) };
        self.max = self.max.max(ms);
        self.sum += ms;
        self.count += 1;
    }

    fn print(&self) {
        let avg = if self.count == 0 { 0.0 } else { self.sum / self.count as f64 };
        println!(
            "frames: {}  frame time ms: avg {avg:.3}  min {:.3}  max {:.3}",
            self.count, self.min, self.max
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn parses_flags() {
        let o = parse_args(&args(
            "--frames 60 --size 320x200 --headless --lib /x/libGL.so.1 --first-frame 7 --screenshot s.png",
        ))
        .unwrap();
        assert_eq!(o.screenshot.as_deref(), Some("s.png"));
        assert_eq!(
            (o.frames, o.first_frame, o.width, o.height, o.headless),
            (60, 7, 320, 200, true)
        );
        assert_eq!(o.lib, "/x/libGL.so.1");
        assert_eq!(o.bench_vertices, None);
        assert!(!o.rebatch && !o.q3 && !o.verbose && o.detail == 1);
        assert!(parse_args(&args("--q3 --verbose")).is_ok_and(|q| q.q3 && q.verbose));
        let r = parse_args(&args("--rebatch --detail 4 --verbose")).unwrap();
        assert!(r.rebatch && r.verbose && r.detail == 4);
        assert_eq!(
            parse_args(&args("--bench-immediate")).unwrap().bench_vertices,
            Some(10_000_000)
        );
        assert_eq!(
            parse_args(&args("--bench-immediate 300 --headless")).unwrap().bench_vertices,
            Some(300)
        );
        let culled = parse_args(&args("--bench-immediate 300 --cull")).unwrap();
        assert!(culled.cull && !parse_args(&args("--bench-immediate")).unwrap().cull);
    }

    #[test]
    fn rejects_bad_flags() {
        assert!(parse_args(&args("--size 0x10")).is_err());
        assert!(parse_args(&args("--frames")).is_err());
        assert!(parse_args(&args("--bogus")).is_err());
        assert!(parse_args(&args("--detail 0")).is_err());
        assert!(parse_args(&args("--detail 65")).is_err());
    }

    #[test]
    fn frame_times_track_extremes() {
        let mut t = FrameTimes::default();
        for ms in [3.0, 1.0, 2.0] {
            t.add(ms);
        }
        assert_eq!((t.count, t.min, t.max), (3, 1.0, 3.0));
        assert!((t.sum / 3.0 - 2.0).abs() < 1e-12);
    }
}

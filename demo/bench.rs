//! `--bench-immediate`: immediate-mode submission throughput. Each frame submits `vertices`
//! vertices as `glColor3f` + `glTexCoord2f` + `glVertex3f` each, in `GL_TRIANGLES` batches of
//! [`BATCH`] vertices per `glBegin`/`glEnd`, then `glFinish` and a swap; one line per frame and
//! the steady rate: vertices per second of the median frame after the first. (Not the best
//! frame: a library that renders a frame while the program submits the next one returns from
//! some swaps before the frame is drawn, and pays for it at the next swap.) Triangles are a pixel or so big so rasterisation does
//! not dominate. With `cull`, `GL_CULL_FACE` is on with `glCullFace(GL_FRONT_AND_BACK)`:
//! every triangle is culled, whatever its winding.

use std::time::Instant;

use crate::gl::*;
use crate::window::Surface;

/// Vertices per `glBegin`/`glEnd`.
pub const BATCH: u64 = 3000;

/// What the benchmark draws.
pub struct Bench {
    /// Vertices per frame (rounded down to whole triangles).
    pub vertices: u64,
    /// Frames drawn.
    pub frames: u64,
    /// Whether every triangle is culled.
    pub cull: bool,
    /// Viewport size.
    pub width: i32,
    /// Viewport size.
    pub height: i32,
}

impl Bench {
    /// Runs the benchmark and prints one line per frame and the best frame.
    pub fn run(&self, api: &GlApi, surface: &Surface) {
        let gl = &api.gl;
        // Safety: a context is current.
        unsafe {
            gl.glViewport(0, 0, self.width, self.height);
            gl.glMatrixMode(GL_PROJECTION);
            gl.glLoadIdentity();
            gl.glMatrixMode(GL_MODELVIEW);
            gl.glLoadIdentity();
            if self.cull {
                gl.glCullFace(GL_FRONT_AND_BACK);
                gl.glEnable(GL_CULL_FACE);
            }
        }
        let culled = if self.cull { ", culled" } else { "" };
        let mut times = Vec::new();
        let mut sent = 0;
        for frame in 1..=self.frames {
            let start = Instant::now();
            sent = self.frame(gl);
            surface.swap();
            let seconds = start.elapsed().as_secs_f64();
            times.push(seconds);
            println!("immediate: frame {frame}: {sent} vertices{culled} in {seconds:.3} s");
        }
        // The first frame compiles pipelines; the median of the others is the steady rate.
        let steady = if times.len() > 1 { &mut times[1..] } else { &mut times[..] };
        steady.sort_by(f64::total_cmp);
        let median = steady[steady.len() / 2];
        println!(
            "immediate: median of {} frames after the first: {sent} vertices{culled} in {median:.3} s: {:.0} vertices/s",
            steady.len(),
            sent as f64 / median.max(1e-9)
        );
    }

    /// Draws one frame up to `glFinish`; returns the vertices sent.
    fn frame(&self, gl: &Gl) -> u64 {
        // Safety: a context is current.
        unsafe { gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT) };
        let mut sent = 0u64;
        while sent < self.vertices {
            let batch = BATCH.min(self.vertices - sent) / 3 * 3;
            if batch == 0 {
                break;
            }
            // Safety: a context is current; only scalar calls inside glBegin/glEnd.
            unsafe {
                gl.glBegin(GL_TRIANGLES);
                for i in 0..batch {
                    let v = sent + i;
                    // Clockwise triangles on a 64 × 64 lattice in clip space.
                    let cell = (v / 3) % 4096;
                    let (cx, cy) = ((cell % 64) as f32 / 32.0 - 1.0, (cell / 64) as f32 / 32.0 - 1.0);
                    let corner = (v % 3) as f32;
                    let f = (v % 251) as f32 / 251.0;
                    gl.glColor3f(f, 1.0 - f, 0.5);
                    gl.glTexCoord2f(corner * 0.5, f);
                    gl.glVertex3f(cx + corner * 0.004, cy + (corner % 2.0) * 0.006, 0.0);
                }
                gl.glEnd();
            }
            sent += batch;
        }
        // Safety: a context is current.
        unsafe { gl.glFinish() };
        sent
    }
}

//! `--bench-immediate`: immediate-mode submission throughput. Submits `vertices` vertices as
//! `glColor3f` + `glTexCoord2f` + `glVertex3f` each, in `GL_TRIANGLES` batches of
//! [`BATCH`] vertices per `glBegin`/`glEnd`, then `glFinish` and a swap, and reports
//! vertices per second. Triangles are a few pixels big so rasterisation does not dominate.

use std::time::Instant;

use crate::gl::*;
use crate::window::Surface;

/// Vertices per `glBegin`/`glEnd`.
pub const BATCH: u64 = 3000;

/// Runs the benchmark and prints the result line.
pub fn run(api: &GlApi, surface: &Surface, vertices: u64, width: i32, height: i32) {
    let gl = &api.gl;
    // Safety: a context is current.
    unsafe {
        gl.glViewport(0, 0, width, height);
        gl.glMatrixMode(GL_PROJECTION);
        gl.glLoadIdentity();
        gl.glMatrixMode(GL_MODELVIEW);
        gl.glLoadIdentity();
        gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    let start = Instant::now();
    let mut sent = 0u64;
    while sent < vertices {
        let batch = BATCH.min(vertices - sent) / 3 * 3;
        if batch == 0 {
            break;
        }
        // Safety: a context is current; only scalar calls inside glBegin/glEnd.
        unsafe {
            gl.glBegin(GL_TRIANGLES);
            for i in 0..batch {
                let v = sent + i;
                // Triangles on a 64 × 64 lattice in clip space, 3 pixels or so each.
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
    surface.swap();
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "immediate: {sent} vertices in {seconds:.3} s: {:.0} vertices/s",
        sent as f64 / seconds.max(1e-9)
    );
}

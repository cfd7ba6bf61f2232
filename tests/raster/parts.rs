//! Frames submitted in parts (`translate::frame_memory`): a program that draws far past the
//! frame budget without swapping (streaming a new texture for every quad, blending, a pixel
//! image and a read-back on the way) gets the image one submission gives, while the frame it
//! holds and the texture versions on the GPU stay bounded.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use crate::lavapipe;

use glrt::frame::pixels::PixelBuffer;
use glrt::frame::{Frame, FrameEnd, FrameSink, Target};
use glrt::render::frame::Renderer;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 64;

/// Quads drawn, each with a texture of its own.
const QUADS: usize = 300;

/// Side of each quad's texture, in texels.
const TEXTURE: usize = 16;

/// A renderer shared with the test, counting the parts it is given.
struct Counting {
    renderer: Arc<Mutex<Renderer>>,
    parts: Arc<AtomicUsize>,
}

impl FrameSink for Counting {
    fn present(&mut self, frame: Frame) {
        if frame.end == FrameEnd::Part {
            self.parts.fetch_add(1, Ordering::Relaxed);
        }
        self.renderer.lock().unwrap().present(frame);
    }

    fn set_target(&mut self, target: Target) {
        self.renderer.lock().unwrap().set_target(target);
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.renderer.lock().unwrap().read_pixels(frame, buffer, rect)
    }
}

/// What one run of [`draw_streaming`] gives.
struct Run {
    image: Vec<u8>,
    parts: usize,
    /// The most bytes the frame held after a quad.
    peak_frame_bytes: u64,
    /// The most texture versions on the GPU after a quad.
    peak_textures: usize,
}

/// Reads the whole window as RGBA8.
fn read_window(ctx: &mut Context) -> Vec<u8> {
    let mut out = vec![0u8; (SIZE * SIZE * 4) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// Clears, then draws [`QUADS`] overlapping blended quads, each textured with a new texture
/// (generated, drawn with, deleted: piglit's `streaming-texture-leak`), with a pixel image
/// and a read-back halfway, all in one frame under a budget of `budget` bytes; reads the window.
fn draw_streaming(budget: u64) -> Run {
    let renderer = Arc::new(Mutex::new(lavapipe::renderer_with(Renderer::new)));
    let parts = Arc::new(AtomicUsize::new(0));
    let sink = Counting { renderer: renderer.clone(), parts: parts.clone() };
    let mut ctx = Context::new(glrt::translate::context::ContextConfig { share: None, sink: Box::new(sink) });
    ctx.bind_drawable(SIZE, SIZE);
    ctx.set_frame_budget(budget);
    let (mut peak_frame_bytes, mut peak_textures) = (0, 0);
    // Safety: plain GL calls on a context of this thread; every pointer outlives its call and
    // holds what the arguments say.
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.1, 0.2, 0.3, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
        dispatch::glEnable(&mut ctx, gl::GL_BLEND);
        dispatch::glBlendFunc(&mut ctx, gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA);
        for i in 0..QUADS {
            let texels: Vec<u8> = (0..TEXTURE * TEXTURE).flat_map(|t| [(i * 7 + t) as u8, (i * 13) as u8, (t * 3) as u8, 96 + (i % 128) as u8]).collect();
            let mut name = 0;
            dispatch::glGenTextures(&mut ctx, 1, &mut name);
            dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, name);
            dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
            dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
            let n = TEXTURE as i32;
            dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, n, n, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
            // Quads of 0.5 × 0.5 walking over the window, overlapping their neighbours.
            let (x, y) = ((i % 7) as f32 * 0.25 - 1.0, ((i / 7) % 7) as f32 * 0.25 - 1.0);
            dispatch::glBegin(&mut ctx, gl::GL_QUADS);
            for (s, t) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                dispatch::glTexCoord2f(&mut ctx, s, t);
                dispatch::glVertex2f(&mut ctx, x + 0.5 * s, y + 0.5 * t);
            }
            dispatch::glEnd(&mut ctx);
            dispatch::glDeleteTextures(&mut ctx, 1, &name);
            if i == QUADS / 2 {
                let image: Vec<u8> = (0..8 * 8).flat_map(|p| [255, (p * 4) as u8, 0, 255]).collect();
                dispatch::glRasterPos2f(&mut ctx, 0.0, 0.0);
                dispatch::glDrawPixels(&mut ctx, 8, 8, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, image.as_ptr().cast());
                let mut probe = [0u8; 4];
                dispatch::glReadPixels(&mut ctx, 40, 40, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, probe.as_mut_ptr().cast());
            }
            peak_frame_bytes = peak_frame_bytes.max(ctx.frame_bytes());
            peak_textures = peak_textures.max(renderer.lock().unwrap().raster().texture_count());
        }
    }
    let image = read_window(&mut ctx);
    Run { image, parts: parts.load(Ordering::Relaxed), peak_frame_bytes, peak_textures }
}

#[test]
fn a_frame_past_its_budget_is_drawn_in_parts_with_the_image_of_one_submission() {
    let whole = draw_streaming(1 << 40);
    assert_eq!(whole.parts, 0, "an unlimited budget submits the frame once");
    // One quad's texture is 1 KB of texels: the frame holds about 300 KB in all.
    assert!(whole.peak_frame_bytes > 300 * 1024, "{}", whole.peak_frame_bytes);
    let budget = 32 * 1024;
    let parts = draw_streaming(budget);
    assert!(parts.parts >= 8, "{} parts", parts.parts);
    let differing = whole.image.chunks(4).zip(parts.image.chunks(4)).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "pixels differ between one submission and {} parts", parts.parts);
    assert!(whole.image.chunks(4).any(|p| p != whole.image[..4].to_vec()), "the quads drew something");
    // Counted after each quad: at most the budget plus the quad that passed it.
    assert!(parts.peak_frame_bytes <= budget + 8 * 1024, "the frame held {} bytes", parts.peak_frame_bytes);
    // The versions of one part (a quad is ~2 KB with its texture) and the white default;
    // the frame drawn once keeps all of them until its end.
    assert!(parts.peak_textures <= 32, "{} texture versions on the GPU", parts.peak_textures);
    assert!(whole.peak_textures >= QUADS / 2, "{} texture versions on the GPU", whole.peak_textures);
}

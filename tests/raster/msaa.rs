//! Multisampled drawables on the Vulkan raster renderer (OpenGL 1.5 sections 3.2.1 and 4.1.3):
//! edges blend after the resolve, `GL_SAMPLES` answers the drawable, `glSampleCoverage` and
//! alpha to coverage write a share of the samples, `GL_MULTISAMPLE` off rasterizes as a
//! single-sampled drawable does, depth reads back. Each test runs at every sample count the
//! device renders (4 on Mesa lavapipe; 2, 4 and 8 on NVIDIA), at 16×16.

use crate::lavapipe;

use glrt::frame::{Surface, Target};
use glrt::render::frame::Renderer;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 16;

/// A context drawing into a Vulkan renderer on lavapipe, with a 16×16 drawable of `samples`
/// samples per pixel.
fn context(samples: u32) -> Context {
    context_with(samples, Renderer::new)
}

/// The multisampled counts of the device (lavapipe renders 4).
fn counts() -> Vec<u32> {
    let counts = lavapipe::renderer_with(Renderer::without_outputs).device().features.sample_counts.clone();
    assert!(!counts.is_empty(), "the device renders multisampled framebuffers");
    counts
}

/// [`context`] on the renderer `make` creates.
fn context_with(samples: u32, make: impl FnOnce() -> Result<Renderer, glrt::render::raster::device::Error>) -> Context {
    let renderer = lavapipe::renderer_with(make);
    assert!(samples == 1 || renderer.device().features.sample_counts.contains(&samples), "the device renders {samples} samples");
    let mut ctx = lavapipe::context_on(renderer);
    ctx.bind_target(Target { size: [SIZE as u32; 2], surface: Surface::Offscreen, swap_interval: 0, samples, alpha: true });
    ctx
}

/// Every pixel's RGBA8 value, rows bottom to top.
fn pixels(ctx: &mut Context) -> Vec<[u8; 4]> {
    let mut out = vec![[0u8; 4]; (SIZE * SIZE) as usize];
    unsafe { dispatch::glReadPixels(ctx, 0, 0, SIZE, SIZE, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

fn integer(ctx: &mut Context, pname: gl::GLenum) -> i32 {
    let mut v = 0;
    unsafe { dispatch::glGetIntegerv(ctx, pname, &mut v) };
    v
}

/// Clears to black and draws a white triangle with two slanted edges over the lower part of
/// the window.
fn slanted_triangle(ctx: &mut Context) {
    unsafe {
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 0.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glColor3f(ctx, 1.0, 1.0, 1.0);
        dispatch::glBegin(ctx, gl::GL_TRIANGLES);
        for (x, y) in [(-0.93, -0.97), (0.91, -0.6), (-0.3, 0.87)] {
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    }
}

/// How many pixels have a red value strictly between 0 and 255.
fn intermediate(image: &[[u8; 4]]) -> usize {
    image.iter().filter(|p| p[0] != 0 && p[0] != 255).count()
}

#[test]
fn samples_blend_edges_where_one_sample_does_not() {
    let mut single = context(1);
    assert_eq!((integer(&mut single, gl::GL_SAMPLE_BUFFERS), integer(&mut single, gl::GL_SAMPLES)), (0, 0));
    slanted_triangle(&mut single);
    let hard = pixels(&mut single);
    assert_eq!(intermediate(&hard), 0, "one sample: only black and white");
    assert!(hard.iter().filter(|p| p[0] == 255).count() > 40, "the triangle is drawn");

    for n in counts() {
        let mut multi = context(n);
        assert_eq!((integer(&mut multi, gl::GL_SAMPLE_BUFFERS), integer(&mut multi, gl::GL_SAMPLES)), (1, n as i32));
        slanted_triangle(&mut multi);
        let smooth = pixels(&mut multi);
        let blended = intermediate(&smooth);
        assert!(blended >= 10, "{n} samples: edge pixels are blended ({blended})");
        // Every blended value is a whole number of covered samples out of n.
        for p in smooth.iter().filter(|p| p[0] != 0 && p[0] != 255) {
            let k = (p[0] as f32 * n as f32 / 255.0).round();
            assert!((p[0] as f32 - k * 255.0 / n as f32).abs() <= 1.0, "{p:?} is k/{n} white");
        }
    }
}

#[test]
fn disabled_multisample_rasterizes_as_single_sampled() {
    let mut single = context(1);
    slanted_triangle(&mut single);
    let expected = pixels(&mut single);
    for n in counts() {
        let mut multi = context(n);
        unsafe { dispatch::glDisable(&mut multi, gl::GL_MULTISAMPLE) };
        slanted_triangle(&mut multi);
        let got = pixels(&mut multi);
        assert_eq!(intermediate(&got), 0, "no blended edge pixels");
        let differing = got.iter().zip(&expected).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "the pixel centres decide coverage, as with one sample");
        // On again: edges blend.
        unsafe { dispatch::glEnable(&mut multi, gl::GL_MULTISAMPLE) };
        slanted_triangle(&mut multi);
        assert!(intermediate(&pixels(&mut multi)) > 0);
    }
}

/// Draws a white quad over the whole window at depth `z` (identity matrices).
fn full_quad(ctx: &mut Context, color: [f32; 4], z: f32) {
    unsafe {
        dispatch::glColor4f(ctx, color[0], color[1], color[2], color[3]);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

#[test]
fn sample_coverage_writes_its_share_of_the_samples() {
    for n in counts() {
        let mut ctx = context(n);
        unsafe {
            dispatch::glClearColor(&mut ctx, 0.0, 0.0, 0.0, 0.0);
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            dispatch::glEnable(&mut ctx, gl::GL_SAMPLE_COVERAGE);
            dispatch::glSampleCoverage(&mut ctx, 0.5, gl::GL_FALSE);
        }
        full_quad(&mut ctx, [1.0; 4], 0.0);
        let half = pixels(&mut ctx);
        assert!(half.iter().all(|p| (p[0] as i32 - 128).abs() <= 4), "half the samples are white: {:?}", half[0]);
        // The inverted mask covers the other half.
        unsafe { dispatch::glSampleCoverage(&mut ctx, 0.5, gl::GL_TRUE) };
        full_quad(&mut ctx, [1.0; 4], 0.0);
        assert!(pixels(&mut ctx).iter().all(|p| p[0] == 255), "both halves white");
        // GL_MULTISAMPLE off: the coverage operations do not apply (section 4.1.3).
        unsafe {
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            dispatch::glDisable(&mut ctx, gl::GL_MULTISAMPLE);
        }
        full_quad(&mut ctx, [1.0; 4], 0.0);
        assert!(pixels(&mut ctx).iter().all(|p| p[0] == 255), "full coverage without multisampling");
    }
}

#[test]
fn alpha_to_coverage_covers_by_alpha() {
    for n in counts() {
        let mut ctx = context(n);
        unsafe {
            dispatch::glClearColor(&mut ctx, 0.0, 0.0, 0.0, 0.0);
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            dispatch::glEnable(&mut ctx, gl::GL_SAMPLE_ALPHA_TO_COVERAGE);
        }
        full_quad(&mut ctx, [1.0, 1.0, 1.0, 0.5], 0.0);
        let image = pixels(&mut ctx);
        let mean = image.iter().map(|p| p[0] as f64).sum::<f64>() / image.len() as f64;
        assert!((mean - 127.5).abs() < 25.0, "about half the samples written: mean red {mean}");
        unsafe {
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            dispatch::glEnable(&mut ctx, gl::GL_SAMPLE_ALPHA_TO_ONE);
        }
        full_quad(&mut ctx, [1.0, 1.0, 1.0, 1.0], 0.0);
        assert!(pixels(&mut ctx).iter().all(|p| p == &[255; 4]), "alpha 1: every sample, alpha stays 1");
    }
}

#[test]
fn depth_and_copies_read_the_resolved_framebuffer() {
    let mut ctx = context(counts()[0]);
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 1.0, 1.0);
        dispatch::glClearDepth(&mut ctx, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
    }
    full_quad(&mut ctx, [1.0, 0.0, 0.0, 1.0], 0.5);
    let mut depth = [0f32; 1];
    unsafe { dispatch::glReadPixels(&mut ctx, 3, 3, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depth.as_mut_ptr().cast()) };
    assert!((depth[0] - 0.75).abs() < 1e-3, "depth of z = 0.5 is 0.75, read {}", depth[0]);
    // glCopyPixels of the lower-left 4×4 pixels onto the upper-right corner, after a clear
    // of the right half to green.
    unsafe {
        dispatch::glDisable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, SIZE / 2, 0, SIZE / 2, SIZE);
        dispatch::glClearColor(&mut ctx, 0.0, 1.0, 0.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glDisable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glWindowPos2i(&mut ctx, SIZE - 4, SIZE - 4);
        dispatch::glCopyPixels(&mut ctx, 0, 0, 4, 4, gl::GL_COLOR);
    }
    let image = pixels(&mut ctx);
    let at = |x: i32, y: i32| image[(y * SIZE + x) as usize];
    assert_eq!(at(SIZE - 2, SIZE - 2), [255, 0, 0, 255], "copied red");
    assert_eq!(at(SIZE - 6, SIZE - 6), [0, 255, 0, 255], "green outside the copy");
    assert_eq!(at(1, 1), [255, 0, 0, 255]);
}

#[test]
fn presented_frames_are_resolved() {
    let dir = std::env::temp_dir().join(format!("glrt-msaa-dump-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut ctx = context_with(counts()[0], || {
        let mut renderer = Renderer::without_outputs()?;
        renderer.add_output(Box::new(glrt::render::raster::dump::Dump::new(dir.clone(), 0).expect("a dump directory")));
        Ok(renderer)
    });
    slanted_triangle(&mut ctx);
    // The image read back before the swap is what the swap shows (rows bottom to top here,
    // top to bottom in the PNG).
    let read = pixels(&mut ctx);
    ctx.end_frame();
    drop(ctx);
    let file = std::fs::File::open(dir.join("frame-00000.png")).expect("the frame's PNG");
    let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().unwrap();
    let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut rgb).unwrap();
    let shown: Vec<u8> = (0..SIZE as usize).rev().flat_map(|row| rgb[row * SIZE as usize * 3..][..SIZE as usize * 3].iter().step_by(3).copied().collect::<Vec<_>>()).collect();
    let expected: Vec<u8> = read.iter().map(|p| p[0]).collect();
    assert_eq!(shown, expected, "the presented red channel equals the resolved read-back");
    assert!(shown.iter().any(|&v| v != 0 && v != 255), "blended edges reach the presented frame");
    let _ = std::fs::remove_dir_all(&dir);
}

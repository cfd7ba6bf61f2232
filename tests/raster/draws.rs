//! The Vulkan raster renderer on real GL calls, read back with `glReadPixels`: clears, draws,
//! the y orientation and front faces through the flipped viewport, depth and stencil reads.
//! Runs on Mesa lavapipe (forced through `VK_DRIVER_FILES` when its ICD file exists), at
//! 64×64 so it stays fast on a CPU.

use crate::lavapipe;

use glrt::render::frame::Renderer;
use glrt::translate::{Context, dispatch, gl};
use lavapipe::pixel;

const SIZE: i32 = 64;

/// A context drawing into a Vulkan renderer on lavapipe, with a 64×64 drawable.
fn context() -> Context {
    context_with(Renderer::new)
}

/// A context drawing into the renderer `make` creates (on lavapipe), with a 64×64 drawable.
fn context_with(make: impl FnOnce() -> Result<Renderer, glrt::render::raster::device::Error>) -> Context {
    let mut ctx = lavapipe::context_on(lavapipe::renderer_with(make));
    ctx.bind_drawable(SIZE, SIZE);
    ctx
}

/// Reads the RGBA8 pixel at window (x, y).
/// Asserts that every channel of `actual` is within 1 of `expected` (the rounding of colours
/// that fall between two 8-bit values differs between devices).
fn assert_near(actual: [u8; 4], expected: [u8; 4]) {
    assert!(actual.iter().zip(expected).all(|(a, e)| a.abs_diff(e) <= 1), "{actual:?} is not within 1 of {expected:?}");
}

/// A triangle covering the window's lower-left half (below the diagonal from the upper-left to
/// the lower-right corner), counter-clockwise when `ccw`.
fn lower_left_triangle(ctx: &mut Context, ccw: bool, color: [f32; 3]) {
    unsafe {
        dispatch::glColor3f(ctx, color[0], color[1], color[2]);
        dispatch::glBegin(ctx, gl::GL_TRIANGLES);
        let v = if ccw { [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0)] } else { [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0)] };
        for (x, y) in v {
            dispatch::glVertex2f(ctx, x, y);
        }
        dispatch::glEnd(ctx);
    }
}

#[test]
fn clear_and_draw_read_back_in_gl_orientation() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 1.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
    }
    assert_eq!(pixel(&mut ctx, 5, 5), [0, 0, 255, 255]);
    lower_left_triangle(&mut ctx, true, [1.0, 0.0, 0.0]);
    // Window y grows upwards: (2, 2) is inside the lower-left triangle, (60, 60) is not.
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 0, 0, 255]);
    assert_eq!(pixel(&mut ctx, 60, 60), [0, 0, 255, 255]);
    assert_eq!(pixel(&mut ctx, 60, 2), [255, 0, 0, 255], "lower-right corner below the diagonal");
    assert_eq!(pixel(&mut ctx, 2, 60), [255, 0, 0, 255], "upper-left corner below the diagonal");
    // Reading again does not draw the frame twice, and the frame goes on after a read.
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_BLEND);
        dispatch::glBlendFunc(&mut ctx, gl::GL_ONE, gl::GL_ONE);
    }
    lower_left_triangle(&mut ctx, true, [0.0, 0.5, 0.0]);
    // 0.5 × 255 = 127.5 converts to 127 or 128 (OpenGL 1.5 section 2.14.9 leaves the
    // rounding to the implementation: lavapipe gives 128, NVIDIA 127).
    assert_near(pixel(&mut ctx, 2, 2), [255, 128, 0, 255]);
    assert_near(pixel(&mut ctx, 2, 2), [255, 128, 0, 255]);
    // Geometry merged into the draw already rendered is rendered once, after the read.
    lower_left_triangle(&mut ctx, true, [0.0, 0.25, 0.0]);
    assert_near(pixel(&mut ctx, 2, 2), [255, 192, 0, 255]);
    ctx.end_frame();
    // The next frame starts from the previous image (no clear): still there.
    assert_near(pixel(&mut ctx, 2, 2), [255, 192, 0, 255]);
}

#[test]
fn culling_keeps_gl_front_faces() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 0.0, 0.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_CULL_FACE);
    }
    // Back faces culled: the counter-clockwise triangle is front-facing and drawn.
    lower_left_triangle(&mut ctx, true, [0.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 2, 2), [0, 255, 0, 255]);
    lower_left_triangle(&mut ctx, false, [1.0, 0.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 2, 2), [0, 255, 0, 255], "the clockwise triangle is a back face");
    unsafe { dispatch::glFrontFace(&mut ctx, gl::GL_CW) };
    lower_left_triangle(&mut ctx, false, [1.0, 0.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 0, 0, 255], "with glFrontFace(GL_CW) it is a front face");
}

#[test]
fn depth_and_stencil_read_back() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearDepth(&mut ctx, 0.5);
        dispatch::glClearStencil(&mut ctx, 7);
        dispatch::glScissor(&mut ctx, 0, 0, 16, 16);
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glClear(&mut ctx, gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT);
        let mut depth = [0f32; 2];
        dispatch::glReadPixels(&mut ctx, 15, 0, 2, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depth.as_mut_ptr().cast());
        assert!((depth[0] - 0.5).abs() < 1e-6, "inside the scissor box: {}", depth[0]);
        assert_eq!(depth[1], 1.0, "outside: the initial depth");
        let mut stencil = [0u8; 2];
        dispatch::glReadPixels(&mut ctx, 15, 0, 2, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_BYTE, stencil.as_mut_ptr().cast());
        assert_eq!(stencil, [7, 0]);
    }
}

/// Draws a window-filling quad with texture coordinates (0, 0) at the lower left and (1, 1)
/// at the upper right.
fn textured_quad(ctx: &mut Context) {
    unsafe {
        dispatch::glColor3f(ctx, 1.0, 1.0, 1.0);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            dispatch::glTexCoord2f(ctx, x, y);
            dispatch::glVertex2f(ctx, x * 2.0 - 1.0, y * 2.0 - 1.0);
        }
        dispatch::glEnd(ctx);
    }
}

#[test]
fn textures_follow_their_versions_with_gl_rows() {
    let mut ctx = context();
    // 2×2 RGB texture, rows bottom to top: red green / blue white.
    let texels: [u8; 12] = [255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255];
    unsafe {
        dispatch::glPixelStorei(&mut ctx, gl::GL_UNPACK_ALIGNMENT, 1);
        dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGB as i32, 2, 2, 0, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
    }
    textured_quad(&mut ctx);
    assert_eq!(pixel(&mut ctx, 5, 5), [255, 0, 0, 255], "texel row 0 is at the bottom");
    assert_eq!(pixel(&mut ctx, 60, 5), [0, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 5, 60), [0, 0, 255, 255]);
    assert_eq!(pixel(&mut ctx, 60, 60), [255, 255, 255, 255]);
    // A new version (glTexSubImage2D) in the same frame: later draws see it.
    let yellow: [u8; 3] = [255, 255, 0];
    unsafe { dispatch::glTexSubImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, 0, 0, 1, 1, gl::GL_RGB, gl::GL_UNSIGNED_BYTE, yellow.as_ptr().cast()) };
    textured_quad(&mut ctx);
    assert_eq!(pixel(&mut ctx, 5, 5), [255, 255, 0, 255]);
    assert_eq!(pixel(&mut ctx, 60, 5), [0, 255, 0, 255]);
}


#[test]
fn glrt_dump_writes_each_presented_frame_top_down() {
    let dir = std::env::temp_dir().join(format!("glrt-dump-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut ctx = context_with(|| {
        let mut renderer = Renderer::without_outputs()?;
        renderer.add_output(Box::new(glrt::render::raster::dump::Dump::new(dir.clone(), 0).expect("a dump directory")));
        Ok(renderer)
    });
    for frame in 0..2 {
        unsafe {
            dispatch::glClearColor(&mut ctx, 0.0, 0.0, frame as f32, 1.0);
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            // The lower half of the window red.
            dispatch::glColor3f(&mut ctx, 1.0, 0.0, 0.0);
            dispatch::glRectf(&mut ctx, -1.0, -1.0, 1.0, 0.0);
        }
        ctx.end_frame();
    }
    drop(ctx);
    for (frame, blue) in [(0, 0), (1, 255)] {
        let file = std::fs::File::open(dir.join(format!("frame-{frame:05}.png"))).expect("the frame's PNG");
        let mut reader = png::Decoder::new(std::io::BufReader::new(file)).read_info().unwrap();
        let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut rgb).unwrap();
        assert_eq!((info.width, info.height, info.color_type), (64, 64, png::ColorType::Rgb));
        assert_eq!(rgb[..3], [0, 0, blue], "the top row shows the clear colour");
        assert_eq!(rgb[rgb.len() - 3..], [255, 0, 0], "the bottom row is red");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A window-filling quad at NDC depth `z` in `color`.
fn quad_at(ctx: &mut Context, z: f32, color: [f32; 3]) {
    unsafe {
        dispatch::glColor3f(ctx, color[0], color[1], color[2]);
        dispatch::glBegin(ctx, gl::GL_QUADS);
        for (x, y) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

#[test]
fn depth_stencil_scissor_and_masks_apply_to_draws() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.0, 0.0, 0.0, 0.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT | gl::GL_STENCIL_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_LESS);
    }
    quad_at(&mut ctx, 0.0, [1.0, 0.0, 0.0]);
    quad_at(&mut ctx, 0.5, [0.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 30, 30), [255, 0, 0, 255], "the farther quad fails GL_LESS");
    let mut depth = [0f32; 1];
    unsafe { dispatch::glReadPixels(&mut ctx, 30, 30, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depth.as_mut_ptr().cast()) };
    assert!((depth[0] - 0.5).abs() < 1e-4, "NDC z 0 is window depth 0.5: {}", depth[0]);
    unsafe {
        // Stencil: write 1 inside the scissor box (left half), then draw where stencil == 1.
        dispatch::glDisable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glEnable(&mut ctx, gl::GL_STENCIL_TEST);
        dispatch::glEnable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glScissor(&mut ctx, 0, 0, 32, 64);
        dispatch::glStencilFunc(&mut ctx, gl::GL_ALWAYS, 1, 0xff);
        dispatch::glStencilOp(&mut ctx, gl::GL_KEEP, gl::GL_KEEP, gl::GL_REPLACE);
        dispatch::glColorMask(&mut ctx, 0, 0, 0, 0);
    }
    quad_at(&mut ctx, 0.0, [1.0, 1.0, 1.0]);
    assert_eq!(pixel(&mut ctx, 10, 30), [255, 0, 0, 255], "colour writes masked");
    unsafe {
        dispatch::glDisable(&mut ctx, gl::GL_SCISSOR_TEST);
        dispatch::glColorMask(&mut ctx, 0, 1, 0, 0);
        dispatch::glStencilFunc(&mut ctx, gl::GL_EQUAL, 1, 0xff);
        dispatch::glStencilOp(&mut ctx, gl::GL_KEEP, gl::GL_KEEP, gl::GL_KEEP);
    }
    quad_at(&mut ctx, 0.0, [0.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 10, 30), [255, 255, 0, 255], "stencil passes, only green written");
    assert_eq!(pixel(&mut ctx, 50, 30), [255, 0, 0, 255], "stencil fails outside the scissored area");
    let mut stencil = [0u8; 2];
    unsafe { dispatch::glReadPixels(&mut ctx, 31, 30, 2, 1, gl::GL_STENCIL_INDEX, gl::GL_UNSIGNED_BYTE, stencil.as_mut_ptr().cast()) };
    assert_eq!(stencil, [1, 0]);
}

#[test]
fn logic_op_viewport_and_depth_range() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 1.0, 0.0, 1.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_COLOR_LOGIC_OP);
        dispatch::glLogicOp(&mut ctx, gl::GL_XOR);
    }
    quad_at(&mut ctx, 0.0, [1.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 30, 30), [0, 255, 255, 0], "magenta XOR yellow (alpha 1 XOR 1)");
    unsafe {
        dispatch::glDisable(&mut ctx, gl::GL_COLOR_LOGIC_OP);
        // The lower-left quarter of the window, depth mapped to [0.25, 0.75].
        dispatch::glViewport(&mut ctx, 0, 0, 32, 32);
        dispatch::glDepthRange(&mut ctx, 0.25, 0.75);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_ALWAYS);
    }
    quad_at(&mut ctx, 1.0, [0.0, 0.0, 1.0]);
    assert_eq!(pixel(&mut ctx, 5, 5), [0, 0, 255, 255]);
    assert_eq!(pixel(&mut ctx, 40, 5), [0, 255, 255, 0], "outside the viewport");
    assert_eq!(pixel(&mut ctx, 5, 40), [0, 255, 255, 0], "outside the viewport (above)");
    let mut depth = [0f32; 1];
    unsafe { dispatch::glReadPixels(&mut ctx, 5, 5, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depth.as_mut_ptr().cast()) };
    assert!((depth[0] - 0.75).abs() < 1e-4, "NDC z 1 is the far end of the depth range: {}", depth[0]);
}

#[test]
fn a_new_drawable_size_recreates_the_framebuffer() {
    let mut ctx = context();
    unsafe {
        dispatch::glClearColor(&mut ctx, 0.0, 1.0, 0.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
    }
    ctx.end_frame();
    ctx.bind_drawable(100, 20);
    unsafe {
        dispatch::glViewport(&mut ctx, 0, 0, 100, 20);
        dispatch::glClearColor(&mut ctx, 1.0, 0.0, 0.0, 1.0);
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
    }
    assert_eq!(pixel(&mut ctx, 99, 19), [255, 0, 0, 255], "the corner of the 100×20 drawable");
    let mut row = [[9u8; 4]; 2];
    unsafe { dispatch::glReadPixels(&mut ctx, 99, 0, 2, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, row.as_mut_ptr().cast()) };
    assert_eq!(row, [[255, 0, 0, 255], [0, 0, 0, 0]], "outside the window reads as 0");
}

#[test]
fn pipelines_and_textures_are_created_once_and_unused_textures_dropped() {
    use glrt::frame::FrameSink;
    // Frames recorded by translate, then given to a renderer directly to look at its caches.
    let (mut ctx, sink) = Context::with_recording();
    ctx.bind_drawable(SIZE, SIZE);
    let texels = [255u8; 4 * 4];
    for frame in 0..12 {
        unsafe {
            dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT);
            if frame < 2 {
                dispatch::glBindTexture(&mut ctx, gl::GL_TEXTURE_2D, 1 + frame);
                dispatch::glTexImage2D(&mut ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
                dispatch::glTexParameteri(&mut ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
                dispatch::glEnable(&mut ctx, gl::GL_TEXTURE_2D);
            } else {
                dispatch::glDisable(&mut ctx, gl::GL_TEXTURE_2D);
            }
        }
        textured_quad(&mut ctx);
        lower_left_triangle(&mut ctx, true, [1.0, 0.0, 0.0]);
        ctx.end_frame();
    }
    let frames = std::mem::take(&mut *sink.frames.lock());
    assert_eq!(frames.len(), 12);
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    let mut counts = Vec::new();
    for frame in frames {
        renderer.present(frame);
        counts.push((renderer.raster().pipeline_count(), renderer.raster().texture_count()));
    }
    // One pipeline for textured and one for untextured draws, created once.
    assert_eq!(counts[0].0, 1);
    assert_eq!(counts[2].0, 2);
    assert_eq!(counts[11].0, 2);
    // Textures 1 (used in frame 0) and 2 (frame 1) uploaded once each, each dropped once
    // eight more frames went by without it.
    assert_eq!(counts[1].1, 2);
    assert_eq!(counts[7].1, 2);
    assert_eq!(counts[8].1, 1);
    assert_eq!(counts[9].1, 0);
}

#[test]
fn idle_pipelines_past_the_cache_size_are_evicted() {
    use glrt::frame::FrameSink;
    use glrt::render::raster::pipelines::{CACHED_PIPELINES, IDLE_SUBMISSIONS};
    // Frames with a blend function of their own (as piglit's `gl-1.0-blend-func` draws them)
    // and a triangle drawn alike in every frame.
    let (mut ctx, sink) = Context::with_recording();
    ctx.bind_drawable(SIZE, SIZE);
    let src = [gl::GL_ZERO, gl::GL_ONE, gl::GL_DST_COLOR, gl::GL_ONE_MINUS_DST_COLOR, gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA, gl::GL_DST_ALPHA, gl::GL_ONE_MINUS_DST_ALPHA];
    let dst = [gl::GL_ZERO, gl::GL_ONE, gl::GL_SRC_COLOR, gl::GL_ONE_MINUS_SRC_COLOR, gl::GL_SRC_ALPHA, gl::GL_ONE_MINUS_SRC_ALPHA, gl::GL_DST_ALPHA, gl::GL_ONE_MINUS_DST_ALPHA];
    for (s, d) in src.iter().flat_map(|&s| dst.iter().map(move |&d| (s, d))) {
        unsafe {
            dispatch::glDisable(&mut ctx, gl::GL_BLEND);
            lower_left_triangle(&mut ctx, true, [1.0, 0.0, 0.0]);
            dispatch::glEnable(&mut ctx, gl::GL_BLEND);
            dispatch::glBlendFunc(&mut ctx, s, d);
            lower_left_triangle(&mut ctx, false, [0.0, 1.0, 0.0]);
        }
        ctx.end_frame();
    }
    let frames = std::mem::take(&mut *sink.frames.lock());
    assert_eq!(frames.len(), 64);
    let mut renderer = lavapipe::renderer_with(Renderer::without_outputs);
    let mut counts = Vec::new();
    for frame in frames {
        renderer.present(frame);
        counts.push(renderer.raster().pipeline_count());
    }
    // All kept up to CACHED_PIPELINES; past it, only those used in the last IDLE_SUBMISSIONS
    // submissions (one per frame here), the triangle's among them.
    assert_eq!(counts[CACHED_PIPELINES - 2], CACHED_PIPELINES);
    assert!(counts.iter().all(|&n| n <= CACHED_PIPELINES), "{counts:?}");
    assert_eq!(counts[CACHED_PIPELINES - 1], IDLE_SUBMISSIONS as usize, "{counts:?}");
    assert!(counts[63] < CACHED_PIPELINES, "{counts:?}");
}

#[test]
fn occlusion_queries_count_samples_that_pass() {
    let mut ctx = context();
    let mut bits = 0;
    unsafe { dispatch::glGetQueryiv(&mut ctx, gl::GL_SAMPLES_PASSED, gl::GL_QUERY_COUNTER_BITS, &mut bits) };
    assert_eq!(bits, 64);
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glBeginQuery(&mut ctx, gl::GL_SAMPLES_PASSED, 1);
    }
    lower_left_triangle(&mut ctx, true, [1.0, 0.0, 0.0]);
    quad_at(&mut ctx, -0.5, [0.0, 1.0, 0.0]);
    unsafe { dispatch::glEndQuery(&mut ctx, gl::GL_SAMPLES_PASSED) };
    // A read-back renders (and submits) the frame so far: the count survives it.
    assert_eq!(pixel(&mut ctx, 30, 30), [0, 255, 0, 255]);
    unsafe {
        // Behind everything drawn: no sample passes.
        dispatch::glBeginQuery(&mut ctx, gl::GL_SAMPLES_PASSED, 2);
    }
    quad_at(&mut ctx, 0.5, [0.0, 0.0, 1.0]);
    unsafe { dispatch::glEndQuery(&mut ctx, gl::GL_SAMPLES_PASSED) };
    let (mut first, mut second) = (0u32, 7u32);
    unsafe {
        dispatch::glGetQueryObjectuiv(&mut ctx, 1, gl::GL_QUERY_RESULT, &mut first);
        dispatch::glGetQueryObjectuiv(&mut ctx, 2, gl::GL_QUERY_RESULT, &mut second);
    }
    // The triangle covers the 2016 pixels whose centres lie below the diagonal (the 64 centres
    // on it go to the other side: the diagonal is its top-right edge), the quad all 4096.
    assert_eq!(first, 2016 + 4096);
    assert_eq!(second, 0);
}

#[test]
fn polygon_offset_moves_filled_polygons_in_depth() {
    let mut ctx = context();
    unsafe {
        dispatch::glClear(&mut ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glEnable(&mut ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthFunc(&mut ctx, gl::GL_LESS);
    }
    quad_at(&mut ctx, 0.0, [1.0, 0.0, 0.0]);
    quad_at(&mut ctx, 0.0, [0.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 30, 30), [255, 0, 0, 255], "a coplanar quad fails GL_LESS");
    unsafe {
        dispatch::glEnable(&mut ctx, gl::GL_POLYGON_OFFSET_FILL);
        dispatch::glPolygonOffset(&mut ctx, 0.0, -4.0);
    }
    quad_at(&mut ctx, 0.0, [0.0, 1.0, 0.0]);
    assert_eq!(pixel(&mut ctx, 30, 30), [0, 255, 0, 255], "pulled towards the viewer by 4 units");
    let mut depth = [0f32; 1];
    unsafe { dispatch::glReadPixels(&mut ctx, 30, 30, 1, 1, gl::GL_DEPTH_COMPONENT, gl::GL_FLOAT, depth.as_mut_ptr().cast()) };
    assert!(depth[0] < 0.5 && depth[0] > 0.49, "{}", depth[0]);
}

//! The Vulkan raster renderer on real GL calls, read back with `glReadPixels`: clears, draws,
//! the y orientation and front faces through the flipped viewport, depth and stencil reads.
//! Runs on Mesa lavapipe (forced through `VK_DRIVER_FILES` when its ICD file exists), at
//! 64×64 so it stays fast on a CPU.

use glrt::render::raster::renderer::Renderer;
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

const SIZE: i32 = 64;

/// A context drawing into a Vulkan renderer on lavapipe, with a 64×64 drawable.
fn context() -> Context {
    context_with(Renderer::new)
}

/// A context drawing into the renderer `make` creates (on lavapipe), with a 64×64 drawable.
fn context_with(make: impl FnOnce() -> Result<Renderer, glrt::render::raster::device::Error>) -> Context {
    let lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
    if std::path::Path::new(lavapipe).exists() {
        // Safety: set before any thread of this test binary loads Vulkan; every test sets the
        // same value.
        unsafe { std::env::set_var("VK_DRIVER_FILES", lavapipe) };
    }
    let renderer = make().expect("a Vulkan device (lavapipe)");
    let mut ctx = Context::new(ContextConfig { share: None, sink: Box::new(renderer) });
    ctx.bind_drawable(SIZE, SIZE);
    ctx
}

/// Reads the RGBA8 pixel at window (x, y).
fn pixel(ctx: &mut Context, x: i32, y: i32) -> [u8; 4] {
    let mut out = [0u8; 4];
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
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
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 128, 0, 255]);
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 128, 0, 255]);
    // Geometry merged into the draw already rendered is rendered once, after the read.
    lower_left_triangle(&mut ctx, true, [0.0, 0.25, 0.0]);
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 192, 0, 255]);
    ctx.end_frame();
    // The next frame starts from the previous image (no clear): still there.
    assert_eq!(pixel(&mut ctx, 2, 2), [255, 192, 0, 255]);
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
    let mut ctx = context_with(|| Renderer::with_dump(glrt::render::raster::dump::Dump::new(dir.clone())));
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

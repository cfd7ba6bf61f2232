//! Shared helpers of the tests that draw through the Vulkan renderer: the renderer on Mesa
//! lavapipe (when its ICD file exists; the machine's Vulkan driver otherwise), a context
//! drawing into it, a renderer shared with the test, a sink that classifies draws as the test
//! says, and pixel read-back; the frames of the whole-frame tests of ambient occlusion, fog
//! and the composite (a 90° camera, a wall facing it, the renderer that traces such a wall
//! noise-free).

#![allow(dead_code)]

pub mod probe;

use std::sync::{Arc, Mutex};

use glrt::frame::Frame;
use glrt::frame::pixels::PixelBuffer;
use glrt::render::frame::Renderer;
use glrt::render::raster::device::Error;
use glrt::render::trace::settings::{Settings, Tonemap};
use glrt::frame::{FrameSink, Target};
use glrt::translate::context::ContextConfig;
use glrt::translate::{Context, dispatch, gl};

/// The renderer `make` creates, on lavapipe when its ICD file exists.
pub fn renderer_with(make: impl FnOnce() -> Result<Renderer, Error>) -> Renderer {
    select(make)
}

/// What `make` creates (a renderer, a device) with Vulkan on lavapipe when its ICD file exists.
pub fn select<T>(make: impl FnOnce() -> Result<T, Error>) -> T {
    static SELECT: std::sync::Once = std::sync::Once::new();
    SELECT.call_once(|| {
        let lavapipe = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";
        if std::path::Path::new(lavapipe).exists() {
            // Safety: set once, by the first test that makes a device, before any thread of
            // this binary loads Vulkan (the others wait here): no thread reads the environment
            // in C (the Vulkan loader, a driver) while it changes.
            unsafe { std::env::set_var("VK_DRIVER_FILES", lavapipe) };
        }
    });
    make().expect("a Vulkan device (lavapipe)")
}

/// A renderer shared between a context and the test (which reads its statistics).
pub struct Shared(pub Arc<Mutex<Renderer>>);

impl FrameSink for Shared {
    fn present(&mut self, frame: Frame) {
        self.0.lock().unwrap().present(frame);
    }

    fn set_target(&mut self, target: Target) {
        self.0.lock().unwrap().set_target(target);
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        self.0.lock().unwrap().read_pixels(frame, buffer, rect)
    }
}

/// A sink that edits every frame before `sink` takes it (presented or read back): the test
/// states what hash tracking (`translate::classify`) concludes about its draws (layers, how
/// surfaces are lit), so the renderer is tested on the frames it will get.
pub struct Classified<S> {
    /// The sink frames go to.
    pub sink: S,
    /// The edit.
    pub edit: Box<dyn Fn(&mut Frame) + Send>,
}

impl<S: FrameSink> FrameSink for Classified<S> {
    fn present(&mut self, mut frame: Frame) {
        (self.edit)(&mut frame);
        self.sink.present(frame);
    }

    fn set_target(&mut self, target: Target) {
        self.sink.set_target(target);
    }

    fn read_pixels(&mut self, frame: &Frame, buffer: PixelBuffer, rect: [i32; 4]) -> Option<Vec<[f32; 4]>> {
        let mut frame = frame.clone();
        (self.edit)(&mut frame);
        self.sink.read_pixels(&frame, buffer, rect)
    }
}

/// A context drawing into `sink` (a renderer, a [`Shared`] one) through [`Classified`] with
/// `edit`, not yet bound to a drawable.
pub fn classified_context_on(sink: impl FrameSink + 'static, edit: impl Fn(&mut Frame) + Send + 'static) -> Context {
    Context::new(ContextConfig { share: None, sink: Box::new(Classified { sink, edit: Box::new(edit) }) })
}

/// A context drawing into `renderer`, not yet bound to a drawable.
pub fn context_on(renderer: Renderer) -> Context {
    Context::new(ContextConfig { share: None, sink: Box::new(renderer) })
}

/// A context drawing into a new renderer, with a `size` × `size` drawable.
pub fn context(size: i32) -> Context {
    let mut ctx = context_on(renderer_with(Renderer::new));
    ctx.bind_drawable(size, size);
    ctx
}

/// Reads the RGBA8 pixel at window (x, y) of the read buffer.
pub fn pixel(ctx: &mut Context, x: i32, y: i32) -> [u8; 4] {
    let mut out = [0u8; 4];
    unsafe { dispatch::glReadPixels(ctx, x, y, 1, 1, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

/// A nearest-filtered 2 × 2 RGBA texture of `texels`, bound to `GL_TEXTURE_2D`.
pub fn texture_2x2(ctx: &mut Context, texels: &[u8; 16]) -> u32 {
    let mut name = 0;
    // Safety: `name` and `texels` outlive the calls; the sizes match the arguments.
    unsafe {
        dispatch::glGenTextures(ctx, 1, &mut name);
        dispatch::glBindTexture(ctx, gl::GL_TEXTURE_2D, name);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MIN_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexParameteri(ctx, gl::GL_TEXTURE_2D, gl::GL_TEXTURE_MAG_FILTER, gl::GL_NEAREST as i32);
        dispatch::glTexImage2D(ctx, gl::GL_TEXTURE_2D, 0, gl::GL_RGBA as i32, 2, 2, 0, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, texels.as_ptr().cast());
    }
    name
}

/// Binds a `size`² drawable with a 60° perspective camera at the origin looking down −z
/// (near 0.1, far 100) and an identity modelview.
pub fn perspective_60(ctx: &mut Context, size: i32) {
    ctx.bind_drawable(size, size);
    // Safety: plain state calls on a current context.
    unsafe {
        dispatch::glViewport(ctx, 0, 0, size, size);
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        let h = 0.1 * (30f64).to_radians().tan();
        dispatch::glFrustum(ctx, -h, h, -h, h, 0.1, 100.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(ctx);
    }
}

/// A renderer without outputs, path traced when `traced` with settings that trace a lit wall
/// noise-free and as the raster path draws it: one sample through each pixel centre, no
/// bounce, directional lights of no angular size, the clamped tone curve at exposure 0.
pub fn exact_renderer(traced: bool) -> Renderer {
    let mut renderer = renderer_with(Renderer::without_outputs);
    if traced {
        let settings = Settings { spp: 1, bounces: 0, sun_angle: 0.0, tonemap: Tonemap::Clamp, exposure: 0.0, ..Settings::default() };
        renderer.enable_tracing(settings).expect("the tracer's pipelines");
    }
    renderer
}

/// Starts a frame of the `size`² drawable: the viewport, colour cleared to black and depth to
/// far, a 90° camera at the origin looking down −z (`glFrustum(−0.1, 0.1, −0.1, 0.1, 0.1,
/// 100)`) and the identity modelview, which stays the current matrix.
pub fn begin_frame_90(ctx: &mut Context, size: i32) {
    // Safety: plain state calls on a current context.
    unsafe {
        dispatch::glViewport(ctx, 0, 0, size, size);
        dispatch::glClearColor(ctx, 0.0, 0.0, 0.0, 1.0);
        dispatch::glClear(ctx, gl::GL_COLOR_BUFFER_BIT | gl::GL_DEPTH_BUFFER_BIT);
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(ctx);
        dispatch::glFrustum(ctx, -0.1, 0.1, -0.1, 0.1, 0.1, 100.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(ctx);
    }
}

/// A quad facing the eye (normal +z) at eye depth `z`, spanning x in `xs` and y in [−10, 10].
pub fn wall(ctx: &mut Context, xs: [f32; 2], z: f32) {
    // Safety: one primitive between glBegin and glEnd on a current context.
    unsafe {
        dispatch::glBegin(ctx, gl::GL_QUADS);
        dispatch::glNormal3f(ctx, 0.0, 0.0, 1.0);
        for [x, y] in [[xs[0], -10.0], [xs[1], -10.0], [xs[1], 10.0], [xs[0], 10.0]] {
            dispatch::glVertex3f(ctx, x, y, z);
        }
        dispatch::glEnd(ctx);
    }
}

/// Draws the wall at eye depth −3 across the view, lit: a white directional light at normal
/// incidence on a diffuse 0.6 material with no ambient light (153 of 255 where traced or
/// rasterized). Depth test and writes are on afterwards, lighting off.
pub fn lit_wall(ctx: &mut Context) {
    let black = [0.0f32, 0.0, 0.0, 1.0];
    // Safety: plain state calls on a current context; the arrays outlive them.
    unsafe {
        dispatch::glEnable(ctx, gl::GL_DEPTH_TEST);
        dispatch::glDepthMask(ctx, gl::GL_TRUE);
        dispatch::glEnable(ctx, gl::GL_LIGHTING);
        dispatch::glEnable(ctx, gl::GL_LIGHT0);
        dispatch::glLightfv(ctx, gl::GL_LIGHT0, gl::GL_POSITION, [0.0f32, 0.0, 1.0, 0.0].as_ptr());
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, [0.6f32, 0.6, 0.6, 1.0].as_ptr());
        dispatch::glLightModelfv(ctx, gl::GL_LIGHT_MODEL_AMBIENT, black.as_ptr());
        dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_AMBIENT, black.as_ptr());
    }
    wall(ctx, [-10.0, 10.0], -3.0);
    // Safety: as above.
    unsafe { dispatch::glDisable(ctx, gl::GL_LIGHTING) };
}

/// Sets up drawing in window coordinates of the `size`² drawable, as games draw their HUD:
/// depth test off, `glOrtho(0, size, 0, size, −1, 1)`, identity modelview (current).
pub fn window_ortho(ctx: &mut Context, size: i32) {
    // Safety: plain state calls on a current context.
    unsafe {
        dispatch::glDisable(ctx, gl::GL_DEPTH_TEST);
        dispatch::glMatrixMode(ctx, gl::GL_PROJECTION);
        dispatch::glLoadIdentity(ctx);
        dispatch::glOrtho(ctx, 0.0, size as f64, 0.0, size as f64, -1.0, 1.0);
        dispatch::glMatrixMode(ctx, gl::GL_MODELVIEW);
        dispatch::glLoadIdentity(ctx);
    }
}

/// The `size`² drawable's RGBA8 image (rows bottom to top), read from the read buffer.
pub fn read_rgba(ctx: &mut Context, size: i32) -> Vec<[u8; 4]> {
    let mut out = vec![[0u8; 4]; (size * size) as usize];
    // Safety: `out` holds `size`² RGBA8 pixels.
    unsafe { dispatch::glReadPixels(ctx, 0, 0, size, size, gl::GL_RGBA, gl::GL_UNSIGNED_BYTE, out.as_mut_ptr().cast()) };
    out
}

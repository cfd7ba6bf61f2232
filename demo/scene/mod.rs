//! The demo's scene, one part per module, drawn in the order an old engine would: sky,
//! static room and pillars, the door, the animated mesh, translucent glass, then the HUD.
//! Everything moves with the frame number (60 steps per second of scene time), never the wall
//! clock, so every run issues the same calls.

mod door;
mod glass;
mod hud;
mod mesh;
mod pillars;
mod room;
mod shapes;
mod sky;
pub mod textures;

use crate::font::Font;
use crate::gl::*;

/// Scene time of a frame, in seconds.
fn time(frame: u64) -> f32 {
    frame as f32 / 60.0
}

/// GL objects and client arrays of the scene.
pub struct Scene {
    textures: textures::Textures,
    pillars: pillars::Pillars,
    mesh: mesh::Mesh,
    font: Font,
    width: i32,
    height: i32,
}

impl Scene {
    /// Uploads textures, compiles the display list and sets the state that never changes.
    pub fn new(api: &GlApi, width: i32, height: i32) -> Self {
        let gl = &api.gl;
        let textures = textures::Textures::new(gl);
        let pillars = pillars::Pillars::new(gl, &textures);
        let fog = [0.55f32, 0.6, 0.68, 1.0];
        let ambient = [0.22f32, 0.22, 0.25, 1.0];
        // Safety: a context is current; arrays have 4 floats.
        unsafe {
            gl.glViewport(0, 0, width, height);
            gl.glClearColor(0.0, 0.0, 0.0, 1.0);
            gl.glEnable(GL_DEPTH_TEST);
            gl.glDepthFunc(GL_LEQUAL);
            gl.glShadeModel(GL_SMOOTH);
            gl.glHint(GL_PERSPECTIVE_CORRECTION_HINT, GL_NICEST);
            gl.glEnable(GL_TEXTURE_2D);
            gl.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE as GLint);
            gl.glEnable(GL_LIGHTING);
            gl.glEnable(GL_NORMALIZE);
            gl.glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient.as_ptr());
            gl.glEnable(GL_LIGHT0);
            gl.glEnable(GL_LIGHT1);
            gl.glEnable(GL_FOG);
            gl.glFogi(GL_FOG_MODE, GL_LINEAR as GLint);
            gl.glFogf(GL_FOG_START, 8.0);
            gl.glFogf(GL_FOG_END, 45.0);
            gl.glFogfv(GL_FOG_COLOR, fog.as_ptr());
        }
        Self { textures, pillars, mesh: mesh::Mesh::new(), font: Font::new(), width, height }
    }

    /// Draws frame `frame` (without presenting it).
    pub fn draw(&mut self, api: &GlApi, frame: u64) {
        let gl = &api.gl;
        let t = time(frame);
        // Safety: a context is current.
        unsafe {
            gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            gl.glMatrixMode(GL_PROJECTION);
            gl.glLoadIdentity();
            let near = 0.1;
            let top = near * (35.0f64).to_radians().tan();
            let aspect = self.width as f64 / self.height.max(1) as f64;
            gl.glFrustum(-top * aspect, top * aspect, -top, top, near, 100.0);
            gl.glMatrixMode(GL_MODELVIEW);
            gl.glLoadIdentity();
            // The camera looks down the room, turning slowly from side to side.
            gl.glRotatef(6.0, 1.0, 0.0, 0.0);
            gl.glRotatef(-18.0 * (t * 0.35).sin(), 0.0, 1.0, 0.0);
        }
        sky::draw(gl);
        // Safety: a context is current.
        unsafe { gl.glTranslatef(0.0, -2.2, -8.5) };
        place_lights(gl, t);
        room::draw(gl, api.multitexture.as_ref(), &self.textures);
        self.pillars.draw(gl);
        door::draw(gl, &self.textures, t);
        self.mesh.update(t);
        self.mesh.draw(gl, api.lock_arrays.as_ref(), &self.textures);
        glass::draw(gl);
        let text = hud::lines(frame, api.multitexture.is_some(), api.lock_arrays.is_some());
        hud::draw(gl, &self.font, self.width, self.height, &text);
    }

    /// Deletes the GL objects.
    pub fn delete(&self, api: &GlApi) {
        self.pillars.delete(&api.gl);
        self.textures.delete(&api.gl);
    }
}

/// Specifies the lights in world space (the modelview holds the view): a warm positional
/// lamp circling under the ceiling and a dim cool directional light from above.
fn place_lights(gl: &Gl, t: f32) {
    let lamp = [3.0 * (t * 0.5).sin(), 4.2, -2.0 + 3.0 * (t * 0.5).cos(), 1.0f32];
    let warm = [1.0f32, 0.9, 0.75, 1.0];
    let sun = [0.3f32, 1.0, 0.5, 0.0];
    let cool = [0.3f32, 0.33, 0.42, 1.0];
    // Safety: a context is current; arrays have 4 floats.
    unsafe {
        gl.glLightfv(GL_LIGHT0, GL_POSITION, lamp.as_ptr());
        gl.glLightfv(GL_LIGHT0, GL_DIFFUSE, warm.as_ptr());
        gl.glLightfv(GL_LIGHT0, GL_SPECULAR, warm.as_ptr());
        gl.glLightf(GL_LIGHT0, GL_CONSTANT_ATTENUATION, 0.5);
        gl.glLightf(GL_LIGHT0, GL_LINEAR_ATTENUATION, 0.06);
        gl.glLightfv(GL_LIGHT1, GL_POSITION, sun.as_ptr());
        gl.glLightfv(GL_LIGHT1, GL_DIFFUSE, cool.as_ptr());
    }
}

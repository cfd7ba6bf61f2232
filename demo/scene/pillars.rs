//! Four stone pillars, compiled into a display list once and called every frame (static
//! geometry the way Quake-era engines stored it). The list holds its texture binding and
//! material, and one `glBegin`/`glEnd` per pillar.

use super::shapes::cuboid;
use super::textures::Textures;
use crate::gl::*;

/// Pillar centres (x, z); each is 0.8 m square and floor to ceiling.
const PLACES: [(f32, f32); 4] = [(-5.0, -6.0), (5.0, -6.0), (-5.0, 2.0), (5.0, 2.0)];
const HALF_SIZE: f32 = 0.4;

/// The compiled pillars.
pub struct Pillars {
    list: GLuint,
}

impl Pillars {
    /// Compiles the display list.
    pub fn new(gl: &Gl, textures: &Textures) -> Self {
        let grey = [0.8f32, 0.8, 0.8, 1.0];
        // Safety: a context is current; the material array has 4 floats.
        unsafe {
            let list = gl.glGenLists(1);
            gl.glNewList(list, GL_COMPILE);
            gl.glBindTexture(GL_TEXTURE_2D, textures.stone);
            gl.glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, grey.as_ptr());
            for (x, z) in PLACES {
                gl.glBegin(GL_QUADS);
                let (min, max) = (
                    [x - HALF_SIZE, 0.0, z - HALF_SIZE],
                    [x + HALF_SIZE, super::room::HEIGHT, z + HALF_SIZE],
                );
                cuboid(gl, min, max);
                gl.glEnd();
            }
            gl.glEndList();
            Self { list }
        }
    }

    /// Calls the list.
    pub fn draw(&self, gl: &Gl) {
        // Safety: a context is current; the list exists.
        unsafe { gl.glCallList(self.list) }
    }

    /// Deletes the list.
    pub fn delete(&self, gl: &Gl) {
        // Safety: a context is current.
        unsafe { gl.glDeleteLists(self.list, 1) }
    }
}

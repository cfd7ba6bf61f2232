//! The door in the back wall: the same box every frame in immediate mode, swinging on its
//! hinge under a rotation that changes with the frame number (movable geometry).

use super::room::{DOOR_HEIGHT, DOOR_X, HALF_DEPTH};
use super::shapes::cuboid;
use super::textures::Textures;
use crate::gl::*;

/// Door thickness in metres.
const THICKNESS: f32 = 0.1;

/// Opening angle in degrees at `time` seconds: swings between closed and 80° open.
pub fn angle(time: f32) -> f32 {
    40.0 * (1.0 - (time * 0.8).cos())
}

/// Draws the door (one `glBegin`/`glEnd`).
pub fn draw(gl: &Gl, textures: &Textures, time: f32) {
    let wood = [1.0f32, 1.0, 1.0, 1.0];
    // Safety: a context is current; the material array has 4 floats.
    unsafe {
        gl.glBindTexture(GL_TEXTURE_2D, textures.wood);
        gl.glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, wood.as_ptr());
        gl.glPushMatrix();
        gl.glTranslatef(DOOR_X.0, 0.0, -HALF_DEPTH);
        // A negative angle about +y turns +x towards +z: the door opens into the room.
        gl.glRotatef(-angle(time), 0.0, 1.0, 0.0);
        gl.glBegin(GL_QUADS);
        cuboid(gl, [0.0, 0.0, 0.0], [DOOR_X.1 - DOOR_X.0, DOOR_HEIGHT, THICKNESS]);
        gl.glEnd();
        gl.glPopMatrix();
    }
}

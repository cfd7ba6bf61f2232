//! The static room, drawn in immediate mode every frame: floor, ceiling and four walls,
//! tessellated in 1 m cells. The back wall has a window (glazed by `glass`) and a doorway
//! (closed by `door`), through which the sky shows. With `GL_ARB_multitexture` a lightmap on
//! unit 1 darkens the corners.

use super::shapes::{Grid, TexCoords, grid};
use super::textures::Textures;
use crate::gl::*;

/// Half width (x), height (y) and half depth (z) of the room, in metres.
pub const HALF_WIDTH: f32 = 8.0;
pub const HEIGHT: f32 = 5.0;
pub const HALF_DEPTH: f32 = 10.0;

/// The window opening in the back wall: x range and y range.
pub const WINDOW_X: (f32, f32) = (-3.0, 3.0);
pub const WINDOW_Y: (f32, f32) = (2.0, 4.0);
/// The doorway in the back wall: x range and height.
pub const DOOR_X: (f32, f32) = (4.0, 6.0);
pub const DOOR_HEIGHT: f32 = 3.0;

/// Draws the room (three `glBegin`/`glEnd` blocks: floor, ceiling, walls).
pub fn draw(gl: &Gl, mt: Option<&Multitexture>, textures: &Textures) {
    let (w, h, d) = (HALF_WIDTH, HEIGHT, HALF_DEPTH);
    let tex = match mt {
        Some(mt) => TexCoords::WithLightmap(mt),
        None => TexCoords::Single,
    };
    let white = [0.9f32, 0.9, 0.9, 1.0];
    // Safety: a context is current; the material array has 4 floats.
    unsafe {
        gl.glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, white.as_ptr());
        if let Some(mt) = mt {
            mt.glActiveTextureARB(GL_TEXTURE1_ARB);
            gl.glEnable(GL_TEXTURE_2D);
            gl.glBindTexture(GL_TEXTURE_2D, textures.lightmap);
            gl.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE as GLint);
            mt.glActiveTextureARB(GL_TEXTURE0_ARB);
        }
        gl.glBindTexture(GL_TEXTURE_2D, textures.checker);
        gl.glBegin(GL_QUADS);
        let floor = Grid {
            origin: [-w, 0.0, d],
            u: [2.0 * w, 0.0, 0.0],
            v: [0.0, 0.0, -2.0 * d],
            nu: 16,
            nv: 20,
        };
        grid(gl, &tex, &floor, |_, _| false);
        gl.glEnd();

        gl.glBindTexture(GL_TEXTURE_2D, textures.brick);
        gl.glBegin(GL_QUADS);
        let ceiling = Grid {
            origin: [-w, h, -d],
            u: [2.0 * w, 0.0, 0.0],
            v: [0.0, 0.0, 2.0 * d],
            nu: 16,
            nv: 20,
        };
        grid(gl, &tex, &ceiling, |_, _| false);
        gl.glEnd();

        gl.glBegin(GL_QUADS);
        let up = [0.0, h, 0.0];
        let back = Grid { origin: [-w, 0.0, -d], u: [2.0 * w, 0.0, 0.0], v: up, nu: 16, nv: 5 };
        grid(gl, &tex, &back, |a, b| {
            let x = a - w;
            let window = x > WINDOW_X.0 && x < WINDOW_X.1 && b > WINDOW_Y.0 && b < WINDOW_Y.1;
            let door = x > DOOR_X.0 && x < DOOR_X.1 && b < DOOR_HEIGHT;
            window || door
        });
        let front = Grid { origin: [w, 0.0, d], u: [-2.0 * w, 0.0, 0.0], v: up, nu: 16, nv: 5 };
        grid(gl, &tex, &front, |_, _| false);
        let left = Grid { origin: [-w, 0.0, d], u: [0.0, 0.0, -2.0 * d], v: up, nu: 20, nv: 5 };
        grid(gl, &tex, &left, |_, _| false);
        let right = Grid { origin: [w, 0.0, -d], u: [0.0, 0.0, 2.0 * d], v: up, nu: 20, nv: 5 };
        grid(gl, &tex, &right, |_, _| false);
        gl.glEnd();

        if let Some(mt) = mt {
            mt.glActiveTextureARB(GL_TEXTURE1_ARB);
            gl.glDisable(GL_TEXTURE_2D);
            mt.glActiveTextureARB(GL_TEXTURE0_ARB);
        }
    }
}

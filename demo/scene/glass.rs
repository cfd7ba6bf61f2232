//! Translucent glass: the pane in the back wall's window and a free-standing green screen,
//! blended with `glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA)` after the opaque scene,
//! depth-tested but without depth writes, unlit and untextured.

use super::room::{HALF_DEPTH, WINDOW_X, WINDOW_Y};
use crate::gl::*;

/// Draws both panes (one `glBegin`/`glEnd`); restores blending, depth writes, lighting and
/// texturing.
pub fn draw(gl: &Gl) {
    let z = -HALF_DEPTH + 0.02;
    // Safety: a context is current.
    unsafe {
        gl.glDisable(GL_LIGHTING);
        gl.glDisable(GL_TEXTURE_2D);
        gl.glEnable(GL_BLEND);
        gl.glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        gl.glDepthMask(GL_FALSE);
        gl.glBegin(GL_QUADS);
        gl.glColor4f(0.55, 0.75, 0.95, 0.3);
        gl.glVertex3f(WINDOW_X.0, WINDOW_Y.0, z);
        gl.glVertex3f(WINDOW_X.1, WINDOW_Y.0, z);
        gl.glVertex3f(WINDOW_X.1, WINDOW_Y.1, z);
        gl.glVertex3f(WINDOW_X.0, WINDOW_Y.1, z);
        gl.glColor4f(0.3, 0.9, 0.4, 0.35);
        gl.glVertex3f(-6.5, 0.0, -1.0);
        gl.glVertex3f(-2.5, 0.0, 0.5);
        gl.glVertex3f(-2.5, 2.6, 0.5);
        gl.glVertex3f(-6.5, 2.6, -1.0);
        gl.glEnd();
        gl.glDepthMask(GL_TRUE);
        gl.glDisable(GL_BLEND);
        gl.glEnable(GL_TEXTURE_2D);
        gl.glEnable(GL_LIGHTING);
    }
}

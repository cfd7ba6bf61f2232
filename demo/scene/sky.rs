//! The sky: a large gradient box centred on the eye (view rotation only), drawn first with
//! depth test and depth writes off so that everything else covers it. It shows through the
//! window and the doorway.

use crate::gl::*;

/// Half size of the box; inside the far plane (its corners are at 50·√3 < 100).
const EXTENT: f32 = 50.0;
/// Colours at the zenith, the horizon and the nadir.
const ZENITH: [f32; 3] = [0.12, 0.28, 0.68];
const HORIZON: [f32; 3] = [0.78, 0.86, 0.95];
const NADIR: [f32; 3] = [0.35, 0.38, 0.42];

/// Draws the sky (one `glBegin`/`glEnd`, 10 quads) with the current modelview, which must
/// hold the view rotation only. Restores depth state, lighting, texturing and fog.
pub fn draw(gl: &Gl) {
    let e = EXTENT;
    let ring = [[-e, -e], [e, -e], [e, e], [-e, e]]; // (x, z) corners around the eye
    // Safety: a context is current.
    unsafe {
        gl.glDisable(GL_DEPTH_TEST);
        gl.glDepthMask(GL_FALSE);
        gl.glDisable(GL_LIGHTING);
        gl.glDisable(GL_TEXTURE_2D);
        gl.glDisable(GL_FOG);
        gl.glBegin(GL_QUADS);
        for k in 0..4 {
            let (a, b) = (ring[k], ring[(k + 1) % 4]);
            // Upper half (horizon to zenith) and lower half (nadir to horizon) of each side.
            for (y0, c0, y1, c1) in [(0.0, HORIZON, e, ZENITH), (-e, NADIR, 0.0, HORIZON)] {
                gl.glColor3f(c0[0], c0[1], c0[2]);
                gl.glVertex3f(a[0], y0, a[1]);
                gl.glVertex3f(b[0], y0, b[1]);
                gl.glColor3f(c1[0], c1[1], c1[2]);
                gl.glVertex3f(b[0], y1, b[1]);
                gl.glVertex3f(a[0], y1, a[1]);
            }
        }
        for (y, c) in [(e, ZENITH), (-e, NADIR)] {
            gl.glColor3f(c[0], c[1], c[2]);
            for corner in ring {
                gl.glVertex3f(corner[0], y, corner[1]);
            }
        }
        gl.glEnd();
        gl.glEnable(GL_FOG);
        gl.glEnable(GL_TEXTURE_2D);
        gl.glEnable(GL_LIGHTING);
        gl.glDepthMask(GL_TRUE);
        gl.glEnable(GL_DEPTH_TEST);
    }
}

//! The HUD: a translucent bar and two lines of text in an orthographic projection in window
//! pixels (`glOrtho`), text drawn with `glBitmap` from the embedded font. Both lines have a
//! fixed length (54 characters together) so every frame issues the same calls.

use crate::font::Font;
use crate::gl::*;

/// Bar height in pixels.
const BAR: f32 = 52.0;

/// The HUD's text lines for `frame`: the frame number (zero-padded to 5 digits) and which
/// extensions the demo uses.
pub fn lines(frame: u64, multitexture: bool, lock_arrays: bool) -> [String; 2] {
    let on = |b: bool| if b { "ON " } else { "OFF" };
    [
        format!("GLRT DEMO  FRAME {:05}", frame % 100_000),
        format!("MULTITEXTURE {}  LOCKARRAYS {}", on(multitexture), on(lock_arrays)),
    ]
}

/// Draws the bar (one `glBegin`/`glEnd`) and `text` over the top of a `width` × `height`
/// window. Saves and restores both matrices; leaves depth test, lighting, fog and texturing
/// as it found them (all on).
pub fn draw(gl: &Gl, font: &Font, width: i32, height: i32, text: &[String; 2]) {
    let (w, h) = (width as f32, height as f32);
    // Safety: a context is current.
    unsafe {
        gl.glMatrixMode(GL_PROJECTION);
        gl.glPushMatrix();
        gl.glLoadIdentity();
        gl.glOrtho(0.0, width as f64, 0.0, height as f64, -1.0, 1.0);
        gl.glMatrixMode(GL_MODELVIEW);
        gl.glPushMatrix();
        gl.glLoadIdentity();
        gl.glDisable(GL_DEPTH_TEST);
        gl.glDisable(GL_LIGHTING);
        gl.glDisable(GL_FOG);
        gl.glDisable(GL_TEXTURE_2D);

        gl.glEnable(GL_BLEND);
        gl.glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        gl.glBegin(GL_QUADS);
        gl.glColor4f(0.0, 0.0, 0.0, 0.55);
        gl.glVertex2f(0.0, h - BAR);
        gl.glVertex2f(w, h - BAR);
        gl.glVertex2f(w, h);
        gl.glVertex2f(0.0, h);
        gl.glEnd();
        gl.glDisable(GL_BLEND);

        gl.glColor3f(1.0, 0.9, 0.3);
        font.draw(gl, 10, height - 22, &text[0]);
        gl.glColor3f(0.8, 0.95, 1.0);
        font.draw(gl, 10, height - 44, &text[1]);

        gl.glEnable(GL_TEXTURE_2D);
        gl.glEnable(GL_FOG);
        gl.glEnable(GL_LIGHTING);
        gl.glEnable(GL_DEPTH_TEST);
        gl.glPopMatrix();
        gl.glMatrixMode(GL_PROJECTION);
        gl.glPopMatrix();
        gl.glMatrixMode(GL_MODELVIEW);
    }
}

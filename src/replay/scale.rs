//! `glrt replay --scale N`: a capture replayed N times larger in each direction, for pictures of
//! a capture at a higher resolution than it was made at.
//!
//! Everything the captured program said in window pixels is multiplied by N: the drawable
//! sizes (make-current and swap events), `glViewport` and `glScissor` rectangles (so viewports
//! and scissors that cover part of the window, such as 3D HUD icons, keep their place),
//! `glLineWidth` and `glPointSize`, and the raster-position moves of empty `glBitmap` calls
//! (how programs move the raster position in pixels). Geometry goes through the scaled
//! viewports, so the picture is the same at N times the pixels.
//!
//! What cannot be scaled exactly is refused before anything is replayed, naming the command
//! and the frame: images drawn or copied in window pixels (`glBitmap` with bits, `glDrawPixels`,
//! `glCopyPixels`, `glCopyTexImage*`, `glCopyTexSubImage*`, `glBlitFramebuffer*`), reads of the
//! window whose pixels the program would use (`glReadPixels`), window coordinates given
//! directly (`glWindowPos*`), patterns and limits in pixels (enabling `GL_LINE_STIPPLE` or
//! `GL_POLYGON_STIPPLE`, `glPointParameter*`), and drawing into framebuffer objects (their
//! viewports are in texels of textures the capture sized).

use super::reader::{Capture, Record};
use crate::translate::capture::format::Event;
use crate::translate::capture::table::COMMANDS;
use crate::translate::gl;

/// The largest factor `--scale` takes.
pub const MAX_FACTOR: u32 = 16;

/// How a command's arguments are scaled, by its capture id.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Rule {
    /// `x, y, width, height` (`glViewport`, `glScissor`).
    Rectangle,
    /// One float, a size in pixels (`glLineWidth`, `glPointSize`).
    Width,
    /// `glBitmap`: refused with bits; without, its origin and move are pixels.
    Bitmap,
}

/// A replay's scale factor and the commands it rewrites.
#[derive(Clone, Debug)]
pub struct Scale {
    factor: u32,
    /// [`Rule`] by capture id, for the commands that are rewritten.
    rules: Vec<Option<Rule>>,
}

/// Why a command of the capture cannot be scaled, if it cannot.
fn refusal(name: &str, args: &[u64]) -> Option<&'static str> {
    let nonzero = |i: usize| args.get(i).is_some_and(|&a| a as u32 != 0);
    match name {
        "glBitmap" if nonzero(0) && nonzero(1) => Some("draws a bitmap in window pixels"),
        "glDrawPixels" => Some("draws an image in window pixels"),
        "glCopyPixels" => Some("copies a rectangle of window pixels"),
        "glReadPixels" => Some("reads window pixels that the program uses"),
        _ if name.starts_with("glCopyTexImage") || name.starts_with("glCopyTexSubImage") => {
            Some("copies window pixels into a texture of the captured size")
        }
        _ if name.starts_with("glBlitFramebuffer") => Some("copies rectangles of pixels"),
        _ if name.starts_with("glWindowPos") => Some("sets the raster position in window pixels"),
        _ if name.starts_with("glPointParameter") => Some("sets point sizes and fades in pixels"),
        "glBindFramebuffer" | "glBindFramebufferEXT" if nonzero(1) => {
            Some("draws into a framebuffer object, whose viewports are in texels")
        }
        "glEnable" if matches!(args.first().map(|&a| a as u32), Some(gl::GL_LINE_STIPPLE | gl::GL_POLYGON_STIPPLE)) => {
            Some("enables a stipple pattern, which is in window pixels")
        }
        _ => None,
    }
}

impl Scale {
    /// The scale `factor` for `capture`, or why it cannot be replayed scaled (the first
    /// command that cannot, and its frame).
    pub fn new(capture: &Capture, factor: u32) -> Result<Scale, String> {
        if !(1..=MAX_FACTOR).contains(&factor) {
            return Err(format!("--scale {factor}: the factor is a whole number from 1 to {MAX_FACTOR}"));
        }
        let mut frame = 0u64;
        for record in capture.records() {
            let (_, record) = record.map_err(|e| e.to_string())?;
            match record {
                Record::Event(Event::Swap(_)) => frame += 1,
                Record::Call { id, args, .. } => {
                    let name = COMMANDS[id].0;
                    if let Some(why) = refusal(name, &args) {
                        return Err(format!(
                            "--scale {factor}: the capture cannot be scaled exactly: in frame {frame} it calls {name}, which {why}; replay it at its own size, or with --size (a larger window, the picture at its captured size)"
                        ));
                    }
                }
                Record::Event(_) => {}
            }
        }
        Ok(Scale::by(factor))
    }

    /// The rewriting rules for `factor`, whatever the capture.
    fn by(factor: u32) -> Scale {
        let rules = COMMANDS
            .iter()
            .map(|(name, _)| match *name {
                "glViewport" | "glScissor" => Some(Rule::Rectangle),
                "glLineWidth" | "glPointSize" => Some(Rule::Width),
                "glBitmap" => Some(Rule::Bitmap),
                _ => None,
            })
            .collect();
        Scale { factor, rules }
    }

    /// A drawable size, scaled.
    pub fn size(&self, (width, height): (i32, i32)) -> (i32, i32) {
        let n = self.factor as i32;
        (width.saturating_mul(n), height.saturating_mul(n))
    }

    /// Scales the arguments of command `id` in place, where they are in window pixels.
    pub fn rewrite(&self, id: usize, args: &mut [u64]) {
        let Some(Some(rule)) = self.rules.get(id) else { return };
        let n = self.factor;
        let int = |a: &mut u64| *a = u64::from((*a as u32 as i32).saturating_mul(n as i32) as u32);
        let float = |a: &mut u64| *a = u64::from((f32::from_bits(*a as u32) * n as f32).to_bits());
        match rule {
            Rule::Rectangle => args.iter_mut().take(4).for_each(int),
            Rule::Width => args.iter_mut().take(1).for_each(float),
            // glBitmap(width, height, xorig, yorig, xmove, ymove, bitmap): only empty ones remain.
            Rule::Bitmap => args.iter_mut().skip(2).take(4).for_each(float),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Scale, refusal};
    use crate::translate::capture::table::COMMANDS;

    fn id(name: &str) -> usize {
        COMMANDS.iter().position(|(n, _)| *n == name).unwrap()
    }

    #[test]
    fn window_pixels_are_multiplied() {
        let s = Scale::by(3);
        let mut viewport = [10u64, (-4i32) as u32 as u64, 320, 240];
        s.rewrite(id("glViewport"), &mut viewport);
        assert_eq!(viewport.map(|a| a as u32 as i32), [30, -12, 960, 720]);
        let mut width = [u64::from(1.5f32.to_bits())];
        s.rewrite(id("glLineWidth"), &mut width);
        assert_eq!(f32::from_bits(width[0] as u32), 4.5);
        let f = |v: f32| u64::from(v.to_bits());
        let mut bitmap = [0, 0, f(0.0), f(0.0), f(8.0), f(-2.0), 0];
        s.rewrite(id("glBitmap"), &mut bitmap);
        assert_eq!(bitmap[4..6].iter().map(|&a| f32::from_bits(a as u32)).collect::<Vec<_>>(), [24.0, -6.0]);
        let mut color = [f(0.5), f(0.25), f(1.0)];
        s.rewrite(id("glColor3f"), &mut color);
        assert_eq!(color, [f(0.5), f(0.25), f(1.0)], "other commands are untouched");
        assert_eq!(s.size((300, 200)), (900, 600));
    }

    #[test]
    fn pixel_images_and_framebuffer_objects_are_refused() {
        assert!(refusal("glBitmap", &[8, 13, 0, 0, 0, 0, 0]).is_some());
        assert!(refusal("glBitmap", &[0, 0, 0, 0, 0, 0, 0]).is_none(), "an empty bitmap only moves");
        assert!(refusal("glCopyTexSubImage2D", &[0; 8]).is_some());
        assert!(refusal("glBindFramebufferEXT", &[0x8D40, 1]).is_some());
        assert!(refusal("glBindFramebufferEXT", &[0x8D40, 0]).is_none(), "the window's framebuffer");
        assert!(refusal("glEnable", &[u64::from(crate::translate::gl::GL_POLYGON_STIPPLE)]).is_some());
        assert!(refusal("glEnable", &[u64::from(crate::translate::gl::GL_DEPTH_TEST)]).is_none());
        assert!(refusal("glViewport", &[0, 0, 64, 64]).is_none());
    }
}

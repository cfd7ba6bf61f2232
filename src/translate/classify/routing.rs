//! Which path a draw takes: traced (its class is then decided by matching) or one of the
//! raster classes. The rules, in this order (the first that applies wins):
//!
//! 1. a texture tagged `ignore` in `glrt.toml`, or no colour written (colour mask all off, or
//!    `glDrawBuffer(GL_NONE)`: depth-only passes) → `Ignored`;
//! 2. a texture tagged `ui` → `Overlay`; `sky` → `Sky`; `translucent` → `Translucent`;
//! 3. an orthographic projection (last row of the projection `(0, 0, 0, 1)`) → `Overlay`;
//! 4. at the far plane (`glDepthRange` near ≥ 0.999, as Quake 3 draws its sky) → `Sky`;
//! 5. drawn before any traced draw of the frame with depth writes off → `Sky`;
//! 6. drawn after a traced draw with the depth test off, or, into the framebuffer of the
//!    frame's first traced draw, in another viewport or another depth range than that draw,
//!    or after a depth clear made since it → `Overlay`: 2D drawn over the scene, a view
//!    weapon squeezed into the front of the depth range (Quake 3: 0..0.3) or drawn after a
//!    depth clear, 3D HUD icons in their own viewports after a (scissored) depth clear:
//!    rasterized as drawn, over the traced image. A traced draw into another framebuffer
//!    starts a scene of its own (a scene rendered to a texture first). Limit: a game that
//!    draws a second view of the world before its main view in the same framebuffer (Quake
//!    3's portals and mirrors) gets its main view rasterized;
//! 7. blending that is not a plain replace (source factor one, destination zero) →
//!    `Translucent`;
//! 8. lines and points (not traced) → `Translucent`, the raster path in the 3D scene;
//! 9. everything else (opaque and alpha-tested triangles) is traced.
//!
//! Tags `static`, `dynamic`, `emissive` and `lightmap` apply to traced draws (see `super`).

use crate::frame::class::{DrawClass, orthographic};
use crate::frame::state::{Blend, BlendFactor};
use crate::frame::{Clear, Draw, Framebuffer, Topology};

/// The `glrt.toml` tags of a draw's textures.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tags {
    /// `ignore`.
    pub ignore: bool,
    /// `ui`.
    pub ui: bool,
    /// `sky`.
    pub sky: bool,
    /// `translucent`.
    pub translucent: bool,
    /// `emissive`.
    pub emissive: bool,
    /// `static`.
    pub static_: bool,
    /// `dynamic`.
    pub dynamic: bool,
    /// `lightmap` (on any texture of the draw; `super::lighting` asks per texture).
    pub lightmap: bool,
}

/// What routing knows of the frame before the draw it routes (rule 6).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Before {
    /// Framebuffer, viewport and depth range of the first traced draw of the frame, or of the
    /// first since a traced draw went to another framebuffer (a scene rendered to a texture
    /// first starts a scene of its own).
    pub scene: Option<(Framebuffer, [i32; 4], [f64; 2])>,
    /// The scene's depth buffer was cleared after its first traced draw.
    pub depth_cleared: bool,
    /// Clears of the frame taken into account so far.
    clears: usize,
}

impl Before {
    /// Takes in the clears of `clears` (a frame's, in program order) made before draw `draw`.
    pub fn clears_before(&mut self, clears: &[Clear], draw: usize) {
        while let Some(clear) = clears.get(self.clears).filter(|c| c.before_draw <= draw) {
            let of_the_scene = self.scene.as_ref().is_some_and(|scene| scene.0 == clear.framebuffer);
            self.depth_cleared |= of_the_scene && clear.depth.is_some() && clear.depth_mask;
            self.clears += 1;
        }
    }

    /// Notes a traced draw: the first one (to its framebuffer) sets the scene.
    pub fn traced(&mut self, draw: &Draw) {
        let s = &draw.state;
        if self.scene.as_ref().is_none_or(|scene| scene.0 != s.framebuffer) {
            self.scene = Some((s.framebuffer.clone(), s.viewport, s.depth_range));
            self.depth_cleared = false;
        }
    }

    /// Whether a draw with this state is drawn over the scene of the traced draws (rule 6).
    fn over_the_scene(&self, draw: &Draw) -> bool {
        let s = &draw.state;
        self.scene.as_ref().is_some_and(|(framebuffer, viewport, depth_range)| {
            s.depth_test.is_none() || (*framebuffer == s.framebuffer && (self.depth_cleared || (*viewport, *depth_range) != (s.viewport, s.depth_range)))
        })
    }
}

/// Whether blending leaves the source as it is.
fn plain_replace(blend: &Blend) -> bool {
    blend.src_rgb == BlendFactor::One && blend.dst_rgb == BlendFactor::Zero && blend.equation_rgb == Default::default()
}

/// The raster class of `draw`, or `None` when it is traced; `before`: what came before it in
/// the frame.
pub fn raster_class(draw: &Draw, before: &Before, tags: Tags) -> Option<DrawClass> {
    let traced_before = before.scene.is_some();
    let s = &draw.state;
    let no_color = s.color_mask == [false; 4] || !(s.draw_buffers.front || s.draw_buffers.back);
    let class = if tags.ignore || no_color {
        DrawClass::Ignored
    } else if tags.ui {
        DrawClass::Overlay
    } else if tags.sky {
        DrawClass::Sky
    } else if tags.translucent {
        DrawClass::Translucent
    } else if orthographic(&draw.projection) {
        DrawClass::Overlay
    } else if s.depth_range[0] >= 0.999 || (!traced_before && !s.depth_write) {
        DrawClass::Sky
    } else if before.over_the_scene(draw) {
        DrawClass::Overlay
    } else if s.blend.as_ref().is_some_and(|b| !plain_replace(b)) || draw.topology != Topology::Triangles {
        DrawClass::Translucent
    } else {
        return None;
    };
    Some(class)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::state::{CompareFunc, RasterState};

    fn draw(f: impl FnOnce(&mut RasterState)) -> Draw {
        let mut s = RasterState { depth_test: Some(CompareFunc::Less), depth_write: true, color_mask: [true; 4], ..RasterState::default() };
        s.depth_range = [0.0, 1.0];
        s.draw_buffers.back = true;
        f(&mut s);
        Draw { state: Arc::new(s), projection: crate::translate::classify::view::perspective(1.0, 1.0, 0.1, 100.0), ..Draw::default() }
    }

    /// What routing knows after the traced draw `draw(|_| {})`.
    fn after_a_traced_draw() -> Before {
        let mut before = Before::default();
        before.traced(&draw(|_| {}));
        before
    }

    #[test]
    fn rules_route_draws() {
        let none = Tags::default();
        let (first, traced) = (Before::default(), after_a_traced_draw());
        assert_eq!(raster_class(&draw(|_| {}), &first, none), None);
        assert_eq!(raster_class(&draw(|s| s.depth_write = false), &first, none), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|s| s.depth_range = [1.0, 1.0]), &traced, none), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|s| s.depth_test = None), &traced, none), Some(DrawClass::Overlay));
        let blend = Blend { src_rgb: BlendFactor::SrcAlpha, dst_rgb: BlendFactor::OneMinusSrcAlpha, ..Blend::default() };
        assert_eq!(raster_class(&draw(|s| s.blend = Some(blend)), &traced, none), Some(DrawClass::Translucent));
        assert_eq!(raster_class(&draw(|s| s.blend = Some(Blend::default())), &traced, none), None, "replace is opaque");
        assert_eq!(raster_class(&draw(|s| s.color_mask = [false; 4]), &traced, none), Some(DrawClass::Ignored));
        let mut ortho = draw(|_| {});
        ortho.projection = crate::translate::classify::view::ortho(0.0, 640.0, 0.0, 480.0, -1.0, 1.0);
        assert_eq!(raster_class(&ortho, &traced, none), Some(DrawClass::Overlay));
        let mut lines = draw(|_| {});
        lines.topology = Topology::Lines;
        assert_eq!(raster_class(&lines, &traced, none), Some(DrawClass::Translucent));
        assert_eq!(raster_class(&draw(|_| {}), &traced, Tags { ui: true, ..none }), Some(DrawClass::Overlay));
        assert_eq!(raster_class(&draw(|_| {}), &traced, Tags { sky: true, ..none }), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|_| {}), &traced, Tags { ignore: true, ..none }), Some(DrawClass::Ignored));
    }

    #[test]
    fn a_view_weapon_and_3d_hud_icons_are_overlays() {
        let none = Tags::default();
        let traced = after_a_traced_draw();
        // Quake 3's view weapon: the front of the depth range; before any traced draw it is
        // the scene itself.
        let weapon = draw(|s| s.depth_range = [0.0, 0.3]);
        assert_eq!(raster_class(&weapon, &traced, none), Some(DrawClass::Overlay));
        assert_eq!(raster_class(&weapon, &Before::default(), none), None);
        // An icon in its own viewport.
        let icon = draw(|s| s.viewport = [143, 0, 24, 24]);
        assert_eq!(raster_class(&icon, &traced, none), Some(DrawClass::Overlay));
        // After a scissored depth clear made since the first traced draw, even in the scene's
        // viewport; a depth clear before it, or a clear of colour only, changes nothing.
        let clear = |before_draw, depth: bool| Clear { before_draw, depth: depth.then_some(1.0), depth_mask: true, scissor: Some([0, 0, 8, 8]), ..Clear::default() };
        let clears = [clear(0, true), clear(2, false), clear(3, true)];
        let mut before = Before::default();
        before.clears_before(&clears, 0);
        before.traced(&draw(|_| {}));
        for d in 1..=2 {
            before.clears_before(&clears, d);
            assert_eq!(raster_class(&draw(|_| {}), &before, none), None, "draw {d}");
        }
        before.clears_before(&clears, 3);
        assert!(before.depth_cleared);
        assert_eq!(raster_class(&draw(|_| {}), &before, none), Some(DrawClass::Overlay));
        let masked = [Clear { depth_mask: false, ..clear(1, true) }];
        let mut before = after_a_traced_draw();
        before.clears_before(&masked, 1);
        assert!(!before.depth_cleared, "depth writes off: the clear leaves depth alone");
    }

    #[test]
    fn a_scene_rendered_to_a_texture_first_starts_a_scene_of_its_own() {
        use crate::frame::framebuffer::FramebufferObject;
        let none = Tags::default();
        let object = Framebuffer::Object(std::sync::Arc::new(FramebufferObject { size: [64, 64], color: None, depth: None, stencil: None, alpha: false }));
        let mut before = Before::default();
        before.traced(&draw(|s| (s.framebuffer, s.viewport) = (object.clone(), [0, 0, 64, 64])));
        // Its depth clear, then the window's scene in another viewport: traced, a new scene.
        before.clears_before(&[Clear { depth: Some(1.0), depth_mask: true, framebuffer: object.clone(), ..Clear::default() }], 1);
        let window = draw(|s| s.viewport = [0, 0, 320, 240]);
        assert_eq!(raster_class(&window, &before, none), None);
        before.traced(&window);
        assert!(!before.depth_cleared);
        assert_eq!(raster_class(&window, &before, none), None);
        assert_eq!(raster_class(&draw(|s| s.viewport = [0, 0, 24, 24]), &before, none), Some(DrawClass::Overlay));
    }
}

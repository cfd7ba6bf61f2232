//! Which path a draw takes: traced (its class is then decided by matching) or one of the
//! raster classes. The rules, in this order (the first that applies wins):
//!
//! 1. a texture tagged `ignore` in `glrt.toml`, or no colour written (colour mask all off, or
//!    `glDrawBuffer(GL_NONE)`: depth-only passes) → `Ignored`;
//! 2. a texture tagged `ui` → `Overlay`; `sky` → `Sky`; `translucent` → `Translucent`;
//! 3. an orthographic projection (last row of the projection `(0, 0, 0, 1)`) → `Overlay`;
//! 4. at the far plane (`glDepthRange` near ≥ 0.999, as Quake 3 draws its sky) → `Sky`;
//! 5. drawn before any traced draw of the frame with depth writes off → `Sky`;
//! 6. drawn after a traced draw with the depth test off → `Overlay` (2D drawn over the scene);
//! 7. blending that is not a plain replace (source factor one, destination zero) →
//!    `Translucent`;
//! 8. lines and points (not traced) → `Translucent`, the raster path in the 3D scene;
//! 9. everything else (opaque and alpha-tested triangles) is traced.
//!
//! Tags `static`, `dynamic` and `emissive` apply to traced draws (see `super`).

use crate::frame::class::{DrawClass, orthographic};
use crate::frame::state::{Blend, BlendFactor};
use crate::frame::{Draw, Topology};

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
}

/// Whether blending leaves the source as it is.
fn plain_replace(blend: &Blend) -> bool {
    blend.src_rgb == BlendFactor::One && blend.dst_rgb == BlendFactor::Zero && blend.equation_rgb == Default::default()
}

/// The raster class of `draw`, or `None` when it is traced; `traced_before`: a draw before it
/// in the frame is traced.
pub fn raster_class(draw: &Draw, traced_before: bool, tags: Tags) -> Option<DrawClass> {
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
    } else if traced_before && s.depth_test.is_none() {
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

    #[test]
    fn rules_route_draws() {
        let none = Tags::default();
        assert_eq!(raster_class(&draw(|_| {}), false, none), None);
        assert_eq!(raster_class(&draw(|s| s.depth_write = false), false, none), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|s| s.depth_range = [1.0, 1.0]), true, none), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|s| s.depth_test = None), true, none), Some(DrawClass::Overlay));
        let blend = Blend { src_rgb: BlendFactor::SrcAlpha, dst_rgb: BlendFactor::OneMinusSrcAlpha, ..Blend::default() };
        assert_eq!(raster_class(&draw(|s| s.blend = Some(blend)), true, none), Some(DrawClass::Translucent));
        assert_eq!(raster_class(&draw(|s| s.blend = Some(Blend::default())), true, none), None, "replace is opaque");
        assert_eq!(raster_class(&draw(|s| s.color_mask = [false; 4]), true, none), Some(DrawClass::Ignored));
        let mut ortho = draw(|_| {});
        ortho.projection = crate::translate::classify::view::ortho(0.0, 640.0, 0.0, 480.0, -1.0, 1.0);
        assert_eq!(raster_class(&ortho, true, none), Some(DrawClass::Overlay));
        let mut lines = draw(|_| {});
        lines.topology = Topology::Lines;
        assert_eq!(raster_class(&lines, true, none), Some(DrawClass::Translucent));
        assert_eq!(raster_class(&draw(|_| {}), true, Tags { ui: true, ..none }), Some(DrawClass::Overlay));
        assert_eq!(raster_class(&draw(|_| {}), true, Tags { sky: true, ..none }), Some(DrawClass::Sky));
        assert_eq!(raster_class(&draw(|_| {}), true, Tags { ignore: true, ..none }), Some(DrawClass::Ignored));
    }
}

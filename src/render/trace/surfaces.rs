//! Which draws of a frame the tracer takes, grouped into surfaces: a traced draw (the
//! surface's base, [`scene::is_traced`]) and the draws of class
//! [`DrawClass::Layer`] that hash tracking put over it (its passes: lightmap, detail, glow,
//! decal; [`crate::frame::Draw::layer`]), in program order. The tracer evaluates a surface's
//! base and passes as one material ([`super::material`]); the renderer rasterizes none of
//! them ([`Surfaces::is_traced`]), so a pass is never drawn a second time over the traced
//! image. In raster mode every layer draw is rasterized as drawn.
//!
//! A layer draw joins its base when the tracer can evaluate it: triangles into the window's
//! framebuffer under the fixed-function pipeline, over a base that is traced, its triangle map
//! as long as its triangle list and inside the base's triangles, texturing with unit 0 at most
//! (a pass's own colour is what unit 0 makes of its primary colour, then its blend function),
//! and among the first [`MAX_LAYERS`] passes of that base. Any other layer draw is rasterized
//! over the traced image, as translucent draws are.
//!
//! A dynamic-light pass ([`DrawClass::Light`]) is not rasterized over a traced image either:
//! its light is one of the frame's lights ([`crate::frame::Frame::lights`]), which the tracer
//! samples.

use crate::frame::class::{DrawClass, Layer, MAX_LAYERS};
use crate::frame::{Draw, Frame, Framebuffer, Topology};

use super::scene;

/// What a draw of the frame is to the tracer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// Not traced: rasterized around the traced image.
    Rasterized,
    /// The base of a traced surface.
    Base,
    /// A pass of the traced surface of the base draw at this index.
    Pass(usize),
    /// A dynamic-light pass, traced as a light.
    Light,
}

/// The traced surfaces of one frame (see the module doc).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Surfaces {
    /// Per draw of the frame.
    parts: Vec<Part>,
}

/// One traced surface: a base draw and its passes, in program order.
#[derive(Clone, Debug)]
pub struct Surface<'a> {
    /// The traced draw.
    pub base: &'a Draw,
    /// Its layer draws (each with [`Draw::layer`] set).
    pub passes: Vec<&'a Draw>,
}

impl Surfaces {
    /// The surfaces of `frame`.
    pub fn of(frame: &Frame) -> Surfaces {
        let mut parts: Vec<Part> = frame.draws.iter().map(|d| if scene::is_traced(d) { Part::Base } else { Part::Rasterized }).collect();
        let mut passes = vec![0usize; frame.draws.len()];
        for (i, draw) in frame.draws.iter().enumerate() {
            let Some(layer) = draw.layer.as_ref().filter(|_| draw.class == DrawClass::Layer) else { continue };
            let base = layer.base;
            if base < i && parts[base] == Part::Base && passes[base] < MAX_LAYERS && fits(&frame.draws[base], draw, layer) {
                parts[i] = Part::Pass(base);
                passes[base] += 1;
            }
        }
        if parts.contains(&Part::Base) {
            for (part, draw) in parts.iter_mut().zip(&frame.draws) {
                if draw.class == DrawClass::Light {
                    *part = Part::Light;
                }
            }
        }
        Surfaces { parts }
    }

    /// Whether draw `index` is traced, as a base, a pass or a light (the renderer does not
    /// rasterize it).
    pub fn is_traced(&self, index: usize) -> bool {
        self.parts.get(index).is_some_and(|p| *p != Part::Rasterized)
    }

    /// Index of the first base: where the traced image is composited, so that draws before it
    /// (sky) are behind it and draws after it (glass, HUD) over it.
    pub fn first(&self) -> Option<usize> {
        self.parts.iter().position(|p| *p == Part::Base)
    }

    /// The surfaces of `frame` (the frame these were made of), in the order of their bases.
    pub fn surfaces<'a>(&self, frame: &'a Frame) -> Vec<Surface<'a>> {
        let mut index_of = vec![usize::MAX; self.parts.len()];
        let mut surfaces: Vec<Surface<'a>> = Vec::new();
        for (i, (part, draw)) in self.parts.iter().zip(&frame.draws).enumerate() {
            match *part {
                Part::Base => {
                    index_of[i] = surfaces.len();
                    surfaces.push(Surface { base: draw, passes: Vec::new() });
                }
                Part::Pass(base) => surfaces[index_of[base]].passes.push(draw),
                Part::Rasterized | Part::Light => {}
            }
        }
        surfaces
    }
}

/// Whether the tracer can evaluate layer draw `draw` over `base` (see the module doc).
fn fits(base: &Draw, draw: &Draw, layer: &Layer) -> bool {
    let base_triangles = base.indices.len() / 3;
    draw.topology == Topology::Triangles
        && draw.program.is_none()
        && draw.state.framebuffer == Framebuffer::default()
        && !draw.indices.is_empty()
        && layer.triangles.len() == draw.indices.len() / 3
        && layer.triangles.iter().all(|&t| (t as usize) < base_triangles)
        && draw.texture_units.iter().skip(1).all(Option::is_none)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::frame::class::LayerRole;
    use crate::frame::{RasterState, TextureUnit, Vertices};

    /// Two triangles of class `class`.
    fn quad(class: DrawClass) -> Draw {
        Draw {
            vertex_count: 4,
            vertices: Vertices { position: vec![[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [1.0, 1.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]], ..Vertices::default() },
            indices: vec![0, 1, 2, 0, 2, 3],
            class,
            state: Arc::new(RasterState::default()),
            ..Draw::default()
        }
    }

    /// A layer draw over draw `base`, its triangles over the base's `triangles`.
    fn pass(base: usize, triangles: &[u32]) -> Draw {
        let mut draw = quad(DrawClass::Layer);
        draw.indices.truncate(3 * triangles.len());
        draw.layer = Some(Layer { base, triangles: triangles.into(), role: LayerRole::BakedLight });
        draw
    }

    #[test]
    fn passes_join_their_traced_base_up_to_the_limit() {
        let mut draws = vec![quad(DrawClass::Sky), quad(DrawClass::Static), pass(1, &[0, 1]), pass(1, &[1])];
        draws.extend((0..MAX_LAYERS).map(|_| pass(1, &[0])));
        let frame = Frame { draws, ..Frame::default() };
        let s = Surfaces::of(&frame);
        assert_eq!(s.first(), Some(1));
        let traced: Vec<bool> = (0..frame.draws.len()).map(|i| s.is_traced(i)).collect();
        assert_eq!(traced, [false, true, true, true, true, true, false, false], "passes past MAX_LAYERS stay rasterized");
        let surfaces = s.surfaces(&frame);
        assert_eq!(surfaces.len(), 1);
        assert!(std::ptr::eq(surfaces[0].base, &frame.draws[1]));
        assert_eq!(surfaces[0].passes.len(), MAX_LAYERS);
        assert!(std::ptr::eq(surfaces[0].passes[1], &frame.draws[3]));
    }

    #[test]
    fn passes_the_tracer_cannot_evaluate_stay_rasterized() {
        let mut over_a_translucent_base = pass(0, &[0]);
        over_a_translucent_base.layer.as_mut().unwrap().base = 0;
        let mut beyond_the_base = pass(1, &[2]);
        beyond_the_base.layer.as_mut().unwrap().base = 1;
        let mut two_units = pass(1, &[0]);
        two_units.texture_units = vec![Some(TextureUnit::default()), Some(TextureUnit::default())];
        let mut short_map = pass(1, &[0, 1]);
        short_map.indices.truncate(3);
        let mut not_a_layer = pass(1, &[0]);
        not_a_layer.class = DrawClass::Translucent;
        let after = pass(5, &[0]);
        let draws = vec![quad(DrawClass::Translucent), quad(DrawClass::Static), over_a_translucent_base, beyond_the_base, two_units, short_map, not_a_layer, after];
        let frame = Frame { draws, ..Frame::default() };
        let s = Surfaces::of(&frame);
        assert_eq!((0..frame.draws.len()).filter(|&i| s.is_traced(i)).collect::<Vec<_>>(), [1]);
        assert!(s.surfaces(&frame)[0].passes.is_empty());
        assert_eq!(Surfaces::of(&Frame::default()).first(), None);
    }

    #[test]
    fn dynamic_light_passes_are_not_rasterized_over_a_traced_image() {
        let draws = vec![quad(DrawClass::Static), quad(DrawClass::Light), quad(DrawClass::Translucent)];
        let frame = Frame { draws, ..Frame::default() };
        let s = Surfaces::of(&frame);
        assert_eq!((0..3).map(|i| s.is_traced(i)).collect::<Vec<_>>(), [true, true, false]);
        assert!(s.surfaces(&frame)[0].passes.is_empty(), "a light is no pass");
        // Nothing traced: the pass is drawn as it is.
        let alone = Frame { draws: vec![quad(DrawClass::Light)], ..Frame::default() };
        assert!(!Surfaces::of(&alone).is_traced(0));
    }
}

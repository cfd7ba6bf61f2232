//! Window-aligned rectangles drawn as a [`Draw`] through the fixed-function pipelines: the
//! fragments of bitmaps, images, copies, masked clears and accumulation returns are produced
//! by rasterizing one rectangle per pixel (or per run of equal pixels), so every per-fragment
//! operation of the state applies exactly as for other primitives.
//!
//! Coordinates are GL window coordinates (x, y in pixels from the lower-left corner, z in
//! [0, 1]); the projection maps them to clip space for a viewport covering the target and the
//! depth range [0, 1].

use std::sync::Arc;

use glam::{Mat4, Vec3};

use crate::frame::pixels::RasterFragment;
use crate::frame::state::{Fog, FogSource, PolygonMode, RasterState, StencilFaces};
use crate::frame::{Attrib, Draw, Topology, Vertices};

/// Rectangles being collected for one draw.
#[derive(Default)]
pub struct Quads {
    vertices: Vertices,
    indices: Vec<u32>,
}

impl Quads {
    /// Adds the rectangle between corners `(x0, y0)` and `(x1, y1)` (any order) at depth `z`
    /// with `color`. Degenerate rectangles are skipped.
    pub fn push(&mut self, rect: [f32; 4], z: f32, color: [f32; 4]) {
        self.push_with(rect, z, color, None);
    }

    /// Adds a rectangle like [`Quads::push`] whose corners take the texture coordinates of
    /// `uv` (s0, t0, s1, t1) on unit 0.
    pub fn push_textured(&mut self, rect: [f32; 4], z: f32, uv: [f32; 4]) {
        self.push_with(rect, z, [1.0; 4], Some(uv));
    }

    fn push_with(&mut self, [x0, y0, x1, y1]: [f32; 4], z: f32, color: [f32; 4], uv: Option<[f32; 4]>) {
        if x0 == x1 || y0 == y1 {
            return;
        }
        let base = self.vertices.position.len() as u32;
        let [s0, t0, s1, t1] = uv.unwrap_or_default();
        for (x, y, s, t) in [(x0, y0, s0, t0), (x1, y0, s1, t0), (x1, y1, s1, t1), (x0, y1, s0, t1)] {
            let count = self.vertices.position.len();
            self.vertices.position.push([x, y, z, 1.0]);
            self.vertices.color.push(color, count);
            if uv.is_some() {
                if self.vertices.texcoords.is_empty() {
                    self.vertices.texcoords.push(Default::default());
                }
                self.vertices.texcoords[0].push([s, t, 0.0, 1.0], count);
            }
        }
        self.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// Whether no rectangle was added.
    pub fn is_empty(&self) -> bool {
        self.indices.is_empty()
    }

    /// Rectangles added.
    pub fn len(&self) -> usize {
        self.indices.len() / 6
    }

    /// The draw of the rectangles for a target of `size`, with the per-fragment operations of
    /// `state` (see [`fragment_state`]).
    pub fn into_draw(self, size: [u32; 2], state: RasterState) -> Draw {
        let [w, h] = [size[0].max(1) as f32, size[1].max(1) as f32];
        let projection = Mat4::from_translation(Vec3::splat(-1.0)) * Mat4::from_scale(Vec3::new(2.0 / w, 2.0 / h, 2.0));
        // Both triangles of a rectangle have two boundary edges: (a, b, c) the first two,
        // (a, c, d) the last two.
        let edge_masks = (0..self.indices.len() / 3).map(|t| if t % 2 == 0 { 0b011 } else { 0b110 }).collect();
        Draw {
            vertex_count: self.vertices.len(),
            topology: Topology::Triangles,
            vertices: self.vertices,
            indices: self.indices,
            edge_masks,
            modelview: Mat4::IDENTITY,
            projection,
            state: Arc::new(state),
            ..Draw::default()
        }
    }
}

/// The state under which pixel rectangles are drawn: the per-fragment operations of `base`
/// (scissor, alpha, stencil (the front face's) and depth tests, blending, logic op, dithering,
/// masks), with
/// whatever belongs to vertices and primitives turned off (lighting, fog, culling, polygon
/// modes, offset and stipple, clip planes) and a viewport covering the target of `size`.
///
/// Texturing, colour sum and fog are off too: [`raster_fragments`] turns them back on for the
/// fragments that take them from the raster position.
pub fn fragment_state(base: &RasterState, size: [u32; 2]) -> RasterState {
    let mut state = base.clone();
    state.lighting = None;
    state.fog = None;
    state.color_sum = false;
    state.cull = None;
    state.polygon_mode = [PolygonMode::Fill; 2];
    state.polygon_offset.fill = false;
    state.polygon_offset.line = false;
    state.polygon_offset.point = false;
    state.polygon_stipple = None;
    state.clip_planes.clear();
    // Pixel rectangles and bitmaps are front-facing (OpenGL 2.0 section 4.1.5).
    state.stencil = base.stencil.map(|s| StencilFaces::both(s.front));
    state.viewport = [0, 0, size[0] as i32, size[1] as i32];
    state.depth_range = [0.0, 1.0];
    state
}

/// The draw of `quads` as fragments of a bitmap, image or copy issued under `base` for a
/// target of `size`: the per-fragment operations of [`fragment_state`], and what the
/// fragments take from the raster position (sections 3.6.5, 3.7 and 4.3.3): every vertex
/// carries its texture coordinates, so the units that texture sample there with their
/// environments; its secondary colour goes through the colour sum when `base` sums (or
/// lights); its distance is the fog coordinate when `base` fogs (section 3.10).
pub fn raster_fragments(quads: Quads, size: [u32; 2], base: &RasterState, raster: &RasterFragment) -> Draw {
    let mut state = fragment_state(base, size);
    state.fog = base.fog.map(|fog| Fog { source: FogSource::FogCoord, ..fog });
    state.color_sum = base.color_sum || base.lighting.is_some();
    let mut draw = quads.into_draw(size, state);
    fn shared<T>(value: T) -> Attrib<T> {
        Attrib { values: vec![value] }
    }
    let [r, g, b, _] = raster.secondary;
    draw.vertices.secondary_color = shared([r, g, b]);
    draw.vertices.fog_coord = shared(raster.fog_coord);
    if raster.textured() {
        draw.vertices.texcoords = raster.texcoords.iter().copied().map(shared).collect();
        draw.textures = raster.textures.clone();
        draw.texture_units = raster.texture_units.clone();
        draw.texture_matrices = raster.texture_units.iter().map(|u| u.map(|_| Mat4::IDENTITY)).collect();
    }
    draw
}

/// Pushes one rectangle per run of equal pixels of an image (`pixels` rows bottom to top,
/// `width` per row) whose lower-left corner is `origin` and pixels are `zoom` apart
/// (section 3.6.5: pixel (i, j) covers x from `x + zx·i` to `x + zx·(i + 1)`, likewise y).
/// `value` gives each pixel's depth and colour, `None` for pixels that produce no fragment.
pub fn push_image<T: PartialEq + Copy>(
    quads: &mut Quads,
    origin: [f32; 2],
    zoom: [f32; 2],
    width: usize,
    pixels: &[T],
    value: impl Fn(T) -> Option<(f32, [f32; 4])>,
) {
    if width == 0 {
        return;
    }
    for (j, row) in pixels.chunks(width).enumerate() {
        let y0 = origin[1] + zoom[1] * j as f32;
        let y1 = y0 + zoom[1];
        let mut i = 0;
        while i < row.len() {
            let start = i;
            while i + 1 < row.len() && row[i + 1] == row[start] {
                i += 1;
            }
            i += 1;
            if let Some((z, color)) = value(row[start]) {
                let x0 = origin[0] + zoom[0] * start as f32;
                let x1 = origin[0] + zoom[0] * i as f32;
                quads.push([x0, y0, x1, y1], z, color);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_equal_pixels_become_one_rectangle() {
        let mut q = Quads::default();
        // 3×2 image: bottom row a a b, top row c c c; zoom (2, -1).
        push_image(&mut q, [10.0, 20.0], [2.0, -1.0], 3, &[1, 1, 2, 3, 3, 3], |v| (v != 2).then_some((0.5, [v as f32; 4])));
        let d = q.into_draw([64, 64], RasterState::default());
        assert_eq!(d.indices.len(), 12, "two rectangles: the run of 1s and the row of 3s");
        let p = &d.vertices.position;
        assert_eq!(p[0], [10.0, 20.0, 0.5, 1.0]);
        assert_eq!(p[2], [14.0, 19.0, 0.5, 1.0]);
        assert_eq!(p[6], [16.0, 18.0, 0.5, 1.0]);
        // The projection maps the window corners to clip space corners.
        let c = d.projection * glam::Vec4::new(64.0, 0.0, 1.0, 1.0);
        assert_eq!(c, glam::Vec4::new(1.0, -1.0, 1.0, 1.0));
    }
}

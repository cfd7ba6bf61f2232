//! What hash tracking (`translate::classify`) says about a frame: the class of each draw, the
//! identity of each traced instance across frames, the camera recovered from the modelview of
//! static draws, and per-frame statistics (`glrt replay --stats`).

use glam::Mat4;

/// How the renderer treats a draw (DESIGN.md, "The frame"): traced classes go into the
/// acceleration structures; the others are rasterized and composited over the traced image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DrawClass {
    /// Not classified yet (a frame read back before it ended).
    #[default]
    Unclassified,
    /// Traced: the same geometry at the same place in the world as in the previous frame.
    Static,
    /// Traced: the same geometry at another place (a new transform); stays movable.
    Movable,
    /// Traced: new vertices every frame (animated); matched by its slot.
    Dynamic,
    /// Raster: blending that is not a plain replace, or lines and points in 3D.
    Translucent,
    /// Raster: 2D/HUD, drawn over everything.
    Overlay,
    /// Raster: the sky, drawn behind everything; also the environment of missed rays.
    Sky,
    /// Traced as part of an earlier traced draw: one pass of a multi-pass material over that
    /// draw's triangles (a lightmap, detail, glow or decal pass; [`crate::frame::Draw::layer`]
    /// says which draw and what the pass does). Rasterized like any draw when nothing traces.
    Layer,
    /// Traced as light: a dynamic-light pass (an additive radial falloff projected over the
    /// surfaces around a point, as Quake 3 draws rockets' and muzzle flashes' light) whose
    /// light is one of [`crate::frame::Frame::lights`]. Rasterized like any draw when nothing
    /// traces; not drawn over a traced image.
    Light,
    /// Not drawn by the renderer (a texture listed under `ignore`, or no colour written).
    Ignored,
}

impl DrawClass {
    /// The eight counted classes, in the order of [`ClassCounts`] and of the JSON keys.
    pub const COUNTED: [DrawClass; 8] = [
        DrawClass::Static,
        DrawClass::Movable,
        DrawClass::Dynamic,
        DrawClass::Translucent,
        DrawClass::Overlay,
        DrawClass::Sky,
        DrawClass::Layer,
        DrawClass::Light,
    ];

    /// Whether the class is traced (in the acceleration structures).
    pub fn is_traced(self) -> bool {
        matches!(self, DrawClass::Static | DrawClass::Movable | DrawClass::Dynamic)
    }

    /// The JSON key of a counted class.
    pub fn key(self) -> &'static str {
        match self {
            DrawClass::Static => "static",
            DrawClass::Movable => "movable",
            DrawClass::Dynamic => "dynamic",
            DrawClass::Translucent => "translucent",
            DrawClass::Overlay => "overlay",
            DrawClass::Sky => "sky",
            DrawClass::Layer => "layer",
            DrawClass::Light => "light",
            DrawClass::Unclassified => "unclassified",
            DrawClass::Ignored => "ignored",
        }
    }
}

/// How a traced instance was found in the previous frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Match {
    /// Not found: a new instance.
    #[default]
    New,
    /// Same geometry key, textures and state.
    Exact,
    /// Same slot (textures, state, vertex count, topology, order of appearance), new vertices.
    Slot,
}

/// The identity of a traced draw across frames.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Instance {
    /// Stable id: the same instance keeps it from frame to frame; unique within a frame; never
    /// reused for another instance.
    pub id: u64,
    /// How it was matched with the previous frame.
    pub matched: Match,
    /// Its modelview in the previous frame (motion vectors); `None` when new or after a camera cut.
    pub previous_modelview: Option<Mat4>,
    /// Object space to world space (the world frame of [`View`]); `None` without a view.
    pub model: Option<Mat4>,
    /// xxh3 of the object-space positions, indices, texture coordinates and topology.
    pub geometry_key: u64,
    /// Surface parameters from `glrt.toml` (`[materials]` and the `emissive` list).
    pub material: MaterialOverride,
    /// Every triangle of the draw is in [`crate::frame::Frame::static_world`] at the end of
    /// this frame (a renderer that draws the chunks leaves the draw out).
    pub in_static_world: bool,
    /// Where the surface's light comes from: traced, its vertex colours, or baked.
    pub lighting: SurfaceLighting,
    /// Bit `u` set: texture unit `u` of the draw holds baked light (a lightmap), not colour.
    pub light_units: u8,
}

/// How a traced surface is lit: what hash tracking (`translate::classify`) concluded from its
/// textures, vertex colours and layers. The renderer shows every surface as the rasterizer
/// would; this says which parts of that colour are light, so traced light is never counted
/// twice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SurfaceLighting {
    /// Its colour (textures times vertex colour) is its albedo; it reflects traced light (GL
    /// lit draws, and unlit surfaces whose colour is constant).
    #[default]
    Traced,
    /// Its vertex colours are lighting the program computed (a vertex-lit model: colours that
    /// change as it moves or turns, or vary over a constant material): the albedo is its
    /// colour without them, and it reflects traced light.
    VertexLit,
    /// Its light is baked: in a lightmap ([`Instance::light_units`] or a
    /// [`LayerRole::BakedLight`] layer) or in its vertex colours (an unlit static surface
    /// whose colours vary). It emits the colour the rasterizer shows, and reflects no traced
    /// light of what the bake already holds.
    Baked,
}

/// What a pass over an earlier traced draw's triangles does to that surface, from its blend
/// function and texture (`translate::classify` decides).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LayerRole {
    /// Multiplies the surface by baked light: a lightmap pass (`GL_DST_COLOR, GL_ZERO` or
    /// `GL_ZERO, GL_SRC_COLOR` of a lightmap texture).
    BakedLight,
    /// Multiplies the surface's colour by a texture that is not light: a texture pass over a
    /// lightmap base, a detail texture (`GL_DST_COLOR, GL_SRC_COLOR`: 2x modulate).
    Albedo,
    /// Adds light (`GL_ONE, GL_ONE`, `GL_SRC_ALPHA, GL_ONE`): glows, dynamic-light passes.
    Emission,
    /// Blended over the colour by its alpha (`GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA`): decals.
    Decal,
}

/// A draw of class [`DrawClass::Layer`]: one pass of a multi-pass material over the triangles
/// of an earlier traced draw of the same frame, its base. The renderer evaluates the base and
/// its layers, in program order, as one surface (the pass's own blend function and depth test
/// say how it combines, as the rasterizer would).
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Index in [`crate::frame::Frame::draws`] of the base draw.
    pub base: usize,
    /// For each triangle of this draw, the triangle of the base draw it lies on (its corners
    /// are the base triangle's corners in the same order).
    pub triangles: std::sync::Arc<[u32]>,
    /// What the pass does to the surface.
    pub role: LayerRole,
}

/// A point light recovered from dynamic-light passes ([`DrawClass::Light`]): where the
/// program centred its radial falloff, how far it reaches and how bright it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynamicLight {
    /// Eye-space position.
    pub position: [f32; 3],
    /// Display-encoded colour (0..=1) of the light at full strength: what the pass adds (or
    /// multiplies the colour under it by) at its centre.
    pub color: [f32; 3],
    /// Eye-space radius of the pass's square of falloff texture (its texture coordinates run
    /// over `[-radius/2, radius/2]` around the centre, as in Quake 3).
    pub radius: f32,
    /// The falloff's inverse-square strength, eye-space units squared: at distance `d` from
    /// the centre across [`DynamicLight::axis`] the pass's texture holds `falloff / d²` (at
    /// most 1).
    pub falloff: f32,
    /// Eye-space unit direction along which the pass projects its texture (Quake 3: the
    /// world's z): `d` is measured across it, and the colour fades with the height `h` along
    /// it (1 up to `radius / 2`, then linearly to 0 at `radius`).
    pub axis: [f32; 3],
    /// The faintest texel of the falloff texture that is not black (display units): where
    /// `falloff / d²` falls below it the pass brings nothing.
    pub floor: f32,
    /// How the pass brings its texture times `color` times the height fade, `b`: added
    /// (`GL_ONE, GL_ONE`), or times the colour under it (`GL_DST_COLOR, GL_ONE`).
    pub modulates: bool,
}

/// Most passes a traced surface keeps as layers (the base's texture units not counted); passes
/// past it stay rasterized over the traced image.
pub const MAX_LAYERS: usize = 4;

/// What OpenGL 1.x does not say about a traced surface, set per texture hash in `glrt.toml`
/// (`[materials]`, keyed by the draw's unit-0 texture; the `emissive` list). Without an entry:
/// a rough dielectric (roughness 0.8: GL 1.x surfaces are mostly diffuse with a dull
/// specular highlight), not emitting (1.0 when a texture is in the `emissive` list).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialOverride {
    /// Perceptual roughness, 0 (mirror) ..= 1 (rough).
    pub roughness: f32,
    /// 0 (dielectric) ..= 1 (metal: the texture colour tints reflections).
    pub metalness: f32,
    /// Emitted radiance as a multiple of the surface's colour (texture times vertex colour);
    /// 0: none.
    pub emissive: f32,
}

impl Default for MaterialOverride {
    fn default() -> MaterialOverride {
        MaterialOverride { roughness: 0.8, metalness: 0.0, emissive: 0.0 }
    }
}

impl MaterialOverride {
    /// The bits of the three values, to key surfaces by.
    pub fn key(&self) -> [u64; 2] {
        [u64::from(self.roughness.to_bits()) << 32 | u64::from(self.metalness.to_bits()), u64::from(self.emissive.to_bits())]
    }
}

/// The camera, recovered from the modelview of draws that are static in the world.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct View {
    /// World space to eye space. The world frame is the object space of a reference static
    /// draw, chained to another static draw's when the reference is no longer drawn.
    pub view: Mat4,
    /// The projection of the reference draw.
    pub projection: Mat4,
    /// Perspective (true) or orthographic projection.
    pub perspective: bool,
    /// Distance to the near plane.
    pub near: f32,
    /// Distance to the far plane.
    pub far: f32,
    /// Vertical field of view in radians (0 for orthographic projections).
    pub fov_y: f32,
    /// Width over height of the view volume.
    pub aspect: f32,
    /// Id of the reference instance.
    pub reference: u64,
}

impl View {
    /// The camera position in world space.
    pub fn eye(&self) -> glam::Vec3 {
        self.view.inverse().w_axis.truncate()
    }
}

/// Whether `projection` is orthographic (its last row is `(0, 0, 0, 1)`): such draws are 2D
/// overlays to hash tracking, and no sky backdrop to the tracer.
pub fn orthographic(projection: &Mat4) -> bool {
    projection.row(3) == glam::Vec4::W
}

/// A count per counted class ([`DrawClass::COUNTED`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClassCounts(pub [u64; 8]);

impl ClassCounts {
    /// Adds `n` to `class` (classes that are not counted are left out).
    pub fn add(&mut self, class: DrawClass, n: u64) {
        if let Some(i) = DrawClass::COUNTED.iter().position(|&c| c == class) {
            self.0[i] += n;
        }
    }

    /// The count of `class`.
    pub fn get(&self, class: DrawClass) -> u64 {
        DrawClass::COUNTED.iter().position(|&c| c == class).map_or(0, |i| self.0[i])
    }

    /// `{"static":1,...}`.
    fn json(&self) -> String {
        let fields: Vec<String> = DrawClass::COUNTED.iter().zip(self.0).map(|(c, n)| format!("\"{}\":{n}", c.key())).collect();
        format!("{{{}}}", fields.join(","))
    }
}

/// Per-frame statistics of hash tracking (the keys are documented in docs/hash-tracking.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Bytes of static geometry to upload this frame: the vertex data of new static instances
    /// that the static world does not hold, plus the static world's new chunks.
    pub static_upload_bytes: u64,
    /// Draws per class.
    pub classes: ClassCounts,
    /// Triangles per class.
    pub triangles: ClassCounts,
    /// Static-world chunks made this frame.
    pub static_chunks_new: usize,
    /// Static-world chunks kept from the previous frame.
    pub static_chunks_reused: usize,
    /// Static-world chunks released this frame.
    pub static_chunks_released: usize,
    /// Triangles in the static world.
    pub static_world_triangles: usize,
    /// Traced instances matched with one of the previous frame.
    pub matches_found: usize,
    /// Traced instances of the previous frame that no instance of this frame matched.
    pub matches_lost: usize,
    /// The world frame was re-established (teleport, level change, reference lost).
    pub camera_cut: bool,
    /// Bytes of vertex data of the traced draws (positions, indices, texture coordinates of
    /// unit 0): what hashing reads.
    pub vertex_bytes: u64,
    /// Time hash tracking took on this frame, in nanoseconds (the only field that differs
    /// between two runs of the same frames).
    pub classify_ns: u64,
}

impl FrameStats {
    /// One JSON object on one line, for frame number `frame` (`glrt replay --stats`).
    pub fn json_line(&self, frame: u64) -> String {
        format!(
            "{{\"frame\":{frame},\"static_upload_bytes\":{},\"classes\":{},\"triangles\":{},\"static_chunks_new\":{},\"static_chunks_reused\":{},\"static_chunks_released\":{},\"static_world_triangles\":{},\"matches_found\":{},\"matches_lost\":{},\"camera_cut\":{},\"vertex_bytes\":{},\"classify_ms\":{:.3}}}",
            self.static_upload_bytes,
            self.classes.json(),
            self.triangles.json(),
            self.static_chunks_new,
            self.static_chunks_reused,
            self.static_chunks_released,
            self.static_world_triangles,
            self.matches_found,
            self.matches_lost,
            self.camera_cut,
            self.vertex_bytes,
            self.classify_ns as f64 / 1e6
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_print_as_one_json_line() {
        let mut s = FrameStats { static_upload_bytes: 96, camera_cut: true, ..FrameStats::default() };
        s.classes.add(DrawClass::Sky, 1);
        s.classes.add(DrawClass::Ignored, 5);
        s.triangles.add(DrawClass::Static, 12);
        let line = s.json_line(7);
        assert!(line.starts_with("{\"frame\":7,\"static_upload_bytes\":96,\"classes\":{\"static\":0,\"movable\":0,\"dynamic\":0,\"translucent\":0,\"overlay\":0,\"sky\":1,\"layer\":0,\"light\":0},\"triangles\":{\"static\":12,"), "{line}");
        assert!(line.ends_with("\"camera_cut\":true,\"vertex_bytes\":0,\"classify_ms\":0.000}") && !line.contains('\n'), "{line}");
        assert_eq!((s.classes.get(DrawClass::Sky), s.classes.get(DrawClass::Ignored)), (1, 0));
    }
}

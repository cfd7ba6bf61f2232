//! The back end (`tr_backend.c`): draws a view's sorted surfaces batch by batch
//! (`RB_RenderDrawSurfList`): a batch ends when the shader, the dynamic-light flag or (for
//! shaders that cannot merge entities) the entity changes; an entity change loads the
//! entity's modelview with `glLoadMatrixf` and switches the depth range to 0..0.3 for the view
//! weapon (`RF_DEPTHHACK`). Each view begins by setting its projection, viewport and scissor
//! and clearing depth (`RB_BeginDrawingView`); 2D pictures switch to a pixel orthographic
//! projection (`RB_SetGL2D`) and batch per shader like everything else (`RB_StretchPic`).

use glam::{Mat3, Mat4, Vec3, Vec4};

use super::gl_state::{Api, GlState};
use super::level::Level;
use super::light_grid::{Dlight, EntityLight};
use super::models::Mesh;
use super::shaders::{Cull, ShaderId, Shaders, StateBits};
use super::tess::Tess;
use crate::gl::*;

/// The entity number of the world (Q3's `REFENTITYNUM_WORLD`, the last one).
pub const ENTITY_WORLD: usize = 1023;

/// A view: the camera, its projection and the part of the window it draws.
#[derive(Clone, Copy, Debug)]
pub struct ViewParms {
    pub origin: Vec3,
    /// Forward, left, up.
    pub axis: Mat3,
    pub projection: Mat4,
    /// World to eye space (the world's modelview).
    pub world: Mat4,
    /// x, y (from the bottom), width, height in pixels.
    pub viewport: [i32; 4],
    pub z_far: f32,
}

impl ViewParms {
    /// A view from `origin` along `axis` over `viewport`, with fields of view `fov` (x, y in
    /// degrees), near plane 4 (`r_znear`) and far plane `z_far`: Q3's projection
    /// (`R_SetupProjection`) and world modelview (`R_RotateForViewer`: the axes as rows, then
    /// Q3's flip from x forward, z up to GL's -z forward, y up).
    pub fn new(origin: Vec3, axis: Mat3, fov: [f32; 2], viewport: [i32; 4], z_far: f32) -> ViewParms {
        let z_near = 4.0;
        let [x, y] = fov.map(|f| z_near * (f.to_radians() / 2.0).tan());
        let depth = z_far - z_near;
        let projection = Mat4::from_cols(
            Vec4::new(z_near / x, 0.0, 0.0, 0.0),
            Vec4::new(0.0, z_near / y, 0.0, 0.0),
            Vec4::new(0.0, 0.0, -(z_far + z_near) / depth, -1.0),
            Vec4::new(0.0, 0.0, -2.0 * z_far * z_near / depth, 0.0),
        );
        let (forward, left, up) = (axis.x_axis, axis.y_axis, axis.z_axis);
        let rows = Mat4::from_cols((-left).extend(left.dot(origin)), up.extend(-up.dot(origin)), (-forward).extend(forward.dot(origin)), Vec4::W);
        ViewParms { origin, axis, projection, world: rows.transpose(), viewport, z_far }
    }
}

/// The vertical field of view that goes with horizontal `fov_x` (degrees) on a `width` ×
/// `height` view (`CG_CalcFov`).
pub fn fov_y(fov_x: f32, width: i32, height: i32) -> f32 {
    let x = width as f32 / (fov_x.to_radians() / 2.0).tan();
    2.0 * (height as f32).atan2(x).to_degrees()
}

/// What an entity draws.
#[derive(Clone, Copy, Debug)]
pub enum EntityKind {
    /// Model `model` (an index into the models), frames blended on the CPU.
    Model { model: usize, frame: usize, old_frame: usize, backlerp: f32 },
    /// A quad facing the camera.
    Sprite { radius: f32, rgba: [u8; 4] },
}

/// An entity of a view (`refEntity_t` with its lighting).
#[derive(Clone, Copy, Debug)]
pub struct RefEntity {
    pub kind: EntityKind,
    pub origin: Vec3,
    /// Forward, left, up.
    pub axis: Mat3,
    pub shader: ShaderId,
    pub light: EntityLight,
    /// The view weapon: drawn in depth range 0..0.3 (`RF_DEPTHHACK`).
    pub depth_hack: bool,
}

/// What a draw surface refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceRef {
    /// A level surface.
    World(usize),
    /// An entity's model or sprite.
    Entity(usize),
}

/// A surface to draw and its sort key.
#[derive(Clone, Copy, Debug)]
pub struct DrawSurf {
    pub sort: u64,
    pub shader: ShaderId,
    pub entity: usize,
    pub dlighted: bool,
    pub surface: SurfaceRef,
}

impl DrawSurf {
    /// A surface with the sort key of Q3's `R_AddDrawSurf`: shader order, then entity, then the
    /// dynamic-light flag.
    pub fn new(shaders: &Shaders, shader: ShaderId, entity: usize, dlighted: bool, surface: SurfaceRef) -> DrawSurf {
        let sort = (shaders.get(shader).sorted_index as u64) << 20 | (entity as u64) << 1 | u64::from(dlighted);
        DrawSurf { sort, shader, entity, dlighted, surface }
    }
}

/// What the surfaces of a view refer to.
pub struct Scene<'a> {
    pub level: &'a Level,
    pub models: &'a [Mesh],
    pub entities: &'a [RefEntity],
    /// Dynamic lights in world space.
    pub dlights: &'a [Dlight],
}

/// Calls made by the back end in a frame (`--verbose`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Batches drawn (`RB_EndSurface` with something in it).
    pub batches: usize,
    /// `glDrawElements` calls.
    pub draw_elements: usize,
    /// `glBegin`/`glEnd` pairs (the sky box).
    pub begins: usize,
}

/// The back end's state during a frame.
pub struct Backend<'a> {
    pub api: Api<'a>,
    pub state: &'a mut GlState,
    pub tess: &'a mut Tess,
    pub shaders: &'a Shaders,
    /// The dynamic light texture.
    pub dlight_image: GLuint,
    /// Scene time in seconds (shader waves and scrolls).
    pub time: f32,
    /// The view being drawn.
    pub view: ViewParms,
    /// The light of the entity being drawn (`None` for the world and 2D).
    pub light: Option<EntityLight>,
    /// Dynamic lights in the space of the surfaces being drawn.
    pub dlights: Vec<Dlight>,
    /// The 2D projection is set.
    pub projection_2d: bool,
    /// The window's size.
    pub screen: [i32; 2],
    pub counts: Counts,
}

impl Backend<'_> {
    /// Starts a batch of `shader` (`RB_BeginSurface`).
    pub fn begin_surface(&mut self, shader: ShaderId, dlighted: bool) {
        self.tess.num_vertexes = 0;
        self.tess.num_indexes = 0;
        self.tess.shader = Some(shader);
        self.tess.dlighted = dlighted;
    }

    /// Makes room for `vertexes` and `indexes` more, drawing the batch when full
    /// (`RB_CHECKOVERFLOW`).
    pub fn check_overflow(&mut self, vertexes: usize, indexes: usize) {
        if !self.tess.fits(vertexes, indexes) {
            let (shader, dlighted) = (self.tess.shader, self.tess.dlighted);
            self.end_surface();
            if let Some(shader) = shader {
                self.begin_surface(shader, dlighted);
            }
        }
    }

    /// Sets the view's projection, viewport and scissor, and clears depth inside it
    /// (`RB_BeginDrawingView`).
    fn begin_drawing_view(&mut self) {
        let gl = self.api.gl;
        self.projection_2d = false;
        let [x, y, w, h] = self.view.viewport;
        // Safety: a context is current; the matrix has 16 floats.
        unsafe {
            gl.glMatrixMode(GL_PROJECTION);
            gl.glLoadMatrixf(self.view.projection.as_ref().as_ptr());
            gl.glMatrixMode(GL_MODELVIEW);
            gl.glViewport(x, y, w, h);
            gl.glScissor(x, y, w, h);
        }
        // Depth writes must be on for the clear.
        self.state.state(self.api, StateBits::DEFAULT);
        // Safety: a context is current.
        unsafe {
            gl.glClear(GL_DEPTH_BUFFER_BIT);
        }
        self.state.forget_culling();
        // Safety: a context is current.
        unsafe { gl.glDisable(GL_CLIP_PLANE0) };
    }

    /// Draws `surfaces` (sorted by key) as view `view` (`RB_DrawSurfs`).
    pub fn render_view(&mut self, view: ViewParms, surfaces: &[DrawSurf], scene: &Scene) {
        if self.tess.num_indexes > 0 {
            self.end_surface(); // 2D drawn before this view
        }
        self.view = view;
        self.begin_drawing_view();
        let mut previous: Option<&DrawSurf> = None;
        let mut depth_range = false;
        let mut entity = None;
        for s in surfaces {
            let shader = self.shaders.get(s.shader);
            let new_batch = previous.is_none_or(|p| p.shader != s.shader || p.dlighted != s.dlighted || (p.entity != s.entity && !shader.entity_mergable));
            if new_batch {
                if previous.is_some() {
                    self.end_surface();
                }
                self.begin_surface(s.shader, s.dlighted);
            }
            if entity != Some(s.entity) {
                entity = Some(s.entity);
                let (modelview, hack) = self.enter_entity(s.entity, scene);
                // Safety: a context is current; the matrix has 16 floats.
                unsafe { self.api.gl.glLoadMatrixf(modelview.as_ref().as_ptr()) };
                if hack != depth_range {
                    depth_range = hack;
                    // Safety: a context is current.
                    unsafe { self.api.gl.glDepthRange(0.0, if hack { 0.3 } else { 1.0 }) };
                }
            }
            self.add_surface(s.surface, scene);
            previous = Some(s);
        }
        if previous.is_some() {
            self.end_surface();
        }
        // Safety: a context is current; the matrix has 16 floats.
        unsafe {
            self.api.gl.glLoadMatrixf(self.view.world.as_ref().as_ptr());
            if depth_range {
                self.api.gl.glDepthRange(0.0, 1.0);
            }
        }
    }

    /// Makes `entity` current: its light and dynamic lights; returns its modelview and
    /// whether it is drawn in the weapon's depth range (`R_RotateForEntity`).
    fn enter_entity(&mut self, entity: usize, scene: &Scene) -> (Mat4, bool) {
        if entity == ENTITY_WORLD {
            self.light = None;
            self.dlights = scene.dlights.to_vec();
            return (self.view.world, false);
        }
        let e = &scene.entities[entity];
        self.light = Some(e.light);
        self.dlights.clear(); // models are lit by dynamic lights through their light
        match e.kind {
            // Sprites are placed in world space.
            EntityKind::Sprite { .. } => (self.view.world, e.depth_hack),
            EntityKind::Model { .. } => {
                let model = Mat4::from_cols(e.axis.x_axis.extend(0.0), e.axis.y_axis.extend(0.0), e.axis.z_axis.extend(0.0), e.origin.extend(1.0));
                (self.view.world * model, e.depth_hack)
            }
        }
    }

    /// Adds a surface's vertices to the batch (the `rb_surfaceTable` functions).
    fn add_surface(&mut self, surface: SurfaceRef, scene: &Scene) {
        match surface {
            SurfaceRef::World(i) => {
                let s = &scene.level.surfaces[i];
                self.check_overflow(s.xyz.len(), s.indexes.len());
                self.tess.add_surface(s);
            }
            SurfaceRef::Entity(i) => {
                let e = &scene.entities[i];
                match e.kind {
                    EntityKind::Model { model, frame, old_frame, backlerp } => {
                        let mesh = &scene.models[model];
                        self.check_overflow(mesh.st.len(), mesh.indexes.len());
                        self.tess.add_mesh(mesh, frame, old_frame, backlerp);
                    }
                    EntityKind::Sprite { radius, rgba } => {
                        self.check_overflow(4, 6);
                        let (left, up) = (self.view.axis.y_axis * radius, self.view.axis.z_axis * radius);
                        self.tess.add_quad_stamp(e.origin, left, up, rgba);
                    }
                }
            }
        }
    }

    /// Switches to 2D: the whole window, an orthographic projection in pixels with y down,
    /// alpha blending without depth test, no culling (`RB_SetGL2D`).
    fn set_gl_2d(&mut self) {
        self.projection_2d = true;
        let [w, h] = self.screen;
        let gl = self.api.gl;
        // Safety: a context is current.
        unsafe {
            gl.glViewport(0, 0, w, h);
            gl.glScissor(0, 0, w, h);
            gl.glMatrixMode(GL_PROJECTION);
            gl.glLoadIdentity();
            gl.glOrtho(0.0, f64::from(w), f64::from(h), 0.0, 0.0, 1.0);
            gl.glMatrixMode(GL_MODELVIEW);
            gl.glLoadIdentity();
        }
        self.state.state(self.api, StateBits::PICTURE);
        self.state.cull(self.api, Cull::TwoSided);
        // Safety: a context is current.
        unsafe { gl.glDisable(GL_CLIP_PLANE0) };
    }

    /// Draws a 2D picture of `shader` over the pixel rectangle `rect` (x, y from the top,
    /// width, height) with texture coordinates `st` and colour `rgba` (`RB_StretchPic`).
    pub fn stretch_pic(&mut self, rect: [f32; 4], st: [f32; 4], shader: ShaderId, rgba: [u8; 4]) {
        if !self.projection_2d {
            self.set_gl_2d();
        }
        if self.tess.shader != Some(shader) {
            if self.tess.num_indexes > 0 {
                self.end_surface();
            }
            self.light = None;
            self.begin_surface(shader, false);
        }
        self.check_overflow(4, 6);
        self.tess.add_picture(rect, st, rgba);
    }

    /// Draws what is left in the batch (before the swap, as `RB_SwapBuffers` does).
    pub fn finish(&mut self) {
        if self.tess.num_indexes > 0 {
            self.end_surface();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q3::shaders::{Script, Stage};

    #[test]
    fn sort_keys_order_shaders_then_entities_then_dlights() {
        let mut shaders = Shaders::default();
        let a = shaders.register(Script::opaque("a", vec![Stage::base(1)]));
        let b = shaders.register(Script::opaque("b", vec![Stage::base(2)]));
        let keys = [
            DrawSurf::new(&shaders, b, 0, false, SurfaceRef::Entity(0)).sort,
            DrawSurf::new(&shaders, a, ENTITY_WORLD, true, SurfaceRef::World(0)).sort,
            DrawSurf::new(&shaders, a, ENTITY_WORLD, false, SurfaceRef::World(1)).sort,
            DrawSurf::new(&shaders, a, 3, false, SurfaceRef::Entity(3)).sort,
        ];
        let mut sorted = keys;
        sorted.sort();
        assert_eq!(sorted, [keys[3], keys[2], keys[1], keys[0]]);
    }

    #[test]
    fn views_look_along_their_forward_axis() {
        let view = ViewParms::new(Vec3::new(10.0, 20.0, 30.0), Mat3::IDENTITY, [90.0, fov_y(90.0, 320, 240)], [0, 0, 320, 240], 4096.0);
        assert!((fov_y(90.0, 320, 240) - 73.74).abs() < 0.01);
        // A point ahead (+x) is on the eye's -z axis; a point to the left (+y) at -x in eye space.
        let ahead = view.world.transform_point3(Vec3::new(110.0, 20.0, 30.0));
        assert!(ahead.abs_diff_eq(Vec3::new(0.0, 0.0, -100.0), 1e-4), "{ahead}");
        let left = view.world.transform_point3(Vec3::new(10.0, 120.0, 30.0));
        assert!(left.abs_diff_eq(Vec3::new(-100.0, 0.0, 0.0), 1e-4), "{left}");
        // 90° across: the view's edge at 45°.
        let edge = view.projection.project_point3(Vec3::new(100.0, 0.0, -100.0));
        assert!((edge.x - 1.0).abs() < 1e-4, "{edge}");
    }
}

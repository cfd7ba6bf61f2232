//! The current raster position (OpenGL 1.5 section 2.13): `glRasterPos4f` (every
//! `glRasterPos*` variant is generated from it) transforms a point like a vertex, clips it and
//! maps it to the window; `glWindowPos3f` sets it in window coordinates directly.

use glam::Vec4;

use super::super::Context;
use super::super::get::Value;
use super::super::gl::{self, GLenum, GLfloat};
use super::super::client_attrib::Restore;
use super::super::limits::MAX_TEXTURE_UNITS;
use super::super::render_mode::{RasterEvent, WindowVertex};
use crate::frame::pixels::RasterFragment;
use crate::frame::state::FogSource;

/// The current values a raster position takes along (colour, texture coordinates...).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterInputs {
    /// Primary colour (after lighting when enabled).
    pub color: [f32; 4],
    /// Secondary colour.
    pub secondary: [f32; 4],
    /// Colour index.
    pub index: f32,
    /// Texture coordinates of each unit, before the texture matrix.
    pub texcoords: [[f32; 4]; MAX_TEXTURE_UNITS],
}

impl Default for RasterInputs {
    fn default() -> RasterInputs {
        RasterInputs {
            color: [1.0; 4],
            secondary: [0.0, 0.0, 0.0, 1.0],
            index: 1.0,
            texcoords: [[0.0, 0.0, 0.0, 1.0]; MAX_TEXTURE_UNITS],
        }
    }
}

/// The current raster position and its associated data (table 6.9).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterPos {
    /// Window x, y, z and clip w.
    pub window: [f32; 4],
    /// `GL_CURRENT_RASTER_POSITION_VALID`.
    pub valid: bool,
    /// `GL_CURRENT_RASTER_DISTANCE`.
    pub distance: f32,
    /// Colour, secondary colour, index and texture coordinates (texture matrix applied).
    pub data: RasterInputs,
}

impl Default for RasterPos {
    fn default() -> RasterPos {
        RasterPos { window: [0.0, 0.0, 0.0, 1.0], valid: true, distance: 0.0, data: RasterInputs::default() }
    }
}

impl Context {
    /// The current colour, secondary colour, index and texture coordinates, which a raster
    /// position takes along (section 2.13). Lighting is the renderer's, so the colour is the
    /// current colour even while lighting is on.
    pub(crate) fn raster_inputs(&self) -> RasterInputs {
        let c = self.immediate.current();
        let [r, g, b] = c.secondary_color;
        RasterInputs { color: c.color, secondary: [r, g, b, 1.0], index: c.color_index, texcoords: c.texcoords }
    }

    /// What the fragments of a pixel operation issued now take from the raster position
    /// (sections 3.6.5 and 3.7): its texture coordinates for the units that texture, with
    /// their environments and textures, its secondary colour and its distance as the fog
    /// coordinate.
    pub(crate) fn raster_fragment(&mut self) -> RasterFragment {
        let units = self.immediate.texturing.units(&self.enables);
        let mut texture_units = self.texture_units_snapshot(units);
        for unit in texture_units.iter_mut().flatten() {
            unit.texgen = [None; 4];
        }
        let textures = if units.contains(&true) { self.texture_snapshot() } else { Vec::new() };
        let r = &self.pixels.raster;
        RasterFragment {
            texcoords: r.data.texcoords.to_vec(),
            textures,
            texture_units: texture_units.to_vec(),
            secondary: r.data.secondary,
            fog_coord: r.distance,
        }
    }

    /// Saves the raster position and its data, the part of `GL_CURRENT_BIT` this module owns
    /// (table 6.5), for `glPopAttrib`.
    pub(crate) fn save_raster_attrib(&self, out: &mut Vec<Restore>) {
        let saved = self.pixels.raster;
        out.push(Box::new(move |ctx| ctx.pixels.raster = saved));
    }

    /// Reports a raster event to selection and feedback with the current raster position
    /// (nothing is recorded while it is invalid). Returns `true` in selection and feedback
    /// mode, where pixels are not drawn.
    pub(crate) fn raster_event(&mut self, event: RasterEvent) -> bool {
        let r = &self.pixels.raster;
        let vertex = WindowVertex { window: r.window, color: r.data.color, texcoord: r.data.texcoords[0] };
        let valid = r.valid;
        self.render_mode_raster_event(event, valid.then_some(&vertex))
    }

    /// `glRasterPos4f`: the point goes through the modelview and projection matrices; if the
    /// clip volume rejects it the raster position becomes invalid, otherwise it is mapped to
    /// window coordinates with the viewport and depth range (and is a selection hit in
    /// `GL_SELECT` mode, section 5.2).
    pub fn glRasterPos4f(&mut self, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat) {
        // Lit, with generated and transformed texture coordinates, like a vertex (2.13).
        let v = self.fixed_vertex(Vec4::new(x, y, z, w), self.immediate.current());
        let eye = v.eye;
        let clip = self.transform.projection() * eye;
        let inside = (0..3).all(|i| -clip.w <= clip[i] && clip[i] <= clip.w)
            && clip.w != 0.0
            && self.inside_user_clip_planes(eye);
        if !inside {
            self.pixels.raster.valid = false;
            return;
        }
        let ndc = [clip.x / clip.w, clip.y / clip.w, clip.z / clip.w];
        let [wx, wy, wz] = self.viewport.to_window(ndc);
        // The fog coordinate when fog takes it from there (OpenGL 1.4 section 2.13).
        let distance = match self.fixed.fog.fog.source {
            FogSource::FogCoord => self.immediate.current().fog_coord,
            FogSource::FragmentDepth => eye.truncate().length(),
        };
        self.pixels.raster = RasterPos {
            window: [wx, wy, wz, clip.w],
            valid: true,
            distance,
            data: RasterInputs {
                color: v.colors.front.primary,
                secondary: v.colors.front.secondary,
                index: self.immediate.current().color_index,
                texcoords: v.texcoords,
            },
        };
        self.raster_event(RasterEvent::Position);
    }

    /// `glWindowPos3f` (section 2.13): the position is given in window coordinates; z maps
    /// into the depth range; the raster position is always valid (a selection hit in
    /// `GL_SELECT` mode).
    pub fn glWindowPos3f(&mut self, x: GLfloat, y: GLfloat, z: GLfloat) {
        let [n, f] = self.viewport.depth_range.map(|v| v as f32);
        self.pixels.raster = RasterPos {
            window: [x, y, n + z.clamp(0.0, 1.0) * (f - n), 1.0],
            valid: true,
            distance: 0.0,
            data: self.raster_inputs(),
        };
        self.raster_event(RasterEvent::Position);
    }

    pub(crate) fn query_raster(&self, pname: GLenum) -> Option<Value> {
        let r = &self.pixels.raster;
        Some(match pname {
            gl::GL_CURRENT_RASTER_POSITION => Value::floats(&r.window),
            gl::GL_CURRENT_RASTER_POSITION_VALID => Value::bool(r.valid),
            gl::GL_CURRENT_RASTER_DISTANCE => Value::float(r.distance),
            gl::GL_CURRENT_RASTER_COLOR => Value::normalized(&r.data.color),
            gl::GL_CURRENT_RASTER_SECONDARY_COLOR => Value::normalized(&r.data.secondary),
            gl::GL_CURRENT_RASTER_INDEX => Value::float(r.data.index),
            gl::GL_CURRENT_RASTER_TEXTURE_COORDS => Value::floats(&r.data.texcoords[self.active_texture_unit()]),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    fn raster(ctx: &mut Context) -> [f32; 4] {
        let mut v = [0.0f32; 4];
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_POSITION, v.as_mut_ptr()) };
        v
    }

    #[test]
    fn raster_position_goes_through_matrices_and_viewport() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(200, 100);
        ctx.glMatrixMode(gl::GL_PROJECTION);
        ctx.glOrtho(0.0, 200.0, 0.0, 100.0, -1.0, 1.0);
        ctx.glMatrixMode(gl::GL_MODELVIEW);
        ctx.glTranslatef(10.0, 5.0, 0.0);
        ctx.glRasterPos4f(20.0, 30.0, 0.5, 1.0);
        let p = raster(&mut ctx);
        assert!((p[0] - 30.0).abs() < 1e-4 && (p[1] - 35.0).abs() < 1e-4, "{p:?}");
        // z = 0.5 in eye space, ortho maps it to ndc −0.5, window 0.25.
        assert!((p[2] - 0.25).abs() < 1e-5 && p[3] == 1.0, "{p:?}");
        let mut valid = 0u8;
        unsafe { ctx.glGetBooleanv(gl::GL_CURRENT_RASTER_POSITION_VALID, &mut valid) };
        assert_eq!(valid, 1);
        ctx.glRasterPos4f(1000.0, 0.0, 0.0, 1.0);
        unsafe { ctx.glGetBooleanv(gl::GL_CURRENT_RASTER_POSITION_VALID, &mut valid) };
        assert_eq!(valid, 0);
        ctx.glWindowPos3f(3.0, 4.0, 1.0);
        assert_eq!(raster(&mut ctx), [3.0, 4.0, 1.0, 1.0]);
        assert!(ctx.pixels.raster.valid);
    }

    #[test]
    fn raster_position_is_lit_and_clipped_by_user_planes() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(100, 100);
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_LIGHT0);
        ctx.glRasterPos4f(0.0, 0.0, 0.0, 1.0);
        let mut v = [0.0f32; 4];
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_COLOR, v.as_mut_ptr()) };
        // Scene ambient 0.2 × material ambient 0.2 + light 0 diffuse 1 × material diffuse 0.8
        // × N·L 1 (default normal and light direction along +z).
        for (got, want) in v.iter().zip([0.84, 0.84, 0.84, 1.0]) {
            assert!((got - want).abs() < 1e-6, "{v:?}");
        }
        let plane = [1.0f64, 0.0, 0.0, -0.5];
        unsafe { ctx.glClipPlane(gl::GL_CLIP_PLANE0, plane.as_ptr()) };
        ctx.glEnable(gl::GL_CLIP_PLANE0);
        ctx.glRasterPos4f(0.0, 0.0, 0.0, 1.0);
        assert_eq!(ctx.query(gl::GL_CURRENT_RASTER_POSITION_VALID).unwrap().to_ints(), [0]);
    }

    #[test]
    fn raster_position_takes_the_current_values() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(100, 100);
        unsafe {
            crate::translate::dispatch::glColor4f(&mut ctx, 0.25, 0.5, 0.75, 1.0);
            crate::translate::dispatch::glSecondaryColor3f(&mut ctx, 0.5, 0.0, 0.25);
            crate::translate::dispatch::glIndexf(&mut ctx, 3.0);
            crate::translate::dispatch::glTexCoord2f(&mut ctx, 0.5, 2.0);
        }
        ctx.glMatrixMode(gl::GL_TEXTURE);
        ctx.glScalef(2.0, 1.0, 1.0);
        ctx.glRasterPos4f(0.0, 0.0, 0.0, 1.0);
        let mut v = [0.0f32; 4];
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_COLOR, v.as_mut_ptr()) };
        assert_eq!(v, [0.25, 0.5, 0.75, 1.0]);
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_SECONDARY_COLOR, v.as_mut_ptr()) };
        assert_eq!(v, [0.5, 0.0, 0.25, 1.0]);
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_INDEX, v.as_mut_ptr()) };
        assert_eq!(v[0], 3.0);
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_TEXTURE_COORDS, v.as_mut_ptr()) };
        assert_eq!(v, [1.0, 2.0, 0.0, 1.0], "texture matrix applied");
        unsafe { crate::translate::dispatch::glColor3f(&mut ctx, 1.0, 0.0, 0.0) };
        ctx.glWindowPos3f(1.0, 1.0, 0.0);
        unsafe { ctx.glGetFloatv(gl::GL_CURRENT_RASTER_COLOR, v.as_mut_ptr()) };
        assert_eq!(v, [1.0, 0.0, 0.0, 1.0]);
    }

    #[test]
    fn raster_distance_is_the_eye_distance_or_the_fog_coordinate() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(100, 100);
        let distance = |ctx: &Context| ctx.query(gl::GL_CURRENT_RASTER_DISTANCE).unwrap().to_doubles()[0];
        ctx.glRasterPos4f(0.3, 0.0, -0.4, 1.0);
        assert!((distance(&ctx) - 0.5).abs() < 1e-6);
        ctx.glFogi(gl::GL_FOG_COORD_SRC, gl::GL_FOG_COORD as i32);
        unsafe { crate::translate::dispatch::glFogCoordf(&mut ctx, 7.0) };
        ctx.glRasterPos4f(0.3, 0.0, -0.4, 1.0);
        assert_eq!(distance(&ctx), 7.0);
    }

    #[test]
    fn pixel_operations_carry_the_raster_texture_coordinates_of_texturing_units() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(100, 100);
        unsafe { crate::translate::dispatch::glTexCoord2f(&mut ctx, 0.25, 0.75) };
        ctx.glWindowPos3f(1.0, 1.0, 0.0);
        let untextured = ctx.raster_fragment();
        assert!(!untextured.textured() && untextured.textures.is_empty());
        ctx.glEnable(gl::GL_TEXTURE_2D);
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        let textured = ctx.raster_fragment();
        assert!(textured.textured());
        assert_eq!(textured.texcoords[0], [0.25, 0.75, 0.0, 1.0]);
        assert_eq!(textured.texture_units[0].map(|u| u.texgen), Some([None; 4]), "coordinates are final");
        assert_eq!(textured.texture_units[1], None);
    }
}

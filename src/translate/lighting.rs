//! Lighting state (OpenGL 1.5 section 2.14): the light sources, the light model, the front
//! and back materials, colour material and the shade model, with their commands and queries.
//! Light positions and spot directions are stored in eye space, transformed by the modelview
//! matrix current when they were specified (section 2.14.1).

use glam::{DVec3, DVec4};

use super::Context;
use super::dispatch;
use super::enums::{COLOR_MATERIAL_MODE, FACE, SHADE_MODEL};
use super::get::Value;
use super::gl::{self, GLenum, GLfloat, GLint};
use super::limits::MAX_LIGHTS;
use super::params::{Param, Shape};
use crate::frame::state::{ColorMaterial, ColorMaterialMode, Face, Light, LightModel, Lighting, Material, ShadeModel};

/// Lighting state of a context.
#[derive(Clone, Debug, PartialEq)]
pub struct LightingState {
    /// `GL_LIGHT0`... in eye space.
    pub lights: [Light; MAX_LIGHTS],
    /// The light model.
    pub model: LightModel,
    /// Front and back materials.
    pub materials: [Material; 2],
    /// `GL_COLOR_INDEXES` of the front and back materials (colour-index lighting).
    pub color_indexes: [[f32; 3]; 2],
    /// `glColorMaterial`.
    pub color_material: ColorMaterial,
    /// `glShadeModel`.
    pub shade_model: ShadeModel,
}

impl Default for LightingState {
    fn default() -> LightingState {
        LightingState {
            lights: std::array::from_fn(Light::initial),
            model: LightModel::default(),
            materials: [Material::default(); 2],
            color_indexes: [[0.0, 1.0, 1.0]; 2],
            color_material: ColorMaterial::default(),
            shade_model: ShadeModel::Smooth,
        }
    }
}

/// The index of `GL_LIGHTi`.
fn light_index(light: GLenum) -> Option<usize> {
    let i = light.checked_sub(gl::GL_LIGHT0)? as usize;
    (i < MAX_LIGHTS).then_some(i)
}

/// Parameters of `glLight*`.
fn light_shape(pname: GLenum) -> Option<Shape> {
    Some(match pname {
        gl::GL_AMBIENT | gl::GL_DIFFUSE | gl::GL_SPECULAR => Shape::COLOR,
        gl::GL_POSITION => Shape::plain(4),
        gl::GL_SPOT_DIRECTION => Shape::plain(3),
        gl::GL_SPOT_EXPONENT
        | gl::GL_SPOT_CUTOFF
        | gl::GL_CONSTANT_ATTENUATION
        | gl::GL_LINEAR_ATTENUATION
        | gl::GL_QUADRATIC_ATTENUATION => Shape::SCALAR,
        _ => return None,
    })
}

/// Parameters of `glMaterial*`.
fn material_shape(pname: GLenum) -> Option<Shape> {
    Some(match pname {
        gl::GL_SHININESS => Shape::SCALAR,
        gl::GL_COLOR_INDEXES => Shape::plain(3),
        _ if COLOR_MATERIAL_MODE.parse(pname).is_some() => Shape::COLOR,
        _ => return None,
    })
}

/// Parameters of `glLightModel*`.
fn light_model_shape(pname: GLenum) -> Option<Shape> {
    Some(match pname {
        gl::GL_LIGHT_MODEL_AMBIENT => Shape::COLOR,
        gl::GL_LIGHT_MODEL_LOCAL_VIEWER | gl::GL_LIGHT_MODEL_TWO_SIDE | gl::GL_LIGHT_MODEL_COLOR_CONTROL => {
            Shape::SCALAR
        }
        _ => return None,
    })
}

/// The material indices (0 front, 1 back) a face names.
fn face_indices(face: Face) -> &'static [usize] {
    match face {
        Face::Front => &[0],
        Face::Back => &[1],
        Face::FrontAndBack => &[0, 1],
    }
}

/// Sets a colour property of a material.
pub(crate) fn set_material_color(m: &mut Material, mode: ColorMaterialMode, c: [f32; 4]) {
    match mode {
        ColorMaterialMode::Emission => m.emission = c,
        ColorMaterialMode::Ambient => m.ambient = c,
        ColorMaterialMode::Diffuse => m.diffuse = c,
        ColorMaterialMode::Specular => m.specular = c,
        ColorMaterialMode::AmbientAndDiffuse => {
            m.ambient = c;
            m.diffuse = c;
        }
    }
}

/// `lighting` with the material properties that colour material tracks set to zero. Two
/// lighting states equal this way light every vertex alike, as those properties come from each
/// vertex's colour (section 2.14.3); draws that differ only there can merge.
pub(crate) fn without_tracked_material(lighting: &Lighting) -> Lighting {
    let mut l = lighting.clone();
    if let Some(ColorMaterial { face, mode }) = l.color_material {
        for &i in face_indices(face) {
            set_material_color(if i == 0 { &mut l.front } else { &mut l.back }, mode, [0.0; 4]);
        }
    }
    l
}

fn rgb(v: [f32; 4]) -> [f32; 3] {
    [v[0], v[1], v[2]]
}

impl Context {
    /// Sets one parameter of a light (section 2.14.1): `GL_INVALID_ENUM` for a light out of
    /// range, `GL_INVALID_VALUE` for a spot exponent outside [0, 128], a cutoff outside
    /// [0, 90] other than 180, or a negative attenuation.
    fn set_light(&mut self, light: GLenum, pname: GLenum, v: [f32; 4], command: &'static str) {
        let Some(i) = light_index(light) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        let invalid = match pname {
            gl::GL_SPOT_EXPONENT => !(0.0..=128.0).contains(&v[0]),
            gl::GL_SPOT_CUTOFF => !((0.0..=90.0).contains(&v[0]) || v[0] == 180.0),
            gl::GL_CONSTANT_ATTENUATION | gl::GL_LINEAR_ATTENUATION | gl::GL_QUADRATIC_ATTENUATION => {
                v[0].is_nan() || v[0] < 0.0
            }
            _ => false,
        };
        if invalid {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let modelview = self.transform.modelview.top();
        let l = &mut self.fixed_mut().lighting.lights[i];
        match pname {
            gl::GL_AMBIENT => l.ambient = v,
            gl::GL_DIFFUSE => l.diffuse = v,
            gl::GL_SPECULAR => l.specular = v,
            gl::GL_POSITION => l.position = (modelview * DVec4::from(v.map(f64::from))).as_vec4().to_array(),
            gl::GL_SPOT_DIRECTION => {
                let d = modelview.transform_vector3(DVec3::from(rgb(v).map(f64::from)));
                l.spot_direction = d.as_vec3().to_array();
            }
            gl::GL_SPOT_EXPONENT => l.spot_exponent = v[0],
            gl::GL_SPOT_CUTOFF => l.spot_cutoff = v[0],
            gl::GL_CONSTANT_ATTENUATION => l.attenuation[0] = v[0],
            gl::GL_LINEAR_ATTENUATION => l.attenuation[1] = v[0],
            gl::GL_QUADRATIC_ATTENUATION => l.attenuation[2] = v[0],
            _ => {}
        }
    }

    /// `glLightf`: scalar parameters only.
    pub fn glLightf(&mut self, light: GLenum, pname: GLenum, param: GLfloat) {
        self.scalar_param(light_shape(pname), param, "glLightf", |ctx, v| ctx.set_light(light, pname, v, "glLightf"));
    }

    /// `glLighti`: scalar parameters only.
    pub fn glLighti(&mut self, light: GLenum, pname: GLenum, param: GLint) {
        self.scalar_param(light_shape(pname), param, "glLighti", |ctx, v| {
            ctx.set_light(light, pname, v, "glLighti")
        });
    }

    /// `glLightfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glLightfv(&mut self, light: GLenum, pname: GLenum, params: *const GLfloat) {
        unsafe {
            self.vector_param(light_shape(pname), params, "glLightfv", |ctx, v| {
                ctx.set_light(light, pname, v, "glLightfv")
            })
        }
    }

    /// `glLightiv`: colours map linearly from the integer range.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glLightiv(&mut self, light: GLenum, pname: GLenum, params: *const GLint) {
        unsafe {
            self.vector_param(light_shape(pname), params, "glLightiv", |ctx, v| {
                ctx.set_light(light, pname, v, "glLightiv")
            })
        }
    }

    /// `glLightfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLightfv`].
    pub unsafe fn compile_glLightfv(&mut self, light: GLenum, pname: GLenum, params: *const GLfloat) {
        let n = light_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glLightfv", move |ctx, p| dispatch::exec_glLightfv(ctx, light, pname, p))
        }
    }

    /// `glLightiv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLightiv`].
    pub unsafe fn compile_glLightiv(&mut self, light: GLenum, pname: GLenum, params: *const GLint) {
        let n = light_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glLightiv", move |ctx, p| dispatch::exec_glLightiv(ctx, light, pname, p))
        }
    }

    /// The value of a light parameter (eye-space position and direction), for `glGetLight*`.
    fn light_value(&self, light: GLenum, pname: GLenum) -> Option<Value> {
        let l = &self.fixed.lighting.lights[light_index(light)?];
        Some(match pname {
            gl::GL_AMBIENT => Value::normalized(&l.ambient),
            gl::GL_DIFFUSE => Value::normalized(&l.diffuse),
            gl::GL_SPECULAR => Value::normalized(&l.specular),
            gl::GL_POSITION => Value::floats(&l.position),
            gl::GL_SPOT_DIRECTION => Value::floats(&l.spot_direction),
            gl::GL_SPOT_EXPONENT => Value::float(l.spot_exponent),
            gl::GL_SPOT_CUTOFF => Value::float(l.spot_cutoff),
            gl::GL_CONSTANT_ATTENUATION => Value::float(l.attenuation[0]),
            gl::GL_LINEAR_ATTENUATION => Value::float(l.attenuation[1]),
            gl::GL_QUADRATIC_ATTENUATION => Value::float(l.attenuation[2]),
            _ => return None,
        })
    }

    unsafe fn get_light<T: Param>(&mut self, light: GLenum, pname: GLenum, params: *mut T, command: &'static str) {
        let v = self.light_value(light, pname);
        unsafe { self.write_answer(v, params, command) }
    }

    /// `glGetLightfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetLightfv(&mut self, light: GLenum, pname: GLenum, params: *mut GLfloat) {
        unsafe { self.get_light(light, pname, params, "glGetLightfv") }
    }

    /// `glGetLightiv`: colours map linearly to the integer range.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetLightiv(&mut self, light: GLenum, pname: GLenum, params: *mut GLint) {
        unsafe { self.get_light(light, pname, params, "glGetLightiv") }
    }

    /// Sets one light-model parameter; `GL_INVALID_ENUM` for a colour control other than
    /// `GL_SINGLE_COLOR` or `GL_SEPARATE_SPECULAR_COLOR`.
    fn set_light_model(&mut self, pname: GLenum, v: [f32; 4], command: &'static str) {
        let separate = match (pname, v[0] as GLenum) {
            (gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_SINGLE_COLOR) => Some(false),
            (gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_SEPARATE_SPECULAR_COLOR) => Some(true),
            (gl::GL_LIGHT_MODEL_COLOR_CONTROL, _) => return self.set_error_in(gl::GL_INVALID_ENUM, command),
            _ => None,
        };
        let m = &mut self.fixed_mut().lighting.model;
        match pname {
            gl::GL_LIGHT_MODEL_AMBIENT => m.ambient = v,
            gl::GL_LIGHT_MODEL_LOCAL_VIEWER => m.local_viewer = v[0] != 0.0,
            gl::GL_LIGHT_MODEL_TWO_SIDE => m.two_side = v[0] != 0.0,
            _ => m.separate_specular = separate.unwrap_or(m.separate_specular),
        }
    }

    /// `glLightModelf`: scalar parameters only.
    pub fn glLightModelf(&mut self, pname: GLenum, param: GLfloat) {
        self.scalar_param(light_model_shape(pname), param, "glLightModelf", |ctx, v| {
            ctx.set_light_model(pname, v, "glLightModelf")
        });
    }

    /// `glLightModeli`: scalar parameters only.
    pub fn glLightModeli(&mut self, pname: GLenum, param: GLint) {
        self.scalar_param(light_model_shape(pname), param, "glLightModeli", |ctx, v| {
            ctx.set_light_model(pname, v, "glLightModeli")
        });
    }

    /// `glLightModelfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glLightModelfv(&mut self, pname: GLenum, params: *const GLfloat) {
        unsafe {
            self.vector_param(light_model_shape(pname), params, "glLightModelfv", |ctx, v| {
                ctx.set_light_model(pname, v, "glLightModelfv")
            })
        }
    }

    /// `glLightModeliv`: the ambient colour maps linearly from the integer range.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glLightModeliv(&mut self, pname: GLenum, params: *const GLint) {
        unsafe {
            self.vector_param(light_model_shape(pname), params, "glLightModeliv", |ctx, v| {
                ctx.set_light_model(pname, v, "glLightModeliv")
            })
        }
    }

    /// `glLightModelfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLightModelfv`].
    pub unsafe fn compile_glLightModelfv(&mut self, pname: GLenum, params: *const GLfloat) {
        let n = light_model_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glLightModelfv", move |ctx, p| dispatch::exec_glLightModelfv(ctx, pname, p))
        }
    }

    /// `glLightModeliv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glLightModeliv`].
    pub unsafe fn compile_glLightModeliv(&mut self, pname: GLenum, params: *const GLint) {
        let n = light_model_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glLightModeliv", move |ctx, p| dispatch::exec_glLightModeliv(ctx, pname, p))
        }
    }

    /// Sets one material parameter of `face` (section 2.14.2): `GL_INVALID_ENUM` for a bad
    /// face, `GL_INVALID_VALUE` for a shininess outside [0, 128]. Allowed inside
    /// `glBegin`/`glEnd`.
    fn set_material(&mut self, face: GLenum, pname: GLenum, v: [f32; 4], command: &'static str) {
        let Some(face) = FACE.parse(face) else { return self.set_error_in(gl::GL_INVALID_ENUM, command) };
        if pname == gl::GL_SHININESS && !(0.0..=128.0).contains(&v[0]) {
            return self.set_error_in(gl::GL_INVALID_VALUE, command);
        }
        let mode = COLOR_MATERIAL_MODE.parse(pname);
        if let Some(mode) = mode
            && self.immediate.primitive.is_some()
        {
            self.begin_material_change(face, mode);
        }
        let lighting = &mut self.fixed_mut().lighting;
        for &i in face_indices(face) {
            match (pname, mode) {
                (gl::GL_SHININESS, _) => lighting.materials[i].shininess = v[0],
                (gl::GL_COLOR_INDEXES, _) => lighting.color_indexes[i] = rgb(v),
                (_, Some(mode)) => set_material_color(&mut lighting.materials[i], mode, v),
                _ => {}
            }
        }
        // The properties colour material tracks keep following the current colour
        // (section 2.14.3): a `glMaterial` of them, direct or from a list, leaves no trace.
        self.apply_color_material(self.immediate.current().color);
    }

    /// `glMaterialf`: `GL_SHININESS` only.
    pub fn glMaterialf(&mut self, face: GLenum, pname: GLenum, param: GLfloat) {
        self.scalar_param(material_shape(pname), param, "glMaterialf", |ctx, v| {
            ctx.set_material(face, pname, v, "glMaterialf")
        });
    }

    /// `glMateriali`: `GL_SHININESS` only.
    pub fn glMateriali(&mut self, face: GLenum, pname: GLenum, param: GLint) {
        self.scalar_param(material_shape(pname), param, "glMateriali", |ctx, v| {
            ctx.set_material(face, pname, v, "glMateriali")
        });
    }

    /// `glMaterialfv`.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glMaterialfv(&mut self, face: GLenum, pname: GLenum, params: *const GLfloat) {
        unsafe {
            self.vector_param(material_shape(pname), params, "glMaterialfv", |ctx, v| {
                ctx.set_material(face, pname, v, "glMaterialfv")
            })
        }
    }

    /// `glMaterialiv`: colours map linearly from the integer range.
    ///
    /// # Safety
    /// `params` must point to the values of `pname`.
    pub unsafe fn glMaterialiv(&mut self, face: GLenum, pname: GLenum, params: *const GLint) {
        unsafe {
            self.vector_param(material_shape(pname), params, "glMaterialiv", |ctx, v| {
                ctx.set_material(face, pname, v, "glMaterialiv")
            })
        }
    }

    /// `glMaterialfv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMaterialfv`].
    pub unsafe fn compile_glMaterialfv(&mut self, face: GLenum, pname: GLenum, params: *const GLfloat) {
        let n = material_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glMaterialfv", move |ctx, p| dispatch::exec_glMaterialfv(ctx, face, pname, p))
        }
    }

    /// `glMaterialiv` in a display list.
    ///
    /// # Safety
    /// As [`Context::glMaterialiv`].
    pub unsafe fn compile_glMaterialiv(&mut self, face: GLenum, pname: GLenum, params: *const GLint) {
        let n = material_shape(pname).map_or(0, |s| s.count);
        unsafe {
            self.compile_params(params, n, "glMaterialiv", move |ctx, p| dispatch::exec_glMaterialiv(ctx, face, pname, p))
        }
    }

    /// The value of a material parameter of `GL_FRONT` or `GL_BACK`, for `glGetMaterial*`.
    fn material_value(&self, face: GLenum, pname: GLenum) -> Option<Value> {
        let i = match face {
            gl::GL_FRONT => 0,
            gl::GL_BACK => 1,
            _ => return None,
        };
        let m = &self.fixed.lighting.materials[i];
        Some(match pname {
            gl::GL_AMBIENT => Value::normalized(&m.ambient),
            gl::GL_DIFFUSE => Value::normalized(&m.diffuse),
            gl::GL_SPECULAR => Value::normalized(&m.specular),
            gl::GL_EMISSION => Value::normalized(&m.emission),
            gl::GL_SHININESS => Value::float(m.shininess),
            gl::GL_COLOR_INDEXES => Value::floats(&self.fixed.lighting.color_indexes[i]),
            _ => return None,
        })
    }

    unsafe fn get_material<T: Param>(&mut self, face: GLenum, pname: GLenum, params: *mut T, command: &'static str) {
        let v = self.material_value(face, pname);
        unsafe { self.write_answer(v, params, command) }
    }

    /// `glGetMaterialfv`.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetMaterialfv(&mut self, face: GLenum, pname: GLenum, params: *mut GLfloat) {
        unsafe { self.get_material(face, pname, params, "glGetMaterialfv") }
    }

    /// `glGetMaterialiv`: colours map linearly to the integer range.
    ///
    /// # Safety
    /// `params` must have room for the values of `pname`.
    pub unsafe fn glGetMaterialiv(&mut self, face: GLenum, pname: GLenum, params: *mut GLint) {
        unsafe { self.get_material(face, pname, params, "glGetMaterialiv") }
    }

    /// `glColorMaterial` (section 2.14.3); while `GL_COLOR_MATERIAL` is on, the newly named
    /// properties take the current colour at once.
    pub fn glColorMaterial(&mut self, face: GLenum, mode: GLenum) {
        match (FACE.parse(face), COLOR_MATERIAL_MODE.parse(mode)) {
            (Some(face), Some(mode)) => {
                self.fixed_mut().lighting.color_material = ColorMaterial { face, mode };
                self.apply_color_material(self.immediate.current().color);
            }
            _ => self.set_error_in(gl::GL_INVALID_ENUM, "glColorMaterial"),
        }
    }

    /// Colour material (section 2.14.3): while `GL_COLOR_MATERIAL` is on, the current colour
    /// is written to the material properties `glColorMaterial` names. Called whenever the
    /// current colour changes (`glColor*`, colour arrays), and when `GL_COLOR_MATERIAL` is
    /// enabled or `glColorMaterial` is called while it is on. An unchanged material leaves the
    /// state version alone, so repeating a colour keeps draws mergeable.
    #[inline]
    pub fn apply_color_material(&mut self, color: [f32; 4]) {
        if self.enables.is_on_const::<{ gl::GL_COLOR_MATERIAL }>() {
            self.track_color_material(color);
        }
    }

    /// [`Context::apply_color_material`] while `GL_COLOR_MATERIAL` is on.
    #[inline(never)]
    fn track_color_material(&mut self, color: [f32; 4]) {
        let lighting = &self.fixed.lighting;
        let ColorMaterial { face, mode } = lighting.color_material;
        let mut materials = lighting.materials;
        for &i in face_indices(face) {
            set_material_color(&mut materials[i], mode, color);
        }
        if materials != lighting.materials {
            self.fixed_mut().lighting.materials = materials;
        }
    }

    /// `glShadeModel`.
    pub fn glShadeModel(&mut self, mode: GLenum) {
        match SHADE_MODEL.parse(mode) {
            Some(m) => self.fixed_mut().lighting.shade_model = m,
            None => self.set_error_in(gl::GL_INVALID_ENUM, "glShadeModel"),
        }
    }

    /// Lighting queries of table 6.9 and 6.10 (the light and material parameters have their
    /// own `glGetLight*`/`glGetMaterial*`).
    pub(crate) fn query_lighting(&self, pname: GLenum) -> Option<Value> {
        let l = &self.fixed.lighting;
        Some(match pname {
            gl::GL_SHADE_MODEL => SHADE_MODEL.value(l.shade_model),
            gl::GL_LIGHT_MODEL_AMBIENT => Value::normalized(&l.model.ambient),
            gl::GL_LIGHT_MODEL_LOCAL_VIEWER => Value::bool(l.model.local_viewer),
            gl::GL_LIGHT_MODEL_TWO_SIDE => Value::bool(l.model.two_side),
            gl::GL_LIGHT_MODEL_COLOR_CONTROL => Value::int(if l.model.separate_specular {
                gl::GL_SEPARATE_SPECULAR_COLOR
            } else {
                gl::GL_SINGLE_COLOR
            }),
            gl::GL_COLOR_MATERIAL_FACE => FACE.value(l.color_material.face),
            gl::GL_COLOR_MATERIAL_PARAMETER => COLOR_MATERIAL_MODE.value(l.color_material.mode),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::dispatch;
    use crate::translate::gl;
    use crate::translate::Context;

    #[test]
    fn light_position_and_direction_use_the_modelview_at_specification() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTranslatef(1.0, 2.0, 3.0);
        ctx.glRotatef(90.0, 0.0, 0.0, 1.0);
        unsafe {
            dispatch::glLightfv(&mut ctx, gl::GL_LIGHT1, gl::GL_POSITION, [1.0f32, 0.0, 0.0, 1.0].as_ptr());
            dispatch::glLightfv(&mut ctx, gl::GL_LIGHT1, gl::GL_SPOT_DIRECTION, [1.0f32, 0.0, 0.0].as_ptr());
        }
        ctx.glLoadIdentity();
        let mut pos = [0.0f32; 4];
        let mut dir = [0.0f32; 3];
        unsafe {
            ctx.glGetLightfv(gl::GL_LIGHT1, gl::GL_POSITION, pos.as_mut_ptr());
            ctx.glGetLightfv(gl::GL_LIGHT1, gl::GL_SPOT_DIRECTION, dir.as_mut_ptr());
        }
        let close = |a: &[f32], b: &[f32]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5);
        assert!(close(&pos, &[1.0, 3.0, 3.0, 1.0]), "{pos:?}");
        assert!(close(&dir, &[0.0, 1.0, 0.0]), "{dir:?}");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn light_errors_and_integer_colours() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_SPOT_EXPONENT, 129.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_SPOT_CUTOFF, 91.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_SPOT_CUTOFF, 180.0);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_LINEAR_ATTENUATION, -1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_AMBIENT, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "a vector name takes (x, 0, 0, 0), as in Mesa");
        ctx.glLightf(gl::GL_LIGHT0 + 8, gl::GL_SPOT_EXPONENT, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        ctx.glLighti(gl::GL_LIGHT2, gl::GL_SPOT_CUTOFF, 45);
        let mut cutoff = 0.0f32;
        let mut diffuse = [0i32; 4];
        unsafe {
            ctx.glLightiv(gl::GL_LIGHT2, gl::GL_DIFFUSE, [i32::MAX, 0, i32::MIN, i32::MAX].as_ptr());
            ctx.glGetLightfv(gl::GL_LIGHT2, gl::GL_SPOT_CUTOFF, &mut cutoff);
            ctx.glGetLightiv(gl::GL_LIGHT2, gl::GL_DIFFUSE, diffuse.as_mut_ptr());
        }
        assert_eq!(cutoff, 45.0);
        assert_eq!(diffuse[0], i32::MAX);
        assert!(diffuse[1].abs() <= 1, "{diffuse:?}");
        assert_eq!(diffuse[2], i32::MIN);
        let mut d = [0.0f32; 4];
        unsafe { ctx.glGetLightfv(gl::GL_LIGHT2, gl::GL_DIFFUSE, d.as_mut_ptr()) };
        assert_eq!(d[0], 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        unsafe { ctx.glGetLightfv(gl::GL_LIGHT2, gl::GL_SHININESS, d.as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn materials_faces_and_colour_material() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            ctx.glMaterialfv(gl::GL_FRONT_AND_BACK, gl::GL_AMBIENT_AND_DIFFUSE, [0.5f32, 0.25, 0.0, 1.0].as_ptr())
        };
        ctx.glMaterialf(gl::GL_BACK, gl::GL_SHININESS, 20.0);
        ctx.glMaterialf(gl::GL_FRONT, gl::GL_SHININESS, 129.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
        ctx.glMaterialf(gl::GL_LEFT, gl::GL_SHININESS, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        let mut v = [0.0f32; 4];
        let mut shininess = [0i32; 2];
        unsafe {
            ctx.glGetMaterialfv(gl::GL_BACK, gl::GL_DIFFUSE, v.as_mut_ptr());
            ctx.glGetMaterialiv(gl::GL_BACK, gl::GL_SHININESS, shininess.as_mut_ptr());
            ctx.glGetMaterialiv(gl::GL_FRONT, gl::GL_SHININESS, shininess[1..].as_mut_ptr());
        }
        assert_eq!(v, [0.5, 0.25, 0.0, 1.0]);
        assert_eq!(shininess, [20, 0]);
        unsafe { ctx.glGetMaterialfv(gl::GL_FRONT_AND_BACK, gl::GL_DIFFUSE, v.as_mut_ptr()) };
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);

        ctx.glColorMaterial(gl::GL_FRONT, gl::GL_EMISSION);
        ctx.apply_color_material([1.0, 0.0, 0.0, 1.0]);
        assert_eq!(ctx.fixed.lighting.materials[0].emission, [0.0, 0.0, 0.0, 1.0], "off: no tracking");
        ctx.glEnable(gl::GL_COLOR_MATERIAL);
        ctx.apply_color_material([1.0, 0.0, 0.0, 1.0]);
        unsafe { ctx.glGetMaterialfv(gl::GL_FRONT, gl::GL_EMISSION, v.as_mut_ptr()) };
        assert_eq!(v, [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(ctx.fixed.lighting.materials[1].emission, [0.0, 0.0, 0.0, 1.0]);
        assert_eq!(ctx.query(gl::GL_COLOR_MATERIAL_PARAMETER).unwrap().to_ints(), [gl::GL_EMISSION as i32]);
        ctx.glColorMaterial(gl::GL_FRONT, gl::GL_SHININESS);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    #[test]
    fn material_inside_begin_end_and_in_lists() {
        let (mut ctx, _) = Context::with_recording();
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
            dispatch::glMaterialf(&mut ctx, gl::GL_FRONT, gl::GL_SHININESS, 7.0);
            dispatch::glShadeModel(&mut ctx, gl::GL_FLAT);
            dispatch::glEnd(&mut ctx);
        }
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "glShadeModel inside glBegin/glEnd");
        assert_eq!(ctx.fixed.lighting.materials[0].shininess, 7.0);

        unsafe {
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            let ambient = [0.1f32, 0.2, 0.3, 0.4];
            dispatch::glLightModelfv(&mut ctx, gl::GL_LIGHT_MODEL_AMBIENT, ambient.as_ptr());
            dispatch::glEndList(&mut ctx);
        }
        assert_eq!(ctx.fixed.lighting.model.ambient, [0.2, 0.2, 0.2, 1.0]);
        unsafe { dispatch::glCallList(&mut ctx, 1) };
        assert_eq!(ctx.query(gl::GL_LIGHT_MODEL_AMBIENT).unwrap().to_doubles()[3] as f32, 0.4);
    }

    #[test]
    fn light_model_and_shade_model() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_SEPARATE_SPECULAR_COLOR as i32);
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_TWO_SIDE, 1);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_FRONT as i32);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
        assert_eq!(
            ctx.query(gl::GL_LIGHT_MODEL_COLOR_CONTROL).unwrap().to_ints(),
            [gl::GL_SEPARATE_SPECULAR_COLOR as i32]
        );
        assert_eq!(ctx.query(gl::GL_LIGHT_MODEL_TWO_SIDE).unwrap().to_bools(), [1]);
        let mut ambient = [0i32; 4];
        unsafe { ctx.glGetIntegerv(gl::GL_LIGHT_MODEL_AMBIENT, ambient.as_mut_ptr()) };
        let expected = (0.2f64 * f64::from(i32::MAX)).round() as i32;
        assert!((ambient[0] - expected).abs() < 256, "{ambient:?}");
        assert_eq!(ambient[3], i32::MAX);
        ctx.glLightModelf(gl::GL_LIGHT_MODEL_AMBIENT, 1.0);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR, "a vector name takes (x, 0, 0, 0), as in Mesa");
        assert_eq!(ctx.query(gl::GL_LIGHT_MODEL_AMBIENT).unwrap().to_doubles(), [1.0, 0.0, 0.0, 0.0]);
        ctx.glShadeModel(gl::GL_FLAT);
        assert_eq!(ctx.query(gl::GL_SHADE_MODEL).unwrap().to_ints(), [gl::GL_FLAT as i32]);
        ctx.glShadeModel(gl::GL_LINE);
        assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    }

    fn material(ctx: &mut Context, face: gl::GLenum, pname: gl::GLenum) -> [f32; 4] {
        let mut v = [f32::NAN; 4];
        unsafe { dispatch::glGetMaterialfv(ctx, face, pname, v.as_mut_ptr()) };
        v
    }

    #[test]
    fn color_material_tracks_color_enable_and_mode_changes() {
        let (mut ctx, _) = Context::with_recording();
        let diffuse = [0.8, 0.8, 0.8, 1.0];
        unsafe { dispatch::glColor4f(&mut ctx, 0.1, 0.2, 0.3, 0.4) };
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE), diffuse, "off: no tracking");
        unsafe { dispatch::glEnable(&mut ctx, gl::GL_COLOR_MATERIAL) };
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE), [0.1, 0.2, 0.3, 0.4], "enable applies the current colour");
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_AMBIENT), [0.1, 0.2, 0.3, 0.4]);
        unsafe { dispatch::glColor3f(&mut ctx, 1.0, 0.0, 0.0) };
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_DIFFUSE), [1.0, 0.0, 0.0, 1.0], "glColor updates it");
        unsafe { dispatch::glColorMaterial(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION) };
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION), [1.0, 0.0, 0.0, 1.0], "glColorMaterial applies it");
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_EMISSION), [0.0, 0.0, 0.0, 1.0]);
        unsafe {
            dispatch::glDisable(&mut ctx, gl::GL_COLOR_MATERIAL);
            dispatch::glColor3f(&mut ctx, 0.0, 1.0, 0.0);
        }
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION), [1.0, 0.0, 0.0, 1.0]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn color_material_follows_color_arrays() {
        let (mut ctx, _) = Context::with_recording();
        let positions: [f32; 6] = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
        let colors: [u8; 12] = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255];
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_COLOR_MATERIAL);
            dispatch::glVertexPointer(&mut ctx, 2, gl::GL_FLOAT, 0, positions.as_ptr().cast());
            dispatch::glColorPointer(&mut ctx, 4, gl::GL_UNSIGNED_BYTE, 0, colors.as_ptr().cast());
            dispatch::glEnableClientState(&mut ctx, gl::GL_VERTEX_ARRAY);
            dispatch::glEnableClientState(&mut ctx, gl::GL_COLOR_ARRAY);
            dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
        }
        let draw = &ctx.frame.draws[0];
        assert_eq!(draw.vertices.color.get(1), Some([0.0, 1.0, 0.0, 1.0]), "each vertex keeps its colour");
        assert_eq!(draw.vertices.color.get(2), Some([0.0, 0.0, 1.0, 1.0]));
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE), [0.0, 0.0, 1.0, 1.0], "the last element's colour");
        unsafe {
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glArrayElement(&mut ctx, 1);
            dispatch::glEnd(&mut ctx);
        }
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_AMBIENT), [0.0, 1.0, 0.0, 1.0], "glArrayElement sets it");
        unsafe {
            dispatch::glDisableClientState(&mut ctx, gl::GL_COLOR_ARRAY);
            dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
        }
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_AMBIENT), [0.0, 1.0, 0.0, 1.0], "no colour array: the material stays");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn material_from_a_list_leaves_tracked_properties_alone() {
        let (mut ctx, _) = Context::with_recording();
        let (red, green) = ([1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]);
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_COLOR_MATERIAL);
            dispatch::glColorMaterial(&mut ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR);
            dispatch::glColor4fv(&mut ctx, green.as_ptr());
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, red.as_ptr());
            dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION, red.as_ptr());
            dispatch::glEndList(&mut ctx);
            dispatch::glCallList(&mut ctx, 1);
        }
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_SPECULAR), green, "tracked: keeps the current colour");
        assert_eq!(material(&mut ctx, gl::GL_BACK, gl::GL_SPECULAR), green);
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION), red, "untracked: set by the list");
        unsafe {
            dispatch::glDisable(&mut ctx, gl::GL_COLOR_MATERIAL);
            dispatch::glCallList(&mut ctx, 1);
        }
        assert_eq!(material(&mut ctx, gl::GL_FRONT, gl::GL_SPECULAR), red, "colour material off: the list sets it");
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}

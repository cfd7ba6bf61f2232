//! The server attribute stack (OpenGL 1.5 section 6.1.14): `glPushAttrib` saves the groups
//! its mask names, `glPopAttrib` restores them.
//!
//! Each group is a line of `GROUPS`: a bit and a saver that captures the group's state as a
//! closure putting it back ([`Restore`]). A group whose state spans several modules has one
//! line per module; savers of state other modules own are written there, with the type
//! `Saver` (`GL_CURRENT_BIT`: the current values of the vertex module and the raster
//! position of the pixel module).

use super::Context;
use super::enable::UNIT_CAPS;
use super::gl::{self, GLbitfield, GLenum};
use super::get::Value;
use super::limits::{MAX_ATTRIB_STACK_DEPTH, MAX_CLIP_PLANES, MAX_LIGHTS, MAX_TEXTURE_UNITS};

/// Puts back the state of one group as it was when saved (the client stack's type).
pub(crate) use super::client_attrib::Restore;

/// Saves the state of one group (or the part one module owns) into `out`.
pub(crate) type Saver = fn(&Context, &mut Vec<Restore>);

/// The pushed entries, each the restores of the groups of one `glPushAttrib`.
#[derive(Default)]
pub(crate) struct AttribStack(Vec<Vec<Restore>>);

/// Attribute groups and their savers (the "attribute" column of tables 6.5 to 6.28).
const GROUPS: &[(GLbitfield, Saver)] = &[
    (gl::GL_CURRENT_BIT, Context::save_current_attrib),
    (gl::GL_CURRENT_BIT, Context::save_raster_attrib),
    (gl::GL_ENABLE_BIT, save_enables),
    (gl::GL_FOG_BIT, save_fog),
    (gl::GL_LIGHTING_BIT, save_lighting),
    (gl::GL_COLOR_BUFFER_BIT, save_color_buffer),
    (gl::GL_DEPTH_BUFFER_BIT, save_depth_buffer),
    (gl::GL_STENCIL_BUFFER_BIT, save_stencil_buffer),
    (gl::GL_ACCUM_BUFFER_BIT, save_accum_buffer),
    (gl::GL_POLYGON_BIT, save_polygon),
    (gl::GL_POLYGON_STIPPLE_BIT, save_polygon_stipple),
    (gl::GL_LINE_BIT, save_line),
    (gl::GL_POINT_BIT, save_point),
    (gl::GL_SCISSOR_BIT, save_scissor),
    (gl::GL_VIEWPORT_BIT, save_viewport),
    (gl::GL_TRANSFORM_BIT, save_transform),
    (gl::GL_HINT_BIT, save_hints),
    (gl::GL_EVAL_BIT, save_eval),
    (gl::GL_LIST_BIT, save_list),
    (gl::GL_MULTISAMPLE_BIT, save_multisample),
    (gl::GL_TEXTURE_BIT, save_texture_enables),
    (gl::GL_TEXTURE_BIT, save_texture_objects),
    (gl::GL_PIXEL_MODE_BIT, save_read_buffer),
    (gl::GL_PIXEL_MODE_BIT, save_pixel_mode),
];

/// Saves global capabilities.
fn caps(ctx: &Context, caps: impl IntoIterator<Item = GLenum>) -> Restore {
    let saved: Vec<(GLenum, bool)> = caps.into_iter().map(|c| (c, ctx.enables.is_on(c))).collect();
    Box::new(move |ctx| {
        for (cap, on) in saved {
            ctx.enables.set(cap, 0, on);
        }
    })
}

/// Saves one value and how to put it back.
fn value<T: Send + 'static>(v: T, put: fn(&mut Context, T)) -> Restore {
    Box::new(move |ctx| put(ctx, v))
}

fn save_enables(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.enables.clone(), |ctx, mut e| {
        // Keep the version moving forward so cached snapshots see the change.
        e.version = ctx.enables.version + 1;
        ctx.enables = e;
    }));
}

fn save_fog(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_FOG]));
    out.push(value(ctx.fixed.fog, |ctx, v| ctx.fixed_mut().fog = v));
}

fn save_lighting(ctx: &Context, out: &mut Vec<Restore>) {
    let lights = (0..MAX_LIGHTS as GLenum).map(|i| gl::GL_LIGHT0 + i);
    out.push(caps(ctx, [gl::GL_LIGHTING, gl::GL_COLOR_MATERIAL].into_iter().chain(lights)));
    out.push(value(ctx.fixed.lighting.clone(), |ctx, v| ctx.fixed_mut().lighting = v));
}

fn save_color_buffer(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_ALPHA_TEST, gl::GL_BLEND, gl::GL_DITHER, gl::GL_INDEX_LOGIC_OP, gl::GL_COLOR_LOGIC_OP]));
    let f = &ctx.fixed;
    let saved = (f.fragment, (f.clear.color, f.clear.color_integer), f.clear.index, f.buffers.draw);
    out.push(value(saved, |ctx, (fragment, (color, color_integer), index, draw)| {
        let f = ctx.fixed_mut();
        let g = &mut f.fragment;
        (g.alpha, g.blend, g.logic_op, g.color_mask, g.index_mask) =
            (fragment.alpha, fragment.blend, fragment.logic_op, fragment.color_mask, fragment.index_mask);
        (f.clear.color, f.clear.color_integer, f.clear.index, f.buffers.draw) = (color, color_integer, index, draw);
    }));
}

fn save_depth_buffer(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_DEPTH_TEST]));
    let f = &ctx.fixed;
    out.push(value((f.fragment.depth_func, f.fragment.depth_write, f.clear.depth), |ctx, (func, write, clear)| {
        let f = ctx.fixed_mut();
        (f.fragment.depth_func, f.fragment.depth_write, f.clear.depth) = (func, write, clear);
    }));
}

fn save_stencil_buffer(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_STENCIL_TEST, gl::GL_STENCIL_TEST_TWO_SIDE_EXT]));
    out.push(value((ctx.fixed.fragment.stencil, ctx.fixed.clear.stencil), |ctx, (stencil, clear)| {
        let f = ctx.fixed_mut();
        (f.fragment.stencil, f.clear.stencil) = (stencil, clear);
    }));
}

fn save_accum_buffer(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.fixed.clear.accum, |ctx, v| ctx.fixed_mut().clear.accum = v));
}

fn save_polygon(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(
        ctx,
        [
            gl::GL_CULL_FACE,
            gl::GL_POLYGON_SMOOTH,
            gl::GL_POLYGON_STIPPLE,
            gl::GL_POLYGON_OFFSET_FILL,
            gl::GL_POLYGON_OFFSET_LINE,
            gl::GL_POLYGON_OFFSET_POINT,
        ],
    ));
    let r = &ctx.fixed.raster;
    out.push(value((r.cull_face, r.front_face, r.polygon_mode, r.offset), |ctx, (cull, front, mode, offset)| {
        let r = &mut ctx.fixed_mut().raster;
        (r.cull_face, r.front_face, r.polygon_mode, r.offset) = (cull, front, mode, offset);
    }));
}

fn save_polygon_stipple(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.fixed.raster.stipple, |ctx, v| ctx.fixed_mut().raster.stipple = v));
}

fn save_line(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_LINE_SMOOTH, gl::GL_LINE_STIPPLE]));
    let r = &ctx.fixed.raster;
    out.push(value((r.line_width, r.line_stipple), |ctx, (width, stipple)| {
        let r = &mut ctx.fixed_mut().raster;
        (r.line_width, r.line_stipple) = (width, stipple);
    }));
}

fn save_point(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_POINT_SMOOTH, gl::GL_POINT_SPRITE]));
    let r = &ctx.fixed.raster;
    out.push(value((r.point, r.sprite), |ctx, (point, sprite)| {
        let r = &mut ctx.fixed_mut().raster;
        (r.point, r.sprite) = (point, sprite);
    }));
}

fn save_scissor(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(ctx, [gl::GL_SCISSOR_TEST]));
    out.push(value(ctx.viewport.scissor, |ctx, v| ctx.viewport.scissor = v));
}

fn save_viewport(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value((ctx.viewport.viewport, ctx.viewport.depth_range), |ctx, (viewport, range)| {
        (ctx.viewport.viewport, ctx.viewport.depth_range) = (viewport, range);
    }));
}

fn save_transform(ctx: &Context, out: &mut Vec<Restore>) {
    let planes = (0..MAX_CLIP_PLANES as GLenum).map(|i| gl::GL_CLIP_PLANE0 + i);
    out.push(caps(ctx, [gl::GL_NORMALIZE, gl::GL_RESCALE_NORMAL].into_iter().chain(planes)));
    out.push(value((ctx.transform.mode, ctx.fixed.clip_planes), |ctx, (mode, planes)| {
        ctx.transform.mode = mode;
        ctx.fixed_mut().clip_planes = planes;
    }));
}

fn save_hints(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.fixed.hints, |ctx, v| ctx.fixed_mut().hints = v));
}

/// The evaluator group: map enables, `GL_AUTO_NORMAL` and the grids (the evaluator module).
fn save_eval(ctx: &Context, out: &mut Vec<Restore>) {
    let saved = ctx.capture_eval_attrib();
    out.push(Box::new(move |ctx| ctx.restore_eval_attrib(&saved)));
}

fn save_list(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.list_base(), |ctx, base| ctx.glListBase(base)));
}

fn save_multisample(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(caps(
        ctx,
        [gl::GL_MULTISAMPLE, gl::GL_SAMPLE_ALPHA_TO_COVERAGE, gl::GL_SAMPLE_ALPHA_TO_ONE, gl::GL_SAMPLE_COVERAGE],
    ));
    out.push(value(ctx.fixed.raster.sample_coverage, |ctx, v| ctx.fixed_mut().raster.sample_coverage = v));
}

fn save_texture_enables(ctx: &Context, out: &mut Vec<Restore>) {
    let units: Vec<[bool; UNIT_CAPS.len()]> =
        (0..MAX_TEXTURE_UNITS).map(|u| UNIT_CAPS.map(|c| ctx.enables.unit_on(u, c))).collect();
    out.push(value((units, ctx.texunit.active), |ctx, (units, active)| {
        for (u, on) in units.iter().enumerate() {
            for (&cap, &on) in UNIT_CAPS.iter().zip(on) {
                ctx.enables.set(cap, u, on);
            }
        }
        ctx.texunit.active = active;
    }));
}

/// Bindings, environments and coordinate generation (the texture module).
fn save_texture_objects(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.save_texture_attrib(), Context::restore_texture_attrib));
}

/// Pixel transfer, maps and zoom (the pixel module).
fn save_pixel_mode(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.save_pixel_mode_attrib(), Context::restore_pixel_mode_attrib));
}

fn save_read_buffer(ctx: &Context, out: &mut Vec<Restore>) {
    out.push(value(ctx.fixed.buffers.read, |ctx, v| ctx.fixed_mut().buffers.read = v));
}

impl Context {
    /// `glPushAttrib`: `GL_STACK_OVERFLOW` when `GL_MAX_ATTRIB_STACK_DEPTH` entries are pushed.
    /// Bits that name no group are ignored, as `GL_ALL_ATTRIB_BITS` sets them all.
    pub fn glPushAttrib(&mut self, mask: GLbitfield) {
        if self.fixed.attrib.0.len() >= MAX_ATTRIB_STACK_DEPTH {
            return self.set_error_in(gl::GL_STACK_OVERFLOW, "glPushAttrib");
        }
        let mut restores = Vec::new();
        for &(bit, save) in GROUPS {
            if mask & bit != 0 {
                save(self, &mut restores);
            }
        }
        self.fixed.attrib.0.push(restores);
    }

    /// Copies the attribute groups of `mask` from this context to `dst` (`glXCopyContext`,
    /// GLX 1.4 section 3.3.7: the same groups as `glPushAttrib`).
    pub fn copy_attributes_to(&self, dst: &mut Context, mask: GLbitfield) {
        let mut restores = Vec::new();
        for &(bit, save) in GROUPS {
            if mask & bit != 0 {
                save(self, &mut restores);
            }
        }
        for restore in restores {
            restore(dst);
        }
    }

    /// `glPopAttrib`: `GL_STACK_UNDERFLOW` when the stack is empty.
    pub fn glPopAttrib(&mut self) {
        let Some(restores) = self.fixed.attrib.0.pop() else {
            return self.set_error_in(gl::GL_STACK_UNDERFLOW, "glPopAttrib");
        };
        for restore in restores.into_iter().rev() {
            restore(self);
        }
    }

    /// `GL_ATTRIB_STACK_DEPTH`.
    pub(crate) fn query_attrib(&self, pname: GLenum) -> Option<Value> {
        (pname == gl::GL_ATTRIB_STACK_DEPTH).then(|| Value::int(self.fixed.attrib.0.len() as i64))
    }
}

#[cfg(test)]
mod tests {
    use crate::translate::Context;
    use crate::translate::gl;

    fn ints(ctx: &Context, pname: gl::GLenum) -> Vec<i32> {
        ctx.query(pname).unwrap().to_ints()
    }

    #[test]
    fn copy_attributes_copies_only_the_masked_groups() {
        let (mut src, _) = Context::with_recording();
        let (mut dst, _) = Context::with_recording();
        src.glLineWidth(5.0);
        src.glEnable(gl::GL_FOG);
        src.copy_attributes_to(&mut dst, gl::GL_LINE_BIT);
        assert_eq!(ints(&dst, gl::GL_LINE_WIDTH), vec![5]);
        assert_eq!(dst.glIsEnabled(gl::GL_FOG), 0);
        src.copy_attributes_to(&mut dst, gl::GL_ENABLE_BIT);
        assert_eq!(dst.glIsEnabled(gl::GL_FOG), 1);
    }

    #[test]
    fn stack_depth_and_errors() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPopAttrib();
        assert_eq!(ctx.glGetError(), gl::GL_STACK_UNDERFLOW);
        for _ in 0..16 {
            ctx.glPushAttrib(gl::GL_ALL_ATTRIB_BITS);
        }
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
        assert_eq!(ints(&ctx, gl::GL_ATTRIB_STACK_DEPTH), [16]);
        ctx.glPushAttrib(gl::GL_FOG_BIT);
        assert_eq!(ctx.glGetError(), gl::GL_STACK_OVERFLOW);
        assert_eq!(ints(&ctx, gl::GL_ATTRIB_STACK_DEPTH), [16]);
        ctx.glPopAttrib();
        assert_eq!(ints(&ctx, gl::GL_ATTRIB_STACK_DEPTH), [15]);
    }

    #[test]
    fn groups_restore_only_what_they_saved() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPushAttrib(gl::GL_COLOR_BUFFER_BIT | gl::GL_LIGHTING_BIT | gl::GL_VIEWPORT_BIT);
        ctx.glEnable(gl::GL_BLEND);
        ctx.glBlendFunc(gl::GL_ONE, gl::GL_ONE);
        ctx.glClearColor(1.0, 0.0, 0.0, 1.0);
        ctx.glEnable(gl::GL_LIGHT5);
        ctx.glLightf(gl::GL_LIGHT5, gl::GL_SPOT_CUTOFF, 30.0);
        ctx.glShadeModel(gl::GL_FLAT);
        ctx.glViewport(1, 2, 3, 4);
        ctx.glDepthFunc(gl::GL_ALWAYS); // depth group not pushed
        ctx.glFogf(gl::GL_FOG_DENSITY, 3.0); // fog group not pushed
        ctx.glPopAttrib();
        assert_eq!(ctx.glIsEnabled(gl::GL_BLEND), 0);
        assert_eq!(ints(&ctx, gl::GL_BLEND_DST), [gl::GL_ZERO as i32]);
        assert_eq!(ctx.query(gl::GL_COLOR_CLEAR_VALUE).unwrap().to_doubles(), [0.0; 4]);
        assert_eq!(ctx.glIsEnabled(gl::GL_LIGHT5), 0);
        let mut cutoff = 0.0f32;
        unsafe { ctx.glGetLightfv(gl::GL_LIGHT5, gl::GL_SPOT_CUTOFF, &mut cutoff) };
        assert_eq!(cutoff, 180.0);
        assert_eq!(ints(&ctx, gl::GL_SHADE_MODEL), [gl::GL_SMOOTH as i32]);
        assert_eq!(ints(&ctx, gl::GL_VIEWPORT), [0; 4]);
        assert_eq!(ints(&ctx, gl::GL_DEPTH_FUNC), [gl::GL_ALWAYS as i32]);
        assert_eq!(ctx.query(gl::GL_FOG_DENSITY).unwrap().to_doubles(), [3.0]);
    }

    #[test]
    fn enable_transform_and_nested_pushes() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glPushAttrib(gl::GL_ENABLE_BIT);
        ctx.glEnable(gl::GL_CULL_FACE);
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        ctx.glEnable(gl::GL_TEXTURE_2D);
        ctx.glPushAttrib(gl::GL_TRANSFORM_BIT | gl::GL_TEXTURE_BIT);
        ctx.glMatrixMode(gl::GL_PROJECTION);
        ctx.glEnable(gl::GL_NORMALIZE);
        ctx.glActiveTexture(gl::GL_TEXTURE0);
        ctx.glEnable(gl::GL_TEXTURE_3D);
        unsafe { ctx.glClipPlane(gl::GL_CLIP_PLANE0, [1.0, 2.0, 3.0, 4.0].as_ptr()) };
        let before = ctx.raster_snapshot();
        assert!(before.normalize);
        ctx.glPopAttrib();
        assert_eq!(ints(&ctx, gl::GL_MATRIX_MODE), [gl::GL_MODELVIEW as i32]);
        assert_eq!(ctx.glIsEnabled(gl::GL_NORMALIZE), 0);
        assert_eq!(ints(&ctx, gl::GL_ACTIVE_TEXTURE), [gl::GL_TEXTURE1 as i32]);
        assert!(!ctx.enables.unit_on(0, gl::GL_TEXTURE_3D));
        assert!(ctx.enables.unit_on(1, gl::GL_TEXTURE_2D));
        let mut eq = [9.0f64; 4];
        unsafe { ctx.glGetClipPlane(gl::GL_CLIP_PLANE0, eq.as_mut_ptr()) };
        assert_eq!(eq, [0.0; 4]);
        assert!(!ctx.raster_snapshot().normalize, "snapshot rebuilt after pop");
        ctx.glPopAttrib();
        assert_eq!(ctx.glIsEnabled(gl::GL_CULL_FACE), 0);
        assert!(!ctx.enables.unit_on(1, gl::GL_TEXTURE_2D));
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }

    #[test]
    fn current_bit_restores_current_values_and_raster_position() {
        let (mut ctx, _) = Context::with_recording();
        ctx.bind_drawable(100, 100);
        unsafe { crate::translate::dispatch::glColor4f(&mut ctx, 0.25, 0.5, 0.75, 1.0) };
        ctx.glRasterPos4f(0.5, 0.0, 0.0, 1.0);
        ctx.glPushAttrib(gl::GL_CURRENT_BIT);
        unsafe {
            crate::translate::dispatch::glColor3f(&mut ctx, 1.0, 0.0, 0.0);
            crate::translate::dispatch::glNormal3f(&mut ctx, 1.0, 0.0, 0.0);
        }
        ctx.glRasterPos4f(9.0, 0.0, 0.0, 1.0);
        assert_eq!(ints(&ctx, gl::GL_CURRENT_RASTER_POSITION_VALID), [0]);
        ctx.glPopAttrib();
        let floats = |ctx: &Context, p| ctx.query(p).unwrap().to_doubles();
        assert_eq!(floats(&ctx, gl::GL_CURRENT_COLOR), [0.25, 0.5, 0.75, 1.0]);
        assert_eq!(floats(&ctx, gl::GL_CURRENT_NORMAL), [0.0, 0.0, 1.0]);
        assert_eq!(ints(&ctx, gl::GL_CURRENT_RASTER_POSITION_VALID), [1]);
        assert_eq!(floats(&ctx, gl::GL_CURRENT_RASTER_POSITION), [75.0, 50.0, 0.5, 1.0]);
        assert_eq!(floats(&ctx, gl::GL_CURRENT_RASTER_COLOR), [0.25, 0.5, 0.75, 1.0]);
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}

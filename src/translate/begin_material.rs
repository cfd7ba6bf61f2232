//! `glMaterial` between `glBegin` and `glEnd` (OpenGL 1.5 section 2.14.2 allows it there: the
//! vertices that follow are lit with the new material). A draw is lit with one material, so a
//! batch in which one colour property of the material changes is drawn the way colour material
//! (section 2.14.3) draws: each vertex carries that property's value as its colour and the draw
//! tracks the property from the vertex colours. With lighting on and colour material off the
//! vertex colour takes no other part in lighting, so the result is the lighting equation with
//! each vertex's own material. A batch that changes two different properties (or faces) keeps
//! the material current at `glEnd` for all its vertices.

use super::Context;
use super::gl;
use crate::frame::state::{ColorMaterial, ColorMaterialMode, Face, Material};

/// What the `glMaterial` calls of the open `glBegin` did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum BeginMaterial {
    /// No colour property changed (or lighting is off, or colour material already tracks).
    #[default]
    Unchanged,
    /// One colour property changed: the vertices carry its values as their colours.
    Tracking(ColorMaterial),
    /// Several properties changed: the batch is lit with the material of `glEnd`.
    Mixed,
}

/// The value of the property `mode` of `m`; `None` for ambient-and-diffuse when the two differ.
fn property(m: &Material, mode: ColorMaterialMode) -> Option<[f32; 4]> {
    Some(match mode {
        ColorMaterialMode::Emission => m.emission,
        ColorMaterialMode::Ambient => m.ambient,
        ColorMaterialMode::Diffuse => m.diffuse,
        ColorMaterialMode::Specular => m.specular,
        ColorMaterialMode::AmbientAndDiffuse => (m.ambient == m.diffuse).then_some(m.diffuse)?,
    })
}

impl Context {
    /// The current value of the tracked property, one colour for the faces it names.
    fn tracked_value(&self, cm: ColorMaterial) -> Option<[f32; 4]> {
        let [front, back] = &self.fixed.lighting.materials;
        match cm.face {
            Face::Front => property(front, cm.mode),
            Face::Back => property(back, cm.mode),
            Face::FrontAndBack => property(front, cm.mode).filter(|&v| property(back, cm.mode) == Some(v)),
        }
    }

    /// Called by `glMaterial` between `glBegin` and `glEnd` before colour property `mode` of
    /// `face` changes: starts tracking it (the vertices so far take its old value as their
    /// colour), or gives up when another property already changed in this batch.
    pub(crate) fn begin_material_change(&mut self, face: Face, mode: ColorMaterialMode) {
        let wanted = ColorMaterial { face, mode };
        let next = match self.immediate.material {
            BeginMaterial::Tracking(t) if t == wanted => return,
            BeginMaterial::Unchanged
                if self.enables.is_on(gl::GL_LIGHTING) && !self.enables.is_on(gl::GL_COLOR_MATERIAL) =>
            {
                let before = self.tracked_value(wanted);
                match before {
                    Some(color) => {
                        self.immediate.batch.set_color(color);
                        BeginMaterial::Tracking(wanted)
                    }
                    None if self.immediate.batch.vertices.is_empty() => BeginMaterial::Tracking(wanted),
                    None => BeginMaterial::Mixed,
                }
            }
            BeginMaterial::Unchanged => return,
            _ => BeginMaterial::Mixed,
        };
        self.immediate.material = next;
    }

    /// The colour the next vertex carries while a material property is tracked.
    pub(crate) fn begin_material_color(&self) -> Option<[f32; 4]> {
        match self.immediate.material {
            BeginMaterial::Tracking(cm) => self.tracked_value(cm),
            _ => None,
        }
    }

    /// Runs `emit` (the emission of the batch of `glEnd`) with colour material tracking the
    /// property the batch changed, if any, then restores colour material; ends the tracking.
    pub(crate) fn emit_with_begin_material(&mut self, emit: impl FnOnce(&mut Context)) {
        let BeginMaterial::Tracking(cm) = std::mem::take(&mut self.immediate.material) else { return emit(self) };
        let saved = self.fixed.lighting.color_material;
        self.fixed_mut().lighting.color_material = cm;
        self.enables.set(gl::GL_COLOR_MATERIAL, 0, true);
        emit(self);
        self.enables.set(gl::GL_COLOR_MATERIAL, 0, false);
        self.fixed_mut().lighting.color_material = saved;
    }
}

#[cfg(test)]
mod tests {
    use crate::frame::state::{ColorMaterial, ColorMaterialMode, Face};
    use crate::translate::Context;
    use crate::translate::dispatch;
    use crate::translate::gl;

    fn material(ctx: &mut Context, pname: gl::GLenum) -> [f32; 4] {
        let mut v = [f32::NAN; 4];
        unsafe { dispatch::glGetMaterialfv(ctx, gl::GL_FRONT, pname, v.as_mut_ptr()) };
        v
    }

    /// A strip whose first two vertices are lit with a red emission, the last two with green.
    unsafe fn strip(ctx: &mut Context, red: &[f32; 4], green: &[f32; 4]) {
        unsafe {
            dispatch::glBegin(ctx, gl::GL_TRIANGLE_STRIP);
            dispatch::glVertex2f(ctx, 0.0, 0.0);
            dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_EMISSION, red.as_ptr());
            dispatch::glVertex2f(ctx, 0.0, 1.0);
            dispatch::glMaterialfv(ctx, gl::GL_FRONT_AND_BACK, gl::GL_EMISSION, green.as_ptr());
            dispatch::glVertex2f(ctx, 1.0, 0.0);
            dispatch::glVertex2f(ctx, 1.0, 1.0);
            dispatch::glEnd(ctx);
        }
    }

    #[test]
    fn material_changes_inside_begin_end_reach_each_vertex() {
        let (mut ctx, _) = Context::with_recording();
        let (red, green) = ([1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]);
        unsafe {
            dispatch::glEnable(&mut ctx, gl::GL_LIGHTING);
            dispatch::glColor3f(&mut ctx, 0.0, 0.0, 1.0);
            dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
            strip(&mut ctx, &red, &green);
            dispatch::glEndList(&mut ctx);
            dispatch::glCallList(&mut ctx, 1);
        }
        let draw = &ctx.frame.draws[0];
        let colors: Vec<_> = (0..4).map(|i| draw.vertices.color.get(i)).collect();
        assert_eq!(colors, [Some([0.0, 0.0, 0.0, 1.0]), Some(red), Some(green), Some(green)]);
        let lighting = draw.state.lighting.as_ref().expect("lighting is on");
        assert_eq!(lighting.color_material, Some(ColorMaterial { face: Face::FrontAndBack, mode: ColorMaterialMode::Emission }));
        assert_eq!(material(&mut ctx, gl::GL_EMISSION), green, "the last material stays current");
        assert_eq!(ctx.glIsEnabled(gl::GL_COLOR_MATERIAL), 0, "colour material is restored");
        let mut current = [0.0f32; 4];
        unsafe { dispatch::glGetFloatv(&mut ctx, gl::GL_CURRENT_COLOR, current.as_mut_ptr()) };
        assert_eq!(current, [0.0, 0.0, 1.0, 1.0], "the current colour is untouched");
    }

    #[test]
    fn two_properties_or_no_lighting_keep_one_material() {
        let (mut ctx, _) = Context::with_recording();
        let (red, green) = ([1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]);
        unsafe {
            strip(&mut ctx, &red, &green);
            dispatch::glEnable(&mut ctx, gl::GL_LIGHTING);
            dispatch::glBegin(&mut ctx, gl::GL_POINTS);
            dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
            dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT_AND_BACK, gl::GL_EMISSION, red.as_ptr());
            dispatch::glMaterialfv(&mut ctx, gl::GL_FRONT_AND_BACK, gl::GL_SPECULAR, red.as_ptr());
            dispatch::glVertex2f(&mut ctx, 1.0, 0.0);
            dispatch::glEnd(&mut ctx);
        }
        let unlit = &ctx.frame.draws[0];
        assert_eq!(unlit.vertices.color.get(0), Some([1.0; 4]), "lighting off: the vertex colour stays");
        let lit = &ctx.frame.draws[1];
        assert_eq!(lit.state.lighting.as_ref().map(|l| l.color_material), Some(None));
        assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    }
}

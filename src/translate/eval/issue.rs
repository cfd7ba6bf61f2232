//! The thin layer between evaluators and the vertex pipeline: evaluated points are issued
//! through the generated `exec_` functions of the commands section 5.1 names (`glColor4f`,
//! `glNormal3f`, `glTexCoord4f`, `glVertex4f`, `glBegin`, `glEnd`), so they are assembled,
//! selected and fed back exactly like a program's own calls.
//!
//! Evaluated values do not update the current values (section 5.1): the current colour,
//! normal and texture coordinates of unit 0 that an evaluation overrides are read back through
//! `glGet` (`GL_CURRENT_COLOR`, `GL_CURRENT_NORMAL`, `GL_CURRENT_TEXTURE_COORDS`) before the
//! vertex and issued again after it.

use super::state::EvalVertex;
use crate::translate::Context;
use crate::translate::dispatch;
use crate::translate::gl::{self, GLenum};

/// The current values an evaluated vertex overrides, to restore after it.
struct Overridden {
    color: Option<[f32; 4]>,
    normal: Option<[f32; 3]>,
    texcoord: Option<[f32; 4]>,
}

impl Context {
    /// A current value read back with `glGet`, if the state is known.
    fn current<const N: usize>(&self, pname: GLenum) -> Option<[f32; N]> {
        let values = self.query(pname)?.to_doubles();
        (values.len() >= N).then(|| std::array::from_fn(|i| values[i] as f32))
    }

    /// The current values that `v` overrides.
    fn overridden(&mut self, v: &EvalVertex) -> Overridden {
        let texcoord = v.texcoord.and_then(|_| {
            // GL_CURRENT_TEXTURE_COORDS reads the active unit; evaluators address unit 0.
            let active = std::mem::replace(&mut self.texunit.active, 0);
            let t = self.current(gl::GL_CURRENT_TEXTURE_COORDS);
            self.texunit.active = active;
            t
        });
        Overridden {
            color: v.color.and_then(|_| self.current(gl::GL_CURRENT_COLOR)),
            normal: v.normal.and_then(|_| self.current(gl::GL_CURRENT_NORMAL)),
            texcoord,
        }
    }

    /// Issues the attributes of `v` (or restores the saved current values): colour, normal,
    /// texture coordinates.
    fn issue_attributes(&mut self, color: Option<[f32; 4]>, normal: Option<[f32; 3]>, texcoord: Option<[f32; 4]>) {
        // Safety: the exec_ functions of scalar commands read no client memory.
        unsafe {
            if let Some([r, g, b, a]) = color {
                dispatch::exec_glColor4f(self, r, g, b, a);
            }
            if let Some([x, y, z]) = normal {
                dispatch::exec_glNormal3f(self, x, y, z);
            }
            if let Some([s, t, r, q]) = texcoord {
                dispatch::exec_glTexCoord4f(self, s, t, r, q);
            }
        }
    }

    /// Issues one evaluated vertex: its attributes, the vertex, then the current values
    /// it overrode.
    pub(super) fn issue_evaluated(&mut self, v: &EvalVertex) {
        let saved = self.overridden(v);
        self.issue_attributes(v.color, v.normal, v.texcoord);
        let [x, y, z, w] = v.position;
        // Safety: scalar command.
        unsafe { dispatch::exec_glVertex4f(self, x, y, z, w) };
        self.issue_attributes(saved.color, saved.normal, saved.texcoord);
    }

    /// `glBegin` of an evaluator mesh.
    pub(super) fn issue_begin(&mut self, mode: GLenum) {
        // Safety: scalar command.
        unsafe { dispatch::exec_glBegin(self, mode) }
    }

    /// `glEnd` of an evaluator mesh.
    pub(super) fn issue_end(&mut self) {
        // Safety: scalar command.
        unsafe { dispatch::exec_glEnd(self) }
    }
}

//! The thin layer between evaluators and the vertex pipeline: evaluated points are issued
//! through the generated `exec_` functions of the commands section 5.1 names (`glColor4f`,
//! `glNormal3f`, `glTexCoord4f`, `glVertex4f`, `glBegin`, `glEnd`), so they are assembled,
//! selected and fed back exactly like a program's own calls.

use super::state::EvalVertex;
use crate::translate::Context;
use crate::translate::dispatch;
use crate::translate::gl::GLenum;

impl Context {
    /// Issues one evaluated vertex: its attributes, then the vertex.
    pub(super) fn issue_evaluated(&mut self, v: &EvalVertex) {
        // Safety: the exec_ functions of scalar commands read no client memory.
        unsafe {
            if let Some([r, g, b, a]) = v.color {
                dispatch::exec_glColor4f(self, r, g, b, a);
            }
            if let Some([x, y, z]) = v.normal {
                dispatch::exec_glNormal3f(self, x, y, z);
            }
            if let Some([s, t, r, q]) = v.texcoord {
                dispatch::exec_glTexCoord4f(self, s, t, r, q);
            }
            let [x, y, z, w] = v.position;
            dispatch::exec_glVertex4f(self, x, y, z, w);
        }
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

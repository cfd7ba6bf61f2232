//! The fixed-function vertex stage on the CPU for one vertex (OpenGL 1.5 sections 2.11 to
//! 2.14): eye position, lit colours and final texture coordinates of every unit, from the
//! object position and the vertex's attributes. The raster position (section 2.13) and
//! feedback (section 5.3) use it; the renderer does the same work for drawn primitives.

use glam::Vec4;

use super::Context;
use super::immediate::CurrentAttribs;
use super::limits::MAX_TEXTURE_UNITS;
use super::vertex_lighting::LitColors;

/// A vertex after the fixed-function vertex stage, before projection and clipping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedVertex {
    /// Eye-space position (modelview times the object position).
    pub eye: Vec4,
    /// Lit (or, with lighting off, current) colours of the front and back face.
    pub colors: LitColors,
    /// Texture coordinates of each unit, generated where enabled and transformed by the
    /// unit's texture matrix.
    pub texcoords: [[f32; 4]; MAX_TEXTURE_UNITS],
}

impl Context {
    /// Runs the vertex stage for a vertex at object position `obj_pos` whose attributes are
    /// `attribs` (the current values for a raster position, the vertex's own for a batch
    /// vertex): [`Context::eye_normal`], [`Context::lit_colors`] (the current secondary colour
    /// with alpha 1, table 6.5) and [`Context::vertex_texcoord`] for each unit.
    pub fn fixed_vertex(&self, obj_pos: Vec4, attribs: &CurrentAttribs) -> FixedVertex {
        let eye = self.transform.modelview() * obj_pos;
        let normal = self.eye_normal(attribs.normal);
        let [r, g, b] = attribs.secondary_color;
        let colors = self.lit_colors(eye, normal, attribs.color, [r, g, b, 1.0]);
        let texcoords =
            std::array::from_fn(|unit| self.vertex_texcoord(unit, obj_pos, eye, normal, attribs.texcoords[unit]));
        FixedVertex { eye, colors, texcoords }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec4;

    use crate::translate::immediate::CurrentAttribs;
    use crate::translate::{Context, gl};

    #[test]
    fn vertex_stage_combines_modelview_lighting_and_texgen() {
        let (mut ctx, _) = Context::with_recording();
        // Lighting with the defaults: light 0 along +z (set under the identity), scene and
        // material ambient 0.2, material diffuse 0.8.
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_LIGHT0);
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_NORMAL_MAP as i32);
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        // Rotate 60° about y: the object normal +z turns to (sin 60°, 0, cos 60°) in eye space.
        ctx.glTranslatef(0.0, 0.0, -4.0);
        ctx.glRotatef(60.0, 0.0, 1.0, 0.0);
        let attribs = CurrentAttribs { secondary_color: [0.5, 0.5, 0.5], ..CurrentAttribs::default() };
        let v = ctx.fixed_vertex(Vec4::new(0.0, 0.0, 0.0, 1.0), &attribs);
        assert!((v.eye - Vec4::new(0.0, 0.0, -4.0, 1.0)).length() < 1e-6, "{}", v.eye);
        let c = 0.04 + 0.8 * 0.5;
        let p = v.colors.front.primary;
        assert!(p[..3].iter().all(|x| (x - c).abs() < 1e-5) && p[3] == 1.0, "{p:?}");
        assert_eq!(v.colors.front.secondary, [0.0; 4], "lit: the secondary colour is the specular sum");
        assert!((v.texcoords[0][0] - 60f32.to_radians().sin()).abs() < 1e-5, "{:?}", v.texcoords[0]);
        assert_eq!(&v.texcoords[0][1..], &[0.0, 0.0, 1.0]);
        ctx.glDisable(gl::GL_LIGHTING);
        let v = ctx.fixed_vertex(Vec4::new(0.0, 0.0, 0.0, 1.0), &attribs);
        assert_eq!(v.colors.front.secondary, [0.5, 0.5, 0.5, 1.0], "unlit: the current secondary colour");
    }
}

//! Per-vertex texture coordinates on the CPU (OpenGL 1.5 sections 2.11.2 and 2.11.4), for the
//! raster position (section 2.13) and feedback vertices (section 5.3): each coordinate whose
//! `GL_TEXTURE_GEN_*` is on is generated with the unit's mode and planes (state of
//! [`super::texture::texgen`]), the others keep the current value, and the result goes
//! through the unit's texture matrix.

use glam::{DVec4, Vec3, Vec4};

use super::Context;
use super::gl;
use super::limits::MAX_TEXTURE_UNITS;

/// `GL_TEXTURE_GEN_S` … `GL_TEXTURE_GEN_Q`, indexed like s, t, r, q.
const GEN_CAPS: [gl::GLenum; 4] =
    [gl::GL_TEXTURE_GEN_S, gl::GL_TEXTURE_GEN_T, gl::GL_TEXTURE_GEN_R, gl::GL_TEXTURE_GEN_Q];

/// `p · v` in double precision, the planes being stored as doubles.
fn plane_dot(p: [f64; 4], v: Vec4) -> f32 {
    DVec4::from_array(p).dot(v.as_dvec4()) as f32
}

/// The reflection vector `r = u − 2 n (n · u)` of section 2.11.4, `u` being the unit vector
/// from the eye to the vertex.
fn reflection(eye_pos: Vec4, n: Vec3) -> Vec3 {
    let p = if eye_pos.w != 0.0 { eye_pos.truncate() / eye_pos.w } else { eye_pos.truncate() };
    let u = p.normalize_or_zero();
    u - 2.0 * n * n.dot(u)
}

impl Context {
    /// The texture coordinates of `unit` for a vertex (object-space `obj_pos`, eye-space
    /// `eye_pos` and `eye_normal` from [`Context::eye_normal`]) whose current texture
    /// coordinates are `current`, before the texture matrix. Generated coordinates
    /// (section 2.11.4): `OBJECT_LINEAR` is the object plane times `obj_pos`; `EYE_LINEAR`
    /// the stored eye plane (already times the inverse modelview of its specification)
    /// times `eye_pos`; `SPHERE_MAP` gives `r/m + ½` for s and t with
    /// `m = 2·√(rx² + ry² + (rz + 1)²)`; `REFLECTION_MAP` the reflection vector `r`;
    /// `NORMAL_MAP` the eye normal. `unit` must be below `MAX_TEXTURE_UNITS`; other units
    /// return `current`.
    pub fn generated_texcoord(
        &self,
        unit: usize,
        obj_pos: Vec4,
        eye_pos: Vec4,
        eye_normal: Vec3,
        current: [f32; 4],
    ) -> [f32; 4] {
        let Some(unit_gen) = self.texture.texgen.get(unit) else { return current };
        let r = reflection(eye_pos, eye_normal);
        let m = 2.0 * (r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0)).sqrt();
        std::array::from_fn(|c| {
            if !self.enables.unit_on(unit, GEN_CAPS[c]) {
                return current[c];
            }
            let g = &unit_gen.coords[c];
            match g.mode {
                gl::GL_OBJECT_LINEAR => plane_dot(g.object_plane, obj_pos),
                gl::GL_EYE_LINEAR => plane_dot(g.eye_plane, eye_pos),
                // glTexGen only accepts SPHERE_MAP for s and t, REFLECTION_MAP and NORMAL_MAP
                // for s, t and r. m = 0 (r = −z) has no limit: the centre of the map.
                gl::GL_SPHERE_MAP if c < 2 => {
                    if m != 0.0 {
                        r[c] / m + 0.5
                    } else {
                        0.5
                    }
                }
                gl::GL_REFLECTION_MAP if c < 3 => r[c],
                gl::GL_NORMAL_MAP if c < 3 => eye_normal[c],
                _ => current[c],
            }
        })
    }

    /// The final texture coordinates of `unit` for a vertex: [`Context::generated_texcoord`]
    /// times the unit's texture matrix (section 2.11.2).
    pub fn vertex_texcoord(
        &self,
        unit: usize,
        obj_pos: Vec4,
        eye_pos: Vec4,
        eye_normal: Vec3,
        current: [f32; 4],
    ) -> [f32; 4] {
        let tc = self.generated_texcoord(unit, obj_pos, eye_pos, eye_normal, current);
        if unit >= MAX_TEXTURE_UNITS {
            return tc;
        }
        (self.transform.texture_matrix(unit) * Vec4::from_array(tc)).to_array()
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec3, Vec4};

    use crate::translate::{Context, gl};

    #[track_caller]
    fn assert_close(a: [f32; 4], b: [f32; 4]) {
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5), "{a:?} != {b:?}");
    }

    const CURRENT: [f32; 4] = [0.25, 0.5, 0.75, 1.0];

    #[test]
    fn disabled_generation_keeps_the_current_coordinates() {
        let (mut ctx, _) = Context::with_recording();
        let obj = Vec4::new(1.0, 2.0, 3.0, 1.0);
        assert_eq!(ctx.generated_texcoord(0, obj, obj, Vec3::Z, CURRENT), CURRENT);
        // The default mode is EYE_LINEAR with s plane (1, 0, 0, 0): only s changes.
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        assert_eq!(
            ctx.generated_texcoord(0, obj, Vec4::new(7.0, 0.0, 0.0, 1.0), Vec3::Z, CURRENT),
            [7.0, 0.5, 0.75, 1.0]
        );
        // Enables are per unit.
        assert_eq!(ctx.generated_texcoord(1, obj, Vec4::new(7.0, 0.0, 0.0, 1.0), Vec3::Z, CURRENT), CURRENT);
    }

    #[test]
    fn object_linear_and_eye_linear() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_OBJECT_LINEAR as i32);
        unsafe { ctx.glTexGenfv(gl::GL_S, gl::GL_OBJECT_PLANE, [1.0f32, 2.0, 3.0, 4.0].as_ptr()) };
        // Eye plane z = 0 given under a translation by (0, 0, −5): stored as (0, 0, 1, 5).
        ctx.glTranslatef(0.0, 0.0, -5.0);
        unsafe { ctx.glTexGenfv(gl::GL_T, gl::GL_EYE_PLANE, [0.0f32, 0.0, 1.0, 0.0].as_ptr()) };
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        ctx.glEnable(gl::GL_TEXTURE_GEN_T);
        let obj = Vec4::new(1.0, 1.0, 1.0, 1.0);
        let eye = ctx.transform.modelview() * obj;
        // s = 1 + 2 + 3 + 4; t = eye z + 5 = object z = 1.
        assert_close(ctx.generated_texcoord(0, obj, eye, Vec3::Z, CURRENT), [10.0, 1.0, 0.75, 1.0]);
    }

    #[test]
    fn sphere_reflection_and_normal_maps() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
        ctx.glTexGeni(gl::GL_T, gl::GL_TEXTURE_GEN_MODE, gl::GL_SPHERE_MAP as i32);
        for cap in [gl::GL_TEXTURE_GEN_S, gl::GL_TEXTURE_GEN_T] {
            ctx.glEnable(cap);
        }
        // Vertex straight ahead at (0, 0, −2) with a normal tilted 45° towards +x:
        // u = (0, 0, −1), n·u = −1/√2, r = u + √2·n = (1, 0, 0); m = 2·√2;
        // s = 1/(2√2) + ½, t = ½.
        let n = Vec3::new(1.0, 0.0, 1.0).normalize();
        let eye = Vec4::new(0.0, 0.0, -2.0, 1.0);
        let s = 0.5 / 2f32.sqrt() + 0.5;
        assert_close(ctx.generated_texcoord(0, eye, eye, n, CURRENT), [s, 0.5, 0.75, 1.0]);

        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_REFLECTION_MAP as i32);
        ctx.glTexGeni(gl::GL_T, gl::GL_TEXTURE_GEN_MODE, gl::GL_NORMAL_MAP as i32);
        let tc = ctx.generated_texcoord(0, eye, eye, n, CURRENT);
        assert_close(tc, [1.0, 0.0, 0.75, 1.0]);
        ctx.glTexGeni(gl::GL_R, gl::GL_TEXTURE_GEN_MODE, gl::GL_NORMAL_MAP as i32);
        ctx.glEnable(gl::GL_TEXTURE_GEN_R);
        assert_close(ctx.generated_texcoord(0, eye, eye, n, CURRENT), [1.0, 0.0, n.z, 1.0]);
    }

    #[test]
    fn texture_matrix_is_applied_after_generation() {
        let (mut ctx, _) = Context::with_recording();
        ctx.glActiveTexture(gl::GL_TEXTURE1);
        ctx.glMatrixMode(gl::GL_TEXTURE);
        ctx.glTranslatef(0.5, 0.0, 0.0);
        ctx.glScalef(2.0, 2.0, 2.0);
        ctx.glTexGeni(gl::GL_S, gl::GL_TEXTURE_GEN_MODE, gl::GL_OBJECT_LINEAR as i32);
        ctx.glEnable(gl::GL_TEXTURE_GEN_S);
        let obj = Vec4::new(3.0, 0.0, 0.0, 1.0);
        // s = x = 3, t = 0.5 (current): (2·3 + 0.5, 2·0.5, 2·0.75, 1).
        assert_close(ctx.vertex_texcoord(1, obj, obj, Vec3::Z, CURRENT), [6.5, 1.0, 1.5, 1.0]);
        // Unit 0 has neither generation nor a texture matrix.
        assert_eq!(ctx.vertex_texcoord(0, obj, obj, Vec3::Z, CURRENT), CURRENT);
    }
}

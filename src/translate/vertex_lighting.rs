//! Per-vertex RGBA lighting on the CPU (OpenGL 1.5 sections 2.11.3 and 2.14.1), for the
//! results the GL computes outside the renderer: the current raster position (section 2.13)
//! and feedback vertices (section 5.3). [`Context::eye_normal`] brings a normal to eye space;
//! [`Context::lit_colors`] evaluates the lighting equation with the state as stored by
//! [`super::lighting`] (lights already in eye space).

use glam::{DMat3, DVec3, Vec3, Vec4};

use super::Context;
use super::gl::{self, GLenum};
use super::lighting::set_material_color;
use super::limits::MAX_LIGHTS;
use crate::frame::state::{ColorMaterialMode, Face, Light, Material};

/// The primary and secondary colour of one face of a vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceColors {
    /// Primary colour, clamped to [0, 1].
    pub primary: [f32; 4],
    /// Secondary colour, clamped to [0, 1].
    pub secondary: [f32; 4],
}

/// The colours of a vertex after lighting: the front colours, and the back colours that
/// back-facing polygons take (equal to the front ones unless two-sided lighting is on).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitColors {
    /// Colours of points, lines and front-facing polygons.
    pub front: FaceColors,
    /// Colours of back-facing polygons.
    pub back: FaceColors,
}

/// The unit vector from point `p1` to point `p2` (homogeneous), with the rules of section
/// 2.14.1 for points at infinity (`w = 0`): towards `p2`'s direction when only `p2` is at
/// infinity, against `p1`'s when only `p1` is, along `p2 − p1` when both are.
fn unit_between(p1: Vec4, p2: Vec4) -> Vec3 {
    let v = match (p1.w != 0.0, p2.w != 0.0) {
        (true, true) => p2.truncate() / p2.w - p1.truncate() / p1.w,
        (true, false) => p2.truncate(),
        (false, true) => -p1.truncate(),
        (false, false) => p2.truncate() - p1.truncate(),
    };
    v.normalize_or_zero()
}

/// `u ⊙ v` of section 2.14.1: the dot product, or 0 when it is negative.
fn pos_dot(u: Vec3, v: Vec3) -> f32 {
    u.dot(v).max(0.0)
}

/// Component-wise product of the RGB of two colours.
fn rgb_mul(a: [f32; 4], b: [f32; 4]) -> Vec3 {
    Vec3::new(a[0] * b[0], a[1] * b[1], a[2] * b[2])
}

/// Clamps a colour component to [0, 1]; NaN (from degenerate input) becomes 0.
fn clamp01(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

/// The attenuation factor of a positional light at distance `d` (infinite for a vertex at
/// infinity): `1 / (k0 + k1·d + k2·d²)`, a term with a zero coefficient dropping out.
fn attenuation(k: [f32; 3], d: f32) -> f32 {
    let term = |k: f32, x: f32| if k == 0.0 { 0.0 } else { k * x };
    1.0 / (k[0] + term(k[1], d) + term(k[2], d * d))
}

/// The spotlight factor of section 2.14.1 for a light whose unit vector to the vertex is
/// `to_vertex`. The equation has no condition on the light's w, so it also applies to
/// directional lights (Mesa skips it for them).
fn spot(light: &Light, to_vertex: Vec3) -> f32 {
    if light.spot_cutoff == 180.0 {
        return 1.0;
    }
    let d = pos_dot(to_vertex, Vec3::from_array(light.spot_direction).normalize_or_zero());
    if d >= light.spot_cutoff.to_radians().cos() { d.powf(light.spot_exponent) } else { 0.0 }
}

/// What the light model contributes to the lighting of one vertex.
struct Scene {
    /// Eye-space vertex position.
    pos: Vec4,
    /// Scene ambient colour (`GL_LIGHT_MODEL_AMBIENT`).
    ambient: [f32; 4],
    /// `GL_LIGHT_MODEL_LOCAL_VIEWER`.
    local_viewer: bool,
    /// `GL_SEPARATE_SPECULAR_COLOR`.
    separate_specular: bool,
}

impl Scene {
    /// The colours of one face with material `m` and normal `n` (already flipped for the
    /// back face), lit by `lights`.
    fn shade<'a>(&self, m: &Material, n: Vec3, lights: impl Iterator<Item = &'a Light>) -> FaceColors {
        let eye_dir = if self.local_viewer { unit_between(self.pos, Vec4::W) } else { Vec3::Z };
        let mut primary = Vec3::from_slice(&m.emission) + rgb_mul(m.ambient, self.ambient);
        let mut specular = Vec3::ZERO;
        for light in lights {
            let position = Vec4::from_array(light.position);
            let to_light = unit_between(self.pos, position);
            let att = if position.w == 0.0 {
                1.0
            } else if self.pos.w == 0.0 {
                attenuation(light.attenuation, f32::INFINITY)
            } else {
                attenuation(
                    light.attenuation,
                    (position.truncate() / position.w - self.pos.truncate() / self.pos.w).length(),
                )
            };
            let factor = att * spot(light, -to_light);
            if factor == 0.0 {
                continue;
            }
            let diffuse = pos_dot(n, to_light);
            primary += factor * (rgb_mul(m.ambient, light.ambient) + diffuse * rgb_mul(m.diffuse, light.diffuse));
            if diffuse != 0.0 {
                let half = (to_light + eye_dir).normalize_or_zero();
                specular += factor * pos_dot(n, half).powf(m.shininess) * rgb_mul(m.specular, light.specular);
            }
        }
        let (primary, secondary) =
            if self.separate_specular { (primary, specular) } else { (primary + specular, Vec3::ZERO) };
        let rgba = |c: Vec3, a: f32| [c.x, c.y, c.z, a].map(clamp01);
        FaceColors { primary: rgba(primary, m.diffuse[3]), secondary: rgba(secondary, 0.0) }
    }
}

/// `m` with the material property `mode` replaced by the colour `c` (section 2.14.3).
fn track_color(mut m: Material, mode: ColorMaterialMode, c: [f32; 4]) -> Material {
    set_material_color(&mut m, mode, c);
    m
}

impl Context {
    /// The eye-space normal of a vertex with object-space normal `normal` (section 2.11.3):
    /// `normal` times the upper-left 3×3 of the inverse modelview matrix, then normalized
    /// when `GL_NORMALIZE` is on, otherwise scaled by `1 / ‖row 3 of that matrix‖` when
    /// `GL_RESCALE_NORMAL` is on.
    pub fn eye_normal(&self, normal: [f32; 3]) -> Vec3 {
        let inverse = self.transform.modelview.top().inverse();
        // (nx ny nz) M⁻¹ as a row vector is (M⁻¹)ᵀ n as a column vector.
        let n = DMat3::from_mat4(inverse).transpose() * DVec3::from(normal.map(f64::from));
        let n = if self.enables.is_on(gl::GL_NORMALIZE) {
            n.normalize_or_zero()
        } else if self.enables.is_on(gl::GL_RESCALE_NORMAL) {
            n / inverse.row(2).truncate().length()
        } else {
            n
        };
        n.as_vec3()
    }

    /// The colours of a vertex at eye-space position `eye_pos` with eye-space normal
    /// `eye_normal` (from [`Context::eye_normal`]) and current colours `color` and
    /// `secondary` (section 2.14.1). With `GL_LIGHTING` off these are the given colours,
    /// clamped. Otherwise, for each face, the emission plus the material ambient times the
    /// scene ambient, plus for each enabled light its attenuation (positional lights) times
    /// its spot factor times the ambient, diffuse (`n ⊙ VP`) and specular (`(n ⊙ ĥ)^shininess`,
    /// with `ĥ` from the eye position or the z axis, see `GL_LIGHT_MODEL_LOCAL_VIEWER`)
    /// terms; the specular sum goes to the secondary colour under
    /// `GL_SEPARATE_SPECULAR_COLOR`. Alpha is the material diffuse alpha (secondary alpha 0).
    /// With `GL_COLOR_MATERIAL` on, `color` replaces the tracked material property; the back
    /// face uses the back material and the negated normal when two-sided lighting is on.
    pub fn lit_colors(&self, eye_pos: Vec4, eye_normal: Vec3, color: [f32; 4], secondary: [f32; 4]) -> LitColors {
        if !self.enables.is_on(gl::GL_LIGHTING) {
            let front = FaceColors { primary: color.map(clamp01), secondary: secondary.map(clamp01) };
            return LitColors { front, back: front };
        }
        let l = &self.fixed.lighting;
        let scene = Scene {
            pos: eye_pos,
            ambient: l.model.ambient,
            local_viewer: l.model.local_viewer,
            separate_specular: l.model.separate_specular,
        };
        let material = |i: usize| {
            let cm = l.color_material;
            let tracked = match cm.face {
                Face::Front => i == 0,
                Face::Back => i == 1,
                Face::FrontAndBack => true,
            };
            let m = l.materials[i];
            if tracked && self.enables.is_on(gl::GL_COLOR_MATERIAL) { track_color(m, cm.mode, color) } else { m }
        };
        let lights =
            || (0..MAX_LIGHTS).filter(|&i| self.enables.is_on(gl::GL_LIGHT0 + i as GLenum)).map(|i| &l.lights[i]);
        let front = scene.shade(&material(0), eye_normal, lights());
        let back = if l.model.two_side { scene.shade(&material(1), -eye_normal, lights()) } else { front };
        LitColors { front, back }
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec3, Vec4};

    use super::{FaceColors, LitColors};
    use crate::translate::{Context, gl};

    const WHITE: [f32; 4] = [1.0; 4];
    const BLACK: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

    fn close(a: [f32; 4], b: [f32; 4]) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5)
    }

    #[track_caller]
    fn assert_color(a: [f32; 4], b: [f32; 4]) {
        assert!(close(a, b), "{a:?} != {b:?}");
    }

    /// Lighting on, light 0 on, no scene ambient, material ambient 0.
    fn lit_context() -> Context {
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_LIGHT0);
        unsafe {
            ctx.glLightModelfv(gl::GL_LIGHT_MODEL_AMBIENT, BLACK.as_ptr());
            ctx.glMaterialfv(gl::GL_FRONT_AND_BACK, gl::GL_AMBIENT, BLACK.as_ptr());
        }
        ctx
    }

    fn light(ctx: &mut Context, pname: gl::GLenum, v: &[f32]) {
        unsafe { ctx.glLightfv(gl::GL_LIGHT0, pname, v.as_ptr()) };
    }

    fn material(ctx: &mut Context, face: gl::GLenum, pname: gl::GLenum, v: [f32; 4]) {
        unsafe { ctx.glMaterialfv(face, pname, v.as_ptr()) };
    }

    fn front(ctx: &Context, pos: Vec4, n: Vec3) -> FaceColors {
        ctx.lit_colors(pos, n, WHITE, BLACK).front
    }

    #[test]
    fn lighting_off_passes_the_current_colours_through() {
        let (mut ctx, _) = Context::with_recording();
        let lit = ctx.lit_colors(Vec4::W, Vec3::Z, [0.25, 1.5, -1.0, 0.5], [0.1, 0.2, 0.3, 0.0]);
        let expected = FaceColors { primary: [0.25, 1.0, 0.0, 0.5], secondary: [0.1, 0.2, 0.3, 0.0] };
        assert_eq!(lit, LitColors { front: expected, back: expected });
        ctx.glEnable(gl::GL_LIGHTING);
        assert_ne!(ctx.lit_colors(Vec4::W, Vec3::Z, [0.25, 1.5, -1.0, 0.5], BLACK).front, expected);
    }

    #[test]
    fn directional_light_at_60_degrees() {
        // Defaults: scene ambient 0.2, material ambient 0.2, diffuse 0.8; light 0 diffuse 1,
        // along +z. A normal at 60° to +z: 0.2·0.2 + 0.8·cos 60° = 0.44; no specular
        // (material specular 0). The light position's w = 0: no attenuation even if set.
        let (mut ctx, _) = Context::with_recording();
        ctx.glEnable(gl::GL_LIGHTING);
        ctx.glEnable(gl::GL_LIGHT0);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_QUADRATIC_ATTENUATION, 5.0);
        let n = Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
        let c = ctx.lit_colors(Vec4::new(3.0, 1.0, -7.0, 1.0), n, WHITE, BLACK);
        assert_color(c.front.primary, [0.44, 0.44, 0.44, 1.0]);
        assert_eq!(c.front.secondary, [0.0; 4]);
        // Facing away: ambient only.
        assert_color(front(&ctx, Vec4::W, -n).primary, [0.04, 0.04, 0.04, 1.0]);
        // Alpha is the material diffuse alpha.
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, [0.8, 0.8, 0.8, 0.25]);
        assert_eq!(front(&ctx, Vec4::W, n).primary[3], 0.25);
    }

    #[test]
    fn positional_light_with_quadratic_attenuation() {
        // Light at (0, 0, 2), vertex at the origin, normal +z: diffuse 0.8 · 1 over
        // (1 + 0.5·2 + 0.25·4) = 3, light ambient 0.3 · material ambient 0.5 also attenuated.
        let mut ctx = lit_context();
        light(&mut ctx, gl::GL_POSITION, &[0.0, 0.0, 2.0, 1.0]);
        light(&mut ctx, gl::GL_AMBIENT, &[0.3, 0.3, 0.3, 1.0]);
        material(&mut ctx, gl::GL_FRONT, gl::GL_AMBIENT, [0.5, 0.5, 0.5, 1.0]);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_LINEAR_ATTENUATION, 0.5);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_QUADRATIC_ATTENUATION, 0.25);
        let v = (0.8 + 0.15) / 3.0;
        assert_color(front(&ctx, Vec4::new(0.0, 0.0, 0.0, 1.0), Vec3::Z).primary, [v, v, v, 1.0]);
        // The same vertex in homogeneous form (w = 2) is at the same place.
        assert_color(front(&ctx, Vec4::new(0.0, 0.0, 0.0, 2.0), Vec3::Z).primary, [v, v, v, 1.0]);
    }

    #[test]
    fn spotlight_inside_and_outside_the_cutoff() {
        // Light at (0, 0, 1) pointing down −z, cutoff 30°, exponent 2. The vertex (x, 0, 0)
        // with normal +z is seen at angle a from the axis, tan a = x; diffuse is cos a.
        let mut ctx = lit_context();
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, WHITE);
        light(&mut ctx, gl::GL_POSITION, &[0.0, 0.0, 1.0, 1.0]);
        light(&mut ctx, gl::GL_SPOT_DIRECTION, &[0.0, 0.0, -2.0]);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_SPOT_CUTOFF, 30.0);
        ctx.glLightf(gl::GL_LIGHT0, gl::GL_SPOT_EXPONENT, 2.0);
        // Inside: 20°: spot cos² 20°, diffuse cos 20°.
        let a = 20f32.to_radians();
        let v = a.cos().powi(3);
        assert_color(front(&ctx, Vec4::new(a.tan(), 0.0, 0.0, 1.0), Vec3::Z).primary, [v, v, v, 1.0]);
        // Outside: 40°: black.
        let a = 40f32.to_radians();
        assert_color(front(&ctx, Vec4::new(a.tan(), 0.0, 0.0, 1.0), Vec3::Z).primary, BLACK);
    }

    #[test]
    fn specular_with_and_without_local_viewer() {
        // Directional light along +z, material specular 1 shininess 4, diffuse 0. Vertex at
        // (1, 0, -1) with normal +z.
        let mut ctx = lit_context();
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, BLACK);
        material(&mut ctx, gl::GL_FRONT, gl::GL_SPECULAR, WHITE);
        ctx.glMaterialf(gl::GL_FRONT, gl::GL_SHININESS, 4.0);
        let (pos, n) = (Vec4::new(1.0, 0.0, -1.0, 1.0), Vec3::Z);
        // Infinite viewer: h = (0,0,1) + (0,0,1): n·ĥ = 1.
        assert_color(front(&ctx, pos, n).primary, WHITE);
        // Local viewer: h = (0,0,1) + (−1,0,1)/√2, n·ĥ = cos 22.5°.
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_LOCAL_VIEWER, 1);
        let v = 22.5f32.to_radians().cos().powi(4);
        assert_color(front(&ctx, pos, n).primary, [v, v, v, 1.0]);
        // No specular where the light is behind the surface, whatever ĥ.
        assert_color(front(&ctx, pos, Vec3::new(-1.0, 0.0, -0.01).normalize()).primary, BLACK);
    }

    #[test]
    fn separate_specular_colour() {
        let mut ctx = lit_context();
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, [0.5, 0.0, 0.0, 0.5]);
        material(&mut ctx, gl::GL_FRONT, gl::GL_SPECULAR, [0.0, 0.25, 0.0, 1.0]);
        material(&mut ctx, gl::GL_FRONT, gl::GL_EMISSION, [0.0, 0.0, 0.125, 1.0]);
        let single = front(&ctx, Vec4::W, Vec3::Z);
        assert_color(single.primary, [0.5, 0.25, 0.125, 0.5]);
        assert_eq!(single.secondary, [0.0; 4]);
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_COLOR_CONTROL, gl::GL_SEPARATE_SPECULAR_COLOR as i32);
        let separate = front(&ctx, Vec4::W, Vec3::Z);
        assert_color(separate.primary, [0.5, 0.0, 0.125, 0.5]);
        assert_color(separate.secondary, [0.0, 0.25, 0.0, 0.0]);
    }

    #[test]
    fn two_sided_back_colour_uses_the_back_material_and_flipped_normal() {
        let mut ctx = lit_context();
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, [1.0, 0.0, 0.0, 1.0]);
        material(&mut ctx, gl::GL_BACK, gl::GL_DIFFUSE, [0.0, 1.0, 0.0, 1.0]);
        // The normal faces away from the light (along +z): the front is dark.
        let c = ctx.lit_colors(Vec4::W, -Vec3::Z, WHITE, BLACK);
        assert_color(c.front.primary, BLACK);
        assert_eq!(c.back, c.front, "one-sided: back = front");
        ctx.glLightModeli(gl::GL_LIGHT_MODEL_TWO_SIDE, 1);
        let c = ctx.lit_colors(Vec4::W, -Vec3::Z, WHITE, BLACK);
        assert_color(c.front.primary, BLACK);
        assert_color(c.back.primary, [0.0, 1.0, 0.0, 1.0]);
    }

    #[test]
    fn colour_material_ambient_and_diffuse() {
        // Scene ambient 0.2 (default) restored; the colour (0.5, 1, 0, 0.75) becomes the
        // ambient and diffuse material: 0.2·c + 1·c·cos 0.
        let mut ctx = lit_context();
        unsafe { ctx.glLightModelfv(gl::GL_LIGHT_MODEL_AMBIENT, [0.2f32, 0.2, 0.2, 1.0].as_ptr()) };
        let color = [0.5, 1.0, 0.0, 0.75];
        let off = ctx.lit_colors(Vec4::W, Vec3::Z, color, BLACK).front.primary;
        assert_color(off, [0.8, 0.8, 0.8, 1.0]);
        ctx.glEnable(gl::GL_COLOR_MATERIAL);
        let on = ctx.lit_colors(Vec4::W, Vec3::Z, color, BLACK).front.primary;
        assert_color(on, [0.6, 1.0, 0.0, 0.75]);
        // Tracking only the back face leaves the front material alone.
        ctx.glColorMaterial(gl::GL_BACK, gl::GL_AMBIENT_AND_DIFFUSE);
        material(&mut ctx, gl::GL_FRONT, gl::GL_AMBIENT, BLACK);
        material(&mut ctx, gl::GL_FRONT, gl::GL_DIFFUSE, [0.8, 0.8, 0.8, 1.0]);
        assert_color(ctx.lit_colors(Vec4::W, Vec3::Z, color, BLACK).front.primary, off);
    }

    #[test]
    fn eye_normal_transform_normalize_and_rescale() {
        let (mut ctx, _) = Context::with_recording();
        // Non-uniform scale (2, 1, 1): the normal (1, 1, 0) becomes (1/2, 1, 0).
        ctx.glScalef(2.0, 1.0, 1.0);
        assert!((ctx.eye_normal([1.0, 1.0, 0.0]) - Vec3::new(0.5, 1.0, 0.0)).length() < 1e-6);
        ctx.glEnable(gl::GL_NORMALIZE);
        let expected = Vec3::new(0.5, 1.0, 0.0).normalize();
        assert!((ctx.eye_normal([1.0, 1.0, 0.0]) - expected).length() < 1e-6);
        // Uniform scale 4 and a rotation: rescaling restores the length.
        ctx.glDisable(gl::GL_NORMALIZE);
        ctx.glLoadIdentity();
        ctx.glRotatef(90.0, 0.0, 0.0, 1.0);
        ctx.glScalef(4.0, 4.0, 4.0);
        assert!((ctx.eye_normal([1.0, 0.0, 0.0]) - Vec3::new(0.0, 0.25, 0.0)).length() < 1e-6);
        ctx.glEnable(gl::GL_RESCALE_NORMAL);
        assert!((ctx.eye_normal([1.0, 0.0, 0.0]) - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-6);
    }
}

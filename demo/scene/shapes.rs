//! Geometry helpers shared by the scene parts: tessellated rectangles (finely enough for
//! per-vertex lighting to look smooth) and boxes, emitted inside an open
//! `glBegin(GL_QUADS)`.

use crate::gl::*;

/// A 3-vector.
pub type V3 = [f32; 3];

/// World size of one texture repeat, in metres.
const TEXTURE_METRES: f32 = 2.0;

/// A rectangle `origin + a·u + b·v` (a, b in 0..1) split into `nu` × `nv` cells; `u × v`
/// points to the lit side.
pub struct Grid {
    pub origin: V3,
    pub u: V3,
    pub v: V3,
    pub nu: usize,
    pub nv: usize,
}

/// Emits texture coordinates: unit 0 only, or unit 0 plus a lightmap on unit 1.
pub enum TexCoords<'a> {
    Single,
    WithLightmap(&'a Multitexture),
}

impl TexCoords<'_> {
    fn emit(&self, gl: &Gl, st: [f32; 2], lightmap: [f32; 2]) {
        // Safety: a context is current, inside glBegin/glEnd.
        unsafe {
            match self {
                TexCoords::Single => gl.glTexCoord2f(st[0], st[1]),
                TexCoords::WithLightmap(mt) => {
                    mt.glMultiTexCoord2fARB(GL_TEXTURE0_ARB, st[0], st[1]);
                    mt.glMultiTexCoord2fARB(GL_TEXTURE1_ARB, lightmap[0], lightmap[1]);
                }
            }
        }
    }
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: V3, s: f32) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn length(a: V3) -> f32 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// `a × b`.
pub fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `a` scaled to unit length (`fallback` when `a` is too short).
pub fn normalize_or(a: V3, fallback: V3) -> V3 {
    let l = length(a);
    if l > 1e-6 { scale(a, 1.0 / l) } else { fallback }
}

/// Emits the cells of `grid` as quads, leaving out those whose centre (in metres along u and
/// v) `hole` accepts. Texture 0 repeats every [`TEXTURE_METRES`]; the lightmap spans the grid.
pub fn grid(gl: &Gl, tex: &TexCoords, grid: &Grid, hole: impl Fn(f32, f32) -> bool) {
    let normal = normalize_or(cross(grid.u, grid.v), [0.0, 1.0, 0.0]);
    let (len_u, len_v) = (length(grid.u), length(grid.v));
    let corner = |i: usize, j: usize| {
        let (a, b) = (i as f32 / grid.nu as f32, j as f32 / grid.nv as f32);
        let p = add(grid.origin, add(scale(grid.u, a), scale(grid.v, b)));
        (p, [a * len_u / TEXTURE_METRES, b * len_v / TEXTURE_METRES], [a, b])
    };
    // Safety: a context is current, inside glBegin(GL_QUADS)/glEnd.
    unsafe { gl.glNormal3f(normal[0], normal[1], normal[2]) };
    for j in 0..grid.nv {
        for i in 0..grid.nu {
            let centre = (
                (i as f32 + 0.5) * len_u / grid.nu as f32,
                (j as f32 + 0.5) * len_v / grid.nv as f32,
            );
            if hole(centre.0, centre.1) {
                continue;
            }
            for (ci, cj) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)] {
                let (p, st, lm) = corner(ci, cj);
                tex.emit(gl, st, lm);
                // Safety: as above.
                unsafe { gl.glVertex3f(p[0], p[1], p[2]) };
            }
        }
    }
}

/// Emits the six faces of the box `min`..`max`, outward-facing, one cell per face.
pub fn cuboid(gl: &Gl, min: V3, max: V3) {
    let d = [max[0] - min[0], max[1] - min[1], max[2] - min[2]];
    let (x, y, z) = ([d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]);
    let faces: [(V3, V3, V3); 6] = [
        (min, z, y),         // -x
        (add(min, x), y, z), // +x
        (min, x, z),         // -y
        (add(min, y), z, x), // +y
        (min, y, x),         // -z
        (add(min, z), x, y), // +z
    ];
    for (origin, u, v) in faces {
        grid(gl, &TexCoords::Single, &Grid { origin, u, v, nu: 1, nv: 1 }, |_, _| false);
    }
}

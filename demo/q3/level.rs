//! The level of `--q3`, in Quake 3 units (1 unit ≈ 2.5 cm, z up): a hall (512 × 384 × 224)
//! with a pillar and two light panels beside a doorway in its east wall, through which a
//! courtyard (512 × 512, walls 320 high) is open to the sky above, with a sunken pool of water.
//! Every face is an axis-aligned rectangle ([`Rect`]) with a material; faces are cut into
//! surfaces of at most [`SURFACE_MAX`] units a side (Q3's BSP cuts faces too), each a grid of
//! vertices at most [`VERTEX_SPACING`] apart, wound clockwise seen from the front as Q3's
//! surfaces are (it culls `GL_FRONT`). The faces are also what light is traced against when
//! the lightmaps and the light grid are baked ([`Level::occluded`], [`Level::reaches_sky`]).

use glam::Vec3;

/// What a face is made of (each a shader of `super::shaders`).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Material {
    /// Hall and pool floor tiles (base × lightmap on two texture units).
    Floor,
    /// Brick walls (base × lightmap, then a detail pass).
    Brick,
    /// Metal walls, pillar and doorway (base pass, then the lightmap as a second pass).
    Metal,
    /// Concrete ceiling and courtyard floor (base × lightmap).
    Concrete,
    /// Light panels (base × lightmap, then an additive glow pass).
    Panel,
    /// The pool's surface (alpha blended).
    Water,
    /// The opening of the courtyard (not drawn: the sky box shows through it).
    Sky,
}

impl Material {
    /// Whether surfaces of this material have a lightmap.
    pub fn lightmapped(self) -> bool {
        !matches!(self, Material::Water | Material::Sky)
    }
}

/// The rectangle `origin + a·u + b·v` for a, b in 0..=1; its front side is along `u × v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    pub origin: Vec3,
    pub u: Vec3,
    pub v: Vec3,
}

impl Rect {
    /// The axis-aligned rectangle between corners `a` and `b` (equal along one axis), facing
    /// `normal`.
    pub fn facing(a: Vec3, b: Vec3, normal: Vec3) -> Rect {
        let (min, d) = (a.min(b), (b - a).abs());
        let axes: Vec<Vec3> = [Vec3::X, Vec3::Y, Vec3::Z].into_iter().filter(|e| e.dot(normal).abs() < 0.5).collect();
        let (mut u, mut v) = (axes[0] * d, axes[1] * d);
        if u.cross(v).dot(normal) < 0.0 {
            std::mem::swap(&mut u, &mut v);
        }
        Rect { origin: min, u, v }
    }

    /// The unit normal of the front side.
    pub fn normal(&self) -> Vec3 {
        self.u.cross(self.v).normalize()
    }

    /// The point at (a, b).
    pub fn at(&self, a: f32, b: f32) -> Vec3 {
        self.origin + self.u * a + self.v * b
    }

    /// Distance along `dir` (unit) from `from` to the rectangle, if it is hit within
    /// `(0.01, max)`, from either side.
    pub fn hit(&self, from: Vec3, dir: Vec3, max: f32) -> Option<f32> {
        let n = self.u.cross(self.v);
        let denom = n.dot(dir);
        if denom.abs() < 1e-9 {
            return None;
        }
        let t = n.dot(self.origin - from) / denom;
        if !(0.01..max).contains(&t) {
            return None;
        }
        let p = from + dir * t - self.origin;
        let (a, b) = (p.dot(self.u) / self.u.length_squared(), p.dot(self.v) / self.v.length_squared());
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
    }
}

/// A face of the level.
#[derive(Clone, Copy, Debug)]
pub struct Face {
    pub rect: Rect,
    pub material: Material,
}

/// Largest side of a surface, in units.
pub const SURFACE_MAX: f32 = 256.0;
/// Largest distance between neighbouring vertices of a surface.
pub const VERTEX_SPACING: f32 = 64.0;
/// World units per repeat of a 64-texel texture (2 units per texel).
const TEXTURE_UNITS: f32 = 128.0;

/// A drawable piece of a face: a grid of vertices of one material.
#[derive(Clone, Debug)]
pub struct Surface {
    pub material: Material,
    pub rect: Rect,
    pub normal: Vec3,
    pub xyz: Vec<Vec3>,
    /// Texture coordinates of the base texture.
    pub st: Vec<[f32; 2]>,
    /// Lightmap coordinates (set by `lightmaps::bake`) and page.
    pub lightmap_st: Vec<[f32; 2]>,
    pub lightmap_page: usize,
    /// Triangles, clockwise seen from the front.
    pub indexes: Vec<u32>,
    pub mins: Vec3,
    pub maxs: Vec3,
}

/// The hall: x 0..512, y 0..384, z 0..224.
const HALL: Vec3 = Vec3::new(512.0, 384.0, 224.0);
/// The doorway: y 128..256, up to z 176, through the 16-unit wall x 512..528.
const DOOR_Y: (f32, f32) = (128.0, 256.0);
const DOOR_TOP: f32 = 176.0;
/// The courtyard: x 528..1040, y -64..448, walls up to z 320.
const COURT_MIN: Vec3 = Vec3::new(528.0, -64.0, 0.0);
const COURT_MAX: Vec3 = Vec3::new(1040.0, 448.0, 320.0);
/// The pool: x 720..880, y 96..288, 32 deep, the water 8 below the courtyard floor.
const POOL_MIN: Vec3 = Vec3::new(720.0, 96.0, -32.0);
const POOL_MAX: Vec3 = Vec3::new(880.0, 288.0, 0.0);
const WATER_Z: f32 = -8.0;
/// The pillar: x 216..264, y 88..136, floor to ceiling.
const PILLAR_MIN: Vec3 = Vec3::new(216.0, 88.0, 0.0);
const PILLAR_MAX: Vec3 = Vec3::new(264.0, 136.0, 224.0);

/// The faces of the level.
pub fn faces() -> Vec<Face> {
    use Material::*;
    let v = Vec3::new;
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let (h, c0, c1, p0, p1) = (HALL, COURT_MIN, COURT_MAX, POOL_MIN, POOL_MAX);
    let (d0, d1, top) = (DOOR_Y.0, DOOR_Y.1, DOOR_TOP);
    let (q0, q1) = (PILLAR_MIN, PILLAR_MAX);
    let list: [(Vec3, Vec3, Vec3, Material); 37] = [
        // The hall.
        (v(0.0, 0.0, 0.0), v(h.x, h.y, 0.0), z, Floor),
        (v(0.0, 0.0, h.z), v(h.x, h.y, h.z), -z, Concrete),
        (v(0.0, 0.0, 0.0), v(0.0, h.y, h.z), x, Brick),
        (v(0.0, 0.0, 0.0), v(h.x, 0.0, h.z), y, Brick),
        (v(0.0, h.y, 0.0), v(h.x, h.y, h.z), -y, Brick),
        (v(h.x, 0.0, 0.0), v(h.x, d0, h.z), -x, Metal),
        (v(h.x, d1, 0.0), v(h.x, h.y, h.z), -x, Metal),
        (v(h.x, d0, top), v(h.x, d1, h.z), -x, Metal),
        // The pillar.
        (v(q0.x, q0.y, 0.0), v(q0.x, q1.y, q1.z), -x, Metal),
        (v(q1.x, q0.y, 0.0), v(q1.x, q1.y, q1.z), x, Metal),
        (v(q0.x, q0.y, 0.0), v(q1.x, q0.y, q1.z), -y, Metal),
        (v(q0.x, q1.y, 0.0), v(q1.x, q1.y, q1.z), y, Metal),
        // The doorway through the wall.
        (v(h.x, d0, 0.0), v(c0.x, d0, top), y, Metal),
        (v(h.x, d1, 0.0), v(c0.x, d1, top), -y, Metal),
        (v(h.x, d0, top), v(c0.x, d1, top), -z, Metal),
        (v(h.x, d0, 0.0), v(c0.x, d1, 0.0), z, Floor),
        // The courtyard floor around the pool.
        (v(c0.x, c0.y, 0.0), v(p0.x, c1.y, 0.0), z, Concrete),
        (v(p1.x, c0.y, 0.0), v(c1.x, c1.y, 0.0), z, Concrete),
        (v(p0.x, c0.y, 0.0), v(p1.x, p0.y, 0.0), z, Concrete),
        (v(p0.x, p1.y, 0.0), v(p1.x, c1.y, 0.0), z, Concrete),
        // The pool and its water.
        (v(p0.x, p0.y, p0.z), v(p1.x, p1.y, p0.z), z, Floor),
        (v(p0.x, p0.y, p0.z), v(p0.x, p1.y, 0.0), x, Concrete),
        (v(p1.x, p0.y, p0.z), v(p1.x, p1.y, 0.0), -x, Concrete),
        (v(p0.x, p0.y, p0.z), v(p1.x, p0.y, 0.0), y, Concrete),
        (v(p0.x, p1.y, p0.z), v(p1.x, p1.y, 0.0), -y, Concrete),
        (v(p0.x, p0.y, WATER_Z), v(p1.x, p1.y, WATER_Z), z, Water),
        // The courtyard walls, the west one around the doorway.
        (v(c0.x, c0.y, 0.0), v(c0.x, d0, c1.z), x, Brick),
        (v(c0.x, d1, 0.0), v(c0.x, c1.y, c1.z), x, Brick),
        (v(c0.x, d0, top), v(c0.x, d1, c1.z), x, Brick),
        (v(c1.x, c0.y, 0.0), v(c1.x, c1.y, c1.z), -x, Brick),
        (v(c0.x, c0.y, 0.0), v(c1.x, c0.y, c1.z), y, Brick),
        (v(c0.x, c1.y, 0.0), v(c1.x, c1.y, c1.z), -y, Brick),
        // The opening to the sky.
        (v(c0.x, c0.y, c1.z), v(c1.x, c1.y, c1.z), -z, Sky),
        // Light panels: two beside the doorway, one on the hall ceiling, one in the courtyard.
        (v(h.x - 2.0, 32.0, 96.0), v(h.x - 2.0, 96.0, 160.0), -x, Panel),
        (v(h.x - 2.0, 288.0, 96.0), v(h.x - 2.0, 352.0, 160.0), -x, Panel),
        (v(96.0, 160.0, h.z - 2.0), v(160.0, 224.0, h.z - 2.0), -z, Panel),
        (v(c1.x - 2.0, 160.0, 160.0), v(c1.x - 2.0, 224.0, 224.0), -x, Panel),
    ];
    list.iter().map(|&(a, b, n, material)| Face { rect: Rect::facing(a, b, n), material }).collect()
}

/// Pieces along a side of `length`: at least 1, each at most `max` long.
fn pieces(length: f32, max: f32) -> usize {
    ((length / max).ceil() as usize).max(1)
}

/// Cuts `face` into surfaces (lightmap coordinates left at 0 for `lightmaps::bake`).
pub fn surfaces_of(face: &Face) -> Vec<Surface> {
    let r = face.rect;
    let (nu, nv) = (pieces(r.u.length(), SURFACE_MAX), pieces(r.v.length(), SURFACE_MAX));
    let normal = r.normal();
    let (du, dv) = (r.u.normalize(), r.v.normalize());
    let mut out = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let rect = Rect {
                origin: r.at(i as f32 / nu as f32, j as f32 / nv as f32),
                u: r.u / nu as f32,
                v: r.v / nv as f32,
            };
            let (cu, cv) = (pieces(rect.u.length(), VERTEX_SPACING), pieces(rect.v.length(), VERTEX_SPACING));
            let mut s = Surface {
                material: face.material,
                rect,
                normal,
                xyz: Vec::new(),
                st: Vec::new(),
                lightmap_st: Vec::new(),
                lightmap_page: 0,
                indexes: Vec::new(),
                mins: Vec3::INFINITY,
                maxs: Vec3::NEG_INFINITY,
            };
            for b in 0..=cv {
                for a in 0..=cu {
                    let p = rect.at(a as f32 / cu as f32, b as f32 / cv as f32);
                    s.xyz.push(p);
                    s.st.push(if face.material == Material::Panel {
                        // A panel shows its whole texture once.
                        let local = p - r.origin;
                        [local.dot(du) / r.u.length(), 1.0 - local.dot(dv) / r.v.length()]
                    } else {
                        [p.dot(du) / TEXTURE_UNITS, -p.dot(dv) / TEXTURE_UNITS]
                    });
                    s.mins = s.mins.min(p);
                    s.maxs = s.maxs.max(p);
                }
            }
            s.lightmap_st = vec![[0.0; 2]; s.xyz.len()];
            let row = cu as u32 + 1;
            for b in 0..cv as u32 {
                for a in 0..cu as u32 {
                    let k = b * row + a;
                    // Clockwise seen from the front (u to the right, v up).
                    s.indexes.extend_from_slice(&[k, k + row + 1, k + 1, k, k + row, k + row + 1]);
                }
            }
            out.push(s);
        }
    }
    out
}

/// The faces and their surfaces.
pub struct Level {
    pub faces: Vec<Face>,
    pub surfaces: Vec<Surface>,
}

impl Level {
    /// The level: [`faces`] cut into surfaces.
    pub fn new() -> Level {
        let faces = faces();
        let surfaces = faces.iter().flat_map(surfaces_of).collect();
        Level { faces, surfaces }
    }

    /// Faces that stop light: all but the sky opening and the water.
    fn solids(&self) -> impl Iterator<Item = &Face> {
        self.faces.iter().filter(|f| !matches!(f.material, Material::Sky | Material::Water))
    }

    /// Whether a solid face lies between `from` and `to`.
    pub fn occluded(&self, from: Vec3, to: Vec3) -> bool {
        let d = to - from;
        let (dir, max) = (d.normalize(), d.length() - 0.01);
        self.solids().any(|f| f.rect.hit(from, dir, max).is_some())
    }

    /// Whether a ray from `from` along `dir` (unit) leaves through the sky opening.
    pub fn reaches_sky(&self, from: Vec3, dir: Vec3) -> bool {
        let sky = self.faces.iter().filter(|f| f.material == Material::Sky);
        let Some(t) = sky.filter_map(|f| f.rect.hit(from, dir, f32::MAX)).reduce(f32::min) else {
            return false;
        };
        !self.solids().any(|f| f.rect.hit(from, dir, t).is_some())
    }

    /// Whether `p` is in the open (inside the hall, the doorway, the courtyard or the pool).
    pub fn inside(&self, p: Vec3) -> bool {
        let within = |lo: Vec3, hi: Vec3| p.cmpgt(lo).all() && p.cmplt(hi).all();
        let pillar = within(PILLAR_MIN, PILLAR_MAX);
        let hall = within(Vec3::ZERO, HALL);
        let door = within(Vec3::new(HALL.x - 1.0, DOOR_Y.0, 0.0), Vec3::new(COURT_MIN.x + 1.0, DOOR_Y.1, DOOR_TOP));
        let court = within(COURT_MIN, COURT_MAX);
        let pool = within(POOL_MIN, POOL_MAX.with_z(1.0));
        (hall && !pillar) || door || court || pool
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangles_face_their_normal() {
        for n in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            let b = Vec3::splat(10.0) - n.abs() * 10.0;
            let r = Rect::facing(Vec3::ZERO, b, n);
            assert!(r.normal().abs_diff_eq(n, 1e-6), "{n}: {r:?}");
            assert!((r.u.length() - 10.0).abs() < 1e-6 && (r.v.length() - 10.0).abs() < 1e-6);
        }
    }

    #[test]
    fn surfaces_are_wound_clockwise_seen_from_the_front() {
        let level = Level::new();
        for s in &level.surfaces {
            assert!(s.rect.u.length() <= SURFACE_MAX + 1e-3 && s.rect.v.length() <= SURFACE_MAX + 1e-3);
            for t in s.indexes.chunks(3) {
                let p = |i: usize| s.xyz[t[i] as usize];
                // Clockwise from the front: the right-hand normal points away from the viewer.
                assert!((p(1) - p(0)).cross(p(2) - p(0)).dot(s.normal) < 0.0, "{:?}", s.material);
            }
        }
        // The hall floor (512 × 384) is cut into 2 × 2 surfaces of 4 × 3 cells.
        let floor: Vec<&Surface> = level.surfaces.iter().filter(|s| s.rect.origin.z == 0.0 && s.material == Material::Floor && s.maxs.x <= 512.0).collect();
        assert_eq!(floor.len(), 4);
        assert!(floor.iter().all(|s| s.indexes.len() == 4 * 3 * 6));
    }

    #[test]
    fn light_is_stopped_by_faces_and_the_sky_is_seen_through_the_opening() {
        let level = Level::new();
        // Through the pillar.
        assert!(level.occluded(Vec3::new(100.0, 112.0, 50.0), Vec3::new(400.0, 112.0, 50.0)));
        assert!(!level.occluded(Vec3::new(100.0, 300.0, 50.0), Vec3::new(400.0, 300.0, 50.0)));
        // Through the doorway, not through the wall beside it.
        assert!(!level.occluded(Vec3::new(400.0, 192.0, 50.0), Vec3::new(700.0, 192.0, 50.0)));
        assert!(level.occluded(Vec3::new(400.0, 50.0, 50.0), Vec3::new(700.0, 50.0, 50.0)));
        assert!(level.reaches_sky(Vec3::new(800.0, 200.0, 1.0), Vec3::Z));
        assert!(!level.reaches_sky(Vec3::new(200.0, 200.0, 1.0), Vec3::Z), "the hall has a ceiling");
        assert!(level.inside(Vec3::new(520.0, 192.0, 50.0)) && !level.inside(Vec3::new(520.0, 50.0, 50.0)));
        assert!(!level.inside(Vec3::new(240.0, 112.0, 50.0)), "in the pillar");
    }
}

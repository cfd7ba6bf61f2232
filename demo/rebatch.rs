//! `--rebatch`: a world drawn the way Quake 3 draws its BSP surfaces. The static world (room
//! floor, ceiling and walls, four pillars) is cut into surfaces of a few quads each (`--detail
//! N` subdivides each quad into N × N), stored once with their bounds. Every frame the surfaces
//! whose bounds meet the view frustum are found on the CPU, sorted nearest first, and re-batched
//! per texture into a scratch buffer of client arrays (like Q3's `tess`, flushed with
//! `glDrawElements` when [`TESS_VERTICES`] would overflow), so the same wall arrives in another
//! batch at another offset, or not at all, from one frame to the next. The modelview is the view
//! (`glLoadMatrixf`, as Quake does) and the camera turns around at a fixed position in
//! [`TURN_FRAMES`] frames, looking up and down twice per turn so that every surface is seen.

use glam::{Mat4, Vec3, Vec4};

use crate::gl::*;
use crate::scene::textures::Textures;

/// Frames of one full turn of the camera.
pub const TURN_FRAMES: u64 = 120;
/// Vertices of the scratch buffer (Quake 3's `SHADER_MAX_VERTEXES`); a larger surface is
/// drawn alone.
const TESS_VERTICES: usize = 1000;
/// Half width (x), height (y), half depth (z) of the room.
const ROOM: Vec3 = Vec3::new(8.0, 5.0, 10.0);
/// Pillar centres (x, z) and half size.
const PILLARS: [(f32, f32); 4] = [(-5.0, -6.0), (5.0, -6.0), (-5.0, 2.0), (5.0, 2.0)];
const PILLAR_HALF: f32 = 0.4;
/// Camera position; vertical field of view, near and far planes.
const EYE: Vec3 = Vec3::new(0.0, 1.6, 0.0);
const FOVY_DEGREES: f32 = 70.0;
const NEAR: f32 = 0.1;
const FAR: f32 = 100.0;

/// A world surface: a grid of quads of one texture, with its bounds.
struct Surface {
    texture: GLuint,
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    /// Triangles, counter-clockwise seen from inside the room (or outside a pillar).
    indices: Vec<u16>,
    min: Vec3,
    max: Vec3,
}

/// The world's surfaces, the textures and the scratch buffer.
pub struct World {
    surfaces: Vec<Surface>,
    textures: Textures,
    tess: Tess,
    aspect: f32,
    verbose: bool,
}

/// The scratch buffer of one batch.
#[derive(Default)]
struct Tess {
    positions: Vec<[f32; 3]>,
    texcoords: Vec<[f32; 2]>,
    indices: Vec<u16>,
}

/// What one frame drew.
#[derive(Default)]
struct Drawn {
    surfaces: usize,
    triangles: usize,
    draws: usize,
}

impl World {
    /// Builds the surfaces (`detail` quads along each side of a surface's cells, 1..=64),
    /// uploads the textures, sets the state, and prints `rebatch: S surfaces, T triangles`.
    pub fn new(gl: &Gl, detail: u32, width: i32, height: i32, verbose: bool) -> Self {
        let textures = Textures::new(gl);
        let surfaces = surfaces(&textures, detail.clamp(1, 64) as usize);
        let triangles: usize = surfaces.iter().map(|s| s.indices.len() / 3).sum();
        println!("rebatch: {} surfaces, {triangles} triangles", surfaces.len());
        // Safety: a context is current.
        unsafe {
            gl.glViewport(0, 0, width, height);
            gl.glClearColor(0.0, 0.0, 0.0, 1.0);
            gl.glEnable(GL_DEPTH_TEST);
            gl.glDepthFunc(GL_LEQUAL);
            gl.glEnable(GL_CULL_FACE);
            gl.glEnable(GL_TEXTURE_2D);
            gl.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE as GLint);
            gl.glColor3f(1.0, 1.0, 1.0);
            gl.glEnableClientState(GL_VERTEX_ARRAY);
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        }
        let aspect = width as f32 / height.max(1) as f32;
        Self { surfaces, textures, tess: Tess::default(), aspect, verbose }
    }

    /// Draws frame `frame`: clear, matrices, then the visible surfaces re-batched per texture.
    pub fn draw(&mut self, gl: &Gl, frame: u64) {
        let projection = frustum(self.aspect);
        let view = view(frame);
        let clip = projection * view;
        let mut visible: Vec<&Surface> =
            self.surfaces.iter().filter(|s| box_meets_frustum(&clip, s.min, s.max)).collect();
        let distance = |s: &Surface| ((s.min + s.max) * 0.5 - EYE).length();
        visible.sort_by(|a, b| distance(a).total_cmp(&distance(b)));
        // Safety: a context is current; the matrices have 16 floats.
        unsafe {
            gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            gl.glMatrixMode(GL_PROJECTION);
            gl.glLoadMatrixf(projection.as_ref().as_ptr());
            gl.glMatrixMode(GL_MODELVIEW);
            gl.glLoadMatrixf(view.as_ref().as_ptr());
        }
        let mut drawn = Drawn { surfaces: visible.len(), ..Drawn::default() };
        let t = &self.textures;
        for texture in [t.checker, t.brick, t.stone] {
            // Safety: a context is current.
            unsafe { gl.glBindTexture(GL_TEXTURE_2D, texture) };
            for surface in visible.iter().filter(|s| s.texture == texture) {
                if self.tess.positions.len() + surface.positions.len() > TESS_VERTICES {
                    self.tess.flush(gl, &mut drawn);
                }
                self.tess.add(surface);
            }
            self.tess.flush(gl, &mut drawn);
        }
        if self.verbose {
            println!(
                "rebatch frame {frame}: {} surfaces, {} triangles, {} draws",
                drawn.surfaces, drawn.triangles, drawn.draws
            );
        }
    }

    /// Deletes the textures.
    pub fn delete(&self, gl: &Gl) {
        self.textures.delete(gl);
    }
}

impl Tess {
    /// Appends a surface (its indices offset to the buffer's vertices).
    fn add(&mut self, s: &Surface) {
        let base = self.positions.len() as u16;
        self.positions.extend_from_slice(&s.positions);
        self.texcoords.extend_from_slice(&s.texcoords);
        self.indices.extend(s.indices.iter().map(|i| base + i));
    }

    /// Draws the buffer with one `glDrawElements` and empties it.
    fn flush(&mut self, gl: &Gl, drawn: &mut Drawn) {
        if self.indices.is_empty() {
            return;
        }
        // Safety: a context is current; the arrays hold every vertex the indices name and
        // stay alive until glDrawElements returns.
        unsafe {
            gl.glVertexPointer(3, GL_FLOAT, 0, self.positions.as_ptr().cast());
            gl.glTexCoordPointer(2, GL_FLOAT, 0, self.texcoords.as_ptr().cast());
            let count = self.indices.len() as GLsizei;
            gl.glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_SHORT, self.indices.as_ptr().cast());
        }
        drawn.triangles += self.indices.len() / 3;
        drawn.draws += 1;
        self.positions.clear();
        self.texcoords.clear();
        self.indices.clear();
    }
}

/// The projection: `glFrustum` of [`FOVY_DEGREES`] at `aspect`.
fn frustum(aspect: f32) -> Mat4 {
    let top = NEAR * (FOVY_DEGREES.to_radians() / 2.0).tan();
    let right = top * aspect;
    Mat4::from_cols(
        Vec4::new(NEAR / right, 0.0, 0.0, 0.0),
        Vec4::new(0.0, NEAR / top, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -(FAR + NEAR) / (FAR - NEAR), -1.0),
        Vec4::new(0.0, 0.0, -2.0 * FAR * NEAR / (FAR - NEAR), 0.0),
    )
}

/// The view of frame `frame`: at [`EYE`], yaw a full turn per [`TURN_FRAMES`], pitch up and
/// down 55° twice per turn.
fn view(frame: u64) -> Mat4 {
    let yaw = std::f32::consts::TAU * (frame % TURN_FRAMES) as f32 / TURN_FRAMES as f32;
    let pitch = 55f32.to_radians() * (2.0 * yaw).sin();
    let f = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), -yaw.cos() * pitch.cos());
    let s = f.cross(Vec3::Y).normalize();
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(EYE), -u.dot(EYE), f.dot(EYE), 1.0),
    )
}

/// Whether the box may meet the frustum of `clip` (false only when its 8 corners are all
/// outside one clip plane).
pub fn box_meets_frustum(clip: &Mat4, min: Vec3, max: Vec3) -> bool {
    let corners: [Vec4; 8] = std::array::from_fn(|i| {
        let pick = |bit: usize, lo: f32, hi: f32| if i & bit == 0 { lo } else { hi };
        *clip * Vec4::new(pick(1, min.x, max.x), pick(2, min.y, max.y), pick(4, min.z, max.z), 1.0)
    });
    (0..3).all(|axis| {
        [1.0f32, -1.0].iter().all(|&side| corners.iter().any(|c| c.w + side * c[axis] >= 0.0))
    })
}

/// The surfaces of the room and the pillars: 1 m cells (pillar sides: one cell across, 1 m
/// high), each of 2 × 2 quads times `detail` × `detail`.
fn surfaces(textures: &Textures, detail: usize) -> Vec<Surface> {
    let (w, h, d) = (ROOM.x, ROOM.y, ROOM.z);
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let mut out = Vec::new();
    let quads = 2 * detail;
    // (texture, origin, u, v, cells along u, cells along v); u × v points inwards.
    let room = [
        (textures.checker, Vec3::new(-w, 0.0, d), x * 2.0 * w, -z * 2.0 * d),
        (textures.brick, Vec3::new(-w, h, -d), x * 2.0 * w, z * 2.0 * d),
        (textures.brick, Vec3::new(-w, 0.0, -d), x * 2.0 * w, y * h),
        (textures.brick, Vec3::new(w, 0.0, d), -x * 2.0 * w, y * h),
        (textures.brick, Vec3::new(-w, 0.0, d), -z * 2.0 * d, y * h),
        (textures.brick, Vec3::new(w, 0.0, -d), z * 2.0 * d, y * h),
    ];
    for (texture, origin, u, v) in room {
        let (nu, nv) = (u.length().round() as usize, v.length().round() as usize);
        grid(&mut out, texture, origin, u, v, (nu, nv), quads);
    }
    for (px, pz) in PILLARS {
        let (a, b) = (PILLAR_HALF, 2.0 * PILLAR_HALF);
        // Outward faces: -z, +x, +z, -x.
        let sides = [
            (Vec3::new(px + a, 0.0, pz - a), -x * b),
            (Vec3::new(px + a, 0.0, pz + a), -z * b),
            (Vec3::new(px - a, 0.0, pz + a), x * b),
            (Vec3::new(px - a, 0.0, pz - a), z * b),
        ];
        for (origin, u) in sides {
            grid(&mut out, textures.stone, origin, u, y * h, (1, h as usize), quads);
        }
    }
    out
}

/// Appends the surfaces of the rectangle `origin + a·u + b·v`, `cells.0` × `cells.1` of them,
/// each a grid of `quads` × `quads` quads; texture coordinates repeat every 2 m.
fn grid(out: &mut Vec<Surface>, texture: GLuint, origin: Vec3, u: Vec3, v: Vec3, cells: (usize, usize), quads: usize) {
    let row = quads + 1;
    let mut indices = Vec::with_capacity(quads * quads * 6);
    for j in 0..quads {
        for i in 0..quads {
            let k = (j * row + i) as u16;
            let r = row as u16;
            indices.extend_from_slice(&[k, k + 1, k + r + 1, k, k + r + 1, k + r]);
        }
    }
    let (len_u, len_v) = (u.length(), v.length());
    for cj in 0..cells.1 {
        for ci in 0..cells.0 {
            let mut s = Surface {
                texture,
                positions: Vec::with_capacity(row * row),
                texcoords: Vec::with_capacity(row * row),
                indices: indices.clone(),
                min: Vec3::INFINITY,
                max: Vec3::NEG_INFINITY,
            };
            for j in 0..row {
                for i in 0..row {
                    let a = (ci as f32 + i as f32 / quads as f32) / cells.0 as f32;
                    let b = (cj as f32 + j as f32 / quads as f32) / cells.1 as f32;
                    let p = origin + u * a + v * b;
                    s.positions.push(p.to_array());
                    s.texcoords.push([a * len_u / 2.0, b * len_v / 2.0]);
                    s.min = s.min.min(p);
                    s.max = s.max.max(p);
                }
            }
            out.push(s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn textures() -> Textures {
        Textures { checker: 1, brick: 2, wood: 3, stone: 4, lightmap: 5 }
    }

    #[test]
    fn the_world_has_the_counted_surfaces_facing_inwards() {
        let s = surfaces(&textures(), 1);
        // Room: 16×20 floor and ceiling, 16×5 and 20×5 walls; pillars: 4 sides of 5 cells.
        assert_eq!(s.len(), 2 * 320 + 2 * 80 + 2 * 100 + 4 * 4 * 5);
        assert!(s.iter().all(|s| s.indices.len() == 2 * 2 * 6 && s.positions.len() == 9));
        assert_eq!(surfaces(&textures(), 3)[0].indices.len(), 6 * 6 * 6);
        // Floor faces up, pillar sides face away from their pillar.
        let normal = |s: &Surface| {
            let p = |i: usize| Vec3::from(s.positions[s.indices[i] as usize]);
            (p(1) - p(0)).cross(p(2) - p(0)).normalize()
        };
        assert!(normal(&s[0]).abs_diff_eq(Vec3::Y, 1e-5));
        let pillar = &s[2 * 320 + 2 * 80 + 2 * 100];
        let centre = (pillar.min + pillar.max) * 0.5;
        assert!(normal(pillar).dot(centre - Vec3::new(-5.0, centre.y, -6.0)) > 0.0);
    }

    #[test]
    fn only_part_of_the_world_is_in_view_and_every_surface_is_seen_in_a_turn() {
        let s = surfaces(&textures(), 1);
        let mut seen = vec![0u32; s.len()];
        for frame in 0..TURN_FRAMES {
            let clip = frustum(4.0 / 3.0) * view(frame);
            let visible: Vec<usize> = (0..s.len()).filter(|&i| box_meets_frustum(&clip, s[i].min, s[i].max)).collect();
            assert!(visible.len() < s.len() * 3 / 4, "frame {frame}: {} of {}", visible.len(), s.len());
            for i in visible {
                seen[i] += 1;
            }
        }
        assert!(seen.iter().all(|&n| n >= 2), "every surface in view in 2 frames or more");
    }
}

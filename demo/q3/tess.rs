//! The tessellation buffer (Q3's `tess`): the vertices and indexes of the batch being built,
//! in fixed arrays whose addresses never change (GL reads them as client arrays: positions and
//! normals padded to 4 floats, both texture coordinates of a vertex side by side, 16 bytes
//! apart), plus the per-stage arrays the shading fills (`tess.svars`) and the scratch arrays of
//! the dynamic light pass. The `add_*` functions are `tr_surface.c`'s surface functions.

use glam::Vec3;

use super::level::Surface;
use super::models::Mesh;
use super::shaders::{Deform, ShaderId};

/// Vertices of a batch (`SHADER_MAX_VERTEXES`).
pub const MAX_VERTEXES: usize = 1000;
/// Indexes of a batch (`SHADER_MAX_INDEXES`).
pub const MAX_INDEXES: usize = 6 * MAX_VERTEXES;

/// The batch being built.
pub struct Tess {
    pub xyz: Vec<[f32; 4]>,
    pub normal: Vec<[f32; 4]>,
    /// `[i][0]`: texture coordinates, `[i][1]`: lightmap coordinates.
    pub tex_coords: Vec<[[f32; 2]; 2]>,
    pub vertex_colors: Vec<[u8; 4]>,
    pub indexes: Vec<u32>,
    pub num_vertexes: usize,
    pub num_indexes: usize,
    /// The batch's shader (set by `begin_surface`; `None` before the first) and whether a
    /// dynamic light touches it.
    pub shader: Option<ShaderId>,
    pub dlighted: bool,
    /// Colours and texture coordinates (two bundles) of the stage being drawn.
    pub colors: Vec<[u8; 4]>,
    pub texcoords: [Vec<[f32; 2]>; 2],
    /// All 255: the colours of the lightmapped multitexture iterator.
    pub constant_color255: Vec<[u8; 4]>,
    /// The dynamic light pass: texture coordinates, colours, clip bits, lit triangles.
    pub dlight_texcoords: Vec<[f32; 2]>,
    pub dlight_colors: Vec<[u8; 4]>,
    pub clip_bits: Vec<u8>,
    pub hit_indexes: Vec<u32>,
}

impl Tess {
    /// Empty buffers of full size.
    pub fn new() -> Tess {
        let v = MAX_VERTEXES;
        Tess {
            xyz: vec![[0.0; 4]; v],
            normal: vec![[0.0; 4]; v],
            tex_coords: vec![[[0.0; 2]; 2]; v],
            vertex_colors: vec![[255; 4]; v],
            indexes: vec![0; MAX_INDEXES],
            num_vertexes: 0,
            num_indexes: 0,
            shader: None,
            dlighted: false,
            colors: vec![[255; 4]; v],
            texcoords: [vec![[0.0; 2]; v], vec![[0.0; 2]; v]],
            constant_color255: vec![[255; 4]; v],
            dlight_texcoords: vec![[0.0; 2]; v],
            dlight_colors: vec![[0; 4]; v],
            clip_bits: vec![0; v],
            hit_indexes: vec![0; MAX_INDEXES],
        }
    }

    /// Whether `vertexes` and `indexes` more fit (Q3's `RB_CHECKOVERFLOW` test).
    pub fn fits(&self, vertexes: usize, indexes: usize) -> bool {
        self.num_vertexes + vertexes < MAX_VERTEXES && self.num_indexes + indexes < MAX_INDEXES
    }

    /// Appends `indexes` offset by the first new vertex, and counts `vertexes` new vertices.
    fn append(&mut self, vertexes: usize, indexes: impl IntoIterator<Item = u32>) {
        let base = self.num_vertexes as u32;
        for i in indexes {
            self.indexes[self.num_indexes] = base + i;
            self.num_indexes += 1;
        }
        self.num_vertexes += vertexes;
    }

    fn set_vertex(&mut self, at: usize, xyz: Vec3, normal: Vec3, st: [f32; 2], lightmap: [f32; 2], color: [u8; 4]) {
        self.xyz[at] = xyz.extend(0.0).to_array();
        self.normal[at] = normal.extend(0.0).to_array();
        self.tex_coords[at] = [st, lightmap];
        self.vertex_colors[at] = color;
    }

    /// A world surface (`RB_SurfaceFace`/`RB_SurfaceGrid`): its vertices, white vertex colours.
    pub fn add_surface(&mut self, s: &Surface) {
        for (i, &p) in s.xyz.iter().enumerate() {
            self.set_vertex(self.num_vertexes + i, p, s.normal, s.st[i], s.lightmap_st[i], [255; 4]);
        }
        self.append(s.xyz.len(), s.indexes.iter().copied());
    }

    /// Vertices at `xyz` with texture coordinates `st` (no normal, white), and triangles
    /// indexing them (the sky's cloud layer).
    pub fn add_vertices(&mut self, vertices: &[(Vec3, [f32; 2])], indexes: &[u32]) {
        for (i, &(p, st)) in vertices.iter().enumerate() {
            self.set_vertex(self.num_vertexes + i, p, Vec3::ZERO, st, [0.0; 2], [255; 4]);
        }
        self.append(vertices.len(), indexes.iter().copied());
    }

    /// A model surface at frame `frame`, blended with `old_frame` by `backlerp` (0: `frame`
    /// alone), as Q3's `LerpMeshVertexes` does on the CPU.
    pub fn add_mesh(&mut self, mesh: &Mesh, frame: usize, old_frame: usize, backlerp: f32) {
        let (new, old) = (&mesh.frames[frame], &mesh.frames[old_frame]);
        for i in 0..mesh.st.len() {
            let xyz = new[i].0.lerp(old[i].0, backlerp);
            let normal = new[i].1.lerp(old[i].1, backlerp).normalize_or(new[i].1);
            self.set_vertex(self.num_vertexes + i, xyz, normal, mesh.st[i], [0.0; 2], [255; 4]);
        }
        self.append(mesh.st.len(), mesh.indexes.iter().copied());
    }

    /// A quad around `origin` spanned by `left` and `up`, textured 0..1, of colour `rgba`
    /// (`RB_AddQuadStamp`).
    pub fn add_quad_stamp(&mut self, origin: Vec3, left: Vec3, up: Vec3, rgba: [u8; 4]) {
        let normal = left.cross(up).normalize_or_zero();
        let corners = [(origin + left + up, [0.0, 0.0]), (origin - left + up, [1.0, 0.0]), (origin - left - up, [1.0, 1.0]), (origin + left - up, [0.0, 1.0])];
        for (i, (p, st)) in corners.into_iter().enumerate() {
            self.set_vertex(self.num_vertexes + i, p, normal, st, [0.0; 2], rgba);
        }
        self.append(4, [0, 1, 3, 3, 1, 2]);
    }

    /// A 2D picture: the screen rectangle `x, y, w, h` (y down) textured `s1,t1`..`s2,t2`
    /// (`RB_StretchPic`).
    pub fn add_picture(&mut self, [x, y, w, h]: [f32; 4], [s1, t1, s2, t2]: [f32; 4], rgba: [u8; 4]) {
        let corners = [(x, y, s1, t1), (x + w, y, s2, t1), (x + w, y + h, s2, t2), (x, y + h, s1, t2)];
        for (i, (px, py, s, t)) in corners.into_iter().enumerate() {
            self.set_vertex(self.num_vertexes + i, Vec3::new(px, py, 0.0), Vec3::Z, [s, t], [0.0; 2], rgba);
        }
        self.append(4, [3, 0, 2, 2, 0, 1]);
    }

    /// `deformVertexes wave`: every vertex pushed along its normal by the wave at `time`
    /// (`RB_DeformTessGeometry`).
    pub fn deform(&mut self, d: Deform, time: f32) {
        let push = d.base + d.amplitude * (std::f32::consts::TAU * d.frequency * time).sin();
        for i in 0..self.num_vertexes {
            for c in 0..3 {
                self.xyz[i][c] += self.normal[i][c] * push;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::q3::level::Level;

    #[test]
    fn surfaces_append_with_offset_indexes_until_full() {
        let level = Level::new();
        let s = &level.surfaces[0];
        let mut tess = Tess::new();
        tess.add_surface(s);
        tess.add_surface(s);
        let n = s.xyz.len();
        assert_eq!((tess.num_vertexes, tess.num_indexes), (2 * n, 2 * s.indexes.len()));
        assert_eq!(tess.indexes[s.indexes.len()], s.indexes[0] + n as u32);
        assert_eq!(tess.tex_coords[n][1], s.lightmap_st[0]);
        assert!(tess.fits(MAX_VERTEXES - 2 * n - 1, 0) && !tess.fits(MAX_VERTEXES - 2 * n, 0));
    }

    #[test]
    fn quads_and_deforms_move_vertices() {
        let mut tess = Tess::new();
        tess.add_quad_stamp(Vec3::new(10.0, 0.0, 0.0), Vec3::Y, Vec3::Z, [1, 2, 3, 4]);
        assert_eq!(tess.xyz[0], [10.0, 1.0, 1.0, 0.0]);
        assert_eq!(tess.vertex_colors[3], [1, 2, 3, 4]);
        assert_eq!(&tess.indexes[..6], &[0, 1, 3, 3, 1, 2]);
        tess.deform(Deform { base: 2.0, amplitude: 0.0, frequency: 1.0 }, 0.3);
        assert_eq!(tess.xyz[0], [12.0, 1.0, 1.0, 0.0], "pushed along the normal (+x)");
    }
}

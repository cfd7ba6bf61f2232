//! The animated mesh: a wobbling sphere whose vertices are recomputed every frame (dynamic
//! geometry), drawn from client arrays (`glVertexPointer`, `glNormalPointer`,
//! `glTexCoordPointer`) with one `glDrawElements`, inside `glLockArraysEXT` when available
//! (as Quake 3 does).

use super::shapes::{V3, cross, normalize_or};
use super::textures::Textures;
use crate::gl::*;

/// Rings from pole to pole and segments around.
const RINGS: usize = 16;
const SEGMENTS: usize = 24;
/// Centre and base radius.
const CENTRE: V3 = [0.0, 1.8, -4.0];
const RADIUS: f32 = 1.0;

/// Vertex and index arrays of the mesh (the client memory GL reads at draw time).
pub struct Mesh {
    positions: Vec<V3>,
    normals: Vec<V3>,
    texcoords: Vec<[f32; 2]>,
    indices: Vec<u16>,
}

/// Point on the surface at longitude `theta`, colatitude `phi` and `time`, relative to the
/// centre.
fn surface(theta: f32, phi: f32, time: f32) -> V3 {
    let r = RADIUS + 0.18 * (3.0 * theta + 2.0 * time).sin() * (4.0 * phi - 1.5 * time).sin();
    [r * phi.sin() * theta.cos(), r * phi.cos(), r * phi.sin() * theta.sin()]
}

impl Mesh {
    /// Builds the index list (fixed) and the vertices of time 0.
    pub fn new() -> Self {
        let row = SEGMENTS + 1;
        let mut indices = Vec::with_capacity(RINGS * SEGMENTS * 6);
        for ring in 0..RINGS {
            for seg in 0..SEGMENTS {
                let a = (ring * row + seg) as u16;
                let b = a + row as u16;
                indices.extend_from_slice(&[a, a + 1, b, b, a + 1, b + 1]);
            }
        }
        let count = (RINGS + 1) * row;
        let mut mesh = Self {
            positions: vec![[0.0; 3]; count],
            normals: vec![[0.0; 3]; count],
            texcoords: vec![[0.0; 2]; count],
            indices,
        };
        mesh.update(0.0);
        mesh
    }

    /// Recomputes positions and normals (by finite differences of the surface) for `time`.
    pub fn update(&mut self, time: f32) {
        const EPS: f32 = 1e-3;
        let row = SEGMENTS + 1;
        for ring in 0..=RINGS {
            for seg in 0..=SEGMENTS {
                let i = ring * row + seg;
                let theta = seg as f32 / SEGMENTS as f32 * std::f32::consts::TAU;
                let phi = ring as f32 / RINGS as f32 * std::f32::consts::PI;
                let p = surface(theta, phi, time);
                let dt = sub(surface(theta + EPS, phi, time), surface(theta - EPS, phi, time));
                let dp = sub(surface(theta, phi + EPS, time), surface(theta, phi - EPS, time));
                // At the poles d/dtheta vanishes: fall back to the radial direction.
                self.normals[i] = normalize_or(cross(dt, dp), normalize_or(p, [0.0, 1.0, 0.0]));
                self.positions[i] = [p[0] + CENTRE[0], p[1] + CENTRE[1], p[2] + CENTRE[2]];
                self.texcoords[i] =
                    [seg as f32 / SEGMENTS as f32 * 4.0, ring as f32 / RINGS as f32 * 2.0];
            }
        }
    }

    /// Draws the mesh (one `glDrawElements`).
    pub fn draw(&self, gl: &Gl, lock: Option<&LockArrays>, textures: &Textures) {
        let red = [0.9f32, 0.35, 0.25, 1.0];
        let specular = [0.8f32, 0.8, 0.8, 1.0];
        let none = [0.0f32, 0.0, 0.0, 1.0];
        let count = self.positions.len() as GLsizei;
        // Safety: a context is current; the arrays outlive the draw and hold `count`
        // vertices, the indices are below `count`.
        unsafe {
            gl.glBindTexture(GL_TEXTURE_2D, textures.stone);
            gl.glMaterialfv(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE, red.as_ptr());
            gl.glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, specular.as_ptr());
            gl.glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 32.0);
            gl.glEnableClientState(GL_VERTEX_ARRAY);
            gl.glEnableClientState(GL_NORMAL_ARRAY);
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
            gl.glVertexPointer(3, GL_FLOAT, 0, self.positions.as_ptr().cast());
            gl.glNormalPointer(GL_FLOAT, 0, self.normals.as_ptr().cast());
            gl.glTexCoordPointer(2, GL_FLOAT, 0, self.texcoords.as_ptr().cast());
            if let Some(lock) = lock {
                lock.glLockArraysEXT(0, count);
            }
            let n = self.indices.len() as GLsizei;
            gl.glDrawElements(GL_TRIANGLES, n, GL_UNSIGNED_SHORT, self.indices.as_ptr().cast());
            if let Some(lock) = lock {
                lock.glUnlockArraysEXT();
            }
            gl.glDisableClientState(GL_VERTEX_ARRAY);
            gl.glDisableClientState(GL_NORMAL_ARRAY);
            gl.glDisableClientState(GL_TEXTURE_COORD_ARRAY);
            gl.glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, none.as_ptr());
        }
    }
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

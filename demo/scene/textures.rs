//! Procedural textures (no files to ship): checker floor, brick walls, wood door, stone pillars
//! and a soft lightmap, uploaded with `glTexImage2D` and bilinear filtering.

use crate::gl::*;

/// Texture size in texels (square, a power of two as GL 1.x requires).
const SIZE: usize = 64;

/// The demo's texture objects.
pub struct Textures {
    /// Floor.
    pub checker: GLuint,
    /// Walls and ceiling.
    pub brick: GLuint,
    /// The door.
    pub wood: GLuint,
    /// Pillars and the animated mesh.
    pub stone: GLuint,
    /// Darkens corners and edges; modulated on texture unit 1.
    pub lightmap: GLuint,
}

impl Textures {
    /// Generates and uploads every texture.
    pub fn new(gl: &Gl) -> Self {
        Self {
            checker: upload(gl, &image(checker)),
            brick: upload(gl, &image(brick)),
            wood: upload(gl, &image(wood)),
            stone: upload(gl, &image(stone)),
            lightmap: upload(gl, &image(lightmap)),
        }
    }

    /// Deletes the texture objects.
    pub fn delete(&self, gl: &Gl) {
        let names = [self.checker, self.brick, self.wood, self.stone, self.lightmap];
        // Safety: a context is current; names has 5 entries.
        unsafe { gl.glDeleteTextures(names.len() as GLsizei, names.as_ptr()) }
    }
}

/// An RGB image of SIZE × SIZE from a texel function of (x, y).
fn image(texel: fn(usize, usize) -> [u8; 3]) -> Vec<u8> {
    (0..SIZE * SIZE).flat_map(|i| texel(i % SIZE, i / SIZE)).collect()
}

/// Small deterministic noise in 0..=31 from a texel position.
pub fn noise(x: usize, y: usize) -> u8 {
    let h = (x as u32).wrapping_mul(73_856_093) ^ (y as u32).wrapping_mul(19_349_663);
    (h.wrapping_mul(2_654_435_761) >> 27) as u8
}

fn checker(x: usize, y: usize) -> [u8; 3] {
    let n = noise(x, y) / 2;
    if (x / 16 + y / 16).is_multiple_of(2) { [200 + n, 200 + n, 190 + n] } else { [60 + n, 60 + n, 70 + n] }
}

/// Red bricks in light mortar, 32 × 16 texels each (rows offset by half a brick).
pub fn brick(x: usize, y: usize) -> [u8; 3] {
    let row = y / 16;
    let offset = if row.is_multiple_of(2) { 0 } else { 16 };
    let mortar = y % 16 < 2 || (x + offset) % 32 < 2;
    let n = noise(x, y);
    if mortar { [170 + n / 2, 165 + n / 2, 150 + n / 2] } else { [150 + n, 60 + n / 2, 40 + n / 2] }
}

fn wood(x: usize, y: usize) -> [u8; 3] {
    let grain = ((x as f32 * 0.6 + (y as f32 * 0.2).sin() * 3.0).sin() * 20.0) as i32;
    let n = noise(x / 4, y) as i32 / 2;
    let v = |base: i32| (base + grain + n).clamp(0, 255) as u8;
    [v(140), v(90), v(45)]
}

/// Grey speckled stone.
pub fn stone(x: usize, y: usize) -> [u8; 3] {
    let n = noise(x, y) + noise(x / 4, y / 4) * 2;
    [110 + n, 110 + n, 115 + n]
}

fn lightmap(x: usize, y: usize) -> [u8; 3] {
    let edge = |v: usize| {
        let t = (v as f32 + 0.5) / SIZE as f32;
        (t * (1.0 - t) * 4.0).sqrt()
    };
    let l = (70.0 + 185.0 * edge(x) * edge(y)) as u8;
    [l, l, l]
}

/// Uploads an RGB SIZE × SIZE image as a new repeating, bilinear texture object.
fn upload(gl: &Gl, rgb: &[u8]) -> GLuint {
    let mut name = 0;
    // Safety: a context is current; rgb holds SIZE × SIZE × 3 bytes, rows tightly packed
    // (unpack alignment 1).
    unsafe {
        gl.glGenTextures(1, &mut name);
        gl.glBindTexture(GL_TEXTURE_2D, name);
        gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR as GLint);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR as GLint);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT as GLint);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT as GLint);
        let size = SIZE as GLsizei;
        gl.glTexImage2D(
            GL_TEXTURE_2D,
            0,
            GL_RGB as GLint,
            size,
            size,
            0,
            GL_RGB,
            GL_UNSIGNED_BYTE,
            rgb.as_ptr().cast(),
        );
    }
    name
}

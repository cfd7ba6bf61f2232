//! Drawing a batch (`tr_shade.c`): the stage iterators of `super::shaders::Iterator`, the
//! per-stage colours and texture coordinates computed on the CPU (`ComputeColors`,
//! `ComputeTexCoords`), the collapsed base × lightmap stage on two texture units
//! (`DrawMultitextured`) and the dynamic light pass (`ProjectDlightTexture`). Every batch
//! is drawn from client arrays inside `glLockArraysEXT`/`glUnlockArraysEXT` with
//! `glDrawElements`, as Quake 3 does when compiled vertex arrays exist.

use std::ffi::c_void;

use super::back_end::Backend;
use super::shaders::{AlphaGen, Iterator, RgbGen, Shader, Sort, Stage, StateBits, TcGen, TcMod};
use super::sky;
use crate::gl::*;

impl Backend<'_> {
    /// Draws the batch and empties it (`RB_EndSurface`).
    pub fn end_surface(&mut self) {
        let Some(id) = self.tess.shader else { return };
        if self.tess.num_indexes == 0 {
            return;
        }
        self.counts.batches += 1;
        let shaders = self.shaders;
        let shader = shaders.get(id);
        match shader.iterator {
            Iterator::Generic => self.iterate_generic(shader),
            Iterator::LightmappedMultitexture => self.iterate_lightmapped_multitexture(shader),
            Iterator::VertexLitTexture => self.iterate_vertex_lit(shader),
            Iterator::Sky => self.iterate_sky(shader),
        }
        self.tess.num_indexes = 0;
    }

    /// `glDrawElements` of `count` indexes at `indexes` (`R_DrawElements`).
    fn draw_elements(&mut self, count: usize, indexes: *const u32) {
        self.counts.draw_elements += 1;
        // Safety: a context is current; the indexes name vertices below `num_vertexes`, in
        // arrays that stay in place until the draw returns.
        unsafe { self.api.gl.glDrawElements(GL_TRIANGLES, count as GLsizei, GL_UNSIGNED_INT, indexes.cast()) }
    }

    fn vertex_pointer_and_lock(&mut self) {
        // Safety: a context is current; xyz holds num_vertexes vertices, 16 bytes apart.
        unsafe {
            self.api.gl.glVertexPointer(3, GL_FLOAT, 16, self.tess.xyz.as_ptr().cast());
            self.api.lock.glLockArraysEXT(0, self.tess.num_vertexes as GLsizei);
        }
    }

    fn unlock(&mut self) {
        // Safety: a context is current, arrays locked.
        unsafe { self.api.lock.glUnlockArraysEXT() }
    }

    /// Whether the dynamic light pass applies to this batch.
    fn dlight_pass_wanted(&self, shader: &Shader) -> bool {
        self.tess.dlighted && shader.sort <= Sort::Opaque && !self.dlights.is_empty()
    }

    /// Any shader: every stage a pass; the arrays that change between passes are enabled only
    /// after the lock (`RB_StageIteratorGeneric`).
    fn iterate_generic(&mut self, shader: &Shader) {
        let gl = self.api.gl;
        if let Some(d) = shader.deform {
            self.tess.deform(d, self.time);
        }
        self.state.cull(self.api, shader.cull);
        let arrays_once = shader.stages.len() == 1 && !shader.multitexture;
        // Safety: a context is current; the svars arrays hold MAX_VERTEXES entries.
        unsafe {
            if arrays_once {
                gl.glEnableClientState(GL_COLOR_ARRAY);
                gl.glColorPointer(4, GL_UNSIGNED_BYTE, 0, self.tess.colors.as_ptr().cast());
                gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
                gl.glTexCoordPointer(2, GL_FLOAT, 0, self.tess.texcoords[0].as_ptr().cast());
            } else {
                gl.glDisableClientState(GL_COLOR_ARRAY);
                gl.glDisableClientState(GL_TEXTURE_COORD_ARRAY);
            }
        }
        self.vertex_pointer_and_lock();
        if !arrays_once {
            // Safety: a context is current.
            unsafe {
                gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
                gl.glEnableClientState(GL_COLOR_ARRAY);
            }
        }
        for stage in &shader.stages {
            self.compute_colors(stage);
            self.compute_texcoords(stage);
            if !arrays_once {
                // Safety: a context is current; colors holds MAX_VERTEXES entries.
                unsafe {
                    gl.glEnableClientState(GL_COLOR_ARRAY);
                    gl.glColorPointer(4, GL_UNSIGNED_BYTE, 0, self.tess.colors.as_ptr().cast());
                }
            }
            if stage.bundles[1].is_some() {
                self.draw_multitextured(stage);
            } else {
                if !arrays_once {
                    // Safety: a context is current.
                    unsafe { gl.glTexCoordPointer(2, GL_FLOAT, 0, self.tess.texcoords[0].as_ptr().cast()) };
                }
                if let Some(b) = stage.bundles[0] {
                    self.state.bind(self.api, b.image);
                }
                self.state.state(self.api, stage.state);
                self.draw_elements(self.tess.num_indexes, self.tess.indexes.as_ptr());
            }
        }
        if self.dlight_pass_wanted(shader) {
            self.project_dlight_texture();
        }
        self.unlock();
    }

    /// Stage `stage` with its second bundle on texture unit 1 (`DrawMultitextured`).
    fn draw_multitextured(&mut self, stage: &Stage) {
        let (api, gl) = (self.api, self.api.gl);
        self.state.state(api, stage.state);
        self.state.select_texture(api, 0);
        // Safety: a context is current; the svars arrays hold MAX_VERTEXES entries.
        unsafe { gl.glTexCoordPointer(2, GL_FLOAT, 0, self.tess.texcoords[0].as_ptr().cast()) };
        if let Some(b) = stage.bundles[0] {
            self.state.bind(api, b.image);
        }
        self.state.select_texture(api, 1);
        // Safety: as above.
        unsafe {
            gl.glEnable(GL_TEXTURE_2D);
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        }
        self.state.tex_env(api, GL_MODULATE);
        // Safety: as above.
        unsafe { gl.glTexCoordPointer(2, GL_FLOAT, 0, self.tess.texcoords[1].as_ptr().cast()) };
        if let Some(b) = stage.bundles[1] {
            self.state.bind(api, b.image);
        }
        self.draw_elements(self.tess.num_indexes, self.tess.indexes.as_ptr());
        // Unit 1's texture coordinate array stays enabled, as in Q3.
        // Safety: a context is current.
        unsafe { gl.glDisable(GL_TEXTURE_2D) };
        self.state.select_texture(api, 0);
    }

    /// One collapsed base × lightmap stage: both units' texture coordinates straight from the
    /// vertices, white vertex colours (`RB_StageIteratorLightmappedMultitexture`).
    fn iterate_lightmapped_multitexture(&mut self, shader: &Shader) {
        let (api, gl) = (self.api, self.api.gl);
        let stage = shader.stages[0];
        self.state.cull(api, shader.cull);
        self.state.state(api, StateBits::DEFAULT);
        let tex = self.tess.tex_coords.as_ptr() as *const u8;
        // Safety: a context is current; xyz, colours and texture coordinates hold
        // MAX_VERTEXES entries (texture coordinates 16 bytes apart, the lightmap's 8 bytes in).
        unsafe {
            gl.glVertexPointer(3, GL_FLOAT, 16, self.tess.xyz.as_ptr().cast());
            gl.glEnableClientState(GL_COLOR_ARRAY);
            gl.glColorPointer(4, GL_UNSIGNED_BYTE, 0, self.tess.constant_color255.as_ptr().cast());
        }
        self.state.select_texture(api, 0);
        // Safety: as above.
        unsafe { gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY) };
        if let Some(b) = stage.bundles[0] {
            self.state.bind(api, b.image);
        }
        // Safety: as above.
        unsafe { gl.glTexCoordPointer(2, GL_FLOAT, 16, tex.cast::<c_void>()) };
        self.state.select_texture(api, 1);
        // Safety: as above.
        unsafe { gl.glEnable(GL_TEXTURE_2D) };
        self.state.tex_env(api, GL_MODULATE);
        if let Some(b) = stage.bundles[1] {
            self.state.bind(api, b.image);
        }
        // Safety: as above; the lightmap coordinates start 8 bytes into each vertex's pair.
        unsafe {
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
            gl.glTexCoordPointer(2, GL_FLOAT, 16, tex.add(8).cast::<c_void>());
            api.lock.glLockArraysEXT(0, self.tess.num_vertexes as GLsizei);
        }
        self.draw_elements(self.tess.num_indexes, self.tess.indexes.as_ptr());
        // Safety: a context is current.
        unsafe {
            gl.glDisable(GL_TEXTURE_2D);
            gl.glDisableClientState(GL_TEXTURE_COORD_ARRAY);
        }
        self.state.select_texture(api, 0);
        if self.dlight_pass_wanted(shader) {
            self.project_dlight_texture();
        }
        self.unlock();
    }

    /// One texture lit by the entity's light per vertex (`RB_StageIteratorVertexLitTexture`).
    fn iterate_vertex_lit(&mut self, shader: &Shader) {
        let (api, gl) = (self.api, self.api.gl);
        let stage = shader.stages[0];
        self.calc_diffuse_colors();
        self.state.cull(api, shader.cull);
        // Safety: a context is current; the arrays hold MAX_VERTEXES entries (texture
        // coordinates 16 bytes apart).
        unsafe {
            gl.glEnableClientState(GL_COLOR_ARRAY);
            gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
            gl.glColorPointer(4, GL_UNSIGNED_BYTE, 0, self.tess.colors.as_ptr().cast());
            gl.glTexCoordPointer(2, GL_FLOAT, 16, self.tess.tex_coords.as_ptr().cast());
        }
        self.vertex_pointer_and_lock();
        if let Some(b) = stage.bundles[0] {
            self.state.bind(api, b.image);
        }
        self.state.state(api, stage.state);
        self.draw_elements(self.tess.num_indexes, self.tess.indexes.as_ptr());
        self.unlock();
    }

    /// The sky box behind everything (depth range 1..1, no depth writes), then the cloud
    /// stages over it (`RB_StageIteratorSky`).
    fn iterate_sky(&mut self, shader: &Shader) {
        let (api, gl) = (self.api, self.api.gl);
        let Some(sides) = shader.sky else { return };
        // Safety: a context is current.
        unsafe {
            gl.glDepthRange(1.0, 1.0);
            gl.glColor3f(1.0, 1.0, 1.0);
            gl.glPushMatrix();
        }
        self.state.state(api, StateBits::NO_DEPTH_WRITE);
        self.state.cull(api, shader.cull);
        let o = self.view.origin;
        // Safety: a context is current.
        unsafe { gl.glTranslatef(o.x, o.y, o.z) };
        self.counts.begins += sky::draw_box(api, self.state, &sides, self.view.z_far);
        // Safety: a context is current; pushed above.
        unsafe { gl.glPopMatrix() };
        if !shader.stages.is_empty() {
            sky::fill_clouds(self.tess, o, self.view.z_far);
            self.iterate_generic(shader);
        }
        // Safety: a context is current.
        unsafe { gl.glDepthRange(0.0, 1.0) };
    }

    /// Vertex colours from the entity's light and the vertex normals (`RB_CalcDiffuseColor`).
    fn calc_diffuse_colors(&mut self) {
        let Some(light) = self.light else { return };
        for i in 0..self.tess.num_vertexes {
            let n = self.tess.normal[i];
            self.tess.colors[i] = light.diffuse(glam::Vec3::new(n[0], n[1], n[2]));
        }
    }

    /// The stage's colours (`ComputeColors`; `tr.identityLight` is 1 here).
    fn compute_colors(&mut self, stage: &Stage) {
        let n = self.tess.num_vertexes;
        match stage.rgb_gen {
            RgbGen::IdentityLighting | RgbGen::Identity => self.tess.colors[..n].fill([255; 4]),
            RgbGen::Vertex => self.tess.colors[..n].copy_from_slice(&self.tess.vertex_colors[..n]),
            RgbGen::LightingDiffuse => self.calc_diffuse_colors(),
            RgbGen::Wave { base, amplitude, frequency } => {
                let v = (base + amplitude * (std::f32::consts::TAU * frequency * self.time).sin()).clamp(0.0, 1.0);
                let c = (v * 255.0) as u8;
                self.tess.colors[..n].fill([c, c, c, 255]);
            }
        }
        match stage.alpha_gen {
            AlphaGen::Identity => self.tess.colors[..n].iter_mut().for_each(|c| c[3] = 255),
            AlphaGen::Vertex => {
                for (c, v) in self.tess.colors[..n].iter_mut().zip(&self.tess.vertex_colors[..n]) {
                    c[3] = v[3];
                }
            }
            AlphaGen::Const(a) => self.tess.colors[..n].iter_mut().for_each(|c| c[3] = a),
        }
    }

    /// The stage's texture coordinates for each bundle (`ComputeTexCoords`).
    fn compute_texcoords(&mut self, stage: &Stage) {
        let n = self.tess.num_vertexes;
        for (b, bundle) in stage.bundles.iter().enumerate() {
            let Some(bundle) = bundle else { continue };
            let source = match bundle.tc_gen {
                TcGen::Texture => 0,
                TcGen::Lightmap => 1,
            };
            for i in 0..n {
                self.tess.texcoords[b][i] = self.tess.tex_coords[i][source];
            }
            let (scale, offset) = match bundle.tc_mod {
                TcMod::None => continue,
                TcMod::Scale(s, t) => ([s, t], [0.0; 2]),
                TcMod::Scroll(s, t) => ([1.0; 2], [(s * self.time).fract(), (t * self.time).fract()]),
            };
            for st in &mut self.tess.texcoords[b][..n] {
                *st = [st[0] * scale[0] + offset[0], st[1] * scale[1] + offset[1]];
            }
        }
    }

    /// Adds each dynamic light to the batch's triangles near it: the light's texture projected
    /// along z (texture coordinates from x and y), its colour faded with the height
    /// difference, only triangles with a vertex inside the light's box, `GL_ONE, GL_ONE` with
    /// `GL_EQUAL` depth (`ProjectDlightTexture`, for lights added as additive).
    fn project_dlight_texture(&mut self) {
        let (api, gl) = (self.api, self.api.gl);
        for l in 0..self.dlights.len() {
            let dl = self.dlights[l];
            let scale = 1.0 / dl.radius;
            let colour = dl.colour * 255.0;
            let t = &mut *self.tess;
            for i in 0..t.num_vertexes {
                let p = t.xyz[i];
                let dist = dl.origin - glam::Vec3::new(p[0], p[1], p[2]);
                let st = [0.5 + dist.x * scale, 0.5 + dist.y * scale];
                let mut clip = 0;
                clip |= if st[0] < 0.0 { 1 } else if st[0] > 1.0 { 2 } else { 0 };
                clip |= if st[1] < 0.0 { 4 } else if st[1] > 1.0 { 8 } else { 0 };
                let modulate = if dist.z > dl.radius {
                    clip |= 16;
                    0.0
                } else if dist.z < -dl.radius {
                    clip |= 32;
                    0.0
                } else if dist.z.abs() < dl.radius * 0.5 {
                    1.0
                } else {
                    2.0 * (dl.radius - dist.z.abs()) * scale
                };
                t.dlight_texcoords[i] = st;
                t.clip_bits[i] = clip;
                let [r, g, b] = (colour * modulate).to_array().map(|c| c as u8);
                t.dlight_colors[i] = [r, g, b, 255];
            }
            let mut hits = 0;
            for tri in t.indexes[..t.num_indexes].chunks_exact(3) {
                if t.clip_bits[tri[0] as usize] & t.clip_bits[tri[1] as usize] & t.clip_bits[tri[2] as usize] != 0 {
                    continue;
                }
                t.hit_indexes[hits..hits + 3].copy_from_slice(tri);
                hits += 3;
            }
            if hits == 0 {
                continue;
            }
            // Safety: a context is current; the dlight arrays hold MAX_VERTEXES entries.
            unsafe {
                gl.glEnableClientState(GL_TEXTURE_COORD_ARRAY);
                gl.glTexCoordPointer(2, GL_FLOAT, 0, self.tess.dlight_texcoords.as_ptr().cast());
                gl.glEnableClientState(GL_COLOR_ARRAY);
                gl.glColorPointer(4, GL_UNSIGNED_BYTE, 0, self.tess.dlight_colors.as_ptr().cast());
            }
            self.state.bind(api, self.dlight_image);
            self.state.state(api, StateBits::ADD.equal());
            self.draw_elements(hits, self.tess.hit_indexes.as_ptr());
        }
    }
}

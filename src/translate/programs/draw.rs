//! What a draw takes of the program in use ([`ProgramDraw`]): the executable, the built-in
//! state block packed now, the uniform bytes, the texture of each sampler slot (bound, for
//! the slot's target, to the unit the sampler's value names, enabled or not) and the
//! `GL_VERTEX_PROGRAM_POINT_SIZE` / `GL_VERTEX_PROGRAM_TWO_SIDE` enables.

use std::sync::Arc;

use crate::frame::program::ProgramDraw;
use crate::translate::Context;
use crate::translate::gl::{self, GLenum};
use crate::translate::glsl::{ActiveUniform, UniformStorage};
use crate::translate::texture::objects::Target;

/// The texture target a sampler type samples.
fn sampler_target(ty: GLenum) -> Target {
    match ty {
        gl::GL_SAMPLER_1D | gl::GL_SAMPLER_1D_SHADOW => Target::D1,
        gl::GL_SAMPLER_3D => Target::D3,
        gl::GL_SAMPLER_CUBE => Target::Cube,
        _ => Target::D2,
    }
}

/// The target of each sampler slot of a program with these uniforms (`slots` slots).
pub(crate) fn slot_targets(uniforms: &[ActiveUniform], slots: usize) -> Vec<Target> {
    let mut targets = vec![Target::D2; slots];
    for u in uniforms {
        if let UniformStorage::Sampler { first_slot } = u.storage {
            for slot in targets.iter_mut().skip(first_slot as usize).take(u.size as usize) {
                *slot = sampler_target(u.ty);
            }
        }
    }
    targets
}

impl Context {
    /// The program a draw emitted now runs, `None` without one.
    pub(crate) fn program_draw(&mut self) -> Option<Arc<ProgramDraw>> {
        let current = self.programs.current;
        if current == 0 {
            return None;
        }
        let (program, uniforms, slots) = {
            let mut shared = self.shared.lock();
            let linked = shared.programs.program_mut(current).ok()?.linked.as_mut()?;
            let values = linked.shared_values.get_or_insert_with(|| linked.values.as_slice().into()).clone();
            let slots: Vec<(usize, Target)> =
                linked.sampler_units.iter().map(|&u| u as usize).zip(linked.sampler_targets.iter().copied()).collect();
            (linked.executable.clone(), values, slots)
        };
        let (textures, depth): (Vec<_>, Vec<_>) = slots.into_iter().map(|(unit, target)| self.sampler_texture(unit, target)).unzip();
        Some(Arc::new(ProgramDraw {
            program,
            builtins: self.pack_builtins(&depth).into(),
            uniforms,
            textures,
            point_size_from_shader: self.enables.is_on(gl::GL_VERTEX_PROGRAM_POINT_SIZE),
            two_side: self.enables.is_on(gl::GL_VERTEX_PROGRAM_TWO_SIDE),
        }))
    }
}

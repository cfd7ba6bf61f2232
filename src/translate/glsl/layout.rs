//! The program's uniforms laid out: the std430 block the rewrite declares (in the same member
//! order, so glslang lays it out the same way), the sampler slots, and the active uniforms
//! `glGetActiveUniform` reports.

use std::collections::HashMap;

use super::declarations::{Type, Variable};
use super::{ActiveUniform, UniformStorage};
use crate::frame::program::{MAX_SAMPLERS, SamplerKind};

/// The uniforms of a linked program.
#[derive(Clone, Debug, Default)]
pub struct UniformLayout {
    /// Active uniforms in enumeration order.
    pub active: Vec<ActiveUniform>,
    /// Size of the block in bytes.
    pub block_size: u32,
    /// Sampler slots: kind, in slot order.
    pub samplers: Vec<SamplerKind>,
    /// Slot of each sampler uniform, by name.
    pub sampler_slots: HashMap<String, u32>,
}

/// (alignment, size) of a type in std430.
fn align_size(ty: &Type, structs: &HashMap<String, Vec<Variable>>) -> (u32, u32) {
    match ty {
        Type::Basic(b) => b.std430(),
        Type::Struct(name) => {
            let mut align = 4u32;
            let mut offset = 0u32;
            for m in &structs[name] {
                let (a, s) = var_align_size(m, structs);
                align = align.max(a);
                offset = offset.next_multiple_of(a) + s;
            }
            (align, offset.next_multiple_of(align))
        }
    }
}

/// (alignment, size) of a variable (an array: its stride times its length).
fn var_align_size(v: &Variable, structs: &HashMap<String, Vec<Variable>>) -> (u32, u32) {
    let (a, s) = align_size(&v.ty, structs);
    match v.array {
        Some(n) => (a, s.next_multiple_of(a) * n),
        None => (a, s),
    }
}

/// Lays out `uniforms` (the program's, each once even if both stages declare it).
pub fn lay_out(uniforms: &[Variable], structs: &HashMap<String, Vec<Variable>>) -> Result<UniformLayout, String> {
    let mut layout = UniformLayout::default();
    let mut offset = 0u32;
    for u in uniforms {
        if let Type::Basic(b) = &u.ty
            && let Some(kind) = b.sampler() {
                if u.array.is_some() {
                    return Err(format!("glrt: sampler arrays ('{}') are not supported", u.name));
                }
                let slot = layout.samplers.len() as u32;
                if layout.samplers.len() == MAX_SAMPLERS {
                    return Err(format!("too many samplers: glrt allows {MAX_SAMPLERS} per program"));
                }
                layout.samplers.push(kind);
                layout.sampler_slots.insert(u.name.clone(), slot);
                layout.active.push(ActiveUniform { name: u.name.clone(), ty: b.gl, size: 1, storage: UniformStorage::Sampler { first_slot: slot } });
                continue;
            }
        let (align, size) = var_align_size(u, structs);
        offset = offset.next_multiple_of(align);
        flatten(&u.name, u, offset, structs, &mut layout.active)?;
        offset += size;
    }
    layout.block_size = offset.next_multiple_of(16);
    Ok(layout)
}

/// Adds the active uniforms of variable `v` (named `name`) placed at `offset`: one entry for a
/// basic type or an array of one, the members of structs one by one.
fn flatten(name: &str, v: &Variable, offset: u32, structs: &HashMap<String, Vec<Variable>>, out: &mut Vec<ActiveUniform>) -> Result<(), String> {
    let (align, size) = align_size(&v.ty, structs);
    match &v.ty {
        Type::Basic(b) => {
            if b.sampler().is_some() {
                return Err(format!("glrt: samplers inside structs ('{name}') are not supported"));
            }
            let array_stride = size.next_multiple_of(align);
            out.push(ActiveUniform {
                name: name.to_string(),
                ty: b.gl,
                size: v.array.unwrap_or(1),
                storage: UniformStorage::Block { offset, array_stride, matrix_stride: b.matrix_stride() },
            });
        }
        Type::Struct(s) => {
            let stride = size.next_multiple_of(align);
            for element in 0..v.array.unwrap_or(1) {
                let base = match v.array {
                    Some(_) => format!("{name}[{element}]"),
                    None => name.to_string(),
                };
                let mut member_offset = offset + element * stride;
                for m in &structs[s] {
                    let (a, s) = var_align_size(m, structs);
                    member_offset = member_offset.next_multiple_of(a);
                    flatten(&format!("{base}.{}", m.name), m, member_offset, structs, out)?;
                    member_offset += s;
                }
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::declarations::parse;
    use super::super::tokens::tokenize;
    use super::*;

    fn layout_of(src: &str) -> UniformLayout {
        let d = parse(&tokenize(src)).unwrap();
        lay_out(&d.uniforms, &d.structs).unwrap()
    }

    #[test]
    fn std430_offsets_and_names() {
        let l = layout_of("struct S { float a; vec3 b; };\nuniform float k;\nuniform vec3 v[2];\nuniform mat3 m;\nuniform S s[2];\nuniform sampler2D tex;\nuniform bool flag;\n");
        let got: Vec<_> = l.active.iter().map(|u| (u.name.as_str(), u.size, u.storage)).collect();
        use UniformStorage::*;
        assert_eq!(
            got,
            vec![
                ("k", 1, Block { offset: 0, array_stride: 4, matrix_stride: 0 }),
                ("v", 2, Block { offset: 16, array_stride: 16, matrix_stride: 0 }),
                ("m", 1, Block { offset: 48, array_stride: 48, matrix_stride: 16 }),
                ("s[0].a", 1, Block { offset: 96, array_stride: 4, matrix_stride: 0 }),
                ("s[0].b", 1, Block { offset: 112, array_stride: 16, matrix_stride: 0 }),
                ("s[1].a", 1, Block { offset: 128, array_stride: 4, matrix_stride: 0 }),
                ("s[1].b", 1, Block { offset: 144, array_stride: 16, matrix_stride: 0 }),
                ("tex", 1, Sampler { first_slot: 0 }),
                ("flag", 1, Block { offset: 160, array_stride: 4, matrix_stride: 0 }),
            ]
        );
        assert_eq!(l.block_size, 176);
        assert_eq!(l.samplers, vec![SamplerKind::D2]);
    }
}

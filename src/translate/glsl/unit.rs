//! Compiling one shader (validation and declarations) and linking a program's shaders (the
//! interface between the stages, layouts, the rewrite and its SPIR-V).

use std::collections::HashMap;

use super::declarations::{self, Declarations, Statement, Type, Variable};
use super::rewrite::{self, StageInput};
use super::tokens::{self, Kind, Token};
use super::{ActiveAttribute, CompiledShader, FIRST_USER_VARYING, LinkedProgram, Stage, compiler, layout};
use crate::frame::program::ShaderProgram;

/// Vulkan locations a stage interface has (the minimum `maxVertexOutputComponents` / 4).
const MAX_LOCATIONS: u32 = 32;
/// Generic attribute indices (`GL_MAX_VERTEX_ATTRIBS`).
const MAX_ATTRIBUTES: u32 = 16;

/// What a compiled shader keeps for linking.
#[derive(Clone, Debug)]
pub struct Unit {
    /// Its preprocessed tokens.
    pub tokens: Vec<Token>,
    /// Its global declarations.
    pub decls: Declarations,
}

impl Unit {
    /// Whether `name` is used outside the statements that declare the program's interface.
    fn references(&self, name: &str) -> bool {
        self.decls.statements.iter().any(|(range, statement)| {
            matches!(statement, Statement::Other | Statement::Const)
                && self.tokens[range.clone()].iter().any(|t| t.kind == Kind::Ident && t.text == name)
        })
    }
}

/// See [`super::compile`].
pub fn compile(stage: Stage, source: &str) -> CompiledShader {
    let result = compiler::validate(stage, source).and_then(|preprocessed| {
        let tokens = tokens::tokenize(&preprocessed);
        let decls = declarations::parse(&tokens).map_err(|e| format!("ERROR: {e}\n"))?;
        Ok(Unit { tokens, decls })
    });
    match result {
        Ok(unit) => CompiledShader { stage, ok: true, log: String::new(), unit: Some(std::sync::Arc::new(unit)) },
        Err(log) => CompiledShader { stage, ok: false, log, unit: None },
    }
}

/// A failed link with `log`.
fn failed(log: String) -> LinkedProgram {
    LinkedProgram { ok: false, log, executable: None, uniforms: Vec::new(), uniform_block_size: 0, attributes: Vec::new() }
}

/// Vulkan locations a variable takes: one per vec4, matrix column or array element.
fn locations(v: &Variable) -> u32 {
    let columns = match &v.ty {
        Type::Basic(b) => b.columns,
        Type::Struct(_) => 1,
    };
    columns * v.array.unwrap_or(1)
}

/// See [`super::link`].
pub fn link(shaders: &[&CompiledShader], attribute_bindings: &HashMap<String, u32>) -> LinkedProgram {
    match try_link(shaders, attribute_bindings) {
        Ok(program) => program,
        Err(log) => failed(log),
    }
}

fn try_link(shaders: &[&CompiledShader], attribute_bindings: &HashMap<String, u32>) -> Result<LinkedProgram, String> {
    let mut vertex: Option<&Unit> = None;
    let mut fragment: Option<&Unit> = None;
    for shader in shaders {
        let unit = shader.unit.as_deref().filter(|_| shader.ok).ok_or("error: an attached shader is not compiled\n")?;
        let slot = if shader.stage == Stage::Vertex { &mut vertex } else { &mut fragment };
        if slot.replace(unit).is_some() {
            return Err("error: glrt links one shader per stage (several shaders of one stage are not supported)\n".into());
        }
    }
    if vertex.is_none() && fragment.is_none() {
        return Err("error: no shaders attached\n".into());
    }
    for (unit, stage) in [(vertex, "vertex"), (fragment, "fragment")] {
        if unit.is_some_and(|u| !u.references("main")) {
            return Err(format!("error: the {stage} shader has no main function\n"));
        }
    }
    let units: Vec<&Unit> = vertex.iter().chain(fragment.iter()).copied().collect();

    // Struct types and uniforms of both stages, each once, in declaration order.
    let mut structs = HashMap::new();
    let mut uniforms: Vec<Variable> = Vec::new();
    for unit in &units {
        for (name, members) in &unit.decls.structs {
            structs.entry(name.clone()).or_insert_with(|| members.clone());
        }
        for u in &unit.decls.uniforms {
            match uniforms.iter().find(|v| v.name == u.name) {
                Some(v) if v != u => return Err(format!("error: uniform '{}' is declared differently in the two stages\n", u.name)),
                Some(_) => {}
                None => uniforms.push(u.clone()),
            }
        }
    }
    let layout = layout::lay_out(&uniforms, &structs).map_err(|e| format!("error: {e}\n"))?;
    let block: Vec<Variable> = uniforms.iter().filter(|u| !layout.sampler_slots.contains_key(&u.name)).cloned().collect();
    let sampler_types: HashMap<String, String> = uniforms
        .iter()
        .filter_map(|u| match &u.ty {
            Type::Basic(b) if b.sampler().is_some() => Some((u.name.clone(), b.name.to_string())),
            _ => None,
        })
        .collect();

    let varying_locations = varying_locations(vertex, fragment)?;
    let attribute_indices = match vertex {
        Some(v) => attribute_indices(v, attribute_bindings)?,
        None => HashMap::new(),
    };

    let stage_spirv = |unit: &Unit, stage: Stage| -> Result<std::sync::Arc<[u32]>, String> {
        let source = rewrite::rewrite(&StageInput {
            stage,
            tokens: &unit.tokens,
            decls: &unit.decls,
            structs: &structs,
            block: &block,
            sampler_slots: &layout.sampler_slots,
            sampler_types: &sampler_types,
            varying_locations: &varying_locations,
            attribute_indices: &attribute_indices,
        });
        compiler::spirv(stage, &source).map(Into::into).map_err(|log| {
            log::debug!("glrt: the {stage:?} stage's translation does not compile:\n{source}");
            format!("error: glrt could not translate the {stage:?} shader to Vulkan GLSL:\n{log}")
        })
    };
    let vertex_spirv = vertex.map(|u| stage_spirv(u, Stage::Vertex)).transpose()?;
    let fragment_spirv = fragment.map(|u| stage_spirv(u, Stage::Fragment)).transpose()?;

    let active = |name: &str| units.iter().any(|u| u.references(name));
    let uniforms = layout
        .active
        .iter()
        .filter(|u| active(u.name.split(['.', '[']).next().unwrap_or(&u.name)))
        .cloned()
        .collect();
    let mut attributes = Vec::new();
    let mut read = Vec::new();
    if let Some(v) = vertex {
        for a in v.decls.attributes.iter().filter(|a| v.references(&a.name)) {
            let Type::Basic(b) = &a.ty else { continue };
            let index = attribute_indices[&a.name];
            attributes.push(ActiveAttribute { name: a.name.clone(), ty: b.gl, index });
            read.extend((index..index + b.columns).filter(|&i| i > 0));
        }
    }
    read.sort_unstable();
    read.dedup();
    Ok(LinkedProgram {
        ok: true,
        log: String::new(),
        executable: Some(ShaderProgram {
            id: 0,
            vertex: vertex_spirv,
            fragment: fragment_spirv,
            samplers: layout.samplers.clone(),
            attributes: read,
        }),
        uniforms,
        uniform_block_size: layout.block_size,
        attributes,
    })
}

/// Where the program's varyings go: the vertex stage's, packed by [`pack_varyings`]; the
/// fragment stage may only read varyings the vertex stage declares (with the same type).
fn varying_locations(vertex: Option<&Unit>, fragment: Option<&Unit>) -> Result<HashMap<String, (u32, u32)>, String> {
    let out = match vertex {
        Some(v) => pack_varyings(&v.decls.varyings)?,
        None => HashMap::new(),
    };
    if let Some(f) = fragment {
        for var in f.decls.varyings.iter().filter(|var| f.references(&var.name)) {
            let written = vertex.and_then(|v| v.decls.varyings.iter().find(|w| w.name == var.name));
            match written {
                None => return Err(format!("error: fragment shader varying '{}' is not written by a vertex shader\n", var.name)),
                Some(w) if w != var => return Err(format!("error: varying '{}' has different types in the two stages\n", var.name)),
                Some(_) => {}
            }
        }
    }
    Ok(out)
}

/// Packs varyings into the vec4 locations from [`FIRST_USER_VARYING`] (GLSL 1.10 section
/// 7.6 lets an implementation pack them, and `GL_MAX_VARYING_FLOATS` counts floats): each
/// gets a location and a first component (Vulkan's `component` qualifier). Scalars and vectors
/// (and arrays of them) share locations, largest first, in the first place they fit; a matrix
/// takes whole locations, one per column. The error says when they do not fit.
fn pack_varyings(varyings: &[Variable]) -> Result<HashMap<String, (u32, u32)>, String> {
    let count = (MAX_LOCATIONS - FIRST_USER_VARYING) as usize;
    let mut used = vec![[false; 4]; count];
    let mut order: Vec<&Variable> = varyings.iter().collect();
    let width = |v: &Variable| match &v.ty {
        Type::Basic(b) if b.columns == 1 => b.rows as usize,
        _ => 4,
    };
    order.sort_by_key(|v| std::cmp::Reverse((width(v), locations(v))));
    let mut out = HashMap::new();
    for v in order {
        let (w, n) = (width(v), locations(v) as usize);
        let fits = |l: usize, c: usize| l + n <= count && (l..l + n).all(|i| used[i][c..c + w].iter().all(|u| !u));
        let place = (0..count).flat_map(|l| (0..=4 - w).map(move |c| (l, c))).find(|&(l, c)| fits(l, c));
        let Some((l, c)) = place else {
            return Err(format!("error: too many varyings: '{}' does not fit in the {count} vec4 locations glrt has for them\n", v.name));
        };
        for row in &mut used[l..l + n] {
            row[c..c + w].iter_mut().for_each(|u| *u = true);
        }
        out.insert(v.name.clone(), (FIRST_USER_VARYING + l as u32, c as u32));
    }
    Ok(out)
}

/// Generic attribute index of each attribute of the vertex stage: its `glBindAttribLocation`
/// binding, else the lowest indices from 1 that are free (a matrix takes one per column).
fn attribute_indices(vertex: &Unit, bindings: &HashMap<String, u32>) -> Result<HashMap<String, u32>, String> {
    let width = |a: &Variable| locations(a);
    let mut used = vec![false; MAX_ATTRIBUTES as usize];
    let mut out = HashMap::new();
    for a in &vertex.decls.attributes {
        if let Some(&index) = bindings.get(&a.name) {
            if index + width(a) > MAX_ATTRIBUTES {
                return Err(format!("error: attribute '{}' bound to index {index} does not fit below {MAX_ATTRIBUTES}\n", a.name));
            }
            for i in index..index + width(a) {
                used[i as usize] = true;
            }
            out.insert(a.name.clone(), index);
        }
    }
    for a in vertex.decls.attributes.iter().filter(|a| !bindings.contains_key(&a.name)) {
        let w = width(a);
        let free = (1..=MAX_ATTRIBUTES.saturating_sub(w)).find(|&i| (i..i + w).all(|j| !used[j as usize]));
        let index = free.ok_or_else(|| format!("error: too many attributes: '{}' does not fit in {MAX_ATTRIBUTES} indices\n", a.name))?;
        for j in index..index + w {
            used[j as usize] = true;
        }
        out.insert(a.name.clone(), index);
    }
    Ok(out)
}

//! Struct layouts read from compiled SPIR-V, and the Rust `const` assertions that hold a
//! `#[repr(C)]` mirror to them (the one check of every struct Rust shares with GLSL,
//! `src/render/shader_abi.rs`). As vulkano-shaders' `structs.rs` does, the layout comes from
//! the module's decorations: member `Offset`s, `ArrayStride`s and `MatrixStride`s, with the
//! names glslang keeps (`OpName`, `OpMemberName`).
//!
//! Used by the build script (`build/shaders.rs`) and by `tests/shader_layout.rs`, which shows
//! that a wrong mirror fails to compile.

use std::collections::HashMap;
use std::fmt::Write;

/// A SPIR-V type, as far as layouts need it.
#[derive(Clone, Debug, PartialEq)]
enum Type {
    /// `float`, `int`, `uint` of `width` bits.
    Scalar { float: bool, signed: bool, width: u32 },
    /// A vector of `count` components of type `component`.
    Vector { component: u32, count: u32 },
    /// A matrix of `count` columns of (vector) type `column`.
    Matrix { column: u32, count: u32 },
    /// A sized array of `element`; `length` is the id of a constant.
    Array { element: u32, length: u32 },
    /// A runtime array of `element` (the last member of a buffer block).
    RuntimeArray,
    /// A struct of these member types.
    Struct(Vec<u32>),
    /// Anything else (images, pointers, functions, booleans).
    Other,
}

/// The decoded parts of a SPIR-V module.
#[derive(Debug, Default)]
pub struct Module {
    names: HashMap<u32, String>,
    member_names: HashMap<(u32, u32), String>,
    offsets: HashMap<(u32, u32), u32>,
    matrix_strides: HashMap<(u32, u32), u32>,
    array_strides: HashMap<u32, u32>,
    types: HashMap<u32, Type>,
    constants: HashMap<u32, u32>,
}

/// One member of a struct: name, byte offset and type.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// Its GLSL name.
    pub name: String,
    /// Its `Offset`.
    pub offset: u32,
    ty: u32,
    /// Its `MatrixStride` when it is a matrix.
    matrix_stride: Option<u32>,
}

/// The layout of one GLSL struct or block.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Its GLSL name.
    pub name: String,
    /// Its size in bytes: the stride of the arrays of it, or else the end of its last member.
    pub size: u32,
    /// Its members, in declaration order.
    pub members: Vec<Member>,
}

const OP_NAME: u32 = 5;
const OP_MEMBER_NAME: u32 = 6;
const OP_TYPE_BOOL: u32 = 20;
const OP_TYPE_INT: u32 = 21;
const OP_TYPE_FLOAT: u32 = 22;
const OP_TYPE_VECTOR: u32 = 23;
const OP_TYPE_MATRIX: u32 = 24;
const OP_TYPE_ARRAY: u32 = 28;
const OP_TYPE_RUNTIME_ARRAY: u32 = 29;
const OP_TYPE_STRUCT: u32 = 30;
const OP_CONSTANT: u32 = 43;
const OP_DECORATE: u32 = 71;
const OP_MEMBER_DECORATE: u32 = 72;
const DECORATION_ARRAY_STRIDE: u32 = 6;
const DECORATION_MATRIX_STRIDE: u32 = 7;
const DECORATION_OFFSET: u32 = 35;
const MAGIC: u32 = 0x0723_0203;

/// A literal string of SPIR-V words (UTF-8, nul-terminated).
fn string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|&b| b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

impl Module {
    /// Decodes the SPIR-V binary `bytes` (little-endian words).
    pub fn decode(bytes: &[u8]) -> Result<Module, String> {
        let words: Vec<u32> = bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        if words.len() < 5 || words[0] != MAGIC {
            return Err("not a SPIR-V module".into());
        }
        let mut m = Module::default();
        let mut i = 5;
        while i < words.len() {
            let (count, op) = ((words[i] >> 16) as usize, words[i] & 0xffff);
            if count == 0 || i + count > words.len() {
                return Err(format!("malformed instruction at word {i}"));
            }
            let a = &words[i + 1..i + count];
            let arg = |k: usize| a.get(k).copied().ok_or_else(|| format!("opcode {op} at word {i} is too short"));
            match op {
                OP_NAME => drop(m.names.insert(arg(0)?, string(&a[1..]))),
                OP_MEMBER_NAME => drop(m.member_names.insert((arg(0)?, arg(1)?), string(&a[2..]))),
                OP_TYPE_BOOL => drop(m.types.insert(arg(0)?, Type::Other)),
                OP_TYPE_INT => drop(m.types.insert(arg(0)?, Type::Scalar { float: false, signed: arg(2)? != 0, width: arg(1)? })),
                OP_TYPE_FLOAT => drop(m.types.insert(arg(0)?, Type::Scalar { float: true, signed: true, width: arg(1)? })),
                OP_TYPE_VECTOR => drop(m.types.insert(arg(0)?, Type::Vector { component: arg(1)?, count: arg(2)? })),
                OP_TYPE_MATRIX => drop(m.types.insert(arg(0)?, Type::Matrix { column: arg(1)?, count: arg(2)? })),
                OP_TYPE_ARRAY => drop(m.types.insert(arg(0)?, Type::Array { element: arg(1)?, length: arg(2)? })),
                OP_TYPE_RUNTIME_ARRAY => drop(m.types.insert(arg(0)?, Type::RuntimeArray)),
                OP_TYPE_STRUCT => drop(m.types.insert(arg(0)?, Type::Struct(a[1..].to_vec()))),
                OP_CONSTANT => drop(m.constants.insert(arg(1)?, arg(2)?)),
                OP_DECORATE if arg(1)? == DECORATION_ARRAY_STRIDE => drop(m.array_strides.insert(arg(0)?, arg(2)?)),
                OP_MEMBER_DECORATE if arg(2)? == DECORATION_OFFSET => drop(m.offsets.insert((arg(0)?, arg(1)?), arg(3)?)),
                OP_MEMBER_DECORATE if arg(2)? == DECORATION_MATRIX_STRIDE => drop(m.matrix_strides.insert((arg(0)?, arg(1)?), arg(3)?)),
                _ => {}
            }
            i += count;
        }
        Ok(m)
    }

    /// The layout of the struct or block named `name`. glslang may emit one struct several
    /// times: once per block layout using it (they must agree), and without offsets for the
    /// copies in function variables (left out).
    pub fn layout(&self, name: &str) -> Result<Layout, String> {
        let laid_out = |id: u32| self.offsets.keys().any(|&(s, _)| s == id);
        let mut ids: Vec<u32> = self
            .types
            .iter()
            .filter(|&(&id, t)| matches!(t, Type::Struct(_)) && self.names.get(&id).is_some_and(|n| n == name) && laid_out(id))
            .map(|(&id, _)| id)
            .collect();
        ids.sort_unstable();
        let mut layouts = ids.iter().map(|&id| self.struct_layout(id));
        let first = layouts.next().ok_or_else(|| format!("no struct `{name}`"))??;
        for other in layouts {
            if other? != first {
                return Err(format!("struct `{name}` has two different layouts"));
            }
        }
        Ok(first)
    }

    fn struct_layout(&self, id: u32) -> Result<Layout, String> {
        let name = self.names.get(&id).cloned().unwrap_or_default();
        let Some(Type::Struct(types)) = self.types.get(&id) else { return Err(format!("`{name}` is not a struct")) };
        let mut members = Vec::new();
        for (index, &ty) in types.iter().enumerate() {
            let key = (id, index as u32);
            let member = self.member_names.get(&key).cloned().ok_or_else(|| format!("member {index} of `{name}` has no name"))?;
            let offset = *self.offsets.get(&key).ok_or_else(|| format!("`{name}.{member}` has no Offset"))?;
            members.push(Member { name: member, offset, ty, matrix_stride: self.matrix_strides.get(&key).copied() });
        }
        let strides: Vec<u32> = self
            .types
            .iter()
            .filter(|(_, t)| matches!(t, Type::Array { element, .. } if *element == id))
            .filter_map(|(array, _)| self.array_strides.get(array).copied())
            .collect();
        let size = match strides.first() {
            Some(&stride) if strides.iter().all(|&s| s == stride) => stride,
            Some(_) => return Err(format!("arrays of `{name}` have different strides")),
            None => {
                let mut end = 0;
                for m in &members {
                    end = end.max(m.offset + self.size(m.ty, m.matrix_stride)?);
                }
                end
            }
        };
        Ok(Layout { name, size, members })
    }

    /// The size in bytes of type `ty` (a matrix's with its `MatrixStride`).
    fn size(&self, ty: u32, matrix_stride: Option<u32>) -> Result<u32, String> {
        match self.types.get(&ty) {
            Some(Type::Scalar { width, .. }) => Ok(width / 8),
            Some(Type::Vector { component, count }) => Ok(self.size(*component, None)? * count),
            Some(Type::Matrix { count, .. }) => Ok(matrix_stride.ok_or("a matrix without MatrixStride")? * count),
            Some(Type::Array { length, .. }) => Ok(self.array_length(*length)? * self.array_strides.get(&ty).ok_or("an array without ArrayStride")?),
            Some(Type::Struct(_)) => Ok(self.struct_layout(ty)?.size),
            Some(Type::RuntimeArray) => Ok(0),
            _ => Err(format!("type {ty} has no layout")),
        }
    }

    fn array_length(&self, constant: u32) -> Result<u32, String> {
        self.constants.get(&constant).copied().ok_or_else(|| "an array whose length is not a constant".into())
    }

    /// The Rust type of a member of GLSL type `ty`, with GLSL structs named by `rust_name`;
    /// an error where no plain Rust type has the same layout (padded matrix columns or array
    /// elements, runtime arrays, structs without a mirror).
    fn rust_type(&self, ty: u32, matrix_stride: Option<u32>, rust_name: &dyn Fn(&str) -> Option<String>) -> Result<String, String> {
        match self.types.get(&ty) {
            Some(Type::Scalar { float: true, width: 32, .. }) => Ok("f32".into()),
            Some(Type::Scalar { float: false, signed: false, width: 32 }) => Ok("u32".into()),
            Some(Type::Scalar { float: false, signed: true, width: 32 }) => Ok("i32".into()),
            Some(Type::Vector { component, count }) => Ok(format!("[{}; {count}]", self.rust_type(*component, None, rust_name)?)),
            Some(Type::Matrix { column, count }) => {
                if matrix_stride != Some(self.size(*column, None)?) {
                    return Err("a matrix with padded columns".into());
                }
                Ok(format!("[{}; {count}]", self.rust_type(*column, None, rust_name)?))
            }
            Some(Type::Array { element, length }) => {
                let stride = self.array_strides.get(&ty).copied();
                if stride != Some(self.size(*element, matrix_stride)?) {
                    return Err("an array with padded elements".into());
                }
                Ok(format!("[{}; {}]", self.rust_type(*element, matrix_stride, rust_name)?, self.array_length(*length)?))
            }
            Some(Type::Struct(_)) => {
                let name = self.names.get(&ty).cloned().unwrap_or_default();
                rust_name(&name).ok_or_else(|| format!("struct `{name}` has no Rust mirror"))
            }
            _ => Err(format!("type {ty} has no Rust mirror")),
        }
    }
}

/// How a Rust item mirrors a GLSL struct.
#[derive(Clone, Copy, Debug)]
pub enum Rust {
    /// A `#[repr(C)]` struct with a field of the same name and type at each member's offset,
    /// and the same size.
    Struct(&'static str),
    /// A constant holding the struct's size in bytes (Rust moves its bytes, never its fields).
    SizeConstant(&'static str),
}

/// One mirror: the GLSL struct (or block, or push-constant block) and its Rust counterpart.
#[derive(Clone, Copy, Debug)]
pub struct Mirror {
    /// The GLSL struct's name.
    pub glsl: &'static str,
    /// Its Rust counterpart.
    pub rust: Rust,
}

/// Rust source asserting that `mirrors` match their structs in `module` (the SPIR-V of
/// `shader`): `const` items that fail to compile where a size, an offset or a field type
/// differs.
pub fn assertions(module: &Module, shader: &str, mirrors: &[Mirror]) -> Result<String, String> {
    let rust_name = |glsl: &str| {
        mirrors.iter().find_map(|m| match m.rust {
            Rust::Struct(name) if m.glsl == glsl => Some(name.to_string()),
            _ => None,
        })
    };
    let mut out = String::new();
    for mirror in mirrors {
        let layout = module.layout(mirror.glsl).map_err(|e| format!("{shader}: {e}"))?;
        let (glsl, size) = (&layout.name, layout.size);
        let _ = writeln!(out, "// `{glsl}` of {shader}: {size} bytes.");
        match mirror.rust {
            Rust::SizeConstant(name) => {
                let _ = writeln!(out, "const _: () = assert!({name} as usize == {size}, \"{name}: `{glsl}` is {size} bytes in {shader}\");");
            }
            Rust::Struct(name) => {
                let _ = writeln!(out, "const _: () = assert!(::core::mem::size_of::<{name}>() == {size}, \"{name}: `{glsl}` is {size} bytes in {shader}\");");
            }
        }
        let Rust::Struct(name) = mirror.rust else { continue };
        for m in &layout.members {
            let ty = module.rust_type(m.ty, m.matrix_stride, &rust_name).map_err(|e| format!("{shader}: `{glsl}.{}` is {e}", m.name))?;
            let (field, offset) = (&m.name, m.offset);
            let _ = writeln!(
                out,
                "const _: () = assert!(::core::mem::offset_of!({name}, {field}) == {offset}, \"{name}.{field}: `{glsl}.{field}` is at byte {offset} in {shader}\");"
            );
            let _ = writeln!(out, "const _: fn(&{name}) -> &{ty} = |s| &s.{field};");
        }
    }
    Ok(out)
}

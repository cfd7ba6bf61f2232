//! What Rust and the GLSL shaders share, kept in step by the build (STYLE.md section 4):
//!
//! - **Constants are defined once, in Rust.** A module of shared constants holds only
//!   [`glsl_constants!`] and [`glsl_fields!`] invocations (the trace bindings, the tracer's
//!   flags, the texture environment's codes, the fixed-function key's fields). The crate
//!   compiles it with the macros below into `pub const`s; `build/glsl_constants.rs` compiles
//!   the same file with its own macros into tables and writes them as a GLSL header,
//!   `generated/<name>.glsl`, which the shaders include. A shader cannot use a number Rust
//!   does not give it.
//! - **Struct layouts are checked against the compiled SPIR-V.** Every `#[repr(C)]` mirror of
//!   a GLSL struct, block or push-constant range is named in `build/shaders.rs`'s `MIRRORS`;
//!   after compiling the shaders the build script reads each struct's member `Offset`
//!   decorations, array strides and member types from the SPIR-V (`build/spirv_layout.rs`)
//!   and writes `const` assertions of the Rust mirror's size, field offsets and field types
//!   into `OUT_DIR/layouts/<file>.rs`, which the mirror's module includes. A layout that
//!   differs on either side does not compile (this module's tests show it).

/// The build's reader of SPIR-V layouts (`build/spirv_layout.rs`), for the test of the checker
/// below and for tests of the blocks of GLSL programs compiled at run time.
#[cfg(test)]
#[path = "../../build/spirv_layout.rs"]
pub(crate) mod spirv_layout;

/// A bit field of a word the shaders read (a specialisation constant, a material word).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// Lowest bit.
    pub shift: u32,
    /// Width in bits.
    pub bits: u32,
}

impl Field {
    /// The field of `bits` bits from bit `shift`.
    pub const fn new(shift: u32, bits: u32) -> Field {
        Field { shift, bits }
    }

    /// `word` with this field set to `value` (which must fit).
    pub fn set(self, word: &mut u32, value: u32) {
        debug_assert!(value < 1 << self.bits, "{value} does not fit in {} bits", self.bits);
        *word |= (value & ((1 << self.bits) - 1)) << self.shift;
    }

    /// The value of this field in `word`.
    pub fn get(self, word: u32) -> u32 {
        (word >> self.shift) & ((1 << self.bits) - 1)
    }

    /// The `index`-th of consecutive fields of this width (the sources of a combiner word,
    /// say): `bits` wide, at `shift + index * bits`.
    pub const fn nth(self, index: u32) -> Field {
        Field::new(self.shift + index * self.bits, self.bits)
    }
}

/// Constants shared with the shaders: `const NAME: type = value;` items with their docs,
/// optionally after `glsl_prefix = "PREFIX_";` (their GLSL names are then `PREFIX_NAME`).
/// Here each becomes a `pub const`; the build script writes each as a GLSL `const` (`uint` for
/// `u32`, `int` otherwise) under the same name (see the module doc).
macro_rules! glsl_constants {
    (glsl_prefix = $prefix:literal; $($rest:tt)*) => {
        glsl_constants!($($rest)*);
    };
    ($( $(#[$attr:meta])* const $name:ident: $ty:ty = $value:expr; )*) => {
        $( $(#[$attr])* pub const $name: $ty = $value; )*
    };
}

/// Bit fields shared with the shaders: `NAME = (shift, bits);` items with their docs. Here
/// each becomes a `pub const` [`Field`]; in GLSL, `NAME_SHIFT` and `NAME_BITS`.
macro_rules! glsl_fields {
    ($( $(#[$attr:meta])* $name:ident = ($shift:expr, $bits:expr); )*) => {
        $( $(#[$attr])* pub const $name: $crate::render::shader_abi::Field = $crate::render::shader_abi::Field::new($shift, $bits); )*
    };
}

#[cfg(test)]
mod tests {
    use super::Field;
    use super::spirv_layout::{Mirror, Module, Rust, assertions};

    #[test]
    fn fields_set_and_get_their_bits() {
        let f = Field::new(3, 3);
        let mut w = 0b111;
        f.set(&mut w, 5);
        assert_eq!(w, 0b101_111);
        assert_eq!(f.get(w), 5);
        assert_eq!(f.nth(2), Field::new(9, 3));
    }

    fn pathtrace() -> Module {
        Module::decode(include_bytes!(concat!(env!("OUT_DIR"), "/shaders/pathtrace.comp.spv"))).expect("SPIR-V")
    }

    #[test]
    fn layouts_come_from_the_offsets_and_strides() {
        let light = pathtrace().layout("Light").expect("Light");
        let members: Vec<_> = light.members.iter().map(|m| (m.name.as_str(), m.offset)).collect();
        assert_eq!(members, [("position", 0), ("radiance", 16), ("spot", 32), ("params", 48)]);
        assert_eq!(light.size, 64, "the stride of `lights[]`");
        assert_eq!(pathtrace().layout("Pass").expect("the push constants").size, 8, "a block's size is its end");
        assert!(pathtrace().layout("NoSuchStruct").is_err());
    }

    /// Compiles `source` as a library with the `rustc` cargo runs; its errors on failure.
    fn rustc(name: &str, source: &str) -> Result<(), String> {
        let dir = std::env::temp_dir().join(format!("glrt-layout-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        std::fs::write(dir.join("lib.rs"), source).expect("writing the source");
        let out = std::process::Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
            .args(["--edition", "2024", "--crate-type", "lib", "--emit=metadata", "--out-dir"])
            .arg(&dir)
            .arg(dir.join("lib.rs"))
            .output()
            .expect("rustc runs");
        let _ = std::fs::remove_dir_all(&dir);
        if out.status.success() { Ok(()) } else { Err(String::from_utf8_lossy(&out.stderr).into_owned()) }
    }

    /// The assertions the build writes hold a right mirror and reject mirrors with a field at
    /// another offset, a field of another type, another size, or a size constant that is off.
    #[test]
    fn layout_assertions_reject_a_wrong_mirror() {
        let mirrors = [
            Mirror { glsl: "Light", rust: Rust::Struct("GpuLight") },
            Mirror { glsl: "BvhTriangle", rust: Rust::Struct("Triangle") },
            Mirror { glsl: "Pass", rust: Rust::SizeConstant("PUSH_BYTES") },
        ];
        let checks = assertions(&pathtrace(), "pathtrace.comp", &mirrors).expect("assertions");
        let source = |light: &str, triangle: &str, push: u32| {
            format!("#[repr(C)] pub struct GpuLight {{ {light} }}\n#[repr(C)] pub struct Triangle {{ {triangle} }}\npub const PUSH_BYTES: u32 = {push};\n{checks}")
        };
        let light = "pub position: [f32; 4], pub radiance: [f32; 4], pub spot: [f32; 4], pub params: [f32; 4]";
        let triangle = "pub v0: [f32; 3], pub member: u32, pub e1: [f32; 3], pub member_triangle: u32, pub e2: [f32; 3], pub pad2: u32";
        rustc("right", &source(light, triangle, 8)).expect("the right mirror compiles");

        let swapped = "pub position: [f32; 4], pub spot: [f32; 4], pub radiance: [f32; 4], pub params: [f32; 4]";
        let e = rustc("swapped", &source(swapped, triangle, 8)).expect_err("fields swapped");
        assert!(e.contains("GpuLight.radiance: `Light.radiance` is at byte 16 in pathtrace.comp"), "{e}");
        let retyped = "pub position: [f32; 4], pub radiance: [f32; 4], pub spot: [f32; 4], pub params: [u32; 4]";
        let e = rustc("retyped", &source(retyped, triangle, 8)).expect_err("a field of another type");
        assert!(e.contains("expected `&[f32; 4]`, found `&[u32; 4]`"), "{e}");
        let padded = "pub v0: [f32; 3], pub member: u32, pub e1: [f32; 3], pub member_triangle: u32, pub e2: [f32; 3], pub pad2: u32, pub more: u32";
        let e = rustc("long", &source(light, padded, 8)).expect_err("a struct of another size");
        assert!(e.contains("Triangle: `BvhTriangle` is 48 bytes in pathtrace.comp"), "{e}");
        let e = rustc("push", &source(light, triangle, 4)).expect_err("a size constant that is off");
        assert!(e.contains("PUSH_BYTES: `Pass` is 8 bytes in pathtrace.comp"), "{e}");
    }
}

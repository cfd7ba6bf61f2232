//! Robustness test: hundreds of thousands of calls of random served commands with random
//! arguments (invalid enums, out-of-range values, calls between `glBegin` and `glEnd`, null
//! pointers, display-list compilation) on one context. Nothing may panic, and the errors the
//! specification prescribes for the generic rules are checked on every call: a negative
//! `GLsizei` raises an error, a command not allowed between `glBegin` and `glEnd` raises
//! `GL_INVALID_OPERATION` there.

#![cfg(test)]

mod generated {
    #![allow(clippy::all, unused_variables, unused_unsafe)]
    include!(concat!(env!("OUT_DIR"), "/fuzz_calls.rs"));
}

use generated::{COMMAND_COUNT, FuzzArgs, call};

use super::Context;
use super::gl;

/// Client memory the fuzzer hands out: large enough for every command given the argument
/// ranges below (integers stay within -2..=64, so 64³ texels of 16 bytes fit).
const CLIENT_BYTES: usize = 16 << 20;

/// Arguments from a fixed-seed xorshift generator.
struct Args {
    state: u64,
    input: Vec<u8>,
    output: Vec<u8>,
}

impl Args {
    fn next(&mut self) -> u64 {
        self.state ^= self.state << 13;
        self.state ^= self.state >> 7;
        self.state ^= self.state << 17;
        self.state
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

impl FuzzArgs for Args {
    fn int(&mut self) -> i64 {
        match self.below(20) {
            0 => -1,
            1 => i64::from(i32::MIN),
            2 => 0,
            _ => self.below(67) as i64 - 2,
        }
    }

    fn float(&mut self) -> f64 {
        const SPECIAL: [f64; 11] = [0.0, 1.0, -1.0, 0.5, 90.0, 128.0, 180.0, 1e30, -1e30, f64::NAN, f64::INFINITY];
        if self.below(2) == 0 {
            SPECIAL[self.below(SPECIAL.len() as u64) as usize]
        } else {
            (self.below(4001) as f64 - 2000.0) / 1000.0
        }
    }

    fn enumeration(&mut self) -> u32 {
        match self.below(10) {
            0 => self.next() as u32,
            1 => self.below(17) as u32,
            2 => gl::GL_TEXTURE0 + self.below(6) as u32,
            _ => {
                let i = self.below(gl::NAMES.len() as u64) as usize;
                gl::NAMES[i].1 as u32
            }
        }
    }

    fn bits(&mut self) -> u32 {
        if self.below(4) == 0 { self.next() as u32 } else { 1 << self.below(21) }
    }

    fn in_ptr(&mut self) -> *const u8 {
        if self.below(20) == 0 { std::ptr::null() } else { self.input.as_ptr() }
    }

    fn out_ptr(&mut self) -> *mut u8 {
        if self.below(20) == 0 { std::ptr::null_mut() } else { self.output.as_mut_ptr() }
    }
}

#[test]
fn random_calls_never_panic_and_raise_specified_errors() {
    const CALLS: usize = 200_000;
    let mut args = Args { state: 0x9E37_79B9_7F4A_7C15, input: vec![0; CLIENT_BYTES], output: vec![0; CLIENT_BYTES] };
    let (mut ctx, _sink) = Context::with_recording();
    ctx.bind_drawable(64, 64);
    let mut errors = 0usize;
    for i in 0..CALLS {
        if i % 1000 == 999 {
            ctx.end_frame();
        }
        let index = args.below(COMMAND_COUNT as u64) as usize;
        let inside = ctx.inside_begin_end();
        let compile_only = ctx.lists.compiling() && !ctx.lists.executing();
        let made = unsafe { call(&mut ctx, index, &mut args) };
        let error = ctx.glGetError();
        errors += usize::from(error != gl::GL_NO_ERROR);
        let executed = !(made.compiled && compile_only);
        if executed && inside && !made.allowed_in_begin_end && made.name != "glGetError" {
            assert_eq!(error, gl::GL_INVALID_OPERATION, "call {i}: {} inside glBegin/glEnd", made.name);
        }
        if executed && made.negative_size && made.name != "glGetError" {
            assert_ne!(error, gl::GL_NO_ERROR, "call {i}: {} with a negative size raised no error", made.name);
        }
    }
    // Random arguments are mostly invalid: most calls must have raised an error, some not.
    assert!(errors > CALLS / 4 && errors < CALLS, "{errors} errors in {CALLS} calls");
}

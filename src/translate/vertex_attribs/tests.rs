//! Tests of generic vertex attributes: current values, arrays, display lists, queries.

use std::ffi::c_void;

use crate::translate::programs::tests::fake_program;
use crate::translate::{Context, dispatch, gl};

fn current(ctx: &mut Context, index: u32) -> [f32; 4] {
    let mut v = [f32::NAN; 4];
    unsafe { dispatch::glGetVertexAttribfv(ctx, index, gl::GL_CURRENT_VERTEX_ATTRIB, v.as_mut_ptr()) };
    v
}

fn attrib_iv(ctx: &mut Context, index: u32, pname: gl::GLenum) -> i32 {
    let mut v = -7;
    unsafe { dispatch::glGetVertexAttribiv(ctx, index, pname, &mut v) };
    v
}

#[test]
fn current_values_and_errors() {
    let (mut ctx, _) = Context::with_recording();
    assert_eq!(current(&mut ctx, 3), [0.0, 0.0, 0.0, 1.0]);
    unsafe {
        dispatch::glVertexAttrib2s(&mut ctx, 3, 5, -2);
        dispatch::glVertexAttrib4Nub(&mut ctx, 4, 255, 0, 51, 255);
        dispatch::glVertexAttrib4bv(&mut ctx, 5, [-1i8, 2, 3, 4].as_ptr());
        dispatch::glVertexAttrib1d(&mut ctx, 15, 0.5);
    }
    assert_eq!(current(&mut ctx, 3), [5.0, -2.0, 0.0, 1.0]);
    assert_eq!(current(&mut ctx, 4), [1.0, 0.0, 0.2, 1.0], "4N variants normalize");
    assert_eq!(current(&mut ctx, 5), [-1.0, 2.0, 3.0, 4.0], "others convert as they are");
    assert_eq!(current(&mut ctx, 15), [0.5, 0.0, 0.0, 1.0]);
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    unsafe { dispatch::glVertexAttrib1f(&mut ctx, 16, 1.0) };
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_VALUE);
    current(&mut ctx, 0);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_OPERATION, "attribute 0 has no current value");
    assert_eq!(attrib_iv(&mut ctx, 1, gl::GL_TEXTURE_2D), -7);
    assert_eq!(ctx.glGetError(), gl::GL_INVALID_ENUM);
    let mut max = 0;
    unsafe { dispatch::glGetIntegerv(&mut ctx, gl::GL_MAX_VERTEX_ATTRIBS, &mut max) };
    assert_eq!(max, 16);
}

#[test]
fn array_state_and_queries() {
    let (mut ctx, _) = Context::with_recording();
    let data = [0u8; 64];
    let p = data.as_ptr().cast::<c_void>();
    unsafe {
        dispatch::glVertexAttribPointer(&mut ctx, 2, 3, gl::GL_UNSIGNED_SHORT, gl::GL_TRUE, 12, p);
        dispatch::glEnableVertexAttribArray(&mut ctx, 2);
    }
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_ENABLED), 1);
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_SIZE), 3);
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_TYPE), gl::GL_UNSIGNED_SHORT as i32);
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_STRIDE), 12);
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_NORMALIZED), 1);
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING), 0);
    let mut got: *mut c_void = std::ptr::null_mut();
    unsafe { dispatch::glGetVertexAttribPointerv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_POINTER, &raw mut got) };
    assert_eq!(got as usize, p as usize);
    unsafe { dispatch::glPushClientAttrib(&mut ctx, gl::GL_CLIENT_VERTEX_ARRAY_BIT) };
    unsafe { dispatch::glDisableVertexAttribArray(&mut ctx, 2) };
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_ENABLED), 0);
    unsafe { dispatch::glPopClientAttrib(&mut ctx) };
    assert_eq!(attrib_iv(&mut ctx, 2, gl::GL_VERTEX_ATTRIB_ARRAY_ENABLED), 1, "glPopClientAttrib restores it");
    for (call, error) in [
        (Box::new(|c: &mut Context| unsafe { dispatch::glVertexAttribPointer(c, 16, 4, gl::GL_FLOAT, 0, 0, p) }) as Box<dyn Fn(&mut Context)>, gl::GL_INVALID_VALUE),
        (Box::new(|c: &mut Context| unsafe { dispatch::glVertexAttribPointer(c, 1, 5, gl::GL_FLOAT, 0, 0, p) }), gl::GL_INVALID_VALUE),
        (Box::new(|c: &mut Context| unsafe { dispatch::glVertexAttribPointer(c, 1, 4, gl::GL_FLOAT, 0, -1, p) }), gl::GL_INVALID_VALUE),
        (Box::new(|c: &mut Context| unsafe { dispatch::glVertexAttribPointer(c, 1, 4, gl::GL_HALF_FLOAT, 0, 0, p) }), gl::GL_INVALID_ENUM),
        (Box::new(|c: &mut Context| unsafe { dispatch::glEnableVertexAttribArray(c, 16) }), gl::GL_INVALID_VALUE),
    ] {
        call(&mut ctx);
        assert_eq!(ctx.glGetError(), error);
    }
}

#[test]
fn immediate_mode_generic_attributes_and_attribute_zero() {
    let (mut ctx, _) = Context::with_recording();
    unsafe {
        dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
        dispatch::glVertexAttrib3f(&mut ctx, 0, 1.0, 2.0, 3.0);
        dispatch::glVertex2f(&mut ctx, 0.0, 0.0);
        dispatch::glVertexAttrib2f(&mut ctx, 0, 4.0, 5.0);
        dispatch::glEnd(&mut ctx);
    }
    let draw = &ctx.frame.draws[0];
    assert_eq!(draw.vertices.position, vec![[1.0, 2.0, 3.0, 1.0], [0.0, 0.0, 0.0, 1.0], [4.0, 5.0, 0.0, 1.0]]);
    assert!(draw.vertices.generic.is_empty(), "no program: no generic attributes");
    fake_program(&mut ctx, true);
    unsafe {
        dispatch::glVertexAttrib1f(&mut ctx, 2, 7.0);
        dispatch::glBegin(&mut ctx, gl::GL_TRIANGLES);
        dispatch::glVertexAttrib2f(&mut ctx, 0, 0.0, 0.0);
        dispatch::glVertexAttrib2f(&mut ctx, 0, 1.0, 0.0);
        dispatch::glVertexAttrib2f(&mut ctx, 5, 9.0, 8.0);
        dispatch::glVertexAttrib2f(&mut ctx, 0, 1.0, 1.0);
        dispatch::glEnd(&mut ctx);
    }
    let v = &ctx.frame.draws.last().unwrap().vertices;
    assert_eq!(v.generic.len(), 16);
    assert_eq!(v.generic[2].values, vec![[7.0, 0.0, 0.0, 1.0]]);
    assert_eq!(v.generic[5].values, vec![[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0], [9.0, 8.0, 0.0, 1.0]]);
    assert!(v.generic[0].values.is_empty(), "attribute 0 is the position");
}

#[test]
fn generic_arrays_in_draws_and_display_lists() {
    let (mut ctx, _) = Context::with_recording();
    fake_program(&mut ctx, true);
    let positions: [f32; 6] = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    let extra: [u8; 6] = [255, 0, 0, 255, 51, 51];
    unsafe {
        dispatch::glVertexAttribPointer(&mut ctx, 0, 2, gl::GL_FLOAT, 0, 0, positions.as_ptr().cast());
        dispatch::glEnableVertexAttribArray(&mut ctx, 0);
        dispatch::glVertexAttribPointer(&mut ctx, 3, 2, gl::GL_UNSIGNED_BYTE, gl::GL_TRUE, 0, extra.as_ptr().cast());
        dispatch::glEnableVertexAttribArray(&mut ctx, 3);
        dispatch::glVertexAttrib1f(&mut ctx, 4, 6.0);
        dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
    }
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
    let v = ctx.frame.draws[0].vertices.clone();
    assert_eq!(v.position, vec![[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0]], "array 0 gives positions");
    assert_eq!(v.generic[3].values, vec![[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.2, 0.2, 0.0, 1.0]]);
    assert_eq!(v.generic[4].values, vec![[6.0, 0.0, 0.0, 1.0]]);
    unsafe {
        dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
        dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
        dispatch::glArrayElement(&mut ctx, 2);
        dispatch::glEndList(&mut ctx);
        dispatch::glVertexAttrib1f(&mut ctx, 4, 2.0);
        dispatch::glCallList(&mut ctx, 1);
    }
    let v = &ctx.frame.draws.last().unwrap().vertices;
    assert_eq!(v.generic[3].values[..3], [[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.2, 0.2, 0.0, 1.0]], "arrays read at compile time");
    assert_eq!(v.generic[4].get(0), Some([2.0, 0.0, 0.0, 1.0]), "other attributes current at execution");
    assert_eq!(current(&mut ctx, 3), [0.2, 0.2, 0.0, 1.0], "glArrayElement in the list set the current value");
}

#[test]
fn lists_compiled_without_a_program_keep_generic_arrays() {
    let (mut ctx, _) = Context::with_recording();
    let positions: [f32; 6] = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    let extra: [f32; 3] = [4.0, 5.0, 6.0];
    unsafe {
        dispatch::glVertexPointer(&mut ctx, 2, gl::GL_FLOAT, 0, positions.as_ptr().cast());
        dispatch::glEnableClientState(&mut ctx, gl::GL_VERTEX_ARRAY);
        dispatch::glVertexAttribPointer(&mut ctx, 9, 1, gl::GL_FLOAT, 0, 0, extra.as_ptr().cast());
        dispatch::glEnableVertexAttribArray(&mut ctx, 9);
        dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
        dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
        dispatch::glEndList(&mut ctx);
        dispatch::glCallList(&mut ctx, 1);
    }
    assert!(ctx.frame.draws[0].vertices.generic.is_empty(), "no program when the list runs");
    fake_program(&mut ctx, true);
    unsafe { dispatch::glCallList(&mut ctx, 1) };
    let v = &ctx.frame.draws.last().unwrap().vertices;
    assert_eq!(v.generic[9].values, vec![[4.0, 0.0, 0.0, 1.0], [5.0, 0.0, 0.0, 1.0], [6.0, 0.0, 0.0, 1.0]]);
    assert_eq!(v.generic[8].values, vec![[0.0, 0.0, 0.0, 1.0]]);
}

#[test]
fn current_values_in_lists_attrib_stacks_and_buffer_arrays() {
    let (mut ctx, _) = Context::with_recording();
    unsafe {
        dispatch::glNewList(&mut ctx, 1, gl::GL_COMPILE);
        dispatch::glVertexAttrib4fv(&mut ctx, 7, [1.0, 2.0, 3.0, 4.0].as_ptr());
        dispatch::glEndList(&mut ctx);
    }
    assert_eq!(current(&mut ctx, 7), [0.0, 0.0, 0.0, 1.0], "compiled, not executed");
    unsafe { dispatch::glCallList(&mut ctx, 1) };
    assert_eq!(current(&mut ctx, 7), [1.0, 2.0, 3.0, 4.0]);
    unsafe {
        dispatch::glPushAttrib(&mut ctx, gl::GL_CURRENT_BIT | gl::GL_ENABLE_BIT);
        dispatch::glVertexAttrib1f(&mut ctx, 7, 0.0);
        dispatch::glEnable(&mut ctx, gl::GL_VERTEX_PROGRAM_TWO_SIDE);
        dispatch::glPopAttrib(&mut ctx);
    }
    assert_eq!(current(&mut ctx, 7), [1.0, 2.0, 3.0, 4.0], "GL_CURRENT_BIT holds generic values");
    assert_eq!(unsafe { dispatch::glIsEnabled(&mut ctx, gl::GL_VERTEX_PROGRAM_TWO_SIDE) }, 0, "GL_ENABLE_BIT holds it");
    fake_program(&mut ctx, true);
    let data: [f32; 6] = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0];
    let mut vbo = 0;
    unsafe {
        dispatch::glGenBuffers(&mut ctx, 1, &mut vbo);
        dispatch::glBindBuffer(&mut ctx, gl::GL_ARRAY_BUFFER, vbo);
        dispatch::glBufferData(&mut ctx, gl::GL_ARRAY_BUFFER, 24, data.as_ptr().cast(), gl::GL_STATIC_DRAW);
        dispatch::glVertexAttribPointer(&mut ctx, 0, 2, gl::GL_FLOAT, 0, 0, std::ptr::null());
        dispatch::glVertexAttribPointer(&mut ctx, 6, 1, gl::GL_FLOAT, 0, 8, std::ptr::without_provenance(4));
        dispatch::glEnableVertexAttribArray(&mut ctx, 0);
        dispatch::glEnableVertexAttribArray(&mut ctx, 6);
        dispatch::glBindBuffer(&mut ctx, gl::GL_ARRAY_BUFFER, 0);
        dispatch::glDrawArrays(&mut ctx, gl::GL_TRIANGLES, 0, 3);
    }
    assert_eq!(attrib_iv(&mut ctx, 6, gl::GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING), vbo as i32);
    let v = &ctx.frame.draws[0].vertices;
    assert_eq!(v.position[2], [0.0, 1.0, 0.0, 1.0]);
    assert_eq!(v.generic[6].values, vec![[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]], "from the buffer object");
    assert_eq!(ctx.glGetError(), gl::GL_NO_ERROR);
}

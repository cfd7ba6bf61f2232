//! What a capture records of client memory, checked byte for byte on a program made of GL
//! calls in this test (the capture is process-wide, so this file holds one test): a draw
//! records exactly the array elements and indices it read, at draw time; pixel uploads the
//! span the unpack state describes; `glCallLists` its names; `glBufferData` its data; draws
//! from buffer objects, pixels from a pixel unpack buffer and display lists record nothing;
//! what is written through a buffer mapping is recorded at `glUnmapBuffer`, as the
//! `glBufferSubData` that has the same effect. The capture then replays (`glrt
//! replay`) to the same frames and, captured again, to the same file.

mod common;
mod programs;

use std::ffi::c_void;
use std::path::PathBuf;
use std::process::Command;
use std::sync::Arc;

use common::gl;
use glrt::frame::RecordingSink;
use glrt::frame::pixels::{PixelData, PixelKind};
use glrt::replay::{self, reader::{Capture, Record}};
use glrt::translate::capture::{self, table::COMMANDS};
use glrt::translate::gl::*;

fn scratch(name: &str) -> PathBuf {
    programs::scratch("capture_reads", name)
}

/// Client memory a call read: `(address, bytes)` per range.
type Reads = Vec<(u64, Vec<u8>)>;

/// The calls of a capture by name, with their reads.
fn calls(capture: &Capture) -> Vec<(&'static str, Reads)> {
    capture
        .records()
        .filter_map(|r| match r.unwrap().1 {
            Record::Call { id, reads, .. } => Some((COMMANDS[id].0, reads.into_iter().map(|(a, b)| (a, b.to_vec())).collect())),
            Record::Event(_) => None,
        })
        .collect()
}

fn bytes_of<T: Copy>(values: &[T]) -> Vec<u8> {
    // Safety: plain numbers, viewed as their bytes.
    unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }.to_vec()
}

fn addr<T>(p: *const T) -> u64 {
    p as usize as u64
}

/// Whether one of `reads` holds `bytes` at `address`.
fn covers(reads: &Reads, address: u64, bytes: &[u8]) -> bool {
    reads.iter().any(|(a, b)| {
        address >= *a && (address - a) as usize + bytes.len() <= b.len() && b[(address - a) as usize..][..bytes.len()] == *bytes
    })
}

#[test]
fn captures_record_exactly_the_client_memory_read_and_replay_exactly() {
    let (path, live_log) = (scratch("reads.glrtcap"), scratch("live.frames"));
    // Safety: set before any GL call and any other thread of this test binary exists.
    unsafe {
        std::env::set_var("GLRT_CAPTURE", &path);
        std::env::set_var("GLRT_FRAME_LOG", &live_log);
    }
    let _ctx = common::make_current();
    let mut vertices: Vec<[f32; 3]> = (0..8).map(|i| [i as f32, 0.5, 0.0]).collect();
    let indices: [u16; 3] = [5, 1, 7];
    let texels: Vec<u8> = (0..64).collect();
    let names: [u8; 3] = [0, 2, 1];
    let buffer_data: Vec<f32> = (0..12).map(|i| i as f32).collect();
    let mut seen_vertex_bytes = Vec::new();
    let pixel = |frame: usize| [40 * frame as u8, 255, 0, 255];
    // glShaderSource's strings: one with a length (no NUL), one NUL-terminated.
    let (part1, part2) = (b"void main() {XXXX".to_vec(), c" gl_FragColor = vec4(1.0); }".to_owned());
    let strings: Vec<*const GLchar> = vec![part1.as_ptr().cast(), part2.as_ptr()];
    let lengths: Vec<GLint> = vec![13, -1];
    let generic: Vec<[f32; 2]> = (0..4).map(|i| [i as f32, -1.0]).collect();
    let range_indices: [u8; 3] = [0, 2, 1];
    unsafe {
        let shader = gl::glCreateShader(GL_FRAGMENT_SHADER);
        gl::glShaderSource(shader, 2, strings.as_ptr(), lengths.as_ptr());
        let base = gl::glGenLists(3);
        for i in 0..3 {
            gl::glNewList(base + i, GL_COMPILE);
            gl::glBegin(GL_POINTS);
            gl::glVertex3fv(vertices[i as usize].as_ptr());
            gl::glEnd();
            gl::glEndList();
        }
        let mut vbo = 0;
        gl::glGenBuffers(1, &mut vbo);
        gl::glBindBuffer(GL_ARRAY_BUFFER, vbo);
        gl::glBufferData(GL_ARRAY_BUFFER, 48, buffer_data.as_ptr().cast(), GL_STATIC_DRAW);
        gl::glBindBuffer(GL_ARRAY_BUFFER, 0);
        let mut pbo = 0;
        gl::glGenBuffers(1, &mut pbo);
        gl::glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
        gl::glBufferData(GL_PIXEL_UNPACK_BUFFER, 16, std::ptr::null(), GL_STREAM_DRAW);
        gl::glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
        gl::glPixelStorei(GL_UNPACK_ROW_LENGTH, 4);
        gl::glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
        gl::glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels.as_ptr().cast());
        for frame in 0..3 {
            gl::glClear(GL_COLOR_BUFFER_BIT);
            gl::glEnableClientState(GL_VERTEX_ARRAY);
            gl::glVertexPointer(3, GL_FLOAT, 0, vertices.as_ptr().cast());
            gl::glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_SHORT, indices.as_ptr().cast());
            gl::glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 0, generic.as_ptr().cast());
            gl::glEnableVertexAttribArray(1);
            gl::glDrawRangeElements(GL_POINTS, 0, 2, 3, GL_UNSIGNED_BYTE, range_indices.as_ptr().cast());
            gl::glDisableVertexAttribArray(1);
            gl::glBegin(GL_POINTS);
            gl::glArrayElement(2);
            gl::glEnd();
            gl::glListBase(base);
            gl::glCallLists(3, GL_UNSIGNED_BYTE, names.as_ptr().cast());
            // A pixel from the unpack buffer (offset 8, skip 1 pixel): its bytes 12 to 15,
            // written through a mapping.
            gl::glBindBuffer(GL_PIXEL_UNPACK_BUFFER, pbo);
            let mapped = gl::glMapBufferRange(GL_PIXEL_UNPACK_BUFFER, 12, 4, GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_RANGE_BIT);
            std::ptr::copy_nonoverlapping(pixel(frame).as_ptr(), mapped.cast::<u8>(), 4);
            gl::glUnmapBuffer(GL_PIXEL_UNPACK_BUFFER);
            gl::glDrawPixels(1, 1, GL_RGBA, GL_UNSIGNED_BYTE, std::ptr::without_provenance(8));
            gl::glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
            gl::glBindBuffer(GL_ARRAY_BUFFER, vbo);
            gl::glVertexPointer(3, GL_FLOAT, 0, std::ptr::null::<c_void>());
            gl::glDrawArrays(GL_TRIANGLES, 0, 3);
            gl::glBindBuffer(GL_ARRAY_BUFFER, 0);
            glrt::gl_entry::headless::glrtSwapBuffers();
            seen_vertex_bytes.push(bytes_of(&vertices));
            // Changed after the frame: the capture must hold each frame's values.
            vertices.iter_mut().for_each(|v| v[1] += 1.0 + frame as f32);
        }
    }
    assert_eq!(common::error(), GL_NO_ERROR);
    capture::finish();

    let capture = Capture::open(&path).unwrap();
    let calls = calls(&capture);
    let of = |name: &str| calls.iter().filter(|(n, _)| *n == name).map(|(_, r)| r.clone()).collect::<Vec<_>>();
    let v = addr(vertices.as_ptr());
    let element = |frame: usize, i: usize| (v + 12 * i as u64, seen_vertex_bytes[frame][12 * i..12 * i + 12].to_vec());

    let draws = of("glDrawElements");
    assert_eq!(draws.len(), 3);
    for (frame, reads) in draws.iter().enumerate() {
        // glrt fetches the index range min..=max once (vertices 1 to 7), then assembles.
        let range = (v + 12, seen_vertex_bytes[frame][12..96].to_vec());
        let mut expected = vec![(addr(indices.as_ptr()), bytes_of(&indices)), range];
        expected.sort();
        assert_eq!(*reads, expected, "frame {frame}: indices and vertices 1..=7 as they were at the draw");
    }
    let source = of("glShaderSource");
    assert_eq!(source.len(), 1);
    let pointer_bytes: Vec<u8> = strings.iter().flat_map(|p| (*p as usize).to_ne_bytes()).collect();
    assert!(covers(&source[0], addr(strings.as_ptr()), &pointer_bytes), "the string pointers");
    assert!(covers(&source[0], addr(lengths.as_ptr()), &bytes_of(&lengths)), "the lengths");
    assert!(covers(&source[0], addr(part1.as_ptr()), &part1[..13]), "a string of a given length");
    assert!(covers(&source[0], addr(part2.as_ptr()), part2.to_bytes_with_nul()), "a NUL-terminated string");
    for (frame, reads) in of("glDrawRangeElements").iter().enumerate() {
        // Without a program in use nothing reads generic attribute 1: its array is not fetched.
        assert!(reads.iter().all(|(a, _)| *a != addr(generic.as_ptr())), "generic array 1 unread");
        assert!(covers(reads, v, &seen_vertex_bytes[frame][..36]), "vertex array elements 0..=2");
    }
    for (frame, reads) in of("glArrayElement").iter().enumerate() {
        assert_eq!(*reads, vec![element(frame, 2)], "glArrayElement(2) reads vertex 2");
    }
    assert_eq!(of("glTexImage2D"), vec![vec![(addr(texels.as_ptr()), texels[..28].to_vec())]], "skip 1 pixel, 2 rows of 4");
    assert_eq!(of("glCallLists"), vec![vec![(addr(names.as_ptr()), names.to_vec())]; 3]);
    assert_eq!(of("glBufferData"), vec![vec![(addr(buffer_data.as_ptr()), bytes_of(&buffer_data))], vec![]]);
    let written: Vec<Vec<u8>> = of("glBufferSubData").iter().flat_map(|r| r.iter().map(|(_, bytes)| bytes.clone())).collect();
    assert_eq!(written, (0..3).map(|f| pixel(f).to_vec()).collect::<Vec<_>>(), "each frame's pixel, written through the mapping");
    assert!(of("glUnmapBuffer").iter().chain(&of("glMapBufferRange")).all(Vec::is_empty));
    assert_eq!(of("glDrawPixels"), vec![Vec::new(); 3], "pixels from a buffer read no client memory");
    assert_eq!(of("glVertex3fv").len(), 3, "compiled once into each list, not recorded when lists run");
    assert!(of("glDrawArrays").iter().all(Vec::is_empty), "a buffer-object draw reads no client memory");
    assert_eq!(of("glVertexPointer").iter().filter(|r| !r.is_empty()).count(), 0, "pointers are read at draw time");

    // Replay: the same frames, and the same file when captured again.
    let (replay_log, again) = (scratch("replay.frames"), scratch("again.glrtcap"));
    let out = Command::new(env!("CARGO_BIN_EXE_glrt"))
        .arg("replay")
        .arg(&path)
        .env("GLRT_FRAME_LOG", &replay_log)
        .env("GLRT_CAPTURE", &again)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let live = std::fs::read_to_string(&live_log).unwrap();
    assert_eq!(live.lines().count(), 3);
    assert_eq!(std::fs::read_to_string(&replay_log).unwrap(), live);
    assert!(std::fs::read(&again).unwrap() == std::fs::read(&path).unwrap(), "the replay's capture differs");

    // The frame log hashes an image's size, not its pixels: replayed here with a sink that
    // keeps the frames, each draws the pixel the program wrote through the mapping.
    let sink = RecordingSink::default();
    let keep = sink.clone();
    let options = replay::Options { sink: Some(replay::SinkWrapper(Arc::new(move |_| Box::new(keep.clone())))), ..Default::default() };
    replay::run(&capture, &options).unwrap();
    let drawn: Vec<Vec<u8>> = sink
        .frames
        .lock()
        .iter()
        .flat_map(|f| f.pixels.iter())
        .filter_map(|p| match &p.kind {
            PixelKind::Image { data: PixelData::Rgba8(rgba), .. } => Some(rgba.to_vec()),
            _ => None,
        })
        .collect();
    assert_eq!(drawn, (0..3).map(|f| pixel(f).to_vec()).collect::<Vec<_>>());
}

//! Fuzzes the capture reader: arbitrary bytes as a whole file (`Capture::parse`: header,
//! LZ4 body, trailer), and as records after a valid description of a few of this build's
//! commands, ids 0 to 5 (`Capture::from_body`, reached by files whose checksums pass).
//! Neither may panic, and an error must name an offset inside the input.
#![no_main]

use std::sync::OnceLock;
use glrt::replay::reader::Capture;
use glrt::translate::capture::{format, table::COMMANDS};
use libfuzzer_sys::fuzz_target;

fn read_all(capture: &Capture, limit: usize) {
    for record in capture.records() {
        if let Err(e) = record {
            assert!(e.offset as usize <= limit);
        }
    }
}

fuzz_target!(|data: &[u8]| {
    match Capture::parse(data) {
        Ok(capture) => read_all(&capture, capture.body_len()),
        Err(e) => assert!(e.offset as usize <= data.len() || e.in_body),
    }
    static DESCRIBED: OnceLock<Vec<u8>> = OnceLock::new();
    let described = DESCRIBED.get_or_init(|| {
        let some = ["glBegin", "glVertex3f", "glTexImage2D", "glLightfv", "glCallLists", "glDrawElements"];
        let commands: Vec<(&str, &str)> = COMMANDS.iter().copied().filter(|(n, _)| some.contains(n)).collect();
        format::described(&format::description(&commands))
    });
    let body = [described.as_slice(), data].concat();
    let len = body.len();
    let capture = Capture::from_body(body, len).expect("a valid description");
    read_all(&capture, len);
});

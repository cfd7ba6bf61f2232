//! The capture file layout (format version [`VERSION`]); all integers little-endian.
//!
//! ```text
//! header (uncompressed, 12 bytes):
//!   magic        8 bytes  "GLRTCAP\0"
//!   version      u32      FORMAT VERSION (a reader refuses any other)
//! body: one LZ4 frame (block and content checksums on) holding
//!   desc_len     u32      length of the description, at most MAX_DESCRIPTION
//!   description  bytes    UTF-8: "glrt <crate version>\n", then per command id one line
//!                         "<name> <signature>\n" (signature: one letter per parameter,
//!                         `p` pointer, `v` value)
//!   desc_hash    u64      xxh3 of the description
//!   records, each starting with a tag byte:
//!   0x01 call         varint command id, one varint per parameter (the raw value: integer
//!                     bits, float bits, address), varint read count, then per read
//!                     varint address, varint length, the bytes
//!   0x02 context      varint context id (from 1), varint share-group context id (0: none)
//!   0x03 make-current varint context id (0: release), zigzag width, zigzag height,
//!                     byte double-buffered (0/1)
//!   0x04 swap         byte kind (0 glrtSwapBuffers, 1 glXSwapBuffers), and for glX the
//!                     drawable size: zigzag width, zigzag height
//! trailer (uncompressed, 24 bytes):
//!   magic        8 bytes  "GLRTEND\0"
//!   body_len     u64      bytes of the decompressed body
//!   body_hash    u64      xxh3 of the decompressed body
//! ```
//!
//! The trailer makes a truncated file (a capture that was not finished) an error even when
//! the cut falls between LZ4 blocks. The writer ends a run of blocks after the description,
//! after each frame's swap record and after each batch of records, so a capture stopped by a
//! full disk ends between records, with every frame before the cut whole (`writer`).
//!
//! Varints are LEB128 (at most 10 bytes). A reader matches the description's command names
//! with its own table, so a capture made by another glrt build replays when the commands it
//! uses have the same signatures, and is refused with the name of the first that differs.

/// First bytes of every capture file.
pub const MAGIC: &[u8; 8] = b"GLRTCAP\0";
/// The format version this build writes and reads.
pub const VERSION: u32 = 1;
/// First bytes of the trailer, and its length.
pub const TRAILER_MAGIC: &[u8; 8] = b"GLRTEND\0";
pub const TRAILER_LEN: usize = 24;

/// Largest description a reader accepts (bytes).
pub const MAX_DESCRIPTION: usize = 1 << 20;

/// Record tags.
pub const TAG_CALL: u8 = 1;
pub const TAG_CONTEXT: u8 = 2;
pub const TAG_MAKE_CURRENT: u8 = 3;
pub const TAG_SWAP: u8 = 4;

/// Which call ended a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwapKind {
    /// `glrtSwapBuffers` (headless).
    Headless,
    /// `glXSwapBuffers`, with the drawable size it refreshed.
    Glx { width: i32, height: i32 },
}

impl SwapKind {
    /// The name of the call (for the call log's frame line).
    pub fn name(self) -> &'static str {
        match self {
            SwapKind::Headless => "glrtSwapBuffers",
            SwapKind::Glx { .. } => "glXSwapBuffers",
        }
    }
}

/// A window-system event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// A context was created (ids count from 1 in creation order), sharing objects with
    /// `share` (0: none).
    Context { id: u32, share: u32 },
    /// `id` (0: none) was made current on a drawable of `width` × `height`.
    MakeCurrent { id: u32, width: i32, height: i32, double: bool },
    /// A frame ended.
    Swap(SwapKind),
}

/// The description of this build: version line and one line per command.
pub fn description(commands: &[(&str, &str)]) -> String {
    let mut d = format!("glrt {}\n", env!("CARGO_PKG_VERSION"));
    for (name, signature) in commands {
        d.push_str(name);
        d.push(' ');
        d.push_str(signature);
        d.push('\n');
    }
    d
}

/// The uncompressed header.
pub fn header() -> Vec<u8> {
    [&MAGIC[..], &VERSION.to_le_bytes()].concat()
}

/// The start of the body: the description with its length and hash.
pub fn described(description: &str) -> Vec<u8> {
    let mut h = Vec::with_capacity(description.len() + 12);
    h.extend_from_slice(&(description.len() as u32).to_le_bytes());
    h.extend_from_slice(description.as_bytes());
    h.extend_from_slice(&xxhash_rust::xxh3::xxh3_64(description.as_bytes()).to_le_bytes());
    h
}

/// Appends `v` as a LEB128 varint.
pub fn put_varint(out: &mut Vec<u8>, mut v: u64) {
    while v >= 0x80 {
        out.push((v as u8) | 0x80);
        v >>= 7;
    }
    out.push(v as u8);
}

/// Zigzag encoding of a signed value (small magnitudes give short varints).
pub fn zigzag(v: i32) -> u64 {
    u64::from(((v << 1) ^ (v >> 31)) as u32)
}

/// Inverse of [`zigzag`]; `None` past 32 bits.
pub fn unzigzag(v: u64) -> Option<i32> {
    let v = u32::try_from(v).ok()?;
    Some(((v >> 1) as i32) ^ -((v & 1) as i32))
}

/// Appends the encoding of `event`.
pub fn put_event(out: &mut Vec<u8>, event: Event) {
    match event {
        Event::Context { id, share } => {
            out.push(TAG_CONTEXT);
            put_varint(out, id.into());
            put_varint(out, share.into());
        }
        Event::MakeCurrent { id, width, height, double } => {
            out.push(TAG_MAKE_CURRENT);
            put_varint(out, id.into());
            put_varint(out, zigzag(width));
            put_varint(out, zigzag(height));
            out.push(u8::from(double));
        }
        Event::Swap(SwapKind::Headless) => out.extend_from_slice(&[TAG_SWAP, 0]),
        Event::Swap(SwapKind::Glx { width, height }) => {
            out.extend_from_slice(&[TAG_SWAP, 1]);
            put_varint(out, zigzag(width));
            put_varint(out, zigzag(height));
        }
    }
}

/// Appends a call record: command `id`, raw arguments, and the client memory it read.
pub fn put_call(out: &mut Vec<u8>, id: usize, args: &[u64], reads: &[(u64, &[u8])]) {
    out.push(TAG_CALL);
    put_varint(out, id as u64);
    for &a in args {
        put_varint(out, a);
    }
    put_varint(out, reads.len() as u64);
    for (address, bytes) in reads {
        put_varint(out, *address);
        put_varint(out, bytes.len() as u64);
        out.extend_from_slice(bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zigzag_round_trips_extremes() {
        for v in [0, 1, -1, 640, -480, i32::MAX, i32::MIN] {
            assert_eq!(unzigzag(zigzag(v)), Some(v));
        }
        assert_eq!(zigzag(-1), 1);
        assert_eq!(unzigzag(1 << 40), None);
    }

    #[test]
    fn varints_are_leb128() {
        let mut out = Vec::new();
        put_varint(&mut out, 300);
        put_varint(&mut out, u64::MAX);
        assert_eq!(&out[..2], &[0xac, 0x02]);
        assert_eq!(out.len(), 2 + 10);
    }
}

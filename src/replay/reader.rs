//! Reading a capture file, never trusting it: every length is checked against the bytes that
//! are actually there before anything is sliced or allocated, and every failure is an
//! [`Error`] naming the byte offset and the cause.
//!
//! Records are decoded without allocation: a call's arguments are held in place
//! ([`Args`]) and its memory reads are slices of the body, decoded as they are iterated
//! ([`Reads`]) after the record was checked whole.

use std::collections::HashMap;
use std::fmt;
use std::io::Read;
use std::sync::OnceLock;

use crate::translate::capture::format::{self, Event, SwapKind};
use crate::translate::capture::table::COMMANDS;

/// Largest decompressed body a reader accepts (bytes).
const MAX_BODY: u64 = 4 << 30;

/// Why a capture cannot be read, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Error {
    /// Byte offset: in the file for the header and the compressed stream, in the
    /// decompressed body for records (see `in_body`).
    pub offset: u64,
    /// Whether `offset` counts decompressed body bytes.
    pub in_body: bool,
    /// What is wrong.
    pub cause: String,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let place = if self.in_body { "decompressed body" } else { "file" };
        write!(f, "bad capture at byte {} of the {place}: {}", self.offset, self.cause)
    }
}

impl std::error::Error for Error {}

fn file_error(offset: usize, cause: impl Into<String>) -> Error {
    Error { offset: offset as u64, in_body: false, cause: cause.into() }
}

/// A capture file, read and decompressed.
pub struct Capture {
    /// The description's first line (`glrt 0.1.0`): the build that wrote it.
    pub writer: String,
    /// File command id → this build's command id.
    ids: Vec<usize>,
    /// The decompressed body.
    body: Vec<u8>,
    /// Where the records start in `body` (after the description).
    records_at: usize,
    /// Size of the file.
    pub file_len: usize,
}

/// Most arguments a command of the table has.
pub const MAX_ARGS: usize = 20;

/// The raw arguments of a call (integer bits, float bits, addresses), as a slice.
#[derive(Clone, Copy)]
pub struct Args {
    values: [u64; MAX_ARGS],
    len: usize,
}

impl std::ops::Deref for Args {
    type Target = [u64];

    fn deref(&self) -> &[u64] {
        &self.values[..self.len]
    }
}

impl std::ops::DerefMut for Args {
    fn deref_mut(&mut self) -> &mut [u64] {
        &mut self.values[..self.len]
    }
}

impl fmt::Debug for Args {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl PartialEq for Args {
    fn eq(&self, other: &Args) -> bool {
        **self == **other
    }
}

/// The client memory a call read: `(address, bytes)` ranges, decoded from the record (checked
/// when it was read) as they are iterated.
#[derive(Clone, Copy)]
pub struct Reads<'a> {
    /// The encoded ranges.
    bytes: &'a [u8],
    count: usize,
}

impl<'a> Reads<'a> {
    /// The ranges, in recorded order.
    pub fn iter(&self) -> ReadsIter<'a> {
        ReadsIter { bytes: self.bytes, pos: 0, left: self.count }
    }

    /// How many ranges.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether the call read no client memory.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }
}

impl fmt::Debug for Reads<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl PartialEq for Reads<'_> {
    fn eq(&self, other: &Reads<'_>) -> bool {
        self.iter().eq(other.iter())
    }
}

impl<'a> IntoIterator for Reads<'a> {
    type Item = (u64, &'a [u8]);
    type IntoIter = ReadsIter<'a>;

    fn into_iter(self) -> ReadsIter<'a> {
        self.iter()
    }
}

/// Iterator over [`Reads`].
pub struct ReadsIter<'a> {
    bytes: &'a [u8],
    pos: usize,
    left: usize,
}

impl<'a> Iterator for ReadsIter<'a> {
    type Item = (u64, &'a [u8]);

    fn next(&mut self) -> Option<(u64, &'a [u8])> {
        self.left = self.left.checked_sub(1)?;
        let address = varint(self.bytes, &mut self.pos).ok()?;
        let len = usize::try_from(varint(self.bytes, &mut self.pos).ok()?).ok()?;
        let data = self.bytes.get(self.pos..self.pos.checked_add(len)?)?;
        self.pos += len;
        Some((address, data))
    }
}

/// Why a varint could not be decoded.
enum BadVarint {
    Truncated,
    TooLong,
}

/// The LEB128 varint at `bytes[*pos..]`, advancing `pos` past it.
#[inline(always)]
fn varint(bytes: &[u8], pos: &mut usize) -> Result<u64, BadVarint> {
    match bytes.get(*pos) {
        Some(&b) if b < 0x80 => {
            *pos += 1;
            Ok(u64::from(b))
        }
        _ => varint_long(bytes, pos),
    }
}

/// [`varint`] of more than one byte.
#[inline(never)]
fn varint_long(bytes: &[u8], pos: &mut usize) -> Result<u64, BadVarint> {
    let mut v = 0u64;
    for shift in (0..64).step_by(7) {
        let &b = bytes.get(*pos).ok_or(BadVarint::Truncated)?;
        *pos += 1;
        if shift == 63 && b > 1 {
            break;
        }
        v |= u64::from(b & 0x7f) << shift;
        if b & 0x80 == 0 {
            return Ok(v);
        }
    }
    Err(BadVarint::TooLong)
}

/// One record of the body.
#[derive(Debug, PartialEq)]
pub enum Record<'a> {
    /// A GL call: this build's command id, the raw arguments, the client memory it read.
    Call { id: usize, args: Args, reads: Reads<'a> },
    /// A window-system event.
    Event(Event),
}

/// A cursor over the header or the description.
struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
    in_body: bool,
}

impl<'a> Cursor<'a> {
    fn error(&self, at: usize, cause: impl Into<String>) -> Error {
        Error { offset: at as u64, in_body: self.in_body, cause: cause.into() }
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], Error> {
        let left = self.bytes.len() - self.pos;
        if n > left {
            return Err(self.error(self.pos, format!("truncated: {what} needs {n} bytes, {left} left")));
        }
        self.pos += n;
        Ok(&self.bytes[self.pos - n..self.pos])
    }

    fn u32(&mut self, what: &str) -> Result<u32, Error> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
}

/// Counts the bytes the decompressor consumed, to name the offset of a compressed-stream
/// error.
struct Counting<'a> {
    inner: &'a [u8],
    consumed: usize,
}

impl Read for Counting<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.consumed += n;
        Ok(n)
    }
}

impl Capture {
    /// Reads a capture from its bytes.
    pub fn parse(bytes: &[u8]) -> Result<Capture, Error> {
        let mut c = Cursor { bytes, pos: 0, in_body: false };
        if c.take(format::MAGIC.len(), "the magic")? != format::MAGIC {
            return Err(file_error(0, "not a glrt capture (wrong magic)"));
        }
        let version = c.u32("the format version")?;
        if version != format::VERSION {
            return Err(file_error(
                8,
                format!("format version {version}, this glrt reads version {} only", format::VERSION),
            ));
        }
        let body_at = c.pos;
        let mut input = Counting { inner: &bytes[body_at..], consumed: 0 };
        let mut body = Vec::new();
        let read = lz4_flex::frame::FrameDecoder::new(&mut input).take(MAX_BODY + 1).read_to_end(&mut body);
        if let Err(e) = read {
            return Err(file_error(body_at + input.consumed, format!("compressed body: {e}")));
        }
        if body.len() as u64 > MAX_BODY {
            return Err(file_error(body_at, format!("body larger than {MAX_BODY} bytes")));
        }
        let body_len = input.consumed;
        let trailer_at = body_at + body_len;
        let trailer = &bytes[trailer_at..];
        if trailer.len() != format::TRAILER_LEN || &trailer[..8] != format::TRAILER_MAGIC {
            return Err(file_error(trailer_at, format!(
                "no end trailer after the compressed body ({} bytes there, {} expected): the file is truncated or the capture was not finished",
                trailer.len(),
                format::TRAILER_LEN
            )));
        }
        let le = |b: &[u8]| u64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
        if le(&trailer[8..16]) != body.len() as u64 || le(&trailer[16..24]) != xxhash_rust::xxh3::xxh3_64(&body) {
            return Err(file_error(trailer_at, "the body's length or hash differs from the end trailer's (file corrupted)"));
        }
        Capture::from_body(body, bytes.len())
    }

    /// A capture from its decompressed body (description and records), `file_len` bytes
    /// long as a file.
    pub fn from_body(body: Vec<u8>, file_len: usize) -> Result<Capture, Error> {
        let (writer, ids, records_at) = describe(&body)?;
        Ok(Capture { writer, ids, body, records_at, file_len })
    }

    /// Reads the capture file at `path`.
    pub fn open(path: &std::path::Path) -> Result<Capture, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Capture::parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Bytes of decompressed records.
    pub fn body_len(&self) -> usize {
        self.body.len()
    }

    /// The records, in order.
    pub fn records(&self) -> Records<'_> {
        Records { capture: self, pos: self.records_at }
    }

    /// The frames the capture holds (its swaps, up to the first record that cannot be read):
    /// what a replay of all of it ends.
    pub fn frames(&self) -> u64 {
        let swaps = self.records().map_while(Result::ok).filter(|(_, record)| matches!(record, Record::Event(Event::Swap(_))));
        swaps.count() as u64
    }
}

/// Reads the description at the start of the body: the writer's version line, the command
/// ids, and where the records start.
fn describe(body: &[u8]) -> Result<(String, Vec<usize>, usize), Error> {
    let mut c = Cursor { bytes: body, pos: 0, in_body: true };
    let len = c.u32("the description length")? as usize;
    if len > format::MAX_DESCRIPTION {
        return Err(c.error(0, format!("description of {len} bytes (at most {})", format::MAX_DESCRIPTION)));
    }
    let description = c.take(len, "the description")?;
    let hash_at = c.pos;
    if xxhash_rust::xxh3::xxh3_64(description).to_le_bytes() != c.take(8, "the description hash")? {
        return Err(c.error(hash_at, "description hash mismatch (description corrupted)"));
    }
    let text = std::str::from_utf8(description).map_err(|e| c.error(4 + e.valid_up_to(), "description is not UTF-8"))?;
    let (writer, ids) = match_commands(text).map_err(|(at, cause)| c.error(4 + at, cause))?;
    Ok((writer.to_owned(), ids, c.pos))
}

/// Maps the description's commands to this build's ids: `(version line, ids)`, or the offset
/// in the description and the cause.
fn match_commands(description: &str) -> Result<(&str, Vec<usize>), (usize, String)> {
    static OURS: OnceLock<HashMap<&str, (usize, &str)>> = OnceLock::new();
    let ours = OURS.get_or_init(|| COMMANDS.iter().enumerate().map(|(i, (n, s))| (*n, (i, *s))).collect());
    let mut lines = description.split_inclusive('\n');
    let writer = lines.next().unwrap_or("").trim_end();
    if !writer.starts_with("glrt ") {
        return Err((0, format!("description does not start with a glrt version line: {writer:?}")));
    }
    let mut at = writer.len() + 1;
    let mut ids = Vec::new();
    for line in lines {
        let text = line.trim_end_matches('\n');
        let (name, signature) = text.split_once(' ').unwrap_or((text, ""));
        match ours.get(name) {
            Some(&(id, ours)) if ours == signature => ids.push(id),
            Some(&(_, ours)) => {
                return Err((at, format!(
                    "{name} has signature {signature:?} in the capture and {ours:?} in this build: written by another glrt build ({writer})"
                )));
            }
            None => {
                return Err((at, format!("{name:?} is unknown to this build: written by another glrt build ({writer})")));
            }
        }
        at += line.len();
    }
    Ok((writer, ids))
}

/// Iterator over the records of a [`Capture`]; stops after the first error.
pub struct Records<'a> {
    capture: &'a Capture,
    pos: usize,
}

impl<'a> Records<'a> {
    fn error(&self, at: usize, cause: impl Into<String>) -> Error {
        Error { offset: at as u64, in_body: true, cause: cause.into() }
    }

    fn byte(&mut self, what: &str) -> Result<u8, Error> {
        let b = *self.capture.body.get(self.pos).ok_or_else(|| self.error(self.pos, format!("truncated record: {what} missing")))?;
        self.pos += 1;
        Ok(b)
    }

    #[inline(always)]
    fn varint(&mut self, what: &str) -> Result<u64, Error> {
        let start = self.pos;
        varint(&self.capture.body, &mut self.pos).map_err(|bad| self.varint_error(bad, start, what))
    }

    #[cold]
    fn varint_error(&self, bad: BadVarint, start: usize, what: &str) -> Error {
        match bad {
            BadVarint::Truncated => self.error(self.capture.body.len(), format!("truncated record: {what} missing")),
            BadVarint::TooLong => self.error(start, format!("{what}: varint longer than 64 bits")),
        }
    }

    fn int(&mut self, what: &str) -> Result<i32, Error> {
        let at = self.pos;
        format::unzigzag(self.varint(what)?).ok_or_else(|| self.error(at, format!("{what} does not fit 32 bits")))
    }

    fn u32(&mut self, what: &str) -> Result<u32, Error> {
        let at = self.pos;
        u32::try_from(self.varint(what)?).map_err(|_| self.error(at, format!("{what} does not fit 32 bits")))
    }

    fn flag(&mut self, what: &str) -> Result<bool, Error> {
        match self.byte(what)? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(self.error(self.pos - 1, format!("{what} is {b}, not 0 or 1"))),
        }
    }

    fn call(&mut self) -> Result<Record<'a>, Error> {
        let at = self.pos;
        let file_id = self.varint("command id")?;
        let id = usize::try_from(file_id)
            .ok()
            .and_then(|i| self.capture.ids.get(i).copied())
            .ok_or_else(|| self.error(at, format!("command id {file_id} is not in the description")))?;
        let (name, signature) = COMMANDS[id];
        if signature.len() > MAX_ARGS {
            return Err(self.error(at, format!("{name} has {} arguments, more than {MAX_ARGS}", signature.len())));
        }
        let mut args = Args { values: [0; MAX_ARGS], len: signature.len() };
        for slot in &mut args.values[..signature.len()] {
            *slot = self.varint(name)?;
        }
        let count_at = self.pos;
        let count = self.varint("read count")?;
        let left = self.capture.body.len() - self.pos;
        // Every read takes at least two bytes: the count cannot exceed what is left.
        if count > (left / 2) as u64 {
            return Err(self.error(count_at, format!("{name}: {count} memory reads, only {left} bytes left")));
        }
        let reads_at = self.pos;
        for _ in 0..count {
            let address = self.varint("read address")?;
            let len_at = self.pos;
            let len = self.varint("read length")?;
            let left = self.capture.body.len() - self.pos;
            if len > left as u64 {
                return Err(self.error(len_at, format!("{name}: read of {len} bytes, only {left} left")));
            }
            if address.checked_add(len).is_none() {
                return Err(self.error(len_at, format!("{name}: read of {len} bytes at {address:#x} wraps around")));
            }
            self.pos += len as usize;
        }
        let reads = Reads { bytes: &self.capture.body[reads_at..self.pos], count: count as usize };
        Ok(Record::Call { id, args, reads })
    }

    fn next_record(&mut self) -> Result<Record<'a>, Error> {
        let at = self.pos;
        Ok(match self.byte("record tag")? {
            format::TAG_CALL => return self.call(),
            format::TAG_CONTEXT => Record::Event(Event::Context { id: self.u32("context id")?, share: self.u32("share id")? }),
            format::TAG_MAKE_CURRENT => Record::Event(Event::MakeCurrent {
                id: self.u32("context id")?,
                width: self.int("width")?,
                height: self.int("height")?,
                double: self.flag("double-buffered flag")?,
            }),
            format::TAG_SWAP => Record::Event(Event::Swap(if self.flag("swap kind")? {
                SwapKind::Glx { width: self.int("width")?, height: self.int("height")? }
            } else {
                SwapKind::Headless
            })),
            tag => return Err(self.error(at, format!("unknown record tag {tag:#04x}"))),
        })
    }
}

impl<'a> Iterator for Records<'a> {
    /// The record and the body offset it starts at.
    type Item = Result<(usize, Record<'a>), Error>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.pos >= self.capture.body.len() {
            return None;
        }
        let at = self.pos;
        let record = self.next_record();
        if record.is_err() {
            self.pos = self.capture.body.len();
        }
        Some(record.map(|r| (at, r)))
    }
}

#[cfg(test)]
mod tests {
    use super::{COMMANDS, MAX_ARGS, Reads};

    #[test]
    fn every_command_fits_the_argument_storage() {
        let longest = COMMANDS.iter().map(|(_, signature)| signature.len()).max();
        assert!(longest.is_some_and(|n| (10..=MAX_ARGS).contains(&n)), "{longest:?}");
    }

    #[test]
    fn reads_decode_as_iterated() {
        // Address 0x1234 (two-byte varint), 3 bytes; address 5, no bytes.
        let bytes = [0xb4, 0x24, 3, 7, 8, 9, 5, 0];
        let reads = Reads { bytes: &bytes, count: 2 };
        let ranges: Vec<_> = reads.iter().collect();
        assert_eq!(ranges, [(0x1234, &[7u8, 8, 9][..]), (5, &[][..])]);
        assert_eq!(Reads { bytes: &bytes[..4], count: 1 }.iter().count(), 0, "a cut range is not read");
    }
}

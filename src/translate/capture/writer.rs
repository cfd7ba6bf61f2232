//! Writing a capture file: records are appended to an in-memory batch under a lock; full
//! batches, and the batch that ends each frame, go to a background thread that LZ4-compresses
//! them into the file, so the program only pays for encoding its calls.
//!
//! A write that fails (a full disk) ends the capture, said once on stderr, and the file is
//! closed where the last batch that was written completely ended: the part of the block that
//! failed is cut off, and the body's end mark, its checksum and the trailer follow. Batches end
//! between records, so a reader gets every frame up to the last one that reached the disk
//! (`glrt replay` and `glrt dump` read it as any finished capture). The program goes on,
//! unrecorded. `disk-full@N` in `GLRT_FAULTS` ([`crate::faults`]) makes the file's disk full
//! after N bytes.

use std::fs::File;
use std::io::{self, Seek, SeekFrom, Write};
use std::path::Path;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::thread::JoinHandle;

use lz4_flex::frame::{BlockMode, BlockSize, FrameEncoder, FrameInfo};
use parking_lot::Mutex;

use super::format;

/// Bytes of records collected before a batch goes to the compressing thread.
const BATCH: usize = 1 << 18;
/// Batches in flight before the program waits for the compressor.
const QUEUE: usize = 64;

/// An open capture file.
pub struct Writer {
    state: Mutex<State>,
}

struct State {
    batch: Vec<u8>,
    /// `None` once finished, or once the compressing thread stopped on an error.
    queue: Option<SyncSender<Vec<u8>>>,
    thread: Option<JoinHandle<io::Result<()>>>,
}

/// The LZ4 frame settings of capture bodies (fixed: captures of equal calls are equal files).
fn frame_info() -> FrameInfo {
    FrameInfo::new().block_size(BlockSize::Max256KB).block_mode(BlockMode::Linked).block_checksums(true).content_checksum(true)
}

impl Writer {
    /// Creates `path`, writes the header, and starts the body with the description of
    /// `commands`.
    pub fn create(path: &Path, commands: &[(&str, &str)]) -> io::Result<Writer> {
        Writer::create_on(path, commands, crate::faults::disk_room())
    }

    /// [`Writer::create`] on a disk with `room` bytes free (`None`: as much as the disk has).
    fn create_on(path: &Path, commands: &[(&str, &str)], room: Option<u64>) -> io::Result<Writer> {
        let mut file = CaptureFile::new(File::create(path)?, room);
        file.write_all(&format::header())?;
        let (queue, batches) = sync_channel::<Vec<u8>>(QUEUE);
        // The description goes first, alone: a file cut short by a full disk still has it.
        queue.send(format::described(&format::description(commands))).map_err(io::Error::other)?;
        let path = path.to_path_buf();
        let thread = std::thread::Builder::new().name("glrt-capture".into()).spawn(move || compress(file, batches, &path))?;
        Ok(Writer { state: Mutex::new(State { batch: Vec::with_capacity(BATCH), queue: Some(queue), thread: Some(thread) }) })
    }

    /// Appends one record, encoded by `encode`.
    pub fn record(&self, encode: impl FnOnce(&mut Vec<u8>)) {
        let mut state = self.state.lock();
        if state.queue.is_none() {
            return;
        }
        encode(&mut state.batch);
        if state.batch.len() >= BATCH {
            send(&mut state);
        }
    }

    /// Sends the batch that ends a frame (the swap was the last record): the file then holds
    /// that frame whatever happens to later writes.
    pub fn frame_ended(&self) {
        let mut state = self.state.lock();
        if state.queue.is_some() && !state.batch.is_empty() {
            send(&mut state);
        }
    }

    /// Sends the last batch, waits until the file is complete and closed. Later records are
    /// dropped. Returns the first write error.
    pub fn finish(&self) -> io::Result<()> {
        let (batch, queue, thread) = {
            let mut state = self.state.lock();
            (std::mem::take(&mut state.batch), state.queue.take(), state.thread.take())
        };
        if let Some(queue) = queue {
            let _ = queue.send(batch);
        }
        match thread.map(JoinHandle::join) {
            Some(Ok(result)) => result,
            Some(Err(_)) => Err(io::Error::other("the capture thread failed")),
            None => Ok(()),
        }
    }
}

/// Sends the batch to the compressing thread; once that thread stopped (a write failed),
/// recording stops.
fn send(state: &mut State) {
    let full = std::mem::replace(&mut state.batch, Vec::with_capacity(BATCH));
    if state.queue.as_ref().is_some_and(|queue| queue.send(full).is_err()) {
        state.queue = None;
    }
}

/// The capture file, counting the bytes written, with room for at most `room` bytes when the
/// disk is made full on purpose ([`crate::faults::disk_room`]).
struct CaptureFile {
    file: File,
    written: u64,
    room: Option<u64>,
}

impl CaptureFile {
    fn new(file: File, room: Option<u64>) -> CaptureFile {
        CaptureFile { file, written: 0, room }
    }

    /// Cuts the file to its first `len` bytes and writes on from there.
    fn truncate(&mut self, len: u64) -> io::Result<()> {
        self.file.set_len(len)?;
        self.file.seek(SeekFrom::Start(len))?;
        self.written = len;
        Ok(())
    }
}

impl Write for CaptureFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let room = self.room.map_or(buf.len(), |room| room.saturating_sub(self.written).min(buf.len() as u64) as usize);
        if room == 0 && !buf.is_empty() {
            return Err(io::Error::from_raw_os_error(28)); // ENOSPC, as a full disk answers
        }
        let n = self.file.write(&buf[..room])?;
        self.written += n as u64;
        Ok(n)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

/// Where the body can be ended: everything before is on disk.
#[derive(Clone)]
struct Checkpoint {
    /// Bytes of the file.
    file_len: u64,
    /// Bytes of the body (decompressed).
    body_len: u64,
    /// xxh3 of the body, for the trailer.
    hash: xxhash_rust::xxh3::Xxh3,
    /// xxh32 of the body, the LZ4 frame's content checksum.
    content: xxhash_rust::xxh32::Xxh32,
}

/// The compressing thread: writes every batch into one LZ4 frame until the queue closes,
/// then the trailer; on a write error, ends the file at a batch written before (see the
/// module doc) and stops, which the program sees as a closed queue.
fn compress(file: CaptureFile, batches: Receiver<Vec<u8>>, path: &Path) -> io::Result<()> {
    let room = file.room;
    let mut encoder = FrameEncoder::with_frame_info(frame_info(), file);
    // The ends of the last two batches written: where the file can be closed when a write
    // fails (the earlier one when closing at the last does not fit either).
    let mut ends: [Option<Checkpoint>; 2] = [None, None];
    for batch in batches {
        // Each batch is flushed as its own blocks, so the file ends between records.
        if let Err(e) = encoder.write_all(&batch).and_then(|()| encoder.flush()) {
            return stop(encoder.into_inner(), &ends, path, e);
        }
        let mut end = ends[1].clone().unwrap_or_else(|| Checkpoint {
            file_len: 0,
            body_len: 0,
            hash: xxhash_rust::xxh3::Xxh3::new(),
            content: xxhash_rust::xxh32::Xxh32::new(0),
        });
        end.hash.update(&batch);
        end.content.update(&batch);
        end.body_len += batch.len() as u64;
        end.file_len = encoder.get_ref().written;
        ends = [ends[1].take(), Some(end)];
    }
    let finished = encoder.finish().map_err(io::Error::other).and_then(|mut file| {
        let (len, hash) = ends[1].as_ref().map_or((0, xxhash_rust::xxh3::Xxh3::new()), |e| (e.body_len, e.hash.clone()));
        write_trailer(&mut file, len, &hash)
    });
    match finished {
        Ok(()) => Ok(()),
        // The end itself did not fit: end at a batch instead.
        Err(e) => match File::options().write(true).open(path) {
            Ok(file) => stop(CaptureFile::new(file, room), &ends, path, e),
            Err(_) => Err(e),
        },
    }
}

/// Ends the file at the last of `ends` where the end fits, after write error `error`: what
/// follows cut off, the LZ4 end mark, the content checksum and the trailer written. Says so
/// once on stderr and returns `error`.
fn stop(mut file: CaptureFile, ends: &[Option<Checkpoint>; 2], path: &Path, error: io::Error) -> io::Result<()> {
    let close = |file: &mut CaptureFile, at: &Checkpoint| {
        file.truncate(at.file_len)?;
        file.write_all(&0u32.to_le_bytes())?; // LZ4 end mark
        file.write_all(&at.content.digest().to_le_bytes())?;
        write_trailer(file, at.body_len, &at.hash)
    };
    let mut closed = Err(io::Error::other("not even the description was written"));
    for at in ends.iter().rev().flatten() {
        closed = close(&mut file, at);
        if closed.is_ok() {
            break;
        }
    }
    match closed {
        Ok(()) => eprintln!(
            "glrt: GLRT_CAPTURE: writing {} failed ({error}); the capture stops here and the file holds the frames written before",
            path.display()
        ),
        Err(e) => eprintln!("glrt: GLRT_CAPTURE: writing {} failed ({error}); the capture stops and the file cannot be closed ({e})", path.display()),
    }
    Err(error)
}

/// Writes the trailer of a body of `len` bytes whose xxh3 is `hash`.
fn write_trailer(file: &mut impl Write, len: u64, hash: &xxhash_rust::xxh3::Xxh3) -> io::Result<()> {
    file.write_all(format::TRAILER_MAGIC)?;
    file.write_all(&len.to_le_bytes())?;
    file.write_all(&hash.digest().to_le_bytes())?;
    file.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::replay::reader::{Capture, Record};
    use crate::translate::capture::format::{Event, SwapKind};
    use crate::translate::capture::table::COMMANDS;

    #[test]
    fn what_is_written_reads_back() {
        let path = std::env::temp_dir().join(format!("glrt-writer-{}.glrtcap", std::process::id()));
        let writer = Writer::create(&path, COMMANDS).unwrap();
        let id = COMMANDS.iter().position(|c| c.0 == "glLightfv").unwrap();
        let params = [1.0f32, 2.0, 3.0, 0.0].map(f32::to_ne_bytes).concat();
        let events = [
            Event::Context { id: 1, share: 0 },
            Event::MakeCurrent { id: 1, width: 640, height: -1, double: false },
            Event::Swap(SwapKind::Glx { width: 640, height: 480 }),
            Event::Swap(SwapKind::Headless),
        ];
        writer.record(|out| format::put_event(out, events[0]));
        writer.record(|out| format::put_event(out, events[1]));
        // Enough records to fill several batches.
        for _ in 0..20_000 {
            writer.record(|out| format::put_call(out, id, &[0x4000, 0x1203, 0x7ffc_0000_1000], &[(0x7ffc_0000_1000, &params)]));
        }
        writer.record(|out| format::put_event(out, events[2]));
        writer.record(|out| format::put_event(out, events[3]));
        writer.finish().unwrap();
        writer.record(|out| format::put_event(out, events[3]));
        let capture = Capture::open(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let records: Vec<Record> = capture.records().map(|r| r.unwrap().1).collect();
        assert_eq!(records.len(), 20_004, "nothing is recorded after finish");
        assert_eq!(records[..2], [Record::Event(events[0]), Record::Event(events[1])]);
        let Record::Call { id: call_id, args, reads } = &records[2] else { panic!("record 2 is a call: {:?}", records[2]) };
        assert_eq!((*call_id, &args[..]), (id, &[0x4000, 0x1203, 0x7ffc_0000_1000][..]));
        assert_eq!(reads.iter().collect::<Vec<_>>(), [(0x7ffc_0000_1000, &params[..])]);
        assert_eq!(records[20_002..], [Record::Event(events[2]), Record::Event(events[3])]);
        assert_eq!(capture.writer, format!("glrt {}", env!("CARGO_PKG_VERSION")));
    }

    #[test]
    fn a_full_disk_leaves_the_frames_written_before() {
        let path = std::env::temp_dir().join(format!("glrt-writer-full-{}.glrtcap", std::process::id()));
        let id = COMMANDS.iter().position(|c| c.0 == "glLightfv").unwrap();
        let params: Vec<u8> = (0..64u8).collect();
        // Each frame: 200 calls (about 14 KB), then its swap.
        let frame = |writer: &Writer, n: u64| {
            for i in 0..200u64 {
                writer.record(|out| format::put_call(out, id, &[n, i, 0x1000], &[(0x1000, &params)]));
            }
            writer.record(|out| format::put_event(out, Event::Swap(SwapKind::Headless)));
            writer.frame_ended();
        };
        // A disk with room for the description and a few frames (LZ4 compresses these
        // records well).
        Writer::create_on(&path, COMMANDS, None).unwrap().finish().unwrap();
        let room = std::fs::metadata(&path).unwrap().len() + 6_000;
        let writer = Writer::create_on(&path, COMMANDS, Some(room)).unwrap();
        for n in 0..40 {
            frame(&writer, n);
        }
        let error = writer.finish().unwrap_err();
        assert_eq!(error.raw_os_error(), Some(28), "ENOSPC: {error}");
        assert!(std::fs::metadata(&path).unwrap().len() <= room);
        let capture = Capture::open(&path).unwrap();
        let records: Vec<Record> = capture.records().map(|r| r.unwrap().1).collect();
        std::fs::remove_file(&path).unwrap();
        let swaps = records.iter().filter(|r| matches!(r, Record::Event(Event::Swap(_)))).count();
        assert!((1..40).contains(&swaps), "{swaps} whole frames kept of 40");
        assert_eq!(records.len(), swaps * 201, "the file ends after a frame's swap");
        let Record::Call { id: call_id, args, reads } = &records[201 * swaps - 2] else { panic!("the last frame's last call: {:?}", records[201 * swaps - 2]) };
        assert_eq!((*call_id, &args[..]), (id, &[swaps as u64 - 1, 199, 0x1000][..]));
        assert_eq!(reads.iter().collect::<Vec<_>>(), [(0x1000, &params[..])]);
    }
}

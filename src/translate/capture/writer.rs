//! Writing a capture file: records are appended to an in-memory batch under a lock; full
//! batches go to a background thread that LZ4-compresses them into the file, so the program
//! only pays for encoding its calls.

use std::fs::File;
use std::io::{self, BufWriter, Write};
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
    /// `None` once finished.
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
        let mut file = BufWriter::with_capacity(1 << 16, File::create(path)?);
        file.write_all(&format::header())?;
        let (queue, batches) = sync_channel::<Vec<u8>>(QUEUE);
        let thread = std::thread::Builder::new().name("glrt-capture".into()).spawn(move || compress(file, batches))?;
        let mut batch = Vec::with_capacity(BATCH);
        batch.extend_from_slice(&format::described(&format::description(commands)));
        Ok(Writer { state: Mutex::new(State { batch, queue: Some(queue), thread: Some(thread) }) })
    }

    /// Appends one record, encoded by `encode`.
    pub fn record(&self, encode: impl FnOnce(&mut Vec<u8>)) {
        let mut state = self.state.lock();
        if state.queue.is_none() {
            return;
        }
        encode(&mut state.batch);
        if state.batch.len() >= BATCH {
            let full = std::mem::replace(&mut state.batch, Vec::with_capacity(BATCH));
            if let Some(queue) = &state.queue {
                let _ = queue.send(full);
            }
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

/// The compressing thread: writes every batch into one LZ4 frame until the queue closes,
/// then the trailer.
fn compress(file: BufWriter<File>, batches: Receiver<Vec<u8>>) -> io::Result<()> {
    let mut encoder = FrameEncoder::with_frame_info(frame_info(), file);
    let mut hash = xxhash_rust::xxh3::Xxh3::new();
    let mut len = 0u64;
    for batch in batches {
        hash.update(&batch);
        len += batch.len() as u64;
        encoder.write_all(&batch)?;
    }
    let mut file = encoder.finish().map_err(io::Error::other)?;
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
}

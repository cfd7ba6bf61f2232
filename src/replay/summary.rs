//! `glrt info FILE`: what a capture holds — frames, contexts, calls per function, bytes of
//! client memory, and the texture images uploaded with the hash of their contents.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::reader::{Capture, Record};
use crate::translate::capture::format::Event;
use crate::translate::capture::table::COMMANDS;

/// One texture image upload (`glTexImage*`, `glTexSubImage*`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Upload {
    /// The frame it happened in.
    pub frame: u64,
    /// The command.
    pub command: &'static str,
    /// Width, height and depth as passed (1 for missing dimensions).
    pub size: [u64; 3],
    /// Bytes of client memory read.
    pub bytes: usize,
    /// xxh3 of those bytes, in address order.
    pub hash: u64,
}

/// The summary of a capture.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Summary {
    /// Frames ended.
    pub frames: u64,
    /// Contexts created.
    pub contexts: u64,
    /// Calls per command name.
    pub calls: BTreeMap<&'static str, u64>,
    /// Bytes of client memory recorded.
    pub memory_bytes: u64,
    /// Texture image uploads.
    pub uploads: Vec<Upload>,
}

/// The index of the width parameter of a texture image command, and how many dimensions it
/// has: `glTexImage2D(target, level, internalformat, width, height, ...)`.
fn image_dims(name: &str) -> Option<(usize, usize)> {
    let base = name.trim_end_matches("EXT");
    let dims = match base.chars().nth_back(1)? {
        '1' => 1,
        '2' => 2,
        '3' => 3,
        _ => return None,
    };
    if base.starts_with("glTexImage") {
        Some((3, dims))
    } else if base.starts_with("glTexSubImage") {
        Some((2 + dims, dims))
    } else {
        None
    }
}

impl Summary {
    /// Reads every record of `capture`.
    pub fn of(capture: &Capture) -> Result<Summary, String> {
        let mut s = Summary::default();
        for record in capture.records() {
            match record.map_err(|e| e.to_string())?.1 {
                Record::Call { id, args, reads } => {
                    let name = COMMANDS[id].0;
                    *s.calls.entry(name).or_default() += 1;
                    let bytes: usize = reads.iter().map(|(_, b)| b.len()).sum();
                    s.memory_bytes += bytes as u64;
                    if let Some((first, dims)) = image_dims(name)
                        && bytes > 0
                    {
                        let mut size = [1u64; 3];
                        for (d, slot) in size.iter_mut().enumerate().take(dims) {
                            *slot = args.get(first + d).map_or(0, |&v| u64::from(v as u32));
                        }
                        let mut hasher = xxhash_rust::xxh3::Xxh3::new();
                        reads.iter().for_each(|(_, b)| hasher.update(b));
                        s.uploads.push(Upload { frame: s.frames, command: name, size, bytes, hash: hasher.digest() });
                    }
                }
                Record::Event(Event::Swap(_)) => s.frames += 1,
                Record::Event(Event::Context { .. }) => s.contexts += 1,
                Record::Event(Event::MakeCurrent { .. }) => {}
            }
        }
        Ok(s)
    }

    /// The report `glrt info FILE` prints.
    pub fn report(&self, capture: &Capture) -> String {
        let mut out = String::new();
        let total: u64 = self.calls.values().sum();
        let _ = writeln!(out, "written by: {}", capture.writer);
        let _ = writeln!(out, "file: {} bytes ({} decompressed)", capture.file_len, capture.body_len());
        let per_frame = capture.file_len as u64 / self.frames.max(1);
        let _ = writeln!(out, "frames: {} ({per_frame} bytes per frame)", self.frames);
        let _ = writeln!(out, "contexts: {}", self.contexts);
        let _ = writeln!(out, "calls: {total}");
        let _ = writeln!(out, "client memory recorded: {} bytes", self.memory_bytes);
        let _ = writeln!(out, "calls per function:");
        let mut by_count: Vec<_> = self.calls.iter().collect();
        by_count.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        for (name, n) in by_count {
            let _ = writeln!(out, "  {n:>9} {name}");
        }
        let _ = writeln!(out, "texture uploads: {}", self.uploads.len());
        for u in &self.uploads {
            let [w, h, d] = u.size;
            let _ = writeln!(out, "  frame {} {} {w}x{h}x{d} {} bytes xxh3 {:016x}", u.frame, u.command, u.bytes, u.hash);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::image_dims;

    #[test]
    fn texture_image_commands_name_their_sizes() {
        assert_eq!(image_dims("glTexImage2D"), Some((3, 2)));
        assert_eq!(image_dims("glTexSubImage3DEXT"), Some((5, 3)));
        assert_eq!(image_dims("glTexSubImage1D"), Some((3, 1)));
        assert_eq!(image_dims("glTexParameteri"), None);
    }
}

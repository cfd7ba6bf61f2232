//! `GLRT_DUMP=dir`: every presented frame is written to `dir/frame-NNNNN.png`. The colour
//! image is copied into a host buffer of the frame's slot when the frame is submitted, and
//! handed, once that slot's fence has signalled, to a writer thread that encodes it (no stall
//! on the GPU, no PNG encoding on the program's thread). The image rows are already top-down
//! (see [`super::target`]), as PNG wants them.

use std::path::PathBuf;
use std::sync::mpsc;
use std::thread::JoinHandle;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::device::{Buffer, Device, Result};
use super::output::{FrameOutput, SubmitSync};
use super::renderer::Recorder;
use super::target::Plane;

/// A copy waiting for its frame to finish.
struct Pending {
    buffer: Buffer,
    size: [u32; 2],
    frame: u64,
}

/// A frame for the writer thread: path, size, RGBA8 rows top to bottom.
type Job = (PathBuf, [u32; 2], Vec<u8>);

/// The dump directory, the first frame dumped, the copies in flight (one per slot) and the
/// writer thread.
pub struct Dump {
    dir: PathBuf,
    first: u64,
    pending: Vec<Option<Pending>>,
    jobs: Option<mpsc::SyncSender<Job>>,
    writer: Option<JoinHandle<()>>,
}

impl Dump {
    /// From `GLRT_DUMP`; `None` when unset or when the directory cannot be used (with a
    /// message).
    pub fn from_env() -> Option<Dump> {
        let dir = PathBuf::from(std::env::var_os("GLRT_DUMP").filter(|d| !d.is_empty())?);
        Dump::new(dir, 0).map_err(|e| eprintln!("glrt: GLRT_DUMP: {e}; frames are not dumped")).ok()
    }

    /// Dumps frames `first` and later into `dir` (created if needed); the error names the
    /// directory and the cause.
    pub fn new(dir: PathBuf, first: u64) -> std::result::Result<Dump, String> {
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        // Bounded: when encoding is slower than rendering, the program waits instead of
        // queueing frames without limit.
        let (jobs, queue) = mpsc::sync_channel::<Job>(4);
        let writer = std::thread::Builder::new()
            .name("glrt-dump".into())
            .spawn(move || {
                for (path, size, rgba) in queue {
                    if let Err(e) = write_png(&path, size, &rgba) {
                        eprintln!("glrt: writing {}: {e}", path.display());
                    }
                }
            })
            .map_err(|e| format!("cannot start the writer thread: {e}"))?;
        Ok(Dump { dir, first, pending: Vec::new(), jobs: Some(jobs), writer: Some(writer) })
    }
}

impl FrameOutput for Dump {
    /// Records the copy of the colour image of frame `frame` for slot `slot` (nothing before
    /// the first frame dumped).
    fn record(&mut self, rec: &mut Recorder<'_>, slot: usize, frame: u64) -> Result<SubmitSync> {
        if frame < self.first {
            return Ok(SubmitSync::default());
        }
        let (device, cmd, target) = (rec.device, rec.cmd, &mut *rec.target);
        if self.pending.len() <= slot {
            self.pending.resize_with(slot + 1, || None);
        }
        let [w, h] = target.size;
        let bytes = w as u64 * h as u64 * 4;
        let buffer = device.create_buffer("glrt dump", bytes, vk::BufferUsageFlags::TRANSFER_DST, MemoryLocation::GpuToCpu)?;
        let front = target.readable(device, cmd, Plane::Front);
        let copy = vk::BufferImageCopy {
            image_subresource: vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: 1 },
            image_extent: vk::Extent3D { width: w, height: h, depth: 1 },
            ..Default::default()
        };
        // Safety: the image is in TRANSFER_SRC_OPTIMAL; the buffer holds the whole image.
        unsafe { device.raw.cmd_copy_image_to_buffer(cmd, front, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, buffer.raw, &[copy]) };
        if let Some(old) = self.pending[slot].replace(Pending { buffer, size: [w, h], frame }) {
            device.destroy_buffer(old.buffer);
        }
        Ok(SubmitSync::default())
    }

    /// Sends slot `slot`'s frame (its fence has signalled) to the writer thread.
    fn completed(&mut self, device: &Device, slot: usize) {
        let Some(mut p) = self.pending.get_mut(slot).and_then(Option::take) else { return };
        let path = self.dir.join(format!("frame-{:05}.png", p.frame));
        let rgba = p.buffer.mapped().to_vec();
        device.destroy_buffer(p.buffer);
        if let Some(jobs) = &self.jobs {
            let _ = jobs.send((path, p.size, rgba));
        }
    }

    /// Frees the buffers: the frames in flight on `device` are not dumped.
    fn release(&mut self, device: &Device) {
        for p in self.pending.drain(..).flatten() {
            device.destroy_buffer(p.buffer);
        }
    }

    /// Frees the buffers (the GPU must be idle) and waits for the writer to finish.
    fn destroy(&mut self, device: &Device) {
        self.release(device);
        self.jobs = None;
        if let Some(writer) = self.writer.take() {
            let _ = writer.join();
        }
    }
}

/// Writes RGBA8 rows, top to bottom, as an RGB PNG: a window shows the colour channels only
/// (the framebuffer's alpha is what blending left there, not coverage).
pub fn write_png(path: &std::path::Path, [w, h]: [u32; 2], rgba: &[u8]) -> std::io::Result<()> {
    let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut encoder = png::Encoder::new(file, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(&rgb).map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

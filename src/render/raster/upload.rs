//! Per-frame upload memory for vertices, indices and uniforms: host-visible chunks written by
//! the CPU and read by the GPU. Each frame in flight owns one [`Ring`]; it is reset once that
//! frame's fence has signalled, so writing never waits for the GPU. A frame that needs more
//! than its chunks hold gets a new, larger chunk (kept for later frames).

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::device::{Buffer, Device, Result};

/// Size of the first chunk.
const FIRST_CHUNK: u64 = 4 << 20;

/// Where an upload landed.
#[derive(Clone, Copy, Debug)]
pub struct Slice {
    /// The buffer.
    pub buffer: vk::Buffer,
    /// Byte offset in it.
    pub offset: u64,
}

/// Upload memory of one frame in flight.
#[derive(Default)]
pub struct Ring {
    chunks: Vec<Buffer>,
    /// Chunk being filled and the bytes used in it.
    current: usize,
    used: u64,
}

/// Buffer usages of the chunks.
fn usage() -> vk::BufferUsageFlags {
    vk::BufferUsageFlags::VERTEX_BUFFER
        | vk::BufferUsageFlags::INDEX_BUFFER
        | vk::BufferUsageFlags::STORAGE_BUFFER
        | vk::BufferUsageFlags::TRANSFER_SRC
}

impl Ring {
    /// Forgets every upload: only call once the GPU finished the frame that used them.
    pub fn reset(&mut self) {
        self.current = 0;
        self.used = 0;
    }

    /// Bytes taken since the last [`Ring::reset`] (with the unused tails of filled chunks).
    pub fn bytes_used(&self) -> u64 {
        self.chunks.iter().take(self.current).map(|c| c.size).sum::<u64>() + self.used
    }

    /// Copies `bytes` into the ring at a multiple of `align` (a power of two).
    pub fn push(&mut self, device: &Device, bytes: &[u8], align: u64) -> Result<Slice> {
        let (slice, dst) = self.reserve(device, bytes.len() as u64, align)?;
        if let Some(dst) = dst {
            dst.copy_from_slice(bytes);
        }
        Ok(slice)
    }

    /// Takes `count` values of `T` in the ring at a multiple of `align` (a power of two, at
    /// least `T`'s alignment) and has `fill` write them where the GPU reads them: no copy
    /// through a vector first.
    pub fn push_with<T: bytemuck_free::Plain>(&mut self, device: &Device, count: usize, align: u64, fill: impl FnOnce(&mut [T])) -> Result<Slice> {
        let (slice, dst) = self.reserve(device, (count * std::mem::size_of::<T>()) as u64, align)?;
        if let Some(values) = dst.and_then(bytemuck_free::values_mut) {
            fill(values);
        }
        Ok(slice)
    }

    /// Takes `size` bytes at a multiple of `align`: where they are and their mapped memory
    /// (`None` when the chunk is not mapped).
    fn reserve(&mut self, device: &Device, size: u64, align: u64) -> Result<(Slice, Option<&mut [u8]>)> {
        loop {
            if let Some(chunk) = self.chunks.get(self.current) {
                let offset = (self.used + align - 1) & !(align - 1);
                if offset + size <= chunk.size {
                    self.used = offset + size;
                    let chunk = &mut self.chunks[self.current];
                    let slice = Slice { buffer: chunk.raw, offset };
                    let start = offset as usize;
                    return Ok((slice, chunk.mapped().get_mut(start..start + size as usize)));
                }
                if self.current + 1 < self.chunks.len() {
                    self.current += 1;
                    self.used = 0;
                    continue;
                }
            }
            let last = self.chunks.last().map_or(FIRST_CHUNK / 2, |c| c.size);
            let chunk_size = (last * 2).max(size.next_power_of_two());
            self.chunks.push(device.create_buffer("glrt upload", chunk_size, usage(), MemoryLocation::CpuToGpu)?);
            self.current = self.chunks.len() - 1;
            self.used = 0;
        }
    }

    /// Copies a slice of plain values (`f32`, `u32`).
    pub fn push_slice<T: bytemuck_free::Plain>(&mut self, device: &Device, values: &[T], align: u64) -> Result<Slice> {
        self.push(device, bytemuck_free::bytes(values), align)
    }

    /// Frees the chunks (the GPU must be done with them).
    pub fn destroy(&mut self, device: &Device) {
        for chunk in self.chunks.drain(..) {
            device.destroy_buffer(chunk);
        }
        self.reset();
    }
}

/// Byte views of `f32`/`u32` slices without a dependency.
pub mod bytemuck_free {
    /// Types without padding or invalid bit patterns.
    pub trait Plain: Copy {}
    impl Plain for f32 {}
    impl Plain for u32 {}
    impl Plain for u8 {}

    /// The bytes of `values`.
    pub fn bytes<T: Plain>(values: &[T]) -> &[u8] {
        // Safety: `Plain` types have no padding; u8 has alignment 1; the length is in bytes.
        unsafe { std::slice::from_raw_parts(values.as_ptr().cast::<u8>(), std::mem::size_of_val(values)) }
    }

    /// `bytes` as values of `T`, when they are aligned for `T` and a whole number of them.
    pub fn values_mut<T: Plain>(bytes: &mut [u8]) -> Option<&mut [T]> {
        let size = std::mem::size_of::<T>();
        if !(bytes.as_ptr() as usize).is_multiple_of(std::mem::align_of::<T>()) || !bytes.len().is_multiple_of(size) {
            return None;
        }
        // Safety: aligned and in bounds (checked above); every bit pattern is a valid `Plain`
        // value; the borrow of `bytes` moves to the result.
        Some(unsafe { std::slice::from_raw_parts_mut(bytes.as_mut_ptr().cast::<T>(), bytes.len() / size) })
    }
}

#[cfg(test)]
mod tests {
    use super::bytemuck_free::values_mut;

    #[test]
    fn bytes_become_values_only_when_aligned_and_whole() {
        let mut words = [0u32; 4];
        // Safety: the 16 bytes of `words`, borrowed mutably through this slice only.
        let bytes: &mut [u8] = unsafe { std::slice::from_raw_parts_mut(words.as_mut_ptr().cast::<u8>(), 16) };
        let values = values_mut::<u32>(&mut bytes[4..12]).expect("aligned, two words");
        values.copy_from_slice(&[7, 9]);
        assert!(values_mut::<u32>(&mut bytes[1..9]).is_none(), "misaligned");
        assert!(values_mut::<u32>(&mut bytes[4..10]).is_none(), "not whole words");
        assert_eq!(words, [0, 7, 9, 0]);
    }
}

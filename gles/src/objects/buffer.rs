//! A buffer object: its CPU shadow, its GPU copy and its mapped range.

use crate::flushed::Flushed;

/// A buffer object: a CPU shadow (used to validate draws and convert formats) plus its GPU copy.
#[derive(Default)]
pub struct Buffer {
    /// The contents as the client last wrote them.
    pub data: Vec<u8>,
    /// The GPU copy (size rounded up to 4 bytes).
    pub gpu: Option<wgpu::Buffer>,
    /// `GL_BUFFER_USAGE`.
    pub usage: u32,
    /// Bumped on every write, so derived data (widened indices, converted attributes) can be cached.
    pub generation: u64,
    /// The memory of the shadow and the GPU copy, held against the client's quota.
    pub _reserved: Option<strata_device::account::Reservation>,
    /// The mapped range, while the buffer is mapped (`GL_OES_mapbuffer`, `GL_EXT_map_buffer_range`).
    pub map: Option<Mapping>,
}

impl Buffer {
    /// Writes `bytes` at `off` (already checked to lie within the buffer) into the shadow and
    /// the GPU copy.
    pub fn write(&mut self, gpu: &strata_device::Gpu, flushed: &Flushed, off: usize, bytes: &[u8]) {
        self.data[off..off + bytes.len()].copy_from_slice(bytes);
        self.upload(gpu, flushed, off, bytes.len());
    }

    /// Writes `blob` at `off` (already checked to lie within the buffer) as [`Buffer::write`]
    /// does, a streamed blob read from the ring straight into the shadow.
    pub fn write_blob(
        &mut self,
        gpu: &strata_device::Gpu,
        flushed: &Flushed,
        off: usize,
        blob: &strata_protocol::Blob<'_>,
    ) -> Result<(), strata_protocol::ring::RingError> {
        blob.read_into(&mut self.data[off..off + blob.len()])?;
        self.upload(gpu, flushed, off, blob.len());
        Ok(())
    }

    /// Copies the shadow's `len` bytes at `off` to the GPU copy.
    fn upload(&mut self, gpu: &strata_device::Gpu, flushed: &Flushed, off: usize, len: usize) {
        self.generation += 1;
        if let Some(g) = &self.gpu {
            // wgpu writes whole 4-byte words; widen the range using the shadow.
            let start = off / 4 * 4;
            let stop = ((off + len).div_ceil(4) * 4).min(g.size() as usize);
            let mut words = self.data[start..stop.min(self.data.len())].to_vec();
            words.resize(stop - start, 0);
            if !words.is_empty() {
                write_words(gpu, flushed, g, start as u64, &words);
            }
        }
    }
}

/// Writes whole 4-byte `words` into `buffer` at `offset`, after the pending pass.
pub fn write_words(gpu: &strata_device::Gpu, _: &Flushed, buffer: &wgpu::Buffer, offset: u64, words: &[u8]) {
    gpu.write_buffer(buffer, offset, words);
}

/// A buffer's mapped range and the access it was mapped with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Mapping {
    /// First mapped byte.
    pub offset: usize,
    /// Mapped bytes.
    pub length: usize,
    /// `GL_MAP_*_BIT_EXT` flags (`GL_MAP_WRITE_BIT_EXT` for `glMapBufferOES`).
    pub access: u32,
}

/// An indexed buffer binding: the buffer, and the range `glBindBufferRange` gave (a size of 0:
/// the whole buffer, `glBindBufferBase`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RangeBinding {
    /// The buffer (0: none).
    pub buffer: u32,
    /// The first byte.
    pub offset: u64,
    /// The bytes bound (0: all of it, however large it becomes).
    pub size: u64,
}

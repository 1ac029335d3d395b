//! The producing end of a ring: frames written in place, chunking of large messages, and
//! publishing in batches.

use std::sync::atomic::Ordering;

use super::*;

/// How far into the ring the writer goes before it returns to the start whenever everything
/// unread and its next frame fit before its position: a reader that keeps up then sees the
/// same stretch of the ring over and over, which stays in cache.
pub const HOT_WINDOW: usize = 1 << 20;

/// The most bytes of a streamed blob in one `BULK` frame: each piece is published as soon as
/// it is written, so that the reader copies it on while the writer writes the next, and both
/// work on bytes still in cache.
pub const BULK_PIECE: usize = 64 << 10;

/// The smallest blob a client streams after its message rather than inline (see
/// [`Writer::write_bulk`]).
pub const STREAM_FROM: usize = 64 << 10;

/// The producing end of a ring.
pub struct Writer {
    ring: RingRegion,
    /// Where the next frame goes (the ring's tests move it to test the reader).
    pub(super) head: u32,
    published: u32,
    tail: u32,
    /// The head when the tail was last read for [`Writer::wrap_early`].
    tail_seen_at: u32,
    batch_limit: u32,
    scratch: Vec<u8>,
}

impl Writer {
    /// Takes the producing end. Written frames are published at `publish`, or automatically
    /// once `batch_limit` bytes are pending.
    pub fn new(ring: RingRegion, batch_limit: u32) -> Self {
        let ctl = ring.ctl();
        let head = ctl.head.0.load(Ordering::Acquire);
        let tail = ctl.tail.0.load(Ordering::Acquire);
        let batch_limit = batch_limit.clamp(FRAME_HEADER as u32, ring.capacity / 2);
        Writer { ring, head, published: head, tail, tail_seen_at: head, batch_limit, scratch: Vec::new() }
    }

    /// Largest payload that travels as one frame; larger messages are chunked.
    pub fn max_frame_payload(&self) -> usize {
        self.ring.capacity as usize / 2 - FRAME_HEADER
    }

    /// Bytes written but not yet published.
    pub fn unpublished(&self) -> u32 {
        self.head.wrapping_sub(self.published)
    }

    /// Makes every written frame visible to the reader and wakes it if it sleeps.
    pub fn publish(&mut self) {
        if self.head != self.published {
            let ctl = self.ring.ctl();
            store_and_wake(&ctl.head.0, &ctl.reader_waiting.0, self.head);
            self.published = self.head;
        }
    }

    /// Writes one message of `len` bytes that `fill` produces in place, chunking it when it
    /// exceeds one frame. Waits (publishing first) while the ring is full.
    pub fn write<E: From<RingError>>(
        &mut self,
        len: usize,
        alive: &dyn Fn() -> bool,
        fill: impl FnOnce(&mut [u8]) -> Result<(), E>,
    ) -> Result<(), E> {
        if len <= self.max_frame_payload() {
            let off = self.reserve(frame_size(len), alive)?;
            // SAFETY: `reserve` found `frame_size(len)` free contiguous bytes at `off`.
            fill(unsafe { self.ring.bytes_mut(off + FRAME_HEADER, len) })?;
            self.commit(off, len, KIND_WHOLE);
        } else {
            let mut scratch = std::mem::take(&mut self.scratch);
            scratch.clear();
            scratch.resize(len, 0);
            let r = fill(&mut scratch).and_then(|()| self.write_chunked(&scratch, alive).map_err(E::from));
            if scratch.capacity() <= (64 << 20) {
                self.scratch = scratch;
            }
            r?;
        }
        if self.unpublished() >= self.batch_limit {
            self.publish();
        }
        Ok(())
    }

    /// Streams `bytes` as `BULK` frames of at most [`BULK_PIECE`] bytes (and at most a quarter
    /// of the ring), publishing each and keeping at most [`HOT_WINDOW`] unread: the blob of the
    /// message written just before, which announced their number (see [`super::Bulk`]).
    pub fn write_bulk(&mut self, bytes: &[u8], alive: &dyn Fn() -> bool) -> Result<(), RingError> {
        let cap = self.ring.capacity as usize;
        let piece = BULK_PIECE.min(cap / 4 - FRAME_HEADER);
        let lead = HOT_WINDOW.min(cap / 2);
        for part in bytes.chunks(piece) {
            // Never more than the hot window ahead of the reader: a writer further ahead
            // would spread the stream over the whole ring, out of cache.
            self.wait_space(cap - lead + frame_size(part.len()), alive)?;
            let off = self.reserve(frame_size(part.len()), alive)?;
            // SAFETY: `reserve` found `frame_size(part.len())` free contiguous bytes at `off`.
            unsafe { self.ring.bytes_mut(off + FRAME_HEADER, part.len()) }.copy_from_slice(part);
            self.commit(off, part.len(), KIND_BULK);
            self.publish();
        }
        Ok(())
    }

    /// Writes every chunk of `msg` but its last (`msg` must need chunks: longer than a
    /// quarter of the ring), and publishes them: a message begun and never finished, the tool
    /// for testing what a reader holds for a writer that stops.
    #[cfg(feature = "fault-injection")]
    pub fn write_unfinished(&mut self, msg: &[u8], alive: &dyn Fn() -> bool) -> Result<(), RingError> {
        self.write_chunked_but(msg, alive, true)
    }

    fn write_chunked(&mut self, msg: &[u8], alive: &dyn Fn() -> bool) -> Result<(), RingError> {
        self.write_chunked_but(msg, alive, false)
    }

    /// Writes `msg` in chunks; with `unfinished`, all but the last.
    fn write_chunked_but(&mut self, msg: &[u8], alive: &dyn Fn() -> bool, unfinished: bool) -> Result<(), RingError> {
        let piece = self.ring.capacity as usize / 4 - 2 * FRAME_HEADER;
        let first = msg.len().min(piece);
        let off = self.reserve(frame_size(8 + first), alive)?;
        // SAFETY: reserved above.
        let dst = unsafe { self.ring.bytes_mut(off + FRAME_HEADER, 8 + first) };
        dst[..8].copy_from_slice(&(msg.len() as u64).to_le_bytes());
        dst[8..].copy_from_slice(&msg[..first]);
        self.commit(off, 8 + first, KIND_CHUNK_FIRST);
        self.publish();
        let mut rest = &msg[first..];
        loop {
            let n = rest.len().min(piece);
            let kind = if n == rest.len() { KIND_CHUNK_LAST } else { KIND_CHUNK_MORE };
            if unfinished && kind == KIND_CHUNK_LAST {
                return Ok(());
            }
            let off = self.reserve(frame_size(n), alive)?;
            // SAFETY: reserved above.
            unsafe { self.ring.bytes_mut(off + FRAME_HEADER, n) }.copy_from_slice(&rest[..n]);
            self.commit(off, n, kind);
            self.publish();
            rest = &rest[n..];
            if kind == KIND_CHUNK_LAST {
                return Ok(());
            }
        }
    }

    /// Finds `need` contiguous free bytes at the head and returns their offset, wrapping to the
    /// ring's start when they do not fit before its end or [`Writer::wrap_early`] says so.
    fn reserve(&mut self, need: usize, alive: &dyn Fn() -> bool) -> Result<usize, RingError> {
        let off = self.ring.offset(self.head);
        let to_end = self.ring.capacity as usize - off;
        if need > to_end || self.wrap_early(off, need) {
            self.wait_space(to_end, alive)?;
            self.ring.write_header(off, 0, KIND_WRAP);
            self.head = self.head.wrapping_add(to_end as u32);
        }
        self.wait_space(need, alive)?;
        Ok(self.ring.offset(self.head))
    }

    /// Whether to go back to the ring's start before its end: past [`HOT_WINDOW`], once the
    /// reader has consumed enough that everything unread and `need` fit before `off`. A reader
    /// that keeps up then sees the same megabyte or so over and over, which stays in both
    /// cores' caches, rather than the whole ring, which does not. The price: after such a wrap
    /// the writer has about [`HOT_WINDOW`] of room, not the whole ring, should the reader stall.
    fn wrap_early(&mut self, off: usize, need: usize) -> bool {
        if off < HOT_WINDOW {
            return false;
        }
        // The reader's tail is looked at once per [`BULK_PIECE`] written, not per frame: its
        // cache line is the reader's to write.
        if self.head.wrapping_sub(self.tail_seen_at) >= BULK_PIECE as u32 {
            self.tail = self.ring.ctl().tail.0.load(Ordering::Acquire);
            self.tail_seen_at = self.head;
        }
        let used = self.head.wrapping_sub(self.tail) as usize;
        used <= self.ring.capacity as usize && used + need <= off
    }

    fn commit(&mut self, off: usize, len: usize, kind: u32) {
        self.ring.write_header(off, len as u32, kind);
        self.head = self.head.wrapping_add(frame_size(len) as u32);
    }

    fn wait_space(&mut self, need: usize, alive: &dyn Fn() -> bool) -> Result<(), RingError> {
        let cap = self.ring.capacity;
        loop {
            let used = self.head.wrapping_sub(self.tail);
            if used > cap {
                return Err(RingError::BadTail { used, capacity: cap });
            }
            if (cap - used) as usize >= need {
                return Ok(());
            }
            let t = self.ring.ctl().tail.0.load(Ordering::Acquire);
            if t != self.tail {
                self.tail = t;
                continue;
            }
            self.publish();
            let ctl = self.ring.ctl();
            self.tail = wait_change(&ctl.tail.0, &ctl.writer_waiting.0, self.tail, alive)?;
        }
    }

    /// Writes `bytes` at the head verbatim and publishes the head advanced by `advance`,
    /// bypassing all framing: the tool for testing how a reader survives a hostile writer.
    #[cfg(feature = "fault-injection")]
    pub fn inject(&mut self, bytes: &[u8], advance: u32) {
        let off = self.ring.offset(self.head);
        let n = bytes.len().min(self.ring.capacity as usize - off);
        // SAFETY: clamped to the data area.
        unsafe { self.ring.bytes_mut(off, n) }.copy_from_slice(&bytes[..n]);
        self.head = self.head.wrapping_add(advance);
        self.publish();
    }
}

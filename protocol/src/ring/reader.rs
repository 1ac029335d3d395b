//! The consuming end of a ring: validates every frame against its own tail and the
//! published head, copies its payload out of the shared memory once (what it delivers is
//! always that private copy, never a view of memory the peer can still write), reassembles
//! chunked messages, and skips those over its limit.

use std::sync::atomic::Ordering;

use super::*;

/// What the reader does with a message beyond its limit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Oversized {
    /// Fails the read with [`RingError::TooLarge`].
    Refuse,
    /// Skips a chunked one and reports it as [`Message::Oversized`].
    Skip,
}

/// A message as the reader delivers it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Message<'a> {
    /// A whole message.
    Whole(&'a [u8]),
    /// A chunked message larger than the reader's limit, skipped without being kept: its
    /// announced length and the start of its first chunk (enough to name its command).
    Oversized {
        /// The announced length.
        len: u64,
        /// Up to [`OVERSIZED_HEAD`] bytes from its start.
        head: &'a [u8],
    },
}

/// Bytes kept from the start of a message that is skipped for its size.
pub const OVERSIZED_HEAD: usize = 16;

/// The consuming end of a ring.
pub struct Reader {
    ring: RingRegion,
    tail: u32,
    released: u32,
    max_message: usize,
    /// The private copy of the frame being handled: all that decoding reads.
    frame: Vec<u8>,
    assembly: Vec<u8>,
    expected: Option<usize>,
    /// Of an oversized message being skipped: the bytes seen so far.
    skipped: Option<usize>,
}

impl Reader {
    /// Takes the consuming end; `max_message` bounds chunked messages.
    pub fn new(ring: RingRegion, max_message: usize) -> Self {
        let tail = ring.ctl().tail.0.load(Ordering::Acquire);
        Reader {
            ring,
            tail,
            released: tail,
            max_message,
            frame: Vec::new(),
            assembly: Vec::new(),
            expected: None,
            skipped: None,
        }
    }

    /// Whether a chunked message has begun but not ended.
    pub fn mid_message(&self) -> bool {
        self.expected.is_some()
    }

    /// Whether the writer has published anything not yet consumed.
    pub fn has_data(&self) -> bool {
        self.ring.ctl().head.0.load(Ordering::Acquire) != self.tail
    }

    /// Waits until frames are published, then hands every complete message among them to
    /// `on_message`, in order. Returns the number of messages delivered (0 if only chunks of
    /// a larger message arrived).
    pub fn recv_batch<E: From<RingError>>(
        &mut self,
        alive: &dyn Fn() -> bool,
        mut on_message: impl FnMut(&[u8]) -> Result<(), E>,
    ) -> Result<usize, E> {
        let limit = self.max_message;
        self.recv_messages(alive, Oversized::Refuse, |m| match m {
            Message::Whole(bytes) => on_message(bytes),
            Message::Oversized { len, .. } => Err(RingError::TooLarge { len, limit }.into()),
        })
    }

    /// Waits until frames are published, then hands every message among them to `on_message`,
    /// in order; returns the number delivered. A message beyond the limit is refused at once
    /// with [`Oversized::Refuse`]; with [`Oversized::Skip`] a chunked one is skipped without
    /// being kept and reported as [`Message::Oversized`] once its last chunk is read, so that
    /// the stream goes on after it.
    pub fn recv_messages<E: From<RingError>>(
        &mut self,
        alive: &dyn Fn() -> bool,
        oversized: Oversized,
        mut on_message: impl FnMut(Message<'_>) -> Result<(), E>,
    ) -> Result<usize, E> {
        let ctl = self.ring.ctl();
        let mut head = ctl.head.0.load(Ordering::Acquire);
        if head == self.tail {
            head = wait_change(&ctl.head.0, &ctl.reader_waiting.0, self.tail, alive)?;
        }
        let cap = self.ring.capacity;
        let mut delivered = 0;
        while self.tail != head {
            let ahead = head.wrapping_sub(self.tail);
            if ahead > cap {
                return Err(RingError::BadHead { ahead, capacity: cap }.into());
            }
            let available = ahead as usize;
            if available < FRAME_HEADER {
                return Err(RingError::Truncated { needed: FRAME_HEADER, available }.into());
            }
            let off = self.ring.offset(self.tail);
            // Frames keep the tail aligned; only a tail planted before the reader began is not.
            if !off.is_multiple_of(8) {
                return Err(RingError::MisalignedTail(self.tail).into());
            }
            let (len, kind) = self.ring.read_header(off);
            if kind == KIND_WRAP {
                let skip = cap as usize - off;
                if skip > available {
                    return Err(RingError::Truncated { needed: skip, available }.into());
                }
                self.tail = self.tail.wrapping_add(skip as u32);
                continue;
            }
            let limit = cap as usize - off - FRAME_HEADER;
            if len as usize > limit {
                return Err(RingError::BadLength { len, limit }.into());
            }
            let size = frame_size(len as usize);
            if size > available {
                return Err(RingError::Truncated { needed: size, available }.into());
            }
            let payload = off + FRAME_HEADER;
            let len = len as usize;
            match kind {
                KIND_WHOLE => {
                    if self.expected.is_some() {
                        return Err(RingError::BadChunk("whole message inside a chunked one").into());
                    }
                    self.frame.clear();
                    // SAFETY: `payload + len <= capacity` was checked above.
                    unsafe { self.ring.copy_out(payload, len, &mut self.frame) };
                    let r = on_message(Message::Whole(&self.frame));
                    if self.frame.capacity() > (64 << 20) {
                        self.frame = Vec::new();
                    }
                    r?;
                    delivered += 1;
                }
                KIND_CHUNK_FIRST => {
                    if self.expected.is_some() {
                        return Err(RingError::BadChunk("chunked message started twice").into());
                    }
                    if len < 8 {
                        return Err(RingError::BadChunk("first chunk lacks the total length").into());
                    }
                    // SAFETY: `payload + len <= capacity` was checked above, and `len >= 8`.
                    let total = u64::from_le_bytes(unsafe { self.ring.read_array::<8>(payload) });
                    let (rest, rest_len) = (payload + 8, len - 8);
                    if (rest_len as u64) > total {
                        return Err(RingError::BadChunk("chunk exceeds the announced size").into());
                    }
                    if total > self.max_message as u64 && oversized == Oversized::Refuse {
                        return Err(RingError::TooLarge { len: total, limit: self.max_message }.into());
                    }
                    if total > self.max_message as u64 {
                        // Kept: only the head, to name the command when it is refused.
                        let total = usize::try_from(total)
                            .map_err(|_| RingError::TooLarge { len: total, limit: self.max_message })?;
                        self.assembly.clear();
                        // SAFETY: within this frame's payload, checked above.
                        unsafe { self.ring.copy_out(rest, rest_len.min(OVERSIZED_HEAD), &mut self.assembly) };
                        self.skipped = Some(rest_len);
                        self.expected = Some(total);
                        self.tail = self.tail.wrapping_add(size as u32);
                        continue;
                    }
                    self.assembly.clear();
                    self.assembly.reserve(total as usize);
                    // SAFETY: within this frame's payload, checked above.
                    unsafe { self.ring.copy_out(rest, rest_len, &mut self.assembly) };
                    self.expected = Some(total as usize);
                }
                KIND_CHUNK_MORE | KIND_CHUNK_LAST if self.skipped.is_some() => {
                    let total = self.expected.ok_or(RingError::BadChunk("continuation without a first chunk"))?;
                    let seen = self.skipped.unwrap_or(0) + len;
                    if seen > total {
                        return Err(RingError::BadChunk("chunks exceed the announced size").into());
                    }
                    self.skipped = Some(seen);
                    if kind == KIND_CHUNK_LAST {
                        if seen != total {
                            return Err(RingError::BadChunk("chunked message ended short").into());
                        }
                        self.expected = None;
                        self.skipped = None;
                        on_message(Message::Oversized { len: total as u64, head: &self.assembly })?;
                        delivered += 1;
                    }
                }
                KIND_CHUNK_MORE | KIND_CHUNK_LAST => {
                    let total = self.expected.ok_or(RingError::BadChunk("continuation without a first chunk"))?;
                    if self.assembly.len() + len > total {
                        return Err(RingError::BadChunk("chunks exceed the announced size").into());
                    }
                    // SAFETY: `payload + len <= capacity` was checked above.
                    unsafe { self.ring.copy_out(payload, len, &mut self.assembly) };
                    if kind == KIND_CHUNK_LAST {
                        if self.assembly.len() != total {
                            return Err(RingError::BadChunk("chunked message ended short").into());
                        }
                        self.expected = None;
                        let msg = std::mem::take(&mut self.assembly);
                        let r = on_message(Message::Whole(&msg));
                        self.assembly = msg;
                        if self.assembly.capacity() > (64 << 20) {
                            self.assembly = Vec::new();
                        }
                        r?;
                        delivered += 1;
                    }
                }
                other => return Err(RingError::UnknownKind(other).into()),
            }
            self.tail = self.tail.wrapping_add(size as u32);
            if self.tail.wrapping_sub(self.released) >= cap / 4 {
                self.release();
            }
        }
        self.release();
        Ok(delivered)
    }

    fn release(&mut self) {
        let ctl = self.ring.ctl();
        store_and_wake(&ctl.tail.0, &ctl.writer_waiting.0, self.tail);
        self.released = self.tail;
    }
}

//! The consuming end of a ring: validates every frame against its own tail and the
//! published head, copies its payload out of the shared memory once (what it delivers is
//! always that private copy, never a view of memory the peer can still write), reassembles
//! chunked messages, and skips those over its limit.

use std::cell::RefCell;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use super::bulk::BulkState;
use super::frame::{next_frame, Frame, RELEASE_EVERY};
use super::holdings::Holdings;
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
    /// A chunked message larger than the reader's limit, or one whose memory its
    /// [`Holdings`] refused, skipped without being kept: its announced length and the start
    /// of its first chunk (enough to name its command).
    Oversized {
        /// The announced length.
        len: u64,
        /// Up to [`OVERSIZED_HEAD`] bytes from its start.
        head: &'a [u8],
        /// Why its memory was refused (`None`: it is over the limit).
        why: Option<&'a str>,
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
    /// What the assembly's memory is charged to, and how much it holds.
    holdings: RefCell<Option<(Box<dyn Holdings>, usize)>>,
    /// Where the blob streamed after a message is read.
    bulk: BulkState,
    /// Why the memory for the message being skipped was refused.
    refused: Option<String>,
    /// When the chunked message being read began, and how long one may take in all.
    partial: Option<Instant>,
    partial_limit: Option<Duration>,
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
            holdings: RefCell::new(None),
            bulk: BulkState::default(),
            refused: None,
            partial: None,
            partial_limit: None,
        }
    }

    /// Charges the memory of chunked messages being assembled to `holdings`, before it is
    /// allocated.
    pub fn with_holdings(mut self, holdings: Box<dyn Holdings>) -> Self {
        self.holdings = RefCell::new(Some((holdings, 0)));
        self
    }

    /// Fails the read with [`RingError::Stale`] when a chunked message is not finished within
    /// `limit` of its first chunk.
    pub fn with_partial_limit(mut self, limit: Duration) -> Self {
        self.partial_limit = Some(limit);
        self
    }

    /// Charges `bytes` as what the assembly holds; the reason if refused.
    fn hold(&mut self, bytes: usize) -> Result<(), String> {
        if let Some((h, held)) = self.holdings.get_mut() {
            if bytes != *held {
                h.hold(bytes)?;
                *held = bytes;
            }
        }
        Ok(())
    }

    /// The chunked message being read, taken too long.
    fn stale(&self) -> RingError {
        let (len, have) = (self.expected.unwrap_or(0) as u64, self.skipped.unwrap_or(self.assembly.len()));
        let secs = self.partial.map_or(0.0, |t| t.elapsed().as_secs_f64());
        RingError::Stale { len, have: have as u64, secs }
    }

    /// Lets the assembly's memory go if it is large, and charges what it keeps.
    fn trim(&mut self) {
        if self.assembly.capacity() > (64 << 20) {
            self.assembly = Vec::new();
        }
        // Giving back is never refused.
        let _ = self.hold(self.assembly.capacity());
    }

    /// Whether a chunked message has begun but not ended, or a streamed blob has not all come.
    pub fn mid_message(&self) -> bool {
        self.expected.is_some() || self.bulk.unfinished()
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
        self.recv_messages(alive, Oversized::Refuse, |m, _| match m {
            Message::Whole(bytes) => on_message(bytes),
            Message::Oversized { len, .. } => Err(RingError::TooLarge { len, limit }.into()),
        })
    }

    /// Waits until frames are published, then hands every message among them to `on_message`,
    /// in order, with the [`Bulk`] that streams a blob the message announces (consumed or
    /// not, its bytes are gone once `on_message` returns); returns the number delivered. A message beyond the limit is refused at once
    /// with [`Oversized::Refuse`]; with [`Oversized::Skip`] a chunked one is skipped without
    /// being kept and reported as [`Message::Oversized`] once its last chunk is read, so that
    /// the stream goes on after it.
    pub fn recv_messages<E: From<RingError>>(
        &mut self,
        alive: &dyn Fn() -> bool,
        oversized: Oversized,
        mut on_message: impl FnMut(Message<'_>, &Bulk<'_>) -> Result<(), E>,
    ) -> Result<usize, E> {
        let ctl = self.ring.ctl();
        let mut head = ctl.head.0.load(Ordering::Acquire);
        let due = self.partial.zip(self.partial_limit).map(|(t, l)| t + l);
        let in_time = || due.is_none_or(|d| Instant::now() < d);
        if !in_time() {
            return Err(self.stale().into());
        }
        if head == self.tail {
            head = match wait_change(&ctl.head.0, &ctl.reader_waiting.0, self.tail, &|| alive() && in_time()) {
                Err(RingError::PeerGone) if alive() => return Err(self.stale().into()),
                other => other?,
            };
        }
        let mut delivered = 0;
        while self.tail != head {
            let Frame { off, len, kind, size } = next_frame(&self.ring, self.tail, head)?;
            if kind == KIND_WRAP {
                self.tail = self.tail.wrapping_add(size as u32);
                continue;
            }
            let payload = off + FRAME_HEADER;
            match kind {
                KIND_WHOLE => {
                    if self.expected.is_some() {
                        return Err(RingError::BadChunk("whole message inside a chunked one").into());
                    }
                    self.frame.clear();
                    // SAFETY: `payload + len <= capacity` was checked by `next_frame`.
                    unsafe { self.ring.copy_out(payload, len, &mut self.frame) };
                    let frame = std::mem::take(&mut self.frame);
                    let r = self.deliver(Message::Whole(&frame), (size, head), alive, &mut on_message);
                    self.frame = frame;
                    if self.frame.capacity() > (64 << 20) {
                        self.frame = Vec::new();
                    }
                    head = r?;
                    delivered += 1;
                    continue;
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
                    self.partial = Some(Instant::now());
                    // Charged before it is allocated; refused, it is skipped as one too large.
                    let held = match total {
                        t if t > self.max_message as u64 => None,
                        t => Some(self.hold((t as usize).max(self.assembly.capacity()))),
                    };
                    if let Some(Err(why)) = &held {
                        if oversized == Oversized::Refuse {
                            return Err(RingError::NotHeld { len: total, why: why.clone() }.into());
                        }
                    }
                    if !matches!(held, Some(Ok(()))) {
                        self.refused = held.and_then(Result::err);
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
                        self.partial = None;
                        let why = self.refused.take();
                        let kept = std::mem::take(&mut self.assembly);
                        let message = Message::Oversized { len: total as u64, head: &kept, why: why.as_deref() };
                        let r = self.deliver(message, (size, head), alive, &mut on_message);
                        self.assembly = kept;
                        head = r?;
                        delivered += 1;
                        continue;
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
                        self.partial = None;
                        let msg = std::mem::take(&mut self.assembly);
                        let r = self.deliver(Message::Whole(&msg), (size, head), alive, &mut on_message);
                        self.assembly = msg;
                        self.trim();
                        head = r?;
                        delivered += 1;
                        continue;
                    }
                }
                KIND_BULK => return Err(RingError::BadChunk("bulk frame outside a streamed blob").into()),
                other => return Err(RingError::UnknownKind(other).into()),
            }
            self.tail = self.tail.wrapping_add(size as u32);
            self.release_if_due();
        }
        self.release();
        Ok(delivered)
    }

    /// Hands `message` (a frame of `size` bytes at the tail, `head` the published head as last
    /// seen) to `on_message` with a [`Bulk`] over the frames after it, then skips what of its
    /// blob `on_message` left unread; returns the published head as last seen.
    fn deliver<E: From<RingError>>(
        &mut self,
        message: Message<'_>,
        (size, head): (usize, u32),
        alive: &dyn Fn() -> bool,
        on_message: &mut impl FnMut(Message<'_>, &Bulk<'_>) -> Result<(), E>,
    ) -> Result<u32, E> {
        self.tail = self.tail.wrapping_add(size as u32);
        self.bulk.begin(self.tail, head, self.released);
        let bulk = Bulk::new(&self.ring, &self.bulk, alive, self.partial_limit, &self.holdings);
        let r = on_message(message, &bulk);
        if let Some(e) = self.bulk.failure() {
            return Err(e.into());
        }
        r?;
        if !self.bulk.used.get() {
            return Ok(head);
        }
        bulk.finish()?;
        (self.tail, self.released) = (self.bulk.tail.get(), self.bulk.released.get());
        self.release_if_due();
        Ok(self.bulk.head.get())
    }

    /// Hands consumed space back once enough has gathered (a quarter of the ring, at most
    /// [`RELEASE_EVERY`]), mid-batch too.
    fn release_if_due(&mut self) {
        if self.tail.wrapping_sub(self.released) >= (self.ring.capacity / 4).min(RELEASE_EVERY) {
            self.release();
        }
    }

    fn release(&mut self) {
        let ctl = self.ring.ctl();
        store_and_wake(&ctl.tail.0, &ctl.writer_waiting.0, self.tail);
        self.released = self.tail;
    }
}

//! A streamed blob: the `BULK` frames after a message, read by whoever consumes the message
//! straight into the memory where the bytes go (a staging buffer, a texture upload), each byte
//! read once, so that bulk data crosses from the client to its destination in one copy rather
//! than two (Chromium's command buffer keeps such data in a separate transfer buffer for the
//! same reason). The bytes are opaque: nothing the daemon decides depends on them.

use std::cell::{Cell, RefCell};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use super::frame::{next_frame, Frame};
use super::holdings::Holdings;
use super::*;

/// What a [`Bulk`] keeps between calls, owned by the reader so that a message with no blob
/// costs it only a few stores.
#[derive(Default)]
pub(super) struct BulkState {
    pub tail: Cell<u32>,
    pub head: Cell<u32>,
    pub released: Cell<u32>,
    /// Bytes of the blob not yet read.
    remaining: Cell<u64>,
    /// Of the current frame: the offset of its next unread byte and how many are left.
    piece: Cell<(usize, usize)>,
    /// Whether a blob was announced or read: only then has the reader anything to take back.
    pub used: Cell<bool>,
    due: Cell<Option<Instant>>,
    /// What failed while the blob was read.
    failed: RefCell<Option<RingError>>,
    /// Bytes charged to the holdings for blobs read into the daemon's own memory.
    charged: Cell<usize>,
}

impl BulkState {
    /// Starts on the frames after a message: at `tail`, with `head` as last seen.
    pub fn begin(&self, tail: u32, head: u32, released: u32) {
        self.tail.set(tail);
        self.head.set(head);
        self.released.set(released);
        self.used.set(false);
    }

    /// What failed while the blob was read, if anything did.
    /// Whether a streamed blob was announced and not all of it has come: a peer gone now left
    /// in the middle of a command.
    pub fn unfinished(&self) -> bool {
        self.used.get() && self.remaining.get() > 0
    }

    pub fn failure(&self) -> Option<RingError> {
        if self.used.get() {
            self.failed.borrow().clone()
        } else {
            None
        }
    }
}

/// The `BULK` frames that follow the message being delivered, as that message's consumer
/// reads them. Nothing is expected until [`Bulk::expect`] announces the blob's length; what of
/// it is not read when the message has been handled is skipped.
pub struct Bulk<'r> {
    ring: &'r RingRegion,
    st: &'r BulkState,
    alive: &'r dyn Fn() -> bool,
    /// How long the blob may keep the reader waiting, from its first wait.
    limit: Option<Duration>,
    holdings: &'r RefCell<Option<(Box<dyn Holdings>, usize)>>,
}

impl<'r> Bulk<'r> {
    pub(super) fn new(
        ring: &'r RingRegion,
        st: &'r BulkState,
        alive: &'r dyn Fn() -> bool,
        limit: Option<Duration>,
        holdings: &'r RefCell<Option<(Box<dyn Holdings>, usize)>>,
    ) -> Self {
        Bulk { ring, st, alive, limit, holdings }
    }

    /// Announces that `len` bytes of blob follow the message; once per message (a second
    /// announcement is refused).
    pub fn expect(&self, len: u64) -> Result<(), RingError> {
        if len == 0 {
            return Ok(());
        }
        let st = self.st;
        if st.used.get() {
            return self.fail(RingError::BadChunk("a second streamed blob in one message"));
        }
        st.used.set(true);
        st.remaining.set(len);
        st.piece.set((0, 0));
        st.due.set(None);
        st.charged.set(0);
        *st.failed.borrow_mut() = None;
        Ok(())
    }

    /// Bytes of the announced blob not yet read.
    pub fn remaining(&self) -> u64 {
        if self.st.used.get() {
            self.st.remaining.get()
        } else {
            0
        }
    }

    /// Copies the blob's next `dst.len()` bytes into `dst`, waiting for the writer to publish
    /// them. Any failure (a peer gone, a frame that breaks the rules) also ends the reader's
    /// batch with that error, whatever the caller does with it.
    pub fn read(&self, dst: &mut [u8]) -> Result<(), RingError> {
        if let Some(e) = self.st.failure() {
            return Err(e);
        }
        if dst.len() as u64 > self.remaining() {
            return self.fail(RingError::BadChunk("read past the end of a streamed blob"));
        }
        let mut done = 0;
        while done < dst.len() {
            let (off, left) = self.next_piece()?;
            let n = left.min(dst.len() - done);
            // SAFETY: `off + left` lies within a checked frame's payload, and `dst[done..done + n]`
            // is the caller's memory.
            unsafe { self.ring.copy_raw(off, n, dst.as_mut_ptr().add(done)) };
            self.consume(off, left, n);
            done += n;
        }
        Ok(())
    }

    /// The blob's next `len` bytes, read into memory of the daemon's own that is charged to
    /// the reader's holdings before it is allocated.
    pub fn read_owned(&self, len: usize) -> Result<Vec<u8>, RingError> {
        if len as u64 > self.remaining() {
            return self.fail(RingError::BadChunk("read past the end of a streamed blob"));
        }
        if let Some((h, held)) = self.holdings.borrow_mut().as_mut() {
            let want = *held + self.st.charged.get() + len;
            if let Err(why) = h.hold(want) {
                return Err(RingError::NotHeld { len: len as u64, why });
            }
            self.st.charged.set(self.st.charged.get() + len);
        }
        let mut v = vec![0u8; len];
        self.read(&mut v)?;
        Ok(v)
    }

    fn fail<T>(&self, e: RingError) -> Result<T, RingError> {
        self.st.used.set(true);
        *self.st.failed.borrow_mut() = Some(e.clone());
        Err(e)
    }

    /// Skips what of the blob was not read, gives back what reading it charged, and hands the
    /// position back to the reader.
    pub(super) fn finish(&self) -> Result<(), RingError> {
        let st = self.st;
        while st.remaining.get() > 0 {
            let (off, left) = self.next_piece()?;
            let n = (left as u64).min(st.remaining.get()) as usize;
            self.consume(off, left, n);
        }
        if st.charged.get() > 0 {
            if let Some((h, held)) = self.holdings.borrow_mut().as_mut() {
                // Giving back is never refused.
                let _ = h.hold(*held);
            }
            st.charged.set(0);
        }
        Ok(())
    }

    fn consume(&self, off: usize, left: usize, n: usize) {
        self.st.piece.set((off + n, left - n));
        self.st.remaining.set(self.st.remaining.get() - n as u64);
    }

    /// The unread rest of the current `BULK` frame, moving on to the next one (waiting for it
    /// if needed) when the current one is used up.
    fn next_piece(&self) -> Result<(usize, usize), RingError> {
        let (off, left) = self.st.piece.get();
        if left > 0 {
            return Ok((off, left));
        }
        loop {
            let tail = self.st.tail.get();
            if tail == self.st.head.get() {
                self.release();
                let ctl = self.ring.ctl();
                if self.st.due.get().is_none() {
                    self.st.due.set(self.limit.map(|l| Instant::now() + l));
                }
                let due = self.st.due.get();
                let in_time = || due.is_none_or(|d| Instant::now() < d);
                let head = ctl.head.0.load(Ordering::Acquire);
                let head = if head != tail {
                    head
                } else {
                    match wait_change(&ctl.head.0, &ctl.reader_waiting.0, tail, &|| (self.alive)() && in_time()) {
                        Ok(h) => h,
                        Err(RingError::PeerGone) if (self.alive)() => {
                            let e = RingError::Stale { len: self.st.remaining.get(), have: 0, secs: 0.0 };
                            return self.fail(e);
                        }
                        Err(e) => return self.fail(e),
                    }
                };
                self.st.head.set(head);
            }
            let Frame { off, len, kind, size } = match next_frame(self.ring, tail, self.st.head.get()) {
                Ok(f) => f,
                Err(e) => return self.fail(e),
            };
            self.st.tail.set(tail.wrapping_add(size as u32));
            match kind {
                KIND_WRAP => continue,
                KIND_BULK if len as u64 > self.st.remaining.get() => {
                    return self.fail(RingError::BadChunk("bulk frames exceed the streamed blob's length"))
                }
                KIND_BULK if len > 0 => {
                    self.st.piece.set((off + FRAME_HEADER, len));
                    if tail != self.st.released.get() {
                        // Each piece read is handed back before the next is copied, so that a
                        // writer held at its lead resumes within a piece's time, while still
                        // spinning, rather than after it has gone to sleep.
                        self.release_to(tail);
                    }
                    return Ok((off + FRAME_HEADER, len));
                }
                KIND_BULK => continue,
                _ => return self.fail(RingError::BadChunk("a streamed blob ended before its announced length")),
            }
        }
    }

    /// Hands back to the writer everything before the tail.
    fn release(&self) {
        self.release_to(self.st.tail.get());
    }

    /// Hands back to the writer everything before `pos`.
    fn release_to(&self, pos: u32) {
        let ctl = self.ring.ctl();
        store_and_wake(&ctl.tail.0, &ctl.writer_waiting.0, pos);
        self.st.released.set(pos);
    }
}

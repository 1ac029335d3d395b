//! Single-producer/single-consumer byte ring in shared memory, carrying length-prefixed frames.
//!
//! Layout: a control block (`head`, `tail` and two waiting flags, each on its own cache line)
//! and a power-of-two data area. Positions are free-running `u32` byte counters; the offset
//! is `position & (capacity - 1)`. Every frame is 8-byte aligned and contiguous:
//! `[len: u32][kind: u32][payload; len][padding]`. When a frame does not fit before the end
//! of the data area the writer emits a `WRAP` frame and continues at offset 0. A message larger
//! than half the ring is split into `CHUNK_FIRST` (payload starts with the total length as
//! `u64`), `CHUNK_MORE` and `CHUNK_LAST` frames. A large blob may instead follow its message in `BULK`
//! frames, which the consumer of the message copies straight to where the bytes go (see [`Bulk`]).
//!
//! The reader trusts nothing in shared memory except what it validates: it keeps its own tail,
//! reads each header once into locals, checks every length against the published head and
//! the data area, and then copies the payload out once: the decoder reads only that private
//! copy, never the shared memory, so a peer that rewrites a frame while it is decoded changes
//! nothing the daemon checked. The writer never overwrites unread bytes: when the
//! ring is full it publishes, then waits for the reader.
//!
//! Waiting spins briefly, yields a few times, then sleeps on a futex on the word it waits for,
//! with a short timeout so that a dead peer is noticed.

use std::ptr::NonNull;
use std::sync::atomic::{AtomicU32, AtomicU64, AtomicU8, Ordering};
use std::sync::Arc;
use std::time::Duration;

use crate::futex;

/// Bytes of a frame header.
pub const FRAME_HEADER: usize = 8;
/// A complete message.
pub const KIND_WHOLE: u32 = 1;
/// First piece of a chunked message; payload begins with the total length (`u64`).
pub const KIND_CHUNK_FIRST: u32 = 2;
/// Middle piece of a chunked message.
pub const KIND_CHUNK_MORE: u32 = 3;
/// Last piece of a chunked message.
pub const KIND_CHUNK_LAST: u32 = 4;
/// A piece of a streamed blob: raw bytes that belong to the message before it (see
/// [`Bulk`]).
pub const KIND_BULK: u32 = 5;
/// Skip to the start of the data area.
pub const KIND_WRAP: u32 = 0x5041_5257;

/// Smallest data area a ring may have.
pub const MIN_CAPACITY: u32 = 4096;
/// Largest data area a ring may have.
pub const MAX_CAPACITY: u32 = 1 << 30;

const SPINS: u32 = 200;
const YIELDS: u32 = 8;
const SLEEP: Duration = Duration::from_millis(10);

/// Bytes a frame with `payload` bytes occupies, header and padding included.
pub fn frame_size(payload: usize) -> usize {
    (FRAME_HEADER + payload + 7) & !7
}

#[repr(C, align(64))]
struct Line(AtomicU32);

/// The ring's control block as it lies in shared memory.
#[repr(C)]
pub struct RingControl {
    head: Line,
    tail: Line,
    reader_waiting: Line,
    writer_waiting: Line,
}

/// Bytes the control block occupies.
pub const CONTROL_BYTES: usize = std::mem::size_of::<RingControl>();

/// A ring failure: a peer that vanished or broke the framing rules.
#[derive(Debug, Clone, thiserror::Error)]
pub enum RingError {
    /// The peer disconnected or died while we waited.
    #[error("peer disconnected")]
    PeerGone,
    /// The peer published a head that is not a valid position.
    #[error("published head is {ahead} bytes ahead of the tail; the ring holds only {capacity}")]
    BadHead {
        /// Bytes between tail and the published head.
        ahead: u32,
        /// The ring's capacity.
        capacity: u32,
    },
    /// The peer moved the tail to an impossible position.
    #[error("reader tail is {used} bytes behind the head; the ring holds only {capacity}")]
    BadTail {
        /// Bytes between the reader's tail and our head.
        used: u32,
        /// The ring's capacity.
        capacity: u32,
    },
    /// A frame was published only in part.
    #[error("truncated frame: it needs {needed} bytes but only {available} were published")]
    Truncated {
        /// Bytes the frame claims.
        needed: usize,
        /// Bytes actually published.
        available: usize,
    },
    /// A frame's length field cannot fit in the ring.
    #[error("frame length {len} does not fit: at most {limit} bytes remain before the ring's end")]
    BadLength {
        /// The length field.
        len: u32,
        /// The largest payload that would fit.
        limit: usize,
    },
    /// A frame kind the protocol does not define.
    #[error("unknown frame kind {0:#x}")]
    UnknownKind(u32),
    /// A chunked message announced a size beyond the limit.
    #[error("message of {len} bytes exceeds the {limit}-byte limit")]
    TooLarge {
        /// Announced size.
        len: u64,
        /// The limit.
        limit: usize,
    },
    /// The memory to assemble a chunked message was not granted (the reason).
    #[error("a chunked message of {len} bytes cannot be held: {why}")]
    NotHeld {
        /// Announced size.
        len: u64,
        /// Why it was refused.
        why: String,
    },
    /// A chunked message was begun and not finished in time.
    #[error("a chunked message of {len} bytes was begun {secs:.0} s ago and not finished ({have} bytes came)")]
    Stale {
        /// Announced size.
        len: u64,
        /// Bytes that came.
        have: u64,
        /// Seconds since its first chunk.
        secs: f64,
    },
    /// Chunk frames out of order or inconsistent with their announced size.
    #[error("bad chunk sequence: {0}")]
    BadChunk(&'static str),
    /// The region handed to the ring is unusable.
    #[error("bad ring geometry: {0}")]
    Geometry(String),
    /// The tail the reader started from (as the peer left it in shared memory) is not at a
    /// frame boundary: frames start 8-byte aligned.
    #[error("reader tail {0} is not 8-byte aligned")]
    MisalignedTail(u32),
}

/// Keeps the memory behind a ring mapped while any ring end uses it.
pub trait Backing: Send + Sync {}

/// Where one ring lives: its control block and data area, kept alive by `backing`.
#[derive(Clone)]
pub struct RingRegion {
    ctl: NonNull<RingControl>,
    data: NonNull<u8>,
    capacity: u32,
    _backing: Arc<dyn Backing>,
}

// SAFETY: the region only hands out atomics and bounds-checked byte ranges of memory that
// `_backing` keeps mapped; the SPSC protocol decides who writes which bytes.
unsafe impl Send for RingRegion {}

impl RingRegion {
    /// Describes a ring inside memory kept alive by `backing`.
    ///
    /// # Safety
    /// `ctl` must point to `CONTROL_BYTES` writable bytes aligned to 64, and `data` to
    /// `capacity` writable bytes aligned to 8, both valid for as long as `backing` lives.
    pub unsafe fn new(
        ctl: *mut u8,
        data: *mut u8,
        capacity: u32,
        backing: Arc<dyn Backing>,
    ) -> Result<Self, RingError> {
        if !capacity.is_power_of_two() || !(MIN_CAPACITY..=MAX_CAPACITY).contains(&capacity) {
            return Err(RingError::Geometry(format!(
                "capacity {capacity} must be a power of two in {MIN_CAPACITY}..={MAX_CAPACITY}"
            )));
        }
        if !(ctl as usize).is_multiple_of(64) || !(data as usize).is_multiple_of(8) {
            return Err(RingError::Geometry("misaligned control block or data area".into()));
        }
        let ctl = NonNull::new(ctl.cast()).ok_or_else(|| RingError::Geometry("null control".into()))?;
        let data = NonNull::new(data).ok_or_else(|| RingError::Geometry("null data".into()))?;
        Ok(RingRegion { ctl, data, capacity, _backing: backing })
    }

    fn ctl(&self) -> &RingControl {
        // SAFETY: valid per `new`'s contract; only atomics are accessed through it.
        unsafe { self.ctl.as_ref() }
    }

    /// Bytes in the data area.
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Wakes a reader sleeping on this ring, e.g. so it notices its peer is gone.
    pub fn wake_reader(&self) {
        futex::wake(&self.ctl().head.0);
    }

    /// Wakes a writer sleeping on this ring.
    pub fn wake_writer(&self) {
        futex::wake(&self.ctl().tail.0);
    }

    /// Zeroes the control block; only the creator calls this, before sharing the ring.
    pub fn reset(&self) {
        let c = self.ctl();
        for w in [&c.head, &c.tail, &c.reader_waiting, &c.writer_waiting] {
            w.0.store(0, Ordering::SeqCst);
        }
    }

    fn offset(&self, pos: u32) -> usize {
        (pos & (self.capacity - 1)) as usize
    }

    /// Reads the two header words at `off` once, into locals.
    fn read_header(&self, off: usize) -> (u32, u32) {
        debug_assert!(off + FRAME_HEADER <= self.capacity as usize && off.is_multiple_of(8));
        // SAFETY: `off` is 8-aligned and below `capacity`, and capacity is a multiple of 8, so
        // both words lie inside the data area. Volatile: the peer may write concurrently.
        unsafe {
            let p = self.data.as_ptr().add(off).cast::<u32>();
            (p.read_volatile(), p.add(1).read_volatile())
        }
    }

    fn write_header(&self, off: usize, len: u32, kind: u32) {
        // SAFETY: as in `read_header`; the writer owns the bytes between tail and capacity.
        unsafe {
            let p = self.data.as_ptr().add(off).cast::<u32>();
            p.write_volatile(len);
            p.add(1).write_volatile(kind);
        }
    }

    /// Appends the `len` bytes at `off` to `dst`, each read once: the reader's private copy,
    /// which is all that decoding ever sees. The peer may rewrite the ring at any moment, so
    /// no reference to it is ever formed. Every word is read by an atomic load, which a
    /// concurrent write cannot make undefined; on x86-64 a copy of [`STRING_COPY_FROM`] bytes
    /// or more is one `rep movsb`, whose reads are such loads too (the instruction reads each
    /// byte once, and the language sees only the opaque instruction), at the speed of the
    /// machine's own memcpy.
    ///
    /// # Safety
    /// `off + len` must lie within the data area.
    unsafe fn copy_out(&self, off: usize, len: usize, dst: &mut Vec<u8>) {
        dst.reserve(len);
        self.copy_raw(off, len, dst.as_mut_ptr().add(dst.len()));
        dst.set_len(dst.len() + len);
    }

    /// Copies the `len` bytes at `off` to `out`, each read once (as [`RingRegion::copy_out`]).
    ///
    /// # Safety
    /// `off + len` must lie within the data area, and `out` must name `len` writable bytes of
    /// the daemon's own memory.
    unsafe fn copy_raw(&self, off: usize, len: usize, out: *mut u8) {
        let src = self.data.as_ptr().add(off);
        #[cfg(target_arch = "x86_64")]
        if len >= STRING_COPY_FROM {
            // SAFETY: `src` names `len` readable bytes of the data area and `out` `len`
            // writable bytes of the caller's; they do not overlap (`out` is the daemon's).
            std::arch::asm!(
                "rep movsb",
                inout("rcx") len => _,
                inout("rsi") src => _,
                inout("rdi") out => _,
                options(nostack, preserves_flags)
            );
            return;
        }
        let byte = |i: usize| AtomicU8::from_ptr(src.add(i)).load(Ordering::Relaxed);
        let mut i = 0;
        while i < len && !(src as usize + i).is_multiple_of(8) {
            out.add(i).write(byte(i));
            i += 1;
        }
        while i + 8 <= len {
            let word = AtomicU64::from_ptr(src.add(i).cast::<u64>()).load(Ordering::Relaxed);
            out.add(i).cast::<u64>().write_unaligned(word);
            i += 8;
        }
        while i < len {
            out.add(i).write(byte(i));
            i += 1;
        }
    }

    /// The `N` bytes at `off`, read once (as [`RingRegion::copy_out`] reads them).
    ///
    /// # Safety
    /// `off + N` must lie within the data area.
    unsafe fn read_array<const N: usize>(&self, off: usize) -> [u8; N] {
        let mut v = Vec::with_capacity(N);
        self.copy_out(off, N, &mut v);
        let mut a = [0u8; N];
        a.copy_from_slice(&v);
        a
    }

    /// Stores `byte` at `off` (taken modulo the capacity) of the data area, whatever lies
    /// there: the tool for testing a reader against a peer that rewrites frames as they are read.
    #[cfg(feature = "fault-injection")]
    pub fn scribble(&self, off: usize, byte: u8) {
        let off = off % self.capacity as usize;
        // SAFETY: `off` lies inside the data area; an atomic store races with nothing undefined.
        unsafe { AtomicU8::from_ptr(self.data.as_ptr().add(off)).store(byte, Ordering::Relaxed) }
    }

    /// # Safety
    /// `off + len` must lie within the data area, in the writer's free space.
    #[allow(clippy::mut_from_ref)]
    unsafe fn bytes_mut(&self, off: usize, len: usize) -> &mut [u8] {
        std::slice::from_raw_parts_mut(self.data.as_ptr().add(off), len)
    }
}

/// The smallest copy out of the ring made with one string instruction rather than word by
/// word (x86-64).
const STRING_COPY_FROM: usize = 256;

/// Publishes `value` to `word` and wakes the peer if it sleeps on it.
fn store_and_wake(word: &AtomicU32, waiting: &AtomicU32, value: u32) {
    word.store(value, Ordering::SeqCst);
    if waiting.load(Ordering::SeqCst) != 0 {
        futex::wake(word);
    }
}

/// Waits until `word` differs from `current`: spin, yield, then futex sleeps that check
/// `alive` on every timeout.
fn wait_change(
    word: &AtomicU32,
    waiting: &AtomicU32,
    current: u32,
    alive: &dyn Fn() -> bool,
) -> Result<u32, RingError> {
    for _ in 0..SPINS {
        let v = word.load(Ordering::Acquire);
        if v != current {
            return Ok(v);
        }
        std::hint::spin_loop();
    }
    for _ in 0..YIELDS {
        std::thread::yield_now();
        let v = word.load(Ordering::Acquire);
        if v != current {
            return Ok(v);
        }
    }
    loop {
        waiting.store(1, Ordering::SeqCst);
        let v = word.load(Ordering::SeqCst);
        if v != current {
            waiting.store(0, Ordering::Relaxed);
            return Ok(v);
        }
        futex::wait(word, current, SLEEP);
        waiting.store(0, Ordering::Relaxed);
        let v = word.load(Ordering::Acquire);
        if v != current {
            return Ok(v);
        }
        if !alive() {
            return Err(RingError::PeerGone);
        }
    }
}

mod bulk;
mod frame;
mod holdings;
mod reader;
mod writer;

pub use bulk::Bulk;
pub use holdings::Holdings;
pub use reader::{Message, Oversized, Reader, OVERSIZED_HEAD};
pub use writer::{Writer, BULK_PIECE, HOT_WINDOW, STREAM_FROM};

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    struct Heap(#[allow(dead_code)] Vec<u64>);
    impl Backing for Heap {}

    fn heap_ring(capacity: u32) -> RingRegion {
        let words = (CONTROL_BYTES + capacity as usize) / 8 + 8;
        let mut mem = vec![0u64; words];
        let base = mem.as_mut_ptr().cast::<u8>();
        let ctl = ((base as usize + 63) & !63) as *mut u8;
        // SAFETY: `ctl` is 64-aligned inside `mem`, followed by CONTROL_BYTES + capacity bytes
        // that `mem` (moved into the backing Arc, which does not move its heap buffer) keeps.
        unsafe { RingRegion::new(ctl, ctl.add(CONTROL_BYTES), capacity, Arc::new(Heap(mem))) }.expect("ring")
    }

    fn message(seed: u64, len: usize) -> Vec<u8> {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        (0..len).map(|_| rng.random()).collect()
    }

    /// Two threads, random sizes (including some larger than the ring) across many wraps:
    /// nothing lost, nothing reordered, every checksum equal.
    #[test]
    fn two_threads_random_sizes() {
        let ring = heap_ring(1 << 14);
        let reader_ring = ring.clone();
        const N: u64 = 20_000;
        let producer = std::thread::spawn(move || {
            let mut w = Writer::new(ring, 4096);
            let mut rng = rand::rngs::StdRng::seed_from_u64(7);
            for i in 0..N {
                let len = if i % 997 == 0 { rng.random_range(20_000..70_000) } else { rng.random_range(0..3000) };
                let msg = message(i, len);
                w.write::<RingError>(len + 8, &|| true, |buf| {
                    buf[..8].copy_from_slice(&i.to_le_bytes());
                    buf[8..].copy_from_slice(&msg);
                    Ok(())
                })
                .expect("write");
            }
            w.publish();
        });
        let mut r = Reader::new(reader_ring, 1 << 20);
        let mut next = 0u64;
        while next < N {
            r.recv_batch::<RingError>(&|| true, |m| {
                let seq = u64::from_le_bytes(m[..8].try_into().expect("seq"));
                assert_eq!(seq, next, "reordered or lost");
                assert_eq!(crc32fast::hash(&m[8..]), crc32fast::hash(&message(seq, m.len() - 8)));
                next += 1;
                Ok(())
            })
            .expect("read");
        }
        producer.join().expect("producer");
    }

    /// A chunked message beyond the reader's limit is skipped unkept and reported with its
    /// length and head; the messages around it arrive whole and in order. `recv_batch` still
    /// refuses it.
    #[test]
    fn oversized_messages_are_skipped_and_the_stream_goes_on() {
        let ring = heap_ring(1 << 14);
        let reader_ring = ring.clone();
        let producer = std::thread::spawn(move || {
            let mut w = Writer::new(ring, 4096);
            for len in [100usize, 50_000, 200] {
                let msg = message(len as u64, len);
                w.write::<RingError>(len, &|| true, |buf| {
                    buf.copy_from_slice(&msg);
                    Ok(())
                })
                .expect("write");
            }
            w.publish();
        });
        let mut r = Reader::new(reader_ring, 10_000);
        let mut seen = Vec::new();
        while seen.len() < 3 {
            r.recv_messages::<RingError>(&|| true, Oversized::Skip, |m, _| {
                seen.push(match m {
                    Message::Whole(b) => (b.len() as u64, b.to_vec()),
                    Message::Oversized { len, head, .. } => (len, head.to_vec()),
                });
                Ok(())
            })
            .expect("read");
        }
        producer.join().expect("producer");
        assert_eq!(seen[0], (100, message(100, 100)));
        assert_eq!(seen[1], (50_000, message(50_000, 50_000)[..OVERSIZED_HEAD].to_vec()));
        assert_eq!(seen[2], (200, message(200, 200)));
        assert!(!r.mid_message());
    }

    fn read_one(ring: RingRegion) -> Result<usize, RingError> {
        let mut r = Reader::new(ring, 1 << 20);
        r.recv_batch::<RingError>(&|| false, |_| Ok(()))
    }

    #[test]
    fn hostile_headers_are_rejected() {
        let cases: Vec<(Vec<u8>, u32, &str)> = vec![
            ([100u32.to_le_bytes(), KIND_WHOLE.to_le_bytes()].concat(), 64, "Truncated"),
            ([0x7fff_ffffu32.to_le_bytes(), KIND_WHOLE.to_le_bytes()].concat(), 64, "BadLength"),
            ([4u32.to_le_bytes(), 77u32.to_le_bytes()].concat(), 16, "UnknownKind"),
            (vec![1, 2, 3], 3, "Truncated"),
            ([4u32.to_le_bytes(), KIND_CHUNK_MORE.to_le_bytes()].concat(), 16, "BadChunk"),
            ([0u32.to_le_bytes(), KIND_WHOLE.to_le_bytes()].concat(), 1 << 20, "BadHead"),
        ];
        for (bytes, advance, want) in cases {
            let ring = heap_ring(4096);
            let mut w = Writer::new(ring.clone(), 4096);
            let off = 0;
            // SAFETY: test writes at the start of a fresh ring.
            unsafe { ring.bytes_mut(off, bytes.len()) }.copy_from_slice(&bytes);
            w.head = advance;
            w.publish();
            let err = read_one(ring).expect_err(want);
            assert!(format!("{err:?}").starts_with(want), "{want}: got {err:?}");
        }
    }

    /// A client can set the tail before the daemon's reader starts: one off a frame boundary,
    /// near the ring's end, is refused before any header is read past the data area.
    #[test]
    fn planted_misaligned_tail_is_rejected() {
        let ring = heap_ring(4096);
        let tail = 4096 - 3;
        ring.ctl().tail.0.store(tail, Ordering::SeqCst);
        ring.ctl().head.0.store(tail + 16, Ordering::SeqCst);
        match read_one(ring) {
            Err(RingError::MisalignedTail(t)) => assert_eq!(t, tail),
            other => panic!("expected MisalignedTail, got {other:?}"),
        }
    }

    #[test]
    fn announced_size_over_limit_is_rejected() {
        let ring = heap_ring(4096);
        let mut w = Writer::new(ring.clone(), 4096);
        let mut frame = Vec::new();
        frame.extend_from_slice(&8u32.to_le_bytes());
        frame.extend_from_slice(&KIND_CHUNK_FIRST.to_le_bytes());
        frame.extend_from_slice(&(u64::MAX).to_le_bytes());
        // SAFETY: start of a fresh ring.
        unsafe { ring.bytes_mut(0, frame.len()) }.copy_from_slice(&frame);
        w.head = 16;
        w.publish();
        assert!(matches!(read_one(ring), Err(RingError::TooLarge { .. })));
    }

    #[test]
    fn dead_peer_ends_the_wait() {
        let ring = heap_ring(4096);
        let mut r = Reader::new(ring, 1024);
        let t = std::time::Instant::now();
        let e = r.recv_batch::<RingError>(&|| false, |_| Ok(()));
        assert!(matches!(e, Err(RingError::PeerGone)));
        assert!(t.elapsed() < Duration::from_secs(2));
    }
}

//! What the ring tests share: a ring in heap memory, and the peer's view of its data area.

#![allow(dead_code)]

use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};
use std::sync::Arc;

use strata_protocol::ring::{Backing, RingRegion, CONTROL_BYTES};

/// Heap memory standing in for the shared segment.
struct Heap(#[allow(dead_code)] Vec<u64>);
impl Backing for Heap {}

/// The data area of a heap ring, as the peer sees it: rewritten byte by byte.
#[derive(Clone, Copy)]
pub struct Peer {
    pub data: *mut u8,
    pub len: usize,
}
// SAFETY: the pointer names memory that the ring's backing keeps alive for the whole test, and
// the peer only ever stores to it atomically.
unsafe impl Send for Peer {}

impl Peer {
    pub fn byte(&self, i: usize) -> &AtomicU8 {
        assert!(i < self.len);
        // SAFETY: `i` lies inside the data area, which outlives every use (see `Send` above).
        unsafe { AtomicU8::from_ptr(self.data.add(i)) }
    }

    /// Replaces every occurrence of `from` in the data area with `to` (of the same length);
    /// returns how many it rewrote.
    pub fn rewrite(&self, from: &[u8], to: &[u8]) -> usize {
        let mut n = 0;
        for start in 0..=self.len - from.len() {
            if (0..from.len()).all(|k| self.byte(start + k).load(Ordering::Relaxed) == from[k]) {
                for (k, &b) in to.iter().enumerate() {
                    self.byte(start + k).store(b, Ordering::Relaxed);
                }
                n += 1;
            }
        }
        n
    }
}

pub fn heap_ring(capacity: u32) -> (RingRegion, Peer) {
    let words = (CONTROL_BYTES + capacity as usize) / 8 + 8;
    let mut mem = vec![0u64; words];
    let base = mem.as_mut_ptr().cast::<u8>();
    let ctl = ((base as usize + 63) & !63) as *mut u8;
    // SAFETY: `ctl` is 64-aligned inside `mem` and followed by CONTROL_BYTES + capacity bytes,
    // which `mem` (moved into the backing, which does not move its heap buffer) keeps.
    let (ctl, data) = unsafe { (ctl, ctl.add(CONTROL_BYTES)) };
    // SAFETY: as above.
    let ring = unsafe { RingRegion::new(ctl, data, capacity, Arc::new(Heap(mem))) }.expect("ring");
    (ring, Peer { data, len: capacity as usize })
}

/// Starts the racing peer: a thread that stores random bytes at random offsets of the data
/// area that `pick` accepts, counting each store in `strokes`, until `stop` is raised.
pub fn scribbler(
    peer: Peer,
    seed: u64,
    stop: Arc<AtomicBool>,
    strokes: Arc<AtomicUsize>,
    pick: impl Fn(usize) -> bool + Send + 'static,
) -> std::thread::JoinHandle<()> {
    use rand::{Rng, SeedableRng};
    std::thread::spawn(move || {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        while !stop.load(Ordering::Relaxed) {
            let i = rng.random_range(0..peer.len);
            if pick(i) {
                peer.byte(i).store(rng.random(), Ordering::Relaxed);
                strokes.fetch_add(1, Ordering::Relaxed);
            }
        }
    })
}

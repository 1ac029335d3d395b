//! The daemon's end of a command ring, fed a ring whose every byte a hostile client controls.
//!
//! Input: `[tail: u32]` then rounds of `[advance: u32][offset: u16][length: u16][bytes]`. The
//! control block and a zeroed data area are built over a plain heap buffer; each round writes
//! the bytes into the data area at the offset, publishes a head `advance` bytes past the tail
//! the reader last released (so that most rounds are plausible, and any head is possible),
//! then runs `recv_messages` and decodes every delivered message as the session does (a
//! streamed blob announced, then read from the `BULK` frames after it). The peer counts as gone, so a reader
//! that would wait returns instead; `recv_messages` is only entered with data published, because
//! with none it sleeps on the futex before it notices.
#![no_main]

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

use libfuzzer_sys::fuzz_target;
use strata_protocol::codec::decode_command;
use strata_protocol::ring::{Backing, Message, Oversized, Reader, RingError, RingRegion, CONTROL_BYTES, MIN_CAPACITY};

/// The data area's size: the smallest a ring may have, so that the input covers it.
const CAPACITY: usize = MIN_CAPACITY as usize;
/// The largest chunked message the reader assembles (the daemon allows 512 MiB).
const MAX_MESSAGE: usize = 1 << 20;
/// Rounds per input, so that one input cannot run long.
const MAX_ROUNDS: usize = 64;
/// Byte offsets of the head and tail words in the control block (one cache line each).
const HEAD: usize = 0;
const TAIL: usize = 64;

/// Heap memory standing in for the shared-memory segment.
struct Heap(#[allow(dead_code)] Vec<u64>);
impl Backing for Heap {}

/// Reads `N` bytes from the front of `input`, if it has them.
fn take<const N: usize>(input: &mut &[u8]) -> Option<[u8; N]> {
    let (head, rest) = input.split_first_chunk::<N>()?;
    *input = rest;
    Some(*head)
}

fuzz_target!(|data: &[u8]| {
    let mut input = data;
    let Some(tail) = take::<4>(&mut input).map(u32::from_le_bytes) else { return };
    let mut mem = vec![0u64; (CONTROL_BYTES + CAPACITY) / 8 + 8];
    let base = mem.as_mut_ptr().cast::<u8>();
    let ctl = ((base as usize + 63) & !63) as *mut u8;
    // SAFETY: `ctl` is 64-aligned inside `mem` and followed by CONTROL_BYTES + CAPACITY bytes;
    // the vector's heap buffer does not move when the vector moves into the backing.
    let (ctl, data_area) = unsafe { (ctl, ctl.add(CONTROL_BYTES)) };
    let word = |offset: usize| {
        // SAFETY: `offset` is 0 or 64, a 4-aligned word inside the control block, which lives
        // as long as `mem` does (inside the ring's backing, dropped after every use below).
        unsafe { AtomicU32::from_ptr(ctl.add(offset).cast::<u32>()) }
    };
    word(TAIL).store(tail, Ordering::SeqCst);
    word(HEAD).store(tail, Ordering::SeqCst);
    // SAFETY: as above; `Heap` keeps the memory alive as long as the region.
    let ring = unsafe { RingRegion::new(ctl, data_area, CAPACITY as u32, Arc::new(Heap(mem))) }.expect("ring geometry");
    let mut reader = Reader::new(ring, MAX_MESSAGE);
    for _ in 0..MAX_ROUNDS {
        let Some(advance) = take::<4>(&mut input).map(u32::from_le_bytes) else { break };
        let Some(patch) = take::<4>(&mut input) else { break };
        let at = usize::from(u16::from_le_bytes([patch[0], patch[1]])) % CAPACITY;
        let n = usize::from(u16::from_le_bytes([patch[2], patch[3]])).min(CAPACITY - at).min(input.len());
        // SAFETY: `at + n <= CAPACITY`.
        unsafe { std::ptr::copy_nonoverlapping(input.as_ptr(), data_area.add(at), n) };
        input = &input[n..];
        let released = word(TAIL).load(Ordering::SeqCst);
        word(HEAD).store(released.wrapping_add(advance), Ordering::SeqCst);
        if !reader.has_data() {
            continue;
        }
        let r = reader.recv_messages::<RingError>(&|| false, Oversized::Refuse, |m, bulk| {
            let Message::Whole(msg) = m else { return Ok(()) };
            assert!(msg.len() <= MAX_MESSAGE, "a {}-byte message passed the {MAX_MESSAGE}-byte limit", msg.len());
            // As the session does: a streamed blob is announced, then read from the frames after.
            let Ok(mut cmd) = decode_command(msg) else { return Ok(()) };
            if let Some(blob) = cmd.bulk_mut() {
                let len = blob.streamed_len().unwrap_or(0);
                if len <= MAX_MESSAGE as u64 {
                    bulk.expect(len)?;
                    blob.attach(bulk);
                    blob.materialize()?;
                    assert_eq!(blob.as_bytes().len() as u64, len, "a streamed blob read at another length");
                }
            }
            Ok(())
        });
        if r.is_err() {
            // The session ends at the first violation; so does this client.
            break;
        }
    }
});

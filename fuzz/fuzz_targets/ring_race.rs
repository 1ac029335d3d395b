//! The daemon's end of a command ring while a second thread of the peer rewrites the ring's
//! bytes (frames, headers, padding) as the reader takes and decodes them.
//!
//! Input: `[count: u8]`, then `count` messages `[len: u16][bytes]`, then the peer's strokes,
//! each `[offset: u16][byte: u8]`. The messages are framed into a 4 KiB heap ring by the real
//! writer while nothing races; then a second thread applies the strokes over and over (atomic
//! stores, as a peer's process would write) while the reader runs `recv_batch` and decodes
//! every message it delivers. Each delivered message must stay the same for as long as it is
//! handled, and decode the same twice: the reader hands out a private copy, never a view of
//! the ring. The peer counts as gone, so nothing waits.
#![no_main]

use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};
use std::sync::Arc;

use libfuzzer_sys::fuzz_target;
use strata_protocol::codec::decode_command;
use strata_protocol::ring::{Backing, Reader, RingError, RingRegion, Writer, CONTROL_BYTES, MIN_CAPACITY};

/// The data area's size: the smallest a ring may have.
const CAPACITY: usize = MIN_CAPACITY as usize;
/// The largest chunked message the reader assembles.
const MAX_MESSAGE: usize = 1 << 20;
/// Strokes the peer makes at most per input, so that one input cannot run long.
const MAX_STROKES: usize = 1 << 16;

/// Heap memory standing in for the shared-memory segment.
struct Heap(#[allow(dead_code)] Vec<u64>);
impl Backing for Heap {}

/// The data area as the racing thread sees it.
#[derive(Clone, Copy)]
struct Area(*mut u8);
// SAFETY: the area lives in the ring's backing, which outlives the racing thread (joined
// before the ring drops), and the thread only stores to it atomically.
unsafe impl Send for Area {}

/// Reads `N` bytes from the front of `input`, if it has them.
fn take<const N: usize>(input: &mut &[u8]) -> Option<[u8; N]> {
    let (head, rest) = input.split_first_chunk::<N>()?;
    *input = rest;
    Some(*head)
}

/// Decodes `msg` into a comparable form.
fn decoded(msg: &[u8]) -> String {
    match decode_command(msg) {
        Ok(c) => format!("{c:?}"),
        Err(e) => e.to_string(),
    }
}

fuzz_target!(|data: &[u8]| {
    let mut input = data;
    let Some([count]) = take::<1>(&mut input) else { return };
    let mut messages = Vec::new();
    for _ in 0..count {
        let Some(len) = take::<2>(&mut input).map(u16::from_le_bytes) else { break };
        let len = usize::from(len).min(input.len());
        messages.push(&input[..len]);
        input = &input[len..];
    }
    let strokes: Vec<(usize, u8)> = input
        .chunks_exact(3)
        .map(|s| (usize::from(u16::from_le_bytes([s[0], s[1]])) % CAPACITY, s[2]))
        .collect();

    let mut mem = vec![0u64; (CONTROL_BYTES + CAPACITY) / 8 + 8];
    let base = mem.as_mut_ptr().cast::<u8>();
    let ctl = ((base as usize + 63) & !63) as *mut u8;
    // SAFETY: `ctl` is 64-aligned inside `mem` and followed by CONTROL_BYTES + CAPACITY bytes;
    // the vector's heap buffer does not move when the vector moves into the backing.
    let (ctl, area) = unsafe { (ctl, ctl.add(CONTROL_BYTES)) };
    // SAFETY: as above; `Heap` keeps the memory alive as long as the region.
    let ring = unsafe { RingRegion::new(ctl, area, CAPACITY as u32, Arc::new(Heap(mem))) }.expect("ring geometry");

    // The writer frames the messages while nothing races it (its slices are not atomic).
    let mut writer = Writer::new(ring.clone(), CAPACITY as u32);
    let mut room = CAPACITY / 2;
    for m in &messages {
        if m.len() + 16 > room {
            break;
        }
        room -= m.len() + 16;
        let written = writer.write::<RingError>(m.len(), &|| false, |buf| {
            buf.copy_from_slice(m);
            Ok(())
        });
        if written.is_err() {
            return;
        }
    }
    writer.publish();

    let stop = Arc::new(AtomicBool::new(false));
    let racer = (!strokes.is_empty()).then(|| {
        let stop = stop.clone();
        let area = Area(area);
        std::thread::spawn(move || {
            let area = area;
            for &(off, byte) in strokes.iter().cycle().take(MAX_STROKES) {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                // SAFETY: `off < CAPACITY`, inside the data area (see `Area`).
                unsafe { AtomicU8::from_ptr(area.0.add(off)) }.store(byte, Ordering::Relaxed);
            }
        })
    });
    let mut reader = Reader::new(ring, MAX_MESSAGE);
    if reader.has_data() {
        let _ = reader.recv_batch::<RingError>(&|| false, |msg| {
            let held = msg.to_vec();
            let first = decoded(msg);
            assert_eq!(decoded(msg), first, "a message decoded twice gave two answers");
            assert_eq!(msg, &held[..], "a delivered message changed while it was handled");
            Ok(())
        });
    }
    stop.store(true, Ordering::Relaxed);
    if let Some(racer) = racer {
        racer.join().expect("racer");
    }
});

//! A peer that rewrites the ring's frames while the daemon's end reads and decodes them: what
//! the reader delivers is a private copy, so a value checked once stays the value used, and a
//! frame scribbled over ends the stream with an error, never a panic.
//!
//! The ring lies in heap memory here; the peer's rewrites are atomic stores, as the reader's
//! copy is made of atomic loads, so the race the test stages is one the language defines.

mod support;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use rand::{Rng, SeedableRng};
use strata_protocol::codec::{decode_command, encode_to_vec};
use strata_protocol::ring::{Reader, RingError, Writer};
use strata_protocol::{Command, Text};
use support::{heap_ring, scribbler};

fn write(w: &mut Writer, msg: &[u8]) {
    w.write::<RingError>(msg.len(), &|| true, |buf| {
        buf.copy_from_slice(msg);
        Ok(())
    })
    .expect("write");
}

/// The peer rewrites an attribute's name between the daemon's check of it (no `gl_` prefix)
/// and its use: the use still sees the name that was checked.
#[test]
fn a_value_checked_is_the_value_used() {
    let (ring, peer) = heap_ring(4096);
    let cmd = Command::BindAttribLocation { program: 1, index: 0, name: Text::borrowed("position") };
    let mut w = Writer::new(ring.clone(), 4096);
    write(&mut w, &encode_to_vec(&cmd).expect("encode"));
    w.publish();
    let mut r = Reader::new(ring, 1 << 20);
    let delivered = r
        .recv_batch::<RingError>(&|| true, |msg| {
            let Ok(Command::BindAttribLocation { name, .. }) = decode_command(msg) else {
                panic!("not the command written");
            };
            // The check, as the executor makes it.
            assert!(!name.as_str().starts_with("gl_"), "checked");
            // The peer strikes between the check and the use.
            assert_eq!(peer.rewrite(b"position", b"gl_Posit"), 1, "the frame still lies in the ring");
            // The use.
            assert_eq!(name.as_str(), "position", "the value used is not the value checked");
            Ok(())
        })
        .expect("read");
    assert_eq!(delivered, 1);
}

/// A second thread scribbles over the frames (payloads and headers) while the reader takes
/// them and decodes each: the reader never panics, every message it delivers stays the same
/// for as long as it is handled, and a scribbled header ends the stream with an error.
#[test]
fn a_racing_writer_changes_nothing_delivered() {
    const CAPACITY: u32 = 1 << 14;
    let deadline = Instant::now() + Duration::from_secs(3);
    let mut rng = rand::rngs::StdRng::seed_from_u64(42);
    let (mut delivered, mut ended, mut rounds) = (0usize, 0usize, 0usize);
    while Instant::now() < deadline || rounds < 20 {
        rounds += 1;
        let (ring, peer) = heap_ring(CAPACITY);
        let mut w = Writer::new(ring.clone(), CAPACITY);
        let mut r = Reader::new(ring, 1 << 20);
        // The writer fills the ring while nothing races it (its slices are not atomic) ...
        for i in 0..rng.random_range(1..40u32) {
            let text = format!("attribute_{i}_{}", "x".repeat(rng.random_range(0..300)));
            let cmd = Command::BindAttribLocation { program: i, index: 0, name: Text::borrowed(&text) };
            let bytes = encode_to_vec(&cmd).expect("encode");
            if bytes.len() + 64 > (CAPACITY as usize - w.unpublished() as usize) / 2 {
                break;
            }
            write(&mut w, &bytes);
        }
        w.publish();
        // ... then the peer scribbles while the reader reads and decodes.
        let stop = Arc::new(AtomicBool::new(false));
        let strokes = Arc::new(AtomicUsize::new(0));
        // Payload bytes only, except in every fourth round.
        let headers_too = rounds % 4 == 0;
        let pick = move |i: usize| headers_too || i % 8 >= 4;
        let racer = scribbler(peer, rng.random(), stop.clone(), strokes.clone(), pick);
        let result = r.recv_batch::<RingError>(&|| false, |msg| {
            let before = msg.to_vec();
            let decoded = decode_command(msg).map(|c| format!("{c:?}")).map_err(|e| e.to_string());
            // Let the peer strike while the message is in hand.
            let start = strokes.load(Ordering::Relaxed);
            let wait = Instant::now();
            while strokes.load(Ordering::Relaxed) < start + 64 && wait.elapsed() < Duration::from_millis(50) {
                std::hint::spin_loop();
            }
            assert_eq!(msg, &before[..], "a delivered message changed while it was handled");
            let again = decode_command(msg).map(|c| format!("{c:?}")).map_err(|e| e.to_string());
            assert_eq!(again, decoded, "decoded twice, read twice");
            delivered += 1;
            Ok(())
        });
        stop.store(true, Ordering::Relaxed);
        racer.join().expect("racer");
        if result.is_err() {
            ended += 1;
        }
    }
    assert!(delivered > 100, "too few messages delivered to mean anything: {delivered}");
    assert!(ended > 0, "no scribbled header ended a stream in {rounds} rounds");
}

//! The memory a reader holds for its peer: a chunked message is charged to the reader's
//! holdings before its assembly is allocated, a refused charge skips the message with the
//! reason while the stream goes on, and a message begun and never finished ends the read
//! once its time is up.

mod support;

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::ring::{Holdings, Message, Oversized, Reader, RingError, Writer};
use support::heap_ring;

/// Holdings that grant up to `cap` bytes and record every charge.
#[derive(Clone)]
struct Ledger {
    cap: usize,
    charges: Arc<Mutex<Vec<usize>>>,
}

impl Holdings for Ledger {
    fn hold(&mut self, bytes: usize) -> Result<(), String> {
        if bytes > self.cap {
            return Err(format!("{bytes} bytes exceed the ledger's {}", self.cap));
        }
        self.charges.lock().expect("ledger").push(bytes);
        Ok(())
    }
}

fn message(len: usize, seed: u8) -> Vec<u8> {
    (0..len).map(|i| (i as u8).wrapping_mul(31).wrapping_add(seed)).collect()
}

#[test]
fn a_chunked_message_is_charged_before_it_is_assembled_and_refused_when_it_cannot_be() {
    let (ring, _) = heap_ring(1 << 14);
    let reader_ring = ring.clone();
    let producer = std::thread::spawn(move || {
        let mut w = Writer::new(ring, 4096);
        for (len, seed) in [(50_000usize, 1u8), (200_000, 2), (300, 3)] {
            let msg = message(len, seed);
            w.write::<RingError>(len, &|| true, |buf| {
                buf.copy_from_slice(&msg);
                Ok(())
            })
            .expect("write");
        }
        w.publish();
    });
    let ledger = Ledger { cap: 100_000, charges: Arc::default() };
    let mut r = Reader::new(reader_ring, 1 << 20).with_holdings(Box::new(ledger.clone()));
    let mut seen = Vec::new();
    while seen.len() < 3 {
        let charges = ledger.charges.clone();
        r.recv_messages::<RingError>(&|| true, Oversized::Skip, |m, _| {
            // What is held while a message is delivered: charged before it was assembled.
            let held = charges.lock().expect("ledger").last().copied().unwrap_or(0);
            seen.push(match m {
                Message::Whole(b) => {
                    assert!(held >= b.len(), "{} bytes delivered with {held} charged", b.len());
                    (b.len(), None)
                }
                Message::Oversized { len, why, .. } => (len as usize, why.map(str::to_string)),
            });
            Ok(())
        })
        .expect("read");
    }
    producer.join().expect("producer");
    assert_eq!(seen[0], (50_000, None));
    let refused = Some("200000 bytes exceed the ledger's 100000".to_string());
    assert_eq!(seen[1], (200_000, refused), "skipped with the reason");
    assert_eq!(seen[2], (300, None), "the stream goes on");
    let charges = ledger.charges.lock().expect("ledger").clone();
    assert!(charges.first().is_some_and(|&c| c >= 50_000), "the first charge covers the message: {charges:?}");
}

#[test]
fn a_message_begun_and_never_finished_ends_the_read_in_time() {
    let (ring, _) = heap_ring(1 << 14);
    let reader_ring = ring.clone();
    // The peer writes all of a large message but its last chunk, then stops for good.
    let producer = std::thread::spawn(move || {
        let mut w = Writer::new(ring, 4096);
        w.write_unfinished(&[7u8; 100_000], &|| true).expect("write");
    });
    let limit = Duration::from_millis(300);
    let mut r = Reader::new(reader_ring, 1 << 20).with_partial_limit(limit);
    let start = Instant::now();
    let err = loop {
        if let Err(e) = r.recv_messages::<RingError>(&|| true, Oversized::Skip, |_, _| Ok(())) {
            break e;
        }
        assert!(start.elapsed() < Duration::from_secs(10), "the read never ended");
    };
    producer.join().expect("producer");
    let RingError::Stale { len, have, secs } = err else { panic!("{err}") };
    assert_eq!(len, 100_000);
    assert!(have > 0 && have < 100_000, "{have}");
    assert!(secs >= limit.as_secs_f64(), "{secs}");
    assert!(err.to_string().contains("not finished"), "{err}");
}

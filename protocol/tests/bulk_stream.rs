//! Blobs streamed after their message in `BULK` frames: they arrive whole and in order across
//! many wraps of a small ring, what the consumer leaves unread is skipped, and frames that
//! break the rules (bulk outside a blob, a blob cut short or overrun, a peer gone mid-blob)
//! end the read with an error, never a panic. The command set's split and decode of a
//! streamed blob round-trips.

mod support;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use strata_protocol::codec::{decode_command, encode_to_vec};
use strata_protocol::ring::{Bulk, Message, Oversized, Reader, RingError, Writer};
use strata_protocol::{Blob, Command};
use support::{heap_ring, scribbler};

/// A message announcing a blob of `len` bytes (the test's own framing: the length, LE).
fn announce(w: &mut Writer, len: u64) {
    w.write::<RingError>(8, &|| true, |buf| {
        buf.copy_from_slice(&len.to_le_bytes());
        Ok(())
    })
    .expect("write");
}

fn blob(len: usize, seed: u8) -> Vec<u8> {
    (0..len).map(|i| (i as u8).wrapping_mul(13).wrapping_add(seed) ^ (i >> 9) as u8).collect()
}

/// Reads every message until `want` are delivered, handing each (its announced length) and
/// its [`Bulk`] to `each`.
fn read_all(
    r: &mut Reader,
    want: usize,
    mut each: impl FnMut(u64, &Bulk<'_>) -> Result<(), RingError>,
) -> Result<(), RingError> {
    let mut seen = 0;
    while seen < want {
        seen += r.recv_messages::<RingError>(&|| true, Oversized::Refuse, |m, bulk| {
            let Message::Whole(bytes) = m else { panic!("no message here is oversized") };
            let len = u64::from_le_bytes(bytes.try_into().expect("an 8-byte announcement"));
            bulk.expect(len)?;
            each(len, bulk)
        })?;
    }
    Ok(())
}

#[test]
fn streamed_blobs_arrive_whole_and_in_order_across_wraps() {
    // Pieces of a quarter ring less a header: every blob spans many frames and wraps.
    let (ring, _) = heap_ring(1 << 14);
    let sizes = [0usize, 1, 4087, 4088, 4089, 65_536, 100_003, 300_000, 7];
    let writer_ring = ring.clone();
    let producer = std::thread::spawn(move || {
        let mut w = Writer::new(writer_ring, 4096);
        for (i, &len) in sizes.iter().enumerate() {
            announce(&mut w, len as u64);
            w.write_bulk(&blob(len, i as u8), &|| true).expect("stream");
        }
        w.publish();
    });
    let mut r = Reader::new(ring, 1 << 20);
    let mut i = 0;
    read_all(&mut r, sizes.len(), |len, bulk| {
        // Read in uneven parts, as an upload row by row would.
        let mut got = vec![0u8; len as usize];
        let mut at = 0;
        for part in [3usize, 5000, usize::MAX] {
            let n = part.min(got.len() - at);
            bulk.read(&mut got[at..at + n])?;
            at += n;
        }
        assert_eq!(bulk.remaining(), 0);
        assert!(got == blob(sizes[i], i as u8), "blob {i} ({len} bytes) arrived changed");
        i += 1;
        Ok(())
    })
    .expect("read");
    producer.join().expect("producer");
    assert_eq!(i, sizes.len());
}

#[test]
fn a_blob_left_unread_is_skipped_and_the_stream_goes_on() {
    let (ring, _) = heap_ring(1 << 14);
    let writer_ring = ring.clone();
    let producer = std::thread::spawn(move || {
        let mut w = Writer::new(writer_ring, 4096);
        for (i, len) in [50_000usize, 20_000, 9].into_iter().enumerate() {
            announce(&mut w, len as u64);
            w.write_bulk(&blob(len, i as u8), &|| true).expect("stream");
        }
        w.publish();
    });
    let mut r = Reader::new(ring, 1 << 20);
    let mut i = 0;
    read_all(&mut r, 3, |len, bulk| {
        match i {
            // Not read at all.
            0 => {}
            // Read in part.
            1 => bulk.read(&mut [0u8; 100])?,
            _ => {
                let mut got = vec![0u8; len as usize];
                bulk.read(&mut got)?;
                assert_eq!(got, blob(9, 2), "the blob after two skipped ones arrived changed");
            }
        }
        i += 1;
        Ok(())
    })
    .expect("read");
    producer.join().expect("producer");
}

/// Runs a reader over what `write` produces; returns its error.
fn violation(write: impl FnOnce(&mut Writer), messages: usize) -> RingError {
    violation_mid(write, messages).0
}

/// [`violation`], and whether the reader then says it was in the middle of a message.
fn violation_mid(write: impl FnOnce(&mut Writer), messages: usize) -> (RingError, bool) {
    let (ring, _) = heap_ring(1 << 14);
    let mut w = Writer::new(ring.clone(), 4096);
    write(&mut w);
    w.publish();
    let mut r = Reader::new(ring, 1 << 20);
    let gone = Arc::new(AtomicBool::new(false));
    let mut seen = 0;
    loop {
        let alive = || !gone.load(Ordering::Relaxed);
        let res = r.recv_messages::<RingError>(&alive, Oversized::Refuse, |m, bulk| {
            let Message::Whole(bytes) = m else { panic!("no message here is oversized") };
            let len = u64::from_le_bytes(bytes.try_into().expect("an 8-byte announcement"));
            bulk.expect(len)?;
            let mut got = vec![0u8; len as usize];
            // The writer is done: a wait for more means the peer is gone.
            gone.store(true, Ordering::Relaxed);
            bulk.read(&mut got)
        });
        match res {
            Ok(n) => {
                seen += n;
                assert!(seen < messages, "every message was delivered without an error");
            }
            Err(e) => return (e, r.mid_message()),
        }
    }
}

#[test]
fn bulk_frames_outside_a_blob_are_refused() {
    let e = violation(|w| w.write_bulk(&[1, 2, 3], &|| true).expect("stream"), 1);
    assert!(matches!(e, RingError::BadChunk(m) if m.contains("outside")), "{e}");
}

#[test]
fn a_blob_cut_short_is_refused() {
    let e = violation(
        |w| {
            announce(w, 10_000);
            w.write_bulk(&blob(6_000, 0), &|| true).expect("stream");
            // The next message where the blob's last bytes should be.
            announce(w, 0);
        },
        2,
    );
    assert!(matches!(e, RingError::BadChunk(m) if m.contains("ended before")), "{e}");
}

#[test]
fn a_blob_overrun_is_refused() {
    let e = violation(
        |w| {
            announce(w, 100);
            w.write_bulk(&blob(3_000, 0), &|| true).expect("stream");
        },
        1,
    );
    assert!(matches!(e, RingError::BadChunk(m) if m.contains("exceed")), "{e}");
}

#[test]
fn a_peer_gone_mid_blob_ends_the_read() {
    let (e, mid) = violation_mid(
        |w| {
            announce(w, 10_000);
            w.write_bulk(&blob(5_000, 0), &|| true).expect("stream");
        },
        1,
    );
    assert!(matches!(e, RingError::PeerGone), "{e}");
    // As a peer gone between a chunked message's chunks: the session says so.
    assert!(mid, "a peer gone mid-blob is not reported as gone in the middle of a command");
}

#[test]
fn a_command_splits_its_large_blob_off_and_decodes_it_as_streamed() {
    let data = blob(100_000, 5);
    let cmd = Command::BufferData { target: 0x8892, size: 100_000, data: Some(Blob::borrowed(&data)), usage: 0x88E4 };
    assert!(cmd.split_bulk(100_001).is_none(), "a blob under the threshold stays inline");
    let (head, bytes) = cmd.split_bulk(65_536).expect("split");
    assert_eq!(bytes, &data[..]);
    let wire = encode_to_vec(&head).expect("encode");
    assert!(wire.len() < 32, "the streamed blob's bytes stayed in the message ({} bytes)", wire.len());
    let mut decoded = decode_command(&wire).expect("decode");
    let Command::BufferData { size, usage, .. } = &decoded else { panic!("not the command written") };
    assert_eq!((*size, *usage), (100_000, 0x88E4), "the fields around the blob changed");
    let streamed = decoded.bulk_mut().expect("a streamed blob");
    assert_eq!((streamed.streamed_len(), streamed.as_bytes()), (Some(100_000), &[][..]));
    // Inline blobs round-trip as bytes.
    let small = Command::BufferSubData { target: 0x8892, offset: 4, data: Blob::borrowed(&data[..300]) };
    let wire = encode_to_vec(&small).expect("encode");
    let mut back = decode_command(&wire).expect("decode");
    assert!(back.bulk_mut().is_none());
    assert_eq!(back, small);
}

/// A peer that scribbles over the ring (headers too) while blobs stream: the reader never
/// panics, reads nothing outside the frames it checked, and ends with an error or with every
/// blob delivered at its announced length.
#[test]
fn a_racing_writer_over_streamed_blobs_never_breaks_the_reader() {
    use rand::{Rng, SeedableRng};
    use std::sync::atomic::AtomicUsize;
    const CAPACITY: u32 = 1 << 14;
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let (mut ended, mut blobs) = (0usize, 0usize);
    for _ in 0..200 {
        let (ring, peer) = heap_ring(CAPACITY);
        let mut w = Writer::new(ring.clone(), CAPACITY);
        // Written before the race (the writer's slices are not atomic), within the writer's
        // lead (half this ring, less the frames' headers): no reader runs yet to make room.
        let len = rng.random_range(1..(CAPACITY as usize / 2 - 256));
        announce(&mut w, len as u64);
        w.write_bulk(&blob(len, 1), &|| true).expect("stream");
        w.publish();
        let stop = Arc::new(AtomicBool::new(false));
        let strokes = Arc::new(AtomicUsize::new(0));
        let racer = scribbler(peer, rng.random(), stop.clone(), strokes.clone(), |_| true);
        // Let the peer strike before the reader starts, too.
        while strokes.load(Ordering::Relaxed) < 4 {
            std::hint::spin_loop();
        }
        let mut r = Reader::new(ring, 1 << 20);
        let result = r.recv_messages::<RingError>(&|| false, Oversized::Refuse, |m, bulk| {
            let Message::Whole(bytes) = m else { return Ok(()) };
            let Ok(announced) = <[u8; 8]>::try_from(bytes) else { return Ok(()) };
            let announced = u64::from_le_bytes(announced);
            if announced > CAPACITY as u64 {
                return Ok(());
            }
            bulk.expect(announced)?;
            let mut got = vec![0u8; announced as usize];
            bulk.read(&mut got)?;
            blobs += 1;
            Ok(())
        });
        stop.store(true, Ordering::Relaxed);
        racer.join().expect("racer");
        if result.is_err() {
            ended += 1;
        }
    }
    assert!(ended > 0, "no scribbled frame ended a stream");
    assert!(blobs > 0, "no blob was read through the race");
}

//! `stratad ctl watch`: a control connection turned into a stream of events, one JSON line
//! each, with every surface's frame statistics once a second. The daemon never waits for a
//! watcher: events reach it through a broadcast channel that drops what a slow receiver has
//! not taken, and a watcher that falls behind, or does not take a line within
//! `WRITE_TIMEOUT`, is told so where it can be and dropped.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use strata_protocol::events::Event;
use strata_protocol::handshake::ControlReply;
use tokio::io::{AsyncReadExt, AsyncWriteExt, BufReader};
use tokio::net::unix::{OwnedReadHalf, OwnedWriteHalf};
use tokio::sync::broadcast::error::RecvError;
use tracing::{debug, warn};

use super::shared::Shared;

/// Longest a watcher may leave a line unread before it is dropped.
const WRITE_TIMEOUT: Duration = Duration::from_secs(1);

/// How often frame statistics are sent.
const FRAMES_EVERY: Duration = Duration::from_secs(1);

/// Sends `e` as a line, within `WRITE_TIMEOUT`; false if the watcher is gone or too slow.
async fn send(wr: &mut OwnedWriteHalf, e: Event, id: u64) -> bool {
    let Ok(line) = strata_protocol::json_control::line(&ControlReply::Event(e)) else { return false };
    match tokio::time::timeout(WRITE_TIMEOUT, wr.write_all(&line)).await {
        Ok(Ok(())) => true,
        Ok(Err(e)) => {
            debug!(control = id, "watcher gone: {e}");
            false
        }
        Err(_) => {
            warn!(control = id, "dropped a watcher that left its events unread for {WRITE_TIMEOUT:?}");
            false
        }
    }
}

/// Streams events to the watcher until it closes, falls behind or stops reading.
pub(super) async fn watch(mut rd: BufReader<OwnedReadHalf>, mut wr: OwnedWriteHalf, shared: &Arc<Shared>, id: u64) {
    let mut events = shared.scene.subscribe();
    let mut tick = tokio::time::interval(FRAMES_EVERY);
    tick.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    // Each surface's (frames, shown, misses) at the last tick.
    let mut last: HashMap<u64, [u64; 3]> = HashMap::new();
    let mut at = Instant::now();
    let mut scratch = [0u8; 256];
    loop {
        tokio::select! {
            e = events.recv() => match e {
                Ok(e) => if !send(&mut wr, e, id).await { return },
                Err(RecvError::Lagged(missed)) => {
                    warn!(control = id, missed, "dropped a watcher that fell behind by {missed} events");
                    let _ = send(&mut wr, Event::Dropped { missed }, id).await;
                    return;
                }
                Err(RecvError::Closed) => return,
            },
            _ = tick.tick() => {
                let now = Instant::now();
                let secs = now.duration_since(at).as_secs_f64().max(1e-3);
                at = now;
                let rows = shared.scene.rows();
                let mut seen = HashMap::with_capacity(rows.len());
                for r in rows {
                    let now = [r.frames, r.shown, r.deadline_misses];
                    // A surface seen for the first time reports from its start.
                    let before = last.get(&r.id).copied().unwrap_or_default();
                    seen.insert(r.id, now);
                    let frames = now[0].saturating_sub(before[0]);
                    let e = Event::Frames {
                        surface: r.id,
                        frames,
                        shown: now[1].saturating_sub(before[1]).min(frames),
                        deadline_misses: now[2].saturating_sub(before[2]),
                        fps: frames as f64 / secs,
                    };
                    if !send(&mut wr, e, id).await {
                        return;
                    }
                }
                last = seen;
            },
            // The watcher sends nothing more; it closing ends the stream.
            r = rd.read(&mut scratch) => if !matches!(r, Ok(n) if n > 0) { return },
        }
    }
}

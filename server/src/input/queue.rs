//! One client's queue of input events on their way to its socket. The daemon never waits for
//! a client: events are queued here and a task of the client's connection writes them out.
//! Consecutive motion of one point over one surface is merged into the newest; presses,
//! releases, keys and text are never dropped. A client that lets [`MAX_QUEUED`] events pile up
//! (its socket full, reading none) is disconnected.

use std::collections::VecDeque;
use std::sync::Mutex;

use strata_protocol::input::InputEvent;

/// Most events a client's queue holds (beyond what its socket's buffer took) before the
/// client is disconnected.
pub const MAX_QUEUED: usize = 1024;

/// A client's pending input events.
#[derive(Debug, Default)]
pub struct EventQueue {
    state: Mutex<State>,
    ready: tokio::sync::Notify,
    /// Told once, when the queue overflows.
    overflow: tokio::sync::Notify,
}

#[derive(Debug, Default)]
struct State {
    events: VecDeque<InputEvent>,
    /// The queue overflowed: the client is disconnected and nothing more is queued.
    overflowed: bool,
    /// Motion events merged into a newer one.
    merged: u64,
}

/// The queue is full: the client reads none of its events.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the client read none of its last {MAX_QUEUED} input events")]
pub struct Overflow;

impl EventQueue {
    /// Queues `e` (merged into the last event where both are motion of the same point);
    /// `Overflow` once [`MAX_QUEUED`] events wait, after which the queue takes nothing more.
    pub fn push(&self, e: InputEvent) -> Result<(), Overflow> {
        let Ok(mut s) = self.state.lock() else { return Err(Overflow) };
        if s.overflowed {
            return Err(Overflow);
        }
        let merges = s.events.back().is_some_and(|last| last.merges_with(&e));
        if merges {
            if let Some(last) = s.events.back_mut() {
                *last = e;
            }
            s.merged += 1;
        } else if s.events.len() >= MAX_QUEUED {
            s.overflowed = true;
            s.events.clear();
            drop(s);
            self.ready.notify_one();
            self.overflow.notify_one();
            return Err(Overflow);
        } else {
            s.events.push_back(e);
        }
        drop(s);
        self.ready.notify_one();
        Ok(())
    }

    /// The next event to write, waiting for one; `Err(Overflow)` once the queue overflowed.
    pub async fn next(&self) -> Result<InputEvent, Overflow> {
        loop {
            let notified = self.ready.notified();
            {
                let Ok(mut s) = self.state.lock() else { return Err(Overflow) };
                if s.overflowed {
                    return Err(Overflow);
                }
                if let Some(e) = s.events.pop_front() {
                    return Ok(e);
                }
            }
            notified.await;
        }
    }

    /// Returns once the queue has overflowed (while the connection may be stuck writing to
    /// a client that reads nothing).
    pub async fn overflowed(&self) {
        loop {
            let told = self.overflow.notified();
            if self.state.lock().map_or(true, |s| s.overflowed) {
                return;
            }
            told.await;
        }
    }

    /// Events waiting.
    pub fn len(&self) -> usize {
        self.state.lock().map_or(0, |s| s.events.len())
    }

    /// Whether none waits.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Motion events merged into newer ones so far.
    pub fn merged(&self) -> u64 {
        self.state.lock().map_or(0, |s| s.merged)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use strata_protocol::input::{Device, Phase};

    fn point(phase: Phase, x: f32) -> InputEvent {
        InputEvent::Point { surface: 7, device: Device::Touch, id: 0, phase, x, y: 0.0 }
    }

    #[test]
    fn motion_merges_and_presses_are_kept_until_the_limit() {
        let q = EventQueue::default();
        q.push(point(Phase::Down, 0.0)).expect("room");
        for i in 0..100 {
            q.push(point(Phase::Motion, i as f32)).expect("room");
        }
        q.push(point(Phase::Up, 99.0)).expect("room");
        assert_eq!((q.len(), q.merged()), (3, 99));
        let rt = tokio::runtime::Builder::new_current_thread().build().expect("runtime");
        assert_eq!(rt.block_on(q.next()), Ok(point(Phase::Down, 0.0)));
        assert_eq!(rt.block_on(q.next()), Ok(point(Phase::Motion, 99.0)));
        assert_eq!(rt.block_on(q.next()), Ok(point(Phase::Up, 99.0)));
        for _ in 0..MAX_QUEUED {
            q.push(point(Phase::Down, 0.0)).expect("room");
        }
        assert_eq!(q.push(point(Phase::Up, 0.0)), Err(Overflow));
        assert_eq!(q.push(point(Phase::Motion, 0.0)), Err(Overflow), "nothing more once overflowed");
        assert_eq!(rt.block_on(q.next()), Err(Overflow));
    }
}

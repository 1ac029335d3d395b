//! Pacing between the clients and the compositor thread: a swap waits while its surface has
//! K frames in flight, or for its swap interval's refreshes; the compositor thread sleeps until
//! the damage count moves, a swap waits for a refresh, or a deadline surface is watched.

use std::time::{Duration, Instant};

use tracing::warn;

use crate::state::{Scene, MAX_SWAP_WAIT};

/// What the compositor thread should do next.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Work {
    /// Something changed since the given damage count, or a swap waits for a refresh.
    Refresh,
    /// Nothing changed within the time asked for.
    Quiet,
    /// The daemon is stopping.
    Stop,
}

impl Scene {
    /// Blocks the swapping client while its surface has K frames in flight, and with a swap
    /// interval n ≥ 1 until n refreshes have passed since its previous swap.
    pub fn throttle(&self, client: u64, surface: u32) {
        let Some(mut g) = self.lock() else { return };
        let start = Instant::now();
        let mut waiting_refresh = false;
        loop {
            let root = g.root;
            let refreshes = g.refreshes;
            let Some(s) = g.surfaces.get_mut(&(client, surface)) else { break };
            if !root || s.interval == 0 {
                break;
            }
            let in_flight = s.frames - s.shown;
            let due = s.last_swap_refresh + s.interval as u64;
            if in_flight < self.frames_in_flight && refreshes >= due {
                s.last_swap_refresh = refreshes;
                break;
            }
            let left = MAX_SWAP_WAIT.saturating_sub(start.elapsed());
            if left.is_zero() {
                warn!(surface, in_flight, "the compositor did not take a frame in time; swapping without pacing");
                s.last_swap_refresh = refreshes;
                break;
            }
            if !waiting_refresh {
                waiting_refresh = true;
                g.pacing_waiters += 1;
                self.changed.notify_all();
            }
            g = match self.changed.wait_timeout(g, left) {
                Ok((g, _)) => g,
                Err(_) => return,
            };
        }
        if waiting_refresh {
            g.pacing_waiters -= 1;
        }
    }

    /// Whether a compositor thread runs (until `Root::stop`).
    pub fn root_running(&self) -> bool {
        self.lock().is_some_and(|g| g.root)
    }

    /// Marks that a compositor thread consumes frames (or, with `false`, that none does any
    /// more, which releases every waiting swap).
    pub fn set_root(&self, running: bool) {
        if let Some(mut g) = self.lock() {
            g.root = running;
        }
        self.changed.notify_all();
    }

    /// Counts one output refresh and wakes swaps waiting for it. A deadline surface whose newest frame is now older than its swap interval allows
    /// counts a miss.
    pub fn refreshed(&self) {
        if let Some(mut g) = self.lock() {
            g.refreshes += 1;
            let now = g.refreshes;
            for s in g.surfaces.values_mut().filter(|s| s.deadline && s.interval > 0) {
                if let Some((_, at)) = s.presented {
                    if now - at > s.interval as u64 {
                        s.deadline_misses += 1;
                    }
                }
            }
        }
        self.changed.notify_all();
    }

    /// For the compositor thread: waits until the damage count differs from `seen` or a swap
    /// waits for a refresh, or until the root is stopped.
    pub fn wait_for_work(&self, seen: u64, quiet: Option<Duration>) -> Work {
        let Some(mut g) = self.lock() else { return Work::Stop };
        let until = quiet.map(|q| Instant::now() + q);
        loop {
            if !g.root {
                return Work::Stop;
            }
            // A deadline surface is watched at every refresh, even when nothing changes.
            let watched = g.surfaces.values().any(|s| s.deadline && s.presented.is_some());
            if g.damage != seen || g.pacing_waiters > 0 || watched {
                return Work::Refresh;
            }
            g = match until {
                None => match self.changed.wait(g) {
                    Ok(g) => g,
                    Err(_) => return Work::Stop,
                },
                Some(until) => {
                    let Some(left) = until.checked_duration_since(Instant::now()) else { return Work::Quiet };
                    match self.changed.wait_timeout(g, left) {
                        Ok((g, _)) => g,
                        Err(_) => return Work::Stop,
                    }
                }
            };
        }
    }
}

//! Caps on what clients take at the doors: sessions in all, per user and per `[[quota]]`
//! entry; devices of their own per user; connections at the door in all, and handshakes in
//! progress per user; and the devices held back for the reserved class. A connection beyond a
//! cap is refused at the handshake with the reason, and the refusal is counted (`ctl stats`)
//! and logged at most once a second per cap. A user's connections beyond its handshakes in
//! progress wait their turn for as long as one handshake step may take, so that a burst of
//! one user's clients is served while a flood of its silent connections holds up only itself.

use std::collections::{BTreeMap, HashMap};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use strata_protocol::control::Priority;
use tracing::warn;

use crate::quota::ByteSize;

/// `stratad serve`'s caps on sessions, devices and handshakes, and the reserves of the
/// reserved class (0: no cap).
#[derive(Debug, Clone, clap::Args)]
pub struct CapArgs {
    /// Most client sessions at once.
    #[arg(long, default_value_t = 256)]
    pub max_sessions: usize,
    /// Most sessions one user (uid) holds at once; a `[[quota]]` entry's `sessions` caps its
    /// clients' sessions together.
    #[arg(long, default_value_t = 128)]
    pub max_sessions_per_uid: usize,
    /// Most devices of their own one user's sessions hold; a session beyond it is refused.
    #[arg(long, default_value_t = 0)]
    pub max_client_devices_per_uid: usize,
    /// Most connections at the door at once: in their handshake, or waiting for their turn.
    #[arg(long, default_value_t = 256)]
    pub max_handshakes: usize,
    /// Most connections of one user in their handshake at once; more wait their turn.
    #[arg(long, default_value_t = 16)]
    pub max_handshakes_per_uid: usize,
    /// The class that the reserves are for (with those more urgent): high, normal or low.
    #[arg(long, default_value = "high")]
    pub reserve_for: Priority,
    /// Of `--max-client-devices`, places only the reserved class takes; other clients beyond
    /// the rest share the compositor's device.
    #[arg(long, default_value_t = 0)]
    pub reserve_devices: usize,
    /// Of `--quota-total-gpu-bytes`, bytes that only the reserved class holds.
    #[arg(long, default_value = "0", value_parser = |s: &str| s.parse::<ByteSize>())]
    pub reserve_gpu_bytes: ByteSize,
}

impl Default for CapArgs {
    fn default() -> Self {
        CapArgs {
            max_sessions: 256,
            max_sessions_per_uid: 128,
            max_client_devices_per_uid: 0,
            max_handshakes: 256,
            max_handshakes_per_uid: 16,
            reserve_for: Priority::High,
            reserve_devices: 0,
            reserve_gpu_bytes: ByteSize(0),
        }
    }
}

/// Caps that cannot hold together.
#[derive(Debug, thiserror::Error)]
pub enum CapError {
    /// Devices reserved without a number of devices to reserve them from.
    #[error("--reserve-devices {0} needs --max-client-devices, the places it is a part of")]
    ReserveWithoutMax(usize),
    /// More devices reserved than there are.
    #[error("--reserve-devices {reserve} is more than --max-client-devices {max}")]
    ReserveAboveMax {
        /// The reserve.
        reserve: usize,
        /// The places.
        max: usize,
    },
    /// More memory reserved than there is.
    #[error("--reserve-gpu-bytes {reserve} is more than the total for all clients, {total}")]
    ReserveAboveTotal {
        /// The reserve.
        reserve: u64,
        /// The total.
        total: u64,
    },
}

impl CapArgs {
    /// Checks the reserves against `max_devices` (`--max-client-devices`) and `total_bytes`.
    pub fn check(&self, max_devices: Option<usize>, total_bytes: u64) -> Result<(), CapError> {
        match (self.reserve_devices, max_devices) {
            (0, _) => {}
            (r, None) => return Err(CapError::ReserveWithoutMax(r)),
            (reserve, Some(max)) if reserve > max => return Err(CapError::ReserveAboveMax { reserve, max }),
            _ => {}
        }
        if self.reserve_gpu_bytes.0 > total_bytes {
            return Err(CapError::ReserveAboveTotal { reserve: self.reserve_gpu_bytes.0, total: total_bytes });
        }
        Ok(())
    }

    /// Whether a client of `class` (or one whose entry says so) draws on the reserves.
    pub fn reserved(&self, class: Priority) -> bool {
        class <= self.reserve_for
    }
}

/// What a session asks for at the handshake.
#[derive(Debug, Clone)]
pub struct Ask {
    /// Its user.
    pub uid: u32,
    /// Its `[[quota]]` entry: place, `sessions` cap and how to name it.
    pub entry: Option<(usize, Option<u64>, String)>,
    /// Whether it draws on the reserves.
    pub reserved: bool,
    /// Whether it wants a device of its own.
    pub device: bool,
}

#[derive(Debug, Default)]
struct PerUid {
    sessions: usize,
    devices: usize,
    /// Connections at the door.
    handshakes: usize,
    /// Of those, in their handshake.
    active: usize,
}

#[derive(Debug, Default)]
struct Counts {
    sessions: usize,
    handshakes: usize,
    devices: usize,
    /// Devices held by sessions without access to the reserve.
    devices_unreserved: usize,
    uids: HashMap<u32, PerUid>,
    entries: HashMap<usize, usize>,
    /// Refusals by cap.
    refused: BTreeMap<&'static str, u64>,
    /// Per cap: when it was last logged, and refusals since.
    logged: HashMap<&'static str, (Instant, u64)>,
}

/// The caps in force and what is counted against them.
#[derive(Debug)]
pub struct Caps {
    args: CapArgs,
    max_devices: Option<usize>,
    counts: Mutex<Counts>,
}

/// Shortest time between two log lines about one cap's refusals.
const LOG_EVERY: Duration = Duration::from_secs(1);

/// 0 is no cap.
fn over(n: usize, cap: usize) -> bool {
    cap != 0 && n >= cap
}

impl Caps {
    /// Caps from `args`; `max_devices` is `--max-client-devices`.
    pub fn new(args: CapArgs, max_devices: Option<usize>) -> Arc<Self> {
        Arc::new(Caps { args, max_devices, counts: Mutex::default() })
    }

    /// The options.
    pub fn args(&self) -> &CapArgs {
        &self.args
    }

    fn lock(&self) -> MutexGuard<'_, Counts> {
        self.counts.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Counts a refusal by `cap`, logging it unless that cap was logged less than a second
    /// ago (the next line then gives the refusals in between).
    pub fn refuse(&self, cap: &'static str, reason: String) -> String {
        let mut c = self.lock();
        *c.refused.entry(cap).or_default() += 1;
        let now = Instant::now();
        let (last, since) = c.logged.entry(cap).or_insert((now - LOG_EVERY, 0));
        *since += 1;
        if now.duration_since(*last) >= LOG_EVERY {
            let n = std::mem::take(since);
            *last = now;
            warn!(cap, refusals = n, "connection refused: {reason} ({n} refusal(s) by this cap since the last line)");
        }
        reason
    }

    /// Counts a refusal by `cap` that is logged elsewhere (`accept`: the system refused a
    /// connection, see the doors).
    pub fn count(&self, cap: &'static str) {
        *self.lock().refused.entry(cap).or_default() += 1;
    }

    /// Refusals so far, by cap.
    pub fn refusals(&self) -> BTreeMap<String, u64> {
        self.lock().refused.iter().map(|(k, v)| ((*k).to_string(), *v)).collect()
    }

    /// Admits a connection of `uid` to the door and, once it is its turn, into its
    /// handshake; waits at most `wait` for that turn. Says which cap refuses it otherwise.
    pub async fn handshake(self: &Arc<Self>, uid: u32, wait: Duration) -> Result<Handshake, String> {
        let mut h = self.arrive(uid)?;
        let until = tokio::time::Instant::now() + wait;
        while !self.turn(&mut h) {
            if tokio::time::Instant::now() >= until {
                let cap = self.args.max_handshakes_per_uid;
                let reason =
                    format!("uid {uid} has {cap} handshakes in progress (--max-handshakes-per-uid), and no turn came");
                return Err(self.refuse("handshakes-per-uid", reason));
            }
            tokio::time::sleep(Duration::from_millis(10)).await;
        }
        Ok(h)
    }

    /// Admits a connection of `uid` to the door, unless the door holds its most.
    fn arrive(self: &Arc<Self>, uid: u32) -> Result<Handshake, String> {
        let mut c = self.lock();
        if over(c.handshakes, self.args.max_handshakes) {
            let reason = format!("{} connections are at the door (--max-handshakes)", c.handshakes);
            drop(c);
            return Err(self.refuse("handshakes", reason));
        }
        c.handshakes += 1;
        c.uids.entry(uid).or_default().handshakes += 1;
        Ok(Handshake { caps: self.clone(), uid, active: false })
    }

    /// Starts `h`'s handshake if its user has fewer than its most in progress.
    fn turn(&self, h: &mut Handshake) -> bool {
        let mut c = self.lock();
        let u = c.uids.entry(h.uid).or_default();
        if over(u.active, self.args.max_handshakes_per_uid) {
            return false;
        }
        u.active += 1;
        h.active = true;
        true
    }

    /// Admits a session, with a device place if it wants one and one is free to it (none:
    /// it shares the compositor's device), or says which cap refuses it.
    pub fn admit(self: &Arc<Self>, ask: &Ask) -> Result<(Seat, Option<DevicePlace>), String> {
        let mut c = self.lock();
        let a = &self.args;
        let mine = c.uids.get(&ask.uid).map_or((0, 0), |u| (u.sessions, u.devices));
        let entry_sessions = ask.entry.as_ref().map_or(0, |(i, _, _)| c.entries.get(i).copied().unwrap_or(0));
        let refusal = if over(mine.0, a.max_sessions_per_uid) {
            Some(("sessions-per-uid", format!("uid {} holds {} sessions (--max-sessions-per-uid)", ask.uid, mine.0)))
        } else if let Some((_, Some(cap), label)) =
            ask.entry.as_ref().filter(|(_, cap, _)| cap.is_some_and(|cap| entry_sessions as u64 >= cap))
        {
            Some(("sessions-per-entry", format!("the [[quota]] entry {label} allows {cap} sessions, all held")))
        } else if over(c.sessions, a.max_sessions) {
            Some(("sessions", format!("the daemon holds {} sessions (--max-sessions)", c.sessions)))
        } else if ask.device && over(mine.1, a.max_client_devices_per_uid) {
            Some((
                "devices-per-uid",
                format!("uid {} holds {} devices of its own (--max-client-devices-per-uid)", ask.uid, mine.1),
            ))
        } else {
            None
        };
        if let Some((cap, reason)) = refusal {
            drop(c);
            return Err(self.refuse(cap, reason));
        }
        c.sessions += 1;
        c.uids.entry(ask.uid).or_default().sessions += 1;
        if let Some((i, _, _)) = &ask.entry {
            *c.entries.entry(*i).or_default() += 1;
        }
        let seat = Seat { caps: self.clone(), uid: ask.uid, entry: ask.entry.as_ref().map(|e| e.0) };
        let place = ask.device.then(|| self.place(&mut c, ask)).flatten();
        Ok((seat, place))
    }

    fn place(self: &Arc<Self>, c: &mut Counts, ask: &Ask) -> Option<DevicePlace> {
        if let Some(max) = self.max_devices {
            let open_to_all = max.saturating_sub(self.args.reserve_devices);
            if c.devices >= max || (!ask.reserved && c.devices_unreserved >= open_to_all) {
                return None;
            }
        }
        c.devices += 1;
        if !ask.reserved {
            c.devices_unreserved += 1;
        }
        c.uids.entry(ask.uid).or_default().devices += 1;
        Some(DevicePlace { caps: self.clone(), uid: ask.uid, reserved: ask.reserved })
    }

    fn forget_uid_if_idle(c: &mut Counts, uid: u32) {
        if c.uids.get(&uid).is_some_and(|u| u.sessions == 0 && u.devices == 0 && u.handshakes == 0) {
            c.uids.remove(&uid);
        }
    }
}

/// A connection at the door (in its handshake once `active`); counted until dropped.
#[derive(Debug)]
pub struct Handshake {
    caps: Arc<Caps>,
    uid: u32,
    active: bool,
}

impl Drop for Handshake {
    fn drop(&mut self) {
        let mut c = self.caps.lock();
        c.handshakes -= 1;
        if let Some(u) = c.uids.get_mut(&self.uid) {
            u.handshakes -= 1;
            u.active -= usize::from(self.active);
        }
        Caps::forget_uid_if_idle(&mut c, self.uid);
    }
}

/// An admitted session; counted until dropped.
#[derive(Debug)]
pub struct Seat {
    caps: Arc<Caps>,
    uid: u32,
    entry: Option<usize>,
}

impl Drop for Seat {
    fn drop(&mut self) {
        let mut c = self.caps.lock();
        c.sessions -= 1;
        if let Some(u) = c.uids.get_mut(&self.uid) {
            u.sessions -= 1;
        }
        if let Some(n) = self.entry.and_then(|i| c.entries.get_mut(&i)) {
            *n -= 1;
        }
        Caps::forget_uid_if_idle(&mut c, self.uid);
    }
}

/// One of the places for clients' own devices, held while a client's device is open.
#[derive(Debug)]
pub struct DevicePlace {
    caps: Arc<Caps>,
    uid: u32,
    reserved: bool,
}

impl Drop for DevicePlace {
    fn drop(&mut self) {
        let mut c = self.caps.lock();
        c.devices -= 1;
        if !self.reserved {
            c.devices_unreserved -= 1;
        }
        if let Some(u) = c.uids.get_mut(&self.uid) {
            u.devices -= 1;
        }
        Caps::forget_uid_if_idle(&mut c, self.uid);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ask(uid: u32, reserved: bool) -> Ask {
        Ask { uid, entry: None, reserved, device: true }
    }

    #[test]
    fn sessions_are_capped_per_user_per_entry_and_in_all() {
        let args = CapArgs { max_sessions: 5, max_sessions_per_uid: 2, ..CapArgs::default() };
        let caps = Caps::new(args, None);
        let a1 = caps.admit(&ask(1, false)).expect("first");
        let _a2 = caps.admit(&ask(1, false)).expect("second");
        let e = caps.admit(&ask(1, false)).expect_err("third of uid 1");
        assert!(e.contains("uid 1 holds 2 sessions (--max-sessions-per-uid)"), "{e}");
        let _b = caps.admit(&ask(2, false)).expect("another user is not held back");
        drop(a1);
        let _a3 = caps.admit(&ask(1, false)).expect("a freed seat is taken again");
        let entry = |uid| Ask { entry: Some((0, Some(1), "for uid 3".into())), ..ask(uid, false) };
        let _c = caps.admit(&entry(3)).expect("the entry's first");
        let e = caps.admit(&entry(4)).expect_err("the entry allows one");
        assert!(e.contains("[[quota]] entry for uid 3 allows 1 sessions"), "{e}");
        let _d = caps.admit(&ask(5, false)).expect("fifth");
        let e = caps.admit(&ask(6, false)).expect_err("sixth");
        assert!(e.contains("(--max-sessions)"), "{e}");
        assert_eq!(caps.refusals().values().sum::<u64>(), 3);
    }

    #[test]
    fn reserved_devices_are_left_to_the_reserved_class_and_per_user_devices_are_capped() {
        let args = CapArgs { reserve_devices: 1, max_client_devices_per_uid: 2, ..CapArgs::default() };
        let caps = Caps::new(args, Some(3));
        let hu: Vec<_> = (0..2).map(|_| caps.admit(&ask(7, false)).expect("admitted")).collect();
        assert!(hu.iter().all(|(_, p)| p.is_some()), "two places are open to all");
        let (_other, place) = caps.admit(&ask(8, false)).expect("another user is admitted");
        assert!(place.is_none(), "it shares the compositor's device: the last place is reserved");
        let (_ic, place) = caps.admit(&ask(1, true)).expect("the IC is admitted");
        assert!(place.is_some(), "the reserved place is the IC's");
        let e = caps.admit(&ask(7, false)).expect_err("a third device of uid 7");
        assert!(e.contains("uid 7 holds 2 devices of its own (--max-client-devices-per-uid)"), "{e}");
        drop(hu);
        let (_s, p) = caps.admit(&ask(8, false)).expect("admitted");
        assert!(p.is_some(), "places come back");
    }

    #[tokio::test]
    async fn a_users_handshakes_beyond_its_most_wait_their_turn_and_the_door_is_capped() {
        let args = CapArgs { max_handshakes: 4, max_handshakes_per_uid: 2, ..CapArgs::default() };
        let caps = Caps::new(args, None);
        let wait = Duration::from_millis(300);
        let (h1, _h2) = (caps.handshake(9, wait).await.expect("1"), caps.handshake(9, wait).await.expect("2"));
        let e = caps.handshake(9, wait).await.expect_err("no turn comes for a third");
        assert!(e.contains("uid 9 has 2 handshakes in progress (--max-handshakes-per-uid)"), "{e}");
        let _other = caps.handshake(1, wait).await.expect("another user's turn is its own");
        // A third of uid 9 waits, and gets its turn when the first ends.
        let caps2 = caps.clone();
        let third = tokio::spawn(async move { caps2.handshake(9, wait).await.map(|_| ()) });
        tokio::time::sleep(Duration::from_millis(50)).await;
        let e = caps.handshake(2, wait).await.expect_err("the door holds four");
        assert!(e.contains("4 connections are at the door (--max-handshakes)"), "{e}");
        drop(h1);
        third.await.expect("task").expect("its turn came");
    }
}

//! The scene's events for `stratad ctl watch`: clients and surfaces coming and going, and
//! property changes, sent on a broadcast channel that never blocks the sender (a watcher that
//! falls behind is told so and dropped by its own task).

use strata_protocol::events::Event;
use tokio::sync::broadcast;

use crate::state::Scene;

impl Scene {
    /// A new receiver of every event from now on.
    pub fn subscribe(&self) -> broadcast::Receiver<Event> {
        self.events.subscribe()
    }

    /// Sends `e` to every watcher (none: dropped).
    pub fn emit(&self, e: Event) {
        let _ = self.events.send(e);
    }

    /// Client `client` connected, with the kernel's credentials `peer`.
    pub fn client_connected(&self, client: u64, name: &str, peer: strata_protocol::control::Peer) {
        if let Some(mut g) = self.lock() {
            g.peers.insert(client, peer);
        }
        self.emit(Event::ClientConnected { client, name: name.to_string(), pid: peer.pid });
    }

    /// Client `client`'s session ended, for `reason`.
    pub fn client_gone(&self, client: u64, name: &str, reason: String) {
        let pid = self.lock().and_then(|mut g| g.peers.remove(&client)).map_or(0, |p| p.pid);
        self.emit(Event::ClientGone { client, name: name.to_string(), pid, reason });
    }

    /// Client `client`'s credentials (all 0 where unknown).
    pub fn peer(&self, client: u64) -> strata_protocol::control::Peer {
        self.lock().and_then(|g| g.peers.get(&client).copied()).unwrap_or_default()
    }
}

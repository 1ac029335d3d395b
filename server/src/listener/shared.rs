//! What every connection's task and the daemon's threads share: the options, the scene and
//! compositor, the connected clients, the input router.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::AtomicU64;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use strata_device::Gpu;
use strata_protocol::handshake::ControlReply;
use strata_protocol::input::InputRequest;
use tokio::sync::{oneshot, watch};

use super::options::ServeOptions;

/// One request for the input routing thread: what, when it arrived, and where the answer goes.
pub(crate) type Routed = (InputRequest, Instant, Option<oneshot::Sender<ControlReply>>);

/// What the daemon knows about a connected client.
#[derive(Debug, Clone)]
pub struct ClientInfo {
    /// Name from the hello.
    pub name: String,
    /// Role from the hello.
    pub role: String,
    /// Its quota and what it holds.
    pub account: Arc<strata_device::account::Account>,
    /// Its way onto the GPU queue: class, and where its frames waited.
    pub lane: Option<Arc<strata_device::Lane>>,
    /// The device it renders on, once its session has opened it.
    pub device: Arc<std::sync::OnceLock<Arc<Gpu>>>,
    /// Input events on their way to its socket.
    pub events: Arc<crate::input::EventQueue>,
}

pub(crate) struct Shared {
    pub(crate) opts: ServeOptions,
    pub(crate) gpu: Option<Arc<Gpu>>,
    pub(crate) scene: Arc<strata_scene::Scene>,
    pub(crate) root: Option<Arc<strata_compositor::root::Root>>,
    pub(crate) next_id: AtomicU64,
    pub(crate) clients: Mutex<HashMap<u64, ClientInfo>>,
    pub(crate) pool: Arc<strata_device::account::Pool>,
    /// The daemon's own memory that sessions hold for their clients.
    pub(crate) daemon_pool: Arc<strata_device::account::Pool>,
    /// Grabs and keyboard focus.
    pub(crate) input: crate::input::Router,
    /// The input routing thread's queue.
    pub(crate) router: Mutex<Option<std::sync::mpsc::Sender<crate::listener::shared::Routed>>>,
    pub(crate) sessions: AtomicU64,
    /// Sessions, devices and handshakes counted against their caps.
    pub(crate) caps: Arc<crate::caps::Caps>,
    pub(crate) shutdown: watch::Receiver<bool>,
    /// Where the client socket is (for refusals that point there).
    pub(crate) client_path: PathBuf,
    /// Where the control socket is.
    pub(crate) control_path: PathBuf,
}

//! The daemon's front doors: claims the client and control sockets, performs each client's
//! handshake, learns who it is from the kernel, creates its segment, starts its session
//! thread, and shuts everything down on request.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use strata_protocol::control::Priority;
use strata_protocol::handshake::{self, HandshakeError, Hello, Purpose, ServerMessage};
use tokio::io::AsyncWriteExt;
use tokio::net::UnixStream;
use tokio::sync::watch;
use tracing::{debug, info, warn, Instrument};

use strata_device::Gpu;
use crate::session::SessionEnd;

mod client;
mod control;
mod doors;
mod export;
mod input;
mod watcher;

/// How long a client may take over each handshake step.
const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(5);

/// Daemon settings.
#[derive(Debug, Clone)]
pub struct ServeOptions {
    /// The client socket: where render clients connect.
    pub socket: PathBuf,
    /// The control socket (`None`: beside the client socket, `NAME-control.sock`).
    pub control_socket: Option<PathBuf>,
    /// The group the client socket is opened to (mode 0660; `None`: 0600, the daemon's user).
    pub client_group: Option<u32>,
    /// The group the control socket is opened to (mode 0660; `None`: 0600).
    pub control_group: Option<u32>,
    /// Command ring capacity per client, bytes (power of two).
    pub cmd_ring: u32,
    /// Reply ring capacity per client, bytes (power of two).
    pub reply_ring: u32,
    /// What runs each client's commands.
    pub executor: ExecutorKind,
    /// Sampled textures per compositor pass (`None`: the device's limit).
    pub max_textures: Option<u32>,
    /// How the compositor combines surfaces (3D, or the 2D baseline).
    pub compositor: strata_compositor::Mode,
    /// The colour format of chained compositor passes' intermediates.
    pub intermediate: strata_compositor::Intermediate,
    /// How surfaces' depth is stored: format and reversed-Z (`--depth-format`, `--reversed-z`).
    pub depth: strata_gles::DepthOptions,
    /// How render clients send `GL_FLOAT` client-side vertex arrays (told in the welcome).
    pub vertex_wire: strata_protocol::handshake::VertexWire,
    /// Whether the compositor leaves out surfaces under opaque nearer groups (the image is the
    /// same either way).
    pub cull: bool,
    /// Uniform lighting of composited output (initially; `stratad ctl light` changes it).
    pub lighting: strata_compositor::Lighting,
    /// The outputs the compositor draws.
    pub outputs: Vec<strata_compositor::root::OutputSpec>,
    /// Most composites per second.
    pub refresh_hz: f64,
    /// Frames a window surface may have swapped but not yet shown before its swap blocks.
    pub frames_in_flight: u32,
    /// Where clients' window surfaces go unless they say (first match by client name wins).
    pub layout: Vec<crate::layout::LayoutEntry>,
    /// Placement and properties of surfaces by stable ID (the configuration's `[[surface]]`).
    pub surfaces: Vec<crate::layout::SurfaceEntry>,
    /// Layers created at start (the configuration's `[[layer]]`).
    pub layers: Vec<crate::layout::LayerEntry>,
    /// Each client's limits, unless a quota entry names it.
    pub limits: strata_device::account::Limits,
    /// Per-client limits by client name (first match wins).
    pub quotas: Vec<crate::quota::QuotaEntry>,
    /// GPU memory all clients together may hold.
    pub total_gpu_bytes: u64,
    /// The class of clients the configuration does not name and whose contexts do not ask.
    pub default_class: Priority,
    /// Whether each client renders on a device of its own or all share the compositor's.
    pub devices: DeviceMode,
    /// How window surfaces' frames reach the compositor's device.
    pub frame_transfer: strata_gles::TransferMode,
    /// Whether devices ask for a queue global priority by class where the adapter offers it.
    pub global_priority: bool,
    /// Whether `ctl` may destroy a client's device (`ControlRequest::LoseDevice`; tests).
    pub fault_injection: bool,
    /// Rasterizer threads of each client's device on a CPU rasterizer (`None`: the driver's
    /// default).
    pub client_rasterizer_threads: Option<u32>,
    /// Most clients' devices open at once (`None`: as many as the driver opens); clients
    /// beyond it share the compositor's device.
    pub max_client_devices: Option<usize>,
    /// When the compositor draws a lower-priority change band by band between refreshes.
    pub bands: strata_compositor::root::BandOptions,
    /// Real input devices (`--input libinput`).
    pub input: crate::input::libinput::InputArgs,
}

/// Which device each client renders on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum DeviceMode {
    /// A device (and instance) of its own, created on its session thread at its class's
    /// priority; its window surfaces' frames reach the compositor's device through shared
    /// memory.
    #[default]
    PerClient,
    /// The compositor's device, one queue for everyone: no parallelism between clients and no
    /// isolation from each other's faults; a client's class only sets its session thread's
    /// CPU priority (to compare, or for a driver that cannot open a device per client).
    Shared,
}

/// The executor each client session gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ExecutorKind {
    /// The GLES 2.0 executor on the GPU (Vulkan; lavapipe without a GPU).
    #[default]
    Gles,
    /// Transport only: decode, stage bulk data, execute nothing (for transport benchmarks).
    Drain,
}

impl Default for ServeOptions {
    fn default() -> Self {
        ServeOptions {
            socket: handshake::default_socket_path(),
            control_socket: None,
            client_group: None,
            control_group: None,
            cmd_ring: 8 << 20,
            reply_ring: 1 << 20,
            executor: ExecutorKind::Gles,
            max_textures: None,
            compositor: strata_compositor::Mode::ThreeD,
            intermediate: strata_compositor::Intermediate::Rgba8,
            depth: strata_gles::DepthOptions::default(),
            vertex_wire: strata_protocol::handshake::VertexWire::Float,
            cull: true,
            lighting: strata_compositor::Lighting::default(),
            outputs: vec![strata_compositor::root::OutputSpec::default()],
            refresh_hz: 60.0,
            frames_in_flight: 2,
            layout: Vec::new(),
            surfaces: Vec::new(),
            layers: Vec::new(),
            limits: strata_device::account::Limits::default(),
            quotas: Vec::new(),
            total_gpu_bytes: strata_device::account::default_total(),
            default_class: Priority::Normal,
            devices: DeviceMode::PerClient,
            frame_transfer: strata_gles::TransferMode::Auto,
            global_priority: true,
            fault_injection: false,
            client_rasterizer_threads: Some(1),
            bands: strata_compositor::root::BandOptions::default(),
            max_client_devices: None,
            input: crate::input::libinput::InputArgs::default(),
        }
    }
}

/// Why the daemon could not serve.
#[derive(Debug, thiserror::Error)]
pub enum ServerError {
    /// Another daemon answers on the socket.
    #[error("another stratad is already serving on {0}")]
    AlreadyServing(PathBuf),
    /// Something other than a socket sits at the path.
    #[error("{0} exists and is not a socket; refusing to replace it")]
    NotASocket(PathBuf),
    /// No GPU device could be opened.
    #[error(transparent)]
    Gpu(#[from] strata_device::GpuError),
    /// The socket the service manager passed cannot be served on.
    #[error(transparent)]
    Activation(#[from] crate::systemd::ActivationError),
    /// The compositor or an output cannot run as configured.
    #[error(transparent)]
    Root(#[from] strata_compositor::root::RootError),
    /// No outputs, or two with one name.
    #[error("{0}")]
    Outputs(String),
    /// Ring sizes are unusable.
    #[error("ring capacity {0} must be a power of two between 4 KiB and 1 GiB")]
    BadRing(u32),
    /// Input devices cannot be read as configured.
    #[error(transparent)]
    Input(#[from] crate::input::libinput::LibinputError),
    /// Socket I/O failed.
    #[error("{context}: {source}")]
    Io {
        /// What was being done.
        context: String,
        /// The OS error.
        source: std::io::Error,
    },
}

fn io_err(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> ServerError {
    let context = context.into();
    move |source| ServerError::Io { context, source }
}

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

struct Shared {
    opts: ServeOptions,
    gpu: Option<Arc<Gpu>>,
    scene: Arc<strata_scene::Scene>,
    root: Option<Arc<strata_compositor::root::Root>>,
    next_id: AtomicU64,
    clients: Mutex<HashMap<u64, ClientInfo>>,
    pool: Arc<strata_device::account::Pool>,
    /// Grabs and keyboard focus.
    input: crate::input::Router,
    /// The input routing thread's queue.
    router: Mutex<Option<std::sync::mpsc::Sender<input::Routed>>>,
    sessions: AtomicU64,
    /// Clients' devices open now (for `--max-client-devices`).
    client_devices: Arc<std::sync::atomic::AtomicUsize>,
    shutdown: watch::Receiver<bool>,
    /// Where the client socket is (for refusals that point there).
    client_path: PathBuf,
    /// Where the control socket is.
    control_path: PathBuf,
}

/// Opens the compositor's device from a thread at the high class's nice value, so that the
/// driver's threads of that device inherit it (and the caller's own thread keeps its own).
fn open_compositor_device(global_priority: bool) -> Result<Arc<Gpu>, ServerError> {
    use strata_protocol::control::Priority;
    let opts = strata_device::DeviceOptions {
        priority: Priority::High,
        global_priority,
        label: "compositor",
        ..Default::default()
    };
    let opened = std::thread::Builder::new()
        .name("open-compositor".into())
        .spawn(move || {
            strata_device::set_thread_class(Priority::High);
            Gpu::open_with(opts)
        })
        .map_err(io_err("starting the thread that opens the compositor's device"))?
        .join()
        .map_err(|_| ServerError::Outputs("opening the compositor's device panicked".into()))?;
    Ok(opened?)
}

/// Raises this process's soft limit on open files to its hard limit: every client's device
/// holds descriptors of its own (a GPU driver's device files, shared images), so the common
/// soft limit of 1024 would refuse clients long before memory or quotas do.
fn raise_open_file_limit() {
    // SAFETY: getrlimit and setrlimit on this process with a valid struct.
    unsafe {
        let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        if libc::getrlimit(libc::RLIMIT_NOFILE, &mut lim) == 0 && lim.rlim_cur < lim.rlim_max {
            let old = lim.rlim_cur;
            lim.rlim_cur = lim.rlim_max;
            if libc::setrlimit(libc::RLIMIT_NOFILE, &lim) == 0 {
                debug!(from = old, to = lim.rlim_max, "open file limit raised");
            }
        }
    }
}

/// Serves clients on `opts.socket` until `shutdown` resolves, then stops every session and
/// removes the socket.
pub async fn serve(opts: ServeOptions, shutdown: impl std::future::Future<Output = ()>) -> Result<(), ServerError> {
    raise_open_file_limit();
    for cap in [opts.cmd_ring, opts.reply_ring] {
        if !cap.is_power_of_two() || !(4096..=1 << 30).contains(&cap) {
            return Err(ServerError::BadRing(cap));
        }
    }
    let gpu = match opts.executor {
        ExecutorKind::Gles => Some(open_compositor_device(opts.global_priority)?),
        ExecutorKind::Drain => None,
    };
    if opts.outputs.is_empty() {
        return Err(ServerError::Outputs("at least one output is needed".into()));
    }
    for (i, o) in opts.outputs.iter().enumerate() {
        if opts.outputs[..i].iter().any(|p| p.name == o.name) {
            return Err(ServerError::Outputs(format!("two outputs are named {:?}", o.name)));
        }
    }
    let scene = Arc::new(strata_scene::Scene::new(opts.frames_in_flight, opts.lighting));
    scene.reserve_ids(opts.layout.iter().flat_map(|e| e.id.0.iter().map(|&id| u64::from(id))));
    scene.configure(&opts.surfaces, &opts.layers);
    if let Some(gpu) = &gpu {
        scene.set_compositor(gpu.clone());
        if let Some(pick) = input::open_pick_device(&opts) {
            scene.set_pick_device(pick);
        }
    }
    let root = match &gpu {
        Some(gpu) => {
            let (outputs, m, inter) = (&opts.outputs, opts.max_textures, opts.intermediate);
            let (mode, cull) = (opts.compositor, opts.cull);
            let root = strata_compositor::root::Root::new(gpu.clone(), scene.clone(), outputs, m, mode, inter, cull)?;
            Some(Arc::new(root.with_bands(opts.bands)))
        }
        None => None,
    };
    // Socket activation: the service manager's sockets, else those at `--socket` and
    // `--control-socket`.
    let doors = doors::open(&opts)?;
    let watchdog = crate::systemd::watchdog_period()
        .map(|period| strata_compositor::root::Watchdog { period, ping: crate::systemd::watchdog_ping });
    let compositor_thread = match &root {
        Some(r) => Some(r.spawn(opts.refresh_hz, watchdog).map_err(io_err("starting the compositor thread"))?),
        None => None,
    };
    let (at, control_at) = (doors.client_path.clone(), doors.control_path.clone());
    let activated = doors.activated.0;
    let watchdog_ms = watchdog.map(|w| w.period.as_millis() as u64);
    let (stop_tx, stop_rx) = watch::channel(false);
    let (to_router, routed) = std::sync::mpsc::channel();
    let shared = Arc::new(Shared {
        gpu,
        scene,
        root,
        pool: strata_device::account::Pool::new(opts.total_gpu_bytes),
        next_id: AtomicU64::new(1),
        clients: Mutex::default(),
        input: Default::default(),
        router: Mutex::new(Some(to_router)),
        sessions: AtomicU64::new(0),
        client_devices: Arc::default(),
        shutdown: stop_rx,
        client_path: at,
        control_path: control_at,
        opts,
    });
    let window_input = shared.root.as_ref().and_then(|r| r.take_window_input());
    input::start(Arc::downgrade(&shared), routed, window_input);
    if let Err(e) = input::start_devices(&shared) {
        if let Some(r) = &shared.root {
            r.stop();
        }
        doors::close(&doors);
        return Err(e.into());
    }
    let (at, control_at) = (&shared.client_path, &shared.control_path);
    info!(socket = %at.display(), control = %control_at.display(), activated, watchdog_ms, "stratad serving");
    crate::systemd::ready(&format!("serving on {}", at.display()));
    let mut tasks = tokio::task::JoinSet::new();
    tokio::pin!(shutdown);
    loop {
        tokio::select! {
            _ = &mut shutdown => break,
            accepted = doors.client.accept() => match accepted {
                Ok((stream, _)) => {
                    let shared = shared.clone();
                    tasks.spawn(async move { handle_connection(stream, shared, doors::Door::Client).await });
                }
                Err(e) => warn!("accept failed: {e}"),
            },
            accepted = doors.control.accept() => match accepted {
                Ok((stream, _)) => {
                    let shared = shared.clone();
                    tasks.spawn(async move { handle_connection(stream, shared, doors::Door::Control).await });
                }
                Err(e) => warn!("accept on the control socket failed: {e}"),
            },
            Some(_) = tasks.join_next(), if !tasks.is_empty() => {}
        }
    }
    info!("shutting down: closing {} connection(s)", tasks.len());
    crate::systemd::stopping();
    let _ = stop_tx.send(true);
    if let Some(r) = &shared.root {
        r.stop();
    }
    while tasks.join_next().await.is_some() {}
    if let Some(t) = compositor_thread {
        let _ = tokio::task::spawn_blocking(move || t.join()).await;
    }
    // An activated socket is the service manager's: it stays for the next start.
    doors::close(&doors);
    info!("stratad stopped");
    Ok(())
}

async fn send(stream: &mut UnixStream, msg: &ServerMessage) -> Result<(), HandshakeError> {
    stream.write_all(&handshake::frame(msg)?).await?;
    Ok(())
}

async fn recv<T: serde::de::DeserializeOwned>(
    stream: &mut UnixStream,
    what: &'static str,
) -> Result<T, HandshakeError> {
    let mut prefix = [0u8; 4];
    doors::read_plain(stream, &mut prefix).await?;
    let mut body = vec![0u8; handshake::frame_len(prefix)?];
    doors::read_plain(stream, &mut body).await?;
    Ok(strata_protocol::codec::decode_owned(&body, what)?)
}

async fn timed<T>(f: impl std::future::Future<Output = Result<T, HandshakeError>>) -> Result<T, HandshakeError> {
    tokio::time::timeout(HANDSHAKE_TIMEOUT, f).await.unwrap_or_else(|_| {
        Err(HandshakeError::Io(std::io::Error::new(std::io::ErrorKind::TimedOut, "handshake timed out")))
    })
}

/// Reads the rest of the preamble (its first byte is `first`) and the hello; refusals are sent
/// to the client before the error returns.
async fn greet(stream: &mut UnixStream, first: u8) -> Result<Hello, HandshakeError> {
    let mut pre = [first, 0, 0, 0, 0, 0, 0, 0];
    let read = timed(async { Ok(doors::read_plain(stream, &mut pre[1..]).await?) }).await;
    let checked = read.and_then(|()| handshake::check_preamble(pre));
    let hello = match checked {
        Ok(()) => timed(recv::<Hello>(stream, "hello")).await,
        Err(e) => Err(e),
    };
    if let Err(e) = &hello {
        if !matches!(e, HandshakeError::Io(io) if io.kind() != std::io::ErrorKind::InvalidData) {
            let _ = send(stream, &ServerMessage::Refused { reason: e.to_string() }).await;
        }
    }
    hello
}

/// Reads a connection's first byte (refusing descriptors sent with it).
async fn first_byte(stream: &UnixStream) -> Result<u8, HandshakeError> {
    let mut first = [0u8; 1];
    timed(async { Ok(doors::read_plain(stream, &mut first).await?) }).await?;
    Ok(first[0])
}

/// The kernel's credentials of the process that connected.
fn peer_of(stream: &UnixStream) -> std::io::Result<strata_protocol::control::Peer> {
    let c = stream.peer_cred()?;
    Ok(strata_protocol::control::Peer {
        pid: c.pid().map_or(0, |p| p.unsigned_abs()),
        uid: c.uid(),
        gid: c.gid(),
        unverified: false,
    })
}

async fn handle_connection(mut stream: UnixStream, shared: Arc<Shared>, door: doors::Door) {
    let id = shared.next_id.fetch_add(1, Ordering::Relaxed);
    let mut peer = match peer_of(&stream) {
        Ok(p) => p,
        Err(e) => {
            warn!(client = id, "refused: the kernel gave no credentials for the connection: {e}");
            return;
        }
    };
    let first = match first_byte(&stream).await {
        Ok(b) => b,
        Err(HandshakeError::Io(e)) if e.kind() == std::io::ErrorKind::InvalidData => {
            warn!(client = id, pid = peer.pid, uid = peer.uid, "refused: {e}");
            let _ = send(&mut stream, &ServerMessage::Refused { reason: e.to_string() }).await;
            return;
        }
        Err(e) => {
            debug!(client = id, "connection closed before it said anything: {e}");
            return;
        }
    };
    // A control client speaks JSON lines, whose first byte no preamble starts with; each kind
    // of client has a socket of its own.
    match (door, first == b'{') {
        (doors::Door::Control, true) => return control::serve_json(stream, &shared, id, peer).await,
        (doors::Door::Client, true) => {
            let reason = format!(
                "control requests are refused on the client socket; stratad ctl and controllers use the control \
                 socket {}",
                shared.control_path.display()
            );
            warn!(client = id, pid = peer.pid, uid = peer.uid, "refused a control request on the client socket");
            return control::refuse(stream, reason).await;
        }
        (doors::Door::Control, false) => {
            let reason = format!(
                "this is the control socket, which speaks JSON lines (docs/control.md); render clients connect to \
                 the client socket {}",
                shared.client_path.display()
            );
            debug!(client = id, "refused a render handshake on the control socket");
            let _ = send(&mut stream, &ServerMessage::Refused { reason }).await;
            return;
        }
        (doors::Door::Client, false) => {}
    }
    let hello = match greet(&mut stream, first).await {
        Ok(h) => h,
        Err(HandshakeError::Io(e)) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            debug!(client = id, "connection closed before the handshake finished");
            return;
        }
        Err(e) => {
            warn!(client = id, pid = peer.pid, uid = peer.uid, "handshake refused: {e}");
            return;
        }
    };
    if hello.purpose == Purpose::Control {
        let reason = "control connections speak JSON lines on the control socket (docs/control.md)".to_string();
        let _ = send(&mut stream, &ServerMessage::Refused { reason }).await;
        return;
    }
    let identity = crate::identity::identify(&shared.opts.layout, &shared.opts.quotas, &hello.name, &peer);
    if let Some((section, req)) = identity.refused {
        peer.unverified = true;
        warn!(
            client = id,
            name = %hello.name,
            pid = peer.pid,
            uid = peer.uid,
            gid = peer.gid,
            "claims the name of a {section} entry that requires {req}: treated as unnamed (no entry's placement, \
             class, deadline, projection, surface IDs or quota)"
        );
    }
    let span =
        tracing::info_span!("client", id, uid = peer.uid, pid = peer.pid, name = %hello.name, role = %hello.role);
    shared.scene.client_connected(id, &hello.name, peer);
    let run = client::run_client(&mut stream, &shared, id, &hello, identity);
    let reason = match run.instrument(span.clone()).await {
        Ok(end) => {
            match end {
                SessionEnd::Violation(_) | SessionEnd::Failed(_) => span.in_scope(|| warn!("disconnected: {end}")),
                _ => span.in_scope(|| info!("{end}")),
            }
            end.to_string()
        }
        Err(e) => {
            span.in_scope(|| warn!("session setup failed: {e}"));
            format!("session setup failed: {e}")
        }
    };
    shared.scene.client_gone(id, &hello.name, reason);
    shared.clients.lock().map(|mut c| c.remove(&id)).ok();
}

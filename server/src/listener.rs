//! The daemon's front door: claims the Unix socket, performs each client's handshake, creates
//! its segment, starts its session thread, and shuts everything down on request.

use std::collections::HashMap;
use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use strata_protocol::codec::MAX_MESSAGE_LEN;
use strata_protocol::handshake::{
    self, ClientMessage, ControlReply, ControlRequest, HandshakeError, Hello, Purpose, ServerMessage,
};
use strata_protocol::ring::{Reader, Writer};
use strata_protocol::segment::{Segment, SegmentError};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::{UnixListener, UnixStream};
use tokio::sync::{oneshot, watch};
use tracing::{debug, info, warn, Instrument};

use crate::executor::Drain;
use crate::gles::GlesExecutor;
use crate::gpu::Gpu;
use crate::session::{Session, SessionEnd};

/// How long a client may take over each handshake step.
const HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(5);

/// Daemon settings.
#[derive(Debug, Clone)]
pub struct ServeOptions {
    /// Socket path to listen on.
    pub socket: PathBuf,
    /// Command ring capacity per client, bytes (power of two).
    pub cmd_ring: u32,
    /// Reply ring capacity per client, bytes (power of two).
    pub reply_ring: u32,
    /// What runs each client's commands.
    pub executor: ExecutorKind,
    /// Sampled textures per compositor pass (`None`: the device's limit).
    pub max_textures: Option<u32>,
    /// How the compositor combines surfaces (3D, or the 2D baseline).
    pub compositor: crate::compositor::Mode,
    /// The colour format of chained compositor passes' intermediates.
    pub intermediate: crate::compositor::Intermediate,
    /// How surfaces' depth is stored: format and reversed-Z (`--depth-format`, `--reversed-z`).
    pub depth: crate::gles::DepthOptions,
    /// How render clients send `GL_FLOAT` client-side vertex arrays (told in the welcome).
    pub vertex_wire: strata_protocol::handshake::VertexWire,
    /// Whether the compositor leaves out surfaces under opaque nearer groups (the image is the
    /// same either way).
    pub cull: bool,
    /// Uniform lighting of composited output (initially; `stratad ctl light` changes it).
    pub lighting: crate::compositor::Lighting,
    /// The outputs the compositor draws.
    pub outputs: Vec<crate::root::OutputSpec>,
    /// Most composites per second.
    pub refresh_hz: f64,
    /// Frames a window surface may have swapped but not yet shown before its swap blocks.
    pub frames_in_flight: u32,
    /// Where clients' window surfaces go unless they say (first match by client name wins).
    pub layout: Vec<crate::layout::LayoutEntry>,
    /// Each client's limits, unless a quota entry names it.
    pub limits: crate::quota::Limits,
    /// Per-client limits by client name (first match wins).
    pub quotas: Vec<crate::quota::QuotaEntry>,
    /// GPU memory all clients together may hold.
    pub total_gpu_bytes: u64,
    /// How clients' work is scheduled on the queue (its period is the refresh period).
    pub schedule: crate::schedule::Policy,
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
            cmd_ring: 8 << 20,
            reply_ring: 1 << 20,
            executor: ExecutorKind::Gles,
            max_textures: None,
            compositor: crate::compositor::Mode::ThreeD,
            intermediate: crate::compositor::Intermediate::Rgba8,
            depth: crate::gles::DepthOptions::default(),
            vertex_wire: strata_protocol::handshake::VertexWire::Float,
            cull: true,
            lighting: crate::compositor::Lighting::default(),
            outputs: vec![crate::root::OutputSpec::default()],
            refresh_hz: 60.0,
            frames_in_flight: 2,
            layout: Vec::new(),
            limits: crate::quota::Limits::default(),
            quotas: Vec::new(),
            total_gpu_bytes: crate::quota::default_total(),
            schedule: crate::schedule::Policy::default(),
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
    Gpu(#[from] crate::gpu::GpuError),
    /// The compositor or an output cannot run as configured.
    #[error(transparent)]
    Root(#[from] crate::root::RootError),
    /// No outputs, or two with one name.
    #[error("{0}")]
    Outputs(String),
    /// Ring sizes are unusable.
    #[error("ring capacity {0} must be a power of two between 4 KiB and 1 GiB")]
    BadRing(u32),
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

/// Claims `path`: refuses a live socket, replaces a stale one.
fn claim_socket(path: &Path) -> Result<UnixListener, ServerError> {
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if !meta.file_type().is_socket() {
            return Err(ServerError::NotASocket(path.into()));
        }
        if std::os::unix::net::UnixStream::connect(path).is_ok() {
            return Err(ServerError::AlreadyServing(path.into()));
        }
        info!(socket = %path.display(), "replacing stale socket");
        std::fs::remove_file(path).map_err(io_err(format!("removing stale socket {}", path.display())))?;
    }
    let listener = UnixListener::bind(path).map_err(io_err(format!("binding {}", path.display())))?;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o600))
        .map_err(io_err(format!("restricting {}", path.display())))?;
    Ok(listener)
}

/// What the daemon knows about a connected client.
#[derive(Debug, Clone)]
pub struct ClientInfo {
    /// Name from the hello.
    pub name: String,
    /// Role from the hello.
    pub role: String,
    /// Its quota and what it holds.
    pub account: Arc<crate::quota::Account>,
    /// Its way onto the GPU queue: class, and where its frames waited.
    pub lane: Option<Arc<crate::schedule::Lane>>,
}

struct Shared {
    opts: ServeOptions,
    gpu: Option<Arc<Gpu>>,
    scene: Arc<crate::scene::Scene>,
    root: Option<Arc<crate::root::Root>>,
    next_id: AtomicU64,
    clients: Mutex<HashMap<u64, ClientInfo>>,
    pool: Arc<crate::quota::Pool>,
    sessions: AtomicU64,
    shutdown: watch::Receiver<bool>,
}

/// Serves clients on `opts.socket` until `shutdown` resolves, then stops every session and
/// removes the socket.
pub async fn serve(opts: ServeOptions, shutdown: impl std::future::Future<Output = ()>) -> Result<(), ServerError> {
    for cap in [opts.cmd_ring, opts.reply_ring] {
        if !cap.is_power_of_two() || !(4096..=1 << 30).contains(&cap) {
            return Err(ServerError::BadRing(cap));
        }
    }
    let gpu = match opts.executor {
        ExecutorKind::Gles => Some(Gpu::open()?),
        ExecutorKind::Drain => None,
    };
    if let Some(gpu) = &gpu {
        let period = std::time::Duration::from_secs_f64(1.0 / opts.refresh_hz.clamp(1.0, 1000.0));
        gpu.scheduler.configure(crate::schedule::Policy { period, ..opts.schedule });
    }
    if opts.outputs.is_empty() {
        return Err(ServerError::Outputs("at least one output is needed".into()));
    }
    for (i, o) in opts.outputs.iter().enumerate() {
        if opts.outputs[..i].iter().any(|p| p.name == o.name) {
            return Err(ServerError::Outputs(format!("two outputs are named {:?}", o.name)));
        }
    }
    let scene = Arc::new(crate::scene::Scene::new(opts.frames_in_flight, opts.lighting));
    let root = match &gpu {
        Some(gpu) => {
            let (outputs, m, inter) = (&opts.outputs, opts.max_textures, opts.intermediate);
            let (mode, cull) = (opts.compositor, opts.cull);
            Some(Arc::new(crate::root::Root::new(gpu.clone(), scene.clone(), outputs, m, mode, inter, cull)?))
        }
        None => None,
    };
    let listener = claim_socket(&opts.socket)?;
    let compositor_thread = match &root {
        Some(r) => Some(r.spawn(opts.refresh_hz).map_err(io_err("starting the compositor thread"))?),
        None => None,
    };
    info!(socket = %opts.socket.display(), "stratad serving");
    let (stop_tx, stop_rx) = watch::channel(false);
    let shared = Arc::new(Shared {
        gpu,
        scene,
        root,
        pool: crate::quota::Pool::new(opts.total_gpu_bytes),
        next_id: AtomicU64::new(1),
        clients: Mutex::default(),
        sessions: AtomicU64::new(0),
        shutdown: stop_rx,
        opts,
    });
    let mut tasks = tokio::task::JoinSet::new();
    tokio::pin!(shutdown);
    loop {
        tokio::select! {
            _ = &mut shutdown => break,
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => {
                    let shared = shared.clone();
                    tasks.spawn(async move { handle_connection(stream, shared).await });
                }
                Err(e) => warn!("accept failed: {e}"),
            },
            Some(_) = tasks.join_next(), if !tasks.is_empty() => {}
        }
    }
    info!("shutting down: closing {} connection(s)", tasks.len());
    let _ = stop_tx.send(true);
    if let Some(r) = &shared.root {
        r.stop();
    }
    while tasks.join_next().await.is_some() {}
    if let Some(t) = compositor_thread {
        let _ = tokio::task::spawn_blocking(move || t.join()).await;
    }
    let _ = std::fs::remove_file(&shared.opts.socket);
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
    stream.read_exact(&mut prefix).await?;
    let mut body = vec![0u8; handshake::frame_len(prefix)?];
    stream.read_exact(&mut body).await?;
    Ok(strata_protocol::codec::decode_owned(&body, what)?)
}

async fn timed<T>(f: impl std::future::Future<Output = Result<T, HandshakeError>>) -> Result<T, HandshakeError> {
    tokio::time::timeout(HANDSHAKE_TIMEOUT, f).await.unwrap_or_else(|_| {
        Err(HandshakeError::Io(std::io::Error::new(std::io::ErrorKind::TimedOut, "handshake timed out")))
    })
}

/// Reads the preamble and hello; refusals are sent to the client before the error returns.
async fn greet(stream: &mut UnixStream) -> Result<Hello, HandshakeError> {
    let mut pre = [0u8; 8];
    timed(async { Ok(stream.read_exact(&mut pre).await?) }).await?;
    if let Err(e) = handshake::check_preamble(pre) {
        let _ = send(stream, &ServerMessage::Refused { reason: e.to_string() }).await;
        return Err(e);
    }
    timed(recv::<Hello>(stream, "hello")).await
}

async fn handle_connection(mut stream: UnixStream, shared: Arc<Shared>) {
    let id = shared.next_id.fetch_add(1, Ordering::Relaxed);
    let hello = match greet(&mut stream).await {
        Ok(h) => h,
        Err(HandshakeError::Io(e)) if e.kind() == std::io::ErrorKind::UnexpectedEof => {
            debug!(client = id, "connection closed before the handshake finished");
            return;
        }
        Err(e) => {
            warn!(client = id, "handshake refused: {e}");
            return;
        }
    };
    if hello.purpose == Purpose::Control {
        if let Err(e) = serve_control(&mut stream, &shared).await {
            debug!(client = id, "control connection ended: {e}");
        }
        return;
    }
    let span = tracing::info_span!("client", id, name = %hello.name, role = %hello.role);
    match run_client(&mut stream, &shared, id, &hello).instrument(span.clone()).await {
        Ok(end) => match end {
            SessionEnd::Violation(_) => span.in_scope(|| warn!("disconnected: {end}")),
            _ => span.in_scope(|| info!("{end}")),
        },
        Err(e) => span.in_scope(|| warn!("session setup failed: {e}")),
    }
    shared.clients.lock().map(|mut c| c.remove(&id)).ok();
}

/// Answers `stratad ctl` requests until the connection closes.
async fn serve_control(stream: &mut UnixStream, shared: &Arc<Shared>) -> Result<(), HandshakeError> {
    send(stream, &ServerMessage::ControlReady).await?;
    loop {
        let req: ControlRequest = recv(stream, "control request").await?;
        let shared2 = shared.clone();
        let reply = tokio::task::spawn_blocking(move || control(&shared2, req))
            .await
            .unwrap_or_else(|e| ControlReply::Error(format!("control request failed: {e}")));
        stream.write_all(&handshake::frame_limited(&reply, handshake::MAX_CONTROL_REPLY)?).await?;
    }
}

fn control(shared: &Shared, req: ControlRequest) -> ControlReply {
    match req {
        ControlRequest::List => ControlReply::List {
            outputs: shared.root.as_ref().map(|r| r.rows()).unwrap_or_default(),
            surfaces: shared.scene.rows(),
        },
        ControlRequest::Stats => ControlReply::Stats(crate::stats::collect(
            shared.gpu.as_deref(),
            &shared.pool,
            shared.sessions.load(Ordering::Relaxed),
            &shared.clients.lock().map(|c| c.clone()).unwrap_or_default(),
            &shared.scene,
        )),
        ControlRequest::Screenshot { output } => {
            let Some(root) = &shared.root else {
                return ControlReply::Error("this daemon runs without a GPU, so it has no outputs".into());
            };
            match root.screenshot(&output) {
                Ok((width, height, rgba)) => ControlReply::Image { width, height, rgba: strata_protocol::Bytes(rgba) },
                Err(e) => ControlReply::Error(e),
            }
        }
        ControlRequest::Move { surface, x, y, z } => {
            if !z.is_finite() {
                return ControlReply::Error(format!("z {z} is not a finite number"));
            }
            match shared.scene.move_surface(surface, x, y, z) {
                Some(row) => {
                    info!(surface, x, y, z, "surface moved");
                    ControlReply::Moved(row)
                }
                None => ControlReply::Error(format!("no surface {surface}; `stratad ctl list` shows them")),
            }
        }
        ControlRequest::Normal { surface, normal } => {
            if !normal.iter().all(|v| v.is_finite()) || normal.iter().all(|v| *v == 0.0) {
                return ControlReply::Error(format!("normal {normal:?} must be finite and not zero"));
            }
            match shared.scene.set_normal(surface, normal) {
                Some(row) => {
                    info!(surface, ?normal, "surface normal set");
                    ControlReply::Moved(row)
                }
                None => ControlReply::Error(format!("no surface {surface}; `stratad ctl list` shows them")),
            }
        }
        ControlRequest::Light(change) => match change.validate() {
            Ok(()) => {
                let light = shared.scene.change_lighting(&change);
                if change != Default::default() {
                    info!(?light, "lighting changed");
                }
                ControlReply::Light(light)
            }
            Err(e) => ControlReply::Error(e),
        },
    }
}

/// Returns the allocator's free pages to the system (glibc keeps them in its heaps otherwise).
fn release_free_memory() {
    #[cfg(target_env = "gnu")]
    // SAFETY: malloc_trim only releases free memory; it is safe to call from any thread.
    unsafe {
        libc::malloc_trim(0);
    }
}

#[derive(Debug, thiserror::Error)]
enum SetupError {
    #[error(transparent)]
    Handshake(#[from] HandshakeError),
    #[error(transparent)]
    Segment(#[from] SegmentError),
    #[error("starting the session thread: {0}")]
    Thread(std::io::Error),
}

async fn run_client(
    stream: &mut UnixStream,
    shared: &Shared,
    id: u64,
    hello: &Hello,
) -> Result<SessionEnd, SetupError> {
    let opts = &shared.opts;
    let limits = crate::quota::limits_for(opts.limits, &opts.quotas, &hello.name);
    let account = crate::quota::Account::new(&hello.name, limits, shared.pool.clone());
    let mut segment = Segment::create(opts.cmd_ring, opts.reply_ring)?;
    let welcome = ServerMessage::Welcome {
        client_id: id,
        segment: segment.name().to_string(),
        cmd_capacity: opts.cmd_ring,
        reply_capacity: opts.reply_ring,
        vertex_wire: opts.vertex_wire,
    };
    timed(send(stream, &welcome)).await?;
    let mapped: ClientMessage = timed(recv(stream, "mapped")).await?;
    let ClientMessage::Mapped = mapped;
    segment.unlink()?;
    let cmd_ring = segment.command_ring()?;
    let reply_ring = segment.reply_ring()?;
    let waker = cmd_ring.clone();
    let closed = Arc::new(AtomicBool::new(false));
    let mut lane = None;
    let session = Session::new(
        // Larger commands are skipped unread and refused (see `Session::with_account`).
        Reader::new(cmd_ring, usize::try_from(limits.command_bytes).unwrap_or(MAX_MESSAGE_LEN).min(MAX_MESSAGE_LEN)),
        Writer::new(reply_ring, 0),
        hello.tally,
        match &shared.gpu {
            Some(gpu) => {
                let entry = crate::layout::find(&opts.layout, &hello.name);
                // A placement the client states wins over the daemon's layout; the class,
                // deadline and projection always come from the daemon's entry.
                let layout = if hello.placement.is_some() { None } else { entry };
                if let Some(l) = layout {
                    info!(x = l.x, y = l.y, z = l.z, "window surfaces placed by the daemon's layout");
                }
                let fixed = entry.and_then(|e| e.priority);
                let class = fixed.unwrap_or(opts.schedule.default_class);
                let deadline = entry.is_some_and(|e| e.deadline);
                shared.scene.set_policy(id, class, deadline);
                if fixed.is_some() || deadline {
                    info!(priority = class.name(), deadline, "scheduled by the daemon's configuration");
                }
                let projection = entry.and_then(|e| e.projection);
                if let Some(p) = projection {
                    info!(projection = %p, "window surfaces' projection set by the daemon's configuration");
                }
                let executor = GlesExecutor::new(gpu.clone())
                    .with_scene(shared.scene.clone(), id, &hello.name)
                    .with_layout(layout.cloned())
                    .with_account(account.clone())
                    .with_priority(class, fixed.is_some(), deadline)
                    .with_projection(projection)
                    .with_depth(opts.depth);
                lane = Some(executor.lane());
                Box::new(executor) as Box<dyn crate::executor::Executor>
            }
            None => Box::new(Drain::default()),
        },
        closed.clone(),
    )
    .with_byte_counter(shared.scene.stream_counter(id))
    .with_account(account.clone());
    let thread_lane = lane.clone();
    let info = ClientInfo { name: hello.name.clone(), role: hello.role.clone(), account, lane };
    shared.clients.lock().map(|mut c| c.insert(id, info)).ok();
    shared.sessions.fetch_add(1, Ordering::Relaxed);
    info!(segment = segment.name(), "client connected");
    let (done_tx, mut done_rx) = oneshot::channel();
    let span = tracing::Span::current();
    std::thread::Builder::new()
        .name(format!("session-{id}"))
        .spawn(move || {
            // Everything the session logs (GPU errors included) carries the client's identity.
            let _span = span.enter();
            let _keep = segment;
            if let Some(lane) = thread_lane.filter(|l| l.class() == strata_protocol::control::Priority::Low) {
                lane.lower_thread();
            }
            let ended = session.run();
            // The session and everything its client held are freed by now: give the pages
            // back, so that clients coming and going leave the daemon's memory where it was.
            release_free_memory();
            let _ = done_tx.send(ended);
        })
        .map_err(|e| {
            shared.scene.forget_stream(id);
            SetupError::Thread(e)
        })?;

    let mut shutdown = shared.shutdown.clone();
    let mut buf = [0u8; 64];
    let mut socket_open = true;
    let mut forced: Option<SessionEnd> = None;
    loop {
        tokio::select! {
            done = &mut done_rx => {
                let (end, stats) = done.unwrap_or((SessionEnd::Violation("session thread panicked".into()), Default::default()));
                info!(commands = stats.commands, bytes = stats.bytes, "session ended");
                shared.scene.forget_stream(id);
                return Ok(forced.unwrap_or(end));
            }
            read = stream.read(&mut buf), if socket_open => {
                socket_open = false;
                if let Ok(n @ 1..) = read {
                    forced = Some(SessionEnd::Violation(format!("{n} unexpected bytes on the control socket")));
                }
                closed.store(true, Ordering::Release);
                waker.wake_reader();
                waker.wake_writer();
            }
            _ = shutdown.changed() => {
                closed.store(true, Ordering::Release);
                waker.wake_reader();
                waker.wake_writer();
            }
        }
    }
}

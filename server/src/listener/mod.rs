//! The daemon's front doors: claims the client and control sockets, performs each client's
//! handshake, learns who it is from the kernel, creates its segment, starts its session
//! thread, and shuts everything down on request.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use strata_protocol::handshake::{HandshakeError, Purpose, ServerMessage};
use tokio::net::UnixStream;
use tokio::sync::watch;
use tracing::{debug, info, warn, Instrument};

use crate::session::SessionEnd;
use strata_device::Gpu;

mod client;
mod control;
mod doors;
mod export;
mod greeting;
mod input;
mod options;
pub(crate) mod shared;
mod watcher;

pub use options::{DeviceMode, ExecutorKind, ServeOptions, ServerError};
pub use shared::ClientInfo;

use greeting::{first_byte, greet, peer_of, send, shown};
use options::io_err;
use shared::Shared;

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
    opts.caps.check(opts.max_client_devices, opts.total_gpu_bytes)?;
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
    scene.reserve_ids(reserved_ids(&opts));
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
        pool: strata_device::account::Pool::with_reserve(opts.total_gpu_bytes, opts.caps.reserve_gpu_bytes.0),
        daemon_pool: strata_device::account::Pool::daemon(opts.total_daemon_bytes),
        next_id: AtomicU64::new(1),
        clients: Mutex::default(),
        input: Default::default(),
        router: Mutex::new(Some(to_router)),
        sessions: AtomicU64::new(0),
        caps: crate::caps::Caps::new(opts.caps.clone(), opts.max_client_devices),
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
    let (mut client_refusals, mut control_refusals) = (doors::Refusals::default(), doors::Refusals::default());
    loop {
        let (client_wake, control_wake) = (client_refusals.reopens_at(), control_refusals.reopens_at());
        tokio::select! {
            _ = &mut shutdown => break,
            accepted = doors.client.accept(), if client_refusals.open() => match accepted {
                Ok((stream, _)) => {
                    let shared = shared.clone();
                    tasks.spawn(async move { handle_connection(stream, shared, doors::Door::Client).await });
                }
                Err(e) => {
                    client_refusals.failed("client", &e);
                    shared.caps.count("accept");
                }
            },
            accepted = doors.control.accept(), if control_refusals.open() => match accepted {
                Ok((stream, _)) => {
                    let shared = shared.clone();
                    tasks.spawn(async move { handle_connection(stream, shared, doors::Door::Control).await });
                }
                Err(e) => {
                    control_refusals.failed("control", &e);
                    shared.caps.count("accept");
                }
            },
            () = tokio::time::sleep_until(client_wake), if !client_refusals.open() => client_refusals.reopen(),
            () = tokio::time::sleep_until(control_wake), if !control_refusals.open() => control_refusals.reopen(),
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

/// The stable IDs the configuration names, each with the claim of an entry that requires
/// credentials for it: the layout's, and `[[surface]]` entries' that require credentials.
fn reserved_ids(opts: &ServeOptions) -> Vec<(u64, Option<(String, strata_protocol::control::Requirement)>)> {
    use crate::identity::Entry;
    let layout = opts.layout.iter().flat_map(|e| {
        let claim = e.requirement().any().then(|| (format!("[[layout]] {}", e.label()), e.requirement()));
        e.id.0.iter().map(move |&id| (u64::from(id), claim.clone()))
    });
    let surfaces = opts.surfaces.iter().filter(|s| s.requirement().any());
    layout.chain(surfaces.map(|s| (s.id, Some((format!("[[surface]] {}", s.id), s.requirement()))))).collect()
}

/// Admits a session of `peer` with `identity` against the caps (the refusal's reason if not):
/// its class as the daemon's configuration fixes it, whether it draws on the reserves, and
/// a device place if it is to have a device of its own and one is free to it.
fn admit(
    shared: &Shared,
    peer: &strata_protocol::control::Peer,
    identity: &crate::identity::Identity<'_>,
    handshake: Option<crate::caps::Handshake>,
) -> Result<client::Admission, String> {
    use crate::identity::Entry;
    let opts = &shared.opts;
    let class = identity.layout.and_then(|e| e.priority).unwrap_or(opts.default_class);
    let by_entry = identity.quota.is_some_and(|(_, q)| q.reserve == Some(true));
    let reserved = by_entry || shared.caps.args().reserved(class);
    let ask = crate::caps::Ask {
        uid: peer.uid,
        entry: identity.quota.map(|(i, q)| (i, q.sessions, q.label())),
        reserved,
        device: opts.executor == options::ExecutorKind::Gles && opts.devices == options::DeviceMode::PerClient,
    };
    let (seat, place) = shared.caps.admit(&ask)?;
    Ok(client::Admission { seat, place, reserved, class, handshake })
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
    // A user's connections in their handshake are capped, so that a flood of half-open ones
    // from one user leaves the others' doors open.
    let handshake = match door {
        doors::Door::Client => match shared.caps.handshake(peer.uid, greeting::HANDSHAKE_TIMEOUT).await {
            Ok(h) => Some(h),
            Err(reason) => {
                let _ = send(&mut stream, &ServerMessage::Refused { reason }).await;
                return;
            }
        },
        doors::Door::Control => None,
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
            name = %shown(&hello.name),
            pid = peer.pid,
            uid = peer.uid,
            gid = peer.gid,
            "claims the name of a {section} entry that requires {req}: treated as unnamed (no entry's placement, \
             class, deadline, projection, surface IDs or quota)"
        );
    }
    let span = tracing::info_span!("client", id, uid = peer.uid, pid = peer.pid, name = %shown(&hello.name), role = %shown(&hello.role));
    let admitted = admit(&shared, &peer, &identity, handshake);
    let admission = match admitted {
        Ok(a) => a,
        Err(reason) => {
            let _ = send(&mut stream, &ServerMessage::Refused { reason }).await;
            return;
        }
    };
    shared.scene.client_connected(id, &hello.name, peer);
    let run = client::run_client(&mut stream, &shared, id, &hello, identity, admission);
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

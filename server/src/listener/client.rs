//! One render client's session: its segment, its executor (built on its session thread, with a
//! device of its own opened there at its class's priority) and the session thread itself.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use strata_protocol::codec::MAX_MESSAGE_LEN;
use strata_protocol::control::Priority;
use strata_protocol::handshake::{self, ClientMessage, HandshakeError, Hello, ServerMessage};
use strata_protocol::ring::{Reader, Writer};
use strata_protocol::segment::{Segment, SegmentError};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::UnixStream;
use tokio::sync::oneshot;
use tracing::{info, warn};

use super::greeting::{recv, timed};
use super::options::DeviceMode;
use super::shared::{ClientInfo, Shared};
use crate::drain::Drain;
use crate::session::{Session, SessionEnd};
use strata_device::Gpu;
use strata_gles::{GlesExecutor, Placement};

/// Returns the allocator's free pages to the system (glibc keeps them in its heaps otherwise).
fn release_free_memory() {
    #[cfg(target_env = "gnu")]
    // SAFETY: malloc_trim only releases free memory; it is safe to call from any thread.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// A session's chunked commands being assembled, charged to its account.
struct Assembly(strata_device::account::Reservation);

impl strata_protocol::ring::Holdings for Assembly {
    fn hold(&mut self, bytes: usize) -> Result<(), String> {
        self.0.resize(bytes as u64).map_err(|e| e.to_string())
    }
}

/// What the caps granted a session at its handshake.
pub(super) struct Admission {
    /// Its place among the sessions, held for the session's life.
    pub(super) seat: crate::caps::Seat,
    /// Its place among clients' own devices (none: it shares the compositor's device).
    pub(super) place: Option<crate::caps::DevicePlace>,
    /// Whether it draws on the reserves.
    pub(super) reserved: bool,
    /// Its class as the daemon's configuration gives it (its entry's, else the default).
    pub(super) class: Priority,
    /// Its place among handshakes in progress, given up once the client has mapped its
    /// segment.
    pub(super) handshake: Option<crate::caps::Handshake>,
}

/// What a session thread builds its GLES executor from.
struct ExecutorPlan {
    compositor: Arc<Gpu>,
    lane: Arc<strata_device::Lane>,
    layout: Option<crate::layout::LayoutEntry>,
    class: Priority,
    fixed: bool,
    deadline: bool,
    projection: Option<strata_protocol::projection::Projection>,
    /// The stable IDs the daemon's entry gives the client's window surfaces.
    surface_ids: crate::layout::SurfaceIds,
}

#[derive(Debug, thiserror::Error)]
pub(super) enum SetupError {
    #[error(transparent)]
    Handshake(#[from] HandshakeError),
    #[error(transparent)]
    Segment(#[from] SegmentError),
    #[error("starting the session thread: {0}")]
    Thread(std::io::Error),
    #[error("{0}")]
    Held(String),
}

/// Sends the welcome with the segment's memory file attached.
async fn welcome(stream: &mut UnixStream, msg: &ServerMessage, segment: &Segment) -> Result<(), HandshakeError> {
    let fd = segment.fd().ok_or_else(|| std::io::Error::other("the segment's memory file is already closed"))?;
    super::doors::write_with_fd(stream, &handshake::frame(msg)?, fd).await?;
    Ok(())
}

pub(super) async fn run_client(
    stream: &mut UnixStream,
    shared: &Shared,
    id: u64,
    hello: &Hello,
    identity: crate::identity::Identity<'_>,
    admission: Admission,
) -> Result<SessionEnd, SetupError> {
    let opts = &shared.opts;
    let limits = identity.limits(opts.limits);
    let Admission { seat: _seat, place, reserved, class, handshake } = admission;
    let pools = (shared.pool.clone(), shared.daemon_pool.clone());
    let account = strata_device::account::Account::new(&hello.name, limits, pools, reserved);
    // The segment, and the private copy of a frame the reader makes, are charged before they
    // are made.
    let segment_bytes = 2 * u64::from(opts.cmd_ring) + u64::from(opts.reply_ring);
    let charged = account.hold(segment_bytes).and_then(|segment| Ok((segment, account.hold(0)?)));
    let (segment_held, assembly_held) = match charged {
        Ok(held) => held,
        Err(e) => {
            let reason = format!("its segment of {segment_bytes} bytes cannot be held: {e}");
            let _ = super::greeting::send(stream, &ServerMessage::Refused { reason: reason.clone() }).await;
            return Err(SetupError::Held(reason));
        }
    };
    let mut segment = Segment::create(opts.cmd_ring, opts.reply_ring)?;
    let msg = ServerMessage::Welcome {
        client_id: id,
        cmd_capacity: opts.cmd_ring,
        reply_capacity: opts.reply_ring,
        vertex_wire: opts.vertex_wire,
    };
    timed(welcome(stream, &msg, &segment)).await?;
    let mapped: ClientMessage = timed(recv(stream, "mapped")).await?;
    let ClientMessage::Mapped = mapped;
    drop(handshake);
    // The client has its own descriptor and mapping now; the daemon keeps only its mapping.
    segment.close_fd();
    let cmd_ring = segment.command_ring()?;
    let reply_ring = segment.reply_ring()?;
    let waker = cmd_ring.clone();
    let closed = Arc::new(AtomicBool::new(false));
    let closed_for_thread = closed.clone();
    let reader =
        // Larger commands are skipped unread and refused (see `Session::with_account`).
        Reader::new(cmd_ring, usize::try_from(limits.command_bytes).unwrap_or(MAX_MESSAGE_LEN).min(MAX_MESSAGE_LEN))
            .with_holdings(Box::new(Assembly(assembly_held)))
            .with_partial_limit(opts.command_time);
    let writer = Writer::new(reply_ring, 0);
    let device = Arc::new(std::sync::OnceLock::new());
    // What the session thread builds its executor from.
    let plan = match &shared.gpu {
        Some(gpu) => {
            let entry = identity.layout;
            // A placement the client states wins over the daemon's layout, unless the entry
            // fixes it; the class, deadline, projection and surface IDs always come from the
            // daemon's entry.
            let client_wins = hello.placement.is_some() && !entry.is_some_and(|e| e.fixed_placement());
            let layout = if client_wins { None } else { entry };
            if let Some(l) = layout {
                info!(x = l.x, y = l.y, z = l.z, "window surfaces placed by the daemon's layout");
            }
            // A client that claimed an entry's name without its credentials keeps the default
            // class: its context cannot ask for another.
            let fixed = entry.and_then(|e| e.priority).or(identity.refused.map(|_| opts.default_class));
            let deadline = entry.is_some_and(|e| e.deadline);
            shared.scene.set_policy(id, class, deadline);
            if fixed.is_some() || deadline {
                info!(priority = class.name(), deadline, "scheduled by the daemon's configuration");
            }
            let projection = entry.and_then(|e| e.projection);
            if let Some(p) = projection {
                info!(projection = %p, "window surfaces' projection set by the daemon's configuration");
            }
            Some(ExecutorPlan {
                compositor: gpu.clone(),
                lane: strata_device::Lane::new(class),
                layout: layout.cloned(),
                class,
                fixed: fixed.is_some(),
                deadline,
                projection,
                surface_ids: entry.map(|e| e.id.clone()).unwrap_or_default(),
            })
        }
        None => None,
    };
    let lane = plan.as_ref().map(|p| p.lane.clone());
    // The client reads its reached fences from its segment, without asking.
    if let Some(l) = &lane {
        l.publish_marks(segment.fence_word());
    }
    let events = Arc::new(crate::input::EventQueue::default());
    let info = ClientInfo {
        events: events.clone(),
        name: hello.name.clone(),
        role: hello.role.clone(),
        account: account.clone(),
        lane,
        device: device.clone(),
    };
    shared.clients.lock().map(|mut c| c.insert(id, info)).ok();
    shared.sessions.fetch_add(1, Ordering::Relaxed);
    info!("client connected");
    let (done_tx, mut done_rx) = oneshot::channel();
    let span = tracing::Span::current();
    let (scene, counter, name, tally) =
        (shared.scene.clone(), shared.scene.stream_counter(id), hello.name.clone(), hello.tally);
    let (devices, frame_transfer, depth, global_priority, es3) =
        (opts.devices, opts.frame_transfer, opts.depth, opts.global_priority, opts.es3);
    let rasterizer_threads = opts.client_rasterizer_threads;
    std::thread::Builder::new()
        .name(format!("session-{id}"))
        .spawn(move || {
            // Everything the session logs (GPU errors included) carries the client's identity.
            let _span = span.enter();
            let keep = (segment, segment_held);
            // The device's place (`--max-client-devices`) is held for the whole session.
            let (executor, _place): (Box<dyn strata_gles::execute::Executor>, _) = match plan {
                Some(p) => {
                    let class = p.class;
                    // The session's decoding, and the driver threads of a device opened here,
                    // run at the class's nice value. A low-priority device's driver threads are
                    // also in the idle class (`Gpu::open_with`); the session itself is not, as it
                    // takes the scene's lock, which the compositor waits for.
                    strata_device::set_thread_class(class);
                    let own = match devices {
                        DeviceMode::Shared => None,
                        DeviceMode::PerClient => match place {
                            None => {
                                warn!(
                                    "--max-client-devices devices are open (or all that are left are reserved): it \
                                     shares the compositor's device, without isolation"
                                );
                                None
                            }
                            Some(slot) => match Gpu::open_with(strata_device::DeviceOptions {
                                priority: class,
                                global_priority,
                                label: "client",
                                rasterizer_threads,
                            }) {
                                Ok(g) => Some((g, slot)),
                                // A driver may refuse more devices (NVIDIA opens 64 per
                                // process): the client still renders, on the compositor's.
                                Err(e) => {
                                    warn!("no device of its own ({e}): it shares the compositor's, without isolation");
                                    None
                                }
                            },
                        },
                    };
                    let (gpu, slot) = match own {
                        Some((g, slot)) => (g, Some(slot)),
                        None => (p.compositor.clone(), None),
                    };
                    let _ = device.set(gpu.clone());
                    let executor = GlesExecutor::new(gpu)
                        .with_lane(p.lane)
                        .with_scene(scene, id, &name)
                        .with_placement(p.layout.as_ref().map(|l| Placement {
                            x: l.x,
                            y: l.y,
                            z: l.z,
                            size: l.width.zip(l.height),
                        }))
                        .with_account(account.clone())
                        .with_priority(class, p.fixed, p.deadline)
                        .with_projection(p.projection)
                        .with_surface_ids(p.surface_ids.0.iter().map(|&i| u64::from(i)).collect())
                        .with_depth(depth)
                        .with_frame_transfer(frame_transfer)
                        .with_es3(es3);
                    (Box::new(executor), slot)
                }
                None => (Box::new(Drain::default()), None),
            };
            let session = Session::new(reader, writer, tally, executor, closed_for_thread)
                .with_byte_counter(counter)
                .with_account(account);
            let ended = session.run();
            // Everything the session held is given back before the daemon says it has ended.
            drop(keep);
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
    let (mut rd, mut wr) = stream.split();
    // Input events go out on the socket as they are queued; the daemon never waits for them.
    let writer = async {
        loop {
            let Ok(e) = events.next().await else { return };
            let Ok(frame) = handshake::frame(&ServerMessage::Input(e)) else { continue };
            if wr.write_all(&frame).await.is_err() {
                // The client closed: the reading side ends the session.
                return;
            }
        }
    };
    tokio::pin!(writer);
    let mut writing = true;
    loop {
        tokio::select! {
            done = &mut done_rx => {
                let (end, stats) = done.unwrap_or((SessionEnd::Violation("session thread panicked".into()), Default::default()));
                info!(commands = stats.commands, bytes = stats.bytes, "session ended");
                shared.scene.forget_stream(id);
                return Ok(forced.unwrap_or(end));
            }
            () = &mut writer, if writing => writing = false,
            () = events.overflowed(), if forced.is_none() => {
                forced = Some(SessionEnd::Failed(format!(
                    "it read none of its last {} input events",
                    crate::input::MAX_QUEUED
                )));
                closed.store(true, Ordering::Release);
                waker.wake_reader();
                waker.wake_writer();
            }
            read = rd.read(&mut buf), if socket_open => {
                socket_open = false;
                if let Ok(n @ 1..) = read {
                    forced = Some(SessionEnd::Violation(format!("{n} unexpected bytes on the client socket")));
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

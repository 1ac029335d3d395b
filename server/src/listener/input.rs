//! Input routing's thread: `ctl input` requests and the output windows' own input are routed
//! one after another on a thread at the high class's CPU priority, so that a busy machine
//! delays a tap as little as it delays the compositor.

use std::sync::mpsc;
use std::sync::{Arc, Weak};
use std::time::Instant;

use strata_protocol::handshake::ControlReply;
use strata_protocol::input::{InputOutcome, InputRequest};
use tokio::sync::oneshot;
use tracing::{debug, info, warn};

use super::shared::Shared;
use crate::input::libinput::{self, LibinputError, Source};

/// Routes an input request that arrived at `arrived`: where its events went, or why none did.
pub(super) fn route(shared: &Shared, req: &InputRequest, arrived: Instant) -> ControlReply {
    let Some(root) = &shared.root else {
        return ControlReply::Error("this daemon runs without a GPU, so it has no outputs".into());
    };
    let queued = std::cell::Cell::new(None);
    let deliver = |client: u64, e| {
        let queue = shared.clients.lock().ok().and_then(|c| c.get(&client).map(|c| c.events.clone()));
        // A full queue disconnects its client (its connection sees the overflow); the event
        // counts as delivered to it, never to another.
        queue.is_some_and(|q| {
            let _ = q.push(e);
            if queued.get().is_none() {
                queued.set(Some(arrived.elapsed().as_micros() as u64));
            }
            true
        })
    };
    let cx = crate::input::Context { root, scene: &shared.scene, deliver: &deliver };
    match shared.input.handle(&cx, req) {
        Ok(outcome) => ControlReply::Input(InputOutcome { queued_us: queued.get(), ..outcome }),
        Err(e) => ControlReply::Error(e),
    }
}

/// Hands a control connection's input request to the routing thread and waits for its answer.
pub(super) async fn ask(shared: &Arc<Shared>, req: InputRequest) -> ControlReply {
    let (tx, rx) = oneshot::channel();
    let sent = shared.router.lock().ok().and_then(|r| r.as_ref().map(|r| r.send((req, Instant::now(), Some(tx)))));
    if !matches!(sent, Some(Ok(()))) {
        return ControlReply::Error("input routing is unavailable".into());
    }
    rx.await.unwrap_or_else(|_| ControlReply::Error("input routing is unavailable".into()))
}

/// Puts the calling thread at input routing's priority: real-time at `realtime` where it may
/// (1–99), else the high class's nice value. Returns why real-time was refused, if it was.
fn set_input_priority(realtime: u8) -> Option<String> {
    use strata_protocol::control::Priority;
    if realtime > 0 {
        match strata_device::set_thread_realtime(i32::from(realtime)) {
            Ok(()) => return None,
            Err(e) => {
                strata_device::set_thread_class(Priority::High);
                return Some(e.to_string());
            }
        }
    }
    strata_device::set_thread_class(Priority::High);
    None
}

/// Opens input routing's pick device where `--input-pick own` asks and clients render on
/// devices of their own (with `--devices shared` the compositor's device holds every frame):
/// from a thread at input routing's priority, which the driver's threads inherit, with no
/// rasterizer threads of its own (a pick is one texel a surface). `None` where it is not
/// wanted or does not open (picks then read on the compositor's device).
pub(super) fn open_pick_device(opts: &super::options::ServeOptions) -> Option<Arc<strata_device::Gpu>> {
    use crate::input::libinput::PickDevice;
    if opts.input.input_pick != PickDevice::Own || opts.devices != super::options::DeviceMode::PerClient {
        return None;
    }
    let realtime = opts.input.input_realtime;
    let dev = strata_device::DeviceOptions {
        priority: strata_protocol::control::Priority::High,
        global_priority: opts.global_priority,
        label: "input",
        rasterizer_threads: Some(0),
    };
    let opened = std::thread::Builder::new().name("open-input".into()).spawn(move || {
        set_input_priority(realtime);
        strata_device::Gpu::open_with(dev)
    });
    match opened.map(|t| t.join()) {
        Ok(Ok(Ok(gpu))) => Some(gpu),
        Ok(Ok(Err(e))) => {
            warn!("input routing's device did not open ({e}); picks read on the compositor's device");
            None
        }
        _ => {
            warn!("input routing's device did not open; picks read on the compositor's device");
            None
        }
    }
}

/// Starts the routing thread for `requests`, and a thread that passes the output windows'
/// `window` input on to it; both end with the daemon.
pub(super) fn start(
    shared: Weak<Shared>,
    requests: mpsc::Receiver<crate::listener::shared::Routed>,
    window: Option<mpsc::Receiver<InputRequest>>,
) {
    let to_router = shared.upgrade().and_then(|s| s.router.lock().ok().and_then(|r| r.clone()));
    let realtime = shared.upgrade().map_or(0, |s| s.opts.input.input_realtime);
    let routing = std::thread::Builder::new().name("input".into()).spawn(move || {
        match set_input_priority(realtime) {
            Some(why) => info!(
                realtime,
                "input routing runs at the high class's priority: real-time priority was refused ({why})"
            ),
            None if realtime > 0 => debug!(realtime, "input routing runs at real-time priority"),
            None => {}
        }
        while let Ok((req, arrived, reply)) = requests.recv() {
            let Some(shared) = shared.upgrade() else { return };
            let answer = route(&shared, &req, arrived);
            match reply {
                Some(tx) => {
                    let _ = tx.send(answer);
                }
                None => {
                    if let ControlReply::Error(e) = answer {
                        debug!(output = req.output, "window input: {e}");
                    }
                }
            }
        }
    });
    if let Err(e) = routing {
        warn!("input is not routed: {e}");
    }
    let (Some(window), Some(to_router)) = (window, to_router) else { return };
    let passing = std::thread::Builder::new().name("window input".into()).spawn(move || {
        while let Ok(req) = window.recv() {
            if to_router.send((req, Instant::now(), None)).is_err() {
                return;
            }
        }
    });
    if let Err(e) = passing {
        warn!("the output windows' input is not routed: {e}");
    }
}

/// Starts reading real input devices where `--input libinput` asks, their actions routed as
/// the output windows' are; an error where they cannot be read.
pub(super) fn start_devices(shared: &Arc<Shared>) -> Result<(), LibinputError> {
    let args = &shared.opts.input;
    if args.input == Source::None {
        return Ok(());
    }
    let Some(root) = shared.root.clone() else {
        return Err(LibinputError::Output("this daemon runs without a GPU, so it has no outputs".into()));
    };
    // Outputs are fixed at start, so the devices' output keeps its size.
    let (output, r) = root.output(&args.input_output).map_err(LibinputError::Output)?;
    let to_router = shared.router.lock().ok().and_then(|r| r.clone());
    let Some(to_router) = to_router else {
        return Err(LibinputError::Thread("input routing is unavailable".into()));
    };
    let size = (r[2].max(0) as u32, r[3].max(0) as u32);
    let send =
        move |action| to_router.send((InputRequest { output: output.clone(), action }, Instant::now(), None)).is_ok();
    libinput::start(args, size, send)
}

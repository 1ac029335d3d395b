//! The control connection: JSON lines (`strata_protocol::json_control`, docs/control.md),
//! each request answered from the daemon's state; `watch` turns it into an event stream.

use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::Instant;

use strata_protocol::control::Peer;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::json_control::{self, Greeting, Opening, CONTROL_VERSION, MAX_REQUEST_LINE};
use tokio::io::{AsyncBufReadExt, AsyncReadExt, AsyncWriteExt, BufReader};
use tokio::net::unix::{OwnedReadHalf, OwnedWriteHalf};
use tokio::net::UnixStream;
use tracing::{debug, info, warn};

use super::greeting::timed;
use super::shared::Shared;

/// Reads one line into `buf` (after what it holds): its length, 0 at the end of the stream;
/// an error for a line longer than `limit`.
async fn read_line(rd: &mut BufReader<OwnedReadHalf>, buf: &mut Vec<u8>, limit: usize) -> std::io::Result<usize> {
    let n = (&mut *rd).take(limit as u64 + 1).read_until(b'\n', buf).await?;
    if buf.len() > limit {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("a control line longer than {limit} bytes"),
        ));
    }
    Ok(n)
}

/// Writes `v` as one line.
async fn write_line<T: serde::Serialize>(wr: &mut OwnedWriteHalf, v: &T) -> std::io::Result<()> {
    let line = json_control::line(v).map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e))?;
    wr.write_all(&line).await
}

/// Answers a control client that came to the wrong socket with a refusal naming `reason`,
/// after reading its opening line (so that the refusal is not lost to a reset).
pub(super) async fn refuse(stream: UnixStream, reason: String) {
    let (rd, mut wr) = stream.into_split();
    let mut buf = Vec::new();
    let _ = timed(async { Ok(read_line(&mut BufReader::new(rd), &mut buf, MAX_REQUEST_LINE).await?) }).await;
    let _ = write_line(&mut wr, &Greeting::Refused { reason }).await;
}

/// Serves a control client whose first byte, `{`, has been read: its opening, then requests
/// until it closes.
pub(super) async fn serve_json(stream: UnixStream, shared: &Arc<Shared>, id: u64, peer: Peer) {
    let (rd, mut wr) = stream.into_split();
    let mut rd = BufReader::new(rd);
    let mut buf = b"{".to_vec();
    let opened = timed(async { Ok(read_line(&mut rd, &mut buf, MAX_REQUEST_LINE).await?) }).await;
    let refuse = |reason: String| Greeting::Refused { reason };
    let name = match opened.map(|_| json_control::parse::<Opening>(&buf, "opening")) {
        Ok(Ok(Opening::Hello { version, name })) if version == CONTROL_VERSION => name,
        Ok(Ok(Opening::Hello { version, name })) => {
            let why = format!("control protocol version {version}; this daemon speaks {CONTROL_VERSION}");
            warn!(control = id, name, "refused: {why}");
            let _ = write_line(&mut wr, &refuse(why)).await;
            return;
        }
        Ok(Err(e)) => {
            warn!(control = id, "refused: {e}");
            let _ = write_line(&mut wr, &refuse(e.to_string())).await;
            return;
        }
        Err(e) => {
            debug!(control = id, "control connection ended before its opening: {e}");
            return;
        }
    };
    debug!(control = id, name, pid = peer.pid, uid = peer.uid, "control client");
    if write_line(&mut wr, &Greeting::Ready { version: CONTROL_VERSION }).await.is_err() {
        return;
    }
    loop {
        buf.clear();
        match read_line(&mut rd, &mut buf, MAX_REQUEST_LINE).await {
            Ok(0) => return,
            Ok(_) => {}
            Err(e) => {
                let _ = write_line(&mut wr, &ControlReply::Error(e.to_string())).await;
                return;
            }
        }
        if buf.iter().all(u8::is_ascii_whitespace) {
            continue;
        }
        let reply = match json_control::parse::<ControlRequest>(&buf, "control request") {
            Err(e) => ControlReply::Error(e.to_string()),
            Ok(ControlRequest::Watch) => {
                super::watcher::watch(rd, wr, shared, id).await;
                return;
            }
            Ok(ControlRequest::Input(req)) => super::input::ask(shared, req).await,
            Ok(req) => {
                let shared2 = shared.clone();
                let arrived = Instant::now();
                tokio::task::spawn_blocking(move || control(&shared2, req, arrived))
                    .await
                    .unwrap_or_else(|e| ControlReply::Error(format!("control request failed: {e}")))
            }
        };
        if write_line(&mut wr, &reply).await.is_err() {
            return;
        }
    }
}

/// Every output's rectangle in the output space.
fn outputs(shared: &Shared) -> Vec<[i32; 4]> {
    shared.root.as_ref().map(|r| r.rows().into_iter().map(|o| o.rect).collect()).unwrap_or_default()
}

/// The daemon's and its clients' resources, and the input it dropped.
fn stats(shared: &Shared) -> strata_protocol::control::DaemonStats {
    let clients = shared.clients.lock().map(|c| c.clone()).unwrap_or_default();
    let sessions = shared.sessions.load(Ordering::Relaxed);
    let s = crate::stats::collect(
        shared.gpu.as_deref(),
        (&shared.pool, &shared.daemon_pool),
        sessions,
        &clients,
        &shared.scene,
    );
    let pick_reads = shared.root.as_ref().map_or([0; 2], |r| r.pick_reads());
    let refused = shared.caps.refusals();
    strata_protocol::control::DaemonStats { input_dropped: shared.input.dropped(), pick_reads, refused, ..s }
}

/// Every output, with its keyboard focus.
fn output_rows(shared: &Shared) -> Vec<strata_protocol::control::OutputRow> {
    let focus = shared.input.focus();
    let mut rows = shared.root.as_ref().map(|r| r.rows()).unwrap_or_default();
    for o in &mut rows {
        o.focus = focus.get(&o.name).copied();
    }
    rows
}

/// Every output, surface and layer.
fn list(shared: &Shared) -> ControlReply {
    ControlReply::List {
        outputs: output_rows(shared),
        surfaces: shared.scene.rows(),
        layers: shared.scene.layers(),
        damage: shared.scene.damage(),
    }
}

/// Answers one request, which arrived at `arrived`.
fn control(shared: &Shared, req: ControlRequest, arrived: Instant) -> ControlReply {
    match req {
        ControlRequest::List => list(shared),
        ControlRequest::Apply { changes } => match shared.scene.apply(&changes) {
            Ok(()) => {
                info!(changes = changes.len(), "properties changed");
                list(shared)
            }
            Err(e) => ControlReply::Error(e.to_string()),
        },
        ControlRequest::Stats => ControlReply::Stats(stats(shared)),
        ControlRequest::Screenshot { output } => {
            let Some(root) = &shared.root else {
                return ControlReply::Error("this daemon runs without a GPU, so it has no outputs".into());
            };
            match root.screenshot(&output) {
                Ok((width, height, rgba)) => ControlReply::Image { width, height, rgba: strata_protocol::Bytes(rgba) },
                Err(e) => ControlReply::Error(e),
            }
        }
        ControlRequest::SurfaceScreenshot { surface } => {
            let Some(root) = &shared.root else {
                return ControlReply::Error("this daemon runs without a GPU, so it has no surfaces".into());
            };
            match root.surface_screenshot(surface) {
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
        ControlRequest::LoseDevice { client } => {
            if !shared.opts.fault_injection {
                return ControlReply::Error(
                    "losing a device is a fault injection for tests: start the daemon with --allow-fault-injection"
                        .into(),
                );
            }
            let device = shared.clients.lock().ok().and_then(|c| c.get(&client).and_then(|c| c.device.get().cloned()));
            match device {
                Some(gpu) if shared.gpu.as_ref().is_some_and(|g| Arc::ptr_eq(g, &gpu)) => ControlReply::Error(format!(
                    "client {client} renders on the compositor's device, which is not lost alone"
                )),
                Some(gpu) => {
                    warn!(client, "destroying the client's device (fault injection)");
                    gpu.device.destroy();
                    ControlReply::Stats(stats(shared))
                }
                None => {
                    ControlReply::Error(format!("no client {client} with a device; `stratad ctl stats` shows them"))
                }
            }
        }
        ControlRequest::Analyze { surface } => match shared.scene.analyze(surface, &outputs(shared)) {
            Some(a) => ControlReply::Analysis(a),
            None => ControlReply::Error(format!("no surface {surface}; `stratad ctl list` shows them")),
        },
        ControlRequest::Export => ControlReply::Scene(super::export::export(shared)),
        ControlRequest::Watch => ControlReply::Error("watch is answered by the connection itself".into()),
        ControlRequest::WedgeCompositor => match (&shared.root, shared.opts.fault_injection) {
            (_, false) => ControlReply::Error(
                "wedging the compositor is a fault injection for tests: start the daemon with --allow-fault-injection"
                    .into(),
            ),
            (None, true) => ControlReply::Error("this daemon runs without a GPU, so it has no compositor".into()),
            (Some(root), true) => {
                root.wedge();
                list(shared)
            }
        },
        ControlRequest::Input(req) => super::input::route(shared, &req, arrived),
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

//! The control connection: `stratad ctl`'s requests, answered from the daemon's state.

use std::sync::atomic::Ordering;
use std::sync::Arc;

use strata_protocol::handshake::{self, ControlReply, ControlRequest, HandshakeError, ServerMessage};
use tokio::io::AsyncWriteExt;
use tokio::net::UnixStream;
use tracing::{info, warn};

use super::{recv, send, Shared};

/// Answers `stratad ctl` requests until the connection closes.
pub(super) async fn serve_control(stream: &mut UnixStream, shared: &Arc<Shared>) -> Result<(), HandshakeError> {
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

/// Every output, surface and layer.
fn list(shared: &Shared) -> ControlReply {
    ControlReply::List {
        outputs: shared.root.as_ref().map(|r| r.rows()).unwrap_or_default(),
        surfaces: shared.scene.rows(),
        layers: shared.scene.layers(),
    }
}

fn control(shared: &Shared, req: ControlRequest) -> ControlReply {
    match req {
        ControlRequest::List => list(shared),
        ControlRequest::Apply { changes } => match shared.scene.apply(&changes) {
            Ok(()) => {
                info!(changes = changes.len(), "properties changed");
                list(shared)
            }
            Err(e) => ControlReply::Error(e.to_string()),
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
                    ControlReply::Stats(crate::stats::collect(
                        shared.gpu.as_deref(),
                        &shared.pool,
                        shared.sessions.load(Ordering::Relaxed),
                        &shared.clients.lock().map(|c| c.clone()).unwrap_or_default(),
                        &shared.scene,
                    ))
                }
                None => {
                    ControlReply::Error(format!("no client {client} with a device; `stratad ctl stats` shows them"))
                }
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

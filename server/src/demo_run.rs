//! `stratad demo`: a daemon and two built-in client processes, whose composited output is
//! written as a PNG (and, for the planes scene, checked against the f64 line).

use std::process::Stdio;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use strata_client::ControlConnection;
use strata_protocol::handshake::{control_socket_for, ControlReply, ControlRequest};

use crate::args::{Projections, Scene};
use crate::png::save_png;

/// Runs the demo: `frames` per client, the screenshot written to `out`.
pub(crate) fn demo(
    frames: u32,
    out: &std::path::Path,
    scene: Scene,
    projections: Projections,
    daemon_args: &[String],
) -> Result<()> {
    let dir = std::env::temp_dir().join(format!("strata-demo-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let socket = dir.join("strata.sock");
    let exe = std::env::current_exe()?;
    let mut daemon = std::process::Command::new(&exe)
        .args(["serve", "--output"])
        .arg(format!("demo={}x{}", strata_server::demo::OUTPUT.0, strata_server::demo::OUTPUT.1))
        .arg("--socket")
        .arg(&socket)
        // The planes are compared by colour: unlit.
        .args(if scene == Scene::Planes { &["--lighting", "off"][..] } else { &[] })
        .args(daemon_args)
        .spawn()
        .context("starting the daemon")?;
    let deadline = Instant::now() + std::time::Duration::from_secs(20);
    while std::os::unix::net::UnixStream::connect(&socket).is_err() {
        if Instant::now() > deadline || daemon.try_wait()?.is_some() {
            let _ = daemon.kill();
            bail!("daemon did not start listening on {}", socket.display());
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let result = (|| -> Result<()> {
        let mut clients = Vec::new();
        let roles = if scene == Scene::Planes { ["plane-a", "plane-b"] } else { ["ic", "hu"] };
        let declare = scene == Scene::Planes && projections == Projections::Declared;
        for role in roles {
            let child = std::process::Command::new(&exe)
                .args(["demo-client", "--role", role, "--frames", &frames.to_string(), "--socket"])
                .arg(&socket)
                .args(if declare { &["--declare"][..] } else { &[] })
                .stdin(Stdio::piped())
                .stdout(Stdio::piped())
                .spawn()
                .with_context(|| format!("starting the {role} client"))?;
            clients.push(child);
        }
        for c in &mut clients {
            use std::io::BufRead;
            let stdout = c.stdout.take().context("client stdout")?;
            let mut line = String::new();
            std::io::BufReader::new(stdout).read_line(&mut line)?;
            if line.trim() != "ready" {
                bail!("a demo client failed before rendering its frames");
            }
        }
        let mut c = ControlConnection::connect(&control_socket_for(&socket))?;
        let reply = c.request(&ControlRequest::Screenshot { output: "demo".into() })?;
        for mut child in clients {
            drop(child.stdin.take());
            let _ = child.wait();
        }
        let (width, rgba) = match reply {
            ControlReply::Image { width, height, rgba } => {
                save_png(out, width, height, rgba.0.clone())?;
                (width, rgba.0)
            }
            ControlReply::Error(e) => bail!("screenshot failed: {e}"),
            other => bail!("unexpected reply {other:?}"),
        };
        if scene == Scene::Planes {
            use strata_server::demo::planes;
            let found: Vec<u32> = planes::line_columns(&rgba, width).into_iter().flatten().collect();
            let want = planes::expected_column();
            let mean = found.iter().map(|&c| f64::from(c)).sum::<f64>() / found.len().max(1) as f64;
            println!(
                "demo: two planes, near/far {}/{} and {}/{}, projections {}: their line is at column {mean:.1} of {} rows (the f64 line: column {want}): {}",
                planes::A.near,
                planes::A.far,
                planes::B.near,
                planes::B.far,
                if declare { "declared" } else { "undeclared (raw depth)" },
                found.len(),
                out.display()
            );
        } else {
            println!(
                "demo: instrument cluster and head unit at the same z, composited per fragment with uniform lighting: {}",
                out.display()
            );
        }
        Ok(())
    })();
    // SAFETY: plain kill(2) on our own child.
    unsafe { libc::kill(daemon.id() as i32, libc::SIGTERM) };
    let _ = daemon.wait();
    let _ = std::fs::remove_dir_all(&dir);
    result
}

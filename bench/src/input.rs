//! `strata-bench input`: input routing under load. A real `stratad` shows `--clients` window
//! surfaces side by side, each from a client that reads its input events; the benchmark taps
//! them through the control protocol and measures:
//!
//! - the daemon's latency from a tap's arrival to its event in the client's queue (the
//!   daemon's own `queued_us`), with every client drawing at its swap interval, against the
//!   same taps while no client draws (the baseline, same run, same daemon);
//! - the refreshes from a tap until the application's reaction (a new colour, swapped on the
//!   touch-down it received) is shown on the output: from sending the tap to the first
//!   completed composite that took the reacting frame.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{Action, InputEvent, InputRequest, Phase};

use crate::control::summary;
use crate::stratad::Stratad;

/// `strata-bench input` options.
#[derive(clap::Args)]
pub struct Args {
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
    /// Clients, each with one window surface, side by side.
    #[arg(long, default_value_t = 8)]
    clients: u32,
    /// Taps timed in each phase (idle, drawing).
    #[arg(long, default_value_t = 300)]
    taps: u32,
    /// Taps whose reaction is timed to the output.
    #[arg(long, default_value_t = 30)]
    reactions: u32,
    /// The daemon's refresh rate.
    #[arg(long, default_value_t = 60.0)]
    refresh_hz: f64,
    /// The stratad binary (default: beside this one).
    #[arg(long)]
    stratad: Option<PathBuf>,
    /// Write the JSON result here too.
    #[arg(long)]
    out: Option<PathBuf>,
    /// The daemon's `--input-pick`: `own` (input routing's own device) or `compositor`.
    #[arg(long, default_value = "own")]
    pick: String,
    /// The daemon's `--input-realtime` (0: input routing at the high class's nice value).
    #[arg(long, default_value_t = 10)]
    realtime: u8,
}

/// Tile side in output pixels.
const TILE: i32 = 96;

/// What a client thread shares with the benchmark.
#[derive(Default)]
struct Shared {
    /// Whether clients draw continuously.
    drawing: AtomicBool,
    /// Whether clients stop.
    stop: AtomicBool,
    /// Client 0's swaps so far, and the swap that carried its newest reaction.
    swaps: AtomicU64,
    reacted_at: AtomicU64,
}

/// One client: a window surface in tile `i`, drawn at swap interval 1 while `drawing`, its
/// input read between frames; client 0 changes colour on each touch-down and swaps at once.
fn client(socket: PathBuf, i: u32, shared: Arc<Shared>, ready: std::sync::mpsc::Sender<Result<()>>) {
    let run = || -> Result<()> {
        let opts = ConnectOptions { socket, name: format!("input-{i}"), ..Default::default() };
        let mut gl = Connection::connect(&opts).context("connecting")?;
        let rect = [i as i32 * TILE, 0, TILE, TILE];
        let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Window { rect, z: 0.5 })?;
        let mut shade = 0.2f32;
        let swap = |gl: &mut Connection, shade: f32| -> Result<()> {
            gl.glClearColor(shade, 0.3, 1.0 - shade, 1.0)?;
            gl.glClear(0x4000)?;
            gl.eglSwapBuffers(cur.display, cur.surface)?.map_err(|e| anyhow::anyhow!("eglSwapBuffers: {e:#x}"))?;
            if i == 0 {
                shared.swaps.fetch_add(1, Ordering::SeqCst);
            }
            Ok(())
        };
        swap(&mut gl, shade)?;
        gl.glFinish()?;
        ready.send(Ok(())).ok();
        while !shared.stop.load(Ordering::Relaxed) {
            let wait = if shared.drawing.load(Ordering::Relaxed) { Duration::ZERO } else { Duration::from_millis(5) };
            while let Some(e) = gl.next_input(wait)? {
                if let (0, InputEvent::Point { phase: Phase::Down, .. }) = (i, &e) {
                    shade = if shade > 0.5 { 0.2 } else { 0.8 };
                    swap(&mut gl, shade)?;
                    shared.reacted_at.store(shared.swaps.load(Ordering::SeqCst), Ordering::SeqCst);
                }
                if !shared.drawing.load(Ordering::Relaxed) {
                    break;
                }
            }
            if shared.drawing.load(Ordering::Relaxed) {
                swap(&mut gl, shade)?;
            }
        }
        Ok(())
    };
    if let Err(e) = run() {
        let _ = ready.send(Err(e));
    }
}

/// One tap's figures from the daemon: microseconds to the client's queue, and of those the
/// wait on the device it read on (when the pick read texels).
#[derive(Clone, Copy)]
struct Timed {
    queued_us: f64,
    device_us: Option<f64>,
}

/// Tap `k` on tile `i`, each at a point of its own within the tile (so that each reads its
/// texels afresh, unless an earlier tap of the same scene read the same); the daemon's
/// `queued_us` and `device_us`.
fn tap(c: &mut ControlConnection, i: u32, k: u32) -> Result<Timed> {
    let (dx, dy) = ((k * 7) % 64, (k * 13 / 64) % 64);
    let x = (i as i32 * TILE + 16 + dx as i32) as f32 + 0.5;
    let req = InputRequest { output: String::new(), action: Action::Tap { x, y: 16.5 + dy as f32 } };
    match c.request(&ControlRequest::Input(req))? {
        ControlReply::Input(o) => match (o.surface, o.queued_us) {
            (Some(_), Some(us)) => Ok(Timed { queued_us: us as f64, device_us: o.device_us.map(|d| d as f64) }),
            _ => bail!("a tap on tile {i} went nowhere: {o:?}"),
        },
        other => bail!("unexpected reply {other:?}"),
    }
}

/// p50, p99 and max of the taps' latency, of their device waits (taps that read texels), and
/// of the latency less the device wait.
fn figures(taps: &[Timed]) -> serde_json::Value {
    let device: Vec<f64> = taps.iter().filter_map(|t| t.device_us).collect();
    serde_json::json!({
        "queued_us": summary(taps.iter().map(|t| t.queued_us).collect()),
        "device_us": summary(device.clone()),
        "device_reads": device.len(),
        "without_device_us": summary(taps.iter().map(|t| t.queued_us - t.device_us.unwrap_or(0.0)).collect()),
    })
}

/// Client 0's surface row: frames swapped and the newest a completed composite took.
fn shown(c: &mut ControlConnection) -> Result<u64> {
    match c.request(&ControlRequest::List)? {
        ControlReply::List { surfaces, .. } => {
            surfaces.iter().find(|s| s.client == "input-0").map(|s| s.shown).context("client 0's surface")
        }
        other => bail!("unexpected reply {other:?}"),
    }
}

/// Milliseconds from a tap on client 0 to a composite taking the frame it swapped in reaction.
fn reaction(c: &mut ControlConnection, shared: &Shared) -> Result<f64> {
    let before = shared.reacted_at.load(Ordering::SeqCst);
    let t0 = Instant::now();
    tap(c, 0, 0)?;
    let limit = Duration::from_secs(5);
    let frame = loop {
        let f = shared.reacted_at.load(Ordering::SeqCst);
        if f != before {
            break f;
        }
        if t0.elapsed() > limit {
            bail!("client 0 did not react within 5 s");
        }
        std::thread::sleep(Duration::from_micros(100));
    };
    while shown(c)? < frame {
        if t0.elapsed() > limit {
            bail!("client 0's reaction did not show within 5 s");
        }
        std::thread::sleep(Duration::from_micros(200));
    }
    Ok(t0.elapsed().as_secs_f64() * 1000.0)
}

pub fn run(args: &Args) -> Result<()> {
    let exe = std::env::current_exe()?;
    let stratad = match &args.stratad {
        Some(p) => p.clone(),
        None => exe.parent().context("program directory")?.join("stratad"),
    };
    let dir = std::env::temp_dir().join(format!("strata-bench-input-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let n = args.clients.max(1);
    let output = format!("headless:main={}x{}", n as i32 * TILE, TILE);
    let hz = args.refresh_hz.to_string();
    let realtime = args.realtime.to_string();
    let daemon_args = [
        "--output",
        output.as_str(),
        "--refresh-hz",
        hz.as_str(),
        "--lighting",
        "off",
        "--input-pick",
        args.pick.as_str(),
        "--input-realtime",
        realtime.as_str(),
    ];
    let mut daemon = Stratad::start(&stratad, daemon_args, dir.join("stratad.sock"), dir.join("stratad.log"), false)?;
    let shared = Arc::new(Shared::default());
    let (ready_tx, ready) = std::sync::mpsc::channel();
    let threads: Vec<_> = (0..n)
        .map(|i| {
            let (socket, shared, ready) = (daemon.socket.clone(), shared.clone(), ready_tx.clone());
            std::thread::spawn(move || client(socket, i, shared, ready))
        })
        .collect();
    for _ in 0..n {
        ready.recv_timeout(Duration::from_secs(60)).context("a client did not start")??;
    }
    let mut c =
        ControlConnection::connect_as(&strata_protocol::handshake::control_socket_for(&daemon.socket), "strata-bench")?;
    let bar =
        if args.json { ProgressBar::hidden() } else { ProgressBar::new(u64::from(args.taps * 2 + args.reactions)) };
    bar.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}")?);
    let phase = |label: &str, c: &mut ControlConnection| -> Result<Vec<Timed>> {
        bar.set_message(label.to_string());
        (0..args.taps)
            .map(|k| {
                bar.inc(1);
                tap(c, k % n, k)
            })
            .collect()
    };
    let idle = phase("idle", &mut c)?;
    shared.drawing.store(true, Ordering::Relaxed);
    std::thread::sleep(Duration::from_millis(500));
    let loaded = phase("drawing", &mut c)?;
    bar.set_message("reactions");
    let mut reactions = Vec::new();
    for _ in 0..args.reactions {
        reactions.push(reaction(&mut c, &shared)?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    shared.stop.store(true, Ordering::Relaxed);
    for t in threads {
        let _ = t.join();
    }
    daemon.alive()?;
    drop(daemon);
    let _ = std::fs::remove_dir_all(&dir);

    let (idle_fig, loaded_fig) = (figures(&idle), figures(&loaded));
    let us = |v: &[Timed]| summary(v.iter().map(|t| t.queued_us).collect());
    let (idle_us, loaded_us) = (us(&idle), us(&loaded));
    let part = |f: &serde_json::Value, k: &str, i: usize| f[k][i].as_f64().unwrap_or(f64::NAN);
    let period = 1000.0 / args.refresh_hz;
    let react_ms = summary(reactions.clone());
    let react_refreshes = summary(reactions.iter().map(|t| t / period).collect());
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let result = serde_json::json!({
        "clients": n,
        "refresh_hz": args.refresh_hz,
        "pick": args.pick,
        "realtime": args.realtime,
        "taps": args.taps,
        "queued_us_idle": idle_us,
        "queued_us_drawing": loaded_us,
        "idle": idle_fig,
        "drawing": loaded_fig,
        "drawing_over_idle_p99": loaded_us[1] / idle_us[1].max(1e-9),
        "reaction_ms": react_ms,
        "reaction_refreshes": react_refreshes,
        "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>(),
    });
    if !args.json {
        println!(
            "{n} clients, refresh {} Hz, --input-pick {}, --input-realtime {} (p50 / p99 / max)",
            args.refresh_hz, args.pick, args.realtime
        );
        println!(
            "tap to the client's queue, {n} clients drawing: {:.0} / {:.0} / {:.0} µs; target p99 <= 1000",
            loaded_us[0], loaded_us[1], loaded_us[2]
        );
        println!(
            "  no client drawing (baseline): {:.0} / {:.0} / {:.0} µs; ratio at p99 {:.2}",
            idle_us[0],
            idle_us[1],
            idle_us[2],
            loaded_us[1] / idle_us[1].max(1e-9)
        );
        println!(
            "  of which the wait on the pick's device for the texels ({} of {} taps read any): {:.0} / {:.0} / {:.0} µs; the rest {:.0} / {:.0} / {:.0} µs",
            loaded_fig["device_reads"],
            args.taps,
            part(&loaded_fig, "device_us", 0),
            part(&loaded_fig, "device_us", 1),
            part(&loaded_fig, "device_us", 2),
            part(&loaded_fig, "without_device_us", 0),
            part(&loaded_fig, "without_device_us", 1),
            part(&loaded_fig, "without_device_us", 2),
        );
        println!(
            "tap to the reaction on the output: {:.2} / {:.2} / {:.2} refreshes ({:.1} / {:.1} / {:.1} ms)",
            react_refreshes[0], react_refreshes[1], react_refreshes[2], react_ms[0], react_ms[1], react_ms[2]
        );
        println!("load average {}", load.trim());
    }
    println!("{result}");
    if let Some(out) = &args.out {
        std::fs::write(out, result.to_string() + "\n").with_context(|| format!("writing {}", out.display()))?;
    }
    Ok(())
}

//! `strata-bench control`: the control surface under a full scene. A real `stratad` shows 64
//! window surfaces from real client processes (`control-client`, each holding several), and
//! the benchmark measures, over the JSON control protocol:
//!
//! - how many output refreshes a 10-change `ctl apply` takes to show: from sending the batch to
//!   the first completed composite whose damage count reaches the one the batch's reply gives
//!   (baseline: a 1-change apply, measured the same way in the same run);
//! - how long `ctl list --json` takes to answer: the request's round trip with 64 surfaces
//!   (baseline: the smallest request, `light show`, on the same connection), and the whole
//!   `stratad ctl list --json` process (baseline: `stratad ctl light show`).

use std::io::Write as _;
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_client::{ConnectOptions, Connection, ControlConnection};
use strata_protocol::control::LightChange;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::properties::Change;
use strata_protocol::{Calls, Slice};

use crate::stratad::Stratad;

/// `strata-bench control` options.
#[derive(clap::Args)]
pub struct Args {
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
    /// Window surfaces in all.
    #[arg(long, default_value_t = 64)]
    surfaces: u32,
    /// Client processes holding them.
    #[arg(long, default_value_t = 16)]
    clients: u32,
    /// Batches applied (each of the two sizes).
    #[arg(long, default_value_t = 40)]
    applies: u32,
    /// Requests timed (each kind).
    #[arg(long, default_value_t = 300)]
    requests: u32,
    /// `stratad ctl` processes timed (each kind).
    #[arg(long, default_value_t = 20)]
    processes: u32,
    /// The daemon's refresh rate.
    #[arg(long, default_value_t = 60.0)]
    refresh_hz: f64,
    /// The stratad binary (default: beside this one).
    #[arg(long)]
    stratad: Option<PathBuf>,
    /// Write the JSON result here too.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `strata-bench control-client` options: one client process holding several window surfaces.
#[derive(Debug, clap::Args)]
pub struct ClientArgs {
    /// The daemon's socket.
    #[arg(long)]
    socket: PathBuf,
    /// Its first surface's tile index.
    #[arg(long)]
    first: u32,
    /// Surfaces it holds.
    #[arg(long)]
    count: u32,
}

/// Tile side in output pixels, and tiles per output row.
const TILE: i32 = 64;
const COLUMNS: u32 = 16;

/// An EGL result, its error named.
fn egl<T>(r: Result<T, i32>, what: &str) -> Result<T> {
    r.map_err(|e| anyhow!("{what}: EGL error {e:#x}"))
}

/// Creates `count` window surfaces on one connection, swaps one frame into each, and keeps
/// them until its stdin closes.
pub fn client(args: &ClientArgs) -> Result<()> {
    let opts =
        ConnectOptions { socket: args.socket.clone(), name: format!("tiles-{}", args.first), ..Default::default() };
    let mut gl = Connection::connect(&opts).context("connecting")?;
    let d = gl.eglGetDisplay(0)?;
    egl(gl.eglInitialize(d)?, "eglInitialize")?;
    let want = [0x3033, 0x0004, 0x3040, 4, 0x3024, 8, 0x3023, 8, 0x3022, 8, 0x3038];
    let config =
        *egl(gl.eglChooseConfig(d, Slice::new(&want), 1)?, "eglChooseConfig")?.first().context("no EGL config")?;
    let ctx = egl(gl.eglCreateContext(d, config, 0, Slice::new(&[0x3098, 2, 0x3038]))?, "eglCreateContext")?;
    for i in args.first..args.first + args.count {
        let rect = [(i % COLUMNS) as i32 * TILE, (i / COLUMNS) as i32 * TILE, TILE, TILE];
        let z = 0.5;
        let s = egl(
            gl.eglCreateWindowSurface(d, config, 0, rect[0], rect[1], z, rect[2], rect[3], Slice::new(&[0x3038]))?,
            "eglCreateWindowSurface",
        )?;
        egl(gl.eglMakeCurrent(d, s, s, ctx)?, "eglMakeCurrent")?;
        let v = (i % 7) as f32 / 7.0;
        gl.glClearColor(v, 1.0 - v, 0.5, 1.0)?;
        gl.glClear(0x4000)?;
        egl(gl.eglSwapBuffers(d, s)?, "eglSwapBuffers")?;
    }
    gl.glFinish()?;
    println!("ready");
    std::io::stdout().flush()?;
    let _ = std::io::stdin().lines().count();
    Ok(())
}

/// p50, p99 and max of `v`, in the unit of its values.
pub(crate) fn summary(mut v: Vec<f64>) -> [f64; 3] {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v.get(((v.len().max(1) - 1) as f64 * q).round() as usize).copied().unwrap_or(0.0);
    [at(0.5), at(0.99), at(1.0)]
}

/// Every output's newest completed composite shows damage count `damage` or later.
fn shown(c: &mut ControlConnection, damage: u64) -> Result<bool> {
    match c.request(&ControlRequest::List)? {
        ControlReply::List { outputs, .. } => Ok(outputs.iter().all(|o| o.shown_damage >= damage)),
        other => bail!("unexpected reply {other:?}"),
    }
}

/// Milliseconds from sending `changes` to the output showing them.
fn apply_latency(c: &mut ControlConnection, changes: Vec<Change>) -> Result<f64> {
    let t0 = Instant::now();
    let damage = match c.request(&ControlRequest::Apply { changes })? {
        ControlReply::List { damage, .. } => damage,
        ControlReply::Error(e) => bail!("apply refused: {e}"),
        other => bail!("unexpected reply {other:?}"),
    };
    while !shown(c, damage)? {
        if t0.elapsed() > Duration::from_secs(5) {
            bail!("a batch did not show within 5 s");
        }
        std::thread::sleep(Duration::from_micros(200));
    }
    Ok(t0.elapsed().as_secs_f64() * 1000.0)
}

/// Round trips of `req`, milliseconds.
fn round_trips(c: &mut ControlConnection, req: &ControlRequest, n: u32) -> Result<Vec<f64>> {
    (0..n)
        .map(|_| {
            let t = Instant::now();
            c.request(req)?;
            Ok(t.elapsed().as_secs_f64() * 1000.0)
        })
        .collect()
}

/// Wall times of `stratad ctl ARGS --socket SOCKET` processes, milliseconds.
fn processes(stratad: &std::path::Path, socket: &std::path::Path, args: &[&str], n: u32) -> Result<Vec<f64>> {
    (0..n)
        .map(|_| {
            let t = Instant::now();
            let out = Command::new(stratad).arg("ctl").args(args).arg("--socket").arg(socket).output()?;
            if !out.status.success() {
                bail!("stratad ctl {args:?}: {}", String::from_utf8_lossy(&out.stderr));
            }
            Ok(t.elapsed().as_secs_f64() * 1000.0)
        })
        .collect()
}

pub fn run(args: &Args) -> Result<()> {
    let exe = std::env::current_exe()?;
    let stratad = match &args.stratad {
        Some(p) => p.clone(),
        None => exe.parent().context("program directory")?.join("stratad"),
    };
    let dir = std::env::temp_dir().join(format!("strata-bench-control-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let rows = args.surfaces.div_ceil(COLUMNS) as i32;
    let output = format!("headless:main={}x{}", COLUMNS as i32 * TILE, rows * TILE);
    let hz = args.refresh_hz.to_string();
    let daemon_args = ["--output", output.as_str(), "--refresh-hz", hz.as_str(), "--devices", "shared"];
    let daemon = Stratad::start(&stratad, daemon_args, dir.join("stratad.sock"), dir.join("stratad.log"), false)?;
    let per = args.surfaces.div_ceil(args.clients.max(1));
    let mut clients: Vec<Child> = Vec::new();
    let mut first = 0;
    while first < args.surfaces {
        let count = per.min(args.surfaces - first);
        let mut child = Command::new(&exe)
            .args(["control-client", "--socket"])
            .arg(&daemon.socket)
            .args(["--first", &first.to_string(), "--count", &count.to_string()])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()?;
        let mut line = String::new();
        std::io::BufRead::read_line(&mut std::io::BufReader::new(child.stdout.take().context("stdout")?), &mut line)?;
        if line.trim() != "ready" {
            bail!("a control client did not start; the daemon's log:\n{}", std::fs::read_to_string(&daemon.log)?);
        }
        clients.push(child);
        first += count;
    }
    let mut c =
        ControlConnection::connect_as(&strata_protocol::handshake::control_socket_for(&daemon.socket), "strata-bench")?;
    match c.request(&ControlRequest::List)? {
        ControlReply::List { surfaces, .. } if surfaces.len() == args.surfaces as usize => {}
        other => bail!("expected {} surfaces, got {other:?}", args.surfaces),
    }
    let total = u64::from(args.applies * 2 + args.requests * 2 + args.processes * 2);
    let bar = if args.json { ProgressBar::hidden() } else { ProgressBar::new(total) };
    bar.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} {msg}")?);
    let ids: Vec<u64> = match c.request(&ControlRequest::List)? {
        ControlReply::List { surfaces, .. } => surfaces.iter().map(|r| r.id).collect(),
        _ => Vec::new(),
    };
    let (mut ten, mut one) = (Vec::new(), Vec::new());
    for k in 0..args.applies {
        bar.set_message("apply");
        let opacity = if k % 2 == 0 { 0.5 } else { 1.0 };
        let batch = |n: usize| -> Vec<Change> {
            (0..n).map(|i| Change::Opacity { surface: ids[(k as usize * 7 + i) % ids.len()], opacity }).collect()
        };
        ten.push(apply_latency(&mut c, batch(10))?);
        bar.inc(1);
        one.push(apply_latency(&mut c, batch(1))?);
        bar.inc(1);
    }
    bar.set_message("list");
    let list = round_trips(&mut c, &ControlRequest::List, args.requests)?;
    bar.inc(u64::from(args.requests));
    let light = round_trips(&mut c, &ControlRequest::Light(LightChange::default()), args.requests)?;
    bar.inc(u64::from(args.requests));
    bar.set_message("ctl processes");
    let list_proc = processes(&stratad, &daemon.socket, &["list", "--json"], args.processes)?;
    bar.inc(u64::from(args.processes));
    let light_proc = processes(&stratad, &daemon.socket, &["light", "show"], args.processes)?;
    bar.inc(u64::from(args.processes));
    bar.finish_and_clear();
    for mut child in clients {
        drop(child.stdin.take());
        let _ = child.wait();
    }
    drop(daemon);
    let _ = std::fs::remove_dir_all(&dir);

    let period = 1000.0 / args.refresh_hz;
    let refreshes = |ms: &[f64]| summary(ms.iter().map(|t| t / period).collect());
    let (ten_ms, one_ms) = (summary(ten.clone()), summary(one.clone()));
    let (list_ms, light_ms) = (summary(list), summary(light));
    let (list_p, light_p) = (summary(list_proc), summary(light_proc));
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let result = serde_json::json!({
        "surfaces": args.surfaces,
        "clients": args.clients,
        "refresh_hz": args.refresh_hz,
        "apply10_ms": ten_ms, "apply10_refreshes": refreshes(&ten),
        "apply1_ms": one_ms, "apply1_refreshes": refreshes(&one),
        "apply10_over_apply1_p50": ten_ms[0] / one_ms[0].max(1e-9),
        "list_ms": list_ms, "light_ms": light_ms,
        "list_over_light_p50": list_ms[0] / light_ms[0].max(1e-9),
        "ctl_list_process_ms": list_p, "ctl_light_process_ms": light_p,
        "loadavg": load.split_whitespace().take(3).collect::<Vec<_>>(),
    });
    if !args.json {
        println!(
            "{} surfaces from {} clients, refresh {} Hz (p50 / p99 / max)",
            args.surfaces, args.clients, args.refresh_hz
        );
        let r = refreshes(&ten);
        println!(
            "10-change apply shows in {:.2} / {:.2} / {:.2} refreshes ({:.1} / {:.1} / {:.1} ms); target <= 2",
            r[0], r[1], r[2], ten_ms[0], ten_ms[1], ten_ms[2]
        );
        println!(
            "  1-change apply (baseline): {:.1} / {:.1} / {:.1} ms; ratio 10:1 at p50 {:.2}",
            one_ms[0],
            one_ms[1],
            one_ms[2],
            ten_ms[0] / one_ms[0].max(1e-9)
        );
        println!(
            "list --json answers in {:.2} / {:.2} / {:.2} ms; target <= 5; light show (baseline) {:.2} ms; ratio {:.2}",
            list_ms[0],
            list_ms[1],
            list_ms[2],
            light_ms[0],
            list_ms[0] / light_ms[0].max(1e-9)
        );
        println!(
            "`stratad ctl list --json` process: {:.1} / {:.1} / {:.1} ms; `ctl light show` process {:.1} ms",
            list_p[0], list_p[1], list_p[2], light_p[0]
        );
        println!("load average {}", load.trim());
    }
    println!("{result}");
    if let Some(out) = &args.out {
        std::fs::write(out, result.to_string() + "\n").with_context(|| format!("writing {}", out.display()))?;
    }
    Ok(())
}

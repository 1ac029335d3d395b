//! `strata-bench clients`: what an idle client costs the daemon. Each client connects, makes a
//! context and a window surface (its session opens a device of its own), and draws nothing.
//! The daemon's resident memory and thread count are read with no client, then at each count
//! (10 and 64 by default), every figure against the empty daemon of the same run.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::{ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};

use crate::stratad::Stratad;

/// `strata-bench clients` options.
#[derive(clap::Args)]
pub struct Args {
    /// Connected idle clients at each measurement (ascending).
    #[arg(long, value_delimiter = ',', default_value = "10,64")]
    counts: Vec<usize>,
    /// One more option for the daemon (repeatable), e.g. `--daemon-arg=--devices=shared`.
    #[arg(long = "daemon-arg", allow_hyphen_values = true)]
    daemon_args: Vec<String>,
    /// The daemon binary [default: `stratad` beside this program].
    #[arg(long)]
    stratad: Option<PathBuf>,
    /// Where the JSON goes.
    #[arg(long, default_value = "target/strata-bench/clients.json")]
    out: PathBuf,
}

/// The daemon's resident memory (bytes), its threads, and its connected clients' devices.
fn sample(socket: &std::path::Path, pid: u32) -> Result<(u64, usize, usize)> {
    let mut c = ControlConnection::connect_beside(socket).context("connecting to the daemon's control socket")?;
    let s = match c.request(&ControlRequest::Stats)? {
        ControlReply::Stats(s) => s,
        other => bail!("unexpected control reply {other:?}"),
    };
    let threads = std::fs::read_dir(format!("/proc/{pid}/task"))?.count();
    Ok((s.rss_bytes, threads, s.clients.iter().filter(|c| c.device.is_some()).count()))
}

/// Runs the benchmark; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    let stratad = crate::glmark2::stratad_binary(args.stratad.as_deref())?;
    let socket = std::env::temp_dir().join(format!("strata-clients-{}.sock", std::process::id()));
    let log = std::env::temp_dir().join(format!("strata-clients-{}.log", std::process::id()));
    let mut daemon_args = vec!["--output".to_string(), "headless:c=640x480".into()];
    daemon_args.extend(args.daemon_args.iter().cloned());
    let daemon = Stratad::start(&stratad, &daemon_args, socket.clone(), log, false)?;
    let pid = daemon.pid();
    std::thread::sleep(Duration::from_millis(500));
    let (rss0, threads0, _) = sample(&socket, pid)?;
    println!("no client: RSS {:.1} MiB, {threads0} threads", rss0 as f64 / 1048576.0);
    let mut clients: Vec<Connection> = Vec::new();
    let mut rows = Vec::new();
    for &n in &args.counts {
        while clients.len() < n {
            let i = clients.len();
            let opts = ConnectOptions { socket: socket.clone(), name: format!("idle-{i}"), ..Default::default() };
            let why = || format!("client {i}; the daemon's log:\n{}", crate::stratad::tail(&daemon.log, 10));
            let mut gl = Connection::connect(&opts).with_context(why)?;
            let rect = [(i % 16) as i32 * 40, (i / 16) as i32 * 40, 32, 32];
            egl_context(&mut gl, 24, 0, SurfaceKind::Window { rect, z: 0.5 }).with_context(why)?;
            clients.push(gl);
        }
        // Every session has opened its device.
        let start = Instant::now();
        let (rss, threads) = loop {
            let (rss, threads, devices) = sample(&socket, pid)?;
            if devices >= n || start.elapsed() > Duration::from_secs(60) {
                break (rss, threads);
            }
            std::thread::sleep(Duration::from_millis(100));
        };
        let per_rss = (rss.saturating_sub(rss0)) as f64 / n as f64;
        let per_threads = (threads.saturating_sub(threads0)) as f64 / n as f64;
        println!(
            "{n:>3} idle clients: RSS {:.1} MiB ({:.2} MiB per client), {threads} threads ({per_threads:.1} per client)",
            rss as f64 / 1048576.0,
            per_rss / 1048576.0
        );
        rows.push(serde_json::json!({
            "clients": n, "rss_bytes": rss, "threads": threads,
            "rss_bytes_per_client": per_rss, "threads_per_client": per_threads,
        }));
    }
    drop(clients);
    drop(daemon);
    let doc = serde_json::json!({
        "benchmark": "clients",
        "daemon_args": args.daemon_args,
        "no_client": { "rss_bytes": rss0, "threads": threads0 },
        "rows": rows,
    });
    if let Some(dir) = args.out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&args.out, serde_json::to_string_pretty(&doc)?)?;
    println!("{doc}");
    Ok(())
}

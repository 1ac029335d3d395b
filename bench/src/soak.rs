//! `strata-bench soak`: the daemon under client churn for a long time. A bystander client
//! renders a known animation, and every frame of it, as composited, is checked against the
//! same frame composited while it ran alone; meanwhile client processes are started one after
//! another and killed with SIGKILL at random points (mid-command, mid-upload, mid-swap, blocked
//! in a paced swap, stalled), or leave cleanly, or run into their quota. The daemon's resident
//! memory is sampled throughout and plotted; it must be flat after warm-up.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use rand::{Rng, SeedableRng};
use serde::Serialize;
use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::control::DaemonStats;
use strata_protocol::handshake::{ControlReply, ControlRequest};

use crate::soak_client::Behaviour;

/// The bystander's animation repeats after this many frames.
const PERIOD: u32 = 16;
/// The bystander's square, at the output's top left.
const SIDE: u32 = 128;
/// How long a swapped bystander frame may take to be shown before it counts as late.
const LATE: Duration = Duration::from_secs(5);

/// `strata-bench soak` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// How long to run, minutes.
    #[arg(long, default_value_t = 30.0)]
    pub minutes: f64,
    /// Client processes to start over the run.
    #[arg(long, default_value_t = 1000)]
    pub clients: u32,
    /// Most churning clients alive at once.
    #[arg(long, default_value_t = 3)]
    pub concurrent: usize,
    /// The daemon binary [default: `stratad` beside this program].
    #[arg(long)]
    pub stratad: Option<PathBuf>,
    /// Where the JSON, the plot and the daemon's log go.
    #[arg(long, default_value = "target/strata-bench/soak")]
    pub out: PathBuf,
    /// Seed of the behaviours and kill times.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Only these behaviours (comma-separated) [default: all of them].
    #[arg(long, value_enum, value_delimiter = ',')]
    pub behaviours: Vec<Behaviour>,
    /// Print only the JSON (no progress bar).
    #[arg(long)]
    pub json: bool,
}

/// What the bystander saw.
#[derive(Debug, Default, Clone, Serialize)]
struct Bystander {
    frames_checked: u64,
    wrong: u64,
    late: u64,
    /// PNGs of wrong frames (the first few).
    evidence: Vec<String>,
}

/// One sample of the daemon's state.
#[derive(Debug, Clone, Serialize)]
struct Sample {
    minutes: f64,
    rss_mib: f64,
    clients: usize,
    gpu_mib: f64,
    /// Taken with only the bystander connected (churn paused until the others were gone), so
    /// that it shows what the daemon keeps rather than what live clients hold.
    settled: bool,
}

#[derive(Debug, Serialize)]
struct Report {
    minutes: f64,
    clients_started: u32,
    killed: u64,
    killed_by_behaviour: std::collections::BTreeMap<String, u64>,
    ended_themselves: u64,
    ended_with_error: u64,
    daemon_faults: Vec<String>,
    bystander: Bystander,
    rss_warm_mib: f64,
    rss_end_mib: f64,
    rss_growth_pct: f64,
    rss_peak_mib: f64,
    sessions: u64,
    load_average: String,
    samples: Vec<Sample>,
    plot: String,
}

/// Runs the soak.
pub fn run(args: &Args) -> Result<()> {
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let exe = std::env::current_exe()?;
    let stratad = crate::glmark2::stratad_binary(args.stratad.as_deref())?;
    let socket = args.out.join("soak.sock");
    let log = args.out.join("stratad.log");
    let mut daemon = Command::new(&stratad)
        .args(["serve", "--output", "soak=256x128", "--quota-gpu-bytes", "48M", "--socket"])
        .arg(&socket)
        .env("RUST_LOG", "warn")
        .stderr(std::fs::File::create(&log)?)
        .spawn()
        .with_context(|| format!("starting {}", stratad.display()))?;
    let result = soak(args, &exe, &socket, &mut daemon, &log);
    let _ = daemon.kill();
    let _ = daemon.wait();
    result
}

fn stats(c: &mut ControlConnection) -> Result<DaemonStats> {
    match c.request(&ControlRequest::Stats)? {
        ControlReply::Stats(s) => Ok(s),
        other => bail!("stats: unexpected {other:?}"),
    }
}

fn soak(args: &Args, exe: &Path, socket: &Path, daemon: &mut Child, log: &Path) -> Result<()> {
    let deadline = Instant::now() + Duration::from_secs(20);
    while std::os::unix::net::UnixStream::connect(socket).is_err() {
        if Instant::now() > deadline || daemon.try_wait()?.is_some() {
            bail!("stratad did not start; see {}", log.display());
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let mut control = ControlConnection::connect_beside(socket)?;
    let mut by = BystanderClient::start(socket)?;
    let refs = by.references()?;
    let stop = Arc::new(AtomicBool::new(false));
    let by_thread = {
        let (stop, out) = (stop.clone(), args.out.clone());
        std::thread::spawn(move || by.check_until(&refs, &stop, &out))
    };
    let total = Duration::from_secs_f64(args.minutes * 60.0);
    let start = Instant::now();
    let pb = if args.json { ProgressBar::hidden() } else { ProgressBar::new(u64::from(args.clients)) };
    pb.set_style(ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} clients {msg}")?);
    let mut rng = rand::rngs::StdRng::seed_from_u64(args.seed);
    let mut live: Vec<(Child, Behaviour, Instant)> = Vec::new();
    let (mut started, mut killed, mut ended, mut errors) = (0u32, 0u64, 0u64, 0u64);
    let mut by_behaviour = std::collections::BTreeMap::new();
    let mut samples = Vec::new();
    let mut faults = Vec::new();
    let mut next_sample = start;
    let settle_every = Duration::from_secs_f64((total.as_secs_f64() / 40.0).clamp(3.0, 30.0));
    let (mut next_settle, mut draining) = (start + settle_every, false);
    let mib = |b: u64| b as f64 / f64::from(1 << 20);
    while start.elapsed() < total || started < args.clients {
        if let Some(status) = daemon.try_wait()? {
            faults.push(format!("stratad exited ({status}) at {:.1} min", start.elapsed().as_secs_f64() / 60.0));
            break;
        }
        // Clients that are due die; those that end themselves are reaped.
        let now = Instant::now();
        let mut i = 0;
        while i < live.len() {
            let (child, behaviour, due) = &mut live[i];
            if let Some(status) = child.try_wait()? {
                if behaviour.ends_itself() && status.success() {
                    ended += 1;
                } else {
                    errors += 1;
                }
                live.swap_remove(i);
            } else if now >= *due {
                let _ = child.kill();
                let _ = child.wait();
                killed += 1;
                *by_behaviour.entry(format!("{behaviour:?}").to_lowercase()).or_insert(0u64) += 1;
                live.swap_remove(i);
            } else {
                i += 1;
            }
        }
        // Now and then churn pauses until only the bystander is left, for a settled sample.
        if Instant::now() >= next_settle {
            draining = true;
        }
        if draining && live.is_empty() {
            let s = stats(&mut control)?;
            if s.clients.len() <= 1 {
                let minutes = start.elapsed().as_secs_f64() / 60.0;
                let (rss_mib, gpu_mib) = (mib(s.rss_bytes), mib(s.gpu_bytes));
                samples.push(Sample { minutes, rss_mib, clients: s.clients.len(), gpu_mib, settled: true });
                draining = false;
                next_settle = Instant::now() + settle_every;
            }
        }
        // Start clients at the rate that spreads them over the run.
        let due_started = (start.elapsed().as_secs_f64() / total.as_secs_f64() * f64::from(args.clients)).ceil() as u32;
        while !draining && live.len() < args.concurrent && started < args.clients.min(due_started.max(1)) {
            let pool: &[Behaviour] = if args.behaviours.is_empty() { &Behaviour::ALL } else { &args.behaviours };
            let behaviour = pool[rng.random_range(0..pool.len())];
            let child = Command::new(exe)
                .args(["soak-client", "--behaviour", &format!("{behaviour:?}").to_lowercase(), "--socket"])
                .arg(socket)
                .args(["--seed", &rng.random::<u32>().to_string()])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .context("starting a soak client")?;
            let life = if behaviour.ends_itself() {
                Duration::from_secs(60)
            } else {
                Duration::from_millis(rng.random_range(50..1500))
            };
            live.push((child, behaviour, Instant::now() + life));
            started += 1;
            pb.inc(1);
        }
        if Instant::now() >= next_sample {
            let s = stats(&mut control)?;
            let minutes = start.elapsed().as_secs_f64() / 60.0;
            let (rss_mib, gpu_mib) = (mib(s.rss_bytes), mib(s.gpu_bytes));
            samples.push(Sample { minutes, rss_mib, clients: s.clients.len(), gpu_mib, settled: false });
            pb.set_message(format!("rss {:.0} MiB, {killed} killed", mib(s.rss_bytes)));
            next_sample += Duration::from_secs_f64((total.as_secs_f64() / 200.0).clamp(1.0, 5.0));
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    for (mut child, _, _) in live.drain(..) {
        let _ = child.kill();
        let _ = child.wait();
        killed += 1;
    }
    stop.store(true, Ordering::Relaxed);
    let bystander = by_thread.join().map_err(|_| anyhow::anyhow!("the bystander thread panicked"))??;
    pb.finish_and_clear();
    let last = stats(&mut control)?;
    drop(control);
    // A clean stop after all that is part of surviving it.
    // SAFETY: kill(2) on our own child.
    unsafe { libc::kill(daemon.id() as i32, libc::SIGTERM) };
    let status = daemon.wait()?;
    if !status.success() && faults.is_empty() {
        faults.push(format!("stratad did not stop cleanly: {status}"));
    }
    let text = std::fs::read_to_string(log).unwrap_or_default();
    faults.extend(text.lines().filter(|l| l.contains("panicked")).take(10).map(str::to_string));
    report(args, samples, bystander, faults, last, started, killed, by_behaviour, ended, errors)
}

#[allow(clippy::too_many_arguments)]
fn report(
    args: &Args,
    samples: Vec<Sample>,
    bystander: Bystander,
    faults: Vec<String>,
    last: DaemonStats,
    started: u32,
    killed: u64,
    killed_by_behaviour: std::collections::BTreeMap<String, u64>,
    ended: u64,
    errors: u64,
) -> Result<()> {
    // Warm-up is the first tenth of the run; growth compares the settled samples of the tenth
    // after it with those of the last tenth.
    let span = samples.iter().map(|s| s.minutes).fold(1e-9, f64::max);
    let mean = |from: f64, to: f64| {
        let v: Vec<f64> = samples
            .iter()
            .filter(|s| s.settled && s.minutes >= from * span && s.minutes <= to * span)
            .map(|s| s.rss_mib)
            .collect();
        v.iter().sum::<f64>() / v.len().max(1) as f64
    };
    let (warm, end) = (mean(0.1, 0.25), mean(0.85, 1.0));
    let plot = args.out.join("soak-rss.png");
    let series = |settled: bool, name: &str| crate::plot::Series {
        name: name.into(),
        points: samples.iter().filter(|s| s.settled == settled).map(|s| (s.minutes, s.rss_mib)).collect(),
        reference: false,
    };
    crate::plot::line_plot(
        &plot,
        &format!("stratad resident memory, {started} clients started and killed"),
        "minutes",
        "RSS (MiB)",
        &[series(false, "RSS under churn"), series(true, "RSS with only the bystander connected")],
    )?;
    let r = Report {
        minutes: args.minutes,
        clients_started: started,
        killed,
        killed_by_behaviour,
        ended_themselves: ended,
        ended_with_error: errors,
        daemon_faults: faults,
        bystander,
        rss_warm_mib: warm,
        rss_end_mib: end,
        rss_growth_pct: (end - warm) / warm.max(1e-9) * 100.0,
        rss_peak_mib: last.peak_rss_bytes as f64 / f64::from(1 << 20),
        sessions: last.sessions,
        load_average: std::fs::read_to_string("/proc/loadavg").unwrap_or_default().trim().to_string(),
        samples,
        plot: plot.display().to_string(),
    };
    let json = serde_json::to_string_pretty(&r)?;
    std::fs::write(args.out.join("soak.json"), &json)?;
    if args.json {
        println!("{json}");
    } else {
        println!(
            "soak: {:.1} min, {} clients started, {} killed with SIGKILL, {} ended themselves ({} with an error)",
            r.minutes, r.clients_started, r.killed, r.ended_themselves, r.ended_with_error
        );
        println!(
            "bystander: {} frames checked, {} wrong, {} late (> {} s)",
            r.bystander.frames_checked,
            r.bystander.wrong,
            r.bystander.late,
            LATE.as_secs()
        );
        println!(
            "stratad: {} faults; RSS {:.1} MiB after warm-up, {:.1} MiB at the end ({:+.2} %), peak {:.1} MiB",
            r.daemon_faults.len(),
            r.rss_warm_mib,
            r.rss_end_mib,
            r.rss_growth_pct,
            r.rss_peak_mib
        );
        for f in &r.daemon_faults {
            println!("  fault: {f}");
        }
        println!("load average {}; {} and {}", r.load_average, args.out.join("soak.json").display(), r.plot);
    }
    Ok(())
}

/// The client whose frames are checked.
struct BystanderClient {
    gl: Connection,
    control: ControlConnection,
    cur: Current,
    frame: u32,
}

impl BystanderClient {
    fn start(socket: &Path) -> Result<Self> {
        let opts =
            ConnectOptions { socket: socket.into(), name: "bystander".into(), role: "ic".into(), ..Default::default() };
        let mut gl = Connection::connect(&opts)?;
        let cur = egl_context(&mut gl, 24, 0, SurfaceKind::Window { rect: [0, 0, SIDE as i32, SIDE as i32], z: 0.1 })?;
        Ok(BystanderClient { gl, control: ControlConnection::connect_beside(socket)?, cur, frame: 0 })
    }

    /// Draws and swaps the next frame: a background and a bar that moves with the frame.
    fn draw(&mut self) -> Result<u32> {
        let k = self.frame % PERIOD;
        let gl = &mut self.gl;
        gl.glClearColor(0.1, 0.2 + k as f32 / 40.0, 0.6, 1.0)?;
        gl.glClear(0x4000 | 0x0100)?;
        gl.glEnable(0x0C11)?;
        gl.glScissor((k * 7) as i32, 0, 16, SIDE as i32)?;
        gl.glClearColor(0.9, 0.8, 0.1, 1.0)?;
        gl.glClear(0x4000)?;
        gl.glDisable(0x0C11)?;
        self.gl
            .eglSwapBuffers(self.cur.display, self.cur.surface)?
            .map_err(|e| anyhow::anyhow!("bystander eglSwapBuffers: EGL error {e:#x}"))?;
        self.frame += 1;
        Ok(k)
    }

    /// The bystander's square of the output now.
    fn shown(&mut self) -> Result<image::RgbaImage> {
        match self.control.request(&ControlRequest::Screenshot { output: "soak".into() })? {
            ControlReply::Image { width, height, rgba } => {
                let img = image::RgbaImage::from_raw(width, height, rgba.0).context("screenshot size")?;
                Ok(image::imageops::crop_imm(&img, 0, 0, SIDE, SIDE).to_image())
            }
            other => bail!("screenshot: unexpected {other:?}"),
        }
    }

    /// Every frame of the period composited alone: the reference each later frame must equal.
    fn references(&mut self) -> Result<Vec<image::RgbaImage>> {
        let mut refs: Vec<image::RgbaImage> = Vec::new();
        for _ in 0..PERIOD {
            self.draw()?;
            let since = Instant::now();
            let img = loop {
                let a = self.shown()?;
                let new = refs.last().is_none_or(|prev| *prev != a) && a.pixels().any(|p| p.0 != [0, 0, 0, 255]);
                if new && self.shown()? == a {
                    break a;
                }
                if since.elapsed() > LATE {
                    bail!("the bystander's frame {} was never shown while it ran alone", refs.len());
                }
            };
            if refs.contains(&img) {
                bail!("two frames of the bystander's animation composite alike");
            }
            refs.push(img);
        }
        Ok(refs)
    }

    /// Draws frames until `stop`, checking each as shown against `refs`.
    fn check_until(mut self, refs: &[image::RgbaImage], stop: &AtomicBool, out: &Path) -> Result<Bystander> {
        let mut b = Bystander::default();
        while !stop.load(Ordering::Relaxed) {
            let k = self.draw()? as usize;
            let prev = &refs[(k + refs.len() - 1) % refs.len()];
            let since = Instant::now();
            loop {
                let img = self.shown()?;
                if img == refs[k] {
                    b.frames_checked += 1;
                    break;
                }
                if img != *prev {
                    b.frames_checked += 1;
                    b.wrong += 1;
                    if b.evidence.len() < 5 {
                        let path = out.join(format!("wrong-frame-{}.png", self.frame));
                        img.save(&path)?;
                        b.evidence.push(path.display().to_string());
                    }
                    break;
                }
                if since.elapsed() > LATE {
                    b.late += 1;
                    break;
                }
                std::thread::sleep(Duration::from_millis(2));
            }
        }
        Ok(b)
    }
}

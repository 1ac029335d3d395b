//! `strata-bench interference`: freedom from interference. An instrument-cluster client (IC,
//! a dial at swap interval 1) must keep its frame deadline whatever a head-unit client (HU)
//! does. The IC runs alone, then beside each HU load in turn (glmark2-es2 `terrain` and
//! `refract` through the drop-in libraries, one huge draw per frame, 64 MiB of uploads per
//! frame, a flood of sessions each drawing huge draws); its frame times are compared with
//! those it had alone. The daemon is this
//! benchmark's own, configured to place both clients and, unless `--no-priorities`, to give
//! the IC high priority and a deadline.

use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::Value;
use strata_client::ControlConnection;
use strata_protocol::control::Priority;
use strata_protocol::handshake::{ControlReply, ControlRequest};

use crate::interference_client::{lines, read_outcome, FrameStats};
use crate::stratad::{stop, tail, wait_for, Stratad};

mod measures;
mod report;

pub use measures::{Args, Load};
use measures::{Phase, DEADLINE_MS, OUTPUT};

/// How long a HU load runs before the IC is measured beside it.
const SETTLE: Duration = Duration::from_secs(2);
/// Longest the HU is given to show its first frame before the IC is measured beside it.
const SETTLE_LIMIT: Duration = Duration::from_secs(60);

/// The daemon's layout: the IC at the left, the HU beside it; the HU's sessions are capped
/// at 8 (the session flood's).
fn config(priorities: bool) -> String {
    let (ic, hu) =
        if priorities { ("priority = \"high\"\ndeadline = true\n", "priority = \"low\"\n") } else { ("", "") };
    format!(
        "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\n{ic}\
         [[layout]]\nclient = \"hu\"\nx = 400\ny = 0\nz = 0.6\n{hu}\
         [[quota]]\nclient = \"hu\"\nsessions = 8\n"
    )
}

/// `ctl list` and `ctl stats` at one moment, as JSON (so that fields the daemon adds, such as
/// `deadline_misses`, are read without this code naming them).
struct Snapshot {
    at: Instant,
    surfaces: Vec<Value>,
    clients: Vec<Value>,
}

impl Snapshot {
    fn take(control: &mut ControlConnection) -> Result<Snapshot> {
        let hint = "(is stratad built from this tree?)";
        let surfaces = match control.request(&ControlRequest::List).with_context(|| format!("ctl list {hint}"))? {
            ControlReply::List { surfaces, .. } => surfaces,
            other => bail!("ctl list: unexpected {other:?}"),
        };
        let stats = match control.request(&ControlRequest::Stats).with_context(|| format!("ctl stats {hint}"))? {
            ControlReply::Stats(s) => serde_json::to_value(s)?,
            other => bail!("ctl stats: unexpected {other:?}"),
        };
        let surfaces = surfaces.iter().map(serde_json::to_value).collect::<Result<_, _>>()?;
        let clients = stats.get("clients").and_then(Value::as_array).cloned().unwrap_or_default();
        Ok(Snapshot { at: Instant::now(), surfaces, clients })
    }

    fn rows<'a>(&'a self, client: &'a str) -> impl Iterator<Item = &'a Value> + 'a {
        self.surfaces.iter().filter(move |s| s.get("client").and_then(Value::as_str) == Some(client))
    }

    /// Frames `client` has swapped, all its surfaces together.
    fn frames(&self, client: &str) -> u64 {
        self.rows(client).filter_map(|s| s.get("frames")?.as_u64()).sum()
    }

    /// `client`'s deadline misses, all its surfaces together (None where no row has the field).
    fn deadline_misses(&self, client: &str) -> Option<u64> {
        self.rows(client).filter_map(|s| s.get("deadline_misses")?.as_u64()).reduce(|a, b| a + b)
    }

    fn has_client(&self, client: &str) -> bool {
        self.clients.iter().any(|c| c.get("name").and_then(Value::as_str) == Some(client))
    }
}

/// A running HU load.
struct Hu {
    load: Load,
    child: Child,
    /// The client's result file (interference-client loads).
    result: Option<PathBuf>,
    log: PathBuf,
}

/// What the glmark2 loads need: a temporary directory, the shim directory and an X server.
type Glmark2Env = (crate::glmark2::TempDir, PathBuf, crate::glmark2::Xvfb);

/// Everything the phases share.
struct Bench<'a> {
    args: &'a Args,
    exe: PathBuf,
    daemon: Stratad,
    control: ControlConnection,
    glmark2: Option<Glmark2Env>,
}

impl Bench<'_> {
    /// A client process of `class`: run through `nice` at the class's nice value unless
    /// `--same-process-nice` (or `--no-priorities`). Raising priority needs `CAP_SYS_NICE`;
    /// without it `nice` says so and runs the program at the benchmark's own value.
    fn process(&self, program: &Path, class: Priority) -> Command {
        if self.args.same_process_nice || self.args.no_priorities {
            return Command::new(program);
        }
        let mut cmd = Command::new("nice");
        cmd.args(["-n", &strata_device::nice_for(class).to_string()]).arg(program);
        cmd
    }

    fn start_hu(&self, load: Load) -> Result<Hu> {
        let name = load.name();
        let log = self.args.out.join(format!("hu-{name}.log"));
        let file = std::fs::File::create(&log).with_context(|| format!("creating {}", log.display()))?;
        let (mut cmd, result) = if load.is_glmark2() {
            let (_, shim, x) = self.glmark2.as_ref().context("glmark2-es2 is not set up")?;
            let mut cmd = self.process("glmark2-es2".as_ref(), Priority::Low);
            cmd.args(["-b", &format!("{name}:duration=100000"), "-s", &self.args.hu_size, "--swap-mode", "immediate"])
                .env("DISPLAY", &x.display)
                .env("LD_LIBRARY_PATH", shim)
                .env("STRATA_SOCKET", &self.daemon.socket)
                .env("STRATA_NAME", "hu")
                .env_remove("STRATA_WINDOW");
            (cmd, None)
        } else {
            let result = self.args.out.join(format!("hu-{name}.json"));
            let _ = std::fs::remove_file(&result);
            let mut cmd = self.process(&self.exe, Priority::Low);
            cmd.args(["interference-client", "--role", &name, "--seconds", "1000000", "--socket"])
                .arg(&self.daemon.socket)
                .arg("--out")
                .arg(&result)
                .args(["--window", &format!("400,0,{}", self.args.hu_size)])
                .args(["--iterations", &self.args.iterations.to_string()]);
            (cmd, Some(result))
        };
        let child = cmd
            .stdin(Stdio::null())
            .stdout(file.try_clone()?)
            .stderr(file)
            .spawn()
            .with_context(|| format!("starting the {name} load"))?;
        Ok(Hu { load, child, result, log })
    }

    /// Stops the HU; returns its own frame rate, and an error if it failed before it was
    /// stopped. Waits until the daemon has let it go.
    fn stop_hu(&mut self, mut hu: Hu) -> (Option<f64>, Option<String>) {
        let early = hu.child.try_wait().ok().flatten();
        stop(&mut hu.child, Duration::from_secs(10));
        let error = early.map(|s| format!("the {} load exited early ({s}):\n{}", hu.load.name(), tail(&hu.log, 8)));
        let fps = match &hu.result {
            Some(path) => read_outcome(path).ok().map(|o| o.fps),
            // glmark2 prints `[scene] ...: FPS: N FrameTime: ...` when a scene ends.
            None => std::fs::read_to_string(&hu.log)
                .unwrap_or_default()
                .lines()
                .rev()
                .find_map(|l| l.split_once("FPS:")?.1.split_whitespace().next()?.parse().ok()),
        };
        let deadline = Instant::now() + Duration::from_secs(60);
        while Instant::now() < deadline {
            match Snapshot::take(&mut self.control) {
                Ok(s) if !s.has_client("hu") => break,
                Ok(_) => std::thread::sleep(Duration::from_millis(100)),
                Err(_) => break,
            }
        }
        (fps, error)
    }

    /// Measures the IC for `--seconds`, beside whatever runs now.
    fn measure(&mut self, name: &str) -> Result<Phase> {
        let result = self.args.out.join(format!("ic-{name}.json"));
        let log = self.args.out.join(format!("ic-{name}.log"));
        let _ = std::fs::remove_file(&result);
        let mut child = self
            .process(&self.exe, Priority::High)
            .args(["interference-client", "--role", "ic", "--hold", "--seconds", &self.args.seconds.to_string()])
            .arg("--socket")
            .arg(&self.daemon.socket)
            .arg("--out")
            .arg(&result)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(std::fs::File::create(&log)?)
            .spawn()
            .context("starting the IC")?;
        let stdin = child.stdin.take();
        let r = self.measured(name, &mut child, stdin, &result);
        if wait_for(&mut child, Duration::from_secs(30)).is_none() {
            stop(&mut child, Duration::from_secs(5));
        }
        r.map_err(|e| anyhow!("{e:#}\nthe IC's log:\n{}", tail(&log, 8)))
    }

    fn measured(&mut self, name: &str, child: &mut Child, stdin: Option<ChildStdin>, result: &Path) -> Result<Phase> {
        let rx = lines(child.stdout.take().context("the IC's stdout")?);
        let expect = |what: &str, limit: Duration| -> Result<()> {
            let until = Instant::now() + limit;
            loop {
                let left = until.saturating_duration_since(Instant::now());
                match rx.recv_timeout(left) {
                    Ok(line) if line == what => return Ok(()),
                    Ok(_) => {}
                    Err(_) => bail!("the IC did not say {what:?} within {limit:?}"),
                }
            }
        };
        let slack = Duration::from_secs(120);
        expect("measuring", slack)?;
        let before = Snapshot::take(&mut self.control)?;
        expect("end", Duration::from_secs_f64(self.args.seconds) + slack)?;
        let after = Snapshot::take(&mut self.control)?;
        drop(stdin);
        if wait_for(child, Duration::from_secs(30)).is_none_or(|s| !s.success()) {
            bail!("the IC did not end cleanly");
        }
        let outcome = read_outcome(result)?;
        let secs = (after.at - before.at).as_secs_f64().max(1e-9);
        let hu = name != "alone";
        let hu_fps = hu.then(|| after.frames("hu").saturating_sub(before.frames("hu")) as f64 / secs);
        let hu_interval = after.rows("hu").find_map(|s| s.get("interval")?.as_i64());
        let misses = match (before.deadline_misses("ic"), after.deadline_misses("ic")) {
            (Some(b), Some(a)) => Some(a.saturating_sub(b)),
            _ => None,
        };
        let loadavg = std::fs::read_to_string("/proc/loadavg").ok();
        let ic_surface = after.rows("ic").next().cloned();
        Ok(Phase {
            phase: name.to_string(),
            ic: FrameStats::of(&outcome.frame_times_ms, DEADLINE_MS),
            daemon_deadline_misses: misses,
            p50_ratio: None,
            p99_ratio: None,
            max_ratio: None,
            hu_fps,
            hu_reported_fps: None,
            hu_alone_fps: None,
            hu_vs_alone: None,
            hu_interval,
            hu_error: None,
            load_average_1m: loadavg.and_then(|l| l.split_whitespace().next()?.parse().ok()),
            ic_surface,
            clients: after
                .clients
                .iter()
                .filter(|c| matches!(c.get("name").and_then(Value::as_str), Some("ic" | "hu")))
                .cloned()
                .collect(),
            frame_times_ms: outcome.frame_times_ms,
        })
    }

    /// The HU's frames per second over `--seconds` with no IC connected.
    fn hu_alone(&mut self) -> Result<f64> {
        let before = Snapshot::take(&mut self.control)?;
        std::thread::sleep(Duration::from_secs_f64(self.args.seconds));
        let after = Snapshot::take(&mut self.control)?;
        let secs = (after.at - before.at).as_secs_f64().max(1e-9);
        Ok(after.frames("hu").saturating_sub(before.frames("hu")) as f64 / secs)
    }

    /// One load's phase: start it, let it settle, measure it alone, then the IC beside it,
    /// and stop it.
    fn load_phase(&mut self, load: Load) -> Result<Phase> {
        let hu = self.start_hu(load)?;
        // Measure the steady state: after the HU's first frame (its pipelines compiled, its
        // first uploads done), or after `SETTLE_LIMIT` at most.
        let until = Instant::now() + SETTLE_LIMIT;
        while load != Load::CpuHog && Instant::now() < until {
            match Snapshot::take(&mut self.control) {
                Ok(s) if s.frames("hu") >= 1 => break,
                Ok(_) => std::thread::sleep(Duration::from_millis(200)),
                Err(_) => break,
            }
        }
        std::thread::sleep(SETTLE);
        // The HU alone first, over as long as the IC is measured beside it.
        let alone = (load != Load::CpuHog).then(|| self.hu_alone()).transpose();
        let phase = alone.and_then(|alone| Ok((alone, self.measure(&load.name())?)));
        let (fps, error) = self.stop_hu(hu);
        let (alone, mut phase) = phase?;
        phase.hu_reported_fps = fps;
        phase.hu_error = error;
        phase.hu_alone_fps = alone;
        phase.hu_vs_alone = match (phase.hu_fps, alone) {
            (Some(with), Some(a)) if a > 0.0 => Some(with / a),
            _ => None,
        };
        Ok(phase)
    }
}

/// Runs the benchmark.
pub fn run(args: &Args) -> Result<()> {
    if !args.seconds.is_finite() || args.seconds <= 0.0 {
        bail!("--seconds must be positive");
    }
    crate::glmark2::size(&args.hu_size)?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let exe = std::env::current_exe()?;
    let stratad = crate::glmark2::stratad_binary(args.stratad.as_deref())?;
    let config_path = args.out.join("stratad.toml");
    std::fs::write(&config_path, config(!args.no_priorities))
        .with_context(|| format!("writing {}", config_path.display()))?;

    let mut skipped = Vec::new();
    let mut loads = args.loads.clone();
    // glmark2 loads need glmark2-es2, Xvfb and the shim (`prepare` says what is missing).
    let glmark2 = match loads.iter().any(|l| l.is_glmark2()).then(|| crate::glmark2::prepare(args.shim.as_deref())) {
        Some(Ok(env)) => Some(env),
        Some(Err(e)) => {
            for l in loads.iter().filter(|l| l.is_glmark2()) {
                skipped.push(format!("{}: skipped: {e:#}", l.name()));
                if !args.json {
                    eprintln!("{}", skipped[skipped.len() - 1]);
                }
            }
            loads.retain(|l| !l.is_glmark2());
            None
        }
        None => None,
    };

    let socket = std::env::temp_dir().join(format!("strata-interference-{}.sock", std::process::id()));
    let mut daemon_args: Vec<&std::ffi::OsStr> =
        vec!["--output".as_ref(), OUTPUT.as_ref(), "--config".as_ref(), config_path.as_os_str()];
    daemon_args.extend(args.daemon_args.iter().map(std::ffi::OsStr::new));
    let daemon = Stratad::start(&stratad, daemon_args, socket, args.out.join("stratad.log"), true)?;
    let control =
        ControlConnection::connect_beside(&daemon.socket).context("connecting to stratad's control socket")?;
    let mut bench = Bench { args, exe, daemon, control, glmark2 };

    let pb = if args.json { ProgressBar::hidden() } else { ProgressBar::new(1 + loads.len() as u64) };
    pb.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} phases: {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    pb.enable_steady_tick(Duration::from_millis(250));
    pb.set_message("IC alone");
    let alone = bench.measure("alone").context("the IC alone")?;
    pb.inc(1);
    let mut phases = vec![alone];
    let mut failures = Vec::new();
    for &load in &loads {
        pb.set_message(format!("IC beside {}", load.name()));
        bench.daemon.alive()?;
        match bench.load_phase(load) {
            Ok(p) => phases.push(p),
            Err(e) => {
                let why = format!("{}: {e:#}", load.name());
                pb.println(format!("phase failed: {why}"));
                failures.push(why);
            }
        }
        pb.inc(1);
    }
    pb.finish_and_clear();
    bench.daemon.alive()?;
    let daemon_log = bench.daemon.log.display().to_string();
    drop(bench);
    report::report(args, phases, skipped, failures, &config_path, daemon_log)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn config_has_priorities_only_when_asked() {
        let with = config(true);
        assert!(with.contains("priority = \"high\"") && with.contains("deadline = true"));
        assert!(with.contains("priority = \"low\""));
        let without = config(false);
        assert!(!without.contains("priority") && !without.contains("deadline"));
        assert_eq!(without.matches("[[layout]]").count(), 2);
    }
}

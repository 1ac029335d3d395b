//! Unmodified glmark2-es2 through Strata against the same program on Mesa, same run.
//!
//! One Xvfb and one daemon (this binary re-executed, running `strata_server::serve` with a
//! headless output) serve every run. glmark2-es2 runs natively (Mesa on llvmpipe, under the
//! same X server) and through the drop-in libEGL/libGLESv2 alternately, and the medians of
//! its scores are compared. Then n = 1…N instances run concurrently through Strata, all at the
//! same window rectangle and z, so that every pixel is a per-fragment depth contest between
//! n surfaces (the same-z curve), and optionally the same n natively. With `--z-step` the
//! instances sit at one z each instead (the thesis' Table 5.3), and with `--compositor 2d` the
//! daemon composites them as a 2D blitting compositor would (Table 5.4).

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Context, Result};
use clap::ValueEnum;
use indicatif::{ProgressBar, ProgressStyle};

use crate::plot::{line_plot, Series};
use crate::transport::{start_daemon_with, DaemonProc};

/// `strata-bench glmark2` options.
#[derive(clap::Args)]
pub struct Args {
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
    /// glmark2 model of the `build` scene.
    #[arg(long, default_value = "horse")]
    model: String,
    /// Seconds each glmark2 scene runs.
    #[arg(long, default_value_t = 5)]
    duration: u32,
    /// glmark2 window size, WxH.
    #[arg(long, default_value = "540x540")]
    size: String,
    /// Native/Strata pairs of the single-instance comparison (run alternately; medians reported).
    #[arg(long, default_value_t = 3)]
    pairs: u32,
    /// Most concurrent instances of the same-z curve (0: no curve).
    #[arg(long, default_value_t = 10)]
    max_instances: u32,
    /// Skip the native side of the curve.
    #[arg(long)]
    no_native_curve: bool,
    /// The daemon's compositor (2d: the baseline of the thesis' Table 5.4).
    #[arg(long, value_enum, default_value_t = strata_compositor::Mode::ThreeD)]
    compositor: strata_compositor::Mode,
    /// Instance i of a concurrent run sits at z = i · STEP (0: all at one z, the same-z curve;
    /// 1: one z each, as in the thesis' Tables 5.3 and 5.4).
    #[arg(long, default_value_t = 0.0)]
    z_step: f32,
    /// The daemon's headless output, WxH.
    #[arg(long, default_value = "1920x720")]
    output: String,
    /// Directory holding libEGL.so.1 and libGLESv2.so.2 from `tools/build-shim` [default: the
    /// libstrata_egl.so cargo built next to this binary].
    #[arg(long)]
    shim: Option<PathBuf>,
    /// Where to write the curve (JSON) and its plot (PNG, same name).
    #[arg(long, default_value = "target/strata-bench/glmark2.json")]
    out: PathBuf,
}

/// The `stratad` a benchmark starts: `arg` if given, else the one beside this program; an
/// error if it is not built.
pub(crate) fn stratad_binary(arg: Option<&Path>) -> Result<PathBuf> {
    let stratad = match arg {
        Some(p) => p.to_path_buf(),
        None => std::env::current_exe()?.parent().context("program directory")?.join("stratad"),
    };
    if !stratad.is_file() {
        bail!("{} is not built (cargo build -p strata-server)", stratad.display());
    }
    Ok(stratad)
}

/// A program on `PATH`.
pub(crate) fn which(program: &str) -> Option<PathBuf> {
    std::env::var_os("PATH")?.to_str()?.split(':').map(|d| Path::new(d).join(program)).find(|p| p.is_file())
}

/// A private X server on a display it chose itself; killed on drop.
pub(crate) struct Xvfb {
    child: Child,
    /// The `DISPLAY` value.
    pub(crate) display: String,
}

impl Xvfb {
    pub(crate) fn start() -> Result<Xvfb> {
        let mut child = Command::new("Xvfb")
            .args(["-displayfd", "1", "-screen", "0", "1920x1080x24", "-nolisten", "tcp"])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .context("starting Xvfb")?;
        // Xvfb writes the display number it chose once it accepts connections.
        let mut line = String::new();
        let read = child.stdout.take().map(|s| BufReader::new(s).read_line(&mut line));
        let mut x = Xvfb { child, display: String::new() };
        match (read, line.trim().parse::<u32>()) {
            (Some(Ok(_)), Ok(n)) => {
                x.display = format!(":{n}");
                Ok(x)
            }
            _ => bail!("Xvfb did not report a display number (it printed {line:?})"),
        }
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A temporary directory, removed on drop.
pub(crate) struct TempDir(pub(crate) PathBuf);

impl TempDir {
    pub(crate) fn new() -> Result<TempDir> {
        let p = std::env::temp_dir().join(format!("strata-bench-glmark2-{}", std::process::id()));
        std::fs::create_dir_all(&p).with_context(|| format!("creating {}", p.display()))?;
        Ok(TempDir(p))
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The directory applications load the shim from: `--shim`, or links to the libstrata_egl.so
/// cargo built beside this binary (strata-egl is a dependency of this crate, so building the
/// benchmark builds it).
pub(crate) fn shim_dir(arg: Option<&Path>, tmp: &TempDir) -> Result<PathBuf> {
    if let Some(dir) = arg {
        for name in ["libEGL.so.1", "libGLESv2.so.2"] {
            if !dir.join(name).is_file() {
                bail!("{} has no {name}; run tools/build-shim DIR and pass DIR", dir.display());
            }
        }
        return Ok(dir.to_path_buf());
    }
    let exe = std::env::current_exe().context("locating this binary")?;
    let bin_dir = exe.parent().context("this binary has no directory")?;
    let lib = [bin_dir.join("libstrata_egl.so"), bin_dir.join("deps").join("libstrata_egl.so")]
        .into_iter()
        .find(|p| p.is_file())
        .with_context(|| {
            format!(
                "libstrata_egl.so not found beside {}; build it with `cargo build --release -p strata-egl` \
                 or pass --shim $(tools/build-shim)",
                exe.display()
            )
        })?;
    let dir = tmp.0.join("strata-gl");
    std::fs::create_dir_all(&dir)?;
    for name in ["libEGL.so.1", "libGLESv2.so.2", "libEGL.so", "libGLESv2.so"] {
        std::os::unix::fs::symlink(&lib, dir.join(name)).with_context(|| format!("linking {name}"))?;
    }
    Ok(dir)
}

/// Where glmark2 renders.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    /// Mesa's own libEGL/libGLESv2 (llvmpipe).
    Native,
    /// The drop-in libraries, executed and composited by the daemon.
    Strata,
}

/// Everything a glmark2 run needs.
struct Runner<'a> {
    args: &'a Args,
    display: String,
    shim: PathBuf,
    socket: PathBuf,
    window: String,
}

/// One glmark2 process's result.
pub(crate) struct Run {
    /// glmark2's score: the instance's frames per second.
    pub(crate) score: u32,
}

impl Runner<'_> {
    /// glmark2 on `side`; through Strata, as instance `i` of its run.
    fn command(&self, side: Side, i: u32) -> Command {
        let mut cmd = Command::new("glmark2-es2");
        let bench = format!("build:model={}:duration={}", self.args.model, self.args.duration);
        cmd.args(["-b", &bench, "-s", &self.args.size])
            .env("DISPLAY", &self.display)
            .env_remove("LD_LIBRARY_PATH")
            .env_remove("STRATA_SOCKET")
            .env_remove("STRATA_WINDOW")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        if side == Side::Strata {
            cmd.env("LD_LIBRARY_PATH", &self.shim)
                .env("STRATA_SOCKET", &self.socket)
                .env("STRATA_WINDOW", format!("{},{}", self.window, i as f32 * self.args.z_step));
        }
        cmd
    }

    /// Runs `n` instances at once on `side` and returns each one's score.
    fn run(&self, side: Side, n: u32) -> Result<Vec<Run>> {
        let children: Vec<Child> =
            (0..n).map(|i| self.command(side, i).spawn().context("starting glmark2-es2")).collect::<Result<_>>()?;
        let deadline = Duration::from_secs(u64::from(self.args.duration) * 3 + 120);
        // Collect every child even if one fails, so none is left running.
        let outcomes: Vec<Result<Run>> = children.into_iter().map(|c| finish(c, deadline)).collect();
        outcomes.into_iter().collect()
    }
}

/// Waits for a glmark2 process (killing it after `deadline`) and parses its score.
pub(crate) fn finish(mut child: Child, deadline: Duration) -> Result<Run> {
    let pipes = (child.stdout.take(), child.stderr.take());
    let read = |p: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = String::new();
            if let Some(mut p) = p {
                let _ = p.read_to_string(&mut s);
            }
            s
        })
    };
    let t_out = read(pipes.0.map(|p| Box::new(p) as Box<dyn Read + Send>));
    let t_err = read(pipes.1.map(|p| Box::new(p) as Box<dyn Read + Send>));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait()? {
            break Some(s);
        }
        if start.elapsed() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let text = format!("{}{}", t_out.join().unwrap_or_default(), t_err.join().unwrap_or_default());
    let tail = || text.lines().rev().take(12).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("\n");
    let Some(status) = status else {
        bail!("glmark2-es2 did not finish within {deadline:?}:\n{}", tail());
    };
    match parse_score(&text) {
        Some(score) if status.success() => Ok(Run { score }),
        _ => bail!("glmark2-es2 exited with {status} without a score:\n{}", tail()),
    }
}

/// The number on glmark2's `glmark2 Score: N` line.
fn parse_score(text: &str) -> Option<u32> {
    text.lines().find_map(|l| l.split_once("glmark2 Score:")?.1.split_whitespace().next()?.parse().ok())
}

/// The median of `v` (mean of the middle two for even lengths).
fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    match s.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => s[n / 2],
        n => (s[n / 2 - 1] + s[n / 2]) / 2.0,
    }
}

/// Parses `WxH`.
pub(crate) fn size(s: &str) -> Result<(u32, u32)> {
    let (w, h) = s.split_once('x').with_context(|| format!("{s:?} is not WxH"))?;
    let parse = |v: &str| v.parse::<u32>().ok().filter(|&v| v > 0).with_context(|| format!("{s:?} is not WxH"));
    Ok((parse(w)?, parse(h)?))
}

/// One point of the same-z curve.
#[derive(serde::Serialize)]
struct Point {
    instances: u32,
    strata_scores: Vec<u32>,
    strata_total_fps: f64,
    strata_average_fps: f64,
    native_scores: Option<Vec<u32>>,
    native_total_fps: Option<f64>,
    native_average_fps: Option<f64>,
}

fn total(scores: &[u32]) -> f64 {
    scores.iter().map(|&s| f64::from(s)).sum()
}

/// What every glmark2 run needs: glmark2-es2 and Xvfb installed, a temporary directory, the
/// shim directory (`--shim` or the library built beside this binary), and an X server.
pub(crate) fn prepare(shim: Option<&Path>) -> Result<(TempDir, PathBuf, Xvfb)> {
    for (program, package) in [("glmark2-es2", "glmark2-es2-x11 and glmark2-data"), ("Xvfb", "xvfb")] {
        if which(program).is_none() {
            bail!("{program} not found on PATH; install the Debian package {package} (tools/install-deps does)");
        }
    }
    let tmp = TempDir::new()?;
    let shim = shim_dir(shim, &tmp)?;
    let x = Xvfb::start()?;
    Ok((tmp, shim, x))
}

/// Runs the benchmark and prints its report; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    if args.pairs == 0 || args.duration == 0 {
        bail!("--pairs and --duration must be positive");
    }
    let (win_w, win_h) = size(&args.size)?;
    let (out_w, out_h) = size(&args.output)?;
    let (tmp, shim, x) = prepare(args.shim.as_deref())?;
    let log = tmp.0.join("daemon.log");
    let daemon: DaemonProc = start_daemon_with(
        strata_server::ExecutorKind::Gles,
        &[
            "--output".into(),
            format!("headless:bench={out_w}x{out_h}"),
            "--compositor".into(),
            args.compositor.to_possible_value().map_or("3d".into(), |v| v.get_name().to_string()),
        ],
        Some(&log),
    )?;
    // Every instance's window surface: the same rectangle (centred in the output); z by
    // `--z-step`.
    let window = format!("{},{}", out_w.saturating_sub(win_w) / 2, out_h.saturating_sub(win_h) / 2);
    let runner = Runner { args, display: x.display.clone(), shim, socket: daemon.1.clone(), window: window.clone() };
    let daemon_log = || {
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        text.lines().rev().take(20).collect::<Vec<_>>().into_iter().rev().collect::<Vec<_>>().join("\n")
    };
    let with_log = |e: anyhow::Error| anyhow!("{e:#}\ndaemon log (last lines):\n{}", daemon_log());

    let curve_native = !args.no_native_curve;
    let steps = u64::from(2 * args.pairs + args.max_instances * if curve_native { 2 } else { 1 });
    let pb = if args.json { ProgressBar::hidden() } else { ProgressBar::new(steps) };
    pb.set_style(
        ProgressStyle::with_template("{msg:>24} [{bar:40}] {pos}/{len} {elapsed} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    let mut native_runs = Vec::new();
    let mut strata_runs = Vec::new();
    for i in 0..args.pairs {
        pb.set_message(format!("native {}/{}", i + 1, args.pairs));
        native_runs.push(runner.run(Side::Native, 1).map_err(with_log)?[0].score);
        pb.inc(1);
        pb.set_message(format!("strata {}/{}", i + 1, args.pairs));
        strata_runs.push(runner.run(Side::Strata, 1).map_err(with_log)?[0].score);
        pb.inc(1);
    }
    let mut points = Vec::new();
    for n in 1..=args.max_instances {
        pb.set_message(format!("same z: {n} via strata"));
        let strata: Vec<u32> = runner.run(Side::Strata, n).map_err(with_log)?.iter().map(|r| r.score).collect();
        pb.inc(1);
        let native: Option<Vec<u32>> = if curve_native {
            pb.set_message(format!("same z: {n} native"));
            let r = runner.run(Side::Native, n)?.iter().map(|r| r.score).collect();
            pb.inc(1);
            Some(r)
        } else {
            None
        };
        points.push(Point {
            instances: n,
            strata_total_fps: total(&strata),
            strata_average_fps: total(&strata) / f64::from(n),
            native_total_fps: native.as_deref().map(total),
            native_average_fps: native.as_deref().map(|s| total(s) / f64::from(n)),
            strata_scores: strata,
            native_scores: native,
        });
    }
    pb.finish_and_clear();
    drop(daemon);
    drop(x);

    let as_f64 = |v: &[u32]| v.iter().map(|&s| f64::from(s)).collect::<Vec<_>>();
    let native_score = median(&as_f64(&native_runs));
    let strata_score = median(&as_f64(&strata_runs));
    let ratio = strata_score / native_score;
    let png = args.out.with_extension("png");
    let bench = format!("build:model={}:duration={}", args.model, args.duration);
    if !args.json {
        println!(
            "glmark2-es2 -b {bench} -s {}, Xvfb; through Strata ({:?} compositor) at STRATA_WINDOW={window},i*{}",
            args.size, args.compositor, args.z_step
        );
        println!("  native (Mesa llvmpipe) scores: {native_runs:?}  median {native_score}");
        println!("  through Strata scores:         {strata_runs:?}  median {strata_score}");
        println!("  strata / native:               {ratio:.3}");
        if !points.is_empty() {
            println!();
            println!(
                "{}, same area: n concurrent instances (score = FPS of each instance)",
                if args.z_step == 0.0 { "same z" } else { "one z each" }
            );
            println!(
                "{:>3} {:>12} {:>12} {:>12} {:>12}  strata scores",
                "n", "strata total", "strata avg", "native total", "native avg"
            );
            let opt = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.0}"));
            for p in &points {
                println!(
                    "{:>3} {:>12.0} {:>12.1} {:>12} {:>12}  {:?}",
                    p.instances,
                    p.strata_total_fps,
                    p.strata_average_fps,
                    opt(p.native_total_fps),
                    opt(p.native_average_fps),
                    p.strata_scores
                );
            }
        }
    }
    let summary = serde_json::json!({
        "benchmark": "glmark2",
        "glmark2_benchmark": bench,
        "size": args.size,
        "window": window,
        "compositor": format!("{:?}", args.compositor),
        "z_step": args.z_step,
        "native_runs": native_runs,
        "strata_runs": strata_runs,
        "native_score": native_score,
        "strata_score": strata_score,
        "ratio": ratio,
        "max_instances": args.max_instances,
        "curve": (!points.is_empty()).then_some(&args.out),
        "plot": (!points.is_empty()).then_some(&png),
    });
    if !points.is_empty() {
        if let Some(dir) = args.out.parent() {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        let doc = serde_json::json!({ "summary": summary, "points": points });
        std::fs::write(&args.out, serde_json::to_string_pretty(&doc)?)
            .with_context(|| format!("writing {}", args.out.display()))?;
        let xy = |f: &dyn Fn(&Point) -> Option<f64>| -> Vec<(f64, f64)> {
            points.iter().filter_map(|p| Some((f64::from(p.instances), f(p)?))).collect()
        };
        let mut series = vec![
            Series { name: "Strata: total FPS".into(), points: xy(&|p| Some(p.strata_total_fps)), reference: false },
            Series {
                name: "Strata: FPS per instance".into(),
                points: xy(&|p| Some(p.strata_average_fps)),
                reference: false,
            },
        ];
        if curve_native {
            series.push(Series {
                name: "native Mesa: total FPS".into(),
                points: xy(&|p| p.native_total_fps),
                reference: true,
            });
            series.push(Series {
                name: "native Mesa: FPS per instance".into(),
                points: xy(&|p| p.native_average_fps),
                reference: true,
            });
        }
        match line_plot(
            &png,
            &format!(
                "glmark2-es2 {bench}, {}: n instances, one area, {}, {:?} compositor",
                args.size,
                if args.z_step == 0.0 { "one z" } else { "one z each" },
                args.compositor
            ),
            "concurrent instances (n)",
            "frames per second",
            &series,
        ) {
            Ok(()) if !args.json => println!("curve: {} and {}", args.out.display(), png.display()),
            Ok(()) => {}
            Err(e) => eprintln!("plot not written: {e:#}"),
        }
    }
    println!("{summary}");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn score_line_parses() {
        let out = "=====\n                                  glmark2 Score: 207 \n=====\n";
        assert_eq!(parse_score(out), Some(207));
        assert_eq!(parse_score("[build] model=horse: FPS: 77 FrameTime: 13.109 ms"), None);
    }

    #[test]
    fn median_of_odd_and_even() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}

//! `strata-bench thesis`: the evaluation of the thesis Strata comes from (chapter 5), run on
//! this machine. n = 1…N unmodified glmark2-es2 instances draw the `build` scene in one window
//! rectangle of a headless output:
//!
//! | table | figure | how |
//! |---|---|---|
//! | 5.1 | 5.2 | through Strata, every instance at one z (per-fragment depth contests everywhere) |
//! | 5.2 | 5.3 | natively on Mesa (llvmpipe), under the same X server |
//! | 5.3 | 5.4 | through Strata, one z each (no contest: the nearest surface wins) |
//! | 5.4 | 5.5 | through the 2D baseline (`--compositor 2d`): painter's order, opaque copies |
//!
//! The daemon chains at `--max-textures 8` (the thesis' i.MX6 had 8 texture units), lighting on,
//! 60 Hz. Per n it reports each instance's fps, the total, the compositor's milliseconds per
//! composite (from `ctl list`, over the run) and the passes (chaining stages) of the busiest
//! composite. Instance i draws `MODELS[i % 4]`: Debian's glmark2-data has the thesis' horse,
//! cat and bunny, but neither its dragon nor its buddha, so the asteroid stands in for both.
//!
//! The data path of the server/client rendering split (seed 000): per model, one instance's
//! command-stream bytes per frame (from `ctl list`, in the steady state) beside the colour and
//! depth bytes per frame that rendering in the client would ship instead.
//!
//! Figures 5.6 and 5.7 are the two crossing triangles of `compositor::figures`, composited with
//! the far and the near light (`tests/compositor/figures.rs` checks them against the reference).

use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use strata_client::ControlConnection;
use strata_protocol::control::{OutputRow, SurfaceRow};
use strata_protocol::handshake::{ControlReply, ControlRequest};

use crate::glmark2::{finish, prepare, size, Side};
use crate::plot::{line_plot, Series};
use crate::transport::start_daemon_with;

/// The models instance i draws, `MODELS[i % 4]`.
const MODELS: [&str; 4] = ["horse", "cat", "bunny", "asteroid-low"];

/// `strata-bench thesis` options.
#[derive(clap::Args)]
pub struct Args {
    /// Print only the final JSON line.
    #[arg(long)]
    json: bool,
    /// Seconds each glmark2 instance runs.
    #[arg(long, default_value_t = 5)]
    duration: u32,
    /// Most concurrent instances (the thesis went to 10).
    #[arg(long, default_value_t = 10)]
    max_instances: u32,
    /// Textures per compositor pass (the thesis' i.MX6 had 8).
    #[arg(long, default_value_t = 8)]
    max_textures: u32,
    /// glmark2 window size, WxH (the thesis' 540×540).
    #[arg(long, default_value = "540x540")]
    size: String,
    /// The daemon's headless output, WxH.
    #[arg(long, default_value = "1920x720")]
    output: String,
    /// Directory holding libEGL.so.1 and libGLESv2.so.2 [default: the libstrata_egl.so cargo
    /// built next to this binary].
    #[arg(long)]
    shim: Option<PathBuf>,
    /// Directory for thesis.json and one PNG per figure.
    #[arg(long, default_value = "target/strata-bench/thesis")]
    out: PathBuf,
    /// One more option for every daemon the benchmark starts (repeatable), e.g.
    /// `--daemon-arg=--devices=shared` to measure the one shared device.
    #[arg(long = "daemon-arg", allow_hyphen_values = true)]
    daemon_args: Vec<String>,
    /// Only these tables (5.1, 5.2, 5.3, 5.4; repeatable) [default: all four].
    #[arg(long = "table")]
    tables: Vec<String>,
    /// Skip the data path (one instance per model).
    #[arg(long)]
    no_data_path: bool,
}

/// One table of the evaluation.
struct Table {
    table: &'static str,
    figure: &'static str,
    what: &'static str,
    side: Side,
    compositor: &'static str,
    z_step: f32,
}

const TABLES: [Table; 4] = [
    Table {
        table: "5.1",
        figure: "5.2",
        what: "one z, through Strata",
        side: Side::Strata,
        compositor: "3d",
        z_step: 0.0,
    },
    Table { table: "5.2", figure: "5.3", what: "natively (Mesa)", side: Side::Native, compositor: "-", z_step: 0.0 },
    Table {
        table: "5.3",
        figure: "5.4",
        what: "one z each, through Strata",
        side: Side::Strata,
        compositor: "3d",
        z_step: 1.0,
    },
    Table {
        table: "5.4",
        figure: "5.5",
        what: "2D baseline, one z each",
        side: Side::Strata,
        compositor: "2d",
        z_step: 1.0,
    },
];

/// One row of a table: n instances at once.
#[derive(serde::Serialize)]
struct Row {
    instances: u32,
    fps: Vec<u32>,
    total_fps: f64,
    per_instance_fps: f64,
    /// The compositor's mean milliseconds per composite over the run (Strata only).
    composite_ms: Option<f64>,
    /// Composites during the run (Strata only).
    composites: Option<u64>,
    /// Passes of the busiest composite seen (chaining stages; Strata only).
    stages: Option<u64>,
    /// The compositor's share of the machine while the most instances drew: the CPU time of its
    /// device's threads and of its own thread, over that time on every core (Strata on a CPU
    /// rasterizer only).
    compositor_share: Option<f64>,
}

/// The compositor's busy time so far: its device's, plus its thread's planning and encoding
/// (microseconds).
fn compositor_busy(socket: &std::path::Path) -> Result<u64> {
    let mut c = ControlConnection::connect_beside(socket).context("connecting to the daemon's control socket")?;
    let device = match c.request(&ControlRequest::Stats)? {
        ControlReply::Stats(s) => s.compositor_device.map_or(0, |d| d.busy_us),
        other => bail!("unexpected control reply {other:?}"),
    };
    let (outputs, _) = list(socket)?;
    Ok(device + outputs.iter().map(|o| o.encode_us).sum::<u64>())
}

/// `ctl list`: the daemon's outputs and surfaces.
fn list(socket: &std::path::Path) -> Result<(Vec<OutputRow>, Vec<SurfaceRow>)> {
    let mut c = ControlConnection::connect_beside(socket).context("connecting to the daemon's control socket")?;
    match c.request(&ControlRequest::List)? {
        ControlReply::List { outputs, surfaces, .. } => Ok((outputs, surfaces)),
        other => bail!("unexpected control reply {other:?}"),
    }
}

/// The first output's composites, time spent compositing (µs) and last pass count.
fn output_stats(socket: &std::path::Path) -> Result<(u64, u64, u64)> {
    let (outputs, _) = list(socket)?;
    let o = outputs.first().context("the daemon has no output")?;
    Ok((o.composites, o.composite_us, o.passes))
}

/// One model's data path: the command stream its client sends per frame, beside the image
/// bytes per frame that rendering in the client (seed 000's split) would send instead.
#[derive(serde::Serialize)]
struct DataPath {
    model: &'static str,
    fps: u32,
    /// Command-stream bytes per frame in the steady state (the model's upload excluded).
    stream_bytes_per_frame: f64,
    /// Colour (RGBA8) and depth (32-bit) of the window: what the compositor reads per frame.
    image_bytes_per_frame: u64,
}

/// Everything the runs of one table share.
struct Bench<'a> {
    args: &'a Args,
    display: String,
    shim: PathBuf,
    window: String,
}

impl Bench<'_> {
    fn command(&self, t: &Table, socket: Option<&std::path::Path>, i: u32) -> Command {
        let model = MODELS[i as usize % MODELS.len()];
        let mut cmd = Command::new("glmark2-es2");
        cmd.args(["-b", &format!("build:model={model}:duration={}", self.args.duration), "-s", &self.args.size])
            .env("DISPLAY", &self.display)
            .env_remove("LD_LIBRARY_PATH")
            .env_remove("STRATA_SOCKET")
            .env_remove("STRATA_WINDOW")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped());
        if let (Side::Strata, Some(socket)) = (t.side, socket) {
            cmd.env("LD_LIBRARY_PATH", &self.shim)
                .env("STRATA_SOCKET", socket)
                .env("STRATA_WINDOW", format!("{},{}", self.window, i as f32 * t.z_step));
        }
        cmd
    }

    /// n instances at once; with a daemon, its compositor's figures over the run.
    fn row(&self, t: &Table, socket: Option<&std::path::Path>, n: u32) -> Result<Row> {
        let before = socket.map(output_stats).transpose()?;
        let children: Vec<Child> = (0..n)
            .map(|i| self.command(t, socket, i).spawn().context("starting glmark2-es2"))
            .collect::<Result<_>>()?;
        // Sampled while the instances run: the passes of the busiest composite, and the
        // compositor's busy time while all n draw (the window their frame rates cover).
        let stop = Arc::new(AtomicBool::new(false));
        let sampler = socket.map(|s| {
            let (s, stop) = (s.to_path_buf(), stop.clone());
            std::thread::spawn(move || sample(&s, n, &stop))
        });
        let deadline = Duration::from_secs(u64::from(self.args.duration) * 3 + 120);
        let outcomes: Vec<Result<u32>> = children.into_iter().map(|c| finish(c, deadline).map(|r| r.score)).collect();
        stop.store(true, Ordering::Release);
        let sampled = sampler.and_then(|h| h.join().ok());
        let fps: Vec<u32> = outcomes.into_iter().collect::<Result<_>>()?;
        let after = socket.map(output_stats).transpose()?;
        let cores = std::thread::available_parallelism().map_or(1, |c| c.get()) as f64;
        let compositor_share = sampled.as_ref().and_then(|s| s.share(cores));
        let (composites, composite_ms) = match (before, after) {
            (Some(b), Some(a)) if a.0 > b.0 => {
                let count = a.0 - b.0;
                (Some(count), Some((a.1 - b.1) as f64 / 1000.0 / count as f64))
            }
            _ => (None, None),
        };
        let total: f64 = fps.iter().map(|&f| f64::from(f)).sum();
        Ok(Row {
            instances: n,
            total_fps: total,
            per_instance_fps: total / f64::from(n),
            fps,
            composite_ms,
            composites,
            stages: sampled.map(|s| s.passes),
            compositor_share,
        })
    }
}

/// The compositor's busy time (µs) at an instant.
type Busy = (std::time::Instant, u64);

/// What a row's sampler saw of the daemon.
struct Sampled {
    /// Passes of the busiest composite.
    passes: u64,
    /// Per count c of instances drawing (index c − 1): the compositor's busy time (µs) when at
    /// least c were first seen drawing, and the last time at least c were.
    drawing: Vec<Option<(Busy, Busy)>>,
}

impl Sampled {
    /// The compositor's share of the machine while the most instances drew, over a window of
    /// at least a second (all n, unless the first instance finished before the last had
    /// drawn for that long): its busy time over that window's time on every core.
    fn share(&self, cores: f64) -> Option<f64> {
        self.drawing.iter().rev().flatten().find_map(|&((t0, b0), (t1, b1))| {
            let secs = t1.duration_since(t0).as_secs_f64();
            (secs >= 1.0).then(|| (b1.saturating_sub(b0) as f64 / 1e6 / (secs * cores)).min(1.0))
        })
    }
}

/// Samples the daemon at `socket` every 250 ms until `stop`: the busiest composite's passes,
/// and the compositor's busy time while 1, 2, … `n` surfaces have shown a frame (glmark2
/// reports its frame rate over its drawing, not over its start-up).
fn sample(socket: &std::path::Path, n: u32, stop: &AtomicBool) -> Sampled {
    let mut out = Sampled { passes: 0, drawing: vec![None; n as usize] };
    while !stop.load(Ordering::Acquire) {
        if let Ok((outputs, surfaces)) = list(socket) {
            out.passes = out.passes.max(outputs.first().map_or(0, |o| o.passes));
            let drawing = surfaces.iter().filter(|r| r.frames > 0).count().min(n as usize);
            if drawing > 0 {
                if let Ok(busy) = compositor_busy(socket) {
                    let at = (std::time::Instant::now(), busy);
                    for w in &mut out.drawing[..drawing] {
                        *w = Some(w.map_or((at, at), |(first, _)| (first, at)));
                    }
                }
            }
        }
        std::thread::sleep(Duration::from_millis(250));
    }
    out
}

impl Bench<'_> {
    /// Model `k` alone through the daemon at `socket` (table `t`'s settings), its stream and
    /// frames sampled from `ctl list` while it runs.
    fn data_path(&self, t: &Table, socket: &std::path::Path, k: u32) -> Result<DataPath> {
        let child = self.command(t, Some(socket), k).spawn().context("starting glmark2-es2")?;
        let stop = Arc::new(AtomicBool::new(false));
        let sampler = {
            let (s, stop) = (socket.to_path_buf(), stop.clone());
            std::thread::spawn(move || {
                let mut samples: Vec<(u64, u64)> = Vec::new();
                while !stop.load(Ordering::Acquire) {
                    if let Ok((_, surfaces)) = list(&s) {
                        if let Some(r) = surfaces.first() {
                            samples.push((r.frames, r.stream_bytes));
                        }
                    }
                    std::thread::sleep(Duration::from_millis(250));
                }
                samples
            })
        };
        let deadline = Duration::from_secs(u64::from(self.args.duration) * 3 + 120);
        let run = finish(child, deadline);
        stop.store(true, Ordering::Release);
        let samples = sampler.join().unwrap_or_default();
        let fps = run?.score;
        // The steady state: from a quarter of the way in (the model is uploaded by then) to
        // the last sample.
        let live: Vec<&(u64, u64)> = samples.iter().filter(|s| s.0 > 0).collect();
        let (Some(first), Some(last)) = (live.get(live.len() / 4), live.last()) else {
            bail!("{} ran too briefly to sample its stream", MODELS[k as usize]);
        };
        if last.0 <= first.0 {
            bail!("{} swapped no frames while sampled", MODELS[k as usize]);
        }
        let (w, h) = size(&self.args.size)?;
        Ok(DataPath {
            model: MODELS[k as usize],
            fps,
            stream_bytes_per_frame: (last.1 - first.1) as f64 / (last.0 - first.0) as f64,
            image_bytes_per_frame: u64::from(w) * u64::from(h) * 8,
        })
    }
}

/// Runs the evaluation and prints its tables; the last line is JSON.
pub fn run(args: &Args) -> Result<()> {
    if args.duration == 0 || args.max_instances == 0 {
        bail!("--duration and --max-instances must be positive");
    }
    let (win_w, win_h) = size(&args.size)?;
    let (out_w, out_h) = size(&args.output)?;
    let (tmp, shim, x) = prepare(args.shim.as_deref())?;
    let window = format!("{},{}", out_w.saturating_sub(win_w) / 2, out_h.saturating_sub(win_h) / 2);
    let bench = Bench { args, display: x.display.clone(), shim, window };

    let chosen: Vec<&Table> =
        TABLES.iter().filter(|t| args.tables.is_empty() || args.tables.iter().any(|n| n == t.table)).collect();
    let pb = if args.json {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(
            chosen.len() as u64 * u64::from(args.max_instances)
                + if args.no_data_path { 0 } else { MODELS.len() as u64 },
        )
    };
    pb.set_style(
        ProgressStyle::with_template("{msg:>28} [{bar:40}] {pos}/{len} {elapsed} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    // Every table's daemon up front, so that each n runs table after table: native and
    // Strata at the same n then see the machine in the same state (minutes apart, its load
    // and clocks drift more than the figures differ).
    let mut daemons = Vec::new();
    for t in &chosen {
        let log = tmp.0.join(format!("daemon-{}.log", t.table));
        let daemon = match t.side {
            Side::Native => None,
            Side::Strata => Some(start_daemon_with(
                strata_server::ExecutorKind::Gles,
                &[
                    "--output".into(),
                    format!("headless:thesis={out_w}x{out_h}"),
                    "--compositor".into(),
                    t.compositor.into(),
                    "--max-textures".into(),
                    args.max_textures.to_string(),
                ]
                .into_iter()
                .chain(args.daemon_args.iter().cloned())
                .collect::<Vec<_>>(),
                Some(&log),
            )?),
        };
        daemons.push((daemon, log));
    }
    // The data path, with the first daemon (one model at a time).
    let mut paths = Vec::new();
    if let Some((t, (Some(d), _))) = chosen.iter().zip(&daemons).find(|(_, (d, _))| d.is_some()) {
        for k in 0..MODELS.len() as u32 {
            if args.no_data_path {
                break;
            }
            pb.set_message(format!("data path: {}", MODELS[k as usize]));
            paths.push(bench.data_path(t, &d.1, k)?);
            pb.inc(1);
        }
    }
    let mut rows: Vec<Vec<Row>> = chosen.iter().map(|_| Vec::new()).collect();
    for n in 1..=args.max_instances {
        for ((t, (daemon, log)), rows) in chosen.iter().zip(&daemons).zip(&mut rows) {
            pb.set_message(format!("table {}: {n} instance(s)", t.table));
            let row = bench.row(t, daemon.as_ref().map(|d| d.1.as_path()), n).map_err(|e| {
                let tail = std::fs::read_to_string(log).unwrap_or_default();
                let tail: Vec<&str> = tail.lines().rev().take(20).collect();
                anyhow::anyhow!("{e:#}\ndaemon log (last lines, newest first):\n{}", tail.join("\n"))
            })?;
            rows.push(row);
            pb.inc(1);
        }
    }
    drop(daemons);
    let tables: Vec<(&Table, Vec<Row>)> = chosen.into_iter().zip(rows).collect();
    pb.finish_and_clear();
    drop(x);
    report(args, &tables, &paths)
}

/// Figures 5.6 and 5.7: the two crossing triangles composited by the GPU compositor with the
/// far and the near light, as PNGs in `dir`.
fn lit_triangles(dir: &std::path::Path) -> Result<Vec<PathBuf>> {
    use strata_compositor::figures::{far_light, near_light, two_triangles};
    use strata_compositor::reference::upload;
    use strata_compositor::{Compositor, Layer};
    let (w, h) = (960u32, 540u32);
    let gpu = strata_device::Gpu::open().context("opening the GPU for figures 5.6 and 5.7")?;
    let mut comp = Compositor::new(gpu.clone(), None).context("creating the compositor")?;
    let layers = two_triangles(w, h);
    let up: Vec<_> = layers.iter().map(|l| upload(&gpu, l)).collect();
    let gl: Vec<Layer<'_>> = layers.iter().zip(&up).map(|(l, u)| u.layer(l)).collect();
    let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let out = crate::composite::texture(&gpu, w, h, wgpu::TextureFormat::Rgba8Unorm, usage);
    let mut written = Vec::new();
    for (figure, light) in [("5-6", far_light()), ("5-7", near_light())] {
        comp.composite(&gl, &light, &out, [0.0, 0.0, 0.0, 1.0], None).context("compositing the figure")?;
        let rgba = gpu.read_rgba8(&out, [0, 0, w, h]).context("reading the figure back")?;
        let img = image::RgbaImage::from_raw(w, h, rgba).context("figure image of the wrong size")?;
        let path = dir.join(format!("figure-{figure}.png"));
        img.save(&path).with_context(|| format!("writing {}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// Prints the tables, writes thesis.json and the figures.
fn report(args: &Args, tables: &[(&Table, Vec<Row>)], paths: &[DataPath]) -> Result<()> {
    let opt = |v: Option<f64>, prec: usize| v.map_or_else(|| "-".to_string(), |v| format!("{v:.prec$}"));
    if !args.json {
        println!(
            "glmark2-es2 -b build:model=M:duration={} -s {}, M cycling {MODELS:?}; headless {} output, --max-textures {}",
            args.duration, args.size, args.output, args.max_textures
        );
        let native = tables.iter().find(|(t, _)| t.side == Side::Native).map(|(_, rows)| rows);
        for (t, rows) in tables {
            println!();
            println!("Table {} (figure {}): {}", t.table, t.figure, t.what);
            println!(
                "{:>3} {:>10} {:>14} {:>13} {:>7} {:>7} {:>9} {:>9}  fps of each",
                "n", "total fps", "per instance", "composite ms", "stages", "comp %", "x native", "bound x"
            );
            for r in rows {
                let stages = r.stages.map_or_else(|| "-".to_string(), |s| s.to_string());
                let native_fps =
                    native.and_then(|n| n.iter().find(|x| x.instances == r.instances)).map(|x| x.total_fps);
                let vs = native_fps.filter(|_| t.side == Side::Strata).map(|n| r.total_fps / n.max(1e-9));
                // What the compositor's share leaves the clients: 0.95 × (1 − share).
                let bound = r.compositor_share.map(|s| 0.95 * (1.0 - s));
                println!(
                    "{:>3} {:>10.0} {:>14.1} {:>13} {:>7} {:>7} {:>9} {:>9}  {:?}",
                    r.instances,
                    r.total_fps,
                    r.per_instance_fps,
                    opt(r.composite_ms, 2),
                    stages,
                    opt(r.compositor_share.map(|s| s * 100.0), 1),
                    opt(vs, 2),
                    opt(bound, 2),
                    r.fps
                );
            }
        }
        println!();
        println!("Data path (seed 000's split): one instance per model through Strata");
        println!(
            "{:<14} {:>6} {:>22} {:>22} {:>8}",
            "model", "fps", "stream bytes/frame", "image bytes/frame", "image/stream"
        );
        for p in paths {
            println!(
                "{:<14} {:>6} {:>22.0} {:>22} {:>8.0}",
                p.model,
                p.fps,
                p.stream_bytes_per_frame,
                p.image_bytes_per_frame,
                p.image_bytes_per_frame as f64 / p.stream_bytes_per_frame.max(1.0)
            );
        }
    }
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating {}", args.out.display()))?;
    let doc = serde_json::json!({
        "models": MODELS,
        "duration_s": args.duration,
        "size": args.size,
        "output": args.output,
        "max_textures": args.max_textures,
        "data_path": paths,
        "tables": tables.iter().map(|(t, rows)| serde_json::json!({
            "table": t.table, "figure": t.figure, "what": t.what, "compositor": t.compositor, "z_step": t.z_step, "rows": rows,
        })).collect::<Vec<_>>(),
    });
    let json_path = args.out.join("thesis.json");
    std::fs::write(&json_path, serde_json::to_string_pretty(&doc)?)
        .with_context(|| format!("writing {}", json_path.display()))?;
    let xy = |rows: &[Row], f: &dyn Fn(&Row) -> Option<f64>| -> Vec<(f64, f64)> {
        rows.iter().filter_map(|r| Some((f64::from(r.instances), f(r)?))).collect()
    };
    let native = tables.iter().find(|(t, _)| t.side == Side::Native).map(|(_, rows)| rows);
    let mut written = Vec::new();
    for (t, rows) in tables {
        let mut series = vec![
            Series { name: "total fps".into(), points: xy(rows, &|r| Some(r.total_fps)), reference: false },
            Series {
                name: "fps per instance".into(),
                points: xy(rows, &|r| Some(r.per_instance_fps)),
                reference: false,
            },
        ];
        if let (Side::Strata, Some(native)) = (t.side, native) {
            series.push(Series {
                name: "native: total fps".into(),
                points: xy(native, &|r| Some(r.total_fps)),
                reference: true,
            });
        }
        let png = args.out.join(format!("figure-{}.png", t.figure.replace('.', "-")));
        let title = format!("Figure {} (table {}): n glmark2-es2 instances, {}", t.figure, t.table, t.what);
        line_plot(&png, &title, "concurrent instances (n)", "frames per second", &series)?;
        written.push(png);
    }
    let composite: Vec<Series> = tables
        .iter()
        .filter(|(t, _)| t.side == Side::Strata)
        .map(|(t, rows)| Series {
            name: format!("table {}: {}", t.table, t.what),
            points: xy(rows, &|r| r.composite_ms),
            reference: false,
        })
        .collect();
    let png = args.out.join("composite-ms.png");
    line_plot(
        &png,
        "Compositor: milliseconds per composite",
        "concurrent instances (n)",
        "ms per composite",
        &composite,
    )?;
    written.push(png);
    written.extend(lit_triangles(&args.out)?);
    if !args.json {
        println!();
        println!("written: {}", json_path.display());
        for p in &written {
            println!("         {}", p.display());
        }
    }
    let summary = serde_json::json!({
        "benchmark": "thesis",
        "json": json_path,
        "figures": written,
        "total_fps": tables.iter().map(|(t, rows)| (t.table, rows.iter().map(|r| r.total_fps).collect::<Vec<_>>()))
            .collect::<std::collections::BTreeMap<_, _>>(),
    });
    println!("{summary}");
    Ok(())
}

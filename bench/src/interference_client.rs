//! The clients `strata-bench interference` runs: the instrument cluster (`ic`), which draws a
//! dial with a moving needle at swap interval 1 and records when each swap returns, and two
//! head-unit loads (`huge-draw`, `upload`) that swap unthrottled and count their frames.
//! Each stops after `--seconds`, or at SIGTERM/SIGINT, and writes its result as JSON.

use std::io::{BufRead, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{anyhow, Context, Result};
use plotters::prelude::*;
use serde::{Deserialize, Serialize};
use strata_client::setup::{egl_context, link_program, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::{Blob, Slice, Text};

const GL_ARRAY_BUFFER: u32 = 0x8892;
const GL_STATIC_DRAW: u32 = 0x88E4;
const GL_FLOAT: u32 = 0x1406;
const GL_TRIANGLE_FAN: u32 = 0x0006;
const GL_TRIANGLE_STRIP: u32 = 0x0005;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_TEXTURE_MIN_FILTER: u32 = 0x2801;
const GL_TEXTURE_MAG_FILTER: u32 = 0x2800;
const GL_LINEAR: i32 = 0x2601;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

/// Frames drawn before the IC starts recording.
pub const WARM_UP: usize = 10;
/// Side of the uploaded textures (RGBA8: 16 MiB each, four per frame).
const UPLOAD_SIDE: i32 = 2048;

/// Set by SIGTERM or SIGINT: finish the frame, write the result, leave.
static STOP: AtomicBool = AtomicBool::new(false);

extern "C" fn on_signal(_: libc::c_int) {
    STOP.store(true, Ordering::Relaxed);
}

/// What an interference client does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Role {
    /// The instrument cluster: a dial at swap interval 1, every swap's return time recorded.
    Ic,
    /// A head unit drawing one fullscreen quad per frame with a very long fragment loop.
    HugeDraw,
    /// A head unit uploading 64 MiB of texels per frame and drawing one textured quad.
    Upload,
    /// Not a client: one busy thread per core, the CPU contention no daemon can schedule.
    CpuHog,
    /// A head unit that opens sessions until the daemon refuses one, each drawing the huge
    /// draw in a small window of its own.
    SessionFlood,
}

/// The `interference-client` arguments.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// What to do.
    #[arg(long, value_enum)]
    pub role: Role,
    /// Socket of the daemon.
    #[arg(long)]
    pub socket: PathBuf,
    /// Seconds to run (the IC: seconds recorded, after warm-up).
    #[arg(long, default_value_t = 20.0)]
    pub seconds: f64,
    /// Where to write the result (JSON).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The window surface: x,y,WxH.
    #[arg(long)]
    pub window: Option<String>,
    /// Fragment-loop iterations of `huge-draw` (sets the cost of its one draw).
    #[arg(long, default_value_t = 50)]
    pub iterations: u32,
    /// IC: print `measuring` and `end` on stdout around the recorded time, and keep drawing
    /// after it (unrecorded) until stdin closes, so the caller can read the daemon's counters
    /// while the dial is still live.
    #[arg(long)]
    pub hold: bool,
}

/// What a client writes to `--out`.
#[derive(Debug, Default, Serialize, Deserialize)]
pub struct Outcome {
    /// The role, as given.
    pub role: String,
    /// Frames swapped in the measured time.
    pub frames: u64,
    /// The measured time, seconds.
    pub seconds: f64,
    /// Frames per second over the measured time.
    pub fps: f64,
    /// IC only: intervals between successive swap returns after warm-up, ms.
    pub frame_times_ms: Vec<f64>,
}

/// Runs one interference client.
pub fn run(args: &Args) -> Result<()> {
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe.
    unsafe {
        libc::signal(libc::SIGTERM, on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t);
        libc::signal(libc::SIGINT, on_signal as extern "C" fn(libc::c_int) as libc::sighandler_t);
    }
    if args.role == Role::Ic {
        // As the instrument cluster's own process would: the high class's short slice, so that
        // its thread preempts longer-slice work sooner when its swap returns.
        let slice = strata_device::slice_for(strata_protocol::control::Priority::High);
        strata_device::set_thread_slice(0, slice);
    }
    let (name, default_window, interval) = match args.role {
        Role::Ic => ("ic", "0,0,320x320", 1),
        Role::HugeDraw | Role::Upload => ("hu", "400,0,1280x720", 0),
        Role::CpuHog => return cpu_hog(args),
        Role::SessionFlood => return write_outcome(args, &session_flood(args)?),
    };
    let rect = parse_window(args.window.as_deref().unwrap_or(default_window))?;
    let z = if args.role == Role::Ic { 0.5 } else { 0.6 };
    let opts =
        ConnectOptions { socket: args.socket.clone(), name: name.into(), role: name.into(), ..Default::default() };
    let mut gl = Connection::connect(&opts).with_context(|| format!("connecting to {}", args.socket.display()))?;
    let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Window { rect, z })?;
    gl.eglSwapInterval(cur.display, interval)?.map_err(|e| anyhow!("eglSwapInterval: EGL error {e:#x}"))?;
    gl.glViewport(0, 0, rect[2], rect[3])?;
    let outcome = match args.role {
        Role::Ic => ic(&mut gl, cur, args)?,
        Role::HugeDraw => huge_draw(&mut gl, cur, args)?,
        Role::Upload => upload(&mut gl, cur, args)?,
        Role::CpuHog | Role::SessionFlood => unreachable!("handled before connecting"),
    };
    write_outcome(args, &outcome)
}

/// Writes `outcome` to `--out`, if given.
fn write_outcome(args: &Args, outcome: &Outcome) -> Result<()> {
    if let Some(out) = &args.out {
        std::fs::write(out, serde_json::to_string(outcome)?).with_context(|| format!("writing {}", out.display()))?;
    }
    Ok(())
}

/// Opens sessions named `hu` until the daemon refuses one (at most 256), each on a thread of
/// its own drawing the huge draw unthrottled in a 160×90 window; their frames together.
fn session_flood(args: &Args) -> Result<Outcome> {
    let start = Instant::now();
    let frames = std::sync::atomic::AtomicU64::new(0);
    std::thread::scope(|s| -> Result<()> {
        let mut sessions = 0;
        let refusal = loop {
            if sessions == 256 {
                break "none: 256 sessions opened".to_string();
            }
            let opts = ConnectOptions {
                socket: args.socket.clone(),
                name: "hu".into(),
                role: "hu".into(),
                ..Default::default()
            };
            let mut gl = match Connection::connect(&opts) {
                Ok(gl) => gl,
                Err(e) => break e.to_string(),
            };
            let rect = [400 + (sessions % 8) * 160, (sessions / 8 % 8) * 90, 160, 90];
            let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Window { rect, z: 0.6 })?;
            gl.eglSwapInterval(cur.display, 0)?.map_err(|e| anyhow!("eglSwapInterval: EGL error {e:#x}"))?;
            gl.glViewport(0, 0, rect[2], rect[3])?;
            let frames = &frames;
            s.spawn(move || match huge_draw(&mut gl, cur, args) {
                Ok(o) => frames.fetch_add(o.frames, Ordering::Relaxed),
                Err(e) => {
                    eprintln!("session-flood: a session failed: {e:#}");
                    0
                }
            });
            sessions += 1;
        };
        eprintln!("session-flood: {sessions} sessions open; the next was refused: {refusal}");
        Ok(())
    })?;
    let seconds = start.elapsed().as_secs_f64();
    let frames = frames.load(Ordering::Relaxed);
    let fps = frames as f64 / seconds.max(1e-9);
    Ok(Outcome { role: "session-flood".into(), frames, seconds, fps, frame_times_ms: Vec::new() })
}

/// Spins one thread per core until `--seconds` pass or a signal stops it.
fn cpu_hog(args: &Args) -> Result<()> {
    let start = Instant::now();
    let limit = Duration::from_secs_f64(args.seconds.max(0.0));
    let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..cores {
            s.spawn(|| {
                let mut x = 0u64;
                while !STOP.load(Ordering::Relaxed) && start.elapsed() < limit {
                    for i in 0..100_000u64 {
                        x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(i));
                    }
                }
            });
        }
    });
    let seconds = start.elapsed().as_secs_f64();
    let outcome = Outcome { role: "cpuhog".into(), frames: 0, seconds, fps: 0.0, frame_times_ms: Vec::new() };
    if let Some(out) = &args.out {
        std::fs::write(out, serde_json::to_string(&outcome)?).with_context(|| format!("writing {}", out.display()))?;
    }
    Ok(())
}

/// Parses `x,y,WxH` into a window rectangle.
fn parse_window(s: &str) -> Result<[i32; 4]> {
    let bad = || anyhow!("--window {s:?} is not x,y,WxH");
    let mut parts = s.split(',');
    let (x, y, wh) = (parts.next().ok_or_else(bad)?, parts.next().ok_or_else(bad)?, parts.next().ok_or_else(bad)?);
    let (w, h) = wh.split_once('x').ok_or_else(bad)?;
    let n = |v: &str| v.trim().parse::<i32>().map_err(|_| bad());
    let r = [n(x)?, n(y)?, n(w)?, n(h)?];
    if parts.next().is_some() || r[2] <= 0 || r[3] <= 0 {
        return Err(bad());
    }
    Ok(r)
}

fn swap(gl: &mut Connection, cur: Current) -> Result<()> {
    gl.eglSwapBuffers(cur.display, cur.surface)?.map_err(|e| anyhow!("eglSwapBuffers: EGL error {e:#x}"))
}

/// Puts `vertices` (x, y pairs) into buffer `name` as attribute 0.
fn vertices(gl: &mut Connection, name: u32, vertices: &[f32]) -> Result<()> {
    gl.glGenBuffers(Slice::new(&[name]))?;
    gl.glBindBuffer(GL_ARRAY_BUFFER, name)?;
    let bytes: &[u8] = bytemuck::cast_slice(vertices);
    gl.glBufferData(GL_ARRAY_BUFFER, bytes.len() as i64, Some(Blob::borrowed(bytes)), GL_STATIC_DRAW)?;
    gl.glVertexAttribPointer(0, 2, GL_FLOAT, false, 8, 0)?;
    gl.glEnableVertexAttribArray(0)?;
    Ok(())
}

const DIAL_VS: &str = "attribute vec2 a_pos;
uniform float u_angle;
uniform float u_scale;
void main() {
    float c = cos(u_angle);
    float s = sin(u_angle);
    vec2 p = a_pos * u_scale;
    gl_Position = vec4(c * p.x - s * p.y, s * p.x + c * p.y, 0.0, 1.0);
}";

const DIAL_FS: &str = "precision mediump float;
uniform vec4 u_color;
void main() {
    gl_FragColor = u_color;
}";

/// Vertices of the dial in one buffer: a disc as a triangle fan (centre and `SEGMENTS + 1`
/// rim points), then the needle as a thin strip pointing up.
const SEGMENTS: usize = 48;

fn dial_vertices() -> Vec<f32> {
    let mut v = vec![0.0, 0.0];
    for i in 0..=SEGMENTS {
        let a = i as f32 / SEGMENTS as f32 * std::f32::consts::TAU;
        v.extend([a.cos(), a.sin()]);
    }
    v.extend([-0.025, -0.12, 0.025, -0.12, -0.008, 0.85, 0.008, 0.85]);
    v
}

/// The instrument cluster: dial, needle, hub, swap; records each swap's return.
fn ic(gl: &mut Connection, cur: Current, args: &Args) -> Result<Outcome> {
    let p = link_program(gl, (1, 2, 3), DIAL_VS, DIAL_FS, &["a_pos"])?;
    let angle = gl.glGetUniformLocation(p, Text::borrowed("u_angle"))?;
    let scale = gl.glGetUniformLocation(p, Text::borrowed("u_scale"))?;
    let color = gl.glGetUniformLocation(p, Text::borrowed("u_color"))?;
    vertices(gl, 10, &dial_vertices())?;
    gl.glClearColor(0.02, 0.02, 0.05, 1.0)?;
    let fan = (SEGMENTS + 2) as i32;
    let released = Arc::new(AtomicBool::new(false));
    if args.hold {
        let released = released.clone();
        std::thread::spawn(move || {
            let _ = std::io::copy(&mut std::io::stdin().lock(), &mut std::io::sink());
            released.store(true, Ordering::Relaxed);
        });
    }
    let say = |what: &str| -> Result<()> {
        if args.hold {
            let mut out = std::io::stdout().lock();
            writeln!(out, "{what}")?;
            out.flush()?;
        }
        Ok(())
    };
    let measured = Duration::from_secs_f64(args.seconds.max(0.0));
    let mut returns: Vec<Instant> = Vec::new();
    let mut started: Option<Instant> = None;
    let mut ended: Option<Instant> = None;
    for f in 0u32.. {
        gl.glClear(GL_COLOR_BUFFER_BIT)?;
        gl.glUniform1f(angle, 0.0)?;
        gl.glUniform1f(scale, 0.95)?;
        gl.glUniform4f(color, 0.25, 0.27, 0.32, 1.0)?;
        gl.glDrawArrays(GL_TRIANGLE_FAN, 0, fan)?;
        gl.glUniform1f(angle, -(f as f32 * 0.05) % std::f32::consts::TAU)?;
        gl.glUniform1f(scale, 0.9)?;
        gl.glUniform4f(color, 1.0, 0.35, 0.1, 1.0)?;
        gl.glDrawArrays(GL_TRIANGLE_STRIP, fan, 4)?;
        gl.glUniform1f(scale, 0.08)?;
        gl.glUniform4f(color, 0.9, 0.9, 0.9, 1.0)?;
        gl.glDrawArrays(GL_TRIANGLE_FAN, 0, fan)?;
        swap(gl, cur)?;
        let now = Instant::now();
        if ended.is_none() {
            returns.push(now);
        }
        if started.is_none() && returns.len() > WARM_UP {
            started = Some(now);
            say("measuring")?;
        }
        let stop = STOP.load(Ordering::Relaxed);
        if ended.is_none() && (stop || started.is_some_and(|s| now - s >= measured)) {
            ended = Some(now);
            say("end")?;
        }
        if let Some(e) = ended {
            // Held: keep the dial live until released (at most 60 s more).
            if !args.hold || stop || released.load(Ordering::Relaxed) || now - e > Duration::from_secs(60) {
                break;
            }
        }
    }
    let frame_times_ms: Vec<f64> =
        returns.windows(2).skip(WARM_UP).map(|w| (w[1] - w[0]).as_secs_f64() * 1e3).collect();
    let seconds = frame_times_ms.iter().sum::<f64>() / 1e3;
    Ok(Outcome {
        role: "ic".into(),
        frames: frame_times_ms.len() as u64,
        seconds,
        fps: frame_times_ms.len() as f64 / seconds.max(1e-9),
        frame_times_ms,
    })
}

const QUAD_VS: &str = "attribute vec2 a_pos;
varying vec2 v_uv;
void main() {
    v_uv = a_pos * 0.5 + 0.5;
    gl_Position = vec4(a_pos, 0.0, 1.0);
}";

/// The huge draw's fragment shader; `ITERATIONS` is defined in front of it.
const HUGE_FS: &str = "precision highp float;
varying vec2 v_uv;
void main() {
    vec2 z = v_uv;
    float acc = 0.0;
    for (int i = 0; i < ITERATIONS; i++) {
        z = vec2(sin(z.x * 3.1 + z.y), cos(z.y * 2.7 - z.x)) * 0.98 + v_uv * 0.02;
        acc += z.x * z.y;
    }
    gl_FragColor = vec4(fract(acc), z * 0.5 + 0.5, 1.0);
}";

const TEXTURE_FS: &str = "precision mediump float;
varying vec2 v_uv;
uniform sampler2D u_tex;
void main() {
    gl_FragColor = texture2D(u_tex, v_uv);
}";

const QUAD: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];

/// Swaps `frame` until `--seconds` pass or a signal comes; returns the frame rate.
fn unthrottled(
    gl: &mut Connection,
    cur: Current,
    args: &Args,
    mut frame: impl FnMut(&mut Connection, u64) -> Result<()>,
) -> Result<Outcome> {
    let start = Instant::now();
    let limit = Duration::from_secs_f64(args.seconds.max(0.0));
    let mut frames = 0u64;
    while !STOP.load(Ordering::Relaxed) && start.elapsed() < limit {
        frame(gl, frames)?;
        swap(gl, cur)?;
        frames += 1;
    }
    let seconds = start.elapsed().as_secs_f64();
    let role = format!("{:?}", args.role).to_lowercase();
    Ok(Outcome { role, frames, seconds, fps: frames as f64 / seconds.max(1e-9), frame_times_ms: Vec::new() })
}

/// One fullscreen quad per frame whose every fragment runs a long loop.
fn huge_draw(gl: &mut Connection, cur: Current, args: &Args) -> Result<Outcome> {
    let fs = format!("#define ITERATIONS {}\n{HUGE_FS}", args.iterations.max(1));
    link_program(gl, (1, 2, 3), QUAD_VS, &fs, &["a_pos"])?;
    vertices(gl, 10, &QUAD)?;
    unthrottled(gl, cur, args, |gl, _| {
        gl.glDrawArrays(GL_TRIANGLE_STRIP, 0, 4)?;
        Ok(())
    })
}

/// Four 2048² RGBA8 textures (64 MiB) re-uploaded per frame, one of them drawn.
fn upload(gl: &mut Connection, cur: Current, args: &Args) -> Result<Outcome> {
    let p = link_program(gl, (1, 2, 3), QUAD_VS, TEXTURE_FS, &["a_pos"])?;
    let sampler = gl.glGetUniformLocation(p, Text::borrowed("u_tex"))?;
    gl.glUniform1i(sampler, 0)?;
    vertices(gl, 10, &QUAD)?;
    let names = [20, 21, 22, 23];
    gl.glGenTextures(Slice::new(&names))?;
    for &t in &names {
        gl.glBindTexture(GL_TEXTURE_2D, t)?;
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR)?;
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR)?;
        let (w, h) = (UPLOAD_SIDE, UPLOAD_SIDE);
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, None)?;
    }
    let side = UPLOAD_SIDE as usize;
    let mut texels: Vec<u8> = (0..side * side * 4).map(|i| ((i / 4) % 251) as u8).collect();
    unthrottled(gl, cur, args, |gl, f| {
        // A different first row each frame, so no two uploads are alike.
        texels[..side * 4].fill(f as u8);
        for &t in &names {
            gl.glBindTexture(GL_TEXTURE_2D, t)?;
            let data = Blob::borrowed(&texels);
            let s = UPLOAD_SIDE;
            gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, s, s, GL_RGBA, GL_UNSIGNED_BYTE, data)?;
        }
        gl.glBindTexture(GL_TEXTURE_2D, names[(f % 4) as usize])?;
        gl.glDrawArrays(GL_TRIANGLE_STRIP, 0, 4)?;
        Ok(())
    })
}

/// Reads an [`Outcome`] a client wrote.
pub fn read_outcome(path: &Path) -> Result<Outcome> {
    let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    serde_json::from_str(&text).with_context(|| format!("parsing {}", path.display()))
}

/// Lines a held IC prints, read on a thread so the caller can wait with a timeout.
pub fn lines(stdout: std::process::ChildStdout) -> std::sync::mpsc::Receiver<String> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stdout).lines().map_while(Result::ok) {
            if tx.send(line.trim().to_string()).is_err() {
                break;
            }
        }
    });
    rx
}

/// A summary of frame times.
#[derive(Debug, Clone, Serialize)]
pub struct FrameStats {
    /// Frames measured.
    pub frames: u64,
    /// Median frame time, ms.
    pub p50_ms: f64,
    /// 99th percentile, ms.
    pub p99_ms: f64,
    /// Longest, ms.
    pub max_ms: f64,
    /// Mean, ms.
    pub mean_ms: f64,
    /// Frames longer than the deadline.
    pub client_misses: u64,
}

impl FrameStats {
    /// Summarises `times` (ms) against a deadline of `deadline_ms`.
    pub fn of(times: &[f64], deadline_ms: f64) -> FrameStats {
        let mut sorted = times.to_vec();
        sorted.sort_by(f64::total_cmp);
        FrameStats {
            frames: sorted.len() as u64,
            p50_ms: percentile(&sorted, 0.50),
            p99_ms: percentile(&sorted, 0.99),
            max_ms: sorted.last().copied().unwrap_or(f64::NAN),
            mean_ms: sorted.iter().sum::<f64>() / sorted.len().max(1) as f64,
            client_misses: sorted.iter().filter(|&&t| t > deadline_ms).count() as u64,
        }
    }
}

/// The `q` quantile of sorted values (nearest rank).
pub fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let rank = (q * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

/// Font files tried for the plot's labels (Debian's fonts-dejavu-core).
const FONTS: [&str; 2] = ["/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"];

/// Writes frame-time CDFs to `path`: one line per named phase, log-scale x, the deadline
/// dashed.
pub fn plot_cdf(path: &Path, phases: &[(&str, &[f64])], seconds: f64, deadline_ms: f64) -> Result<()> {
    let bytes = FONTS.iter().find_map(|p| std::fs::read(p).ok()).context("no font for plot labels")?;
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
        .map_err(|_| anyhow!("the plot's font did not load"))?;
    let all = phases.iter().flat_map(|p| p.1.iter().copied()).filter(|t| *t > 0.0);
    let (lo, hi) = all.fold((f64::MAX, f64::MIN), |(a, b), t| (a.min(t), b.max(t)));
    let (lo, hi) = if lo <= hi { (lo * 0.9, (hi * 1.1).max(deadline_ms * 1.2)) } else { (1.0, 100.0) };
    let root = BitMapBackend::new(path, (960, 540)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(format!("IC frame times beside each HU load ({seconds} s each)"), ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d((lo..hi).log_scale(), 0.0..1.0)?;
    chart
        .configure_mesh()
        .x_desc("frame time (ms, log scale)")
        .y_desc("fraction of frames at most")
        .x_label_formatter(&|x| format!("{x:.0}"))
        .label_style(("sans-serif", 15))
        .draw()?;
    let palette = [
        RGBColor(0, 0, 0),
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
    ];
    for (i, p) in phases.iter().enumerate() {
        let mut sorted: Vec<f64> = p.1.iter().copied().filter(|t| *t > 0.0).collect();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let step = (n / 500).max(1);
        let mut points: Vec<(f64, f64)> =
            sorted.iter().enumerate().step_by(step).map(|(k, &t)| (t, (k + 1) as f64 / n as f64)).collect();
        if let Some(&last) = sorted.last() {
            points.push((last, 1.0));
        }
        let (color, p99) = (palette[i % palette.len()], percentile(&sorted, 0.99));
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(2)))?
            .label(format!("{} (p99 {p99:.1} ms)", p.0))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2)));
    }
    let grey = RGBColor(120, 120, 120);
    chart
        .draw_series(DashedLineSeries::new([(deadline_ms, 0.0), (deadline_ms, 1.0)], 6, 4, grey.stroke_width(1)))?
        .label(format!("deadline {deadline_ms:.1} ms"))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], grey));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .position(SeriesLabelPosition::LowerRight)
        .draw()?;
    root.present().with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_parses() {
        assert_eq!(parse_window("400,0,1280x720").ok(), Some([400, 0, 1280, 720]));
        assert!(parse_window("400,0").is_err());
        assert!(parse_window("1,2,0x5").is_err());
    }

    #[test]
    fn percentiles_are_nearest_rank() {
        let v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(percentile(&v, 0.5), 50.0);
        assert_eq!(percentile(&v, 0.99), 99.0);
        assert!(percentile(&[], 0.5).is_nan());
    }
}

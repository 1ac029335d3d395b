//! Rows for the depth format and reversed-Z as the daemon runs them (`stratad serve
//! --depth-format FORMAT [--reversed-z]`), end to end: one daemon per setting, two client
//! connections in this process, each a full-output window surface declaring its perspective
//! projection (`PLANES`), drawing the precision scene's plane as a quad in eye space through
//! GL's standard perspective matrix for that projection. The composite (lighting off) is read
//! back with a screenshot and each pixel's surface (by its colour) compared with the f64
//! nearest one (`exact_winners`):
//! - `wrong@ln`, `wrong all`: the fraction of pixels within `BAND` of an intersection line, and
//!   of the whole output, that show the other surface;
//! - `ms`: the client's frame time: a clear, the plane's draw, `eglSwapBuffers` (swap interval
//!   0) and a `glFinish`, to its reply (the frame rendered on the daemon's device), the median
//!   over both surfaces' frames;
//!
//! The clients use the depth-32 config, which has no stencil, so every format applies (a
//! config with stencil keeps Depth24PlusStencil8 under `16unorm`); `24plus` is the depth
//! precision of the depth-24 config every client asking for depth gets by default.
//! - the stored depth cannot be read back through the daemon: `depth max/p99` are NaN and
//!   `fmt@ln`, `c.max`, `c.mean` are not measured.

use std::path::Path;

use std::time::{Duration, Instant};

use anyhow::{anyhow, bail, Result};
use strata_client::setup::{egl_context_with, link_program, Current, SurfaceKind};
use strata_client::{Calls, ClientError, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::projection::{Projection, ProjectionKind};
use strata_protocol::{Blob, Slice, Text};

use super::report::Row;
use super::scene::{exact_winners, inv_eye, shown, PLANES};
use crate::glmark2::stratad_binary;
use crate::stratad::Stratad;

/// Frames each surface draws for the timing.
const FRAMES: usize = 30;
/// The output's name.
const OUTPUT: &str = "bench";
/// The surfaces' colours: each the dominant channel `shown` reads for its index.
const COLOURS: [[f32; 4]; 2] = [[1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]];

/// One daemon setting.
struct DaemonSetting {
    name: &'static str,
    format: &'static str,
    reversed: bool,
}

/// The settings measured, one row each.
const SETTINGS: [DaemonSetting; 5] = [
    DaemonSetting { name: "24plus (clients' default)", format: "24plus", reversed: false },
    DaemonSetting { name: "16unorm", format: "16unorm", reversed: false },
    DaemonSetting { name: "32float", format: "32float", reversed: false },
    DaemonSetting { name: "32float reversed-Z", format: "32float", reversed: true },
    DaemonSetting { name: "24plus reversed-Z", format: "24plus", reversed: true },
];

/// The rows, one per setting, calling `progress` with each setting's name before measuring it.
/// A setting that cannot be measured (no `stratad`, a failed client) gives a row saying why.
pub(super) fn rows(w: u32, h: u32, mut progress: impl FnMut(&str)) -> Result<Vec<Row>> {
    let stratad = stratad_binary(None);
    let (win, band) = exact_winners(2, w, h);
    Ok(SETTINGS
        .iter()
        .map(|s| {
            progress(s.name);
            let measured = stratad.as_ref().map_err(|e| anyhow!("{e:#}")).and_then(|b| measure(b, s, w, h));
            match measured {
                Ok((ms, img)) => row(s, ms, Some(errors(&img, &win, &band)), ""),
                Err(e) => {
                    let why = format!("; not measured: {}", format!("{e:#}").lines().next().unwrap_or(""));
                    row(s, f64::NAN, None, &why)
                }
            }
        })
        .collect())
}

/// The fractions of the band's pixels and of all pixels that show another surface than the
/// f64 nearest one, and the band's pixel count.
fn errors(img: &[u8], win: &[usize], band: &[bool]) -> (f64, f64, usize) {
    let wrong: Vec<bool> = img.chunks(4).zip(win).map(|(p, &e)| shown(p) != e).collect();
    let on_line = band.iter().filter(|&&b| b).count();
    let wrong_on_line = wrong.iter().zip(band).filter(|(&x, &b)| x && b).count();
    let wrong_all = wrong.iter().filter(|&&x| x).count();
    (wrong_on_line as f64 / on_line.max(1) as f64, wrong_all as f64 / wrong.len().max(1) as f64, on_line)
}

/// `s`'s row from its client frame time and its error fractions.
fn row(s: &DaemonSetting, ms: f64, err: Option<(f64, f64, usize)>, why: &str) -> Row {
    let note = format!(
        "stratad --depth-format {}{}: ms = client frame time (clear, draw, eglSwapBuffers at interval 0, glFinish); \
         depth max/p99 not readable through the daemon (NaN){why}",
        s.format,
        if s.reversed { " --reversed-z" } else { "" }
    );
    Row {
        knob: "daemon depth",
        setting: s.name,
        surfaces: 2,
        depth_format: s.format,
        reversed: s.reversed,
        declared: true,
        lit: false,
        normals: "-",
        max_textures: None,
        intermediate: "rgba8",
        passes: 0,
        chained_cells: 0,
        ms,
        depth_err_max: f64::NAN,
        depth_err_p99: f64::NAN,
        line_pixels: err.map_or(0, |e| e.2),
        wrong_line: err.map(|e| e.0),
        wrong_all: err.map(|e| e.1),
        stored_wrong_line: None,
        colour_err_max: 0,
        colour_err_mean: 0.0,
        // One string per row of a one-shot benchmark run.
        note: Box::leak(note.into_boxed_str()),
    }
}

/// Runs setting `s`: its daemon, both clients' timed frames, and the composite showing both
/// (RGBA8, top row first).
fn measure(stratad: &Path, s: &DaemonSetting, w: u32, h: u32) -> Result<(f64, Vec<u8>)> {
    let tag = format!("{}{}", s.format, if s.reversed { "-rev" } else { "" });
    let output = format!("headless:{OUTPUT}={w}x{h}");
    let mut args = vec!["--output", &output, "--depth-format", s.format, "--lighting", "off"];
    if s.reversed {
        args.push("--reversed-z");
    }
    let dir = std::env::temp_dir();
    let socket = dir.join(format!("strata-bench-depth-{}-{tag}.sock", std::process::id()));
    let log = dir.join(format!("strata-bench-depth-{}-{tag}.log", std::process::id()));
    let daemon = Stratad::start(stratad, args, socket, log, false)?;
    let mut clients = (0..2).map(|i| Client::new(&daemon.socket, i, w, h)).collect::<Result<Vec<_>>>()?;
    let mut times = Vec::with_capacity(FRAMES * clients.len());
    for _ in 0..FRAMES {
        for c in &mut clients {
            times.push(c.frame()?);
        }
    }
    times.sort_by(f64::total_cmp);
    let ms = times[times.len() / 2];
    let img = screenshot(&daemon.socket, w, h)?;
    drop(clients);
    Ok((ms, img))
}

/// The output's image once it shows both surfaces.
fn screenshot(socket: &Path, w: u32, h: u32) -> Result<Vec<u8>> {
    let mut ctl = ControlConnection::connect_beside(socket)?;
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        match ctl.request(&ControlRequest::Screenshot { output: OUTPUT.into() })? {
            ControlReply::Image { width, height, rgba } if (width, height) == (w, h) => {
                let both = (0..2).all(|i| rgba.0.chunks(4).any(|p| shown(p) == i && p[i * 2] > 128));
                if both {
                    return Ok(rgba.0);
                }
            }
            ControlReply::Image { width, height, .. } => bail!("screenshot is {width}x{height}, not {w}x{h}"),
            ControlReply::Error(e) => bail!("screenshot failed: {e}"),
            other => bail!("unexpected screenshot reply {other:?}"),
        }
        if Instant::now() > deadline {
            bail!("the two surfaces never showed together");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// GL's standard perspective matrix (`glFrustum` with l = b = −n, r = t = n), column-major,
/// in f64 rounded to f32.
fn perspective(n: f64, f: f64) -> [f32; 16] {
    let a = -(f + n) / (f - n);
    let b = -2.0 * f * n / (f - n);
    [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, a as f32, -1.0, 0.0, 0.0, b as f32, 0.0]
}

/// Surface `i`'s plane as two eye-space triangles covering NDC [−1, 1]²: the corners at the
/// eye distances of `inv_eye` (t, u across the output, u from the bottom), where a plane's
/// 1/distance is linear in NDC.
fn plane(i: usize) -> Vec<f32> {
    let corner = |t: f64, u: f64| {
        let z = 1.0 / inv_eye(i, t, u);
        [((2.0 * t - 1.0) * z) as f32, ((2.0 * u - 1.0) * z) as f32, -z as f32]
    };
    let c = [corner(0.0, 0.0), corner(1.0, 0.0), corner(1.0, 1.0), corner(0.0, 1.0)];
    [c[0], c[1], c[2], c[0], c[2], c[3]].concat()
}

const VS: &str = "attribute vec3 eye; uniform mat4 proj;
    void main() { gl_Position = proj * vec4(eye, 1.0); }";
const FS: &str = "precision mediump float; uniform vec4 color; void main() { gl_FragColor = color; }";

/// One client: a full-output window surface declaring `PLANES[i]`, its plane's program and
/// vertices set up, ready to draw frames.
struct Client {
    conn: Connection,
    cur: Current,
}

impl Client {
    fn new(socket: &Path, i: usize, w: u32, h: u32) -> Result<Client> {
        let (near, far) = PLANES[i];
        let opts =
            ConnectOptions { socket: socket.to_path_buf(), name: format!("plane-{i}"), ..ConnectOptions::default() };
        let mut conn = Connection::connect(&opts)?;
        let decl = Projection { kind: ProjectionKind::Perspective, near, far, reversed: false };
        let (wi, hi) = (i32::try_from(w)?, i32::try_from(h)?);
        // Depth 32: the config without stencil, whose depth format `--depth-format` sets
        // (configs with stencil keep Depth24PlusStencil8 under `16unorm`).
        let kind = SurfaceKind::Window { rect: [0, 0, wi, hi], z: 0.5 };
        let cur = egl_context_with(&mut conn, 32, 0, kind, &decl.to_egl_attribs())?;
        egl(conn.eglSwapInterval(cur.display, 0)?, "eglSwapInterval")?;
        conn.glViewport(0, 0, wi, hi)?;
        conn.glEnable(0x0B71)?; // DEPTH_TEST
        conn.glClearColor(0.0, 0.0, 0.0, 1.0)?;
        let p = link_program(&mut conn, (1, 2, 3), VS, FS, &["eye"])?;
        let proj = conn.glGetUniformLocation(p, Text::borrowed("proj"))?;
        conn.glUniformMatrix4fv(proj, false, Slice::new(&perspective(f64::from(near), f64::from(far))))?;
        let colour = conn.glGetUniformLocation(p, Text::borrowed("color"))?;
        let [r, g, b, a] = COLOURS[i];
        conn.glUniform4f(colour, r, g, b, a)?;
        let bytes: Vec<u8> = plane(i).iter().flat_map(|x| x.to_ne_bytes()).collect();
        conn.glGenBuffers(Slice::new(&[4]))?;
        conn.glBindBuffer(0x8892, 4)?; // ARRAY_BUFFER
        conn.glBufferData(0x8892, bytes.len() as i64, Some(Blob::borrowed(&bytes)), 0x88E4)?; // STATIC_DRAW
        conn.glVertexAttribPointer(0, 3, 0x1406, false, 0, 0)?; // FLOAT
        conn.glEnableVertexAttribArray(0)?;
        Ok(Client { conn, cur })
    }

    /// Draws and shows one frame; its milliseconds to the reply of the `glFinish` after
    /// `eglSwapBuffers` (the frame rendered on the daemon's device).
    fn frame(&mut self) -> Result<f64> {
        let t = Instant::now();
        self.conn.glClear(0x4000 | 0x0100)?; // COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT
        self.conn.glDrawArrays(0x0004, 0, 6)?; // TRIANGLES
        egl(self.conn.eglSwapBuffers(self.cur.display, self.cur.surface)?, "eglSwapBuffers")?;
        self.conn.glFinish()?;
        Ok(t.elapsed().as_secs_f64() * 1e3)
    }
}

/// An EGL result as an error naming the call.
fn egl<T>(r: Result<T, i32>, what: &str) -> Result<T, ClientError> {
    r.map_err(|e| ClientError::Unsupported(format!("{what} failed with EGL error {e:#x}")))
}

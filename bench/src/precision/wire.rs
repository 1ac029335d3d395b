//! Rows for the vertex data wire format (`stratad serve --vertex-wire float|half|fixed`), one per
//! format, each measured from both sides:
//! - speed: `ms` is the client's frame time, 1000 / the fps of a real client process,
//!   `glmark2-es2 -b build:use-vbo=false` (a mesh drawn from `GL_FLOAT` client-side arrays
//!   every frame) through the drop-in libraries and a daemon started with that format;
//! - error: the precision scene's planes (eye distances 20–60) as a mesh with one vertex per
//!   output pixel, eye position (x, y, −z) under a 90° horizontal field of view: each
//!   component rounded to f32 by the application and then to the format as the client sends
//!   it, against f64. `depth max/p99` is the eye depth error over both surfaces; `fmt@ln` is
//!   the pixels within `BAND` of an intersection line that an exact select of those depths
//!   gets wrong (the position error is in the note). No compositing: the other columns are
//!   not measured (shown as 0 or -).

use std::process::{Command, Stdio};
use std::time::Duration;

use anyhow::{Context, Result};
use strata_client::vertex_wire::{quantise, VertexWire};

use super::report::Row;
use super::scene::{exact_winners, inv_eye, quantile, DEFAULT};
use crate::glmark2::{finish, prepare, stratad_binary};
use crate::stratad::Stratad;

/// Seconds glmark2 draws per format.
const DURATION_S: u32 = 3;
/// glmark2's window.
const WINDOW: &str = "400x300";

/// The rows: float, half and fixed.
pub(super) fn rows(w: u32, h: u32) -> Result<Vec<Row>> {
    let fps = client_fps();
    VertexWire::ALL
        .iter()
        .map(|&wire| {
            let ms = match &fps {
                Ok(f) => f.iter().find(|(x, _)| *x == wire).map_or(f64::NAN, |(_, fps)| 1000.0 / fps),
                Err(_) => f64::NAN,
            };
            let why = fps.as_ref().err().map(|e| format!("; client not run: {}", e.lines().next().unwrap_or("")));
            Ok(error_row(wire, w, h, ms, why.as_deref().unwrap_or("")))
        })
        .collect()
}

/// The error half of `wire`'s row, with the client's frame time `ms`.
fn error_row(wire: VertexWire, w: u32, h: u32, ms: f64, why: &str) -> Row {
    let surfaces = DEFAULT.surfaces;
    let tan_y = f64::from(h) / f64::from(w);
    let (mut depth_err, mut pos_err) = (Vec::new(), Vec::new());
    // Per surface, the sent eye depth at each pixel (bottom row first).
    let mut sent: Vec<Vec<f64>> = (0..surfaces).map(|_| Vec::with_capacity((w * h) as usize)).collect();
    for py in 0..h {
        let u = (f64::from(py) + 0.5) / f64::from(h);
        for x in 0..w {
            let t = (f64::from(x) + 0.5) / f64::from(w);
            for (i, s) in sent.iter_mut().enumerate() {
                let z = 1.0 / inv_eye(i, t, u);
                let exact = [(2.0 * t - 1.0) * z, (2.0 * u - 1.0) * z * tan_y, -z];
                let got = exact.map(|c| quantise(wire, c as f32));
                let d2: f64 = exact.iter().zip(&got).map(|(e, g)| (e - g) * (e - g)).sum();
                pos_err.push(d2.sqrt());
                depth_err.push((got[2] - exact[2]).abs());
                s.push(-got[2]);
            }
        }
    }
    let (win, band) = exact_winners(surfaces, w, h);
    let (mut line_pixels, mut wrong) = (0usize, 0usize);
    for py in 0..h as usize {
        // `exact_winners` is top row first; `sent` bottom row first.
        let row = (h as usize - 1 - py) * w as usize;
        for x in 0..w as usize {
            let k = py * w as usize + x;
            if !band[k] {
                continue;
            }
            line_pixels += 1;
            let pick = (0..surfaces).fold(0, |b, i| if sent[i][row + x] <= sent[b][row + x] { i } else { b });
            wrong += usize::from(pick != win[k]);
        }
    }
    let pos_max = pos_err.iter().copied().fold(0.0, f64::max);
    let pos_p99 = quantile(&mut pos_err, 0.99);
    let note = format!(
        "vertex wire {wire}: ms = client frame time (glmark2 build:use-vbo=false); eye position error max {pos_max:.2e}, \
         p99 {pos_p99:.2e}{why}"
    );
    Row {
        knob: "vertex wire",
        setting: match wire {
            VertexWire::Float => "float: client ms, eye err",
            VertexWire::Half => "half: client ms, eye err",
            VertexWire::Fixed => "fixed: client ms, eye err",
        },
        surfaces,
        depth_format: "-",
        reversed: false,
        declared: true,
        lit: false,
        normals: "-",
        max_textures: None,
        intermediate: "-",
        passes: 0,
        chained_cells: 0,
        ms,
        depth_err_max: depth_err.iter().copied().fold(0.0, f64::max),
        depth_err_p99: quantile(&mut depth_err, 0.99),
        line_pixels,
        wrong_line: None,
        wrong_all: None,
        stored_wrong_line: Some(wrong as f64 / line_pixels.max(1) as f64),
        colour_err_max: 0,
        colour_err_mean: 0.0,
        // One string per row of a one-shot benchmark run.
        note: Box::leak(note.into_boxed_str()),
    }
}

/// glmark2's fps per format, each through its own daemon; an error (as text) if glmark2, Xvfb
/// or the daemon is missing or a run fails.
fn client_fps() -> Result<Vec<(VertexWire, f64)>, String> {
    let go = || -> Result<Vec<(VertexWire, f64)>> {
        let stratad = stratad_binary(None)?;
        let (tmp, shim, x) = prepare(None)?;
        VertexWire::ALL
            .iter()
            .map(|&wire| {
                let log = tmp.0.join(format!("stratad-{wire}.log"));
                let socket = tmp.0.join(format!("stratad-{wire}.sock"));
                let args = ["--output", "headless:bench=640x480", "--vertex-wire", wire.name()];
                let daemon = Stratad::start(&stratad, args, socket, log, true)?;
                let child = Command::new("glmark2-es2")
                    .args(["-b", &format!("build:use-vbo=false:duration={DURATION_S}"), "-s", WINDOW])
                    .env("DISPLAY", &x.display)
                    .env("LD_LIBRARY_PATH", &shim)
                    .env("STRATA_SOCKET", &daemon.socket)
                    .env_remove("STRATA_WINDOW")
                    .stdin(Stdio::null())
                    .stdout(Stdio::piped())
                    .stderr(Stdio::piped())
                    .spawn()
                    .context("starting glmark2-es2")?;
                let run = finish(child, Duration::from_secs(u64::from(DURATION_S) * 3 + 60))?;
                Ok((wire, f64::from(run.score)))
            })
            .collect()
    };
    go().map_err(|e| format!("{e:#}"))
}

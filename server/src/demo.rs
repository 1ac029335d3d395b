//! The built-in demo clients: an instrument cluster (a dial with a needle) and a head unit (a
//! map block), each a separate process rendering through EGL/GLES on its own window surface.
//! Both sit at the same z over overlapping rectangles, and their tilted geometry intersects.

use std::io::Write;

pub mod planes;

use strata_client::setup::{egl_context, link_program, SurfaceKind};
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use strata_protocol::{Blob, Slice, Text};

/// Output size of the demo.
pub const OUTPUT: (u32, u32) = (960, 540);
/// The instrument cluster's rectangle (x, y, w, h).
pub const IC_RECT: [i32; 4] = [100, 60, 560, 400];
/// The head unit's rectangle.
pub const HU_RECT: [i32; 4] = [300, 80, 560, 400];
/// Both clients' depth layer.
pub const Z: f32 = 0.5;

const VS: &str = "attribute vec2 pos; attribute vec3 col; uniform vec3 plane; varying vec3 v;
void main() { v = col; gl_Position = vec4(pos, plane.x * pos.x + plane.y * pos.y + plane.z, 1.0); }";
const FS: &str = "precision mediump float; varying vec3 v; void main() { gl_FragColor = vec4(v, 1.0); }";

/// Clip-space depth plane of the dial: z = 0.5·y (its top leans away).
pub const IC_PLANE: [f32; 3] = [0.0, 0.5, 0.0];
/// Clip-space depth plane of the map block: z = 0.6·x + 0.2 (its right side leans away).
pub const HU_PLANE: [f32; 3] = [0.6, 0.0, 0.2];

/// The client's geometry for `frame`: (base, overlay). The overlay (the dial's needle) is drawn
/// slightly in front of the base.
fn geometry(ic: bool, frame: u32) -> (Vec<f32>, Vec<f32>) {
    let mut needle = Vec::new();
    let mut v = Vec::new();
    let mut tri = |a: [f32; 5], b: [f32; 5], c: [f32; 5]| {
        v.extend_from_slice(&a);
        v.extend_from_slice(&b);
        v.extend_from_slice(&c);
    };
    if ic {
        // Dial: a disc of 64 segments, dark face with a bright rim.
        let n = 64;
        for i in 0..n {
            let (a0, a1) =
                (i as f32 / n as f32 * std::f32::consts::TAU, (i + 1) as f32 / n as f32 * std::f32::consts::TAU);
            let rim = [1.0, 0.55, 0.1];
            let p = |a: f32, r: f32, c: [f32; 3]| [a.cos() * r, a.sin() * r, c[0], c[1], c[2]];
            tri(p(0.0, 0.0, [0.35, 0.18, 0.05]), p(a0, 0.85, rim), p(a1, 0.85, rim));
            tri(p(a0, 0.85, rim), p(a0, 0.95, [1.0, 0.8, 0.3]), p(a1, 0.85, rim));
            tri(p(a1, 0.85, rim), p(a0, 0.95, [1.0, 0.8, 0.3]), p(a1, 0.95, [1.0, 0.8, 0.3]));
        }
        // Needle, sweeping with the frame number.
        let a = 2.2 + (frame % 60) as f32 * 0.02;
        let (c, s) = (a.cos(), a.sin());
        let w = 0.05;
        let red = [1.0, 0.1, 0.1];
        needle.extend_from_slice(&[-s * w, c * w, red[0], red[1], red[2]]);
        needle.extend_from_slice(&[s * w, -c * w, red[0], red[1], red[2]]);
        needle.extend_from_slice(&[c * 0.8, s * 0.8, 1.0, 0.9, 0.9]);
    } else {
        // Map block: an 8×8 checker of blues.
        for y in 0..8 {
            for x in 0..8 {
                let c = if (x + y) % 2 == 0 { [0.15, 0.45, 0.9] } else { [0.1, 0.3, 0.65] };
                let (x0, y0) = (-0.95 + x as f32 * 0.2375, -0.95 + y as f32 * 0.2375);
                let (x1, y1) = (x0 + 0.2375, y0 + 0.2375);
                tri([x0, y0, c[0], c[1], c[2]], [x1, y0, c[0], c[1], c[2]], [x1, y1, c[0], c[1], c[2]]);
                tri([x0, y0, c[0], c[1], c[2]], [x1, y1, c[0], c[1], c[2]], [x0, y1, c[0], c[1], c[2]]);
            }
        }
    }
    (v, needle)
}

/// Runs one demo client: `role` is `ic` or `hu`. Renders `frames` frames, prints `ready`, then
/// keeps its surface on screen until stdin closes.
pub fn run_client(socket: &std::path::Path, role: &str, frames: u32) -> Result<(), ClientError> {
    let ic = role == "ic";
    let rect = if ic { IC_RECT } else { HU_RECT };
    let plane = if ic { IC_PLANE } else { HU_PLANE };
    let opts = ConnectOptions {
        socket: socket.to_path_buf(),
        name: if ic { "instrument-cluster".into() } else { "head-unit".into() },
        role: role.into(),
        ..ConnectOptions::default()
    };
    let mut gl = Connection::connect(&opts)?;
    let cur = egl_context(&mut gl, 24, 0, SurfaceKind::Window { rect, z: Z })?;
    let p = link_program(&mut gl, (1, 2, 3), VS, FS, &["pos", "col"])?;
    let loc = gl.glGetUniformLocation(p, Text::borrowed("plane"))?;
    gl.glEnable(0x0B71)?;
    gl.glGenBuffers(Slice::new(&[10]))?;
    gl.glBindBuffer(0x8892, 10)?;
    gl.glVertexAttribPointer(0, 2, 0x1406, false, 20, 0)?;
    gl.glVertexAttribPointer(1, 3, 0x1406, false, 20, 8)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glEnableVertexAttribArray(1)?;
    gl.glClearColor(0.0, 0.0, 0.0, 0.0)?;
    for f in 0..frames.max(1) {
        let (base, overlay) = geometry(ic, f);
        gl.glClear(0x4000 | 0x0100)?;
        for (verts, lift) in [(&base, 0.0), (&overlay, 0.03)] {
            if verts.is_empty() {
                continue;
            }
            let bytes: &[u8] = bytemuck::cast_slice(verts);
            gl.glUniform3f(loc, plane[0], plane[1], plane[2] - lift)?;
            gl.glBufferData(0x8892, bytes.len() as i64, Some(Blob::borrowed(bytes)), 0x88E8)?;
            gl.glDrawArrays(0x0004, 0, (verts.len() / 5) as i32)?;
        }
        swap(&mut gl, cur)?;
    }
    ready_until_stdin_closes(&mut gl)
}

/// Swaps `cur`'s surface, an EGL error becoming a client error.
fn swap(gl: &mut Connection, cur: strata_client::setup::Current) -> Result<(), ClientError> {
    gl.eglSwapBuffers(cur.display, cur.surface)?
        .map_err(|e| ClientError::Unsupported(format!("eglSwapBuffers failed with EGL error {e:#x}")))
}

/// Finishes the client's work, prints `ready`, and stays connected (and visible) until the
/// parent closes our stdin.
fn ready_until_stdin_closes(gl: &mut Connection) -> Result<(), ClientError> {
    gl.glFinish()?;
    println!("ready");
    let _ = std::io::stdout().flush();
    let mut sink = String::new();
    let _ = std::io::stdin().read_line(&mut sink);
    Ok(())
}

//! The projections demo (`stratad demo --scene planes`): two client processes draw a plane
//! each, in their own eye space and under their own perspective projection (near/far 0.5/50
//! and 2/2000, both with a 90° field of view), over the same rectangle at the same z. The
//! planes meet along the vertical line at NDC x = [`line_x`]. With declared projections
//! (`EGL_STRATA_surface_projection`) the compositor compares eye-space depth and the line
//! lands there; compared raw, the two depth scales disagree and it lands far to the left.

use strata_client::setup::{egl_context_with, link_program, SurfaceKind};
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use strata_protocol::projection::{
    EGL_PROJECTION_FAR_STRATA, EGL_PROJECTION_NEAR_STRATA, EGL_PROJECTION_PERSPECTIVE_STRATA, EGL_PROJECTION_STRATA,
};
use strata_protocol::{Blob, Slice, Text};

/// Both planes' rectangle (x, y, w, h) in the demo's output.
pub const RECT: [i32; 4] = [280, 70, 400, 400];
/// Both planes' depth layer.
pub const Z: f32 = 0.5;

/// One client's plane: eye-space `z = -(c + s·x)`, seen through a perspective projection with
/// a 90° field of view and these near and far planes, drawn in one colour.
#[derive(Debug, Clone, Copy)]
pub struct Plane {
    /// Near plane distance.
    pub near: f32,
    /// Far plane distance.
    pub far: f32,
    /// Eye distance of the plane on the view axis.
    pub c: f64,
    /// How far the plane recedes per unit of eye x.
    pub s: f64,
    /// Its colour.
    pub color: [f32; 3],
}

/// The red plane: near/far 0.5/50, receding to the right.
pub const A: Plane = Plane { near: 0.5, far: 50.0, c: 3.0, s: 0.5, color: [1.0, 0.0, 0.0] };
/// The blue plane: near/far 2/2000, receding to the left.
pub const B: Plane = Plane { near: 2.0, far: 2000.0, c: 4.0, s: -0.7, color: [0.0, 0.0, 1.0] };

impl Plane {
    /// The eye distance of the plane along the ray through NDC x.
    pub fn distance(&self, x: f64) -> f64 {
        self.c / (1.0 - self.s * x)
    }

    /// GL window depth (depth range 0..1) of the plane at NDC x.
    pub fn depth(&self, x: f64) -> f64 {
        let (n, f) = (f64::from(self.near), f64::from(self.far));
        f / (f - n) * (1.0 - n / self.distance(x))
    }

    /// Clip-space position of the plane's point on the ray through NDC (x, y).
    fn clip(&self, x: f64, y: f64) -> [f32; 4] {
        let (n, f) = (f64::from(self.near), f64::from(self.far));
        let t = self.distance(x);
        [(x * t) as f32, (y * t) as f32, (((f + n) * t - 2.0 * f * n) / (f - n)) as f32, t as f32]
    }
}

/// NDC x (in f64) where the planes meet: A is nearer to its left, B to its right.
pub fn line_x() -> f64 {
    (B.c - A.c) / (B.c * A.s - A.c * B.s)
}

const VS: &str = "attribute vec4 pos; void main() { gl_Position = pos; }";
const FS: &str = "precision mediump float; uniform vec3 col; void main() { gl_FragColor = vec4(col, 1.0); }";

/// Runs one plane client (`role` `plane-a` or `plane-b`), declaring its projection when
/// `declare`; renders `frames` frames, prints `ready`, and stays until stdin closes.
pub fn run_client(socket: &std::path::Path, role: &str, frames: u32, declare: bool) -> Result<(), ClientError> {
    let plane = if role == "plane-a" { A } else { B };
    let opts = ConnectOptions {
        socket: socket.to_path_buf(),
        name: role.into(),
        role: role.into(),
        ..ConnectOptions::default()
    };
    let mut gl = Connection::connect(&opts)?;
    let bits = |v: f32| v.to_bits() as i32;
    let declared = [
        EGL_PROJECTION_STRATA,
        EGL_PROJECTION_PERSPECTIVE_STRATA,
        EGL_PROJECTION_NEAR_STRATA,
        bits(plane.near),
        EGL_PROJECTION_FAR_STRATA,
        bits(plane.far),
    ];
    let attribs: &[i32] = if declare { &declared } else { &[] };
    let cur = egl_context_with(&mut gl, 24, 0, SurfaceKind::Window { rect: RECT, z: Z }, attribs)?;
    let p = link_program(&mut gl, (1, 2, 3), VS, FS, &["pos"])?;
    let col = gl.glGetUniformLocation(p, Text::borrowed("col"))?;
    gl.glUniform3f(col, plane.color[0], plane.color[1], plane.color[2])?;
    gl.glEnable(0x0B71)?; // GL_DEPTH_TEST
                          // A little past the rectangle's edges, so that the plane covers all of it.
    let e = 1.05;
    let corners = [plane.clip(-e, -e), plane.clip(e, -e), plane.clip(e, e), plane.clip(-e, e)];
    let verts: Vec<f32> = [0, 1, 2, 0, 2, 3].iter().flat_map(|&i| corners[i]).collect();
    let bytes: &[u8] = bytemuck::cast_slice(&verts);
    gl.glGenBuffers(Slice::new(&[10]))?;
    gl.glBindBuffer(0x8892, 10)?;
    gl.glBufferData(0x8892, bytes.len() as i64, Some(Blob::borrowed(bytes)), 0x88E4)?;
    gl.glVertexAttribPointer(0, 4, 0x1406, false, 16, 0)?;
    gl.glEnableVertexAttribArray(0)?;
    gl.glClearColor(0.0, 0.0, 0.0, 0.0)?;
    for _ in 0..frames.max(1) {
        gl.glClear(0x4000 | 0x0100)?;
        gl.glDrawArrays(0x0004, 0, 6)?;
        super::swap(&mut gl, cur)?;
    }
    super::ready_until_stdin_closes(&mut gl)
}

/// The first column of each row of `RECT` in `rgba` (the output, `width` wide) that shows the
/// blue plane, where a red pixel lies to its left; `None` for a row without that transition.
pub fn line_columns(rgba: &[u8], width: u32) -> Vec<Option<u32>> {
    let [x0, y0, w, h] = RECT.map(|v| v as u32);
    (y0..y0 + h)
        .map(|y| {
            let px = |x: u32| {
                let i = ((y * width + x0 + x) * 4) as usize;
                rgba.get(i..i + 3).map_or((0, 0), |p| (p[0], p[2]))
            };
            let blue = |x: u32| {
                let (r, b) = px(x);
                b > 128 && r < 64
            };
            (1..w).find(|&x| blue(x) && !blue(x - 1) && px(x - 1).0 > 128)
        })
        .collect()
}

/// The column of `RECT` that should be the first blue one: the first whose centre lies right
/// of [`line_x`].
pub fn expected_column() -> u32 {
    let w = f64::from(RECT[2]);
    ((line_x() + 1.0) / 2.0 * w - 0.5).ceil() as u32
}

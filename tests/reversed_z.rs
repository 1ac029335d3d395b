//! `stratad serve --depth-format` and `--reversed-z` made real:
//!
//! - with `--reversed-z`, programs using depth tests under several compare functions, a depth
//!   clear other than 1, `glDepthRangef`, polygon offset and `gl_FragCoord.z`, drawn through a
//!   standard perspective projection into a window surface that declares it, and a shader
//!   writing `gl_FragDepthEXT`, give Mesa's
//!   image: the application cannot tell that its depth is stored reversed;
//! - two surfaces under different declared perspective projections whose planes meet along a
//!   line, composited: with `--depth-format 32float --reversed-z` the compositor picks the
//!   surface the f64 geometry says is nearer on every pixel near the line, where forward
//!   32-bit float depth gets a good share of them wrong;
//! - `--depth-format 16unorm` stores 16 bits: two depths in one 16-bit step compare equal.

mod programs;
mod support;

use programs::*;
use strata_client::setup::{egl_context_with, Current, SurfaceKind};
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use strata_protocol::projection::{Projection, ProjectionKind};
use strata_protocol::Slice;
use support::mesa::MesaGl;
use support::Daemon;

/// Mesa's GLES2 is loaded into this process; its contexts must not be used from two test
/// threads at once.
static MESA: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The declared projection of the oracle programs.
const NEAR: f32 = 0.5;
const FAR: f32 = 20.0;

/// GL's standard perspective matrix (`glFrustum` with l = b = −n, r = t = n), column-major:
/// NDC x, y are eye x / distance, y / distance.
fn perspective(n: f64, f: f64) -> [f32; 16] {
    let a = -(f + n) / (f - n);
    let b = -2.0 * f * n / (f - n);
    [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, a as f32, -1.0, 0.0, 0.0, b as f32, 0.0]
}

const VS_EYE: &str = "attribute vec3 eye; uniform mat4 proj;
    void main() { gl_Position = proj * vec4(eye, 1.0); }";
const FS_FLAT: &str = "precision mediump float; uniform vec4 color; void main() { gl_FragColor = color; }";

/// The eye-space vertices (two triangles) of a quad covering NDC [x0, x1] × [y0, y1] whose
/// corners lie at eye distances `d` (x0y0, x1y0, x1y1, x0y1).
fn eye_quad(x0: f32, y0: f32, x1: f32, y1: f32, d: [f32; 4]) -> Vec<f32> {
    let v = |x: f32, y: f32, z: f32| [x * z, y * z, -z];
    let c = [v(x0, y0, d[0]), v(x1, y0, d[1]), v(x1, y1, d[2]), v(x0, y1, d[3])];
    [c[0], c[1], c[2], c[0], c[2], c[3]].concat()
}

/// Uses a program drawing eye-space positions through the declared perspective.
fn eye_program(gl: Gl<'_>, n: &mut Names, near: f32, far: f32) -> Result<u32, ClientError> {
    let p = program(gl, n, VS_EYE, FS_FLAT, &["eye"])?;
    let loc = gl.glGetUniformLocation(p, strata_protocol::Text::borrowed("proj"))?;
    gl.glUniformMatrix4fv(loc, false, Slice::new(&perspective(f64::from(near), f64::from(far))))?;
    Ok(p)
}

/// A program of the oracle comparison.
type Program = fn(Gl<'_>, &mut Names) -> Result<(), ClientError>;

const LESS: u32 = 0x0201;
const EQUAL: u32 = 0x0202;
const LEQUAL: u32 = 0x0203;
const GREATER: u32 = 0x0204;
const GEQUAL: u32 = 0x0206;

/// Overlapping flat and tilted quads under LESS, LEQUAL, GREATER and GEQUAL.
fn compare_funcs(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = eye_program(gl, n, NEAR, FAR)?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.9, -0.9, 0.3, 0.5, [4.0; 4]), TRIANGLES)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.6, -0.6, 0.9, 0.9, [2.0, 9.0, 12.0, 3.0]), TRIANGLES)?;
    gl.glDepthFunc(LEQUAL)?;
    color(gl, p, [0.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.2, -0.95, 0.1, 0.95, [6.0, 6.0, 1.5, 1.5]), TRIANGLES)?;
    gl.glDepthFunc(GREATER)?;
    color(gl, p, [1.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.95, 0.2, 0.95, 0.6, [5.0; 4]), TRIANGLES)?;
    gl.glDepthFunc(GEQUAL)?;
    color(gl, p, [1.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(0.4, -0.95, 0.7, 0.95, [15.0, 1.0, 1.0, 15.0]), TRIANGLES)
}

/// A depth clear of 0.6, then two depth ranges, under LESS and GEQUAL.
fn clear_and_range(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClearDepthf(0.6)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = eye_program(gl, n, NEAR, FAR)?;
    // Window depth 0.6 is about eye distance 1.2 here: nearer passes, farther does not.
    color(gl, p, [1.0, 0.5, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.9, -0.9, 0.9, -0.1, [0.8, 3.0, 3.0, 0.8]), TRIANGLES)?;
    gl.glDepthRangef(0.2, 0.7)?;
    color(gl, p, [0.0, 0.5, 1.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.9, 0.0, 0.9, 0.9, [0.6, 0.6, 10.0, 10.0]), TRIANGLES)?;
    gl.glDepthRangef(0.5, 1.0)?;
    gl.glDepthFunc(GEQUAL)?;
    color(gl, p, [0.5, 1.0, 0.5, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.5, -0.95, 0.5, 0.95, [1.0; 4]), TRIANGLES)
}

/// The same geometry again under EQUAL, and coplanar quads pulled nearer and pushed farther
/// by polygon offset.
fn equal_and_offset(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = eye_program(gl, n, NEAR, FAR)?;
    let tilted = eye_quad(-0.9, -0.9, 0.9, 0.9, [2.0, 8.0, 3.0, 1.0]);
    color(gl, p, [0.3, 0.3, 0.3, 1.0])?;
    draw_positions(gl, n, &tilted, TRIANGLES)?;
    gl.glDepthFunc(EQUAL)?;
    color(gl, p, [0.0, 1.0, 1.0, 1.0])?;
    draw_positions(gl, n, &tilted, TRIANGLES)?;
    gl.glDepthFunc(LESS)?;
    gl.glEnable(POLYGON_OFFSET_FILL)?;
    gl.glPolygonOffset(-1.0, -2.0)?;
    let left = eye_quad(-0.9, -0.9, 0.0, 0.9, [2.0, 5.0, 2.0, 1.0]);
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &left, TRIANGLES)?;
    gl.glPolygonOffset(1.0, 2.0)?;
    color(gl, p, [0.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &left, TRIANGLES)
}

/// A fragment shader showing `gl_FragCoord.z` over tilted quads.
fn frag_coord_depth(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let fs = "precision highp float;
        void main() { gl_FragColor = vec4(gl_FragCoord.z, 1.0 - gl_FragCoord.z * 0.5, 0.5, 1.0); }";
    let p = program(gl, n, VS_EYE, fs, &["eye"])?;
    let loc = gl.glGetUniformLocation(p, strata_protocol::Text::borrowed("proj"))?;
    gl.glUniformMatrix4fv(loc, false, Slice::new(&perspective(f64::from(NEAR), f64::from(FAR))))?;
    draw_positions(gl, n, &eye_quad(-0.9, -0.9, 0.9, 0.9, [0.6, 15.0, 4.0, 1.0]), TRIANGLES)?;
    gl.glDepthRangef(0.25, 0.75)?;
    draw_positions(gl, n, &eye_quad(-0.5, -0.5, 0.5, 0.5, [1.0, 1.0, 1.0, 1.0]), TRIANGLES)
}

/// A fragment shader writing `gl_FragDepthEXT` (`GL_EXT_frag_depth`): a red quad, near in eye
/// space, whose written depth runs from 0 to 1 across x, then green and blue quads at eye
/// distances 1 and 3 under LESS and GREATER: each shows only where the written depth is
/// beyond, or short of, its own.
fn frag_depth_written(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let fs = "#extension GL_EXT_frag_depth : enable
        precision highp float;
        void main() { gl_FragColor = vec4(1.0, 0.0, 0.0, 1.0); gl_FragDepthEXT = gl_FragCoord.x / 64.0; }";
    let p = program(gl, n, VS_EYE, fs, &["eye"])?;
    let loc = gl.glGetUniformLocation(p, strata_protocol::Text::borrowed("proj"))?;
    gl.glUniformMatrix4fv(loc, false, Slice::new(&perspective(f64::from(NEAR), f64::from(FAR))))?;
    draw_positions(gl, n, &eye_quad(-1.0, -1.0, 1.0, 1.0, [0.6; 4]), TRIANGLES)?;
    let p = eye_program(gl, n, NEAR, FAR)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-1.0, -1.0, 1.0, 0.0, [1.0; 4]), TRIANGLES)?;
    gl.glDepthFunc(GREATER)?;
    color(gl, p, [0.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-1.0, 0.0, 1.0, 1.0, [3.0; 4]), TRIANGLES)
}

/// `GL_EXT_polygon_offset_clamp`: a red quad receding from 2 to 10 across x, then green bands
/// 3 % farther pulled forward by a slope-scaled offset under clamps 0 (unbounded), −0.0005
/// (short of the gap) and −0.01.
fn offset_clamp(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = eye_program(gl, n, NEAR, FAR)?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    draw_positions(gl, n, &eye_quad(-0.9, -0.9, 0.9, 0.9, [2.0, 10.0, 10.0, 2.0]), TRIANGLES)?;
    gl.glEnable(0x8037)?; // GL_POLYGON_OFFSET_FILL
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    for (band, clamp) in [0.0f32, -0.0005, -0.01].into_iter().enumerate() {
        gl.glPolygonOffsetClampEXT(-40.0, -4.0, clamp)?;
        let y0 = -0.9 + 0.6 * band as f32;
        draw_positions(gl, n, &eye_quad(-0.9, y0, 0.9, y0 + 0.6, [2.06, 10.3, 10.3, 2.06]), TRIANGLES)?;
    }
    gl.glDisable(0x8037)
}

/// A connection to `daemon` whose current surface is a W×H window surface with depth `depth`
/// declaring `projection`, at `rect`'s place.
fn window(daemon: &Daemon, name: &str, depth: i32, rect: [i32; 4], projection: Option<Projection>) -> Connection {
    window_current(daemon, name, depth, rect, projection).0
}

/// As [`window`], with the display and surface handles.
fn window_current(
    daemon: &Daemon,
    name: &str,
    depth: i32,
    rect: [i32; 4],
    projection: Option<Projection>,
) -> (Connection, Current) {
    let opts = ConnectOptions { socket: daemon.socket.clone(), name: name.into(), ..ConnectOptions::default() };
    let mut c = Connection::connect(&opts).expect("connect");
    let attribs = projection.map(|p| p.to_egl_attribs()).unwrap_or_default();
    let cur = egl_context_with(&mut c, depth, 0, SurfaceKind::Window { rect, z: 0.5 }, &attribs).expect("window");
    (c, cur)
}

fn perspective_decl(near: f32, far: f32) -> Projection {
    Projection { kind: ProjectionKind::Perspective, near, far, reversed: false }
}

/// Runs `run` from cleared buffers and reads the image back.
fn image(gl: Gl<'_>, run: Program) -> Vec<u8> {
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT).expect("clear");
    run(gl, &mut Names::default()).expect("program");
    assert_eq!(gl.glGetError().expect("io"), 0, "GL error after the program");
    gl.glReadPixels(0, 0, W, H, RGBA, UNSIGNED_BYTE).expect("read").0
}

#[test]
fn reversed_depth_is_invisible_to_the_application() {
    let _one_at_a_time = MESA.lock().unwrap_or_else(|e| e.into_inner());
    if let Err(e) = MesaGl::open(W, H) {
        assert!(!support::oracles_required(), "Mesa GLES2 unavailable ({e}) and oracles are required");
        eprintln!("SKIPPED: Mesa GLES2 unavailable ({e})");
        return;
    }
    let daemon = Daemon::start("reversed-z-oracle", &["--depth-format", "32float", "--reversed-z"]);
    let cases: [(&str, Program); 6] = [
        ("compare_funcs", compare_funcs),
        ("clear_and_range", clear_and_range),
        ("equal_and_offset", equal_and_offset),
        ("frag_coord_depth", frag_coord_depth),
        ("frag_depth_written", frag_depth_written),
        ("offset_clamp", offset_clamp),
    ];
    let mut failures = Vec::new();
    for (name, run) in cases {
        let expected = image(&mut MesaGl::open(W, H).expect("Mesa"), run);
        let mut colours: Vec<&[u8]> = expected.chunks(4).collect();
        colours.sort();
        colours.dedup();
        assert!(colours.len() >= 3, "{name}: Mesa's image shows too little to compare ({} colours)", colours.len());
        // Depth 32: the Depth32Float config, so the stored depth is float as the flag says.
        let mut c = window(&daemon, name, 32, [0, 0, W, H], Some(perspective_decl(NEAR, FAR)));
        let actual = image(&mut c, run);
        let differ = actual
            .chunks(4)
            .zip(expected.chunks(4))
            .filter(|(a, e)| a.iter().zip(e.iter()).any(|(x, y)| x.abs_diff(*y) > 1))
            .count();
        // Mesa's 24-bit unorm and the stored reversed float round differently only where two
        // surfaces meet: at most a few pixels along those lines.
        eprintln!("{name}: {differ} of {} pixels differ", W * H);
        if differ > 8 {
            failures.push(format!("{name}: {differ} pixels differ from Mesa's"));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(daemon.log_text().lines().all(|l| !l.contains("reversed-Z stage failed")));
}

/// Output size of the composite test.
const OW: i32 = 256;
const OH: i32 = 128;
/// Eye distance of the common base plane at NDC x = −1 and x = +1.
const BASE: [f64; 2] = [20.0, 60.0];
/// How far each plane leans off the base in 1/distance per NDC unit across the line.
const LEAN: f64 = 5e-6;
/// The line the planes meet along: x = SLANT · y (NDC).
const SLANT: f64 = 0.25;

/// 1/distance of surface `s`'s plane (s = +1 for A, −1 for B) at NDC (x, y).
fn inv_distance(s: f64, x: f64, y: f64) -> f64 {
    let t = (x + 1.0) / 2.0;
    (1.0 - t) / BASE[0] + t / BASE[1] + s * LEAN * (x - SLANT * y)
}

/// Draws surface `s`'s plane (full surface) in `color` and shows it.
fn draw_plane(gl: Gl<'_>, s: f64, near: f32, far: f32, rgba: [f32; 4]) -> Result<(), ClientError> {
    let n = &mut Names::default();
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = eye_program(gl, n, near, far)?;
    color(gl, p, rgba)?;
    let d = |x: f64, y: f64| (1.0 / inv_distance(s, x, y)) as f32;
    draw_positions(
        gl,
        n,
        &eye_quad(-1.0, -1.0, 1.0, 1.0, [d(-1.0, -1.0), d(1.0, -1.0), d(1.0, 1.0), d(-1.0, 1.0)]),
        TRIANGLES,
    )
}

/// Two surfaces under projections (0.1, 100) and (0.5, 200) composited by a daemon started
/// with `args`: the fraction of output pixels within 8 px of the planes' line (and more than
/// 1/4 px from it) whose surface is not the nearer one by the f64 geometry.
fn wrong_near_line(tag: &str, args: &[&str]) -> f64 {
    let size = format!("headless:main={OW}x{OH}");
    let mut all = vec!["--output", &size, "--lighting", "off"];
    all.extend_from_slice(args);
    let daemon = Daemon::start(tag, &all);
    let rect = [0, 0, OW, OH];
    let mut a = window_current(&daemon, "plane-a", 32, rect, Some(perspective_decl(0.1, 100.0)));
    let mut b = window_current(&daemon, "plane-b", 32, rect, Some(perspective_decl(0.5, 200.0)));
    for ((c, cur), s, (n, f), rgba) in
        [(&mut a, 1.0, (0.1, 100.0), [1.0, 0.0, 0.0, 1.0]), (&mut b, -1.0, (0.5, 200.0), [0.0, 0.0, 1.0, 1.0])]
    {
        c.glViewport(0, 0, OW, OH).expect("viewport");
        draw_plane(c, s, n, f, rgba).expect("plane");
        c.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
    }
    let file = daemon.dir.0.join("composite.png");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(20);
    let img = loop {
        let out = std::process::Command::new(support::stratad())
            .args(["ctl", "--socket"])
            .arg(&daemon.socket)
            .args(["screenshot", "main"])
            .arg(&file)
            .output()
            .expect("ctl screenshot");
        assert!(out.status.success(), "screenshot: {}", String::from_utf8_lossy(&out.stderr));
        let img = image::open(&file).expect("png").to_rgba8();
        let both = img.pixels().any(|p| p[0] > 128) && img.pixels().any(|p| p[2] > 128);
        if both {
            break img;
        }
        assert!(std::time::Instant::now() < deadline, "the two surfaces never showed together");
        std::thread::sleep(std::time::Duration::from_millis(50));
    };
    let px = 2.0 / f64::from(OW);
    let (mut near_line, mut wrong) = (0u32, 0u32);
    for (x, y, p) in img.enumerate_pixels() {
        let nx = (f64::from(x) + 0.5) * px - 1.0;
        let ny = 1.0 - (f64::from(y) + 0.5) * 2.0 / f64::from(OH);
        let off = nx - SLANT * ny;
        if off.abs() > 8.0 * px || off.abs() < 0.25 * px {
            continue;
        }
        near_line += 1;
        // A is nearer where its 1/distance is larger.
        let a_nearer = inv_distance(1.0, nx, ny) > inv_distance(-1.0, nx, ny);
        let shows_a = p[0] > p[2];
        if shows_a != a_nearer {
            wrong += 1;
        }
    }
    assert!(near_line > 1000, "too few pixels near the line: {near_line}");
    drop((a, b));
    f64::from(wrong) / f64::from(near_line)
}

#[test]
fn reversed_float_depth_composites_as_the_f64_geometry_does() {
    let reversed = wrong_near_line("reversed-z-composite", &["--depth-format", "32float", "--reversed-z"]);
    let forward = wrong_near_line("forward-composite", &["--depth-format", "32float"]);
    eprintln!("wrong near the line: reversed {:.3}%, forward {:.3}%", reversed * 100.0, forward * 100.0);
    assert!(reversed <= 0.002, "reversed 32float: {:.3}% wrong near the line", reversed * 100.0);
    assert!(forward >= 0.03, "forward 32float should err near the line, got {:.3}%", forward * 100.0);
}

/// With depth test EQUAL, whether a quad at window depth `b` passes over one at `a`, drawn
/// into a window surface of a daemon started with `args` (no projection: window depth is
/// (z + 1)/2 of a w = 1 clip position).
fn equal_passes(daemon: &Daemon, name: &str, a: f64, b: f64) -> bool {
    let mut c = window(daemon, name, 32, [0, 0, 16, 16], None);
    let gl: Gl<'_> = &mut c;
    let n = &mut Names::default();
    gl.glEnable(DEPTH_TEST).expect("io");
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT).expect("io");
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"]).expect("program");
    let z = |d: f64| (2.0 * d - 1.0) as f32;
    color(gl, p, [1.0, 0.0, 0.0, 1.0]).expect("io");
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, z(a)), TRIANGLES).expect("draw");
    gl.glDepthFunc(EQUAL).expect("io");
    color(gl, p, [0.0, 1.0, 0.0, 1.0]).expect("io");
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, z(b)), TRIANGLES).expect("draw");
    let px = gl.glReadPixels(8, 8, 1, 1, RGBA, UNSIGNED_BYTE).expect("read").0;
    px[1] > 128
}

#[test]
fn depth_format_16unorm_stores_16_bits() {
    // Two depths a quarter of a 16-bit step apart, both rounding to step 30000 (Depth16Unorm
    // stores round(d · 65535)), and two that round to different steps.
    let step = 1.0f64 / 65535.0;
    let (a, same, other) = (30000.0 * step, 30000.25 * step, 30000.75 * step);
    assert_eq!((a / step).round(), (same / step).round());
    assert_ne!((a / step).round(), (other / step).round());
    let d16 = Daemon::start("depth-16unorm", &["--depth-format", "16unorm"]);
    assert!(equal_passes(&d16, "same-step", a, same), "16unorm: depths within one step must compare equal");
    assert!(!equal_passes(&d16, "next-step", a, other), "16unorm: depths a step apart must differ");
    // The depth-32 config's own format, 32-bit float, tells the first pair apart.
    let d32 = Daemon::start("depth-config", &[]);
    assert!(!equal_passes(&d32, "float", a, same), "32float: depths 4e-6 apart must differ");
}

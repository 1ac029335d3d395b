//! Non-finite numbers from a client (docs/precision.md, "Extremes"): vertex positions and
//! uniforms holding NaN or ±inf reach the GPU as they are, with no GL error. The daemon does not
//! panic, each draw shows what Mesa shows (a primitive with a NaN vertex is discarded, the
//! others of the same draw are drawn), and the client's session goes on.

mod programs;
mod support;

use programs::harness::{compare, render, render_with, strata_context};
use programs::*;
use strata_client::ClientError;
use strata_protocol::Text;
use support::mesa::MesaGl;
use support::Daemon;

/// GL_POINTS.
const POINTS: u32 = 0x0000;
const NAN: f32 = f32::NAN;
const INF: f32 = f32::INFINITY;

/// Triangles, a fan, lines and points with NaN or infinite vertices, a colour uniform of
/// (inf, NaN, 0.5, 1), and a position offset uniform of NaN.
fn nonfinite(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    #[rustfmt::skip]
    let tris = [
        -0.95, -0.95, 0.0, -0.55, -0.95, 0.0, -0.75, -0.35, 0.0, // finite
        -0.45, -0.95, 0.0, -0.05, -0.95, 0.0, NAN, -0.35, 0.0,   // a NaN x
        0.05, -0.95, 0.0, 0.45, -0.95, NAN, 0.25, -0.35, 0.0,    // a NaN z
        0.05, -0.3, 0.0, 0.45, -0.3, 0.0, INF, -0.1, 0.0,        // an infinite x
    ];
    draw_positions(gl, n, &tris, TRIANGLES)?;
    // A fan with one NaN vertex: the two triangles that use it go.
    #[rustfmt::skip]
    let fan = [
        0.75, -0.75, 0.0, 0.95, -0.95, 0.0, 0.95, -0.55, 0.0,
        NAN, -0.55, 0.0, 0.55, -0.55, 0.0, 0.55, -0.95, 0.0,
    ];
    draw_positions(gl, n, &fan, TRIANGLE_FAN)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &[-0.9, 0.1, 0.0, -0.1, 0.1, 0.0, -0.9, 0.3, 0.0, NAN, 0.3, 0.0], LINES)?;
    // Points, sized by the vertex stage.
    let vs = "attribute vec4 pos; void main() { gl_Position = pos; gl_PointSize = 4.0; }";
    let q = program(gl, n, vs, FS_COLOR, &["pos"])?;
    color(gl, q, [0.0, 0.0, 1.0, 1.0])?;
    draw_positions(gl, n, &[-0.5, 0.5, 0.0, NAN, 0.6, 0.0, -0.3, NAN, 0.0], POINTS)?;
    // Uniforms: an unrepresentable colour, and an offset that makes every vertex NaN.
    gl.glUseProgram(p)?;
    color(gl, p, [INF, NAN, 0.5, 1.0])?;
    draw_positions(gl, n, &quad(0.1, 0.1, 0.9, 0.5, 0.0), TRIANGLES)?;
    let vs = "uniform vec4 off; attribute vec4 pos; void main() { gl_Position = pos + off; }";
    let o = program(gl, n, vs, FS_COLOR, &["pos"])?;
    color(gl, o, [1.0, 1.0, 0.0, 1.0])?;
    let loc = gl.glGetUniformLocation(o, Text::borrowed("off"))?;
    gl.glUniform4f(loc, NAN, 0.0, 0.0, 0.0)?;
    draw_positions(gl, n, &quad(0.1, 0.55, 0.9, 0.95, 0.0), TRIANGLES)
}

/// The RGBA8 pixel at window (x, y) of a W×H image read bottom row first.
fn at(img: &[u8], x: i32, y: i32) -> [u8; 4] {
    let i = ((y * W + x) * 4) as usize;
    [img[i], img[i + 1], img[i + 2], img[i + 3]]
}

#[test]
fn nan_and_infinite_vertices_and_uniforms_draw_as_mesa_and_the_session_goes_on() {
    let case = Case { name: "nonfinite", run: nonfinite, tol: DEFAULT, expects_error: false };
    let cases = programs::all();
    let after = cases.iter().find(|c| c.name == "triangle_flat").expect("a later program");
    let mesa = |c: &Case| MesaGl::open(W, H).map_err(ClientError::Unsupported).and_then(|mut m| render(&mut m, c));
    let expected = match mesa(&case) {
        Ok(e) => e,
        Err(e) if !support::oracles_required() => {
            eprintln!("SKIPPED: Mesa GLES2 unavailable ({e}); install libegl-mesa0 libgles2 to run this test");
            return;
        }
        Err(e) => panic!("Mesa GLES2 unavailable ({e}) and STRATA_REQUIRE_ORACLES is set"),
    };
    let after_expected = mesa(after).expect("mesa");

    let daemon = Daemon::start("gles-nonfinite", &[]);
    let mut gl = strata_context(&daemon.socket, "nonfinite").expect("client");
    let img = render(&mut gl, &case).expect("non-finite draws raise no GL error");
    if let Some(why) = compare(&case, &img, &expected) {
        panic!("non-finite draws differ from Mesa: {why}");
    }
    // The finite triangle is drawn, the one with a NaN vertex is not (as Mesa).
    assert_eq!(at(&img, 8, 8), [255, 0, 0, 255], "the finite triangle");
    assert_eq!(at(&img, 24, 5), [0, 0, 0, 0], "the triangle with a NaN vertex");
    assert_eq!(at(&img, 40, 5), [0; 4], "the triangle with a NaN z");
    assert_eq!([at(&img, 60, 8), at(&img, 52, 8)], [[255, 0, 0, 255]; 2], "the fan's finite triangles");
    assert_eq!(at(&img, 56, 12), [0; 4], "the fan's triangles with the NaN vertex");
    assert_eq!(at(&img, 48, 40), [255, 0, 128, 255], "colour (inf, NaN, 0.5, 1): inf as 1, NaN as 0");
    assert_eq!(at(&img, 48, 56), [0; 4], "a NaN offset: every vertex NaN, nothing drawn");
    // The session goes on: later rendering is Mesa's.
    let next = render_with(&mut gl, after, &mut Names::starting_at(10_000)).expect("later render");
    assert!(compare(after, &next, &after_expected).is_none(), "rendering after non-finite input differs from Mesa");
    assert!(!daemon.log_text().contains("panicked"), "daemon panicked:\n{}", daemon.log_text());
}

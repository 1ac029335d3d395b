//! `GL_EXT_clip_control`: the same geometry in each of the four states, one per quadrant,
//! showing the window origin (an asymmetric shape, both windings coloured by
//! `gl_FrontFacing`, culling), the clip depth range (`gl_FragCoord.z` as red, geometry
//! behind clip z 0 clipped in `GL_ZERO_TO_ONE_EXT`, with a depth range), and point sprites'
//! `gl_PointCoord`; the state's queries and errors, all as colours.

use super::multi_draw::mark_all;
use super::*;

const LOWER_LEFT: u32 = 0x8CA1;
const UPPER_LEFT: u32 = 0x8CA2;
const CLIP_ORIGIN: u32 = 0x935C;
const CLIP_DEPTH_MODE: u32 = 0x935D;
const NEGATIVE_ONE_TO_ONE: u32 = 0x935E;
const ZERO_TO_ONE: u32 = 0x935F;
const BACK: u32 = 0x0405;

const VS: &str = "attribute vec4 pos; attribute vec4 col; varying vec4 v;
    void main() { v = col; gl_Position = pos; gl_PointSize = 9.0; }";

/// Window depth as red, facing as green, the colour's blue.
const FS_FACING: &str = "precision mediump float; varying vec4 v;
    void main() { gl_FragColor = vec4(gl_FragCoord.z, gl_FrontFacing ? 1.0 : 0.25, v.b, 1.0); }";

/// The sprite coordinate as red and green.
const FS_POINT: &str = "precision mediump float; varying vec4 v;
    void main() { gl_FragColor = vec4(gl_PointCoord, v.b, 1.0); }";

/// Sets the state, marking the error and both queries.
fn set(gl: Gl<'_>, marks: &mut Vec<u32>, origin: u32, depth: u32) -> R {
    gl.glClipControlEXT(origin, depth)?;
    marks.push(gl.glGetError()?);
    for pname in [CLIP_ORIGIN, CLIP_DEPTH_MODE] {
        marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-1) as u32);
    }
    Ok(())
}

/// The scene of one quadrant: an asymmetric shape counter-clockwise on the left, clockwise
/// on the right, clip z running from -0.9 to 0.9 across it; then three sprites.
fn scene(gl: Gl<'_>, n: &mut Names, facing: u32, point: u32) -> R {
    gl.glUseProgram(facing)?;
    let vertex = |x: f32, y: f32| [x, y, x * 0.9, 0.0, 0.0, (y + 1.0) / 2.0, 1.0];
    vertex_quad(gl, n, [-1.0, -1.0, 0.0, 0.3], vertex)?;
    vertex_quad(gl, n, [1.0, -0.6, 0.0, 0.3], vertex)?;
    gl.glUseProgram(point)?;
    // No sprite edge falls on a pixel centre, where the two flips' tie rules would differ.
    let v: Vec<f32> = [(-0.6, 0.62), (0.03, 0.71), (0.6, 0.77)]
        .iter()
        .flat_map(|&(x, y): &(f32, f32)| [x, y, 0.5, 0.0, 0.0, (x + 1.0) / 2.0, 1.0])
        .collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    gl.glDrawArrays(POINTS, 0, 3)
}

fn clip_control(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    for pname in [CLIP_ORIGIN, CLIP_DEPTH_MODE] {
        marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-1) as u32);
    }
    // Each bad enum is an error that leaves the state as it was.
    set(gl, &mut marks, UPPER_LEFT, ZERO_TO_ONE)?;
    set(gl, &mut marks, 0x1234, NEGATIVE_ONE_TO_ONE)?;
    set(gl, &mut marks, LOWER_LEFT, 0x1234)?;
    set(gl, &mut marks, ZERO_TO_ONE, UPPER_LEFT)?;
    let facing = program(gl, n, VS, FS_FACING, &["pos", "col"])?;
    let point = program(gl, n, VS, FS_POINT, &["pos", "col"])?;
    let quadrants = [
        ((0, 0), LOWER_LEFT, NEGATIVE_ONE_TO_ONE, false),
        ((32, 0), UPPER_LEFT, NEGATIVE_ONE_TO_ONE, false),
        ((0, 26), LOWER_LEFT, ZERO_TO_ONE, false),
        ((32, 26), UPPER_LEFT, ZERO_TO_ONE, true),
    ];
    for ((x, y), origin, depth, cull) in quadrants {
        set(gl, &mut marks, origin, depth)?;
        // 24 rows high: the marks take the picture's top 12.
        gl.glViewport(x, y, 32, 24)?;
        if depth == ZERO_TO_ONE {
            gl.glDepthRangef(0.25, 0.75)?;
        }
        if cull {
            gl.glEnable(CULL_FACE)?;
            gl.glCullFace(BACK)?;
        }
        scene(gl, n, facing, point)?;
        marks.push(gl.glGetError()?);
    }
    gl.glDisable(CULL_FACE)?;
    gl.glViewport(0, 0, W, H)?;
    set(gl, &mut marks, LOWER_LEFT, NEGATIVE_ONE_TO_ONE)?;
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "clip_control", run: clip_control, tol: DEFAULT, expects_error: false }]
}

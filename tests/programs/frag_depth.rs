//! `GL_EXT_frag_depth`: a fragment shader's `gl_FragDepthEXT` is the depth its fragment is
//! tested and stored with, clamped to [0, 1]; in a depth texture (sampled back, as in
//! `depth_texture_render_and_sample`) and in the window surface's own depth buffer.

use super::*;

/// Writes depth from the varying's x, which runs from −0.25 to 1.25 across the quad: clamped
/// at both ends, a gradient between.
const FS_WRITE_DEPTH: &str = "#extension GL_EXT_frag_depth : enable
precision highp float;
varying vec4 v;
void main() {
    gl_FragColor = vec4(1.0, 0.0, 0.0, 1.0);
    gl_FragDepthEXT = v.x;
}";

/// A full-screen quad at clip z `z` whose colour attribute's x runs −0.25..1.25 left to right
/// and whose y runs 0..1 bottom to top.
fn gradient_quad(gl: Gl<'_>, n: &mut Names, z: f32) -> R {
    vertex_quad(gl, n, [-1.0, -1.0, 1.0, 1.0], |x, y| [x, y, z, 0.5 + 0.75 * x, (y + 1.0) / 2.0, 0.0, 1.0])
}

/// Depth written by the shader into a depth texture (every fragment passes), then shown.
fn frag_depth_into_texture(gl: Gl<'_>, n: &mut Names) -> R {
    let tex = depth_texture_target(gl, n, 32)?;
    gl.glDepthFunc(0x0207)?; // GL_ALWAYS
    gl.glClear(DEPTH_BUFFER_BIT)?;
    program(gl, n, VS_COLOR, FS_WRITE_DEPTH, &["pos", "col"])?;
    // The geometry's own depth (0.9) is replaced by the shader's.
    gradient_quad(gl, n, 0.9)?;
    show_depth_texture(gl, n, tex)
}

/// The window's own depth buffer: a red quad at depth 0 whose shader writes the gradient, then
/// a green quad at window depth 0.5 with GL_LESS: green only where the written depth is
/// greater than 0.5 (right of the middle), although the red quad's geometry is nearer.
fn frag_depth_tested_in_the_window(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClearDepthf(1.0)?;
    gl.glClear(DEPTH_BUFFER_BIT | COLOR_BUFFER_BIT)?;
    program(gl, n, VS_COLOR, FS_WRITE_DEPTH, &["pos", "col"])?;
    gradient_quad(gl, n, -1.0)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    // As cases.rs' depth_tol: fract(16·d) magnifies the difference between Mesa's unorm depth
    // and wgpu's depth storage sixteenfold, so that channel's last bit may round either way.
    let depth_tol = Tol { max_diff: 2, min_fraction: 0.999 };
    // The gradient crosses 0.5 between two pixel columns; which side the column at the
    // crossing falls on may differ by the last bit of interpolation (one column of 64).
    let edge_tol = Tol { max_diff: 1, min_fraction: 0.98 };
    vec![
        Case { name: "frag_depth_into_texture", run: frag_depth_into_texture, tol: depth_tol, expects_error: false },
        Case {
            name: "frag_depth_tested_in_the_window",
            run: frag_depth_tested_in_the_window,
            tol: edge_tol,
            expects_error: false,
        },
    ]
}

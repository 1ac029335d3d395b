//! `GL_OES_standard_derivatives`: `dFdx`, `dFdy` and `fwidth` in a fragment shader, and the
//! derivative hint.

use super::*;

/// `GL_FRAGMENT_SHADER_DERIVATIVE_HINT_OES` and `GL_NICEST`.
const DERIVATIVE_HINT: u32 = 0x8B8B;
const NICEST: u32 = 0x1102;

/// Screen-space derivatives of a linear varying (exact: constant over the triangle) and of a
/// quadratic one (per 2×2 quad), scaled so they are visible.
const FS_DERIVATIVES: &str = "#extension GL_OES_standard_derivatives : enable
precision highp float;
varying vec4 v;
void main() {
    float q = v.x * v.y;
    gl_FragColor = vec4(dFdx(v.x) * 16.0, dFdy(v.y) * 16.0, fwidth(q) * 8.0, 1.0);
}";

/// A quad whose varying runs 0..1 across x and 0..2 up y, shaded by derivatives.
fn derivatives(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glHint(DERIVATIVE_HINT, NICEST)?;
    program(gl, n, VS_COLOR, FS_DERIVATIVES, &["pos", "col"])?;
    vertex_quad(gl, n, [-1.0, -1.0, 1.0, 1.0], |x, y| [x, y, 0.0, (x + 1.0) / 2.0, y + 1.0, 0.0, 1.0])
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    // Both rasterisers difference 2×2 quads, but the quadratic term's derivative rounds
    // differently in the last bits between the two shader compilers (as `math_tol` in cases.rs).
    let tol = Tol { max_diff: 3, min_fraction: 0.995 };
    vec![Case { name: "standard_derivatives", run: derivatives, tol, expects_error: false }]
}

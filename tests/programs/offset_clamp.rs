//! `GL_EXT_polygon_offset_clamp`: `glPolygonOffsetClampEXT` bounds the offset a polygon gets.

use super::*;

/// A tilted red quad, then four green bands a little behind it, each pulled forward by a
/// large slope-scaled offset under its own clamp: none (0), −0.01 (short of the gap, so the
/// red stays in front), −0.05 (past it) and +0.01 (a positive clamp bounds only positive
/// offsets). Then the state as `glGetFloatv` answers it, drawn as grey levels.
fn polygon_offset_clamp(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
    // Clip z from −0.9 on the left to 0.9 on the right: window depth 0.05 … 0.95.
    let tilted = |y0: f32, y1: f32, dz: f32| -> Vec<f32> {
        let (l, r) = (-0.9 + dz, 0.9 + dz);
        vec![-1.0, y0, l, 1.0, y0, r, 1.0, y1, r, -1.0, y0, l, 1.0, y1, r, -1.0, y1, l]
    };
    draw_positions(gl, n, &tilted(-1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glEnable(POLYGON_OFFSET_FILL)?;
    color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
    // 0.04 in clip z is 0.02 in window depth behind the red quad.
    for (band, clamp) in [0.0f32, -0.01, -0.05, 0.01].into_iter().enumerate() {
        gl.glPolygonOffsetClampEXT(-20.0, 0.0, clamp)?;
        let y0 = -1.0 + 0.5 * band as f32;
        draw_positions(gl, n, &tilted(y0, y0 + 0.5, 0.04), TRIANGLES)?;
    }
    gl.glDisable(POLYGON_OFFSET_FILL)?;
    gl.glDisable(DEPTH_TEST)?;
    // The last state set, as the query returns it: factor, units, clamp.
    gl.glPolygonOffsetClampEXT(-0.25, 0.5, 0.75)?;
    let f = |pname: u32, gl: Gl<'_>| -> Result<f32, ClientError> {
        Ok(gl.glGetFloatv(pname)?.first().copied().unwrap_or(f32::NAN))
    };
    let state = [f(0x8038, gl)?, f(0x2A00, gl)?, f(0x8E1B, gl)?];
    let shown = [state[0] + 0.5, state[1], state[2]];
    color(gl, p, [shown[0], shown[1], shown[2], 1.0])?;
    draw_positions(gl, n, &quad(-0.25, -0.25, 0.25, 0.25, 0.0), TRIANGLES)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "polygon_offset_clamp", run: polygon_offset_clamp, tol: DEFAULT, expects_error: false }]
}

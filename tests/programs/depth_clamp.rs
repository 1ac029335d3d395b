//! `GL_EXT_depth_clamp`: a quad whose depth runs from in front of the near plane to beyond the
//! far plane, drawn into a depth texture with the depth range [0.25, 0.75], clamped (left) and
//! clipped (right); the depths shown; the capability's queries and errors marked as colours.

use super::multi_draw::mark_all;
use super::*;

const DEPTH_CLAMP: u32 = 0x864F;
const ALWAYS: u32 = 0x0207;
/// The sampled depth in red (`FS_DEPTH`'s magnified fraction shows how the two rasterizers
/// quantize a depth gradient, which is not what this program compares).
const FS_DEPTH_RED: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { gl_FragColor = vec4(texture2D(s, t).r, 0.0, 0.0, 1.0); }";

fn depth_clamp(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = vec![u32::from(gl.glIsEnabled(DEPTH_CLAMP)?)];
    let tex = depth_texture_target(gl, n, 64)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    gl.glDepthFunc(ALWAYS)?;
    gl.glDepthRangef(0.25, 0.75)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    for (clamp, [x0, x1]) in [(true, [-1.0, 0.0]), (false, [0.0, 1.0])] {
        if clamp {
            gl.glEnable(DEPTH_CLAMP)?;
        } else {
            gl.glDisable(DEPTH_CLAMP)?;
        }
        marks.push(gl.glGetError()?);
        // Mesa held to ES 2.0 answers glGet*v(GL_DEPTH_CLAMP_EXT) with GL_INVALID_ENUM, where
        // the extension lists those queries (Strata answers them): only glIsEnabled is compared.
        marks.push(u32::from(gl.glIsEnabled(DEPTH_CLAMP)?));
        // Clip z from -2 at the bottom to 2 at the top, and across x a little.
        vertex_quad(gl, n, [x0, -1.0, x1, 1.0], |x, y| [x, y, 2.0 * y + 0.1 * x, 1.0, 1.0, 1.0, 1.0])?;
    }
    gl.glDepthRangef(0.0, 1.0)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    program(gl, n, VS_TEX, FS_DEPTH_RED, &["pos", "uv"])?;
    textured_quad(gl, n, 0.0, 1.0)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case { name: "depth_clamp", run: depth_clamp, tol: DEFAULT, expects_error: false }]
}

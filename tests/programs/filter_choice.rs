//! The choice between the magnification and minification filters by the level of detail:
//! a 16×16 texture drawn smaller (λ above 0: the minification filter) and larger (λ below 0:
//! the magnification filter), with the two filters different, without a mipmap filter and
//! with a nearest one over a single level, and with `GL_TEXTURE_MAX_LOD` 0 (ES 3.0; always
//! magnified).

use super::*;

const TEXTURE_MAX_LEVEL: u32 = 0x813D;
const TEXTURE_MAX_LOD: u32 = 0x813B;

/// Draws the bound texture over the square of `size` pixels at (`x`, `y`).
fn square(gl: Gl<'_>, n: &mut Names, [x, y, size]: [i32; 3]) -> R {
    gl.glViewport(x, y, size, size)?;
    // Coordinates a little inside the image: no pixel centre falls on a texel edge.
    textured_quad(gl, n, 0.013, 0.991)
}

/// The filter choices over both sizes; `es3`: with the level-of-detail clamp too.
fn choices(gl: Gl<'_>, n: &mut Names, es3: bool) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    texture(gl, n, 16, 16, RGBA, UNSIGNED_BYTE, &pattern(16, 16), NEAREST, CLAMP_TO_EDGE)?;
    let combos = [(NEAREST, LINEAR), (LINEAR, NEAREST), (NEAREST_MIPMAP_NEAREST, LINEAR)];
    for (k, (min, mag)) in combos.into_iter().enumerate() {
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, min)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, mag)?;
        if min == NEAREST_MIPMAP_NEAREST {
            gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 0)?;
        }
        let y = k as i32 * 21;
        square(gl, n, [0, y, 11])?;
        square(gl, n, [12, y, 20])?;
    }
    if es3 {
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
        gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 0.0)?;
        square(gl, n, [34, 0, 11])?;
    }
    gl.glViewport(0, 0, W, H)
}

/// ES 2.0's filters (`GL_TEXTURE_MAX_LEVEL` of `GL_APPLE_texture_max_level`).
fn filter_choice(gl: Gl<'_>, n: &mut Names) -> R {
    choices(gl, n, false)
}

/// Every program of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "filter_choice", run: filter_choice, tol: DEFAULT, expects_error: false }]
}

/// ES 3.0's, with `GL_TEXTURE_MAX_LOD`.
pub fn filter_choice_es3(gl: Gl<'_>, n: &mut Names) -> R {
    choices(gl, n, true)
}

//! Sampler arrays (GLSL ES 1.00 §4.1.9, Appendix A): elements indexed by constants and by a
//! loop index, passed to a function, and set with one `glUniform1iv`; and arrays of float
//! varyings.

use super::*;

/// Three textures through `s[3]`: a loop over the elements with per-element weights, a constant
/// element, and an element passed to a function taking a `sampler2D`.
const FS_SAMPLER_ARRAY: &str = "precision mediump float;
uniform sampler2D s[3];
varying vec2 t;
varying float w[2];
vec4 swizzled(sampler2D x, vec2 uv) { return texture2D(x, uv.yx).gbra; }
void main() {
    vec4 c = vec4(0.0);
    for (int i = 0; i < 3; i++) {
        c += texture2D(s[i], t) * (0.15 + 0.1 * float(i));
    }
    c += texture2D(s[1], t * 0.5) * w[0];
    c += swizzled(s[2], t) * w[1];
    gl_FragColor = c;
}";

/// `VS_TEX` that also writes an array of float varyings from the position.
const VS_FLOAT_ARRAY: &str = "attribute vec4 pos; attribute vec2 uv; varying vec2 t; varying float w[2];
void main() { t = uv; w[0] = 0.25 + 0.125 * pos.x; w[1] = 0.25 - 0.125 * pos.y; gl_Position = pos; }";

/// Binds a 4×4 texture of pixels `px` to unit `unit`.
fn unit_texture(gl: Gl<'_>, n: &mut Names, unit: u32, px: &[u8]) -> R {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glActiveTexture(TEXTURE0 + unit)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(px)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)
}

fn sampler_array(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_FLOAT_ARRAY, FS_SAMPLER_ARRAY, &["pos", "uv"])?;
    let base = pattern(4, 4);
    let inverted: Vec<u8> = base.iter().enumerate().map(|(i, &b)| if i % 4 == 3 { b } else { 255 - b }).collect();
    let rotated: Vec<u8> = base.chunks(4).flat_map(|c| [c[2], c[0], c[1], c[3]]).collect();
    // Units out of order, so that an element reading the wrong unit shows.
    unit_texture(gl, n, 4, &base)?;
    unit_texture(gl, n, 1, &inverted)?;
    unit_texture(gl, n, 6, &rotated)?;
    let loc = gl.glGetUniformLocation(p, Text::borrowed("s"))?;
    gl.glUniform1iv(loc, Slice::new(&[4, 1, 6]))?;
    // `s[1]` by its own location: the same unit again.
    let second = gl.glGetUniformLocation(p, Text::borrowed("s[1]"))?;
    gl.glUniform1i(second, 1)?;
    textured_quad(gl, n, 0.0, 1.0)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "sampler_array", run: sampler_array, tol: DEFAULT, expects_error: false }]
}

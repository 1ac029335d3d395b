//! ES 3.0's signed normalized formats: `GL_R8_SNORM` … `GL_RGBA8_SNORM` from `GL_BYTE` data
//! (-128 and -127 both -1, 127 one), sampled nearest and filtered, as immutable storage with a
//! sub-image; no colour attachment; the pairings the table refuses, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const RED: u32 = 0x1903;
const RG: u32 = 0x8227;
const R8_SNORM: u32 = 0x8F94;
const RG8_SNORM: u32 = 0x8F95;
const RGB8_SNORM: u32 = 0x8F96;
const RGBA8_SNORM: u32 = 0x8F97;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
// Signed values shown in [0, 1], magnified so that a conversion off by a fraction of a step
// shows.
const FS: &str = "#version 300 es
    precision highp float;
    uniform sampler2D s; uniform vec2 uv;
    out vec4 o;
    void main() { o = fract(texture(s, uv) * 4.0 + 4.25); }";

/// Signed bytes as the bytes an upload carries.
fn signed(v: &[i8]) -> Vec<u8> {
    v.iter().map(|b| *b as u8).collect()
}

/// A new 2D texture bound on unit 0, filtered by `filter`.
fn new_texture(gl: Gl<'_>, n: &mut Names, filter: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, filter)?;
    Ok(t)
}

/// The signed normalized program.
pub fn snorm(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let uv = gl.glGetUniformLocation(p, Text::borrowed("uv"))?;
    let cell = |gl: Gl<'_>, n: &mut Names, k: usize, u: f32| -> R {
        gl.glUniform2f(uv, u, 0.5)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    };
    gl.glActiveTexture(TEXTURE0)?;
    let mut marks = Vec::new();

    // Two RGBA texels at the ends of the range, filtered between them.
    new_texture(gl, n, NEAREST)?;
    let texels = signed(&[-128, -127, 127, 0, 64, -64, 1, -1]);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA8_SNORM as i32, 2, 1, 0, RGBA, BYTE, Some(Blob::borrowed(&texels)))?;
    cell(gl, n, 0, 0.25)?;
    cell(gl, n, 1, 0.75)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    cell(gl, n, 2, 0.5)?;
    let cases: [(u32, u32, Vec<u8>); 3] = [
        (RGB8_SNORM, RGB, signed(&[100, -50, 25])),
        (RG8_SNORM, RG, signed(&[-90, 45])),
        (R8_SNORM, RED, signed(&[-20])),
    ];
    for (k, (internal, format, data)) in cases.iter().enumerate() {
        new_texture(gl, n, NEAREST)?;
        gl.glTexImage2D(TEXTURE_2D, 0, *internal as i32, 1, 1, 0, *format, BYTE, Some(Blob::borrowed(data)))?;
        cell(gl, n, 3 + k, 0.5)?;
    }
    // Immutable storage, a texel written by a sub-image.
    let t = new_texture(gl, n, NEAREST)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, RGBA8_SNORM, 2, 1)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 1, 1, RGBA, BYTE, Blob::borrowed(&signed(&[-100, 80, -5, 127])))?;
    cell(gl, n, 6, 0.75)?;

    // No colour attachment, and the pairings the table refuses.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    new_texture(gl, n, NEAREST)?;
    let refused: [(u32, u32, u32); 3] =
        [(R8_SNORM, RED, UNSIGNED_BYTE), (RGBA8_SNORM, RGB, BYTE), (RGBA8_SNORM, RGBA, FLOAT)];
    for (internal, format, ty) in refused {
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 1, 1, 0, format, ty, None)?;
        marks.push(gl.glGetError()?);
    }
    // Byte data into a half-float image is refused.
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, 0x8D61, None)?;
    marks.push(gl.glGetError()?);
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, BYTE, Blob::borrowed(&[0; 4]))?;
    marks.push(gl.glGetError()?);
    // Byte data into an 8-bit unsigned image is refused too.
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, BYTE, Blob::borrowed(&[0; 4]))?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

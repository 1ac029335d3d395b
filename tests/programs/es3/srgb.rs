//! ES 3.0's sRGB formats: `GL_SRGB8_ALPHA8` and `GL_SRGB8` images sampled as linear colour
//! (nearest and filtered, whole and as immutable storage with a sub-image), an `SRGB8_ALPHA8`
//! image rendered to (a clear and a draw written in linear and encoded, blending in linear)
//! and read back encoded; the attachment's colour encoding, an `SRGB8` attachment refused, and
//! the pairings the table refuses, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const SRGB8_ALPHA8: u32 = 0x8C43;
const SRGB8: u32 = 0x8C41;
const COLOR_ENCODING: u32 = 0x8210;
const ONE: u32 = 1;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform sampler2D s; uniform vec2 uv;
    out vec4 o;
    void main() { o = texture(s, uv); }";
const FS_QUARTER: &str = "#version 300 es
    precision highp float;
    out vec4 o;
    void main() { o = vec4(0.25, 0.5, 0.125, 0.75); }";

/// A new 2D texture bound on unit 0, filtered by `filter`.
fn new_texture(gl: Gl<'_>, n: &mut Names, filter: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, filter)?;
    Ok(t)
}

/// The sRGB program.
pub fn srgb(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let uv = gl.glGetUniformLocation(p, Text::borrowed("uv"))?;
    let cell = |gl: Gl<'_>, n: &mut Names, k: usize, u: f32| -> R {
        gl.glUniform2f(uv, u, 0.5)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    };
    gl.glActiveTexture(TEXTURE0)?;
    let mut marks = Vec::new();

    // Encoded texels, read as linear colour; filtering between them in linear.
    let texels = [128, 64, 200, 255, 32, 240, 90, 128];
    new_texture(gl, n, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, SRGB8_ALPHA8 as i32, 2, 1, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&texels)))?;
    cell(gl, n, 0, 0.25)?;
    cell(gl, n, 1, 0.75)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    cell(gl, n, 2, 0.5)?;
    new_texture(gl, n, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, SRGB8 as i32, 1, 1, 0, RGB, UNSIGNED_BYTE, Some(Blob::borrowed(&[100, 180, 20])))?;
    cell(gl, n, 3, 0.5)?;
    new_texture(gl, n, NEAREST)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, SRGB8_ALPHA8, 2, 1)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[10, 150, 250, 200]))?;
    cell(gl, n, 4, 0.75)?;

    // Rendered to: a clear in one texel, a draw in the other, then the draw again blended.
    let target = new_texture(gl, n, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, SRGB8_ALPHA8 as i32, 2, 1, 0, RGBA, UNSIGNED_BYTE, None)?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, target, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, COLOR_ENCODING)? as u32);
    gl.glViewport(0, 0, 2, 1)?;
    gl.glClearColor(0.5, 0.2, 0.05, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glViewport(1, 0, 1, 1)?;
    program(gl, n, VS, FS_QUARTER, &[])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(ONE, ONE)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glDisable(BLEND)?;
    // Read back encoded: each channel of both texels a mark.
    let px = gl.glReadPixels(0, 0, 2, 1, RGBA, UNSIGNED_BYTE)?.0;
    marks.extend(px.iter().map(|b| u32::from(*b)));
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glUseProgram(p)?;
    gl.glBindTexture(TEXTURE_2D, target)?;
    cell(gl, n, 5, 0.25)?;
    cell(gl, n, 6, 0.75)?;

    // An SRGB8 image is no colour attachment; the pairings the table refuses.
    let rgb = new_texture(gl, n, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, SRGB8 as i32, 1, 1, 0, RGB, UNSIGNED_BYTE, None)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, rgb, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    let refused: [(u32, u32, u32); 3] =
        [(SRGB8_ALPHA8, RGBA, FLOAT), (SRGB8, RGBA, UNSIGNED_BYTE), (SRGB8_ALPHA8, RGB, UNSIGNED_BYTE)];
    for (internal, format, ty) in refused {
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 1, 1, 0, format, ty, None)?;
        marks.push(gl.glGetError()?);
    }
    mark_all(gl, &marks)
}

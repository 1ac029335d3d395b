//! ES 3.0's float depth textures in `glTexImage2D`: `GL_DEPTH_COMPONENT32F` from `GL_FLOAT`
//! depths (clamped to [0, 1]) and `GL_DEPTH32F_STENCIL8` from
//! `GL_FLOAT_32_UNSIGNED_INT_24_8_REV` data, sampled as their red channel, a texel replaced by
//! a sub-image; one as a framebuffer's depth (a depth test between two quads, then sampled);
//! and the pairings ES 3.0's table refuses, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const DEPTH_COMPONENT: u32 = 0x1902;
const DEPTH_STENCIL: u32 = 0x84F9;
const DEPTH_COMPONENT32F: u32 = 0x8CAC;
const DEPTH32F_STENCIL8: u32 = 0x8CAD;
const FLOAT_32_UNSIGNED_INT_24_8_REV: u32 = 0x8DAD;
const LESS: u32 = 0x0201;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2D s; uniform vec2 uv;
    out vec4 o;
    void main() { float d = texture(s, uv).r; o = vec4(d, fract(d * 16.0), 0.0, 1.0); }";

/// A new 2D texture bound on unit 0, filtered nearest.
fn new_texture(gl: Gl<'_>, n: &mut Names) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// The float depth program.
pub fn depth_textures(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let uv = gl.glGetUniformLocation(p, Text::borrowed("uv"))?;
    let cell = |gl: Gl<'_>, n: &mut Names, k: usize, u: [f32; 2]| -> R {
        gl.glUniform2f(uv, u[0], u[1])?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    };
    gl.glActiveTexture(TEXTURE0)?;
    let mut marks = Vec::new();
    let corners = [[0.25, 0.25], [0.75, 0.25], [0.25, 0.75], [0.75, 0.75]];

    // Float depths, one beyond 1 and one below 0, then a texel replaced.
    new_texture(gl, n)?;
    let depths = f32s(&[0.1, 0.3337, 1.03, -0.02]);
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        DEPTH_COMPONENT32F as i32,
        2,
        2,
        0,
        DEPTH_COMPONENT,
        FLOAT,
        Some(Blob::borrowed(&depths)),
    )?;
    marks.push(gl.glGetError()?);
    for (k, c) in corners.iter().enumerate() {
        cell(gl, n, k, *c)?;
    }
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 1, 1, 1, DEPTH_COMPONENT, FLOAT, Blob::borrowed(&f32s(&[0.6875])))?;
    marks.push(gl.glGetError()?);
    cell(gl, n, 4, corners[3])?;

    // Float depth with stencil: each texel a float and a word holding the stencil.
    new_texture(gl, n)?;
    let packed: Vec<u8> = [(0.2f32, 7u32), (0.45, 200), (0.8, 1), (0.999, 255)]
        .iter()
        .flat_map(|(d, s)| d.to_ne_bytes().into_iter().chain(s.to_ne_bytes()))
        .collect();
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        DEPTH32F_STENCIL8 as i32,
        2,
        2,
        0,
        DEPTH_STENCIL,
        FLOAT_32_UNSIGNED_INT_24_8_REV,
        Some(Blob::borrowed(&packed)),
    )?;
    marks.push(gl.glGetError()?);
    for (k, c) in corners.iter().enumerate() {
        cell(gl, n, 8 + k, *c)?;
    }

    // A float depth texture as a framebuffer's depth: the nearer of two quads wins, and its
    // depth is sampled afterwards.
    let target = new_texture(gl, n)?;
    gl.glTexImage2D(TEXTURE_2D, 0, DEPTH_COMPONENT32F as i32, 8, 8, 0, DEPTH_COMPONENT, FLOAT, None)?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, target, 0)?;
    gl.glDrawBuffersEXT(Slice::new(&[0]))?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 8, 8)?;
    gl.glClearDepthf(1.0)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(LESS)?;
    let solid = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, solid, [1.0, 1.0, 1.0, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.5), TRIANGLES)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 0.0, -0.25), TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glUseProgram(p)?;
    gl.glBindTexture(TEXTURE_2D, target)?;
    cell(gl, n, 16, [0.25, 0.25])?;
    cell(gl, n, 17, [0.75, 0.75])?;

    // The pairings the table refuses.
    new_texture(gl, n)?;
    let refused: [(u32, u32, u32); 3] = [
        (DEPTH_COMPONENT32F, DEPTH_COMPONENT, UNSIGNED_INT),
        (DEPTH32F_STENCIL8, DEPTH_STENCIL, FLOAT),
        (DEPTH_COMPONENT, DEPTH_COMPONENT, FLOAT),
    ];
    for (internal, format, ty) in refused {
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 1, 1, 0, format, ty, None)?;
        marks.push(gl.glGetError()?);
    }
    mark_all(gl, &marks)
}

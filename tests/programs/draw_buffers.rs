//! `GL_EXT_draw_buffers`, `GL_NV_draw_buffers` and `GL_NV_fbo_color_attachments`: four colour
//! attachments (one of them RGB) written by one draw through `gl_FragData`, by
//! `gl_FragColor` (every selected buffer), by a loop's dynamic index, cleared whole and
//! scissored with a buffer left out, read and copied through `glReadBufferNV`; the default
//! framebuffer's one buffer; the limits, the selections and the errors, all as colours.

use super::multi_draw::mark_all;
use super::*;

const MAX_DRAW_BUFFERS: u32 = 0x8824;
const MAX_COLOR_ATTACHMENTS: u32 = 0x8CDF;
const DRAW_BUFFER0: u32 = 0x8825;
const BACK: u32 = 0x0405;
const FRONT: u32 = 0x0404;
const NONE: u32 = 0;
const CA: [u32; 4] = [COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1, COLOR_ATTACHMENT0 + 2, COLOR_ATTACHMENT0 + 3];
const FRAGMENT_SHADER: u32 = 0x8B30;
const COMPILE_STATUS: u32 = 0x8B81;
const FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE: u32 = 0x8CD0;

/// Each output its own colour, from the varying colour.
const FS_MRT: &str = "#extension GL_EXT_draw_buffers : require
    precision mediump float; varying vec4 v;
    void main() {
        gl_FragData[0] = v;
        gl_FragData[1] = vec4(1.0) - v;
        gl_FragData[2] = vec4(1.0, 0.0, 1.0, 0.5);
        gl_FragData[3] = v.bgra;
    }";

/// Output `i` yellow, the others blue, through a loop's index.
const FS_LOOP: &str = "#extension GL_EXT_draw_buffers : enable
    precision mediump float; uniform int i;
    void main() {
        for (int k = 0; k < gl_MaxDrawBuffers; k++) {
            gl_FragData[k] = k == i ? vec4(1.0, 1.0, 0.0, 1.0) : vec4(0.0, 0.0, 1.0, 1.0);
        }
    }";

/// The compile status of a shader of type `ty`.
pub(super) fn compiles(gl: Gl<'_>, n: &mut Names, ty: u32, source: &str) -> Result<u32, ClientError> {
    let s = n.next();
    gl.glCreateShader(ty, s)?;
    gl.glShaderSource(s, Text::borrowed(source))?;
    gl.glCompileShader(s)?;
    Ok(gl.glGetShaderiv(s, COMPILE_STATUS)? as u32)
}

/// An integer state value.
fn get(gl: Gl<'_>, pname: u32) -> Result<u32, ClientError> {
    Ok(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-1) as u32)
}

/// Selects `list`, marking the error.
fn select(gl: Gl<'_>, marks: &mut Vec<u32>, list: &[u32]) -> R {
    gl.glDrawBuffersEXT(Slice::new(list))?;
    marks.push(gl.glGetError()?);
    Ok(())
}

/// A `size`×`size` texture of `format` with nearest filters, no data.
fn color_texture(gl: Gl<'_>, n: &mut Names, format: u32, size: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(TEXTURE_2D, 0, format as i32, size, size, 0, format, UNSIGNED_BYTE, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// The default framebuffer's one draw buffer: the errors, and drawing with `GL_NONE`.
fn default_framebuffer(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    for pname in [MAX_DRAW_BUFFERS, MAX_COLOR_ATTACHMENTS, DRAW_BUFFER0, DRAW_BUFFER0 + 1] {
        marks.push(get(gl, pname)?);
    }
    for list in [&[BACK, NONE][..], &[CA[0]], &[FRONT], &[], &[0x1234], &[NONE]] {
        select(gl, marks, list)?;
    }
    marks.push(get(gl, DRAW_BUFFER0)?);
    // Nothing reaches the window while its buffer is GL_NONE.
    gl.glClearColor(1.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    select(gl, marks, &[BACK])?;
    marks.push(get(gl, DRAW_BUFFER0)?);
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)
}

/// A framebuffer object's draw buffers: errors, attachments past the last, completeness.
fn object_errors(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    for list in [
        &[CA[1]][..],
        &[CA[0], CA[0]],
        &[BACK],
        &[CA[1], 0x1234],
        &[COLOR_ATTACHMENT0 + 8],
        &[COLOR_ATTACHMENT0 + 16],
        &[0x1234],
        &[FRONT],
        &[NONE; 9],
    ] {
        select(gl, marks, list)?;
    }
    let t = color_texture(gl, n, RGBA, 32)?;
    for a in [COLOR_ATTACHMENT0 + 8, COLOR_ATTACHMENT0 + 15, COLOR_ATTACHMENT0 + 16] {
        gl.glFramebufferTexture2D(FRAMEBUFFER, a, TEXTURE_2D, t, 0)?;
        marks.push(gl.glGetError()?);
        gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, a, FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE)?;
        marks.push(gl.glGetError()?);
    }
    for mode in [COLOR_ATTACHMENT0 + 8, COLOR_ATTACHMENT0 + 16] {
        gl.glReadBufferNV(mode)?;
        marks.push(gl.glGetError()?);
    }
    // A smaller image at attachment 5 makes the framebuffer incomplete.
    let small = color_texture(gl, n, RGBA, 16)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + 5, TEXTURE_2D, small, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(
        FRAMEBUFFER,
        COLOR_ATTACHMENT0 + 5,
        FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
    )? as u32);
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + 5, TEXTURE_2D, 0, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    // Shaders: an index past the last output, and both outputs, fail; `gl_FragData[1]`
    // needs no directive.
    for fs in [
        "void main() { gl_FragData[8] = vec4(1.0); }",
        "void main() { gl_FragData[1] = vec4(1.0); gl_FragColor = vec4(0.0); }",
        "void main() { gl_FragData[1] = vec4(1.0); }",
        "#ifndef GL_EXT_draw_buffers\n#error missing\n#endif\nvoid main() { gl_FragColor = vec4(1.0); }",
        "uniform mediump float a[gl_MaxDrawBuffers == 8 ? 1 : -1];\nvoid main() { gl_FragData[0] = vec4(a[0]); }",
    ] {
        marks.push(compiles(gl, n, FRAGMENT_SHADER, fs)?);
    }
    Ok(())
}

fn draw_buffers(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    default_framebuffer(gl, n, &mut marks)?;
    let fb = n.next();
    let tex = [
        color_texture(gl, n, RGBA, 32)?,
        color_texture(gl, n, RGBA, 32)?,
        color_texture(gl, n, RGB, 32)?,
        color_texture(gl, n, RGBA, 32)?,
    ];
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    for (a, t) in CA.iter().zip(tex) {
        gl.glFramebufferTexture2D(FRAMEBUFFER, *a, TEXTURE_2D, t, 0)?;
    }
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    for i in 0..4 {
        marks.push(get(gl, DRAW_BUFFER0 + i)?);
    }
    gl.glViewport(0, 0, 32, 32)?;
    // A whole clear of all four, then a scissored one leaving attachment 2 out.
    select(gl, &mut marks, &CA)?;
    gl.glClearColor(0.1, 0.2, 0.3, 0.4)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    select(gl, &mut marks, &[CA[0], CA[1], NONE, CA[3]])?;
    for i in 0..5 {
        marks.push(get(gl, DRAW_BUFFER0 + i)?);
    }
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(0, 0, 12, 32)?;
    gl.glClearColor(0.9, 0.8, 0.7, 0.6)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glDisable(SCISSOR_TEST)?;
    // One draw, four colours.
    select(gl, &mut marks, &CA)?;
    program(gl, n, VS_COLOR, FS_MRT, &["pos", "col"])?;
    vertex_quad(gl, n, [-0.5, -0.5, 1.0, 1.0], |x, y| [x, y, 0.0, (x + 1.0) / 2.0, (y + 1.0) / 2.0, 0.5, 1.0])?;
    // gl_FragColor, blended, into attachments 1 and 3 only.
    select(gl, &mut marks, &[NONE, CA[1], NONE, CA[3]])?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.0, 0.5, 0.0, 0.5])?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(0x0302, 0x0303)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.25, 0.0, 0.0), TRIANGLES)?;
    gl.glDisable(BLEND)?;
    // A loop's index picks attachment 2.
    select(gl, &mut marks, &CA)?;
    let p = program(gl, n, VS_POS, FS_LOOP, &["pos"])?;
    let loc = gl.glGetUniformLocation(p, Text::borrowed("i"))?;
    gl.glUniform1i(loc, 2)?;
    draw_positions(gl, n, &quad(0.5, -1.0, 1.0, -0.5, 0.0), TRIANGLES)?;
    // Reads and a copy from the other attachments.
    for (a, x) in [(CA[1], 20), (CA[3], 4), (CA[2], 28)] {
        gl.glReadBufferNV(a)?;
        let px = gl.glReadPixels(x, 20, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
        let c = |i: usize| u32::from(px.get(i).copied().unwrap_or(0));
        marks.push(c(0) | c(1) << 8);
        marks.push(c(2) | c(3) << 8);
    }
    let copy = color_texture(gl, n, RGB, 32)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGB, 0, 0, 32, 32, 0)?;
    marks.push(gl.glGetError()?);
    // An attachment with no image cannot be read.
    gl.glReadBufferNV(COLOR_ATTACHMENT0 + 7)?;
    marks.push(gl.glGetError()?);
    gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?;
    marks.push(gl.glGetError()?);
    gl.glReadBufferNV(CA[0])?;
    object_errors(gl, n, &mut marks)?;
    // Everything shown.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    for (t, [x, y, s]) in
        tex.iter().chain([&copy]).zip([[0, 0, 24], [24, 0, 24], [0, 24, 24], [24, 24, 24], [48, 0, 16]])
    {
        gl.glBindTexture(TEXTURE_2D, *t)?;
        gl.glViewport(x, y, s, s)?;
        textured_quad(gl, n, 0.0, 1.0)?;
    }
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

/// Mesa's ES 2.0 binds the draw and the read framebuffer apart when `glBindFramebuffer` is
/// given `GL_DRAW_FRAMEBUFFER` or `GL_READ_FRAMEBUFFER`: draws go to one, reads and copies come
/// from the other, and `glReadBufferNV` applies to the read one.
fn split_bindings(gl: Gl<'_>, n: &mut Names) -> R {
    const READ_FRAMEBUFFER: u32 = 0x8CA8;
    const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
    const FRAMEBUFFER_BINDING: u32 = 0x8CA6;
    let mut marks = Vec::new();
    let fb = n.next();
    let tex = [color_texture(gl, n, RGBA, 16)?, color_texture(gl, n, RGBA, 16)?];
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    for (a, t) in CA.iter().zip(tex) {
        gl.glFramebufferTexture2D(FRAMEBUFFER, *a, TEXTURE_2D, t, 0)?;
    }
    select(gl, &mut marks, &[CA[0], CA[1]])?;
    gl.glViewport(0, 0, 16, 16)?;
    program(gl, n, VS_COLOR, FS_MRT, &["pos", "col"])?;
    vertex_quad(gl, n, [-1.0, -1.0, 1.0, 1.0], |x, y| [x, y, 0.0, 0.8, 0.4, (x + 1.0) / 2.0, 1.0])?;
    // Draws to the window, reads from the object.
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    marks.push(gl.glGetError()?);
    marks.push(get(gl, FRAMEBUFFER_BINDING)?);
    marks.push(get(gl, DRAW_BUFFER0)?);
    gl.glViewport(0, 0, W, H)?;
    gl.glClearColor(0.0, 0.0, 0.5, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glReadBufferNV(CA[1])?;
    marks.push(gl.glGetError()?);
    marks.push(get(gl, 0x0C02)?);
    let px = gl.glReadPixels(4, 4, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
    let c = |i: usize| u32::from(px.get(i).copied().unwrap_or(0));
    marks.extend([c(0) | c(1) << 8, c(2) | c(3) << 8]);
    let copy = color_texture(gl, n, RGBA, 16)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, 16, 16, 0)?;
    marks.push(gl.glGetError()?);
    // Only glBindFramebuffer takes the two targets.
    marks.push(gl.glCheckFramebufferStatus(DRAW_FRAMEBUFFER)?);
    marks.push(gl.glGetError()?);
    gl.glFramebufferTexture2D(READ_FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, 0, 0)?;
    marks.push(gl.glGetError()?);
    // Reads from the window again, the object drawn to.
    gl.glBindFramebuffer(READ_FRAMEBUFFER, 0)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, fb)?;
    marks.push(get(gl, FRAMEBUFFER_BINDING)?);
    marks.push(get(gl, 0x0C02)?);
    let px = gl.glReadPixels(4, 4, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
    let c = |i: usize| u32::from(px.get(i).copied().unwrap_or(0));
    marks.extend([c(0) | c(1) << 8, c(2) | c(3) << 8]);
    // Deleting the object unbinds it from both.
    gl.glBindFramebuffer(READ_FRAMEBUFFER, fb)?;
    gl.glDeleteFramebuffers(Slice::new(&[fb]))?;
    marks.push(get(gl, FRAMEBUFFER_BINDING)?);
    marks.push(get(gl, 0x0C02)?);
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, copy)?;
    gl.glViewport(8, 8, 32, 32)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "draw_buffers", run: draw_buffers, tol: DEFAULT, expects_error: false },
        Case { name: "draw_buffers_split_bindings", run: split_bindings, tol: DEFAULT, expects_error: false },
    ]
}

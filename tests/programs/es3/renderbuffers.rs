//! ES 3.0's renderbuffer formats beyond ES 2.0's extensions: an `SRGB8_ALPHA8` colour buffer
//! (cleared and drawn in linear and encoded, read back encoded, blitted to the window decoded),
//! and `DEPTH_COMPONENT32F` and `DEPTH32F_STENCIL8` depth buffers (a depth test between two
//! quads, a stencil test, float depth read back as floats) and 24-bit depth read back as
//! `GL_UNSIGNED_INT_24_8`; their sizes and the reads refused, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const READ_FRAMEBUFFER: u32 = 0x8CA8;
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const SRGB8_ALPHA8: u32 = 0x8C43;
const RGBA8: u32 = 0x8058;
const RG16F: u32 = 0x822F;
const DEPTH_COMPONENT32F: u32 = 0x8CAC;
const DEPTH32F_STENCIL8: u32 = 0x8CAD;
const DEPTH_COMPONENT24: u32 = 0x81A6;
const DEPTH_COMPONENT: u32 = 0x1902;
const UNSIGNED_INT_24_8: u32 = 0x84FA;
const DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const RENDERBUFFER_RED_SIZE: u32 = 0x8D50;
const RENDERBUFFER_DEPTH_SIZE: u32 = 0x8D54;
const RENDERBUFFER_STENCIL_SIZE: u32 = 0x8D55;
const LESS: u32 = 0x0201;
const EQUAL: u32 = 0x0202;
const ALWAYS: u32 = 0x0207;
const KEEP: u32 = 0x1E00;
const REPLACE: u32 = 0x1E01;

/// A new renderbuffer of `format`, 8×8, left bound; its name.
fn renderbuffer(gl: Gl<'_>, n: &mut Names, format: u32) -> Result<u32, ClientError> {
    let rb = n.next();
    gl.glGenRenderbuffers(Slice::new(&[rb]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, format, 8, 8)?;
    Ok(rb)
}

/// The renderbuffer program.
pub fn renderbuffers(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    let mut marks = Vec::new();

    // An sRGB colour buffer: cleared, half drawn, read back encoded, blitted to the window.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    let srgb = renderbuffer(gl, n, SRGB8_ALPHA8)?;
    marks.push(gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_RED_SIZE)? as u32);
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, srgb)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 8, 8)?;
    gl.glClearColor(0.5, 0.2, 0.05, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    color(gl, p, [0.25, 0.75, 0.125, 1.0])?;
    draw_positions(gl, n, &quad(0.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    let px = gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
    marks.extend(px.iter().map(|b| u32::from(*b)));
    let px = gl.glReadPixels(7, 0, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
    marks.extend(px.iter().map(|b| u32::from(*b)));
    gl.glBindFramebuffer(READ_FRAMEBUFFER, fb)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 0, 0, 16, 16, COLOR_BUFFER_BIT, NEAREST as u32)?;

    // 32-bit float depth: the nearer of two quads drawn in either order wins.
    for (k, (format, attachment)) in
        [(DEPTH_COMPONENT32F, DEPTH_ATTACHMENT), (DEPTH32F_STENCIL8, DEPTH_STENCIL_ATTACHMENT)].iter().enumerate()
    {
        let fb = n.next();
        gl.glGenFramebuffers(Slice::new(&[fb]))?;
        gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
        let c = renderbuffer(gl, n, RGBA8)?;
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, c)?;
        let d = renderbuffer(gl, n, *format)?;
        marks.push(gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_DEPTH_SIZE)? as u32);
        marks.push(gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_STENCIL_SIZE)? as u32);
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, *attachment, RENDERBUFFER, d)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        gl.glViewport(0, 0, 8, 8)?;
        gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
        gl.glClearDepthf(1.0)?;
        gl.glClearStencil(0)?;
        gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
        gl.glEnable(DEPTH_TEST)?;
        gl.glDepthFunc(LESS)?;
        // Near first on the left half, far first on the right; the near one is red.
        color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 1.0, -0.5), TRIANGLES)?;
        color(gl, p, [0.0, 1.0, 0.0, 1.0])?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.25), TRIANGLES)?;
        color(gl, p, [1.0, 0.0, 0.0, 1.0])?;
        draw_positions(gl, n, &quad(0.0, -1.0, 1.0, 1.0, -0.5), TRIANGLES)?;
        gl.glDisable(DEPTH_TEST)?;
        if *format == DEPTH32F_STENCIL8 {
            // The stencil marks the bottom half, and a blue quad lands only there.
            gl.glEnable(STENCIL_TEST)?;
            gl.glStencilFunc(ALWAYS, 1, 0xFF)?;
            gl.glStencilOp(KEEP, KEEP, REPLACE)?;
            gl.glColorMask(false, false, false, false)?;
            draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 0.0, 0.0), TRIANGLES)?;
            gl.glColorMask(true, true, true, true)?;
            gl.glStencilFunc(EQUAL, 1, 0xFF)?;
            gl.glStencilOp(KEEP, KEEP, KEEP)?;
            color(gl, p, [0.0, 0.0, 1.0, 1.0])?;
            draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
            gl.glDisable(STENCIL_TEST)?;
        }
        // NV_read_depth in ES 3.0: float depth read as floats (the near quad's 0.25 at the
        // left, the far one's 0.625 at the right), and as nothing else.
        for x in [0, 7] {
            let px = gl.glReadPixels(x, 7, 1, 1, DEPTH_COMPONENT, FLOAT)?.0;
            let depth = px.get(..4).map_or(-1.0, |b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]));
            marks.push((depth * 1000.0).round() as u32);
        }
        gl.glReadPixels(0, 0, 1, 1, DEPTH_COMPONENT, UNSIGNED_INT)?;
        marks.push(gl.glGetError()?);
        gl.glBindFramebuffer(READ_FRAMEBUFFER, fb)?;
        gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
        let x = 16 + 16 * k as i32;
        gl.glBlitFramebuffer(0, 0, 8, 8, x, 0, x + 16, 16, COLOR_BUFFER_BIT, NEAREST as u32)?;
    }
    // 24-bit depth read as GL_UNSIGNED_INT_24_8 (depth in the top 24 bits), not as floats.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    let d = renderbuffer(gl, n, DEPTH_COMPONENT24)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, d)?;
    gl.glClearDepthf(0.3)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    let px = gl.glReadPixels(2, 2, 1, 1, DEPTH_COMPONENT, UNSIGNED_INT_24_8)?.0;
    let v = px.get(..4).map_or(0, |b| u32::from_ne_bytes([b[0], b[1], b[2], b[3]]));
    marks.extend([v >> 16, v & 0xFFFF]);
    gl.glReadPixels(2, 2, 1, 1, DEPTH_COMPONENT, FLOAT)?;
    marks.push(gl.glGetError()?);
    gl.glClearDepthf(1.0)?;
    // A half-float buffer read as RGBA floats (ES 3.0's read format for float buffers), which
    // an 8-bit buffer refuses.
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    let rg = renderbuffer(gl, n, RG16F)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rg)?;
    gl.glClearColor(0.25, 0.625, 0.5, 0.75)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    let px = gl.glReadPixels(1, 1, 1, 1, RGBA, FLOAT)?.0;
    marks.extend(px.chunks_exact(4).map(|b| (f32::from_ne_bytes([b[0], b[1], b[2], b[3]]) * 1000.0) as u32));
    // glClearBufferfv keeps values outside [0, 1] in a float buffer.
    gl.glClearBufferfv(0x1800, 0, Slice::new(&[-2.5, 3.25, 0.5, 1.0]))?;
    let px = gl.glReadPixels(1, 1, 1, 1, RGBA, FLOAT)?.0;
    marks.extend(px.chunks_exact(4).map(|b| (f32::from_ne_bytes([b[0], b[1], b[2], b[3]]) * 1000.0) as i32 as u32));
    let c = renderbuffer(gl, n, RGBA8)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, c)?;
    gl.glReadPixels(0, 0, 1, 1, RGBA, FLOAT)?;
    marks.push(gl.glGetError()?);
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

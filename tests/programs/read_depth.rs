//! `GL_NV_read_depth` and `GL_NV_read_depth_stencil`: `glReadPixels` of depth as 16 and 32
//! bits and of depth with stencil, from the window (cleared, then drawn at a constant depth
//! with a stencil reference), from 16-bit and 24-bit depth renderbuffers, a packed
//! depth-stencil one and a depth texture; the pairs refused and reads of buffers that are not
//! there. Every value is marked as colours, 16 bits a mark.

use super::multi_draw::mark_all;
use super::*;

const DEPTH_COMPONENT: u32 = 0x1902;
const DEPTH_STENCIL: u32 = 0x84F9;
const UNSIGNED_INT_24_8: u32 = 0x84FA;
const DEPTH_COMPONENT24: u32 = 0x81A6;
const DEPTH24_STENCIL8: u32 = 0x88F0;
const STENCIL_ATTACHMENT: u32 = 0x8D20;
const ALWAYS: u32 = 0x0207;
const REPLACE: u32 = 0x1E01;
const KEEP: u32 = 0x1E00;

/// Reads one pixel at (`x`, `y`) as `format` and `ty`, marking the error and the value (as
/// its high and low 16 bits where it has 32).
fn read(gl: Gl<'_>, marks: &mut Vec<u32>, x: i32, y: i32, format: u32, ty: u32) -> R {
    let px = gl.glReadPixels(x, y, 1, 1, format, ty)?;
    let e = gl.glGetError()?;
    marks.push(e);
    if e != 0 {
        return Ok(());
    }
    match px.0.len() {
        2 => marks.push(u32::from(u16::from_ne_bytes([px.0[0], px.0[1]]))),
        4 => {
            let v = u32::from_ne_bytes([px.0[0], px.0[1], px.0[2], px.0[3]]);
            marks.extend([v >> 16, v & 0xFFFF]);
        }
        n => marks.push(0xF000 + n as u32),
    }
    Ok(())
}

/// Every pair read at (`x`, `y`).
fn read_all(gl: Gl<'_>, marks: &mut Vec<u32>, x: i32, y: i32, stencil: bool) -> R {
    read(gl, marks, x, y, DEPTH_COMPONENT, UNSIGNED_SHORT)?;
    read(gl, marks, x, y, DEPTH_COMPONENT, UNSIGNED_INT)?;
    if stencil {
        read(gl, marks, x, y, DEPTH_STENCIL, UNSIGNED_INT_24_8)?;
    }
    Ok(())
}

/// A new framebuffer object with an RGBA8 colour renderbuffer and a depth renderbuffer of
/// `format` (also the stencil attachment with `stencil`), 8×8, bound.
fn fbo(gl: Gl<'_>, n: &mut Names, format: u32, stencil: bool) -> R {
    let (fb, color, depth) = (n.next(), n.next(), n.next());
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    for (rb, f, at) in [(color, 0x8058, COLOR_ATTACHMENT0), (depth, format, DEPTH_ATTACHMENT)] {
        gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
        gl.glRenderbufferStorage(RENDERBUFFER, f, 8, 8)?;
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, at, RENDERBUFFER, rb)?;
    }
    if stencil {
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, STENCIL_ATTACHMENT, RENDERBUFFER, depth)?;
    }
    gl.glViewport(0, 0, 8, 8)
}

fn read_depth(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    // The window: cleared, then its left half drawn at depth 0.75 with stencil 0x33.
    gl.glClearDepthf(0.25)?;
    gl.glClearStencil(0x5a)?;
    gl.glClear(DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    read_all(gl, &mut marks, 3, 3, true)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(ALWAYS)?;
    gl.glEnable(STENCIL_TEST)?;
    gl.glStencilFunc(ALWAYS, 0x33, 0xFF)?;
    gl.glStencilOp(KEEP, KEEP, REPLACE)?;
    vertex_quad(gl, n, [-1.0, -1.0, 0.0, 1.0], |x, y| [x, y, 0.5, 0.5, 0.5, 0.5, 1.0])?;
    gl.glDisable(STENCIL_TEST)?;
    read_all(gl, &mut marks, 3, 40, true)?;
    read_all(gl, &mut marks, 60, 40, true)?;
    // The pairs refused: other types, and types of the other format.
    for (f, t) in [
        (DEPTH_COMPONENT, UNSIGNED_BYTE),
        (DEPTH_COMPONENT, FLOAT),
        (DEPTH_COMPONENT, UNSIGNED_INT_24_8),
        (DEPTH_STENCIL, UNSIGNED_INT),
        (DEPTH_STENCIL, FLOAT),
    ] {
        read(gl, &mut marks, 3, 3, f, t)?;
    }
    // Renderbuffers: 16-bit and 24-bit depth, and packed depth-stencil.
    gl.glDepthFunc(0x0201)?;
    for (format, stencil, clear) in
        [(DEPTH_COMPONENT16, false, 0.5), (DEPTH_COMPONENT24, false, 0.3), (DEPTH24_STENCIL8, true, 0.7)]
    {
        fbo(gl, n, format, stencil)?;
        gl.glClearDepthf(clear)?;
        gl.glClearStencil(0x81)?;
        gl.glClear(DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
        read_all(gl, &mut marks, 2, 2, true)?;
    }
    // A framebuffer with no depth buffer.
    let (fb, color) = (n.next(), n.next());
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glBindRenderbuffer(RENDERBUFFER, color)?;
    gl.glRenderbufferStorage(RENDERBUFFER, 0x8058, 8, 8)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, color)?;
    read_all(gl, &mut marks, 2, 2, true)?;
    // A depth texture.
    depth_texture_target(gl, n, 8)?;
    gl.glClearDepthf(0.5)?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    read(gl, &mut marks, 2, 2, DEPTH_COMPONENT, UNSIGNED_SHORT)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "read_depth", run: read_depth, tol: DEFAULT, expects_error: false }]
}

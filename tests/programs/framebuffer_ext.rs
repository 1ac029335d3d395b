//! Extensions of the fixed-function framebuffer stages: `EXT_blend_minmax` (the `MIN` and `MAX`
//! blend equations) and `EXT_discard_framebuffer` (discards of attachments whose contents are
//! then specified again before they are read), and `OES_stencil8` (a stencil-only renderbuffer).

use super::*;

/// GL_MIN_EXT and GL_MAX_EXT.
const MIN_EXT: u32 = 0x8007;
const MAX_EXT: u32 = 0x8008;
/// The default framebuffer's buffers, as `EXT_discard_framebuffer` names them.
const COLOR_EXT: u32 = 0x1800;
const DEPTH_EXT: u32 = 0x1801;
const STENCIL_EXT: u32 = 0x1802;

/// `EXT_blend_minmax`: MIN and MAX equations, separately for RGB and alpha; the blend factors
/// are ignored by both.
fn blend_minmax(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.5, 0.25, 0.75, 0.5)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(0x0302, 0)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glBlendEquation(MIN_EXT)?;
    color(gl, p, [0.2, 0.9, 0.5, 0.9])?;
    draw_positions(gl, n, &quad(-0.9, -0.9, 0.1, 0.9, 0.0), TRIANGLES)?;
    gl.glBlendEquation(MAX_EXT)?;
    color(gl, p, [0.7, 0.1, 0.6, 0.2])?;
    draw_positions(gl, n, &quad(-0.1, -0.9, 0.9, 0.9, 0.0), TRIANGLES)?;
    gl.glBlendEquationSeparate(MIN_EXT, MAX_EXT)?;
    color(gl, p, [0.3, 0.3, 0.3, 0.8])?;
    draw_positions(gl, n, &quad(-0.5, -0.3, 0.5, 0.3, 0.0), TRIANGLES)
}

/// `EXT_discard_framebuffer` on a framebuffer object and on the default framebuffer: each
/// discarded buffer is cleared again before it is used, so the image is defined; the discards
/// must neither fail nor disturb the attachments they do not name.
fn discard_framebuffer(gl: Gl<'_>, n: &mut Names) -> R {
    let (fb, tex, rb) = (n.next(), n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, DEPTH_COMPONENT16, 32, 32)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, rb)?;
    gl.glViewport(0, 0, 32, 32)?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glClearColor(0.1, 0.3, 0.5, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.9, 0.2, 0.1, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.4, 0.4, -0.5), TRIANGLES)?;
    // Depth only: the colour drawn so far stays; depth is cleared again before the next draw,
    // which then passes the depth test everywhere.
    gl.glDiscardFramebufferEXT(FRAMEBUFFER, Slice::new(&[DEPTH_ATTACHMENT]))?;
    gl.glClear(DEPTH_BUFFER_BIT)?;
    color(gl, p, [0.2, 0.8, 0.3, 1.0])?;
    draw_positions(gl, n, &quad(-0.2, -0.2, 0.8, 0.8, 0.5), TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)?;
    // Show the texture on the default framebuffer, after discarding and clearing it.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glDiscardFramebufferEXT(FRAMEBUFFER, Slice::new(&[COLOR_EXT, DEPTH_EXT, STENCIL_EXT]))?;
    gl.glClearColor(0.3, 0.3, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    // An empty list discards nothing.
    gl.glDiscardFramebufferEXT(FRAMEBUFFER, Slice::new(&[]))
}

/// `OES_stencil8`: a framebuffer object whose stencil is a `STENCIL_INDEX8` renderbuffer; a
/// quad writes 1 into it, and a second quad is drawn only where stencil is 1, then only where
/// it is not; the colour texture is then shown. Its stencil size is queried and shown too.
fn stencil8_renderbuffer(gl: Gl<'_>, n: &mut Names) -> R {
    const STENCIL_INDEX8: u32 = 0x8D48;
    const STENCIL_ATTACHMENT: u32 = 0x8D20;
    const RENDERBUFFER_STENCIL_SIZE: u32 = 0x8D55;
    let (fb, tex, rb) = (n.next(), n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, STENCIL_INDEX8, 32, 32)?;
    let bits = gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_STENCIL_SIZE)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, STENCIL_ATTACHMENT, RENDERBUFFER, rb)?;
    gl.glViewport(0, 0, 32, 32)?;
    gl.glClearColor(0.1, 0.2, 0.3, 1.0)?;
    gl.glClearStencil(0)?;
    gl.glClear(COLOR_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    gl.glEnable(STENCIL_TEST)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glStencilFunc(0x0207, 1, 0xFF)?; // ALWAYS
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E01)?; // KEEP, KEEP, REPLACE
    color(gl, p, [0.9, 0.6, 0.1, 1.0])?;
    draw_positions(gl, n, &quad(-0.7, -0.7, 0.3, 0.3, 0.0), TRIANGLES)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E00)?;
    gl.glStencilFunc(0x0202, 1, 0xFF)?; // EQUAL
    color(gl, p, [0.1, 0.9, 0.4, 1.0])?;
    draw_positions(gl, n, &quad(-0.3, -0.3, 0.8, 0.8, 0.0), TRIANGLES)?;
    gl.glStencilFunc(0x0205, 1, 0xFF)?; // NOTEQUAL
    color(gl, p, [0.5, 0.1, 0.8, 1.0])?;
    draw_positions(gl, n, &quad(0.4, 0.4, 0.95, 0.95, 0.0), TRIANGLES)?;
    gl.glDisable(STENCIL_TEST)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(0, 0, 8, 8)?;
    gl.glClearColor(bits as f32 / 16.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glDisable(SCISSOR_TEST)
}

/// The programs of this module.
pub fn all() -> Vec<Case> {
    let c = |name, run| Case { name, run, tol: DEFAULT, expects_error: false };
    vec![
        c("blend_minmax", blend_minmax),
        c("discard_framebuffer", discard_framebuffer),
        c("stencil8_renderbuffer", stencil8_renderbuffer),
    ]
}

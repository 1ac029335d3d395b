//! `GL_NV_read_buffer`: `glReadBufferNV` on the default framebuffer and on a framebuffer
//! object, each keeping its own selection; reads and copies with no buffer selected; the
//! errors; `GL_READ_BUFFER_NV`; all drawn as colours.

use super::multi_draw::mark_all;
use super::*;

const READ_BUFFER_NV: u32 = 0x0C02;
const BACK: u32 = 0x0405;

/// Reads a pixel and, with `copy`, copies into a texture, marking each one's error.
fn reads(gl: Gl<'_>, marks: &mut Vec<u32>, copy: bool) -> R {
    gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?;
    marks.push(gl.glGetError()?);
    if copy {
        gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, 4, 4, 0)?;
        marks.push(gl.glGetError()?);
    }
    Ok(())
}

fn read_buffer(gl: Gl<'_>, n: &mut Names) -> R {
    let (fb, tex, copy) = (n.next(), n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glBindTexture(TEXTURE_2D, copy)?;
    let mut marks = Vec::new();
    let set = |gl: Gl<'_>, marks: &mut Vec<u32>, mode: u32| -> R {
        gl.glReadBufferNV(mode)?;
        marks.push(gl.glGetError()?);
        marks.push(gl.glGetIntegerv(READ_BUFFER_NV)?.first().copied().unwrap_or(-1) as u32);
        Ok(())
    };
    marks.push(gl.glGetIntegerv(READ_BUFFER_NV)?.first().copied().unwrap_or(-1) as u32);
    // Mesa (swrast) crashes in glReadPixels on a pbuffer whose read buffer is GL_NONE, and in
    // glCopyTexImage2D from any framebuffer whose read buffer is: neither is compared.
    for mode in [BACK, COLOR_ATTACHMENT0, 0x1234, 0] {
        set(gl, &mut marks, mode)?;
    }
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    marks.push(gl.glGetIntegerv(READ_BUFFER_NV)?.first().copied().unwrap_or(-1) as u32);
    for mode in [BACK, 0, COLOR_ATTACHMENT0, 0] {
        set(gl, &mut marks, mode)?;
    }
    reads(gl, &mut marks, false)?;
    // Each framebuffer keeps its selection.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    marks.push(gl.glGetIntegerv(READ_BUFFER_NV)?.first().copied().unwrap_or(-1) as u32);
    set(gl, &mut marks, BACK)?;
    reads(gl, &mut marks, true)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    marks.push(gl.glGetIntegerv(READ_BUFFER_NV)?.first().copied().unwrap_or(-1) as u32);
    set(gl, &mut marks, COLOR_ATTACHMENT0)?;
    gl.glClearColor(0.2, 0.7, 0.4, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    reads(gl, &mut marks, true)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    // The copy of the object's colour, shown.
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glViewport(0, 0, 32, 32)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "read_buffer", run: read_buffer, tol: DEFAULT, expects_error: false }]
}

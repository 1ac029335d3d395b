//! `glBlitFramebuffer`'s colour copies between a texture's framebuffer and the window: one to
//! one, magnified nearest and linear, flipped on both axes, minified, partly outside the
//! source, scissored, from the window into a half-float texture (shown by a draw), and within
//! one framebuffer between two images; the errors, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const READ_FRAMEBUFFER: u32 = 0x8CA8;
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const RGBA16F: i32 = 0x881A;
const HALF_FLOAT: u32 = 0x140B;

/// An 8×8 image of distinct texels.
fn source() -> Vec<u8> {
    (0..64).flat_map(|i| [(i % 8 * 32) as u8, (i / 8 * 32) as u8, ((i * 37) % 256) as u8, 255]).collect()
}

/// A framebuffer with a new `w`×`h` texture as its colour (`internal`, from `format`/`ty`
/// data `data`); (framebuffer, texture). Leaves the framebuffer bound.
#[allow(clippy::too_many_arguments)]
fn textured_framebuffer(
    gl: Gl<'_>,
    n: &mut Names,
    (w, h): (i32, i32),
    internal: i32,
    format: u32,
    ty: u32,
    data: Option<&[u8]>,
) -> Result<(u32, u32), ClientError> {
    let (fb, t) = (n.next(), n.next());
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, internal, w, h, 0, format, ty, data.map(Blob::borrowed))?;
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    Ok((fb, t))
}

/// The blit program.
pub fn blit(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    gl.glClearColor(0.1, 0.2, 0.3, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    let data = source();
    let (a, _) = textured_framebuffer(gl, n, (8, 8), RGBA as i32, RGBA, UNSIGNED_BYTE, Some(&data))?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);

    // From the texture into the window.
    gl.glBindFramebuffer(READ_FRAMEBUFFER, a)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    let blits: [([i32; 4], [i32; 4], i32); 6] = [
        ([0, 0, 8, 8], [0, 0, 8, 8], NEAREST),
        ([0, 0, 8, 8], [8, 0, 24, 16], NEAREST),
        ([0, 0, 8, 8], [24, 0, 40, 16], LINEAR),
        ([0, 0, 8, 8], [48, 8, 40, 0], NEAREST),
        ([0, 0, 8, 8], [0, 16, 4, 20], NEAREST),
        ([-4, -4, 4, 4], [8, 16, 16, 24], NEAREST),
    ];
    for ([s0, s1, s2, s3], [d0, d1, d2, d3], filter) in blits {
        gl.glBlitFramebuffer(s0, s1, s2, s3, d0, d1, d2, d3, COLOR_BUFFER_BIT, filter as u32)?;
        marks.push(gl.glGetError()?);
    }
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(20, 20, 6, 5)?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 16, 16, 32, 32, COLOR_BUFFER_BIT, NEAREST as u32)?;
    gl.glDisable(SCISSOR_TEST)?;

    // From the window into a half-float texture, halved, then shown by a draw.
    let (b, bt) = textured_framebuffer(gl, n, (16, 16), RGBA16F, RGBA, HALF_FLOAT, None)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, 0)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, b)?;
    gl.glBlitFramebuffer(0, 0, 32, 32, 0, 0, 16, 16, COLOR_BUFFER_BIT, LINEAR as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, bt)?;
    let v = [
        0.0f32, 0.0, 0.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.5, 0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 0.0,
        0.5, 0.0, 1.0,
    ];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 6)?;

    // Within one framebuffer, from one colour attachment to another (the read buffer and the
    // draw buffer differ), shown by a blit to the window.
    let (c, _) = textured_framebuffer(gl, n, (8, 8), RGBA as i32, RGBA, UNSIGNED_BYTE, Some(&data))?;
    let other = n.next();
    gl.glGenTextures(Slice::new(&[other]))?;
    gl.glBindTexture(TEXTURE_2D, other)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + 1, TEXTURE_2D, other, 0)?;
    gl.glDrawBuffersEXT(Slice::new(&[0, COLOR_ATTACHMENT0 + 1]))?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 8, 8, 0, 0, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glReadBufferNV(COLOR_ATTACHMENT0 + 1)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 56, 0, 64, 8, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);

    // The errors: the read buffer as the draw buffer, an unknown filter, unknown mask bits,
    // depth with a linear filter, an incomplete framebuffer; depth where the read framebuffer
    // has none is left out, and an empty rectangle does nothing.
    gl.glBindFramebuffer(FRAMEBUFFER, a)?;
    let calls: [(u32, u32); 4] = [
        (COLOR_BUFFER_BIT, NEAREST as u32),
        (COLOR_BUFFER_BIT, 0x1234),
        (COLOR_BUFFER_BIT | 0x8, NEAREST as u32),
        (DEPTH_BUFFER_BIT, LINEAR as u32),
    ];
    for (mask, filter) in calls {
        gl.glBlitFramebuffer(0, 0, 4, 4, 4, 4, 8, 8, mask, filter)?;
        marks.push(gl.glGetError()?);
    }
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 60, 60, 64, 64, DEPTH_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBlitFramebuffer(0, 0, 4, 4, 60, 60, 60, 64, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    let empty = n.next();
    gl.glGenFramebuffers(Slice::new(&[empty]))?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, empty)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 0, 0, 4, 4, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    // Attachments and status through the draw and read targets: a texture attached to the
    // draw framebuffer, a renderbuffer to the read framebuffer, each checked by its target.
    let (d, r) = (n.next(), n.next());
    gl.glGenFramebuffers(Slice::new(&[d, r]))?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, d)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, r)?;
    marks.push(gl.glCheckFramebufferStatus(READ_FRAMEBUFFER)?);
    gl.glFramebufferTexture2D(DRAW_FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, bt, 0)?;
    marks.push(gl.glCheckFramebufferStatus(DRAW_FRAMEBUFFER)?);
    let rb = n.next();
    gl.glGenRenderbuffers(Slice::new(&[rb]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, 0x8058, 4, 4)?;
    gl.glFramebufferRenderbuffer(READ_FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb)?;
    marks.push(gl.glCheckFramebufferStatus(READ_FRAMEBUFFER)?);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(READ_FRAMEBUFFER, COLOR_ATTACHMENT0, 0x8CD0)? as u32);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(DRAW_FRAMEBUFFER, COLOR_ATTACHMENT0, 0x8CD0)? as u32);
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    let _ = c;
    mark_all(gl, &marks)
}

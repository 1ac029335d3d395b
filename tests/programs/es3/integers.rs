//! ES 3.0's integer colour formats: textures of eight of them uploaded from integer data and
//! read back through a framebuffer as `GL_RGBA_INTEGER`, drawn into by integer fragment
//! outputs (two buffers of different kinds at once), cleared by `glClearBufferiv`/`uiv` under
//! a scissor, integer renderbuffers, blits, the attachment queries, and the errors of reads,
//! uploads, mipmaps, blits and renderbuffers that mix integers with other data; all as marks.

use super::super::multi_draw::mark_all;
use super::super::*;
use super::language::{screen, VS_SCREEN};

const RED_INTEGER: u32 = 0x8D94;
const RED: u32 = 0x1903;
const RG_INTEGER: u32 = 0x8228;
const RGB_INTEGER: u32 = 0x8D98;
const RGBA_INTEGER: u32 = 0x8D99;
const INT: u32 = 0x1404;
const R8I: u32 = 0x8231;
const R8UI: u32 = 0x8232;
const RG16I: u32 = 0x8239;
const R32I: u32 = 0x8235;
const RG8UI: u32 = 0x8238;
const RGBA16UI: u32 = 0x8D76;
const RGBA32UI: u32 = 0x8D70;
const RGBA32I: u32 = 0x8D82;
const RGB8UI: u32 = 0x8D7D;
const RGB10_A2UI: u32 = 0x906F;
const UNSIGNED_INT_2_10_10_10_REV: u32 = 0x8368;
const COLOR: u32 = 0x1800;
const READ_FRAMEBUFFER: u32 = 0x8CA8;
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const IMPLEMENTATION_COLOR_READ_TYPE: u32 = 0x8B9A;
const IMPLEMENTATION_COLOR_READ_FORMAT: u32 = 0x8B9B;
const COMPONENT_TYPE: u32 = 0x8211;
const RED_SIZE: u32 = 0x8212;
const ALPHA_SIZE: u32 = 0x8215;
const RENDERBUFFER_GREEN_SIZE: u32 = 0x8D51;

/// A format under test: internal format, upload format and type, whether signed, bytes per
/// component of the upload (4 for the packed type).
struct Fmt(u32, u32, u32, bool, usize);

const FORMATS: [Fmt; 8] = [
    Fmt(R8I, RED_INTEGER, BYTE, true, 1),
    Fmt(R8UI, RED_INTEGER, UNSIGNED_BYTE, false, 1),
    Fmt(RG16I, RG_INTEGER, SHORT, true, 2),
    Fmt(R32I, RED_INTEGER, INT, true, 4),
    Fmt(RG8UI, RG_INTEGER, UNSIGNED_BYTE, false, 1),
    Fmt(RGBA16UI, RGBA_INTEGER, UNSIGNED_SHORT, false, 2),
    Fmt(RGBA32UI, RGBA_INTEGER, UNSIGNED_INT, false, 4),
    Fmt(RGB10_A2UI, RGBA_INTEGER, UNSIGNED_INT_2_10_10_10_REV, false, 4),
];

/// Components of an integer upload format.
fn components(format: u32) -> usize {
    match format {
        RGBA_INTEGER => 4,
        RGB_INTEGER => 3,
        RG_INTEGER => 2,
        _ => 1,
    }
}

/// A 4×4 image of format `f`: texel i's component c is (i * 7 + c * 3) scaled into the
/// format's range, negative for signed formats' odd texels.
fn image(f: &Fmt) -> Vec<u8> {
    let mut out = Vec::new();
    for i in 0..16i64 {
        if f.2 == UNSIGNED_INT_2_10_10_10_REV {
            let v = (i * 61 % 1024) as u32
                | ((i * 7 % 1024) as u32) << 10
                | ((1000 - i) as u32) << 20
                | (i as u32 % 4) << 30;
            out.extend(v.to_ne_bytes());
            continue;
        }
        for c in 0..components(f.1) as i64 {
            let mut v = i * 7 + c * 3 + if f.4 > 1 { 300 } else { 0 };
            if f.3 && i % 2 == 1 {
                v = -v;
            }
            out.extend(&v.to_ne_bytes()[..f.4]);
        }
    }
    out
}

/// Reads pixel (x, y) of the read buffer as RGBA integers of the buffer's signedness; its four
/// components' low 16 bits, and the first's high 16 bits, as marks.
fn read(gl: Gl<'_>, x: i32, y: i32, signed: bool, marks: &mut Vec<u32>) -> R {
    let px = gl.glReadPixels(x, y, 1, 1, RGBA_INTEGER, if signed { INT } else { UNSIGNED_INT })?.0;
    let v: Vec<u32> = px.chunks_exact(4).map(|b| u32::from_ne_bytes([b[0], b[1], b[2], b[3]])).collect();
    marks.extend(v.iter().take(4).map(|c| c & 0xFFFF));
    marks.push(v.first().map_or(0xDEAD, |c| c >> 16));
    Ok(())
}

/// The integer formats program.
pub fn integers(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    let signed_out = "#version 300 es
        layout(location = 0) out highp ivec4 o;
        void main() { o = ivec4(-3, 70, -100, 1); }";
    let unsigned_out = "#version 300 es
        layout(location = 0) out highp uvec4 o;
        void main() { o = uvec4(3u, 70u, 200u, 2u); }";
    let signed_p = screen(gl, n, VS_SCREEN, signed_out)?;
    let unsigned_p = screen(gl, n, VS_SCREEN, unsigned_out)?;
    for f in &FORMATS {
        let t = n.next();
        gl.glGenTextures(Slice::new(&[t]))?;
        gl.glBindTexture(TEXTURE_2D, t)?;
        let data = image(f);
        gl.glTexImage2D(TEXTURE_2D, 0, f.0 as i32, 4, 4, 0, f.1, f.2, Some(Blob::borrowed(&data)))?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, COMPONENT_TYPE)? as u32);
        let red = gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, RED_SIZE)?;
        let alpha = gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, ALPHA_SIZE)?;
        marks.push((red | alpha << 6) as u32);
        marks.push(gl.glGetIntegerv(IMPLEMENTATION_COLOR_READ_FORMAT)?.first().copied().unwrap_or(0) as u32);
        marks.push(gl.glGetIntegerv(IMPLEMENTATION_COLOR_READ_TYPE)?.first().copied().unwrap_or(0) as u32);
        // The upload.
        read(gl, 1, 2, f.3, &mut marks)?;
        // A draw into the left half, a clear of the top right texel.
        gl.glViewport(0, 0, 2, 4)?;
        gl.glUseProgram(if f.3 { signed_p } else { unsigned_p })?;
        gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
        gl.glEnable(SCISSOR_TEST)?;
        gl.glScissor(3, 3, 1, 1)?;
        if f.3 {
            gl.glClearBufferiv(COLOR, 0, Slice::new(&[-9, 33, 44, 55]))?;
        } else {
            gl.glClearBufferuiv(COLOR, 0, Slice::new(&[9, 33, 44, 3]))?;
        }
        gl.glDisable(SCISSOR_TEST)?;
        read(gl, 0, 0, f.3, &mut marks)?;
        read(gl, 3, 3, f.3, &mut marks)?;
        // The buffer's own format and type (its implementation read format).
        let px = gl.glReadPixels(1, 2, 1, 1, f.1, f.2)?.0;
        marks.push(px.first().map_or(0xDEAD, |b| u32::from(*b)) | (px.len() as u32) << 8);
        // Reads of another kind.
        gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?;
        marks.push(gl.glGetError()?);
        gl.glReadPixels(0, 0, 1, 1, RGBA_INTEGER, if f.3 { UNSIGNED_INT } else { INT })?;
        marks.push(gl.glGetError()?);
        // Data of another kind, and mipmaps of an image that cannot be filtered.
        gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[0; 4]))?;
        marks.push(gl.glGetError()?);
        gl.glGenerateMipmap(TEXTURE_2D)?;
        marks.push(gl.glGetError()?);
    }

    // Two buffers of different kinds at once: a signed renderbuffer and an unsigned texture.
    let rb = n.next();
    gl.glGenRenderbuffers(Slice::new(&[rb]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, RGBA32I, 4, 4)?;
    marks.push(gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_GREEN_SIZE)? as u32);
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb)?;
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(TEXTURE_2D, 0, R8UI as i32, 4, 4, 0, RED_INTEGER, UNSIGNED_BYTE, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + 1, TEXTURE_2D, t, 0)?;
    gl.glDrawBuffersEXT(Slice::new(&[COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1]))?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    let both = "#version 300 es
        precision highp float;
        in vec2 uv;
        layout(location = 0) out highp ivec4 s;
        layout(location = 1) out highp uint u;
        void main() { s = ivec4(uv * 8.0, -70000, 5); u = uint(uv.x * 4.0) * 50u; }";
    screen(gl, n, VS_SCREEN, both)?;
    gl.glViewport(0, 0, 4, 4)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    gl.glClearBufferuiv(COLOR, 1, Slice::new(&[77, 0, 0, 0]))?;
    gl.glReadBufferNV(COLOR_ATTACHMENT0)?;
    read(gl, 3, 1, true, &mut marks)?;
    gl.glReadBufferNV(COLOR_ATTACHMENT0 + 1)?;
    read(gl, 3, 1, false, &mut marks)?;
    marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, COMPONENT_TYPE)? as u32);

    // Integer blits: scaled and flipped into a signed buffer; linear filtering, and a float
    // buffer, refused.
    let src_fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[src_fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, src_fb)?;
    let src = n.next();
    gl.glGenTextures(Slice::new(&[src]))?;
    gl.glBindTexture(TEXTURE_2D, src)?;
    let data: Vec<u8> = (0..16i32).flat_map(|i| (i * 1000 - 7000).to_ne_bytes()).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, R32I as i32, 4, 4, 0, RED_INTEGER, INT, Some(Blob::borrowed(&data)))?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, src, 0)?;
    let dst_fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[dst_fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, dst_fb)?;
    let big = n.next();
    gl.glGenRenderbuffers(Slice::new(&[big]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, big)?;
    gl.glRenderbufferStorage(RENDERBUFFER, RGBA32I, 8, 8)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, big)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, src_fb)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 8, 8, 0, 0, COLOR_BUFFER_BIT, NEAREST as u32)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 0, 0, 8, 8, COLOR_BUFFER_BIT, LINEAR as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(READ_FRAMEBUFFER, dst_fb)?;
    read(gl, 1, 1, true, &mut marks)?;
    read(gl, 6, 3, true, &mut marks)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 0, 0, 8, 8, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;

    // An RGB integer image cannot be rendered to; RGB integer renderbuffers do not exist.
    let rgb = n.next();
    gl.glGenTextures(Slice::new(&[rgb]))?;
    gl.glBindTexture(TEXTURE_2D, rgb)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGB8UI as i32, 4, 4, 0, RGB_INTEGER, UNSIGNED_BYTE, None)?;
    marks.push(gl.glGetError()?);
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + 1, TEXTURE_2D, rgb, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glRenderbufferStorage(RENDERBUFFER, RGB8UI, 4, 4)?;
    marks.push(gl.glGetError()?);
    // Uploads whose data does not fit the format.
    gl.glTexImage2D(TEXTURE_2D, 0, R8UI as i32, 1, 1, 0, RED_INTEGER, SHORT, None)?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA_INTEGER, UNSIGNED_BYTE, None)?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_2D, 0, R8I as i32, 1, 1, 0, RED, BYTE, None)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

//! `GL_EXT_color_buffer_half_float`: framebuffers of each half-float renderbuffer format and
//! of half-float textures, their completeness, channel bits and implementation read format;
//! values beyond [0, 1] drawn, blended and cleared into them, then read as `GL_HALF_FLOAT`
//! (the half floats marked as colours), as `GL_UNSIGNED_BYTE` (clamped) and through a texture
//! sampled into the window (scaled, so the stored values show); the formats that are not
//! renderable; and the errors, marked as colours.

use super::multi_draw::mark_all;
use super::textures::new_texture;
use super::*;

const ONE: u32 = 1;
const RGBA16F: u32 = 0x881A;
const RGB16F: u32 = 0x881B;
const RG16F: u32 = 0x822F;
const R16F: u32 = 0x822D;
const RED_EXT: u32 = 0x1903;
const RG_EXT: u32 = 0x8227;
const HALF_FLOAT: u32 = 0x140B;
const RENDERBUFFER: u32 = 0x8D41;
const RED_SIZE: u32 = 0x8D50;
const READ_TYPE: u32 = 0x8B9A;
const READ_FORMAT: u32 = 0x8B9B;
const RED_BITS: u32 = 0x0D52;

/// A fragment stage writing values beyond [0, 1].
const FS_WIDE: &str = "precision highp float; void main() { gl_FragColor = vec4(2.5, -1.5, 0.25, 1.75); }";
/// Shows a texture's values v as v / 4 + 0.5.
const FS_SCALED: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { gl_FragColor = texture2D(s, t) * 0.25 + 0.5; }";

/// Marks the framebuffer's status, red bits and implementation read format and type.
fn state(gl: Gl<'_>, marks: &mut Vec<u32>) -> R {
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    for pname in [RED_BITS, READ_FORMAT, READ_TYPE] {
        marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-7) as u32);
    }
    marks.push(gl.glGetError()?);
    Ok(())
}

/// Draws the wide colour over the bound 4×4 framebuffer, clears part of it, blends the wide
/// colour again over the rest, and marks pixel (1, 1) and (3, 3) read as GL_HALF_FLOAT in
/// `read_format`, and (1, 1) as bytes.
fn draw_and_read(gl: Gl<'_>, n: &mut Names, read_format: u32, marks: &mut Vec<u32>) -> R {
    gl.glViewport(0, 0, 4, 4)?;
    program(gl, n, VS_POS, FS_WIDE, &["pos"])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(ONE, ONE)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 0.0, 0.0), TRIANGLES)?;
    gl.glDisable(BLEND)?;
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(3, 3, 1, 1)?;
    gl.glClearColor(0.75, 0.5, 0.25, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glDisable(SCISSOR_TEST)?;
    for at in [1, 3] {
        let px = gl.glReadPixels(at, at, 1, 1, read_format, HALF_FLOAT)?;
        marks.push(gl.glGetError()?);
        marks.extend(px.0.chunks_exact(2).map(|h| u32::from(u16::from_ne_bytes([h[0], h[1]]))));
    }
    let px = gl.glReadPixels(1, 1, 1, 1, RGBA, UNSIGNED_BYTE)?;
    marks.extend(px.0.iter().map(|&b| u32::from(b)));
    marks.push(gl.glGetError()?);
    Ok(())
}

fn half_float_color(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    // Renderbuffers of each format.
    for (format, read) in [(RGBA16F, RGBA), (RGB16F, RGBA), (RG16F, RG_EXT), (R16F, RED_EXT)] {
        let rb = n.next();
        gl.glGenRenderbuffers(Slice::new(&[rb]))?;
        gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
        gl.glRenderbufferStorage(RENDERBUFFER, format, 4, 4)?;
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb)?;
        for k in 0..4 {
            marks.push(gl.glGetRenderbufferParameteriv(RENDERBUFFER, RED_SIZE + k)? as u32);
        }
        state(gl, &mut marks)?;
        draw_and_read(gl, n, read, &mut marks)?;
    }
    // Half-float textures: renderable as RGBA, RGB, RG and RED, not as luminance; a float
    // one is unsupported.
    // (The state queries of an incomplete framebuffer are Mesa's leftovers: only its status.)
    for (format, ty, complete) in [
        (RGBA, HALF_FLOAT_OES, true),
        (RGB, HALF_FLOAT_OES, true),
        (RG_EXT, HALF_FLOAT_OES, true),
        (RED_EXT, HALF_FLOAT_OES, true),
        (LUMINANCE, HALF_FLOAT_OES, false),
        (RGBA, FLOAT, false),
    ] {
        let t = new_texture(gl, n, NEAREST, NEAREST)?;
        gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 4, 4, 0, format, ty, None)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
        if complete {
            state(gl, &mut marks)?;
        } else {
            marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        }
    }
    // A half-float texture drawn into, then sampled into the window.
    let t = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, HALF_FLOAT_OES, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    draw_and_read(gl, n, RGBA, &mut marks)?;
    // A copy out of it, and a read of a type it does not offer.
    let copy = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    let _ = gl.glReadPixels(0, 0, 1, 1, RGBA, HALF_FLOAT_OES)?;
    marks.push(gl.glGetError()?);
    let _ = gl.glReadPixels(0, 0, 1, 1, RG_EXT, HALF_FLOAT)?;
    marks.push(gl.glGetError()?);
    let _ = copy;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    let _ = gl.glReadPixels(0, 0, 1, 1, RGBA, HALF_FLOAT)?;
    marks.push(gl.glGetError()?);
    gl.glBindTexture(TEXTURE_2D, t)?;
    program(gl, n, VS_TEX, FS_SCALED, &["pos", "uv"])?;
    gl.glViewport(0, 0, 16, 16)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case { name: "half_float_color", run: half_float_color, tol: DEFAULT, expects_error: false }]
}

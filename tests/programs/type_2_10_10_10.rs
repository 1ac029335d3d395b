//! `GL_EXT_texture_type_2_10_10_10_REV`: RGBA and RGB images of `UNSIGNED_INT_2_10_10_10_REV_EXT`
//! texels (red in the low 10 bits, alpha in the top 2, which RGB ignores), unsized and sized
//! (`GL_RGB10_A2_EXT`, `GL_RGB10_EXT`), sampled nearest and linear and updated in part; then
//! the pairs that are refused and a framebuffer with such an image attached (incomplete on
//! Mesa), each marked as a colour.

use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const UNSIGNED_INT_2_10_10_10_REV: u32 = 0x8368;
const RGB10_A2: u32 = 0x8059;
const RGB10: u32 = 0x8052;

/// `n` packed texels: every 10-bit value spread over the channels, every alpha.
fn texels(n: u32, seed: u32) -> Vec<u8> {
    (0..n)
        .flat_map(|i| {
            let k = i * 97 + seed;
            let (r, g, b, a) = (k * 131 % 1024, k * 577 % 1024, k * 313 % 1024, k % 4);
            (r | g << 10 | b << 20 | a << 30).to_ne_bytes()
        })
        .collect()
}

/// A 4×4 image of `internal` from packed `data` in `format`.
fn upload(gl: Gl<'_>, internal: u32, format: u32, data: &[u8]) -> R {
    let ty = UNSIGNED_INT_2_10_10_10_REV;
    gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 4, 4, 0, format, ty, Some(Blob::borrowed(data)))
}

fn type_2_10_10_10(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let uploads = [(RGBA, RGBA, NEAREST), (RGB, RGB, NEAREST), (RGB10_A2, RGBA, LINEAR), (RGB10, RGB, LINEAR)];
    for (i, (internal, format, filter)) in uploads.into_iter().enumerate() {
        new_texture(gl, n, filter, filter)?;
        let data = texels(16, i as u32);
        upload(gl, internal, format, &data)?;
        // One texel replaced, by data of the same type.
        let one = texels(1, 99 + i as u32);
        gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 2, 1, 1, format, UNSIGNED_INT_2_10_10_10_REV, Blob::borrowed(&one))?;
        blit(gl, n, [i as i32 * 16, 0, 16, 48])?;
    }
    let data = texels(16, 7);
    let mut marks = Vec::new();
    // Internal format and format apart, a format the type does not pack, sized formats with
    // another type or format.
    for (internal, format) in [(RGBA, RGB), (RGB, RGBA), (LUMINANCE, LUMINANCE), (RGB10, RGBA), (RGB10_A2, RGB)] {
        upload(gl, internal, format, &data)?;
        marks.push(gl.glGetError()?);
    }
    gl.glTexImage2D(TEXTURE_2D, 0, RGB10_A2 as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))?;
    marks.push(gl.glGetError()?);
    // The last image drawn above, attached to a framebuffer.
    let fb = n.next();
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    let t = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_INT_2_10_10_10_REV, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)?;
    Ok(())
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case { name: "type_2_10_10_10", run: type_2_10_10_10, tol: DEFAULT, expects_error: false }]
}

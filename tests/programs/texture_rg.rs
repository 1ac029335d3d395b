//! `GL_EXT_texture_rg`: RED and RG textures (unsigned bytes, floats, half floats, and the sized
//! R8 and RG8), sampled as (r, 0, 0, 1) and (r, g, 0, 1); an RG texture and an R8 renderbuffer
//! rendered into, whose absent channels draws and clears leave alone; reads in RED and RG; the
//! framebuffers' channel bits and read format.

use super::multi_draw::mark_all;
use super::textures::{blit, float_data, new_texture};
use super::*;

const RED_EXT: u32 = 0x1903;
const RG_EXT: u32 = 0x8227;
const R8_EXT: u32 = 0x8229;
const RG8_EXT: u32 = 0x822B;

/// Six 4×4 textures side by side: RED and RG of bytes, RED of floats, RG of half floats, and
/// the sized R8 and RG8.
fn rg_uploads(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    let bytes: Vec<u8> = (0..32u32).map(|i| (i * 37 % 256) as u8).collect();
    let floats: Vec<f32> = (0..32).map(|i| (i % 7) as f32 / 6.0).collect();
    let uploads: [(u32, u32, u32, Vec<u8>); 6] = [
        (RED_EXT, RED_EXT, UNSIGNED_BYTE, bytes[..16].to_vec()),
        (RG_EXT, RG_EXT, UNSIGNED_BYTE, bytes.clone()),
        (RED_EXT, RED_EXT, FLOAT, float_data(&floats[..16], FLOAT)),
        (RG_EXT, RG_EXT, HALF_FLOAT_OES, float_data(&floats, HALF_FLOAT_OES)),
        (R8_EXT, RED_EXT, UNSIGNED_BYTE, bytes[16..].to_vec()),
        (RG8_EXT, RG_EXT, UNSIGNED_BYTE, bytes.iter().rev().copied().collect()),
    ];
    for (i, (internal, format, ty, data)) in uploads.into_iter().enumerate() {
        new_texture(gl, n, NEAREST, NEAREST)?;
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 4, 4, 0, format, ty, Some(Blob::borrowed(&data)))?;
        blit(gl, n, [(i as i32 % 3) * 21, (i as i32 / 3) * 32, 21, 32])?;
    }
    Ok(())
}

/// An RG texture of unspecified texels rendered into (cleared, then a quad drawn), shown and
/// read back as RG; an R8 renderbuffer likewise, read back as RGBA and as RED; the reads shown
/// as textures, and the channel bits and read format of each framebuffer marked along the top.
fn rg_render(gl: Gl<'_>, n: &mut Names) -> R {
    let (fb, rb) = (n.next(), n.next());
    let tex = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RG_EXT as i32, 16, 16, 0, RG_EXT, UNSIGNED_BYTE, None)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    let mut marks = Vec::new();
    let mut draw_into = |gl: Gl<'_>, n: &mut Names| -> R {
        for pname in [0x0D52, 0x0D53, 0x0D54, 0x0D55, 0x8B9B, 0x8B9A] {
            marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-1) as u32);
        }
        gl.glViewport(0, 0, 16, 16)?;
        gl.glClearColor(0.5, 0.25, 0.75, 0.5)?;
        gl.glClear(COLOR_BUFFER_BIT)?;
        let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
        color(gl, p, [0.9, 0.6, 0.3, 0.2])?;
        draw_positions(gl, n, &quad(-0.5, -0.5, 0.5, 0.5, 0.0), TRIANGLES)
    };
    draw_into(gl, n)?;
    gl.glPixelStorei(0x0D05, 1)?; // PACK_ALIGNMENT
    let rg = gl.glReadPixels(0, 0, 16, 16, RG_EXT, UNSIGNED_BYTE)?.0;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, R8_EXT, 16, 16)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, rb)?;
    draw_into(gl, n)?;
    let rgba = gl.glReadPixels(0, 0, 16, 16, RGBA, UNSIGNED_BYTE)?.0;
    let red = gl.glReadPixels(0, 0, 16, 16, RED_EXT, UNSIGNED_BYTE)?.0;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    blit(gl, n, [0, 0, 16, 16])?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    let shown: [(u32, &[u8]); 3] = [(RGBA, &rgba), (LUMINANCE, &red), (LUMINANCE_ALPHA, &rg)];
    for (i, (format, data)) in shown.into_iter().enumerate() {
        new_texture(gl, n, NEAREST, NEAREST)?;
        gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 16, 16, 0, format, UNSIGNED_BYTE, Some(Blob::borrowed(data)))?;
        blit(gl, n, [16 + 16 * i as i32, 0, 16, 16])?;
    }
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "rg_uploads", run: rg_uploads, tol: DEFAULT, expects_error: false },
        Case { name: "rg_render", run: rg_render, tol: DEFAULT, expects_error: false },
    ]
}

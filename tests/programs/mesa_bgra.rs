//! `GL_MESA_bgra` as Mesa offers it on an ES 2.0 context: RGBA images take BGRA data and BGRA
//! images RGBA data, whole and in part; `GL_BGR_EXT` is a format no upload takes. The images
//! are drawn, and the errors marked as colours.

use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const BGR: u32 = 0x80E0;
const BGRA: u32 = 0x80E1;

fn mesa_bgra(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let texels: Vec<u8> = (0..64u32).map(|i| (i * 29 + 11) as u8).collect();
    let mut marks = Vec::new();
    for (i, (internal, format, sub)) in
        [(RGBA, BGRA, RGBA), (BGRA, RGBA, BGRA), (RGBA, RGBA, BGRA), (BGRA, BGRA, RGBA)].into_iter().enumerate()
    {
        new_texture(gl, n, NEAREST, NEAREST)?;
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 4, 4, 0, format, UNSIGNED_BYTE, Some(Blob::borrowed(&texels)))?;
        marks.push(gl.glGetError()?);
        gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 1, 2, 2, sub, UNSIGNED_BYTE, Blob::borrowed(&texels[20..36]))?;
        marks.push(gl.glGetError()?);
        blit(gl, n, [i as i32 * 16, 0, 16, 40])?;
    }
    // BGR, and BGRA with another type or into RGB.
    for (internal, format, ty) in [
        (BGR, BGR, UNSIGNED_BYTE),
        (BGR, RGB, UNSIGNED_BYTE),
        (RGBA, BGR, UNSIGNED_BYTE),
        (RGB, BGRA, UNSIGNED_BYTE),
        (RGBA, BGRA, 0x8365),
        (BGRA, BGRA, FLOAT),
    ] {
        gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 2, 2, 0, format, ty, Some(Blob::borrowed(&texels)))?;
        marks.push(gl.glGetError()?);
    }
    gl.glCopyTexImage2D(TEXTURE_2D, 0, BGRA, 0, 0, 2, 2, 0)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)?;
    Ok(())
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case { name: "mesa_bgra", run: mesa_bgra, tol: DEFAULT, expects_error: false }]
}

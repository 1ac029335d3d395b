//! `GL_APPLE_texture_max_level`: a 16×16 texture whose five levels are each one colour, with
//! the last level sampled limited to 2, drawn at every level's size (the smaller sizes show
//! level 2); a texture with only levels 0 and 1, complete with the limit at 1 and not at 2;
//! the parameter's default, rounding, errors and queries marked as colours.

use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const TEXTURE_MAX_LEVEL: u32 = 0x813D;

/// Defines levels `0..levels` of a 16×16 texture, level `l` in colour `l`.
fn levels(gl: Gl<'_>, levels: i32) -> R {
    let colours = [[255u8, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 0, 255], [0, 255, 255, 255]];
    for l in 0..levels {
        let size = 16 >> l;
        let data = colours[l as usize].repeat((size * size) as usize);
        gl.glTexImage2D(TEXTURE_2D, l, RGBA as i32, size, size, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))?;
    }
    Ok(())
}

fn max_level(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut marks = Vec::new();
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_MAX_LEVEL)?.first().copied().unwrap_or(-7) as u32);
    levels(gl, 5)?;
    for (v, fl) in [(-1.0, false), (2.6, true), (-0.4, true), (2.0, false)] {
        if fl {
            gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LEVEL, v)?;
        } else {
            gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, v as i32)?;
        }
        marks.push(gl.glGetError()?);
        marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_MAX_LEVEL)?.first().copied().unwrap_or(-7) as u32);
    }
    let mut x = 0;
    for size in [16, 8, 4, 2, 1] {
        blit(gl, n, [x, 0, size, size])?;
        x += size + 2;
    }
    // Linear between levels: level 2 alone at and past its size.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, LINEAR_MIPMAP_LINEAR)?;
    let mut x = 0;
    for size in [12, 6, 3, 1] {
        blit(gl, n, [x, 18, size, size])?;
        x += size + 2;
    }
    // Two levels defined: complete while the limit stops at them.
    for limit in [1, 2] {
        new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
        levels(gl, 2)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, limit)?;
        blit(gl, n, [40 + (limit - 1) * 12, 18, 8, 8])?;
    }
    // A cube map takes it too; a bad target does not.
    let cube = n.next();
    gl.glBindTexture(TEXTURE_CUBE_MAP, cube)?;
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MAX_LEVEL, 3)?;
    marks.push(gl.glGetError()?);
    marks.push(gl.glGetTexParameteriv(TEXTURE_CUBE_MAP, TEXTURE_MAX_LEVEL)?.first().copied().unwrap_or(-7) as u32);
    gl.glTexParameteri(0x1234, TEXTURE_MAX_LEVEL, 3)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)?;
    Ok(())
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case { name: "max_level", run: max_level, tol: DEFAULT, expects_error: false }]
}

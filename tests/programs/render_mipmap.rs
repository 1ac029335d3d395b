//! `GL_OES_fbo_render_mipmap`: levels above 0 of a texture attached and rendered into, then
//! sampled level by level; attachments of levels whose texture's levels are not all defined
//! (incomplete), and of levels out of range (errors); all marked along the top.

use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL: u32 = 0x8CD2;

fn render_mipmap(gl: Gl<'_>, n: &mut Names) -> R {
    let fb = n.next();
    let tex = new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    let mut marks = Vec::new();
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    // Only level 0 and 1 defined: level 1 is not attachable yet.
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glTexImage2D(TEXTURE_2D, 1, RGBA as i32, 16, 16, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 1)?;
    marks.push(gl.glGetError()?);
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    for level in 2..6 {
        let size = 32 >> level;
        gl.glTexImage2D(TEXTURE_2D, level, RGBA as i32, size, size, 0, RGBA, UNSIGNED_BYTE, None)?;
    }
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    // Each of levels 1 to 3 cleared to its own colour, with a quad drawn over part of it.
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    for level in 1..4 {
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, level)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        let level_param = gl.glGetFramebufferAttachmentParameteriv(
            FRAMEBUFFER,
            COLOR_ATTACHMENT0,
            FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL,
        )?;
        marks.push(level_param as u32);
        let size = 32 >> level;
        gl.glViewport(0, 0, size, size)?;
        let l = level as f32;
        gl.glClearColor(0.2 * l, 1.0 - 0.3 * l, 0.5, 1.0)?;
        gl.glClear(COLOR_BUFFER_BIT)?;
        color(gl, p, [1.0 - 0.25 * l, 0.1, 0.3 * l, 1.0])?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 0.0, 0.0), TRIANGLES)?;
    }
    // Levels out of range, and a level whose size no longer matches level 0's.
    for level in [-1, 15] {
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, level)?;
        marks.push(gl.glGetError()?);
    }
    gl.glTexImage2D(TEXTURE_2D, 2, RGBA as i32, 3, 3, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 1)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glTexImage2D(TEXTURE_2D, 2, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    // Levels 1 and 3 shown, each drawn at its own size so that it is the level sampled.
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, tex)?;
    blit(gl, n, [0, 0, 16, 16])?;
    blit(gl, n, [20, 0, 4, 4])?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![Case { name: "render_mipmap", run: render_mipmap, tol: DEFAULT, expects_error: false }]
}

//! `GL_EXT_texture_filter_anisotropic`: a mipmapped checkerboard on a floor seen at a grazing
//! angle, drawn with anisotropy 1, 4 and 16 (trilinear filtering, which wgpu needs for it);
//! the parameter's errors, clamping and queries marked along the top.

use super::multi_draw::mark_all;
use super::textures::new_texture;
use super::*;

const TEXTURE_MAX_ANISOTROPY_EXT: u32 = 0x84FE;
const MAX_TEXTURE_MAX_ANISOTROPY_EXT: u32 = 0x84FF;

/// A floor receding from the viewer: texture coordinates repeat 8 times along it.
const VS_FLOOR: &str = "attribute vec4 pos; attribute vec2 uv; varying vec2 t;
    void main() { t = uv; gl_Position = vec4(pos.x * (1.0 - 0.9 * pos.y), pos.y, 0.0, 1.0 + 6.0 * (pos.y + 1.0)); }";

/// The parameter's limit, initial value, errors and clamping, marked.
fn anisotropic_state(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    marks.push(gl.glGetFloatv(MAX_TEXTURE_MAX_ANISOTROPY_EXT)?.first().copied().unwrap_or(-1.0) as u32);
    anisotropic_texture(gl, n)?;
    marks.push(gl.glGetTexParameterfv(TEXTURE_2D, TEXTURE_MAX_ANISOTROPY_EXT)?.first().copied().unwrap_or(-1.0) as u32);
    // Errors and clamping.
    for v in [0.5f32, 0.0, 100.0, 2.0] {
        gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_ANISOTROPY_EXT, v)?;
        marks.push(gl.glGetError()?);
        marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_MAX_ANISOTROPY_EXT)?.first().copied().unwrap_or(-1) as u32);
    }
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)?;
    Ok(())
}

/// A trilinear, repeating texture of explicit levels, bound.
fn anisotropic_texture(gl: Gl<'_>, n: &mut Names) -> R {
    let tex = new_texture(gl, n, LINEAR_MIPMAP_LINEAR, LINEAR)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_S, REPEAT)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, REPEAT)?;
    let _ = tex;
    // Every level given (not generated, whose filter is the implementation's): a checkerboard
    // whose squares halve with the level, each level a little darker.
    for level in 0..7 {
        let size = 64usize >> level;
        let cell = (4usize >> level).max(1);
        let dim = 20 * level as u8;
        let texels: Vec<u8> = (0..size * size)
            .flat_map(|i| {
                if ((i % size) / cell + (i / size) / cell).is_multiple_of(2) {
                    [230 - dim, 230 - dim, 230, 255]
                } else {
                    [20, 40 + dim, 160, 255]
                }
            })
            .collect();
        let s = size as i32;
        gl.glTexImage2D(TEXTURE_2D, level, RGBA as i32, s, s, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&texels)))?;
    }
    Ok(())
}

/// The floor at anisotropy 1, 4 and 16, side by side.
fn anisotropic_floor(gl: Gl<'_>, n: &mut Names) -> R {
    anisotropic_texture(gl, n)?;
    program(gl, n, VS_FLOOR, FS_TEX, &["pos", "uv"])?;
    let v: Vec<f32> = [(-1.0, -1.0, 0.0, 0.0), (1.0, -1.0, 1.0, 0.0), (1.0, 1.0, 1.0, 8.0), (-1.0, 1.0, 0.0, 8.0)]
        .iter()
        .flat_map(|&(x, y, s, t)| [x, y, s, t])
        .collect();
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 2, FLOAT, false, 16, 0)?;
    attrib(gl, 1, 2, FLOAT, false, 16, 8)?;
    for (i, a) in [1.0f32, 4.0, 16.0].into_iter().enumerate() {
        gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_ANISOTROPY_EXT, a)?;
        gl.glViewport(i as i32 * 21, 0, 21, 56)?;
        gl.glDrawArrays(TRIANGLE_FAN, 0, 4)?;
    }
    Ok(())
}

/// The programs of this file. The floor's tolerance: Mesa's llvmpipe and lavapipe already differ
/// by up to 5 in trilinear filtering under perspective (the anisotropy 1 panel), and by up to 11
/// with anisotropy; without anisotropy applied, over 600 pixels differ by more than 12.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "anisotropic_state", run: anisotropic_state, tol: DEFAULT, expects_error: false },
        Case {
            name: "anisotropic_floor",
            run: anisotropic_floor,
            tol: Tol { max_diff: 12, min_fraction: 0.999 },
            expects_error: false,
        },
    ]
}

//! ES 3.0's packed float formats, `R11F_G11F_B10F` and `RGB9_E5`: images given as floats (which
//! each format rounds to its precision), as half floats, and as their packed types, whole and
//! in part, with `glTexStorage2D` too; shown magnified by several scales (the fractions show the
//! rounding), and the uploads each refuses as marks.

use super::super::multi_draw::mark_all;
use super::super::*;
use super::language::{screen, VS_SCREEN};

const R11F_G11F_B10F: u32 = 0x8C3A;
const UNSIGNED_INT_10F_11F_11F_REV: u32 = 0x8C3B;
const RGB9_E5: u32 = 0x8C3D;
const UNSIGNED_INT_5_9_9_9_REV: u32 = 0x8C3E;
const HALF_FLOAT: u32 = 0x140B;

/// Four RGB texels whose rounding each format shows: just above steps, negatives, values past
/// the largest, tiny ones.
const TEXELS: [f32; 12] = [1.0078125, 0.3333, 70000.0, -1.0, 5e-5, 2.5e-6, 12.34, 0.1, 3.0, 1e-3, 100.7, 0.75];

/// The packed float formats program.
pub fn packed_floats(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let fs = "#version 300 es
        precision highp float;
        uniform sampler2D t;
        uniform float s;
        in vec2 uv;
        out vec4 o;
        void main() { o = vec4(fract(texture(t, uv).rgb * s), 1.0); }";
    let p = screen(gl, n, VS_SCREEN, fs)?;
    let scale = gl.glGetUniformLocation(p, Text::borrowed("s"))?;
    let floats: Vec<u8> = TEXELS.iter().flat_map(|v| v.to_ne_bytes()).collect();
    let halves: Vec<u8> = TEXELS.iter().flat_map(|v| half::f16::from_f32(*v).to_bits().to_ne_bytes()).collect();
    // Packed texels: R11F_G11F_B10F's 1.5, 0.25 and 3.0 (and neighbours); RGB9_E5 with
    // exponent 2^4 and mantissas 3, 200 and 511.
    let r11: Vec<u8> = (0..4u32)
        .flat_map(|i| (((15 << 6) | (32 + i)) | (13 << 6) << 11 | ((16 << 5) | (16 + i)) << 22).to_ne_bytes())
        .collect();
    let e5: Vec<u8> =
        (0..4u32).flat_map(|i| ((15 + 4 - i) << 27 | 511 << 18 | 200 << 9 | (3 + i)).to_ne_bytes()).collect();
    let uploads: [(u32, u32, &[u8]); 6] = [
        (R11F_G11F_B10F, FLOAT, &floats),
        (RGB9_E5, FLOAT, &floats),
        (R11F_G11F_B10F, HALF_FLOAT, &halves),
        (RGB9_E5, HALF_FLOAT, &halves),
        (R11F_G11F_B10F, UNSIGNED_INT_10F_11F_11F_REV, &r11),
        (RGB9_E5, UNSIGNED_INT_5_9_9_9_REV, &e5),
    ];
    for (k, (internal, ty, data)) in uploads.iter().enumerate() {
        let t = n.next();
        gl.glGenTextures(Slice::new(&[t]))?;
        gl.glBindTexture(TEXTURE_2D, t)?;
        if k < 4 {
            gl.glTexImage2D(TEXTURE_2D, 0, *internal as i32, 2, 2, 0, RGB, *ty, Some(Blob::borrowed(data)))?;
        } else {
            // Storage, then the texels in two halves.
            gl.glTexStorage2D(TEXTURE_2D, 1, *internal, 2, 2)?;
            let (a, b) = data.split_at(8);
            gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 2, 1, RGB, *ty, Blob::borrowed(a))?;
            gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 1, 2, 1, RGB, *ty, Blob::borrowed(b))?;
        }
        marks.push(gl.glGetError()?);
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
        for (j, s) in [1.0f32, 1.0 / 64.0, 64.0, 4096.0].iter().enumerate() {
            gl.glUniform1f(scale, *s)?;
            gl.glViewport(k as i32 * W / 6, j as i32 * H / 8, W / 6, H / 8)?;
            gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
        }
        // Filtered linearly: both formats filter (scaled below 1, so that fract keeps it).
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
        gl.glUniform1f(scale, 1.0 / 65536.0)?;
        gl.glViewport(k as i32 * W / 6, H / 2, W / 6, H / 4)?;
        gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
        // The other format's packed type, RGBA data and an unsized format refused.
        let other = if *internal == RGB9_E5 { UNSIGNED_INT_10F_11F_11F_REV } else { UNSIGNED_INT_5_9_9_9_REV };
        gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGB, other, Blob::borrowed(&r11[..4]))?;
        marks.push(gl.glGetError()?);
        gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RGBA, FLOAT, Blob::borrowed(&floats[..16]))?;
        marks.push(gl.glGetError()?);
    }
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        RGB as i32,
        1,
        1,
        0,
        RGB,
        UNSIGNED_INT_10F_11F_11F_REV,
        Some(Blob::borrowed(&r11[..4])),
    )?;
    marks.push(gl.glGetError()?);
    gl.glTexImage2D(TEXTURE_2D, 0, R11F_G11F_B10F as i32, 1, 1, 0, RGBA, FLOAT, Some(Blob::borrowed(&floats[..16])))?;
    marks.push(gl.glGetError()?);
    gl.glViewport(0, 0, W, H)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

//! `GL_EXT_texture_compression_s3tc_srgb`: the four sRGB S3TC formats' blocks of every kind,
//! sampled (read as linear) from whole-block images the device may keep as blocks and from
//! images of other sizes that are decoded on upload, nearest and filtered, mipmapped, and
//! updated in part; and the errors of uncompressed data for them, as colours.

use super::compressed::{s3tc_blocks, Lcg};
use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const SRGB_DXT1: u32 = 0x8C4C;
const SRGB_ALPHA_DXT1: u32 = 0x8C4D;
const SRGB_ALPHA_DXT3: u32 = 0x8C4E;
const SRGB_ALPHA_DXT5: u32 = 0x8C4F;
const DXT5: u32 = 0x83F3;
const FORMATS: [u32; 4] = [SRGB_DXT1, SRGB_ALPHA_DXT1, SRGB_ALPHA_DXT3, SRGB_ALPHA_DXT5];

/// Blocks for a `size`×`size` image of `format`.
fn blocks(format: u32, size: i32, rng: &mut Lcg) -> Vec<u8> {
    s3tc_blocks(format, (((size + 3) / 4) * ((size + 3) / 4)) as usize, rng)
}

fn s3tc_srgb(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut rng = Lcg(31);
    let mut marks = Vec::new();
    for (i, format) in FORMATS.into_iter().enumerate() {
        let x = i as i32 * 16;
        // A mipmapped 8×8 image with one block replaced, nearest.
        new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
        for (level, size) in [8, 4, 2, 1].into_iter().enumerate() {
            let data = blocks(format, size, &mut rng);
            gl.glCompressedTexImage2D(TEXTURE_2D, level as i32, format, size, size, 0, Blob::borrowed(&data))?;
        }
        let block = blocks(format, 4, &mut rng);
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 4, 4, 4, 4, format, Blob::borrowed(&block))?;
        marks.push(gl.glGetError()?);
        blit(gl, n, [x, 0, 16, 16])?;
        blit(gl, n, [x + 2, 16, 4, 4])?;
        // Filtered in linear space: an 8×8 image and a 6×6 one (decoded on upload).
        for (size, y) in [(8, 22), (6, 38)] {
            new_texture(gl, n, LINEAR, LINEAR)?;
            let data = blocks(format, size, &mut rng);
            gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, size, size, 0, Blob::borrowed(&data))?;
            marks.push(gl.glGetError()?);
            blit(gl, n, [x, y, 15, 15])?;
        }
        // Uncompressed data is refused for the sRGB forms, whole or in part, as is data of the
        // format's linear form.
        let rgba = vec![200u8; 8 * 8 * 4];
        gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&rgba)))?;
        marks.push(gl.glGetError()?);
        gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, RGBA, UNSIGNED_BYTE, Blob::borrowed(&rgba[..64]))?;
        marks.push(gl.glGetError()?);
        let other = s3tc_blocks(DXT5, 1, &mut rng);
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, DXT5, Blob::borrowed(&other))?;
        marks.push(gl.glGetError()?);
    }
    // The marks go under the images, in the picture's top rows.
    mark_all(gl, &marks)
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    // Mesa's DXT decoder rounds the interpolated codes differently from Strata's by one step
    // at most (see compressed.rs), and sRGB decoding stretches a step near white to up to
    // 2.3 steps of the linear output.
    let tol = Tol { max_diff: 2, min_fraction: 0.999 };
    vec![Case { name: "s3tc_srgb", run: s3tc_srgb, tol, expects_error: false }]
}

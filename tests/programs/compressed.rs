//! Programs for the compressed formats: S3TC (`EXT_texture_compression_s3tc`, whose DXT1,
//! DXT3 and DXT5 formats `EXT_texture_compression_dxt1`, `ANGLE_texture_compression_dxt3` and
//! `ANGLE_texture_compression_dxt5` also name) and ETC1 (`OES_compressed_ETC1_RGB8_texture`)
//! blocks of every kind, partial blocks of small levels
//! and odd sizes, sub-image updates (of ETC1 images too: `EXT_compressed_ETC1_RGB8_sub_texture`),
//! and uncompressed data for S3TC internal formats.

use super::textures::{blit, new_texture};
use super::*;

const DXT1_RGB: u32 = 0x83F0;
const DXT1_RGBA: u32 = 0x83F1;
const DXT3: u32 = 0x83F2;
const DXT5: u32 = 0x83F3;
const ETC1_RGB8_OES: u32 = 0x8D64;

/// Deterministic pseudo-random bytes.
pub(super) struct Lcg(pub(super) u32);

impl Lcg {
    fn next(&mut self) -> u32 {
        self.0 = self.0.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        self.0 >> 8
    }

    pub(super) fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.next() as u8).collect()
    }
}

/// An S3TC colour block: endpoints and codes from `rng`.
fn colour_block(rng: &mut Lcg) -> Vec<u8> {
    rng.bytes(8)
}

/// `blocks` blocks of `format`.
pub(super) fn s3tc_blocks(format: u32, blocks: usize, rng: &mut Lcg) -> Vec<u8> {
    (0..blocks)
        .flat_map(|_| match format {
            // The sRGB forms' DXT1 too (GL_EXT_texture_compression_s3tc_srgb).
            DXT1_RGB | DXT1_RGBA | 0x8C4C | 0x8C4D => colour_block(rng),
            _ => [rng.bytes(8), colour_block(rng)].concat(),
        })
        .collect()
}

/// Solid colours exactly representable in RGB565, one per 4×4 block of an 8×8 image.
fn quadrants() -> Vec<u8> {
    let colours = [[255u8, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]];
    (0..64).flat_map(|i| colours[((i / 8) / 4) * 2 + (i % 8) / 4]).collect()
}

fn s3tc_textures(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut rng = Lcg(7);
    for (i, format) in [DXT1_RGB, DXT1_RGBA, DXT3, DXT5].into_iter().enumerate() {
        new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
        // 8×8, 4×4, 2×2 and 1×1 levels: the small ones are partial blocks.
        for (level, size) in [8, 4, 2, 1].into_iter().enumerate() {
            let blocks = ((size + 3) / 4) * ((size + 3) / 4);
            let data = s3tc_blocks(format, blocks as usize, &mut rng);
            gl.glCompressedTexImage2D(TEXTURE_2D, level as i32, format, size, size, 0, Blob::borrowed(&data))?;
        }
        // One block replaced in place.
        let block = s3tc_blocks(format, 1, &mut rng);
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 4, 0, 4, 4, format, Blob::borrowed(&block))?;
        let x = i as i32 * 16;
        blit(gl, n, [x, 0, 16, 16])?;
        blit(gl, n, [x, 16, 4, 4])?;
        blit(gl, n, [x + 6, 16, 2, 2])?;
        blit(gl, n, [x + 10, 16, 1, 1])?;
    }
    // Uncompressed data for S3TC internal formats: a whole image, then a block of one that
    // was uploaded compressed (solid RGB565 colours, so that compressing loses nothing).
    new_texture(gl, n, NEAREST, NEAREST)?;
    let q = quadrants();
    gl.glTexImage2D(TEXTURE_2D, 0, DXT5 as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&q)))?;
    blit(gl, n, [0, 32, 16, 16])?;
    new_texture(gl, n, NEAREST, NEAREST)?;
    let data = s3tc_blocks(DXT3, 4, &mut rng);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, DXT3, 8, 8, 0, Blob::borrowed(&data))?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 4, 4, 4, RGBA, UNSIGNED_BYTE, Blob::borrowed(&q[..64]))?;
    blit(gl, n, [16, 32, 16, 16])
}

/// An ETC1 block from `rng`, with differential offsets kept in range (ETC1 leaves the others
/// undefined; ETC2 gives them other meanings).
fn etc1_block(rng: &mut Lcg) -> Vec<u8> {
    let mut b = rng.bytes(8);
    if b[3] & 2 != 0 {
        for c in &mut b[..3] {
            let base = i32::from(*c >> 3);
            let delta = i32::from(((*c & 7) << 5) as i8 >> 5);
            if !(0..32).contains(&(base + delta)) {
                *c &= !7;
            }
        }
    }
    b
}

fn etc1_textures(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut rng = Lcg(11);
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    let mut x = 0;
    for (level, size) in [16, 8, 4, 2, 1].into_iter().enumerate() {
        let blocks = ((size + 3) / 4) * ((size + 3) / 4);
        let data: Vec<u8> = (0..blocks).flat_map(|_| etc1_block(&mut rng)).collect();
        gl.glCompressedTexImage2D(TEXTURE_2D, level as i32, ETC1_RGB8_OES, size, size, 0, Blob::borrowed(&data))?;
    }
    for level in 0..5 {
        let size = 32 >> level;
        blit(gl, n, [x, 0, size, size])?;
        x += size + 1;
    }
    // A size that is not a whole number of blocks.
    new_texture(gl, n, NEAREST, NEAREST)?;
    let data: Vec<u8> = (0..4).flat_map(|_| etc1_block(&mut rng)).collect();
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, ETC1_RGB8_OES, 6, 7, 0, Blob::borrowed(&data))?;
    blit(gl, n, [0, 34, 24, 28])
}

/// `blocks` ETC1 blocks from `rng`.
fn etc1_blocks(blocks: i32, rng: &mut Lcg) -> Vec<u8> {
    (0..blocks).flat_map(|_| etc1_block(rng)).collect()
}

/// `EXT_compressed_ETC1_RGB8_sub_texture`: parts of ETC1 images replaced, in whole blocks and
/// in the partial blocks at the right and top edges, of an image decoded on upload (10×10)
/// and of one whose blocks may be kept (16×16 with its levels); then the errors of parts that
/// are not allowed, for ETC1 and for DXT1, each marked as a colour.
fn etc1_sub_texture(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut rng = Lcg(23);
    new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, ETC1_RGB8_OES, 10, 10, 0, Blob::borrowed(&etc1_blocks(9, &mut rng)))?;
    for [x, y, w, h] in [[0, 0, 4, 4], [4, 4, 6, 6], [8, 8, 2, 2], [8, 0, 2, 4], [0, 0, 0, 0]] {
        let data = etc1_blocks(((w + 3) / 4) * ((h + 3) / 4), &mut rng);
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, x, y, w, h, ETC1_RGB8_OES, Blob::borrowed(&data))?;
    }
    blit(gl, n, [0, 0, 40, 40])?;
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    for (level, size) in [16, 8, 4, 2, 1].into_iter().enumerate() {
        let data = etc1_blocks(((size + 3) / 4) * ((size + 3) / 4), &mut rng);
        gl.glCompressedTexImage2D(TEXTURE_2D, level as i32, ETC1_RGB8_OES, size, size, 0, Blob::borrowed(&data))?;
    }
    for (level, [x, y, w, h]) in
        [(0, [4, 4, 8, 4]), (1, [4, 0, 4, 8]), (2, [0, 0, 4, 4]), (3, [0, 0, 2, 2]), (4, [0, 0, 1, 1])]
    {
        let data = etc1_blocks(((w + 3) / 4) * ((h + 3) / 4), &mut rng);
        gl.glCompressedTexSubImage2D(TEXTURE_2D, level, x, y, w, h, ETC1_RGB8_OES, Blob::borrowed(&data))?;
    }
    blit(gl, n, [42, 0, 16, 16])?;
    blit(gl, n, [42, 18, 8, 8])?;
    blit(gl, n, [52, 18, 4, 4])?;
    let block = etc1_blocks(16, &mut rng);
    let mut i = 0;
    let mut mark = |gl: Gl<'_>| -> R {
        let e = gl.glGetError()?;
        i += 1;
        super::multi_draw::mark_error(gl, i - 1, e)
    };
    for format in [ETC1_RGB8_OES, DXT1_RGB] {
        new_texture(gl, n, NEAREST, NEAREST)?;
        gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 10, 10, 0, Blob::borrowed(&block[..72]))?;
        // Offsets off a block boundary, widths short of the edge, rectangles beyond it.
        for [x, y, w, h] in
            [[2, 0, 4, 4], [0, 2, 4, 4], [0, 0, 3, 4], [4, 0, 5, 4], [8, 8, 4, 4], [0, 0, 12, 12], [-4, 0, 4, 4]]
        {
            let len = (((w + 3) / 4) * ((h + 3) / 4) * 8).clamp(0, 128) as usize;
            gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, x, y, w, h, format, Blob::borrowed(&block[..len]))?;
            mark(gl)?;
        }
        // The wrong size, another compressed format, an undefined level, formats that are not
        // compressed ones (before the level and the offsets are looked at), a bad target.
        let other = if format == DXT1_RGB { ETC1_RGB8_OES } else { DXT1_RGB };
        for (target, level, x, f, len) in [
            (TEXTURE_2D, 0, 0, format, 7),
            (TEXTURE_2D, 0, 0, other, 8),
            (TEXTURE_2D, 1, 0, format, 8),
            (TEXTURE_2D, 0, 0, RGBA, 8),
            (TEXTURE_2D, 0, 0, 0x1234, 8),
            (TEXTURE_2D, -1, 0, 0x1234, 8),
            (TEXTURE_2D, -1, 0, format, 8),
            (TEXTURE_2D, 0, -4, 0x1234, 8),
            (0x1234, 0, 0, 0x1234, 8),
        ] {
            gl.glCompressedTexSubImage2D(target, level, x, 0, 4, 4, f, Blob::borrowed(&block[..len]))?;
            mark(gl)?;
        }
    }
    // An uncompressed image, and the default texture with no image.
    new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    for f in [ETC1_RGB8_OES, RGBA, 0x1234] {
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, f, Blob::borrowed(&block[..8]))?;
        mark(gl)?;
    }
    gl.glBindTexture(TEXTURE_2D, 0)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, ETC1_RGB8_OES, Blob::borrowed(&block[..8]))?;
    mark(gl)
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    let c = |name, run, tol| Case { name, run, tol, expects_error: false };
    vec![
        c("s3tc_textures", s3tc_textures, DEFAULT),
        c("etc1_textures", etc1_textures, DEFAULT),
        c("etc1_sub_texture", etc1_sub_texture, DEFAULT),
    ]
}

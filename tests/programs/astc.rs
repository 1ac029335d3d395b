//! `GL_KHR_texture_compression_astc_ldr`: ASTC images of several footprints, linear and sRGB,
//! from piglit's encoded mip chains (made by ARM's encoder) and from generated blocks of every
//! kind, HDR and reserved ones (the error colour) among them; nearest and filtered, mipmapped,
//! at sizes that are and are not whole blocks, and updated in part; and the errors, as colours.

use super::compressed::Lcg;
use super::multi_draw::mark_all;
use super::textures::{blit, new_texture};
use super::*;

const RGBA_4X4: u32 = 0x93B0;
const RGBA_5X4: u32 = 0x93B1;
const RGBA_6X6: u32 = 0x93B4;
const RGBA_8X8: u32 = 0x93B7;
const RGBA_12X10: u32 = 0x93BC;
const SRGB_OFFSET: u32 = 0x20;

/// Footprints of the piglit images drawn, by their linear format.
const PIGLIT_FORMATS: [(u32, &str); 6] =
    [(RGBA_4X4, "4x4"), (0x93B2, "5x5"), (0x93B3, "6x5"), (0x93B6, "8x6"), (0x93BA, "10x8"), (0x93BD, "12x12")];

/// piglit's ASTC images, as Debian's piglit package installs them.
const PIGLIT_DIR: &str = "/usr/lib/x86_64-linux-gnu/piglit/tests/spec/khr_texture_compression_astc/compressed/2D";

/// The levels of a little-endian KTX 1 file of one 2D image: level-0 width and height, and
/// each level's bytes.
fn ktx_levels(file: &[u8]) -> Option<(i32, i32, Vec<Vec<u8>>)> {
    let word = |i: usize| Some(u32::from_le_bytes(file.get(12 + 4 * i..16 + 4 * i)?.try_into().ok()?));
    let (width, height, levels, kv) = (word(6)?, word(7)?, word(11)?, word(12)?);
    let mut at = 64 + kv as usize;
    let mut out = Vec::new();
    for _ in 0..levels {
        let size = u32::from_le_bytes(file.get(at..at + 4)?.try_into().ok()?) as usize;
        out.push(file.get(at + 4..at + 4 + size)?.to_vec());
        at += 4 + size.div_ceil(4) * 4;
    }
    Some((width as i32, height as i32, out))
}

/// piglit's waffle image of footprint `dims` (`"ldrl"` linear or `"ldrs"` sRGB), from its
/// fourth level on (20×13 and smaller), or nothing where piglit is not installed.
fn piglit_chain(kind: &str, dims: &str) -> Option<Vec<Vec<u8>>> {
    let Ok(file) = std::fs::read(format!("{PIGLIT_DIR}/{kind}/waffles-{dims}.ktx")) else {
        assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "piglit's ASTC images are missing");
        eprintln!("SKIPPED: piglit's ASTC images are not installed (tools/install-deps installs piglit)");
        return None;
    };
    let (w, h, levels) = ktx_levels(&file).expect("a KTX file");
    assert_eq!((w, h, levels.len()), (160, 106, 8), "piglit's waffle mip chain");
    Some(levels[3..].to_vec())
}

/// piglit's images: each footprint in linear and sRGB form, nearest, 20×13 texels drawn one to
/// a pixel, in a grid of three across and four up.
fn astc_piglit(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut tile = 0;
    for (format, dims) in PIGLIT_FORMATS {
        for (kind, format) in [("ldrl", format), ("ldrs", format + SRGB_OFFSET)] {
            let Some(chain) = piglit_chain(kind, dims) else { return Ok(()) };
            new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
            for (level, data) in chain.iter().enumerate() {
                let (w, h) = ((20 >> level).max(1), (13 >> level).max(1));
                gl.glCompressedTexImage2D(TEXTURE_2D, level as i32, format, w, h, 0, Blob::borrowed(data))?;
            }
            blit(gl, n, [tile % 3 * 20, tile / 3 * 13, 20, 13])?;
            tile += 1;
        }
    }
    // The last image (12×12 sRGB) again, filtered, magnified and minified through its mip chain.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, LINEAR_MIPMAP_LINEAR)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    blit(gl, n, [60, 0, 4, 13])?;
    blit(gl, n, [60, 13, 4, 30])
}

/// A void-extent block: one RGBA colour of 16-bit channels for the whole block, LDR or HDR.
fn void_extent(rng: &mut Lcg, hdr: bool) -> Vec<u8> {
    let mode: u16 = if hdr { 0xFFFC } else { 0xFDFC };
    let mut b = mode.to_le_bytes().to_vec();
    b.extend([0xFF; 6]);
    b.extend(rng.bytes(8));
    b
}

/// `count` blocks from `rng`: a third void-extent colours, one in eight an HDR void extent,
/// the rest random bytes, which are blocks of every mode (most of them reserved ones, which
/// decode to the error colour, as HDR blocks do in the LDR profile).
fn blocks(count: usize, rng: &mut Lcg) -> Vec<u8> {
    (0..count)
        .flat_map(|i| match i % 8 {
            0 | 3 | 6 => void_extent(rng, false),
            5 => void_extent(rng, true),
            _ => rng.bytes(16),
        })
        .collect()
}

/// Generated blocks in four footprints, linear and sRGB, at sizes that are and are not whole
/// blocks; a mipmapped image with a block replaced, including one at the partial edge; a
/// filtered image; and the errors.
fn astc_blocks(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut rng = Lcg(47);
    let mut marks = Vec::new();
    let count = |w: i32, h: i32, bw: i32, bh: i32| ((w + bw - 1) / bw * ((h + bh - 1) / bh)) as usize;
    for (i, (format, bw, bh)) in
        [(RGBA_4X4, 4, 4), (RGBA_5X4, 5, 4), (RGBA_8X8, 8, 8), (RGBA_12X10, 12, 10)].into_iter().enumerate()
    {
        for (j, format) in [format, format + SRGB_OFFSET].into_iter().enumerate() {
            let (x, y) = (i as i32 * 16, j as i32 * 24);
            // A whole-block image (two blocks each way), mipmapped, drawn in 16×16 pixels.
            new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
            let (w, h) = (2 * bw, 2 * bh);
            let mut level = 0;
            while (w >> level) > 0 || (h >> level) > 0 {
                let (lw, lh) = ((w >> level).max(1), (h >> level).max(1));
                let data = blocks(count(lw, lh, bw, bh), &mut rng);
                gl.glCompressedTexImage2D(TEXTURE_2D, level, format, lw, lh, 0, Blob::borrowed(&data))?;
                level += 1;
            }
            // One block replaced, then the partial one at the top-right of level 1.
            let block = blocks(1, &mut rng);
            gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, bw, 0, bw, bh, format, Blob::borrowed(&block))?;
            marks.push(gl.glGetError()?);
            blit(gl, n, [x, y, 16, 16])?;
            blit(gl, n, [x, y + 16, 4, 4])?;
            // A 7×9 image (partial blocks at both edges), filtered.
            new_texture(gl, n, LINEAR, LINEAR)?;
            let data = blocks(count(7, 9, bw, bh), &mut rng);
            gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 7, 9, 0, Blob::borrowed(&data))?;
            marks.push(gl.glGetError()?);
            blit(gl, n, [x + 5, y + 16, 11, 8])?;
        }
    }
    astc_errors(gl, n, &mut rng, &mut marks)?;
    mark_all(gl, &marks)
}

/// The refusals, recorded in `marks`: sizes, rectangles off the block grid, another format's
/// data, uncompressed data and copies for ASTC formats, unknown ASTC-like enums, mipmaps.
fn astc_errors(gl: Gl<'_>, n: &mut Names, rng: &mut Lcg, marks: &mut Vec<u32>) -> R {
    new_texture(gl, n, NEAREST, NEAREST)?;
    let six = RGBA_6X6 + SRGB_OFFSET;
    let data = blocks(9, rng);
    // 13×13 in 6×6 blocks: three blocks each way; the size must match exactly.
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, six, 13, 13, 0, Blob::borrowed(&data[..8 * 16]))?;
    marks.push(gl.glGetError()?);
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, six, 13, 13, 0, Blob::borrowed(&data))?;
    marks.push(gl.glGetError()?);
    let one = blocks(2, rng);
    for (x, y, w, h, format) in [
        (6, 6, 6, 6, six),                    // a whole block
        (4, 0, 6, 6, six),                    // off the grid
        (0, 0, 4, 6, six),                    // part of a block, not at an edge
        (12, 12, 1, 1, six),                  // the partial block at the corner
        (6, 0, 7, 6, six),                    // two blocks reaching the edge
        (0, 0, 6, 6, RGBA_6X6),               // the linear format's data
        (0, 0, 8, 8, RGBA_8X8 + SRGB_OFFSET), // another footprint's
    ] {
        let len = if w > 6 { 32 } else { 16 };
        gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, x, y, w, h, format, Blob::borrowed(&one[..len]))?;
        marks.push(gl.glGetError()?);
    }
    let rgba = vec![90u8; 16 * 16 * 4];
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, RGBA, UNSIGNED_BYTE, Blob::borrowed(&rgba[..64]))?;
    marks.push(gl.glGetError()?);
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 0, 0, 0, 0, 4, 4)?;
    marks.push(gl.glGetError()?);
    gl.glGenerateMipmap(TEXTURE_2D)?;
    marks.push(gl.glGetError()?);
    // The image with its updates, squeezed into the row under the marks.
    blit(gl, n, [0, 48, 64, 4])?;
    new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA_4X4 as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&rgba[..64])))?;
    marks.push(gl.glGetError()?);
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA_4X4, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    // Unknown ASTC-like enums, and ES 3.0's ETC2 and EAC formats, which ES 2.0 lacks.
    for format in [0x93BE, 0x93DE, 0x93CF, 0x9270, 0x9274, 0x9279] {
        gl.glCompressedTexImage2D(TEXTURE_2D, 0, format, 4, 4, 0, Blob::borrowed(&one[..16]))?;
        marks.push(gl.glGetError()?);
    }
    Ok(())
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    // The two decoders may round an interpolated ASTC value differently by one step, which
    // sRGB decoding stretches near white to up to 2.3 steps of the linear output.
    let tol = Tol { max_diff: 3, min_fraction: 0.999 };
    vec![
        Case { name: "astc_piglit", run: astc_piglit, tol, expects_error: false },
        Case { name: "astc_blocks", run: astc_blocks, tol, expects_error: false },
    ]
}

//! Client pixel data to texels: where an upload's rows lie in the client's bytes (the unpack
//! state: `UNPACK_ALIGNMENT`, and `EXT_unpack_subimage`'s row length and skips), and the
//! conversion of every accepted format/type pair to the storage it is kept in (RGBA8, RGBA16F,
//! RGBA32F, normalised depth, depth plus stencil).

use half::f16;

use crate::context::PixelStore;
use crate::enums::*;
use crate::formats::Storage;

/// Where the rows of an upload lie in the client's bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unpack {
    /// `UNPACK_ALIGNMENT`: each row starts at a multiple of this many bytes.
    pub alignment: usize,
    /// `UNPACK_ROW_LENGTH`: pixels per row in memory (0: the image's width).
    pub row_length: usize,
    /// `UNPACK_SKIP_ROWS`: rows skipped before the first.
    pub skip_rows: usize,
    /// `UNPACK_SKIP_PIXELS`: pixels skipped at the start of every row.
    pub skip_pixels: usize,
}

impl Unpack {
    /// The unpack state of a context's pixel store.
    pub fn of(store: &PixelStore) -> Self {
        Unpack {
            alignment: store.unpack_alignment.max(1) as usize,
            row_length: store.unpack_row_length.max(0) as usize,
            skip_rows: store.unpack_skip_rows.max(0) as usize,
            skip_pixels: store.unpack_skip_pixels.max(0) as usize,
        }
    }

    /// Tightly packed rows with the given alignment and no skips.
    #[cfg(test)]
    pub fn aligned(alignment: usize) -> Self {
        Unpack { alignment, row_length: 0, skip_rows: 0, skip_pixels: 0 }
    }

    /// The rows of a `width`×`height` image of `bpp`-byte pixels in `src`, each `width * bpp`
    /// bytes, or `None` if `src` is too short.
    pub fn rows<'a>(&self, src: &'a [u8], width: usize, height: usize, bpp: usize) -> Option<Vec<&'a [u8]>> {
        if width == 0 || height == 0 {
            return Some(Vec::new());
        }
        let pixels = if self.row_length > 0 { self.row_length } else { width };
        let stride = pixels.checked_mul(bpp)?.div_ceil(self.alignment) * self.alignment;
        let start = self.skip_rows.checked_mul(stride)?.checked_add(self.skip_pixels.checked_mul(bpp)?)?;
        let end = start.checked_add((height - 1).checked_mul(stride)?)?.checked_add(width * bpp)?;
        if src.len() < end {
            return None;
        }
        Some((0..height).map(|y| &src[start + y * stride..][..width * bpp]).collect())
    }
}

/// Components per pixel of a colour format.
fn components(format: u32) -> usize {
    match format {
        _ if crate::integer::is_integer_format(format) => crate::integer::components(format),
        RGBA | BGRA_EXT => 4,
        RGB => 3,
        LUMINANCE_ALPHA | RG_EXT => 2,
        _ => 1,
    }
}

/// Bytes per pixel of client data in `format`/`ty` (a pair `formats::upload_storage` accepts).
pub fn bytes_per_pixel(format: u32, ty: u32) -> usize {
    match ty {
        UNSIGNED_SHORT_5_6_5 | UNSIGNED_SHORT_4_4_4_4 | UNSIGNED_SHORT_5_5_5_1 => 2,
        UNSIGNED_INT_24_8_OES | UNSIGNED_INT_2_10_10_10_REV_EXT => 4,
        t if crate::packed_float::is_packed_float_type(t) => 4,
        // Depth, and ES 3.0's integer data.
        UNSIGNED_SHORT | SHORT => 2 * components(format),
        UNSIGNED_INT | INT => 4 * components(format),
        FLOAT => 4 * components(format),
        HALF_FLOAT_OES => 2 * components(format),
        _ => components(format),
    }
}

/// An n-bit unsigned value scaled to 8 bits, rounded to nearest.
fn expand(v: u16, bits: u32) -> u8 {
    let max = (1u32 << bits) - 1;
    ((u32::from(v) * 255 + max / 2) / max) as u8
}

/// One pixel of 8-bit or packed 16-bit data as RGBA8.
fn rgba8_pixel(px: &[u8], format: u32, ty: u32) -> [u8; 4] {
    match (format, ty) {
        (RGBA, UNSIGNED_BYTE) => [px[0], px[1], px[2], px[3]],
        (BGRA_EXT, UNSIGNED_BYTE) => [px[2], px[1], px[0], px[3]],
        (RGB, UNSIGNED_BYTE) => [px[0], px[1], px[2], 255],
        (LUMINANCE_ALPHA, UNSIGNED_BYTE) => [px[0], px[0], px[0], px[1]],
        (LUMINANCE, UNSIGNED_BYTE) => [px[0], px[0], px[0], 255],
        (ALPHA, UNSIGNED_BYTE) => [0, 0, 0, px[0]],
        (RED_EXT, UNSIGNED_BYTE) => [px[0], 0, 0, 255],
        (RG_EXT, UNSIGNED_BYTE) => [px[0], px[1], 0, 255],
        (_, t) => {
            let v = u16::from_ne_bytes([px[0], px[1]]);
            match t {
                UNSIGNED_SHORT_5_6_5 => [expand(v >> 11, 5), expand((v >> 5) & 63, 6), expand(v & 31, 5), 255],
                UNSIGNED_SHORT_4_4_4_4 => {
                    [expand(v >> 12, 4), expand((v >> 8) & 15, 4), expand((v >> 4) & 15, 4), expand(v & 15, 4)]
                }
                _ => [expand(v >> 11, 5), expand((v >> 6) & 31, 5), expand((v >> 1) & 31, 5), expand(v & 1, 1)],
            }
        }
    }
}

/// One pixel of `FLOAT`, `HALF_FLOAT_OES`, `UNSIGNED_INT_2_10_10_10_REV_EXT` or (signed
/// normalized) `BYTE` data as RGBA
/// floats (GL's expansion of each format: luminance to R, G and B, missing colour 0, missing
/// alpha 1).
fn float_pixel(px: &[u8], format: u32, ty: u32) -> [f32; 4] {
    let c = |i: usize| {
        if ty == BYTE {
            // ES 3.0's signed normalized conversion: c / 127, -128 clamped to -1.
            (f32::from(px[i] as i8) / 127.0).max(-1.0)
        } else if ty == FLOAT {
            f32::from_ne_bytes([px[4 * i], px[4 * i + 1], px[4 * i + 2], px[4 * i + 3]])
        } else {
            f16::from_bits(u16::from_ne_bytes([px[2 * i], px[2 * i + 1]])).to_f32()
        }
    };
    if crate::packed_float::is_packed_float_type(ty) {
        let v = u32::from_ne_bytes([px[0], px[1], px[2], px[3]]);
        let [r, g, b] = match ty {
            crate::packed_float::UNSIGNED_INT_10F_11F_11F_REV => crate::packed_float::decode_11_11_10(v),
            _ => crate::packed_float::decode_rgb9e5(v),
        };
        return [r, g, b, 1.0];
    }
    if ty == UNSIGNED_INT_2_10_10_10_REV_EXT {
        // Red in the low 10 bits, then green and blue, alpha in the top 2; RGB ignores alpha.
        let v = u32::from_ne_bytes([px[0], px[1], px[2], px[3]]);
        let unorm = |shift: u32, bits: u32| ((v >> shift) & ((1 << bits) - 1)) as f32 / ((1 << bits) - 1) as f32;
        let alpha = if format == RGB { 1.0 } else { unorm(30, 2) };
        return [unorm(0, 10), unorm(10, 10), unorm(20, 10), alpha];
    }
    match format {
        RGBA => [c(0), c(1), c(2), c(3)],
        RGB => [c(0), c(1), c(2), 1.0],
        LUMINANCE_ALPHA => [c(0), c(0), c(0), c(1)],
        LUMINANCE => [c(0), c(0), c(0), 1.0],
        RED_EXT => [c(0), 0.0, 0.0, 1.0],
        RG_EXT => [c(0), c(1), 0.0, 1.0],
        _ => [0.0, 0.0, 0.0, c(0)],
    }
}

/// Converts a colour upload to tightly packed texels of `storage` (`Rgba8`, `Half` or
/// `Float`), or `None` if `src` is too short.
#[cfg(test)]
pub fn to_storage(
    src: &[u8],
    width: usize,
    height: usize,
    format: u32,
    ty: u32,
    unpack: Unpack,
    storage: Storage,
) -> Option<Vec<u8>> {
    to_storage_rounded(src, width, height, (format, ty), unpack, storage, None)
}

/// [`to_storage`], float colour first rounded by `round` where given (the precision of a
/// packed float format, `packed_float::rounding`).
pub fn to_storage_rounded(
    src: &[u8],
    width: usize,
    height: usize,
    (format, ty): (u32, u32),
    unpack: Unpack,
    storage: Storage,
    round: Option<fn([f32; 3]) -> [f32; 3]>,
) -> Option<Vec<u8>> {
    let pixel = |px: &[u8]| {
        let [r, g, b, a] = float_pixel(px, format, ty);
        let [r, g, b] = round.map_or([r, g, b], |f| f([r, g, b]));
        [r, g, b, a]
    };
    let bpp = bytes_per_pixel(format, ty);
    let rows = unpack.rows(src, width, height, bpp)?;
    let mut out = Vec::with_capacity(width * height * storage.texel_bytes() as usize);
    let float_input = matches!(ty, FLOAT | HALF_FLOAT_OES | UNSIGNED_INT_2_10_10_10_REV_EXT)
        || crate::packed_float::is_packed_float_type(ty);
    for row in rows {
        for px in row.chunks_exact(bpp) {
            match storage {
                Storage::Int { bits, .. } => crate::integer::push_texel(px, format, ty, bits, &mut out),
                Storage::Float => pixel(px).iter().for_each(|v| out.extend_from_slice(&v.to_ne_bytes())),
                Storage::Half => {
                    pixel(px).iter().for_each(|v| out.extend_from_slice(&f16::from_f32(*v).to_bits().to_ne_bytes()))
                }
                Storage::Rgb10a2 => out.extend_from_slice(&pack_rgb10a2(pixel(px)).to_ne_bytes()),
                // Packed data as it came (its denormals too); other data cut to it.
                Storage::Rg11b10 if ty == crate::packed_float::UNSIGNED_INT_10F_11F_11F_REV => {
                    out.extend_from_slice(&px[..4])
                }
                Storage::Rg11b10 => {
                    let [r, g, b, _] = pixel(px);
                    out.extend_from_slice(&crate::packed_float::encode_11_11_10([r, g, b]).to_ne_bytes())
                }
                _ if float_input => {
                    out.extend(float_pixel(px, format, ty).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
                }
                _ => out.extend_from_slice(&rgba8_pixel(px, format, ty)),
            }
        }
    }
    Some(out)
}

/// RGBA as one `UNSIGNED_INT_2_10_10_10_REV` value (red in the low 10 bits, alpha in the top
/// 2), each channel clamped to [0, 1] and rounded to its bits.
pub fn pack_rgb10a2([r, g, b, a]: [f32; 4]) -> u32 {
    let n = |v: f32, bits: u32| {
        let max = ((1u32 << bits) - 1) as f32;
        (if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) } * max).round() as u32
    };
    n(r, 10) | n(g, 10) << 10 | n(b, 10) << 20 | n(a, 2) << 30
}

/// Converts a `DEPTH_COMPONENT` upload of `UNSIGNED_SHORT` or `UNSIGNED_INT` values, or a
/// `DEPTH_STENCIL_OES` upload of `UNSIGNED_INT_24_8_OES` values, to normalised depths and
/// stencil values; `None` if `src` is too short.
pub fn depth_stencil_values(
    src: &[u8],
    width: usize,
    height: usize,
    ty: u32,
    unpack: Unpack,
) -> Option<(Vec<f32>, Vec<u8>)> {
    let bpp = match ty {
        UNSIGNED_SHORT => 2,
        FLOAT_32_UNSIGNED_INT_24_8_REV => 8,
        _ => 4,
    };
    let rows = unpack.rows(src, width, height, bpp)?;
    let mut depth = Vec::with_capacity(width * height);
    let mut stencil = Vec::new();
    for px in rows.iter().flat_map(|r| r.chunks_exact(bpp)) {
        match ty {
            UNSIGNED_SHORT => depth.push(f32::from(u16::from_ne_bytes([px[0], px[1]])) / 65535.0),
            UNSIGNED_INT => {
                let v = u32::from_ne_bytes([px[0], px[1], px[2], px[3]]);
                depth.push((f64::from(v) / f64::from(u32::MAX)) as f32);
            }
            // ES 3.0's float depths, clamped to [0, 1]; with stencil, the stencil in the low 8
            // bits of the second word.
            FLOAT | FLOAT_32_UNSIGNED_INT_24_8_REV => {
                let d = f32::from_ne_bytes([px[0], px[1], px[2], px[3]]);
                depth.push(if d.is_nan() { 0.0 } else { d.clamp(0.0, 1.0) });
                if ty == FLOAT_32_UNSIGNED_INT_24_8_REV {
                    stencil.push(u32::from_ne_bytes([px[4], px[5], px[6], px[7]]) as u8);
                }
            }
            _ => {
                // Depth in the high 24 bits, stencil in the low 8.
                let v = u32::from_ne_bytes([px[0], px[1], px[2], px[3]]);
                depth.push((f64::from(v >> 8) / f64::from(0xFF_FFFFu32)) as f32);
                stencil.push(v as u8);
            }
        }
    }
    Some((depth, stencil))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rgba8(src: &[u8], w: usize, h: usize, format: u32, ty: u32, unpack: Unpack) -> Option<Vec<u8>> {
        to_storage(src, w, h, format, ty, unpack, Storage::Rgba8)
    }

    #[test]
    fn uploads_convert_to_rgba8() {
        let a4 = Unpack::aligned(4);
        // 3x1 RGB with alignment 4: one 9-byte row.
        let rgb = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        assert_eq!(rgba8(&rgb, 3, 1, RGB, UNSIGNED_BYTE, a4).expect("rgb").len(), 12);
        // 1x2 LUMINANCE with alignment 4: rows are padded to 4 bytes.
        let l = [10, 0, 0, 0, 20];
        assert_eq!(rgba8(&l, 1, 2, LUMINANCE, UNSIGNED_BYTE, a4).expect("lum"), vec![10, 10, 10, 255, 20, 20, 20, 255]);
        let white565 = 0xFFFFu16.to_ne_bytes();
        assert_eq!(rgba8(&white565, 1, 1, RGB, UNSIGNED_SHORT_5_6_5, Unpack::aligned(1)).expect("565"), vec![255; 4]);
        let red4444 = 0xF00Fu16.to_ne_bytes();
        assert_eq!(
            rgba8(&red4444, 1, 1, RGBA, UNSIGNED_SHORT_4_4_4_4, Unpack::aligned(1)).expect("4444"),
            vec![255, 0, 0, 255]
        );
        assert_eq!(rgba8(&[1, 2, 3, 4], 1, 1, BGRA_EXT, UNSIGNED_BYTE, a4).expect("bgra"), vec![3, 2, 1, 4]);
        assert!(rgba8(&rgb[..5], 3, 1, RGB, UNSIGNED_BYTE, a4).is_none(), "short data");
    }

    #[test]
    fn row_length_and_skips_select_a_sub_rectangle() {
        // A 4x3 RGBA image; take the 2x2 rectangle at (1, 1).
        let img: Vec<u8> = (0..48).collect();
        let unpack = Unpack { alignment: 4, row_length: 4, skip_rows: 1, skip_pixels: 1 };
        let sub = rgba8(&img, 2, 2, RGBA, UNSIGNED_BYTE, unpack).expect("sub");
        let want: Vec<u8> = [20, 24, 36, 40].iter().flat_map(|&p| p..p + 4).collect();
        assert_eq!(sub, want);
        // One byte less than the last pixel read is too short.
        assert!(rgba8(&img[..43], 2, 2, RGBA, UNSIGNED_BYTE, unpack).is_none());
    }

    #[test]
    fn float_formats_expand_like_gl() {
        let f = |v: &[f32]| v.iter().flat_map(|x| x.to_ne_bytes()).collect::<Vec<u8>>();
        let floats = |b: Vec<u8>| b.chunks(4).map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]])).collect::<Vec<_>>();
        let a1 = Unpack::aligned(1);
        let la = to_storage(&f(&[-3.5, 700.0]), 1, 1, LUMINANCE_ALPHA, FLOAT, a1, Storage::Float).expect("la");
        assert_eq!(floats(la), [-3.5, -3.5, -3.5, 700.0]);
        let a = to_storage(&f(&[2.0]), 1, 1, ALPHA, FLOAT, a1, Storage::Float).expect("a");
        assert_eq!(floats(a), [0.0, 0.0, 0.0, 2.0]);
        let one = f16::from_f32(1.0).to_bits().to_ne_bytes();
        let half = to_storage(&one, 1, 1, LUMINANCE, HALF_FLOAT_OES, a1, Storage::Half).expect("half");
        assert_eq!(half, [one, one, one, one].concat());
        // Float data into RGBA8 (an S3TC internal format) is clamped and rounded.
        let c = to_storage(&f(&[2.0, -1.0, 0.5, 1.0]), 1, 1, RGBA, FLOAT, a1, Storage::Rgba8).expect("rgba8");
        assert_eq!(c, [255, 0, 128, 255]);
    }

    #[test]
    fn packed_depth_stencil_splits_24_and_8_bits() {
        let v = ((0xFF_FFFFu32 << 8) | 0x5A).to_ne_bytes();
        let (d, s) = depth_stencil_values(&v, 1, 1, UNSIGNED_INT_24_8_OES, Unpack::aligned(4)).expect("ds");
        assert_eq!((d, s), (vec![1.0], vec![0x5A]));
        let (d, s) =
            depth_stencil_values(&0x8000u16.to_ne_bytes(), 1, 1, UNSIGNED_SHORT, Unpack::aligned(2)).expect("d");
        assert!((d[0] - 0.500_007_6).abs() < 1e-6 && s.is_empty());
    }
}

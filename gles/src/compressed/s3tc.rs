//! S3TC (DXT1, DXT3, DXT5) blocks decoded to RGBA8, as `EXT_texture_compression_s3tc` defines
//! them: 4×4 texels per block, the colour block two RGB565 endpoints and 2-bit codes, DXT3 an
//! explicit 4-bit alpha per texel, DXT5 two alpha endpoints and 3-bit codes. All multi-byte
//! fields are little-endian; texel (x, y) is code number `4 * y + x`.

/// Which of the four S3TC formats a block belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum S3tc {
    /// `COMPRESSED_RGB_S3TC_DXT1_EXT`: the "transparent" code decodes to opaque black.
    Dxt1Rgb,
    /// `COMPRESSED_RGBA_S3TC_DXT1_EXT`: the "transparent" code decodes to (0, 0, 0, 0).
    Dxt1Rgba,
    /// `COMPRESSED_RGBA_S3TC_DXT3_EXT`.
    Dxt3,
    /// `COMPRESSED_RGBA_S3TC_DXT5_EXT`.
    Dxt5,
}

impl S3tc {
    /// Bytes per 4×4 block.
    pub fn block_bytes(self) -> usize {
        match self {
            S3tc::Dxt1Rgb | S3tc::Dxt1Rgba => 8,
            S3tc::Dxt3 | S3tc::Dxt5 => 16,
        }
    }
}

/// A 5- or 6-bit endpoint channel widened to 8 bits by replicating its high bits, as block
/// decoders in hardware (and Mesa's) do; it is within one step of `v * 255 / max`.
fn widen(v: u32, bits: u32) -> u32 {
    (v << (8 - bits)) | (v >> (2 * bits - 8))
}

/// `(a * wa + b * wb) / (wa + wb)`, rounded to nearest.
fn mix(a: u32, wa: u32, b: u32, wb: u32) -> u8 {
    let d = wa + wb;
    ((a * wa + b * wb + d / 2) / d) as u8
}

/// The colour half of a block: the RGBA8 texels in row order. `four_colour` forces the
/// four-colour mode (DXT3/DXT5); `transparent_alpha` is the alpha of the fourth code in
/// three-colour mode.
fn colour_block(b: &[u8], four_colour: bool, transparent_alpha: u8) -> [[u8; 4]; 16] {
    let c0 = u16::from_le_bytes([b[0], b[1]]);
    let c1 = u16::from_le_bytes([b[2], b[3]]);
    let rgb = |c: u16| {
        let c = u32::from(c);
        [widen(c >> 11, 5), widen((c >> 5) & 63, 6), widen(c & 31, 5)]
    };
    let (e0, e1) = (rgb(c0), rgb(c1));
    let mut palette = [[0u8; 4]; 4];
    for i in 0..3 {
        palette[0][i] = e0[i] as u8;
        palette[1][i] = e1[i] as u8;
        if four_colour || c0 > c1 {
            palette[2][i] = mix(e0[i], 2, e1[i], 1);
            palette[3][i] = mix(e0[i], 1, e1[i], 2);
        } else {
            palette[2][i] = mix(e0[i], 1, e1[i], 1);
            palette[3][i] = 0;
        }
    }
    palette[0][3] = 255;
    palette[1][3] = 255;
    palette[2][3] = 255;
    palette[3][3] = if four_colour || c0 > c1 { 255 } else { transparent_alpha };
    let codes = u32::from_le_bytes([b[4], b[5], b[6], b[7]]);
    std::array::from_fn(|t| palette[((codes >> (2 * t)) & 3) as usize])
}

/// The 16 alphas of a DXT5 alpha block.
fn dxt5_alpha(b: &[u8]) -> [u8; 16] {
    let (a0, a1) = (u32::from(b[0]), u32::from(b[1]));
    let mut bits = 0u64;
    for (i, &x) in b[2..8].iter().enumerate() {
        bits |= u64::from(x) << (8 * i);
    }
    std::array::from_fn(|t| {
        let code = ((bits >> (3 * t)) & 7) as u32;
        match code {
            0 => a0 as u8,
            1 => a1 as u8,
            c if a0 > a1 => mix(a0, 8 - c, a1, c - 1),
            6 => 0,
            7 => 255,
            c => mix(a0, 6 - c, a1, c - 1),
        }
    })
}

/// Decodes one block into its 16 RGBA8 texels, in row order (texel `4 * y + x`).
pub fn decode_block(kind: S3tc, b: &[u8]) -> [[u8; 4]; 16] {
    match kind {
        S3tc::Dxt1Rgb => colour_block(b, false, 255),
        S3tc::Dxt1Rgba => colour_block(b, false, 0),
        S3tc::Dxt3 => {
            let mut px = colour_block(&b[8..], true, 255);
            for (t, p) in px.iter_mut().enumerate() {
                let nibble = (b[t / 2] >> (4 * (t % 2))) & 15;
                p[3] = nibble * 17;
            }
            px
        }
        S3tc::Dxt5 => {
            let mut px = colour_block(&b[8..], true, 255);
            for (p, a) in px.iter_mut().zip(dxt5_alpha(b)) {
                p[3] = a;
            }
            px
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A colour block from its endpoints and 16 codes (texel `4 * y + x` first).
    fn block(c0: u16, c1: u16, codes: [u32; 16]) -> Vec<u8> {
        let bits = codes.iter().enumerate().fold(0u32, |b, (i, &c)| b | (c << (2 * i)));
        [c0.to_le_bytes(), c1.to_le_bytes()].concat().into_iter().chain(bits.to_le_bytes()).collect()
    }

    // Expected values below are worked out by hand from the extension's formulas.
    #[test]
    fn dxt1_four_colour_mode_interpolates_thirds() {
        // Red (0xF800) and blue (0x001F); codes 0, 1, 2, 3 along the first row.
        let mut codes = [0; 16];
        codes[..4].copy_from_slice(&[0, 1, 2, 3]);
        let px = decode_block(S3tc::Dxt1Rgb, &block(0xF800, 0x001F, codes));
        assert_eq!(px[0], [255, 0, 0, 255]);
        assert_eq!(px[1], [0, 0, 255, 255]);
        assert_eq!(px[2], [170, 0, 85, 255]); // (2·255 + 0)/3, (0 + 255)/3
        assert_eq!(px[3], [85, 0, 170, 255]);
        assert_eq!(px[15], [255, 0, 0, 255]);
    }

    #[test]
    fn dxt1_three_colour_mode_and_transparency() {
        // c0 <= c1: code 2 is the midpoint, code 3 black (transparent in the RGBA variant).
        let mut codes = [3; 16];
        codes[0] = 2;
        let b = block(0x0000, 0xFFFF, codes);
        let rgb = decode_block(S3tc::Dxt1Rgb, &b);
        let rgba = decode_block(S3tc::Dxt1Rgba, &b);
        assert_eq!(rgb[0], [128, 128, 128, 255]); // (0 + 255)/2 rounded
        assert_eq!(rgb[5], [0, 0, 0, 255]);
        assert_eq!(rgba[5], [0, 0, 0, 0]);
    }

    #[test]
    fn dxt3_alpha_is_explicit_per_texel() {
        let mut b = vec![0u8; 8];
        b[0] = 0xF0; // texel 0: 0, texel 1: 15
        b[7] = 0x8F; // texel 14: 15, texel 15: 8
                     // DXT3's colour block always uses four-colour mode, even with c0 <= c1.
        b.extend(block(0x0000, 0xFFFF, [3; 16]));
        let px = decode_block(S3tc::Dxt3, &b);
        assert_eq!(px[0][3], 0);
        assert_eq!(px[1][3], 255);
        assert_eq!(px[14][3], 255);
        assert_eq!(px[15][3], 136);
        assert_eq!(px[0][..3], [170, 170, 170]); // (0 + 2·255)/3
    }

    #[test]
    fn dxt5_alpha_eight_and_six_step_modes() {
        let alpha = |a0: u8, a1: u8, codes: [u64; 16]| {
            let bits = codes.iter().enumerate().fold(0u64, |b, (i, &c)| b | (c << (3 * i)));
            let mut b = vec![a0, a1];
            b.extend_from_slice(&bits.to_le_bytes()[..6]);
            b.extend(block(0, 0, [0; 16]));
            decode_block(S3tc::Dxt5, &b).map(|p| p[3])
        };
        let codes = [0, 1, 2, 3, 4, 5, 6, 7, 0, 0, 0, 0, 0, 0, 0, 7];
        // a0 > a1: six interpolated steps of (a0 - a1) / 7.
        assert_eq!(alpha(210, 0, codes)[..8], [210, 0, 180, 150, 120, 90, 60, 30]);
        assert_eq!(alpha(210, 0, codes)[15], 30);
        // a0 <= a1: four steps of (a1 - a0) / 5, then 0 and 255.
        assert_eq!(alpha(0, 200, codes)[..8], [0, 200, 40, 80, 120, 160, 0, 255]);
    }
}

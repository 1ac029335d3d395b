//! ES 3.0's ETC2 and EAC formats (all ten of the specification's table 3.19): 4×4 blocks of
//! 8 bytes (`R11_EAC`, `RGB8_ETC2` and its punch-through alpha form) or 16 (`RG11_EAC`,
//! `RGBA8_ETC2_EAC`). Where the device lacks them, the colour formats are decoded here to
//! RGBA8 with the `texture2ddecoder` crate (T, H and planar modes included), and the EAC
//! formats by hand to float, keeping all 11 bits of each value (the crate keeps 8).

/// One ETC2 or EAC format, its sRGB form aside.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Etc2 {
    /// `COMPRESSED_R11_EAC`: one unsigned normalized channel.
    R11,
    /// `COMPRESSED_SIGNED_R11_EAC`: one signed normalized channel.
    SignedR11,
    /// `COMPRESSED_RG11_EAC`: two unsigned normalized channels.
    Rg11,
    /// `COMPRESSED_SIGNED_RG11_EAC`: two signed normalized channels.
    SignedRg11,
    /// `COMPRESSED_RGB8_ETC2` (and `SRGB8_ETC2`): opaque colour.
    Rgb8,
    /// `COMPRESSED_RGB8_PUNCHTHROUGH_ALPHA1_ETC2` (and its sRGB form): colour, each texel opaque
    /// or transparent black.
    Rgb8A1,
    /// `COMPRESSED_RGBA8_ETC2_EAC` (and `SRGB8_ALPHA8_ETC2_EAC`): colour and an EAC alpha.
    Rgba8,
}

/// `GL_COMPRESSED_R11_EAC`, the first of the ten enums; the others follow it in
/// [`ALL`]'s order.
const FIRST: u32 = 0x9270;

/// The formats in the order of their enums (0x9270…0x9279), and whether each is sRGB.
const ALL: [(Etc2, bool); 10] = [
    (Etc2::R11, false),
    (Etc2::SignedR11, false),
    (Etc2::Rg11, false),
    (Etc2::SignedRg11, false),
    (Etc2::Rgb8, false),
    (Etc2::Rgb8, true),
    (Etc2::Rgb8A1, false),
    (Etc2::Rgb8A1, true),
    (Etc2::Rgba8, false),
    (Etc2::Rgba8, true),
];

/// EAC's sixteen modifier tables (the specification's table C.12), by the block's table index.
const EAC_MODIFIERS: [[i32; 8]; 16] = [
    [-3, -6, -9, -15, 2, 5, 8, 14],
    [-3, -7, -10, -13, 2, 6, 9, 12],
    [-2, -5, -8, -13, 1, 4, 7, 12],
    [-2, -4, -6, -13, 1, 3, 5, 12],
    [-3, -6, -8, -12, 2, 5, 7, 11],
    [-3, -7, -9, -11, 2, 6, 8, 10],
    [-4, -7, -8, -11, 3, 6, 7, 10],
    [-3, -5, -8, -11, 2, 4, 7, 10],
    [-2, -6, -8, -10, 1, 5, 7, 9],
    [-2, -5, -8, -10, 1, 4, 7, 9],
    [-2, -4, -8, -10, 1, 3, 7, 9],
    [-2, -5, -7, -10, 1, 4, 6, 9],
    [-3, -4, -7, -10, 2, 3, 6, 9],
    [-1, -2, -3, -10, 0, 1, 2, 9],
    [-4, -6, -8, -9, 3, 5, 7, 8],
    [-3, -5, -7, -9, 2, 4, 6, 8],
];

impl Etc2 {
    /// The format `f` names, and whether it is an sRGB one.
    pub fn from_gl(f: u32) -> Option<(Etc2, bool)> {
        ALL.get(f.checked_sub(FIRST)? as usize).copied()
    }

    /// Every format enum, in the order `GL_COMPRESSED_TEXTURE_FORMATS` lists them.
    pub fn all_gl() -> impl Iterator<Item = u32> {
        FIRST..FIRST + ALL.len() as u32
    }

    /// Bytes per 4×4 block.
    pub fn block_bytes(self) -> usize {
        match self {
            Etc2::Rg11 | Etc2::SignedRg11 | Etc2::Rgba8 => 16,
            _ => 8,
        }
    }

    /// An EAC format: decoded to float, not to RGBA8.
    pub fn is_eac(self) -> bool {
        matches!(self, Etc2::R11 | Etc2::SignedR11 | Etc2::Rg11 | Etc2::SignedRg11)
    }

    /// wgpu's block format of this format, read as linear or (for sRGB) decoded from sRGB.
    pub fn native(self, srgb: bool) -> wgpu::TextureFormat {
        use wgpu::TextureFormat as F;
        match (self, srgb) {
            (Etc2::R11, _) => F::EacR11Unorm,
            (Etc2::SignedR11, _) => F::EacR11Snorm,
            (Etc2::Rg11, _) => F::EacRg11Unorm,
            (Etc2::SignedRg11, _) => F::EacRg11Snorm,
            (Etc2::Rgb8, false) => F::Etc2Rgb8Unorm,
            (Etc2::Rgb8, true) => F::Etc2Rgb8UnormSrgb,
            (Etc2::Rgb8A1, false) => F::Etc2Rgb8A1Unorm,
            (Etc2::Rgb8A1, true) => F::Etc2Rgb8A1UnormSrgb,
            (Etc2::Rgba8, false) => F::Etc2Rgba8Unorm,
            (Etc2::Rgba8, true) => F::Etc2Rgba8UnormSrgb,
        }
    }

    /// Decodes one colour block to its 16 texels as RGBA8, row by row; an EAC block gives its
    /// values rounded to 8 bits ([`Self::decode_eac_block`] keeps them all). sRGB blocks give
    /// sRGB-encoded colour.
    pub fn decode_block(self, block: &[u8]) -> [[u8; 4]; 16] {
        if self.is_eac() {
            return self.decode_eac_block(block).map(|t| t.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8));
        }
        let mut packed = [0u32; 16];
        match self {
            Etc2::Rgb8 => texture2ddecoder::decode_etc2_rgb_block(block, &mut packed),
            Etc2::Rgb8A1 => texture2ddecoder::decode_etc2_rgba1_block(block, &mut packed),
            _ => texture2ddecoder::decode_etc2_rgba8_block(block, &mut packed),
        }
        // The crate packs each texel as the little-endian bytes B, G, R, A, and keeps the colour
        // of a punch-through texel, which the specification makes transparent black.
        let punch_through = self == Etc2::Rgb8A1;
        packed.map(|p| match p.to_le_bytes() {
            [_, _, _, 0] if punch_through => [0; 4],
            [b, g, r, a] => [r, g, b, a],
        })
    }

    /// Decodes one EAC block to its 16 texels, row by row, as RGBA floats: red (and green)
    /// normalized from their 11 bits, blue 0 and alpha 1.
    pub fn decode_eac_block(self, block: &[u8]) -> [[f32; 4]; 16] {
        let signed = matches!(self, Etc2::SignedR11 | Etc2::SignedRg11);
        let red = eac_channel(&block[..8], signed);
        let green = if block.len() >= 16 && matches!(self, Etc2::Rg11 | Etc2::SignedRg11) {
            eac_channel(&block[8..16], signed)
        } else {
            [0.0; 16]
        };
        std::array::from_fn(|t| [red[t], green[t], 0.0, 1.0])
    }
}

/// One 8-byte EAC channel block's 16 values, row by row: a base codeword, a multiplier and a
/// modifier table, and a 3-bit modifier index per texel (texel `4 * x + y` at bits 45 down).
fn eac_channel(b: &[u8], signed: bool) -> [f32; 16] {
    let word = u64::from_be_bytes(std::array::from_fn(|i| b.get(i).copied().unwrap_or(0)));
    let multiplier = i32::from(b[1] >> 4);
    let table = &EAC_MODIFIERS[usize::from(b[1] & 0xF)];
    std::array::from_fn(|t| {
        let (x, y) = (t % 4, t / 4);
        let index = ((word >> (45 - 3 * (4 * x + y))) & 7) as usize;
        // A zero multiplier scales the modifier by 1/8 of the usual 8.
        let step = if multiplier == 0 { table[index] } else { table[index] * multiplier * 8 };
        if signed {
            // The base is a signed byte whose -128 reads as -127.
            let base = i32::from(b[0] as i8).max(-127);
            (base * 8 + step).clamp(-1023, 1023) as f32 / 1023.0
        } else {
            (i32::from(b[0]) * 8 + 4 + step).clamp(0, 2047) as f32 / 2047.0
        }
    })
}

#[cfg(test)]
mod tests {
    use super::super::tests::ktx_levels;
    use crate::formats::Compressed;

    /// An EAC block of base `base`, multiplier `mult`, modifier table `table` and every
    /// texel's modifier index `index`.
    fn eac_block(base: u8, mult: u8, table: u8, index: u64) -> [u8; 8] {
        let indices = (0..16).fold(0u64, |w, _| (w << 3) | index);
        let mut b = indices.to_be_bytes();
        b[0] = base;
        b[1] = (mult << 4) | table;
        b
    }

    /// The arithmetic of the specification's EAC equations, below what an 8-bit image shows:
    /// an unsigned value is offset by half a step (`base * 8 + 4`) and clamped to 2047, a zero
    /// multiplier scales the modifier by 1, a signed base of -128 reads as -127 and a signed
    /// value is clamped to ±1023.
    #[test]
    fn eac_values_follow_the_specification() {
        let r11 = |b: [u8; 8]| super::eac_channel(&b, false)[5] * 2047.0;
        let s11 = |b: [u8; 8]| super::eac_channel(&b, true)[5] * 1023.0;
        // Table 13's modifier 4 is 0, its modifier 0 is -1, its modifier 7 is 9.
        assert_eq!(r11(eac_block(0, 0, 13, 4)), 4.0);
        assert_eq!(r11(eac_block(10, 0, 13, 7)), 93.0);
        assert_eq!(r11(eac_block(10, 2, 13, 7)), 80.0 + 4.0 + 9.0 * 16.0);
        assert_eq!(r11(eac_block(255, 15, 0, 7)), 2047.0);
        assert_eq!(r11(eac_block(0, 15, 0, 3)), 0.0);
        assert_eq!(s11(eac_block(0x80, 0, 13, 4)), -1016.0);
        assert_eq!(s11(eac_block(0x81, 0, 13, 0)), -1017.0);
        assert_eq!(s11(eac_block(0x81, 15, 0, 3)), -1023.0);
        assert_eq!(s11(eac_block(127, 15, 0, 7)), 1023.0);
        assert_eq!(s11(eac_block(5, 1, 13, 7)), 40.0 + 72.0);
    }

    /// piglit's ETC2 and EAC mip chains (all but the signed EAC formats) and their decompressed
    /// RGBA8 references (made by an independent decoder), as Debian's piglit package installs
    /// them: the colour formats decode exactly, EAC within one step of 8 bits (the references
    /// hold 8 of the 11 bits).
    #[test]
    fn etc2_and_eac_match_piglit_reference_images() {
        let dir = "/usr/lib/x86_64-linux-gnu/piglit/tests/spec/gles-3.0";
        for name in ["r11", "rg11", "rgb8", "srgb8", "rgb8-pt-alpha1", "srgb8-pt-alpha1", "rgba8", "srgb8-alpha8"] {
            let (Ok(etc), Ok(rgba)) = (
                std::fs::read(format!("{dir}/waffles-compressed-etc2-{name}-64x32-miptree.ktx")),
                std::fs::read(format!("{dir}/waffles-decompressed-etc2-{name}-64x32-miptree.ktx")),
            ) else {
                assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "piglit's ETC2 images are missing");
                eprintln!("SKIPPED: piglit's ETC2 images are not installed (tools/install-deps installs piglit)");
                return;
            };
            let (internal, mut w, mut h, blocks) = ktx_levels(&etc);
            let (_, _, _, reference) = ktx_levels(&rgba);
            let c = Compressed::from_gl(internal).expect("an ETC2 format");
            let eac = name.contains("11");
            // The EAC references hold R11's red in all three colour channels, RG11's red and
            // green with blue 0.
            let channels = match name {
                "r11" => 1,
                "rg11" => 2,
                _ => 4,
            };
            assert_eq!(blocks.len(), 7);
            for (level, (b, r)) in blocks.iter().zip(&reference).enumerate() {
                let decoded = c.decode(b, w, h);
                for (i, (got, want)) in decoded.chunks_exact(4).zip(r.chunks_exact(4)).enumerate() {
                    let (x, y) = (i % w as usize, i / w as usize);
                    let close = got.iter().zip(want).take(channels).all(|(&g, &e)| g.abs_diff(e) <= u8::from(eac));
                    assert!(close, "{name} level {level} texel ({x}, {y}): {got:?}, piglit {want:?}");
                }
                w = (w / 2).max(1);
                h = (h / 2).max(1);
            }
        }
    }
}

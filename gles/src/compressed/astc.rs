//! ASTC LDR blocks (`KHR_texture_compression_astc_ldr`): 16 bytes per block of any of the
//! fourteen 2D footprints from 4×4 to 12×12 texels. Where the device lacks ASTC, blocks are
//! decoded here with the `astc-decode` crate, in the LDR profile: an HDR block, a void-extent
//! block with HDR values, and a block the format does not allow all decode to the error colour
//! (opaque magenta), as the extension requires.

use std::panic::{catch_unwind, AssertUnwindSafe};

/// Bytes of every ASTC block, whatever its footprint.
pub const BLOCK_BYTES: usize = 16;

/// The error colour of the LDR profile: opaque magenta.
const ERROR_COLOUR: [u8; 4] = [0xFF, 0, 0xFF, 0xFF];

/// The footprints of the 2D formats, in the order of their GL enums (`GL_COMPRESSED_RGBA_ASTC_4x4_KHR`
/// is 0x93B0, `..._SRGB8_ALPHA8_ASTC_4x4_KHR` 0x93D0, and on by one).
const FOOTPRINTS: [(u8, u8); 14] = [
    (4, 4),
    (5, 4),
    (5, 5),
    (6, 5),
    (6, 6),
    (8, 5),
    (8, 6),
    (8, 8),
    (10, 5),
    (10, 6),
    (10, 8),
    (10, 10),
    (12, 10),
    (12, 12),
];

/// The first linear and the first sRGB format enum.
const LINEAR_BASE: u32 = 0x93B0;
const SRGB_BASE: u32 = 0x93D0;

/// The footprint of an ASTC block: its width and height in texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Astc {
    /// Texels across.
    pub width: u8,
    /// Texels down.
    pub height: u8,
}

impl Astc {
    /// The footprint of format `f`, and whether it is an sRGB format.
    pub fn from_gl(f: u32) -> Option<(Astc, bool)> {
        let (base, srgb) =
            if (SRGB_BASE..SRGB_BASE + 14).contains(&f) { (SRGB_BASE, true) } else { (LINEAR_BASE, false) };
        let (width, height) = *FOOTPRINTS.get(f.checked_sub(base)? as usize)?;
        Some((Astc { width, height }, srgb))
    }

    /// Every format enum, linear then sRGB, in the order `GL_COMPRESSED_TEXTURE_FORMATS` lists them.
    pub fn all_gl() -> impl Iterator<Item = u32> {
        (LINEAR_BASE..LINEAR_BASE + 14).chain(SRGB_BASE..SRGB_BASE + 14)
    }

    /// wgpu's block format of this footprint, read as linear or (for sRGB) decoded from sRGB.
    pub fn native(self, srgb: bool) -> wgpu::TextureFormat {
        use wgpu::AstcBlock as B;
        let block = match (self.width, self.height) {
            (4, 4) => B::B4x4,
            (5, 4) => B::B5x4,
            (5, 5) => B::B5x5,
            (6, 5) => B::B6x5,
            (6, 6) => B::B6x6,
            (8, 5) => B::B8x5,
            (8, 6) => B::B8x6,
            (8, 8) => B::B8x8,
            (10, 5) => B::B10x5,
            (10, 6) => B::B10x6,
            (10, 8) => B::B10x8,
            (10, 10) => B::B10x10,
            (12, 10) => B::B12x10,
            _ => B::B12x12,
        };
        let channel = if srgb { wgpu::AstcChannel::UnormSrgb } else { wgpu::AstcChannel::Unorm };
        wgpu::TextureFormat::Astc { block, channel }
    }

    /// Decodes one block to its texels as RGBA8, row by row (`width * height` of them). The
    /// values are the encoded ones: sRGB blocks give sRGB-encoded colour.
    pub fn decode_block(self, block: &[u8]) -> Vec<[u8; 4]> {
        let (w, h) = (u32::from(self.width), u32::from(self.height));
        let mut texels = vec![ERROR_COLOUR; (w * h) as usize];
        let Ok(bytes) = <[u8; BLOCK_BYTES]>::try_from(block) else { return texels };
        let footprint = astc_decode::Footprint::new(w, h);
        // The decoder checks its own invariants with assertions; a block that broke one would
        // be a decoder defect, and decodes to the error colour instead of ending the daemon.
        let decoded = catch_unwind(AssertUnwindSafe(|| {
            let mut out = vec![ERROR_COLOUR; (w * h) as usize];
            astc_decode::astc_decode_block(&bytes, footprint, |x, y, px| {
                if let Some(t) = out.get_mut((y * w + x) as usize) {
                    *t = px;
                }
            });
            out
        }));
        if let Ok(out) = decoded {
            texels = out;
        }
        texels
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A void-extent block: one colour for the whole block, as 16-bit UNORM channels.
    fn void_extent(rgba: [u16; 4], hdr: bool) -> [u8; 16] {
        let mut b = [0u8; 16];
        // Block mode 0b1_1111_1100, bit 9 for HDR, two reserved ones, then the extent's
        // coordinates all ones, which means "no extent".
        let mode: u16 = if hdr { 0xFFFC } else { 0xFDFC };
        b[..2].copy_from_slice(&mode.to_le_bytes());
        b[2..8].copy_from_slice(&[0xFF; 6]);
        for (i, c) in rgba.iter().enumerate() {
            b[8 + 2 * i..10 + 2 * i].copy_from_slice(&c.to_le_bytes());
        }
        b
    }

    #[test]
    fn formats_name_their_footprints() {
        assert_eq!(Astc::from_gl(0x93B0), Some((Astc { width: 4, height: 4 }, false)));
        assert_eq!(Astc::from_gl(0x93BC), Some((Astc { width: 12, height: 10 }, false)));
        assert_eq!(Astc::from_gl(0x93D7), Some((Astc { width: 8, height: 8 }, true)));
        assert_eq!(Astc::from_gl(0x93BE), None);
        assert_eq!(Astc::from_gl(0x93DE), None);
        assert_eq!(Astc::from_gl(0x93AF), None);
        assert_eq!(Astc::all_gl().count(), 28);
    }

    #[test]
    fn void_extent_blocks_decode_to_their_colour() {
        let b = void_extent([0xFFFF, 0x8080, 0x0000, 0xFFFF], false);
        let texels = Astc { width: 6, height: 5 }.decode_block(&b);
        assert_eq!(texels.len(), 30);
        assert!(texels.iter().all(|&t| t == [0xFF, 0x80, 0x00, 0xFF]), "{:?}", texels[0]);
    }

    #[test]
    fn hdr_and_reserved_blocks_decode_to_the_error_colour() {
        let hdr = void_extent([0x3C00; 4], true);
        assert!(Astc { width: 4, height: 4 }.decode_block(&hdr).iter().all(|&t| t == ERROR_COLOUR));
        // Block mode 0: reserved.
        assert!(Astc { width: 8, height: 8 }.decode_block(&[0; 16]).iter().all(|&t| t == ERROR_COLOUR));
        // A short block (never passed by the callers) is the error colour too.
        assert!(Astc { width: 4, height: 4 }.decode_block(&[0; 8]).iter().all(|&t| t == ERROR_COLOUR));
    }

    /// piglit's ASTC mip chains (encoded by ARM's encoder) against the images that encoder
    /// decoded them to, as Debian's piglit package installs them: linear ones as RGB, sRGB
    /// ones as RGBA, both still sRGB encoded.
    #[test]
    fn matches_piglit_reference_images() {
        let dir = "/usr/lib/x86_64-linux-gnu/piglit/tests/spec/khr_texture_compression_astc";
        let mut worst = 0;
        for (i, (bw, bh)) in FOOTPRINTS.into_iter().enumerate() {
            for (kind, channels, base) in [("ldrl", 3, LINEAR_BASE), ("ldrs", 4, SRGB_BASE)] {
                let name = format!("2D/{kind}/waffles-{bw}x{bh}.ktx");
                let (Ok(astc), Ok(reference)) = (
                    std::fs::read(format!("{dir}/compressed/{name}")),
                    std::fs::read(format!("{dir}/decompressed/{name}")),
                ) else {
                    assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "piglit's ASTC images are missing");
                    eprintln!("SKIPPED: piglit's ASTC images are not installed (tools/install-deps installs piglit)");
                    return;
                };
                let (internal, w, h, blocks) = super::super::tests::ktx_levels(&astc);
                let (_, _, _, want) = super::super::tests::ktx_levels(&reference);
                assert_eq!(internal, base + i as u32);
                let c = if base == SRGB_BASE {
                    super::super::super::formats::Compressed::AstcSrgb(Astc { width: bw, height: bh })
                } else {
                    super::super::super::formats::Compressed::Astc(Astc { width: bw, height: bh })
                };
                for (level, (b, r)) in blocks.iter().zip(&want).enumerate() {
                    let (lw, lh) = ((w >> level).max(1) as usize, (h >> level).max(1) as usize);
                    let got = c.decode(b, lw as u32, lh as u32);
                    let row = (lw * channels).div_ceil(4) * 4;
                    for y in 0..lh {
                        for x in 0..lw {
                            let want = &r[y * row + x * channels..][..channels];
                            for (ch, &v) in want.iter().enumerate() {
                                let d = got[(y * lw + x) * 4 + ch].abs_diff(v);
                                worst = worst.max(d);
                                assert!(d <= 1, "{name} level {level} texel ({x}, {y}) channel {ch}: {d}");
                            }
                        }
                    }
                }
            }
        }
        eprintln!("worst difference from the reference: {worst}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]
        /// Any 16 bytes decode to a whole block of texels, whatever the footprint.
        #[test]
        fn any_block_decodes(bytes in proptest::array::uniform16(any::<u8>()), f in 0usize..14) {
            let (width, height) = FOOTPRINTS[f];
            let texels = Astc { width, height }.decode_block(&bytes);
            prop_assert_eq!(texels.len(), usize::from(width) * usize::from(height));
        }
    }
}

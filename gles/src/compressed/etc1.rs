//! ETC1 blocks decoded to RGBA8, as `OES_compressed_ETC1_RGB8_texture` defines them: a 64-bit
//! big-endian word per 4×4 block, split into two 2×4 or 4×2 sub-blocks (the flip bit), each
//! with a base colour (individual 4+4 bits or differential 5+3 bits per channel) and an
//! intensity-modifier table; every texel adds one of its table's four modifiers to all three
//! channels. Texel indices run down the columns (index `4 * x + y`).

/// The intensity-modifier tables (the extension's table 3.17.2), smallest magnitude first.
const MODIFIERS: [[i32; 2]; 8] = [[2, 8], [5, 17], [9, 29], [13, 42], [18, 60], [24, 80], [33, 106], [47, 183]];

/// `bits` wide field of `w` whose lowest bit is `at`.
fn field(w: u64, at: u32, bits: u32) -> u32 {
    ((w >> at) & ((1 << bits) - 1)) as u32
}

/// The two sub-blocks' base colours.
fn base_colours(w: u64) -> [[i32; 3]; 2] {
    let mut out = [[0; 3]; 2];
    // Red, green and blue fields start at bits 56, 48 and 40.
    for (c, at) in [56u32, 48, 40].into_iter().enumerate() {
        if field(w, 33, 1) == 0 {
            // Individual mode: two 4-bit values, widened by replication.
            let (a, b) = (field(w, at + 4, 4), field(w, at, 4));
            out[0][c] = (a * 17) as i32;
            out[1][c] = (b * 17) as i32;
        } else {
            // Differential mode: a 5-bit base and a 3-bit signed offset from it.
            let base = field(w, at + 3, 5) as i32;
            let delta = ((field(w, at, 3) as i32) << 29) >> 29;
            let second = (base + delta) & 31;
            let widen = |v: i32| (v << 3) | (v >> 2);
            out[0][c] = widen(base);
            out[1][c] = widen(second);
        }
    }
    out
}

/// Decodes one 8-byte block into its 16 RGBA8 texels, in row order (texel `4 * y + x`), alpha 1.
pub fn decode_block(b: &[u8]) -> [[u8; 4]; 16] {
    let w = u64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]);
    let base = base_colours(w);
    let tables = [field(w, 37, 3) as usize, field(w, 34, 3) as usize];
    let flip = field(w, 32, 1) == 1;
    std::array::from_fn(|t| {
        let (x, y) = (t % 4, t / 4);
        let sub = usize::from(if flip { y >= 2 } else { x >= 2 });
        let i = (4 * x + y) as u32;
        let (msb, lsb) = (field(w, 16 + i, 1), field(w, i, 1));
        let [small, large] = MODIFIERS[tables[sub]];
        let m = match (msb, lsb) {
            (0, 0) => small,
            (0, _) => large,
            (_, 0) => -small,
            _ => -large,
        };
        let c = base[sub].map(|v| (v + m).clamp(0, 255) as u8);
        [c[0], c[1], c[2], 255]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block from its 32 high bits (colours, tables, diff and flip bits) and 32 index bits.
    fn block(high: u32, indices: u32) -> [u8; 8] {
        ((u64::from(high) << 32) | u64::from(indices)).to_be_bytes()
    }

    // Expected values below are worked out by hand from the extension's bit layout.
    #[test]
    fn individual_mode_side_by_side() {
        // R 0x8/0x2, G 0x4/0x6, B 0xC/0x0; tables 0 and 7; no flip, no diff.
        let high = 0x82_46_C0_00 | (7 << 2);
        // Texel (0,0): index 0 → msb 0, lsb 0 → +2. Texel (1,0): index 4 → lsb 1 → +8.
        // Texel (2,0): index 8 → msb 1 lsb 0 → −47. Texel (3,0): index 12 → msb 1 lsb 1 → −183.
        let indices = (1 << 4) | (1 << (16 + 8)) | (1 << 12) | (1 << (16 + 12));
        let px = decode_block(&block(high, indices));
        assert_eq!(px[0], [0x88 + 2, 0x44 + 2, 0xCC + 2, 255]);
        assert_eq!(px[1], [0x88 + 8, 0x44 + 8, 0xCC + 8, 255]);
        assert_eq!(px[2], [0, 0x66 - 47, 0, 255]); // 0x22 − 47 and 0x00 − 47 clamp at zero
        assert_eq!(px[3], [0, 0, 0, 255]); // −183 clamps every channel
    }

    #[test]
    fn differential_mode_flipped() {
        // Red base 16 with delta −1, green base 28 with delta +3, blue base 0 with delta +2.
        let r = (16 << 3) | 0b111;
        let g = (28 << 3) | 0b011;
        let b = 0b010;
        let high = (r << 24) | (g << 16) | (b << 8) | (1 << 1) | 1; // diff and flip set, tables 0
        let px = decode_block(&block(high, 0));
        let widen = |v: i32| ((v << 3) | (v >> 2)) as u8;
        // Top half: first sub-block; bottom half: second, every texel +2 (index 0).
        assert_eq!(px[0], [widen(16) + 2, widen(28) + 2, 2, 255]);
        assert_eq!(px[7], [widen(16) + 2, widen(28) + 2, 2, 255]);
        assert_eq!(px[8], [widen(15) + 2, widen(31).saturating_add(2), widen(2) + 2, 255]);
        assert_eq!(px[15], px[8]);
    }
}

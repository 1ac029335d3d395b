//! ES 3.0's packed float formats, `R11F_G11F_B10F` and `RGB9_E5`, kept as half floats (every
//! value of either is a half float): their packed data decoded, and float data rounded to
//! their precision as Mesa rounds it (11- and 10-bit floats cut to their mantissa; a shared
//! exponent with each mantissa rounded to nearest). Neither is renderable in ES 3.0 without
//! `EXT_color_buffer_float`.

use crate::enums::*;

/// `GL_R11F_G11F_B10F`.
pub const R11F_G11F_B10F: u32 = 0x8C3A;
/// `GL_UNSIGNED_INT_10F_11F_11F_REV`: red's 11 bits lowest, then green's 11, blue's 10.
pub const UNSIGNED_INT_10F_11F_11F_REV: u32 = 0x8C3B;
/// `GL_RGB9_E5`.
pub const RGB9_E5: u32 = 0x8C3D;
/// `GL_UNSIGNED_INT_5_9_9_9_REV`: three 9-bit mantissas, then a 5-bit exponent.
pub const UNSIGNED_INT_5_9_9_9_REV: u32 = 0x8C3E;

/// An unsigned float of a 5-bit exponent (bias 15) and a `bits`-bit mantissa.
fn small_float(v: u32, bits: u32) -> f32 {
    let (e, m) = ((v >> bits) & 31, v & ((1 << bits) - 1));
    let scale = (1u32 << bits) as f32;
    match e {
        0 => m as f32 / scale * 2f32.powi(-14),
        31 if m == 0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + m as f32 / scale) * 2f32.powi(e as i32 - 15),
    }
}

/// `v` as an unsigned float of a 5-bit exponent and a `bits`-bit mantissa, cut as Mesa cuts
/// it: negative values and values below the least normal one 0, values past the largest the
/// largest, NaN kept.
fn to_small_float(v: f32, bits: u32) -> u32 {
    if v.is_nan() {
        return 31 << bits | 1;
    }
    if v <= 0.0 {
        return 0;
    }
    let max = (2.0 - 2f32.powi(-(bits as i32))) * 2f32.powi(15);
    if v >= max {
        return if v.is_infinite() { 31 << bits } else { 30 << bits | ((1 << bits) - 1) };
    }
    // Below the least normal value, 0: Mesa keeps no denormals.
    let exp = v.log2().floor() as i32;
    if exp < -14 {
        return 0;
    }
    let m = ((v / 2f32.powi(exp) - 1.0) * (1u32 << bits) as f32) as u32;
    ((exp + 15) as u32) << bits | m.min((1 << bits) - 1)
}

/// The red, green and blue of one `UNSIGNED_INT_10F_11F_11F_REV` value.
pub fn decode_11_11_10(v: u32) -> [f32; 3] {
    [small_float(v & 0x7FF, 6), small_float((v >> 11) & 0x7FF, 6), small_float(v >> 22, 5)]
}

/// `rgb` as one `UNSIGNED_INT_10F_11F_11F_REV` value, each channel cut as Mesa cuts it.
pub fn encode_11_11_10([r, g, b]: [f32; 3]) -> u32 {
    to_small_float(r, 6) | to_small_float(g, 6) << 11 | to_small_float(b, 5) << 22
}

/// The red, green and blue of one `UNSIGNED_INT_5_9_9_9_REV` value.
pub fn decode_rgb9e5(v: u32) -> [f32; 3] {
    let scale = 2f32.powi((v >> 27) as i32 - 15 - 9);
    [v & 0x1FF, (v >> 9) & 0x1FF, (v >> 18) & 0x1FF].map(|m| m as f32 * scale)
}

/// `rgb` with a shared exponent and 9-bit mantissas rounded to nearest, as `GL_RGB9_E5`
/// keeps it.
fn rgb9e5(rgb: [f32; 3]) -> [f32; 3] {
    let max_value = 511.0 / 512.0 * 2f32.powi(16);
    let c = rgb.map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, max_value) });
    let max = c[0].max(c[1]).max(c[2]);
    let exp = (max.log2().floor() as i32).max(-16) + 1;
    let mut denom = 2f32.powi(exp - 9);
    if (max / denom + 0.5).floor() >= 512.0 {
        denom *= 2.0;
    }
    c.map(|v| (v / denom + 0.5).floor() * denom)
}

/// The rounding of float data that an image of packed float format `internal` applies, if
/// it is one.
pub fn rounding(internal: u32) -> Option<fn([f32; 3]) -> [f32; 3]> {
    match internal {
        R11F_G11F_B10F => Some(|c: [f32; 3]| {
            [small_float(to_small_float(c[0], 6), 6), small_float(to_small_float(c[1], 6), 6), {
                small_float(to_small_float(c[2], 5), 5)
            }]
        }),
        RGB9_E5 => Some(rgb9e5),
        _ => None,
    }
}

/// Whether `ty` is one of the packed float types.
pub fn is_packed_float_type(ty: u32) -> bool {
    matches!(ty, UNSIGNED_INT_10F_11F_11F_REV | UNSIGNED_INT_5_9_9_9_REV)
}

/// Whether an upload of `format`/`ty` may fill packed float format `sized` (ES 3.0's table
/// 3.2); `None` where `sized` is no packed float format.
pub fn accepts(sized: u32, format: u32, ty: u32) -> Option<bool> {
    let own = match sized {
        R11F_G11F_B10F => UNSIGNED_INT_10F_11F_11F_REV,
        RGB9_E5 => UNSIGNED_INT_5_9_9_9_REV,
        _ => return None,
    };
    Some(format == RGB && (ty == own || matches!(ty, HALF_FLOAT | FLOAT)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_values_decode_as_the_specification_gives_them() {
        // 1.0 in each: exponent 15, mantissa 0.
        let one = 15 << 6 | (15 << 6) << 11 | (15 << 5) << 22;
        assert_eq!(decode_11_11_10(one), [1.0, 1.0, 1.0]);
        // Exponent 15 (2^0 with bias 15 + 9 mantissa bits), mantissas 256, 128, 1.
        let e = 15 + 9;
        assert_eq!(decode_rgb9e5(e << 27 | 1 << 18 | 128 << 9 | 256), [256.0, 128.0, 1.0]);
        assert_eq!(small_float(0x7C0, 6), f32::INFINITY);
    }

    #[test]
    fn float_data_rounds_as_mesa_rounds_it() {
        let r = rounding(R11F_G11F_B10F).expect("r11g11b10");
        // 1 + 2^-7 is below an 11-bit float's step at 1 (2^-6): cut to 1.
        assert_eq!(r([1.0 + 2f32.powi(-7), -3.0, 1e9]), [1.0, 0.0, 64512.0]);
        let e = rounding(RGB9_E5).expect("rgb9e5");
        // The largest of 1000, 1 and 0.001 sets the exponent: steps of 2; 1 rounds to 2.
        assert_eq!(e([1000.0, 1.0, 0.001]), [1000.0, 2.0, 0.0]);
    }
}

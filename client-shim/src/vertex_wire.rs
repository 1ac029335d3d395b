//! Converting a `GL_FLOAT` client-side vertex array for the wire ([`VertexWire`]): the
//! components a draw reads, gathered from the application's stride and tightly packed as
//! IEEE binary16 or 16.16 fixed point. Only client-side `GL_FLOAT` arrays are converted: a
//! buffer object's bytes cross once, untyped, at `glBufferData`, and arrays of other types
//! travel as the application gave them.
//!
//! Rounding: binary16 rounds to nearest, ties to even (values beyond ±65504 become ±∞, NaN
//! stays NaN); 16.16 rounds to nearest, ties away from zero, saturates at the `i32` range
//! (±32768) and maps NaN to 0.

pub use strata_protocol::handshake::VertexWire;

/// The binary16 bits nearest to `x` (ties to even).
pub fn to_half(x: f32) -> u16 {
    half::f16::from_f32(x).to_bits()
}

/// The 16.16 fixed-point value nearest to `x` (ties away from zero), saturated; NaN is 0.
pub fn to_fixed(x: f32) -> i32 {
    // x · 2^16 is exact in f64; the cast saturates and sends NaN to 0.
    (f64::from(x) * 65536.0).round() as i32
}

/// The value a component of `x` has after crossing the wire as `wire`, in f64.
pub fn quantise(wire: VertexWire, x: f32) -> f64 {
    match wire {
        VertexWire::Float => f64::from(x),
        VertexWire::Half => f64::from(half::f16::from_bits(to_half(x)).to_f32()),
        VertexWire::Fixed => f64::from(to_fixed(x)) / 65536.0,
    }
}

/// Packs `vertices` elements of `size` floats, `stride` bytes apart in `src` (native byte
/// order), as `wire` components; `None` if `src` is too short.
pub fn pack(wire: VertexWire, src: &[u8], size: usize, stride: usize, vertices: usize) -> Option<Vec<u8>> {
    let need = vertices.checked_sub(1).map_or(Some(0), |v| v.checked_mul(stride)?.checked_add(size * 4))?;
    if need > src.len() {
        return None;
    }
    let mut out = Vec::with_capacity(vertices * size * wire.component_bytes());
    for v in 0..vertices {
        let base = v * stride;
        for c in 0..size {
            let at = base + c * 4;
            let x = f32::from_ne_bytes([src[at], src[at + 1], src[at + 2], src[at + 3]]);
            match wire {
                VertexWire::Float => out.extend_from_slice(&x.to_ne_bytes()),
                VertexWire::Half => out.extend_from_slice(&to_half(x).to_ne_bytes()),
                VertexWire::Fixed => out.extend_from_slice(&to_fixed(x).to_ne_bytes()),
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_rounds_to_nearest_even() {
        // binary16 has 10 fraction bits: between 1 and 2 its spacing is 2^-10.
        let ulp = 1.0 / 1024.0;
        assert_eq!(to_half(1.0), 0x3C00);
        assert_eq!(to_half(1.0 + ulp / 2.0), 0x3C00, "tie goes to the even neighbour (1.0)");
        assert_eq!(to_half(1.0 + 1.5 * ulp), 0x3C02, "tie goes to the even neighbour (1 + 2 ulp)");
        assert_eq!(to_half(1.0 + 0.6 * ulp), 0x3C01);
        assert_eq!(to_half(-2.0), 0xC000);
        assert_eq!(to_half(1e6), 0x7C00, "overflow is infinity");
    }

    #[test]
    fn fixed_rounds_and_saturates() {
        assert_eq!(to_fixed(1.0), 65536);
        assert_eq!(to_fixed(-0.5), -32768);
        assert_eq!(to_fixed(1.5 / 65536.0), 2, "ties away from zero");
        assert_eq!(to_fixed(0.4 / 65536.0), 0);
        assert_eq!(to_fixed(1e9), i32::MAX);
        assert_eq!(to_fixed(-1e9), i32::MIN);
        assert_eq!(to_fixed(f32::NAN), 0);
    }

    #[test]
    fn pack_gathers_the_stride_and_checks_the_length() {
        // Interleaved (x, y, pad): stride 12, two vertices.
        let src: Vec<u8> = [1.0f32, 2.0, 99.0, -1.0, 0.5, 99.0].iter().flat_map(|f| f.to_ne_bytes()).collect();
        let half = pack(VertexWire::Half, &src, 2, 12, 2).expect("long enough");
        let want: Vec<u8> = [0x3C00u16, 0x4000, 0xBC00, 0x3800].iter().flat_map(|h| h.to_ne_bytes()).collect();
        assert_eq!(half, want);
        let fixed = pack(VertexWire::Fixed, &src, 2, 12, 2).expect("long enough");
        let want: Vec<u8> = [65536i32, 131072, -65536, 32768].iter().flat_map(|h| h.to_ne_bytes()).collect();
        assert_eq!(fixed, want);
        assert!(pack(VertexWire::Half, &src, 2, 12, 3).is_none());
        assert_eq!(pack(VertexWire::Half, &src, 2, 12, 0), Some(vec![]));
    }
}

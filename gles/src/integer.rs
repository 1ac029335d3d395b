//! ES 3.0's integer colour formats (`R8I` … `RGBA32UI`, and `RGB10_A2UI`): which internal
//! formats they are, the storage each is kept in (RGBA of the format's own component width,
//! signed or unsigned; `RGB10_A2UI` in its own packed layout), the data an upload of each
//! takes, how an upload converts to the storage, and how `glReadPixels` of `GL_RGBA_INTEGER`
//! converts from it. Integer images are never filtered nor blended.

use crate::enums::*;

/// An integer internal format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct IntFormat {
    /// Its base format: `GL_RED`, `GL_RG`, `GL_RGB` or `GL_RGBA`.
    pub base: u32,
    /// Whether its components are signed.
    pub signed: bool,
    /// Bits of each component: 8, 16 or 32; 10 for `RGB10_A2UI`.
    pub bits: u8,
}

impl IntFormat {
    /// The integer internal format `internal` names, if it names one.
    pub fn from_gl(internal: u32) -> Option<IntFormat> {
        let f = |base, signed, bits| Some(IntFormat { base, signed, bits });
        match internal {
            // R8I, R8UI, R16I, R16UI, R32I, R32UI, then the same for RG.
            R8I..=RG32UI => {
                let i = internal - R8I;
                let base = if i < 6 { RED_EXT } else { RG_EXT };
                f(base, i.is_multiple_of(2), 8 << ((i % 6) / 2))
            }
            RGBA32UI => f(RGBA, false, 32),
            RGB32UI => f(RGB, false, 32),
            RGBA16UI => f(RGBA, false, 16),
            RGB16UI => f(RGB, false, 16),
            RGBA8UI => f(RGBA, false, 8),
            RGB8UI => f(RGB, false, 8),
            RGBA32I => f(RGBA, true, 32),
            RGB32I => f(RGB, true, 32),
            RGBA16I => f(RGBA, true, 16),
            RGB16I => f(RGB, true, 16),
            RGBA8I => f(RGBA, true, 8),
            RGB8I => f(RGB, true, 8),
            RGB10_A2UI => f(RGBA, false, 10),
            _ => None,
        }
    }

    /// The wgpu format its images are kept in.
    pub fn wgpu(self) -> wgpu::TextureFormat {
        int_wgpu(self.signed, self.bits)
    }

    /// The one format and type of data an upload to it takes (ES 3.0's table 3.2).
    pub fn upload(self) -> (u32, u32) {
        let format = match self.base {
            RED_EXT => RED_INTEGER,
            RG_EXT => RG_INTEGER,
            RGB => RGB_INTEGER,
            _ => RGBA_INTEGER,
        };
        let ty = match (self.bits, self.signed) {
            (10, _) => UNSIGNED_INT_2_10_10_10_REV_EXT,
            (8, true) => BYTE,
            (8, false) => UNSIGNED_BYTE,
            (16, true) => SHORT,
            (16, false) => UNSIGNED_SHORT,
            (_, true) => INT,
            (_, false) => UNSIGNED_INT,
        };
        (format, ty)
    }

    /// Whether a framebuffer can render into it: every integer format but the RGB ones
    /// (ES 3.0's table 3.13).
    pub fn renderable(self) -> bool {
        self.base != RGB
    }

    /// Red, green, blue and alpha bits.
    pub fn color_bits(self) -> [i32; 4] {
        if self.bits == 10 {
            return [10, 10, 10, 2];
        }
        let b = i32::from(self.bits);
        match self.base {
            RED_EXT => [b, 0, 0, 0],
            RG_EXT => [b, b, 0, 0],
            RGB => [b, b, b, 0],
            _ => [b; 4],
        }
    }
}

/// The integer storage's wgpu format: RGBA of `bits`-bit components, or 10/10/10/2.
pub fn int_wgpu(signed: bool, bits: u8) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as F;
    match (signed, bits) {
        (false, 10) => F::Rgb10a2Uint,
        (true, 8) => F::Rgba8Sint,
        (false, 8) => F::Rgba8Uint,
        (true, 16) => F::Rgba16Sint,
        (false, 16) => F::Rgba16Uint,
        (true, _) => F::Rgba32Sint,
        (false, _) => F::Rgba32Uint,
    }
}

/// Whether `format` is one of the integer upload formats (`GL_RED_INTEGER` …).
pub fn is_integer_format(format: u32) -> bool {
    matches!(format, RED_INTEGER | RG_INTEGER | RGB_INTEGER | RGBA_INTEGER)
}

/// Components per pixel of an integer upload format.
pub fn components(format: u32) -> usize {
    match format {
        RGBA_INTEGER => 4,
        RGB_INTEGER => 3,
        RG_INTEGER => 2,
        _ => 1,
    }
}

/// Appends one pixel `px` of integer data (`format`, `ty`) to `out` as a texel of integer
/// storage of `bits`-bit components: the channels the data lacks 0, a lacking alpha 1.
pub fn push_texel(px: &[u8], format: u32, ty: u32, bits: u8, out: &mut Vec<u8>) {
    if bits == 10 {
        // `UNSIGNED_INT_2_10_10_10_REV` is the storage's own layout.
        out.extend_from_slice(&px[..4]);
        return;
    }
    let width = usize::from(bits / 8);
    let n = components(format);
    let size = match ty {
        BYTE | UNSIGNED_BYTE => 1,
        SHORT | UNSIGNED_SHORT => 2,
        _ => 4,
    };
    for c in 0..4 {
        let v: i64 = if c < n {
            let b = &px[c * size..(c + 1) * size];
            match ty {
                BYTE => i64::from(b[0] as i8),
                UNSIGNED_BYTE => i64::from(b[0]),
                SHORT => i64::from(i16::from_ne_bytes([b[0], b[1]])),
                UNSIGNED_SHORT => i64::from(u16::from_ne_bytes([b[0], b[1]])),
                INT => i64::from(i32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
                _ => i64::from(u32::from_ne_bytes([b[0], b[1], b[2], b[3]])),
            }
        } else {
            i64::from(c == 3)
        };
        out.extend_from_slice(&v.to_ne_bytes()[..width]);
    }
}

/// A blank texel of integer storage of `bits`-bit components: 0, 0, 0, 1.
pub fn blank_texel(bits: u8) -> Vec<u8> {
    if bits == 10 {
        return (3u32 << 30).to_ne_bytes().to_vec();
    }
    let width = usize::from(bits / 8);
    let mut t = vec![0u8; 4 * width];
    t[3 * width] = 1;
    t
}

/// The four components of a texel `t` of integer storage `format` (as read back), widened to
/// 32 bits: sign-extended when signed.
pub fn widen(t: &[u8], format: wgpu::TextureFormat) -> [u32; 4] {
    use wgpu::TextureFormat as F;
    let word = |i: usize| u32::from_ne_bytes([t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]]);
    let short = |i: usize| [t[2 * i], t[2 * i + 1]];
    match format {
        F::Rgb10a2Uint => {
            let v = word(0);
            [v & 0x3FF, (v >> 10) & 0x3FF, (v >> 20) & 0x3FF, v >> 30]
        }
        F::Rgba8Sint => [0, 1, 2, 3].map(|i| i32::from(t[i] as i8) as u32),
        F::Rgba8Uint => [0, 1, 2, 3].map(|i| u32::from(t[i])),
        F::Rgba16Sint => [0, 1, 2, 3].map(|i| i32::from(i16::from_ne_bytes(short(i))) as u32),
        F::Rgba16Uint => [0, 1, 2, 3].map(|i| u32::from(u16::from_ne_bytes(short(i)))),
        _ => [0, 1, 2, 3].map(word),
    }
}

/// Components `v` of a texel of a colour buffer lacking the channels `absent`: those read 0,
/// a lacking alpha 1.
pub fn present(v: [u32; 4], absent: wgpu::ColorWrites) -> [u32; 4] {
    let chans = [wgpu::ColorWrites::RED, wgpu::ColorWrites::GREEN, wgpu::ColorWrites::BLUE, wgpu::ColorWrites::ALPHA];
    let mut out = v;
    for (i, c) in chans.iter().enumerate() {
        if absent.contains(*c) {
            out[i] = u32::from(i == 3);
        }
    }
    out
}

/// Bytes per pixel of integer data in `format` and `ty`.
pub fn pixel_bytes(format: u32, ty: u32) -> usize {
    match ty {
        UNSIGNED_INT_2_10_10_10_REV_EXT => 4,
        BYTE | UNSIGNED_BYTE => components(format),
        SHORT | UNSIGNED_SHORT => 2 * components(format),
        _ => 4 * components(format),
    }
}

/// Writes components `v` (32-bit) into `out` as one pixel of `format` and `ty`, each cut to
/// the type's width (a packed type packs 10/10/10/2 bits).
pub fn pack(v: [u32; 4], format: u32, ty: u32, out: &mut [u8]) {
    if ty == UNSIGNED_INT_2_10_10_10_REV_EXT {
        let p = (v[0] & 0x3FF) | (v[1] & 0x3FF) << 10 | (v[2] & 0x3FF) << 20 | (v[3] & 3) << 30;
        out.copy_from_slice(&p.to_ne_bytes());
        return;
    }
    let size = pixel_bytes(format, ty) / components(format);
    for (c, chunk) in v.iter().zip(out.chunks_exact_mut(size)) {
        chunk.copy_from_slice(&c.to_ne_bytes()[..size]);
    }
}

/// Bytes per texel of integer storage of `bits`-bit components.
pub fn texel_bytes(bits: u8) -> u32 {
    match bits {
        8 | 10 => 4,
        16 => 8,
        _ => 16,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_are_named_as_the_specification_numbers_them() {
        let r16ui = IntFormat::from_gl(0x8234).expect("R16UI");
        assert_eq!(r16ui, IntFormat { base: RED_EXT, signed: false, bits: 16 });
        assert_eq!(r16ui.upload(), (RED_INTEGER, UNSIGNED_SHORT));
        let rg32i = IntFormat::from_gl(0x823B).expect("RG32I");
        assert_eq!(rg32i, IntFormat { base: RG_EXT, signed: true, bits: 32 });
        assert_eq!(IntFormat::from_gl(RGB8I).map(|f| (f.renderable(), f.upload())), Some((false, (RGB_INTEGER, BYTE))));
        assert_eq!(IntFormat::from_gl(RGB10_A2UI).map(IntFormat::color_bits), Some([10, 10, 10, 2]));
        assert_eq!(IntFormat::from_gl(RGBA), None);
    }

    #[test]
    fn uploads_fill_missing_channels_and_reads_sign_extend() {
        let mut out = Vec::new();
        push_texel(&(-2i16).to_ne_bytes(), RED_INTEGER, SHORT, 16, &mut out);
        assert_eq!(widen(&out, wgpu::TextureFormat::Rgba16Sint), [(-2i32) as u32, 0, 0, 1]);
        let mut out = Vec::new();
        push_texel(&[200, 7, 9], RGB_INTEGER, UNSIGNED_BYTE, 8, &mut out);
        assert_eq!(widen(&out, wgpu::TextureFormat::Rgba8Uint), [200, 7, 9, 1]);
        let packed = (3u32 << 30 | 5 << 20 | 1023 << 10 | 17).to_ne_bytes();
        let mut out = Vec::new();
        push_texel(&packed, RGBA_INTEGER, UNSIGNED_INT_2_10_10_10_REV_EXT, 10, &mut out);
        assert_eq!(widen(&out, wgpu::TextureFormat::Rgb10a2Uint), [17, 1023, 5, 3]);
        assert_eq!(widen(&blank_texel(32), wgpu::TextureFormat::Rgba32Uint), [0, 0, 0, 1]);
    }
}

//! `GL_NV_read_depth`, `GL_NV_read_depth_stencil` and `GL_NV_read_stencil`: `glReadPixels` of
//! the read framebuffer's depth (`GL_DEPTH_COMPONENT` as `GL_UNSIGNED_SHORT` or
//! `GL_UNSIGNED_INT`), depth and stencil (`GL_DEPTH_STENCIL_OES` as
//! `GL_UNSIGNED_INT_24_8_OES`) and stencil (`GL_STENCIL_INDEX_OES` as `GL_UNSIGNED_BYTE`).
//! Depth is converted from the stored value as Mesa converts it: to the buffer's own bits (16
//! for `GL_DEPTH_COMPONENT16`, else 24), then widened by repeating the bits.

use crate::conv::type_size;
use crate::enums::*;
use crate::error::GlError;

/// `GL_STENCIL_INDEX_OES`.
pub const STENCIL_INDEX_OES: u32 = 0x1901;

/// What a read of depth or stencil writes per pixel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthRead {
    /// `GL_DEPTH_COMPONENT`, `GL_UNSIGNED_SHORT`.
    Depth16,
    /// `GL_DEPTH_COMPONENT`, `GL_UNSIGNED_INT`.
    Depth32,
    /// `GL_DEPTH_STENCIL_OES`, `GL_UNSIGNED_INT_24_8_OES`: depth in the top 24 bits.
    DepthStencil,
    /// `GL_STENCIL_INDEX_OES`, `GL_UNSIGNED_BYTE`.
    Stencil8,
}

impl DepthRead {
    /// The read `format` and `ty` ask for when `format` is a depth or stencil one, or the error
    /// for the pair: `None` for other formats.
    pub fn from_gl(format: u32, ty: u32) -> Option<Result<DepthRead, GlError>> {
        let read = match (format, ty) {
            (DEPTH_COMPONENT, UNSIGNED_SHORT) => DepthRead::Depth16,
            (DEPTH_COMPONENT, UNSIGNED_INT) => DepthRead::Depth32,
            (DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES) => DepthRead::DepthStencil,
            (STENCIL_INDEX_OES, UNSIGNED_BYTE) => DepthRead::Stencil8,
            (DEPTH_COMPONENT | DEPTH_STENCIL_OES | STENCIL_INDEX_OES, _) => {
                let known = type_size(ty).is_some()
                    || matches!(
                        ty,
                        INT | UNSIGNED_INT
                            | UNSIGNED_INT_24_8_OES
                            | UNSIGNED_SHORT_5_6_5
                            | UNSIGNED_SHORT_4_4_4_4
                            | UNSIGNED_SHORT_5_5_5_1
                            | UNSIGNED_SHORT_4_4_4_4_REV_EXT
                            | UNSIGNED_SHORT_1_5_5_5_REV_EXT
                    );
                return Some(Err(if known { GlError::InvalidOperation } else { GlError::InvalidEnum }));
            }
            _ => return None,
        };
        Some(Ok(read))
    }

    /// Bytes a pixel takes.
    pub fn bytes(self) -> usize {
        match self {
            DepthRead::Depth16 => 2,
            DepthRead::Depth32 | DepthRead::DepthStencil => 4,
            DepthRead::Stencil8 => 1,
        }
    }

    /// Whether it reads depth, and whether stencil.
    pub fn aspects(self) -> (bool, bool) {
        match self {
            DepthRead::Depth16 | DepthRead::Depth32 => (true, false),
            DepthRead::DepthStencil => (true, true),
            DepthRead::Stencil8 => (false, true),
        }
    }

    /// Writes the pixel of stored depth `depth` (in [0, 1]) of a buffer of `bits` depth bits
    /// and stencil `stencil` into `out` (`self.bytes()` long).
    pub fn write(self, depth: f32, bits: u32, stencil: u8, out: &mut [u8]) {
        let max = (1u64 << bits) - 1;
        let n = (f64::from(depth.clamp(0.0, 1.0)) * max as f64).round() as u32;
        // The value as 24 bits, and as 32 by repeating its top bits below it; as 16 bits, a
        // 24-bit value is converted, not cut (Mesa reads 0x4CCCCD as 0x4CCD).
        let (n24, n32) = if bits == 16 { (n << 8 | n >> 8, n << 16 | n) } else { (n, n << 8 | n >> 16) };
        let n16 = if bits == 16 { n } else { (f64::from(n) * 65535.0 / 16_777_215.0).round() as u32 };
        match self {
            DepthRead::Depth16 => out.copy_from_slice(&(n16 as u16).to_ne_bytes()),
            DepthRead::Depth32 => out.copy_from_slice(&n32.to_ne_bytes()),
            DepthRead::DepthStencil => out.copy_from_slice(&(n24 << 8 | u32::from(stencil)).to_ne_bytes()),
            DepthRead::Stencil8 => out[0] = stencil,
        }
    }
}

/// The depth bits of a depth/stencil image of `format`, as Mesa stores them: 16 for
/// `GL_DEPTH_COMPONENT16`, 24 for every other.
pub fn depth_bits(format: wgpu::TextureFormat) -> u32 {
    if format == wgpu::TextureFormat::Depth16Unorm {
        16
    } else {
        24
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn written(read: DepthRead, depth: f32, bits: u32, stencil: u8) -> u32 {
        let mut out = [0u8; 4];
        read.write(depth, bits, stencil, &mut out[..read.bytes()]);
        u32::from_ne_bytes(out)
    }

    #[test]
    fn depth_converts_as_mesa_reads_it() {
        // The values Mesa read back from a 24-bit buffer cleared to 0.25 with stencil 0x5a.
        assert_eq!(written(DepthRead::Depth16, 0.25, 24, 0), 0x4000);
        assert_eq!(written(DepthRead::Depth32, 0.25, 24, 0), 0x4000_0040);
        assert_eq!(written(DepthRead::DepthStencil, 0.25, 24, 0x5a), 0x4000_005a);
        assert_eq!(written(DepthRead::Stencil8, 0.25, 24, 0x5a), 0x5a);
        assert_eq!(written(DepthRead::Depth32, 1.0, 24, 0), 0xFFFF_FFFF);
        assert_eq!(written(DepthRead::Depth32, 1.0, 16, 0), 0xFFFF_FFFF);
        assert_eq!(written(DepthRead::Depth16, 0.5, 16, 0), 0x8000);
        // A 24-bit buffer cleared to 0.3 and 0.7, as Mesa read them.
        assert_eq!(written(DepthRead::Depth16, 0.3, 24, 0), 0x4CCD);
        assert_eq!(written(DepthRead::Depth32, 0.3, 24, 0), 0x4CCC_CD4C);
        assert_eq!(written(DepthRead::Depth16, 0.7, 24, 0), 0xB332);
    }

    #[test]
    fn pairs_are_validated_as_on_mesa() {
        assert_eq!(DepthRead::from_gl(DEPTH_COMPONENT, UNSIGNED_BYTE), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(DEPTH_COMPONENT, FLOAT), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(DEPTH_STENCIL_OES, UNSIGNED_INT), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(RGBA, UNSIGNED_BYTE), None);
    }
}

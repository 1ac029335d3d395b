//! Pixel transfer to the client: `glReadPixels` honouring `PACK_ALIGNMENT` (uploads are in
//! `unpack`), as RGBA bytes, or with `GL_EXT_read_format_bgra` as BGRA bytes and the two
//! reversed 16-bit BGRA packings.
//!
//! `GL_NV_read_depth`, `GL_NV_read_depth_stencil` and `GL_NV_read_stencil`: `glReadPixels` of
//! the read framebuffer's depth (`GL_DEPTH_COMPONENT` as `GL_UNSIGNED_SHORT` or
//! `GL_UNSIGNED_INT`), depth and stencil (`GL_DEPTH_STENCIL_OES` as
//! `GL_UNSIGNED_INT_24_8_OES`) and stencil (`GL_STENCIL_INDEX_OES` as `GL_UNSIGNED_BYTE`).
//! Depth is converted from the stored value as Mesa converts it: to the buffer's own bits (16
//! for `GL_DEPTH_COMPONENT16`, else 24), then widened by repeating the bits.

use crate::context::Context;
use crate::conv::{type_size, Mirror};
use crate::enums::*;
use crate::error::GlError;
use crate::limits::MAX_READ_BYTES;
use crate::GlesExecutor;
use strata_protocol::Bytes;

/// Bytes a `width`×`height` image of `bpp`-byte pixels occupies with `alignment` row padding
/// (the last row unpadded).
fn packed_size(width: usize, height: usize, bpp: usize, alignment: usize) -> usize {
    if width == 0 || height == 0 {
        return 0;
    }
    let row = (width * bpp).div_ceil(alignment) * alignment;
    row * (height - 1) + width * bpp
}

/// What a `glReadPixels` reads.
#[derive(Debug, Clone, Copy)]
enum Read {
    /// The colour read buffer.
    Color(ReadFormat),
    /// Depth, stencil, or both (`GL_NV_read_depth` and its kin).
    Depth(DepthRead),
}

/// How `glReadPixels` writes each pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
enum ReadFormat {
    /// `GL_RGBA`, `GL_UNSIGNED_BYTE`.
    Rgba8,
    /// `GL_BGRA_EXT`, `GL_UNSIGNED_BYTE`.
    Bgra8,
    /// `GL_BGRA_EXT`, `GL_UNSIGNED_SHORT_4_4_4_4_REV_EXT`: blue in the low four bits.
    Bgra4444Rev,
    /// `GL_BGRA_EXT`, `GL_UNSIGNED_SHORT_1_5_5_5_REV_EXT`: blue in the low five bits, alpha
    /// in the top bit.
    Bgra1555Rev,
    /// `GL_RED_EXT`, `GL_UNSIGNED_BYTE` (`GL_EXT_texture_rg`): red only.
    R8,
    /// `GL_RG_EXT`, `GL_UNSIGNED_BYTE` (`GL_EXT_texture_rg`): red and green.
    Rg8,
    /// `GL_RGBA`, `GL_RG_EXT` or `GL_RED_EXT` as `GL_HALF_FLOAT`: the first this many channels
    /// of a half-float colour buffer (`GL_EXT_color_buffer_half_float`), its implementation
    /// read format.
    Half(usize),
    /// `GL_RGBA`, `GL_RG` or `GL_RED` as `GL_FLOAT` (ES 3.0): the first this many channels
    /// of a float colour buffer as 32-bit floats (RGBA from any float buffer, fewer from a
    /// 32-bit float buffer of that many, its implementation read format).
    Float(usize),
    /// `GL_RGBA`, `GL_UNSIGNED_INT_2_10_10_10_REV` (ES 3.0): an `RGB10_A2` buffer's own texels.
    Rgb10a2,
    /// `GL_RGB`, `GL_UNSIGNED_INT_10F_11F_11F_REV` (ES 3.0): an `R11F_G11F_B10F` buffer's own
    /// texels.
    Packed11,
    /// Integers (ES 3.0): `GL_RGBA_INTEGER` as `GL_INT` or `GL_UNSIGNED_INT` from an integer
    /// colour buffer of the same signedness, or the buffer's own format and type (its
    /// implementation read format).
    Int {
        /// The `GL_*_INTEGER` format.
        format: u32,
        /// The type.
        ty: u32,
    },
}

impl ReadFormat {
    /// The pair's way of writing, or the error `glReadPixels` raises for it.
    fn from_gl(format: u32, ty: u32, es3: bool) -> Result<ReadFormat, GlError> {
        match (format, ty) {
            (
                f,
                BYTE | UNSIGNED_BYTE | SHORT | UNSIGNED_SHORT | INT | UNSIGNED_INT | UNSIGNED_INT_2_10_10_10_REV_EXT,
            ) if es3 && crate::integer::is_integer_format(f) => Ok(ReadFormat::Int { format, ty }),
            (RGBA, UNSIGNED_BYTE) => Ok(ReadFormat::Rgba8),
            (BGRA_EXT, UNSIGNED_BYTE) => Ok(ReadFormat::Bgra8),
            (BGRA_EXT, UNSIGNED_SHORT_4_4_4_4_REV_EXT) => Ok(ReadFormat::Bgra4444Rev),
            (BGRA_EXT, UNSIGNED_SHORT_1_5_5_5_REV_EXT) => Ok(ReadFormat::Bgra1555Rev),
            (RED_EXT, UNSIGNED_BYTE) => Ok(ReadFormat::R8),
            (RG_EXT, UNSIGNED_BYTE) => Ok(ReadFormat::Rg8),
            (RGBA, HALF_FLOAT) => Ok(ReadFormat::Half(4)),
            (RGBA, FLOAT) if es3 => Ok(ReadFormat::Float(4)),
            (RG_EXT, FLOAT) if es3 => Ok(ReadFormat::Float(2)),
            (RED_EXT, FLOAT) if es3 => Ok(ReadFormat::Float(1)),
            (RGBA, UNSIGNED_INT_2_10_10_10_REV_EXT) if es3 => Ok(ReadFormat::Rgb10a2),
            (RGB, crate::packed_float::UNSIGNED_INT_10F_11F_11F_REV) if es3 => Ok(ReadFormat::Packed11),
            (RG_EXT, HALF_FLOAT) => Ok(ReadFormat::Half(2)),
            (RED_EXT, HALF_FLOAT) => Ok(ReadFormat::Half(1)),
            _ => {
                let format_known =
                    matches!(format, RGBA | RGB | ALPHA | LUMINANCE | LUMINANCE_ALPHA | BGRA_EXT | RED_EXT | RG_EXT)
                        || (es3 && crate::integer::is_integer_format(format));
                let type_known = type_size(ty).is_some()
                    || matches!(
                        ty,
                        UNSIGNED_SHORT_5_6_5
                            | UNSIGNED_SHORT_4_4_4_4
                            | UNSIGNED_SHORT_5_5_5_1
                            | UNSIGNED_SHORT_4_4_4_4_REV_EXT
                            | UNSIGNED_SHORT_1_5_5_5_REV_EXT
                    );
                Err(if format_known && type_known { GlError::InvalidOperation } else { GlError::InvalidEnum })
            }
        }
    }

    /// Bytes a pixel takes.
    fn bytes(self) -> usize {
        match self {
            ReadFormat::Rgba8 | ReadFormat::Bgra8 => 4,
            ReadFormat::Bgra4444Rev | ReadFormat::Bgra1555Rev | ReadFormat::Rg8 => 2,
            ReadFormat::R8 => 1,
            ReadFormat::Half(n) => 2 * n,
            ReadFormat::Int { format, ty } => crate::integer::pixel_bytes(format, ty),
            ReadFormat::Float(n) => 4 * n,
            ReadFormat::Rgb10a2 | ReadFormat::Packed11 => 4,
        }
    }

    /// Writes RGBA8 pixel `p` into `out` (`self.bytes()` long), converting an 8-bit component
    /// to `bits` with GL's rounding.
    fn write(self, p: &[u8], out: &mut [u8]) {
        let to = |c: u8, bits: u32| -> u16 {
            let max = (1u32 << bits) - 1;
            ((u32::from(c) * max + 127) / 255) as u16
        };
        match self {
            ReadFormat::Rgba8 => out.copy_from_slice(p),
            ReadFormat::Bgra8 => out.copy_from_slice(&[p[2], p[1], p[0], p[3]]),
            ReadFormat::R8 => out.copy_from_slice(&p[..1]),
            ReadFormat::Rg8 => out.copy_from_slice(&p[..2]),
            // Half-float and integer pixels are written from the image's own bytes
            // (`glReadPixels`).
            ReadFormat::Half(_)
            | ReadFormat::Int { .. }
            | ReadFormat::Float(_)
            | ReadFormat::Rgb10a2
            | ReadFormat::Packed11 => {}
            ReadFormat::Bgra4444Rev => {
                let v = to(p[2], 4) | to(p[1], 4) << 4 | to(p[0], 4) << 8 | to(p[3], 4) << 12;
                out.copy_from_slice(&v.to_ne_bytes());
            }
            ReadFormat::Bgra1555Rev => {
                let v = to(p[2], 5) | to(p[1], 5) << 5 | to(p[0], 5) << 10 | to(p[3], 1) << 15;
                out.copy_from_slice(&v.to_ne_bytes());
            }
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// Surface `surface`'s colour, RGBA8 rows from the bottom, read past every binding and pack
    /// parameter, after everything drawn to it (a pixmap surface's contents for its X pixmap).
    /// Not a surface of the display: `EGL_BAD_SURFACE`; too large for a reply: `EGL_BAD_ALLOC`.
    pub(super) fn strataReadSurface(&mut self, display: u32, surface: u32) -> Result<Bytes, i32> {
        self.check_display(display)?;
        let target = self.surfaces.get(&surface).map(|s| s.target.clone()).ok_or(crate::enums::EGL_BAD_SURFACE)?;
        let (w, h) = (target.width, target.height);
        if (w as usize).saturating_mul(h as usize).saturating_mul(4) > MAX_READ_BYTES {
            return Err(crate::enums::EGL_BAD_ALLOC);
        }
        Ok(Bytes(self.r.read_rgba(&target, [0, 0, w, h]).unwrap_or_default()))
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glReadPixels(
        &mut self,
        ctx: &mut Context,
        x: i32,
        y: i32,
        width: i32,
        height: i32,
        format: u32,
        pixel_type: u32,
    ) -> Bytes {
        if width < 0 || height < 0 {
            ctx.record(GlError::InvalidValue);
            return Bytes(Vec::new());
        }
        let float_depth = ctx.es3().then(|| float_depth(ctx));
        let how = match DepthRead::from_gl(format, pixel_type, float_depth) {
            Some(depth) => depth.map(Read::Depth),
            None => ReadFormat::from_gl(format, pixel_type, ctx.es3()).map(Read::Color),
        };
        let how = match how {
            Ok(how) => how,
            Err(e) => {
                ctx.record(e);
                return Bytes(Vec::new());
            }
        };
        let selected = match how {
            Read::Color(_) => crate::framebuffers::read_selected(ctx),
            Read::Depth(_) => Ok(()),
        };
        if let Err(e) = selected {
            ctx.record(e);
            return Bytes(Vec::new());
        }
        let Ok(target) = self.read_target(ctx) else {
            ctx.record(GlError::InvalidFramebufferOperation);
            return Bytes(Vec::new());
        };
        // ES 3.0 §4.3.1: a multisample read framebuffer is never read.
        if target.samples > 1 {
            ctx.record(GlError::InvalidOperation);
            return Bytes(Vec::new());
        }
        // An integer colour buffer reads only as integers of its signedness, and integers
        // only from one.
        if let Read::Color(c) = how {
            let fits = match (c, read_buffer_int(ctx)) {
                (ReadFormat::Int { format, ty }, Some(f)) => {
                    (format, ty) == (RGBA_INTEGER, if f.signed { INT } else { UNSIGNED_INT })
                        || (format, ty) == f.upload()
                }
                (ReadFormat::Int { .. }, None) | (_, Some(_)) => false,
                _ => true,
            };
            if !fits {
                ctx.record(GlError::InvalidOperation);
                return Bytes(Vec::new());
            }
        }
        // Each colour buffer reads as the formats and types ES 3.0 gives it, as on Mesa.
        if let Read::Color(c) = how {
            if !color_read_fits(c, &target, ctx.es3()) {
                ctx.record(GlError::InvalidOperation);
                return Bytes(Vec::new());
            }
        }
        let bpp = match how {
            Read::Color(c) => c.bytes(),
            Read::Depth(d) => {
                // The buffers it reads must be there.
                let (depth, stencil) = d.aspects();
                if (depth && !target.has_depth()) || (stencil && !target.has_stencil()) {
                    ctx.record(GlError::InvalidOperation);
                    return Bytes(Vec::new());
                }
                d.bytes()
            }
        };
        let align = ctx.pixel_store.pack_alignment.max(1) as usize;
        let (w, h) = (width as usize, height as usize);
        // The reply holds the whole rectangle: one beyond what a reply can carry cannot be
        // returned (GL's only error for a request too large to serve is OUT_OF_MEMORY).
        let row = (w * bpp).div_ceil(align) * align;
        if row.checked_mul(h).is_none_or(|n| n > MAX_READ_BYTES) {
            ctx.record(GlError::OutOfMemory);
            return Bytes(Vec::new());
        }
        let mut out = vec![0u8; packed_size(w, h, bpp, align)];
        // Only the part inside the framebuffer is defined; the rest stays zero. In i64: x and
        // y are the client's, and x + width may pass i32::MAX.
        let (x, y) = (i64::from(x), i64::from(y));
        let x0 = x.clamp(0, i64::from(target.width));
        let y0 = y.clamp(0, i64::from(target.height));
        let x1 = (x + i64::from(width)).clamp(0, i64::from(target.width));
        let y1 = (y + i64::from(height)).clamp(0, i64::from(target.height));
        if x1 > x0 && y1 > y0 {
            let rect = [x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32];
            let rw = rect[2] as usize;
            match how {
                Read::Color(ReadFormat::Float(n)) => {
                    if let Some(px) = self.r.read_floats(&target, rect) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            for (i, p) in px[r * rw..(r + 1) * rw].iter().enumerate() {
                                for (k, v) in p[..n].iter().enumerate() {
                                    let at = dst + i * bpp + k * 4;
                                    out[at..at + 4].copy_from_slice(&v.to_ne_bytes());
                                }
                            }
                        }
                    }
                }
                Read::Color(ReadFormat::Rgb10a2 | ReadFormat::Packed11) => {
                    // The buffer's own 32-bit texels.
                    if let Some(px) = self.r.read_stored(&target, rect) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            out[dst..dst + rw * 4].copy_from_slice(&px[r * rw * 4..(r + 1) * rw * 4]);
                        }
                    }
                }
                Read::Color(ReadFormat::Half(_)) => {
                    if let Some(px) = self.r.read_half(&target, rect) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            for (i, p) in px[r * rw * 8..(r + 1) * rw * 8].chunks_exact(8).enumerate() {
                                out[dst + i * bpp..dst + (i + 1) * bpp].copy_from_slice(&p[..bpp]);
                            }
                        }
                    }
                }
                Read::Color(ReadFormat::Int { format: to, ty }) => {
                    let format = target.color.as_ref().map(|(t, _)| t.format());
                    let texel = format.and_then(|f| f.block_copy_size(None)).unwrap_or(16) as usize;
                    if let (Some(px), Some(format)) = (self.r.read_stored(&target, rect), format) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            for (i, t) in px[r * rw * texel..(r + 1) * rw * texel].chunks_exact(texel).enumerate() {
                                let v = crate::integer::widen(t, format);
                                let v = crate::integer::present(v, target.absent);
                                crate::integer::pack(v, to, ty, &mut out[dst + i * bpp..dst + (i + 1) * bpp]);
                            }
                        }
                    }
                }
                Read::Color(how) => {
                    if let Some(px) = self.r.read_rgba(&target, rect) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            let src = &px[r * rw * 4..(r + 1) * rw * 4];
                            for (i, p) in src.chunks_exact(4).enumerate() {
                                how.write(p, &mut out[dst + i * bpp..dst + (i + 1) * bpp]);
                            }
                        }
                    }
                }
                Read::Depth(d) => {
                    // Framebuffer 0 of a reversed-Z surface stores 1 − GL's depth.
                    let reversed = self.reversed_framebuffer(ctx.bindings.read_framebuffer).is_some();
                    let bits = target.depth.as_ref().map_or(24, |(_, f)| depth_bits(*f));
                    if let Some((depths, stencils)) = self.r.read_depth_stencil(&target, rect, d.aspects().1) {
                        for r in 0..rect[3] as usize {
                            let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * bpp;
                            for i in 0..rw {
                                let stored = depths.get(r * rw + i).copied().unwrap_or(0.0);
                                let depth = if reversed { Mirror::depth(stored) } else { stored };
                                let stencil = stencils.get(r * rw + i).copied().unwrap_or(0);
                                d.write(depth, bits, stencil, &mut out[dst + i * bpp..dst + (i + 1) * bpp]);
                            }
                        }
                    }
                }
            }
        }
        Bytes(out)
    }
}

/// Whether colour read `c` may read `target`'s read buffer (integer reads are checked before):
/// `GL_RGBA`/`GL_FLOAT` any float buffer, and each buffer its implementation read format (a
/// half-float one's channels as `GL_HALF_FLOAT`, a 32-bit float one's as `GL_FLOAT`, the packed
/// formats' own types); in ES 3.0 (`es3`) float and 10-bit buffers are not read as `GL_RGBA`
/// (10-bit: but for `GL_RGBA`), `GL_RED` or `GL_RG` bytes, as on Mesa. The BGRA reads
/// (`GL_EXT_read_format_bgra`) read every one.
fn color_read_fits(c: ReadFormat, target: &crate::render::Target, es3: bool) -> bool {
    use wgpu::TextureFormat as F;
    let format = target.color_format();
    let absent = target.absent;
    let channels = if absent.contains(wgpu::ColorWrites::GREEN) {
        1
    } else if absent.contains(wgpu::ColorWrites::BLUE) {
        2
    } else {
        4
    };
    let ten = format == Some(F::Rgb10a2Unorm);
    match c {
        ReadFormat::Float(4) => target.float(),
        ReadFormat::Float(n) => format == Some(F::Rgba32Float) && n == channels,
        ReadFormat::Half(n) => format == Some(F::Rgba16Float) && n == channels,
        ReadFormat::Rgb10a2 => ten,
        ReadFormat::Packed11 => format == Some(F::Rg11b10Ufloat),
        ReadFormat::Rgba8 => !(es3 && target.float()),
        ReadFormat::R8 | ReadFormat::Rg8 => !(es3 && (target.float() || ten)),
        ReadFormat::Bgra8 | ReadFormat::Bgra4444Rev | ReadFormat::Bgra1555Rev | ReadFormat::Int { .. } => true,
    }
}

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
    /// `GL_DEPTH_COMPONENT`, `GL_UNSIGNED_INT_24_8` (ES 3.0): depth in the top 24 bits, the
    /// rest 0.
    Depth24,
    /// `GL_DEPTH_COMPONENT`, `GL_FLOAT` (ES 3.0, float depth buffers): the stored value.
    DepthFloat,
}

impl DepthRead {
    /// The read `format` and `ty` ask for when `format` is a depth or stencil one, or the error
    /// for the pair: `None` for other formats. ES 3.0 (`float_depth`: `Some(whether the read
    /// framebuffer's depth is float)`) adds `GL_UNSIGNED_INT_24_8` and, for float depth alone,
    /// `GL_FLOAT`; float depth is read as nothing else, as on Mesa.
    pub fn from_gl(format: u32, ty: u32, float_depth: Option<bool>) -> Option<Result<DepthRead, GlError>> {
        let read = match (format, ty, float_depth) {
            (DEPTH_COMPONENT, FLOAT, Some(true)) => DepthRead::DepthFloat,
            (DEPTH_COMPONENT, UNSIGNED_SHORT | UNSIGNED_INT | UNSIGNED_INT_24_8_OES | FLOAT, Some(f)) => {
                match (ty, f) {
                    (UNSIGNED_SHORT, false) => DepthRead::Depth16,
                    (UNSIGNED_INT, false) => DepthRead::Depth32,
                    (UNSIGNED_INT_24_8_OES, false) => DepthRead::Depth24,
                    _ => return Some(Err(GlError::InvalidOperation)),
                }
            }
            (DEPTH_COMPONENT, UNSIGNED_SHORT, None) => DepthRead::Depth16,
            (DEPTH_COMPONENT, UNSIGNED_INT, None) => DepthRead::Depth32,
            (DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES, _) => DepthRead::DepthStencil,
            (STENCIL_INDEX_OES, UNSIGNED_BYTE, _) => DepthRead::Stencil8,
            (DEPTH_COMPONENT | DEPTH_STENCIL_OES | STENCIL_INDEX_OES, _, _) => {
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
            DepthRead::Depth32 | DepthRead::DepthStencil | DepthRead::Depth24 | DepthRead::DepthFloat => 4,
            DepthRead::Stencil8 => 1,
        }
    }

    /// Whether it reads depth, and whether stencil.
    pub fn aspects(self) -> (bool, bool) {
        match self {
            DepthRead::Depth16 | DepthRead::Depth32 | DepthRead::Depth24 | DepthRead::DepthFloat => (true, false),
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
            DepthRead::Depth24 => out.copy_from_slice(&(n24 << 8).to_ne_bytes()),
            DepthRead::DepthFloat => out.copy_from_slice(&depth.to_ne_bytes()),
        }
    }
}

/// Whether the read framebuffer's depth is ES 3.0's float depth (`GL_DEPTH_COMPONENT32F` or
/// `GL_DEPTH32F_STENCIL8`, a renderbuffer or a texture); framebuffer 0's never is.
fn float_depth(ctx: &Context) -> bool {
    use crate::objects::framebuffer::Attachment;
    let bound = ctx.bindings.read_framebuffer;
    let Some(fb) = ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) else { return false };
    let format = match fb.depth {
        Attachment::Renderbuffer(n) => ctx.objects.renderbuffers.get(&n).map(|rb| rb.format),
        Attachment::Texture { name, .. } => {
            ctx.objects.textures.get(&name).map(|t| if t.sized != 0 { t.sized } else { t.format })
        }
        Attachment::None => None,
    };
    matches!(format, Some(DEPTH_COMPONENT32F | DEPTH32F_STENCIL8))
}

/// The integer format of the read framebuffer's read buffer, if it holds integers: what
/// `GL_IMPLEMENTATION_COLOR_READ_FORMAT` and `_TYPE` answer for.
pub(crate) fn read_buffer_int(ctx: &Context) -> Option<crate::integer::IntFormat> {
    use crate::objects::framebuffer::Attachment;
    let bound = ctx.bindings.read_framebuffer;
    let fb = ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0)?;
    let slot = fb.read.checked_sub(COLOR_ATTACHMENT0)? as usize;
    match *fb.colors.get(slot)? {
        Attachment::Renderbuffer(n) => crate::integer::IntFormat::from_gl(ctx.objects.renderbuffers.get(&n)?.format),
        Attachment::Texture { name, .. } => crate::integer::IntFormat::from_gl(ctx.objects.textures.get(&name)?.sized),
        Attachment::None => None,
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
        assert_eq!(DepthRead::from_gl(DEPTH_COMPONENT, UNSIGNED_BYTE, None), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(DEPTH_COMPONENT, FLOAT, None), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(DEPTH_STENCIL_OES, UNSIGNED_INT, None), Some(Err(GlError::InvalidOperation)));
        assert_eq!(DepthRead::from_gl(RGBA, UNSIGNED_BYTE, None), None);
    }
}

//! Pixel transfer to the client: `glReadPixels` honouring `PACK_ALIGNMENT` (uploads are in
//! `unpack`).

use super::context::Context;
use strata_protocol::Bytes;

use super::conv::type_size;
use super::enums::*;
use super::error::GlError;
use super::GlesExecutor;

/// The largest `glReadPixels` reply: half the protocol's message limit.
const MAX_READ_BYTES: usize = strata_protocol::codec::MAX_MESSAGE_LEN / 2;

/// Bytes a `width`×`height` image of `bpp`-byte pixels occupies with `alignment` row padding
/// (the last row unpadded).
fn packed_size(width: usize, height: usize, bpp: usize, alignment: usize) -> usize {
    if width == 0 || height == 0 {
        return 0;
    }
    let row = (width * bpp).div_ceil(alignment) * alignment;
    row * (height - 1) + width * bpp
}

#[allow(non_snake_case)]
impl GlesExecutor {
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
        if !(format == RGBA && pixel_type == UNSIGNED_BYTE) {
            let known =
                matches!(format, RGBA | RGB | ALPHA | LUMINANCE | LUMINANCE_ALPHA) && type_size(pixel_type).is_some();
            ctx.record(if known { GlError::InvalidOperation } else { GlError::InvalidEnum });
            return Bytes(Vec::new());
        }
        let Ok(target) = self.draw_target(ctx) else {
            ctx.record(GlError::InvalidFramebufferOperation);
            return Bytes(Vec::new());
        };
        let align = ctx.pixel_store.pack_alignment.max(1) as usize;
        let (w, h) = (width as usize, height as usize);
        // The reply holds the whole rectangle: one beyond what a reply can carry cannot be
        // returned (GL's only error for a request too large to serve is OUT_OF_MEMORY).
        let row = (w * 4).div_ceil(align) * align;
        if row.checked_mul(h).is_none_or(|n| n > MAX_READ_BYTES) {
            ctx.record(GlError::OutOfMemory);
            return Bytes(Vec::new());
        }
        let mut out = vec![0u8; packed_size(w, h, 4, align)];
        // Only the part inside the framebuffer is defined; the rest stays zero. In i64: x and
        // y are the client's, and x + width may pass i32::MAX.
        let (x, y) = (i64::from(x), i64::from(y));
        let x0 = x.clamp(0, i64::from(target.width));
        let y0 = y.clamp(0, i64::from(target.height));
        let x1 = (x + i64::from(width)).clamp(0, i64::from(target.width));
        let y1 = (y + i64::from(height)).clamp(0, i64::from(target.height));
        if x1 > x0 && y1 > y0 {
            let rect = [x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32];
            if let Some(px) = self.r.read_rgba(&target, rect) {
                let cw = rect[2] as usize * 4;
                for r in 0..rect[3] as usize {
                    let dst = (r + (y0 - y) as usize) * row + (x0 - x) as usize * 4;
                    out[dst..dst + cw].copy_from_slice(&px[r * cw..(r + 1) * cw]);
                }
            }
        }
        Bytes(out)
    }
}

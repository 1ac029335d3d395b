//! ES 3.0's `glBlitFramebuffer`, colour only: checked in the order of Mesa's `blit.c`, the
//! rectangles clipped to the pixels whose centres map inside the read buffer and fall inside
//! the draw framebuffer and the scissor, then drawn by the renderer (`render::blit`) into every
//! draw buffer; a multisample read buffer is resolved first (`Renderer::resolve`). Depth and
//! stencil blits are refused for now.

use crate::context::Context;
use crate::conv::clip_rect;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::objects::framebuffer::{Attachment, Framebuffer};
use crate::render::Blit;
use crate::GlesExecutor;

/// The destination pixels along one axis whose centres map inside `[0, src_size)` of the
/// source and lie inside `[lo, hi)`: the first and one past the last. `s` and `d` are the
/// rectangles' corners on this axis, in the order given.
fn axis(s: [i32; 2], d: [i32; 2], src_size: u32, [lo, hi]: [i64; 2]) -> [i64; 2] {
    let (s0, s1, d0, d1) = (f64::from(s[0]), f64::from(s[1]), f64::from(d[0]), f64::from(d[1]));
    // Where the source's two edges land in the destination.
    let at = |v: f64| d0 + (v - s0) * (d1 - d0) / (s1 - s0);
    let (a, b) = (at(0.0), at(f64::from(src_size)));
    let (inside_lo, inside_hi) = (a.min(b), a.max(b));
    // Pixel x is drawn when x + 0.5 lies in [inside_lo, inside_hi) and in the destination.
    let first = ((inside_lo - 0.5).ceil() as i64).max(i64::from(d[0].min(d[1]))).max(lo);
    let end = ((inside_hi - 0.5).ceil() as i64).min(i64::from(d[0].max(d[1]))).min(hi);
    [first, end.max(first)]
}

/// The internal format of the read buffer and of each draw buffer, as a resolve compares
/// them (as Mesa's `compatible_resolve_formats` does): unsized formats as their 8-bit sized
/// ones, sRGB as linear; `None` while the read framebuffer is the window's.
fn resolve_formats(ctx: &Context) -> Option<(u32, Vec<u32>)> {
    let of = |a: Attachment| {
        let f = match a {
            Attachment::Renderbuffer(n) => ctx.objects.renderbuffers.get(&n).map_or(0, |r| r.format),
            Attachment::Texture { name, .. } => {
                ctx.objects.textures.get(&name).map_or(0, |t| if t.sized != 0 { t.sized } else { t.format })
            }
            Attachment::None => 0,
        };
        match f {
            RGBA | SRGB8_ALPHA8 => RGBA8_OES,
            RGB | SRGB8 => RGB8_OES,
            f => f,
        }
    };
    let selected = |fb: &Framebuffer, buffer: u32| {
        buffer.checked_sub(COLOR_ATTACHMENT0).and_then(|i| fb.colors.get(i as usize)).copied()
    };
    let read =
        ctx.objects.framebuffers.get(&ctx.bindings.read_framebuffer).filter(|_| ctx.bindings.read_framebuffer != 0)?;
    let read = of(selected(read, read.read)?);
    let draw = match ctx.objects.framebuffers.get(&ctx.bindings.framebuffer).filter(|_| ctx.bindings.framebuffer != 0) {
        Some(fb) => {
            fb.draw_buffers.iter().filter_map(|b| selected(fb, *b)).filter(|a| *a != Attachment::None).map(of).collect()
        }
        None => vec![if ctx.config.rgba[3] == 0 { RGB8_OES } else { RGBA8_OES }],
    };
    Some((read, draw))
}

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glBlitFramebuffer(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        src_x0: i32,
        src_y0: i32,
        src_x1: i32,
        src_y1: i32,
        dst_x0: i32,
        dst_y0: i32,
        dst_x1: i32,
        dst_y1: i32,
        mask: u32,
        filter: u32,
    ) -> GlResult {
        let (Ok(read), Ok(draw)) = (self.read_target(ctx), self.draw_target(ctx)) else {
            return Err(GlError::InvalidFramebufferOperation);
        };
        if !matches!(filter, NEAREST | LINEAR) {
            return Err(GlError::InvalidEnum);
        }
        if mask & !(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT) != 0 {
            return Err(GlError::InvalidValue);
        }
        let depth_stencil = mask & (DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT);
        if depth_stencil != 0 && filter != NEAREST {
            return Err(GlError::InvalidOperation);
        }
        // ES 3.0 §4.3.3: a multisample draw framebuffer is never blitted into, and a
        // multisample read framebuffer is resolved region for region, never scaled or moved.
        if draw.samples > 1 {
            return Err(GlError::InvalidOperation);
        }
        let resolve = read.samples > 1;
        if resolve && [src_x0, src_y0, src_x1, src_y1] != [dst_x0, dst_y0, dst_x1, dst_y1] {
            return Err(GlError::InvalidOperation);
        }
        // A buffer missing on either side is left out, silently (as GL says).
        let depth = mask & DEPTH_BUFFER_BIT != 0 && read.has_depth() && draw.has_depth();
        let stencil = mask & STENCIL_BUFFER_BIT != 0 && read.has_stencil() && draw.has_stencil();
        if depth || stencil {
            tracing::warn!("glBlitFramebuffer: depth and stencil blits are not supported yet");
            return Err(GlError::InvalidOperation);
        }
        let color = mask & COLOR_BUFFER_BIT != 0 && read.color.is_some() && draw.has_color();
        let Some((src, _)) = read.color.as_ref().filter(|_| color) else { return Ok(()) };
        let at = read.color_at;
        // ES 3.0: the read buffer may not be a draw buffer (the same level, layer and face).
        if draw.color.as_ref().is_some_and(|(t, _)| t == src && draw.color_at == at) {
            return Err(GlError::InvalidOperation);
        }
        // ES 3.0 §4.3.3: integer colour goes only to integer buffers of its signedness, and is
        // never filtered linearly.
        let kind = |f: wgpu::TextureFormat| match f.sample_type(None, None) {
            Some(wgpu::TextureSampleType::Sint) => Some(true),
            Some(wgpu::TextureSampleType::Uint) => Some(false),
            _ => None,
        };
        let src_kind = kind(src.format());
        if draw.slots().iter().flatten().any(|s| kind(s.2) != src_kind) || (src_kind.is_some() && filter == LINEAR) {
            return Err(GlError::InvalidOperation);
        }
        // A resolve goes only into buffers of the read buffer's internal format (sRGB or not).
        if resolve && resolve_formats(ctx).is_some_and(|(r, d)| d.iter().any(|f| *f != r)) {
            return Err(GlError::InvalidOperation);
        }
        let empty = src_x0 == src_x1 || src_y0 == src_y1 || dst_x0 == dst_x1 || dst_y0 == dst_y1;
        if empty || ctx.conditional == Some(false) {
            return Ok(());
        }
        let size = (read.width, read.height);
        let [sx, sy, sw, sh] = match ctx.raster.scissor_test {
            true => clip_rect(ctx.raster.scissor, &draw),
            false => [0, 0, draw.width, draw.height],
        };
        let (x_range, y_range) = ([i64::from(sx), i64::from(sx + sw)], [i64::from(sy), i64::from(sy + sh)]);
        let [x0, x1] = axis([src_x0, src_x1], [dst_x0, dst_x1], size.0, x_range);
        let [y0, y1] = axis([src_y0, src_y1], [dst_y0, dst_y1], size.1, y_range);
        let clip = [x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32];
        let slots = draw.slots();
        let dst = slots
            .iter()
            .enumerate()
            .filter_map(|(i, s)| {
                let (view, absent, format) = (*s)?;
                Some((view, format, wgpu::ColorWrites::ALL - absent, draw.slices.get(i).copied().flatten()))
            })
            .collect();
        // The samples of each pixel averaged first, into an image the blit then copies from.
        let resolved = resolve.then(|| self.r.resolve(flushed, src));
        let (src, at) = match &resolved {
            Some(r) => (r, Default::default()),
            None => (src, at),
        };
        let blit = Blit {
            src: (src, at, size),
            dst,
            src_rect: [src_x0, src_y0, src_x1, src_y1],
            dst_rect: [dst_x0, dst_y0, dst_x1, dst_y1],
            clip,
            linear: filter == LINEAR,
        };
        self.r.blit(flushed, &blit);
        Ok(())
    }
}

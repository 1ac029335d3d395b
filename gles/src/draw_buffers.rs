//! `GL_EXT_draw_buffers` / `GL_NV_draw_buffers`: `glDrawBuffersEXT` selects, per fragment
//! output, the colour buffer it writes. The default framebuffer has one output, `GL_BACK` or
//! `GL_NONE`; a framebuffer object's output `i` writes `GL_COLOR_ATTACHMENTi` or nothing.
//! Validated in Mesa's order, which was probed: the count, then each buffer in turn.

use crate::context::Context;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_DRAW_BUFFERS;
use crate::GlesExecutor;

/// `GL_DRAW_BUFFERi_EXT`: what fragment output `i` writes.
pub(super) fn draw_buffer(ctx: &Context, i: usize) -> u32 {
    let bound = ctx.bindings.framebuffer;
    match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb.draw_buffers.get(i).copied().unwrap_or(NONE),
        None if i == 0 && !ctx.draw_none => BACK,
        None => NONE,
    }
}

/// Whether `buffer` is an enum a draw buffer can name at all (Mesa answers
/// `GL_INVALID_OPERATION` for these when they do not fit, `GL_INVALID_ENUM` for the rest).
fn known(buffer: u32) -> bool {
    buffer == BACK || (COLOR_ATTACHMENT0..COLOR_ATTACHMENT0 + 32).contains(&buffer)
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glDrawBuffersEXT(&mut self, ctx: &mut Context, buffers: strata_protocol::Slice<'_, u32>) -> GlResult {
        let bufs: Vec<u32> = buffers.iter().collect();
        if bufs.len() > MAX_DRAW_BUFFERS {
            return Err(GlError::InvalidValue);
        }
        let bound = ctx.bindings.framebuffer;
        let Some(fb) = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0) else {
            // The default framebuffer: exactly one buffer, the back buffer or none.
            ctx.draw_none = match bufs.as_slice() {
                [BACK] => false,
                [NONE] => true,
                _ => return Err(GlError::InvalidOperation),
            };
            return Ok(());
        };
        for (i, b) in bufs.iter().enumerate() {
            if *b == NONE || *b == COLOR_ATTACHMENT0 + i as u32 {
                continue;
            }
            return Err(if known(*b) { GlError::InvalidOperation } else { GlError::InvalidEnum });
        }
        fb.draw_buffers = [NONE; MAX_DRAW_BUFFERS];
        fb.draw_buffers[..bufs.len()].copy_from_slice(&bufs);
        Ok(())
    }
}

//! `GL_NV_read_buffer`: `glReadBufferNV` selects the colour buffer that `glReadPixels` and the
//! texture copies read: `GL_BACK` or `GL_NONE` for the default framebuffer, and
//! `GL_COLOR_ATTACHMENT0` or `GL_NONE` for a framebuffer object, each of which keeps its own.
//! Reading with `GL_NONE` selected is `GL_INVALID_OPERATION`, as on Mesa.

use super::context::Context;
use super::enums::*;
use super::error::{GlError, GlResult};
use super::GlesExecutor;

/// `GL_READ_BUFFER_NV`: the colour buffer reads use, or `GL_NONE`.
pub(super) fn read_buffer(ctx: &Context) -> u32 {
    let bound = ctx.bindings.framebuffer;
    let none = match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb.read_none,
        None => ctx.read_none,
    };
    match (none, bound) {
        (true, _) => NONE,
        (false, 0) => BACK,
        (false, _) => COLOR_ATTACHMENT0,
    }
}

/// `GL_INVALID_OPERATION` where reads have no colour buffer selected.
pub(super) fn read_selected(ctx: &Context) -> GlResult {
    if read_buffer(ctx) == NONE {
        return Err(GlError::InvalidOperation);
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glReadBufferNV(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        let bound = ctx.bindings.framebuffer;
        let attachment = (COLOR_ATTACHMENT0..COLOR_ATTACHMENT0 + 16).contains(&mode);
        let none = match mode {
            NONE => true,
            BACK if bound == 0 => false,
            COLOR_ATTACHMENT0 if bound != 0 => false,
            // The other framebuffer's buffers, and attachments past the one colour attachment.
            BACK => return Err(GlError::InvalidOperation),
            _ if attachment => return Err(GlError::InvalidOperation),
            _ => return Err(GlError::InvalidEnum),
        };
        match ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0) {
            Some(fb) => fb.read_none = none,
            None => ctx.read_none = none,
        }
        Ok(())
    }
}

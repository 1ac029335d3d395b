//! `GL_NV_read_buffer`: `glReadBufferNV` selects the colour buffer that `glReadPixels` and the
//! texture copies read: `GL_BACK` or `GL_NONE` for the default framebuffer, and one of the
//! colour attachments (`GL_NV_fbo_color_attachments`) or `GL_NONE` for a framebuffer object,
//! each of which keeps its own. It applies to the framebuffer bound for reading. Reading with `GL_NONE` selected, or from an attachment with
//! no image, is `GL_INVALID_OPERATION`, as on Mesa.

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::objects::framebuffer::{color_slot, Attachment};
use crate::GlesExecutor;

/// `GL_READ_BUFFER_NV`: the colour buffer reads use, or `GL_NONE`.
pub(super) fn read_buffer(ctx: &Context) -> u32 {
    let bound = ctx.bindings.read_framebuffer;
    match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb.read,
        None if ctx.read_none => NONE,
        None => BACK,
    }
}

/// `GL_INVALID_OPERATION` where reads have no colour buffer selected, or the selected
/// attachment has no image.
pub(super) fn read_selected(ctx: &Context) -> GlResult {
    let bound = ctx.bindings.read_framebuffer;
    let attached = match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb
            .read
            .checked_sub(COLOR_ATTACHMENT0)
            .and_then(|i| fb.colors.get(i as usize))
            .is_some_and(|a| *a != Attachment::None),
        None => !ctx.read_none,
    };
    if !attached {
        return Err(GlError::InvalidOperation);
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glReadBufferNV(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        let bound = ctx.bindings.read_framebuffer;
        let fb = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0);
        match (mode, fb) {
            (NONE, Some(fb)) => fb.read = NONE,
            (NONE, None) => ctx.read_none = true,
            (BACK, None) => ctx.read_none = false,
            // The other framebuffer's buffers, and attachments past the ones Strata has.
            (BACK, Some(_)) => return Err(GlError::InvalidOperation),
            (_, fb) => match (color_slot(mode, 32).ok_or(GlError::InvalidEnum)??, fb) {
                (_, Some(fb)) => fb.read = mode,
                (_, None) => return Err(GlError::InvalidOperation),
            },
        }
        Ok(())
    }
}

//! ES 3.0's `glInvalidateFramebuffer` and `glInvalidateSubFramebuffer`: a hint that the
//! attachments' contents are no longer needed, which Strata takes as `GL_EXT_discard_framebuffer`
//! does (nothing to do: every pass stores what it drew), after GL's checks in Mesa's order.

use strata_protocol::Slice;

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_DRAW_BUFFERS;
use crate::GlesExecutor;

/// `GL_DRAW_FRAMEBUFFER` and `GL_READ_FRAMEBUFFER` (ES 3.0).
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const READ_FRAMEBUFFER: u32 = 0x8CA8;
/// The default framebuffer's buffers as ES 3.0 names them (`GL_COLOR`, `GL_DEPTH`, `GL_STENCIL`).
const DEFAULT_BUFFERS: [u32; 3] = [0x1800, 0x1801, 0x1802];

/// Checks an invalidation of `attachments` of the framebuffer bound to `target`.
fn check(ctx: &Context, target: u32, attachments: &Slice<'_, u32>) -> GlResult {
    let framebuffer = match target {
        FRAMEBUFFER | DRAW_FRAMEBUFFER => ctx.bindings.framebuffer,
        READ_FRAMEBUFFER => ctx.bindings.read_framebuffer,
        _ => return Err(GlError::InvalidEnum),
    };
    for a in attachments.iter() {
        let ok = if framebuffer == 0 {
            DEFAULT_BUFFERS.contains(&a)
        } else if (COLOR_ATTACHMENT0..COLOR_ATTACHMENT0 + 32).contains(&a) {
            if a - COLOR_ATTACHMENT0 >= MAX_DRAW_BUFFERS as u32 {
                return Err(GlError::InvalidOperation);
            }
            true
        } else {
            matches!(a, DEPTH_ATTACHMENT | STENCIL_ATTACHMENT | DEPTH_STENCIL_ATTACHMENT)
        };
        if !ok {
            return Err(GlError::InvalidEnum);
        }
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glInvalidateFramebuffer(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachments: Slice<'_, u32>,
    ) -> GlResult {
        check(ctx, target, &attachments)
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glInvalidateSubFramebuffer(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachments: Slice<'_, u32>,
        _x: i32,
        _y: i32,
        width: i32,
        height: i32,
    ) -> GlResult {
        if width < 0 || height < 0 {
            return Err(GlError::InvalidValue);
        }
        check(ctx, target, &attachments)
    }
}

//! ES 3.0's buffer calls beyond ES 2.0's and the mapping extensions': copies between buffers
//! (`glCopyBufferSubData`, with the `GL_COPY_READ_BUFFER` and `GL_COPY_WRITE_BUFFER` bindings)
//! and 64-bit parameters (`glGetBufferParameteri64v`).

use crate::buffers::{bound, parameter};
use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::typed::BufferTarget;
use crate::GlesExecutor;

#[allow(non_snake_case)]
impl GlesExecutor {
    /// Copies `size` bytes from the buffer bound to `read_target` at `read_offset` to the one
    /// bound to `write_target` at `write_offset`, checked in Mesa's order: the targets, a
    /// buffer bound to each, neither mapped, no negative value, both ranges within their
    /// buffers, and (one buffer) ranges that do not overlap.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glCopyBufferSubData(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        read_target: u32,
        write_target: u32,
        read_offset: i64,
        write_offset: i64,
        size: i64,
    ) -> GlResult {
        let es3 = ctx.es3();
        let (src, dst) = (BufferTarget::from_gl(read_target, es3)?, BufferTarget::from_gl(write_target, es3)?);
        let (src, dst) = (ctx.bindings.buffer(src), ctx.bindings.buffer(dst));
        let (Some(s), Some(d)) = (ctx.objects.buffers.get(&src), ctx.objects.buffers.get(&dst)) else {
            return Err(GlError::InvalidOperation);
        };
        if src == 0 || dst == 0 || s.map.is_some() || d.map.is_some() {
            return Err(GlError::InvalidOperation);
        }
        if read_offset < 0 || write_offset < 0 || size < 0 {
            return Err(GlError::InvalidValue);
        }
        let within = |offset: i64, len: usize| offset.checked_add(size).is_some_and(|end| end as u64 <= len as u64);
        if !within(read_offset, s.data.len()) || !within(write_offset, d.data.len()) {
            return Err(GlError::InvalidValue);
        }
        if src == dst && read_offset < write_offset + size && write_offset < read_offset + size {
            return Err(GlError::InvalidValue);
        }
        let (from, to, n) = (read_offset as usize, write_offset as usize, size as usize);
        let bytes = s.data[from..from + n].to_vec();
        let gpu = &self.gpu;
        if let Some(d) = ctx.objects.buffers.get_mut(&dst) {
            d.write(gpu, flushed, to, &bytes);
        }
        Ok(())
    }

    /// A buffer's parameter as a 64-bit integer (its size and usage, and the mapping's state as
    /// `glGetBufferParameteriv` answers it); 0 after an error.
    pub(super) fn glGetBufferParameteri64v(&mut self, ctx: &mut Context, target: u32, pname: u32) -> i64 {
        let v = bound(ctx, target).and_then(|b| match pname {
            BUFFER_SIZE => Ok(b.data.len() as i64),
            BUFFER_USAGE => Ok(i64::from(if b.usage == 0 { STATIC_DRAW } else { b.usage })),
            _ => parameter(b, pname).map(i64::from).ok_or(GlError::InvalidEnum),
        });
        v.unwrap_or_else(|e| {
            ctx.record(e);
            0
        })
    }
}

//! `GL_EXT_draw_instanced`: `glDrawArraysInstancedEXT` and `glDrawElementsInstancedEXT` draw
//! `primcount` instances, each seeing its number as `gl_InstanceIDEXT` in the vertex shader.
//! The extension has no per-instance attributes, so every attribute still steps per vertex.
//! A negative count or instance count is `GL_INVALID_VALUE`; zero instances draw nothing.

use strata_protocol::Blob;

use crate::context::Context;
use crate::error::{GlError, GlResult};
use crate::indices::Indices;
use crate::GlesExecutor;

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glDrawArraysInstancedEXT(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        first: i32,
        count: i32,
        primcount: i32,
    ) -> GlResult {
        if first < 0 || count < 0 || primcount < 0 {
            return Err(GlError::InvalidValue);
        }
        self.draw_instances(ctx, mode, count as u32, None, first as u32, primcount as u32)
    }

    pub(super) fn glDrawElementsInstancedEXT(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        offset: u64,
        primcount: i32,
    ) -> GlResult {
        if count < 0 || primcount < 0 {
            return Err(GlError::InvalidValue);
        }
        let indices = Some((index_type, Indices::Buffer(offset)));
        self.draw_instances(ctx, mode, count as u32, indices, 0, primcount as u32)
    }

    pub(super) fn strataDrawElementsInstancedData(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        indices: Blob<'_>,
        primcount: i32,
    ) -> GlResult {
        if count < 0 || primcount < 0 {
            return Err(GlError::InvalidValue);
        }
        let indices = Some((index_type, Indices::Client(indices.as_bytes())));
        self.draw_instances(ctx, mode, count as u32, indices, 0, primcount as u32)
    }
}

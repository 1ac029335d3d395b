//! Vertex array objects (`GL_OES_vertex_array_object`): named containers of the vertex attribute
//! arrays (enables, pointers, their buffers) and the element array buffer binding.
//!
//! The bound vertex array's state lives in the context itself (`Context::attribs` and
//! `Bindings::element_buffer`), where draws and the vertex and buffer calls use it; the ones
//! not bound keep theirs in `Objects::vertex_arrays` (vertex array 0, the default, included
//! while another is bound). Binding exchanges the two. Current attribute values
//! (`glVertexAttrib*`) are context state, not vertex array state, so they stay where they are.

use strata_protocol::Slice;

use crate::context::Context;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::objects::vertex_array::VertexArray;
use crate::GlesExecutor;

/// Exchanges the context's vertex array state with `vao`'s, keeping the current values.
fn exchange(ctx: &mut Context, vao: &mut VertexArray) {
    for (bound, stored) in ctx.attribs.iter_mut().zip(vao.attribs.iter_mut()) {
        let current = bound.current;
        std::mem::swap(bound, stored);
        bound.current = current;
    }
    std::mem::swap(&mut ctx.bindings.element_buffer, &mut vao.element_buffer);
}

/// Binds vertex array `array`, which must exist (`GL_INVALID_OPERATION` otherwise).
fn bind(ctx: &mut Context, array: u32) -> GlResult {
    let old = ctx.bindings.vertex_array;
    if array == old {
        return Ok(());
    }
    let mut next = ctx.objects.vertex_arrays.remove(&array).ok_or(GlError::InvalidOperation)?;
    exchange(ctx, &mut next);
    next.ever_bound = true;
    ctx.objects.vertex_arrays.insert(old, next);
    ctx.bindings.vertex_array = array;
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenVertexArraysOES(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let bound = ctx.bindings.vertex_array;
        // The bound array is not in the table (its state is the context's) and stays as it is.
        let fresh = || names.iter().filter(move |&n| n != bound);
        self.admit(ctx, strata_device::account::Kind::VertexArray, ctx.objects.vertex_arrays.fresh(fresh()))?;
        ctx.objects.vertex_arrays.generate(fresh());
        Ok(())
    }

    pub(super) fn glBindVertexArrayOES(&mut self, ctx: &mut Context, array: u32) -> GlResult {
        bind(ctx, array)
    }

    /// Deleting the bound vertex array binds the default one; unknown names and 0 are ignored.
    pub(super) fn glDeleteVertexArraysOES(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let bound = ctx.bindings.vertex_array;
        if bound != 0 && names.iter().any(|n| n == bound) {
            bind(ctx, 0)?;
        }
        for n in ctx.objects.vertex_arrays.delete(names.iter()) {
            ctx.objects.forget_label(VERTEX_ARRAY_KHR, n);
        }
        Ok(())
    }

    pub(super) fn glIsVertexArrayOES(&mut self, ctx: &mut Context, array: u32) -> bool {
        array != 0
            && (array == ctx.bindings.vertex_array
                || ctx.objects.vertex_arrays.get(&array).is_some_and(|v| v.ever_bound))
    }
}

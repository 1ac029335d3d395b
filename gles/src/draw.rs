//! Drawing: `glClear`, `glDrawArrays` and `glDrawElements` (with buffer or client-side
//! indices) and the extensions' draws, `glFlush` and `glFinish`. Each draw asks `draw_state`
//! what it uses and `draw_plan` for its plan, and records it into the target's pass.
//!
//! `GL_OES_draw_elements_base_vertex`: `glDrawElementsBaseVertexOES` adds a base vertex to
//! every index the draw reads. The indices (from the element buffer, or sent along) are read
//! and validated as `glDrawElements` reads them, offset, and drawn as 32-bit indices sent along.
//! An index that the base takes below 0 or to 0xFFFFFFFF (undefined in GL) drops the draw.
//!
//! `GL_EXT_draw_instanced`: `glDrawArraysInstancedEXT` and `glDrawElementsInstancedEXT` draw
//! `primcount` instances, each seeing its number as `gl_InstanceIDEXT` in the vertex shader.
//! The extension has no per-instance attributes, so every attribute still steps per vertex.
//! A negative count or instance count is `GL_INVALID_VALUE`; zero instances draw nothing.
//!
//! `GL_EXT_multi_draw_arrays`: `glMultiDrawArraysEXT` and `glMultiDrawElementsEXT` draw once
//! per entry of their arrays, and with `GL_OES_draw_elements_base_vertex`
//! `glMultiDrawElementsBaseVertexEXT` adds a base vertex per entry. Validation is Mesa's on an
//! ES 2.0 context: the draw count, then the mode and index type, then every count, before
//! anything is drawn. A negative `first` draws nothing and is no error, as on Mesa.

use crate::context::Context;
use crate::conv::{clip_rect, color_writes, Mirror};
use crate::draw_plan::{plan_draw, Instancing};
use crate::draw_state::DrawState;
use crate::enums::UNSIGNED_INT;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::indices::{index_values, Indices};
use crate::typed::{IndexType, Primitive};
use crate::GlesExecutor;
use strata_protocol::Blob;
use strata_protocol::Slice;

#[allow(non_snake_case)]
impl GlesExecutor {
    /// Validates a draw, plans it and records it into the target's pass.
    pub(super) fn draw(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: u32,
        indices: Option<(u32, Indices<'_>)>,
        first: u32,
    ) -> GlResult {
        self.draw_instances(ctx, mode, count, indices, first, 1)
    }

    /// [`Self::draw`] of `instances` instances (`GL_EXT_draw_instanced`). Points, which are
    /// already drawn one instance per point, are drawn once per instance, each told its number.
    pub(super) fn draw_instances(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: u32,
        indices: Option<(u32, Indices<'_>)>,
        first: u32,
        instances: u32,
    ) -> GlResult {
        let prim = Primitive::from_gl(mode)?;
        let indices = match indices {
            Some((ty, i)) => Some((IndexType::from_gl(ty)?, i)),
            None => None,
        };
        let capture = self.capture_plan(ctx, prim, count, indices.is_some(), instances)?;
        let Some(DrawState { target, reversed, stages }) = self.draw_state(ctx, prim == Primitive::Points)? else {
            return Ok(());
        };
        let capture_stage = match &capture {
            Some(c) => match self.capture_stage(ctx, prim == Primitive::Points, c.unroll) {
                Ok(vs) => Some(vs),
                Err(e) => {
                    tracing::warn!("draw dropped: the program's capturing vertex stage failed: {e}");
                    return Ok(());
                }
            },
            None => None,
        };
        let plans = if prim == Primitive::Points { instances } else { instances.min(1) };
        for instance in 0..plans {
            let unroll = capture.as_ref().is_some_and(|c| c.unroll);
            let shape = Instancing { instance, instances, unroll };
            let Some(mut spec) = plan_draw(ctx, &target, reversed, prim, count, indices, first, shape)? else {
                return Ok(());
            };
            // Validated, and discarded by a conditional render whose query passed no sample,
            // or by GL_RASTERIZER_DISCARD where nothing is captured.
            if ctx.conditional == Some(false) || (ctx.raster.discard && capture.is_none()) {
                return Ok(());
            }
            if let Some((vs, fs)) = stages.clone() {
                spec.vs = vs;
                spec.fs = fs;
            }
            if let (Some(plan), Some(vs)) = (&capture, &capture_stage) {
                // Points draw one instance at a time: each writes after the ones before.
                let done = if prim == Primitive::Points { instance } else { 0 };
                spec.capture = self.capture_binding(ctx, plan, first, done);
                spec.vs = vs.clone();
                spec.fs = None;
            }
            self.r.draw(&target, spec);
        }
        if let Some(plan) = &capture {
            self.captured(ctx, plan, instances);
        }
        Ok(())
    }

    pub(super) fn glDrawArrays(&mut self, ctx: &mut Context, mode: u32, first: i32, count: i32) -> GlResult {
        if first < 0 || count < 0 {
            return Err(GlError::InvalidValue);
        }
        self.draw(ctx, mode, count as u32, None, first as u32)
    }

    pub(super) fn glDrawElements(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        offset: u64,
    ) -> GlResult {
        if count < 0 {
            return Err(GlError::InvalidValue);
        }
        self.draw(ctx, mode, count as u32, Some((index_type, Indices::Buffer(offset))), 0)
    }

    pub(super) fn strataDrawElementsData(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        indices: Blob<'_>,
    ) -> GlResult {
        if count < 0 {
            return Err(GlError::InvalidValue);
        }
        self.draw(ctx, mode, count as u32, Some((index_type, Indices::Client(indices.as_bytes()))), 0)
    }

    pub(super) fn glClear(&mut self, ctx: &mut Context, mask: u32) -> GlResult {
        if mask & !(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT) != 0 {
            return Err(GlError::InvalidValue);
        }
        let target = self.draw_target(ctx).map_err(|_| GlError::InvalidFramebufferOperation)?;
        let reversed = self.reversed_target(ctx).is_some();
        let renderer = &mut self.r;
        let (ds, blend) = (&ctx.depth_stencil, &ctx.blend);
        let writes = color_writes(blend.color_mask);
        let color = (mask & COLOR_BUFFER_BIT != 0 && target.has_color() && !writes.is_empty()).then(|| {
            // A float buffer takes the colour as it is (ES 3.0 keeps it unclamped); fixed-point
            // buffers beside it clamp what they store.
            let c = if target.any_float() { blend.clear_color } else { blend.clear_color.map(|c| c.clamp(0.0, 1.0)) };
            (c, writes, None)
        });
        let clear_depth = if reversed { Mirror::depth(ds.clear_depth) } else { ds.clear_depth };
        let depth =
            (mask & DEPTH_BUFFER_BIT != 0 && target.has_depth() && ds.depth_mask).then_some((clear_depth, true));
        let stencil = (mask & STENCIL_BUFFER_BIT != 0 && target.has_stencil() && ds.stencil[0].write & 0xff != 0)
            .then_some((ds.clear_stencil as u32 & 0xff, ds.stencil[0].write & 0xff));
        let scissor = ctx.raster.scissor_test.then(|| clip_rect(ctx.raster.scissor, &target));
        let none = color.is_none() && depth.is_none() && stencil.is_none();
        if none || ctx.conditional == Some(false) || ctx.raster.discard {
            return Ok(());
        }
        renderer.clear(&target, color, depth, stencil, scissor);
        Ok(())
    }

    pub(super) fn glFlush(&mut self, _ctx: &mut Context) -> GlResult {
        self.r.flush();
        Ok(())
    }

    /// `eglCreateSyncKHR`'s fence: flushes, and marks the point after every earlier command.
    pub(super) fn strataFence(&mut self, _ctx: &mut Context) -> u64 {
        self.r.fence()
    }

    pub(super) fn glFinish(&mut self, _ctx: &mut Context) {
        self.r.finish();
        // Every command before it has completed, the swaps too: their frames are published.
        if let Some((scene, client, _)) = &self.scene {
            scene.wait_published(*client);
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// A base-vertex draw of `count` indices of `index_type` from `indices`.
    pub(super) fn draw_base_vertex(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        indices: Indices<'_>,
        base: i32,
    ) -> GlResult {
        if count < 0 {
            return Err(GlError::InvalidValue);
        }
        Primitive::from_gl(mode)?;
        let ty = IndexType::from_gl(index_type)?;
        let (values, _, _) = index_values(ctx, ty, indices, count as u32)?;
        let offset = |v: u32| u32::try_from(i64::from(v) + i64::from(base)).ok().filter(|&i| i != u32::MAX);
        let Some(adjusted) = values.into_iter().map(offset).collect::<Option<Vec<u32>>>() else {
            tracing::debug!(base, "a base-vertex draw whose base takes an index out of range was dropped");
            return Ok(());
        };
        let bytes: &[u8] = bytemuck::cast_slice(&adjusted);
        self.draw(ctx, mode, count as u32, Some((UNSIGNED_INT, Indices::Client(bytes))), 0)
    }

    pub(super) fn glDrawElementsBaseVertexOES(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        offset: u64,
        base_vertex: i32,
    ) -> GlResult {
        self.draw_base_vertex(ctx, mode, count, index_type, Indices::Buffer(offset), base_vertex)
    }

    pub(super) fn strataDrawElementsBaseVertexData(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: i32,
        index_type: u32,
        indices: Blob<'_>,
        base_vertex: i32,
    ) -> GlResult {
        self.draw_base_vertex(ctx, mode, count, index_type, Indices::Client(indices.as_bytes()), base_vertex)
    }
}

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

/// The first `drawcount` entries of each array, validated: `GL_INVALID_VALUE` for a negative
/// draw count, a negative count, or an array shorter than the draw count.
fn entries<T: bytemuck::Pod>(drawcount: i32, counts: &Slice<'_, i32>, other: &Slice<'_, T>) -> GlResult<usize> {
    let n = usize::try_from(drawcount).map_err(|_| GlError::InvalidValue)?;
    if counts.len() < n || other.len() < n {
        return Err(GlError::InvalidValue);
    }
    Ok(n)
}

/// `GL_INVALID_VALUE` if any of the first `n` counts is negative.
fn counts_valid(counts: &Slice<'_, i32>, n: usize) -> GlResult {
    if counts.iter().take(n).any(|c| c < 0) {
        return Err(GlError::InvalidValue);
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glMultiDrawArraysEXT(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        first: Slice<'_, i32>,
        count: Slice<'_, i32>,
        drawcount: i32,
    ) -> GlResult {
        let n = entries(drawcount, &count, &first)?;
        Primitive::from_gl(mode)?;
        counts_valid(&count, n)?;
        for (f, c) in first.iter().zip(count.iter()).take(n) {
            if f >= 0 && c > 0 {
                self.draw(ctx, mode, c as u32, None, f as u32)?;
            }
        }
        Ok(())
    }

    pub(super) fn glMultiDrawElementsEXT(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: Slice<'_, i32>,
        index_type: u32,
        offsets: Slice<'_, u64>,
        drawcount: i32,
    ) -> GlResult {
        let n = entries(drawcount, &count, &offsets)?;
        Primitive::from_gl(mode)?;
        IndexType::from_gl(index_type)?;
        counts_valid(&count, n)?;
        for (c, offset) in count.iter().zip(offsets.iter()).take(n).filter(|&(c, _)| c > 0) {
            self.draw(ctx, mode, c as u32, Some((index_type, Indices::Buffer(offset))), 0)?;
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glMultiDrawElementsBaseVertexEXT(
        &mut self,
        ctx: &mut Context,
        mode: u32,
        count: Slice<'_, i32>,
        index_type: u32,
        offsets: Slice<'_, u64>,
        drawcount: i32,
        base_vertex: Slice<'_, i32>,
    ) -> GlResult {
        let n = entries(drawcount, &count, &offsets)?;
        if base_vertex.len() < n {
            return Err(GlError::InvalidValue);
        }
        Primitive::from_gl(mode)?;
        IndexType::from_gl(index_type)?;
        counts_valid(&count, n)?;
        let draws = count.iter().zip(offsets.iter()).zip(base_vertex.iter()).take(n);
        for ((c, offset), base) in draws.filter(|&((c, _), _)| c > 0) {
            self.draw_base_vertex(ctx, mode, c, index_type, Indices::Buffer(offset), base)?;
        }
        Ok(())
    }
}

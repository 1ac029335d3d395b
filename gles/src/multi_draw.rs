//! `GL_EXT_multi_draw_arrays`: `glMultiDrawArraysEXT` and `glMultiDrawElementsEXT` draw once
//! per entry of their arrays, and with `GL_OES_draw_elements_base_vertex`
//! `glMultiDrawElementsBaseVertexEXT` adds a base vertex per entry. Validation is Mesa's on an
//! ES 2.0 context: the draw count, then the mode and index type, then every count, before
//! anything is drawn. A negative `first` draws nothing and is no error, as on Mesa.

use strata_protocol::Slice;

use crate::context::Context;
use crate::error::{GlError, GlResult};
use crate::indices::Indices;
use crate::typed::{IndexType, Primitive};
use crate::GlesExecutor;

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

//! `GL_OES_draw_elements_base_vertex`: `glDrawElementsBaseVertexOES` adds a base vertex to
//! every index the draw reads. The indices (from the element buffer, or sent along) are read
//! and validated as `glDrawElements` reads them, offset, and drawn as 32-bit indices sent along.
//! An index that the base takes below 0 or to 0xFFFFFFFF (undefined in GL) drops the draw.

use strata_protocol::Blob;

use crate::context::Context;
use crate::enums::UNSIGNED_INT;
use crate::error::{GlError, GlResult};
use crate::indices::{index_values, Indices};
use crate::typed::{IndexType, Primitive};
use crate::GlesExecutor;

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

//! A draw's indices: where they come from, how they are read and checked (robust contexts
//! reading what lies past the index data as 0), and what wgpu reads for them: the element
//! buffer itself, or a list generated per pass for loops, fans, byte indices and client data.

use crate::context::Context;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_CONVERTED;
use crate::render::Source;
use crate::typed::{IndexType, Primitive};

/// Where a draw's indices come from.
#[derive(Clone, Copy)]
pub(super) enum Indices<'a> {
    /// The bound element array buffer, at a byte offset.
    Buffer(u64),
    /// A client-side index array sent with the draw.
    Client(&'a [u8]),
}

/// A draw's indices: the index source wgpu reads, and how many vertices they reach.
pub(super) struct IndexPlan {
    /// The index buffer wgpu reads, if indexed.
    pub(super) index: Option<(Source, wgpu::IndexFormat)>,
    /// The vertices or indices wgpu draws.
    pub(super) count: u32,
    /// One more than the largest vertex the draw reads.
    pub(super) vertex_count: u64,
}

/// Reads a draw's `count` indices, checked against their source: the values, and the byte
/// offset and GPU buffer of an element array buffer (`None` for client indices).
pub(super) fn index_values<'c>(
    ctx: &'c Context,
    ty: IndexType,
    indices: Indices<'c>,
    count: u32,
) -> GlResult<(Vec<u32>, u64, Option<&'c wgpu::Buffer>)> {
    let (offset, gpu, data): (u64, Option<&wgpu::Buffer>, &[u8]) = match indices {
        Indices::Buffer(offset) => {
            let buf = ctx.objects.buffers.get(&ctx.bindings.element_buffer).ok_or(GlError::InvalidOperation)?;
            (offset, buf.gpu.as_ref(), &buf.data)
        }
        // Client indices are always rewritten into the per-pass ring.
        Indices::Client(bytes) => (0, None, bytes),
    };
    let end = offset.checked_add(u64::from(count) * ty.size());
    let bytes = match end.and_then(|e| data.get(offset as usize..e as usize)) {
        Some(bytes) => bytes,
        // Robust access: the indices past the data read as 0.
        None if ctx.robust => data.get(offset as usize..).unwrap_or(&[]),
        None => return Err(GlError::InvalidOperation),
    };
    let mut values: Vec<u32> = match ty {
        IndexType::U8 => bytes.iter().map(|&b| u32::from(b)).collect(),
        IndexType::U16 => bytes.chunks_exact(2).map(|c| u32::from(u16::from_ne_bytes([c[0], c[1]]))).collect(),
        IndexType::U32 => bytes.chunks_exact(4).map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])).collect(),
    };
    if values.len() < count as usize {
        generated_size(count)?;
        values.resize(count as usize, 0);
        // The element buffer holds too few: wgpu must not read it.
        return Ok((values, offset, None));
    }
    Ok((values, offset, gpu))
}

/// Refuses a draw whose generated index list (at most three indices per vertex, for a fan)
/// would pass `MAX_CONVERTED` bytes: `GL_OUT_OF_MEMORY`, where a count the client chose would
/// otherwise make the daemon allocate without bound.
pub(super) fn generated_size(count: u32) -> GlResult {
    if u64::from(count) * 12 > MAX_CONVERTED as u64 {
        return Err(GlError::OutOfMemory);
    }
    Ok(())
}

/// Validates a draw's indices (or its vertex range) and plans what wgpu reads: the element
/// buffer directly where wgpu can, else indices generated into the per-pass ring.
pub(super) fn plan_indices(
    ctx: &Context,
    prim: Primitive,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
) -> GlResult<IndexPlan> {
    let mut index: Option<(Source, wgpu::IndexFormat)> = None;
    let mut list: Option<Vec<u32>> = None;
    let vertex_count: u64;
    if let Some((ty, indices)) = indices {
        let (values, offset, gpu) = index_values(ctx, ty, indices, count)?;
        vertex_count = u64::from(values.iter().copied().max().unwrap_or(0)) + 1;
        // A u16 strip containing 0xFFFF would restart under wgpu; widen it to u32, whose
        // restart value no validated index can reach.
        let restart_hazard = prim.is_strip() && ty == IndexType::U16 && values.contains(&0xFFFF);
        let direct = ty != IndexType::U8
            && offset.is_multiple_of(ty.size())
            && !prim.generates_indices()
            && !restart_hazard
            && gpu.is_some();
        if direct {
            let fmt = if ty == IndexType::U16 { wgpu::IndexFormat::Uint16 } else { wgpu::IndexFormat::Uint32 };
            index = gpu.cloned().map(|g| (Source::Buffer(g, offset), fmt));
        } else {
            list = Some(values);
        }
    } else {
        vertex_count = u64::from(first) + u64::from(count);
        if prim.generates_indices() {
            generated_size(count)?;
            list = Some((first..first + count).collect());
        }
    }
    let mut draw_count = count;
    if let Some(v) = list {
        generated_size(count)?;
        let out = expand(prim, v);
        draw_count = out.len() as u32;
        index = Some((Source::Bytes(bytemuck::cast_slice(&out).to_vec()), wgpu::IndexFormat::Uint32));
    }
    Ok(IndexPlan { index, count: draw_count, vertex_count })
}

/// The vertices `v` of a `prim` draw as wgpu draws them: loops closed, fans as triangles.
fn expand(prim: Primitive, v: Vec<u32>) -> Vec<u32> {
    match prim {
        Primitive::LineLoop => v.iter().copied().chain(v.first().copied()).collect(),
        Primitive::TriangleFan => (1..v.len().saturating_sub(1)).flat_map(|i| [v[0], v[i], v[i + 1]]).collect(),
        _ => v,
    }
}

/// Robust access: every vertex a draw reads, in the order wgpu draws them unindexed (its
/// indices, those past the index data read as 0, or its vertex range), for a draw that reads
/// past an array.
pub(super) fn robust_order(
    ctx: &Context,
    prim: Primitive,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
) -> GlResult<Vec<u32>> {
    generated_size(count)?;
    let v = match indices {
        Some((ty, i)) => index_values(ctx, ty, i, count)?.0,
        // Vertices past u32 are past every array: they read as 0 anyway.
        None => (0..count).map(|i| first.saturating_add(i)).collect(),
    };
    Ok(expand(prim, v))
}

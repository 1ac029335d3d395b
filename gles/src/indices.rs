//! A draw's indices: where they come from, how they are read and checked (robust contexts
//! reading what lies past the index data as 0), and what wgpu reads for them: the element
//! buffer itself, or a list generated per pass for loops, fans, byte indices and client data.
//!
//! Two ES 3.0 rules rearrange the vertices ([`Reorder`]), each primitive then drawn on its own
//! as a list: `GL_PRIMITIVE_RESTART_FIXED_INDEX`, where the type's largest index ends one
//! primitive and starts the next (wgpu restarts strips only, and always), and GL's provoking
//! vertex, the last of each primitive, which gives `flat` varyings their values where wgpu
//! takes the first: a program with flat varyings has each primitive's last vertex put first,
//! turning its vertices without changing its winding.

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
    /// What wgpu draws the vertices as.
    pub(super) topology: wgpu::PrimitiveTopology,
}

/// How a draw's vertices are rearranged beyond what its primitive needs.
#[derive(Clone, Copy, Default)]
pub(super) struct Reorder {
    /// The restart index, where the draw's indices hold it with restart enabled.
    pub(super) restart: Option<u32>,
    /// Whether each primitive's last vertex goes first (the program has flat varyings).
    pub(super) last_first: bool,
}

impl Reorder {
    /// The rearrangement of a draw of `values` (indices of `ty`; `None` for a vertex range)
    /// in `ctx`, by a program with flat varyings if `flat`.
    pub(super) fn of(ctx: &Context, values: Option<(IndexType, &[u32])>, flat: bool) -> Reorder {
        let restart = values
            .filter(|_| ctx.raster.primitive_restart)
            .map(|(ty, v)| (ty.restart_index(), v))
            .and_then(|(r, v)| v.contains(&r).then_some(r));
        Reorder { restart, last_first: flat }
    }

    /// Whether the draw's vertices are rearranged at all (points have no provoking vertex).
    fn any(self, prim: Primitive) -> bool {
        self.restart.is_some() || (self.last_first && prim != Primitive::Points)
    }
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
/// buffer directly where wgpu can, else indices generated into the per-pass ring. `flat`:
/// the program has flat varyings.
pub(super) fn plan_indices(
    ctx: &Context,
    prim: Primitive,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
    flat: bool,
) -> GlResult<IndexPlan> {
    let mut index: Option<(Source, wgpu::IndexFormat)> = None;
    let mut list: Option<(Vec<u32>, Reorder)> = None;
    let vertex_count: u64;
    if let Some((ty, indices)) = indices {
        let (values, offset, gpu) = index_values(ctx, ty, indices, count)?;
        let reorder = Reorder::of(ctx, Some((ty, &values)), flat);
        let reached = values.iter().copied().filter(|&i| Some(i) != reorder.restart).max();
        vertex_count = u64::from(reached.unwrap_or(0)) + 1;
        // A u16 strip containing 0xFFFF would restart under wgpu; widen it to u32, whose
        // restart value no validated index can reach.
        let restart_hazard = prim.is_strip() && ty == IndexType::U16 && values.contains(&0xFFFF);
        let direct = ty != IndexType::U8
            && offset.is_multiple_of(ty.size())
            && !prim.generates_indices()
            && !restart_hazard
            && !reorder.any(prim)
            && gpu.is_some();
        if direct {
            let fmt = if ty == IndexType::U16 { wgpu::IndexFormat::Uint16 } else { wgpu::IndexFormat::Uint32 };
            index = gpu.cloned().map(|g| (Source::Buffer(g, offset), fmt));
        } else {
            list = Some((values, reorder));
        }
    } else {
        vertex_count = u64::from(first) + u64::from(count);
        let reorder = Reorder::of(ctx, None, flat);
        if prim.generates_indices() || reorder.any(prim) {
            generated_size(count)?;
            list = Some(((first..first + count).collect(), reorder));
        }
    }
    let mut draw_count = count;
    let mut topology = prim.topology();
    if let Some((v, reorder)) = list {
        generated_size(count)?;
        let (out, drawn) = expand(prim, v, reorder);
        draw_count = out.len() as u32;
        topology = drawn;
        index = Some((Source::Bytes(bytemuck::cast_slice(&out).to_vec()), wgpu::IndexFormat::Uint32));
    }
    Ok(IndexPlan { index, count: draw_count, vertex_count, topology })
}

/// The vertices `v` of a `prim` draw as wgpu draws them, and what it draws them as: loops
/// closed, fans as triangles; rearranged by `r`, each primitive on its own in a list.
fn expand(prim: Primitive, v: Vec<u32>, r: Reorder) -> (Vec<u32>, wgpu::PrimitiveTopology) {
    if !r.any(prim) {
        let out = match prim {
            Primitive::LineLoop => v.iter().copied().chain(v.first().copied()).collect(),
            Primitive::TriangleFan => (1..v.len().saturating_sub(1)).flat_map(|i| [v[0], v[i], v[i + 1]]).collect(),
            _ => v,
        };
        return (out, prim.topology());
    }
    let mut out = Vec::with_capacity(v.len() * 3);
    for run in v.split(|&i| Some(i) == r.restart) {
        primitives(prim, run, r.last_first, &mut out);
    }
    (out, prim.list_topology())
}

/// Appends the primitives of one run of `prim` vertices (between restarts) to `out` as a list,
/// each primitive's last vertex first if `last_first`.
fn primitives(prim: Primitive, s: &[u32], last_first: bool, out: &mut Vec<u32>) {
    let line = |out: &mut Vec<u32>, a: u32, b: u32| out.extend(if last_first { [b, a] } else { [a, b] });
    // A rotation: the winding stays.
    let tri = |out: &mut Vec<u32>, a: u32, b: u32, c: u32| out.extend(if last_first { [c, a, b] } else { [a, b, c] });
    let n = s.len();
    match prim {
        Primitive::Points => out.extend_from_slice(s),
        Primitive::Lines => s.chunks_exact(2).for_each(|p| line(out, p[0], p[1])),
        Primitive::LineStrip => s.windows(2).for_each(|p| line(out, p[0], p[1])),
        Primitive::LineLoop => {
            s.windows(2).for_each(|p| line(out, p[0], p[1]));
            if n >= 2 {
                line(out, s[n - 1], s[0]);
            }
        }
        Primitive::Triangles => s.chunks_exact(3).for_each(|t| tri(out, t[0], t[1], t[2])),
        // Odd triangles of a strip take their first two vertices swapped, keeping the winding.
        Primitive::TriangleStrip => (0..n.saturating_sub(2)).for_each(|i| match i % 2 {
            0 => tri(out, s[i], s[i + 1], s[i + 2]),
            _ => tri(out, s[i + 1], s[i], s[i + 2]),
        }),
        Primitive::TriangleFan => (1..n.saturating_sub(1)).for_each(|i| tri(out, s[0], s[i], s[i + 1])),
    }
}

/// The vertex range `first..first + count` of a `prim` draw as independent primitives, in GL's
/// order (a strip's odd triangles with their first two vertices swapped, a loop closed), and
/// the list topology they are drawn as: what transform feedback records of a strip, fan or loop.
pub(super) fn unrolled(prim: Primitive, first: u32, count: u32) -> GlResult<(Vec<u32>, wgpu::PrimitiveTopology)> {
    generated_size(count)?;
    let v: Vec<u32> = (0..count).map(|i| first.saturating_add(i)).collect();
    let mut out = Vec::with_capacity(v.len() * 3);
    primitives(prim, &v, false, &mut out);
    Ok((out, prim.list_topology()))
}

/// Robust access: every vertex a draw reads, in the order wgpu draws them unindexed (its
/// indices, those past the index data read as 0, or its vertex range), for a draw that reads
/// past an array, and what wgpu draws them as.
pub(super) fn robust_order(
    ctx: &Context,
    prim: Primitive,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
    flat: bool,
) -> GlResult<(Vec<u32>, wgpu::PrimitiveTopology)> {
    generated_size(count)?;
    let (v, reorder) = match indices {
        Some((ty, i)) => {
            let v = index_values(ctx, ty, i, count)?.0;
            let reorder = Reorder::of(ctx, Some((ty, &v)), flat);
            (v, reorder)
        }
        // Vertices past u32 are past every array: they read as 0 anyway.
        None => ((0..count).map(|i| first.saturating_add(i)).collect(), Reorder::of(ctx, None, flat)),
    };
    Ok(expand(prim, v, reorder))
}

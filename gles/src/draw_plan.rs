//! A draw's plan: validated against `&Context` into a [`DrawSpec`] (the vertex inputs,
//! converted where wgpu lacks a format, every read checked against the CPU shadows of the
//! buffers involved; points as squares of two triangles; the samplers' textures and their wrap
//! parameters; the viewport and scissor), which the renderer then lowers onto its open pass.

use std::borrow::Cow;

use crate::channels::border_color;
use crate::context::Context;
use crate::conv::{clip_rect, element, element_size, float_format, native_format, reads_src1, viewport, Mirror};
use crate::divisors::{plan_divided, InstanceReads};
use crate::draw_state::{bound_textures, raster_state, Bound};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::formats::Storage;
use crate::glsl::types::Ty;
use crate::glsl::Scalar;
use crate::indices::{index_values, plan_indices, robust_order, unrolled, IndexPlan, Indices};
use crate::int_attribs::plan_integer;
use crate::limits::MAX_CONVERTED;
use crate::objects::program::LinkedProgram;
use crate::objects::surface::ReversedZ;
use crate::objects::texture::SamplerState;
use crate::render::{DrawSpec, Source, Target, VertexInput};
use crate::typed::{IndexType, Primitive};

/// Validates the program's vertex inputs against their arrays for `vertex_count` vertices and
/// plans each: the buffer as wgpu reads it, or converted to float in the per-pass ring. With
/// `order` (indexed points), each array is gathered in that order and converted. With `robust`
/// what lies past an array reads as zeros (a vec4 of 2 components as (0, 0, 0, 1)), as on
/// Mesa, where it is otherwise `GL_INVALID_OPERATION`.
pub(crate) fn plan_inputs(
    ctx: &Context,
    program: &LinkedProgram,
    vertex_count: u64,
    order: Option<&[u32]>,
    robust: bool,
    reads: InstanceReads,
) -> GlResult<Vec<VertexInput>> {
    let mut inputs = Vec::with_capacity(program.info.attributes.len());
    // A matrix input reads a location per column, each a float vector.
    let slots = program
        .info
        .attributes
        .iter()
        .flat_map(|(var, loc)| (0..var.ty.columns().max(1) as u32).map(move |i| (var.ty.scalar(), loc + i)));
    for (scalar, loc) in slots {
        let loc = &loc;
        let a = ctx.attribs.get(*loc as usize).ok_or(GlError::InvalidOperation)?;
        if let kind @ (Scalar::Int | Scalar::UInt) = scalar {
            let signed = kind == Scalar::Int;
            inputs.push(plan_integer(ctx, a, *loc, signed, (vertex_count, order, robust), reads)?);
            continue;
        }
        if !a.enabled {
            inputs.push(VertexInput {
                location: *loc,
                format: wgpu::VertexFormat::Float32x4,
                stride: 0,
                source: Source::Bytes(bytemuck::cast_slice(&a.current).to_vec()),
                per_instance: false,
            });
            continue;
        }
        if a.divisor > 0 {
            inputs.push(plan_divided(ctx, a, *loc, reads)?);
            continue;
        }
        // A buffer object's shadow, or the client array sent for this draw (offset 0).
        let (data, gpu, offset): (&[u8], Option<&wgpu::Buffer>, u64) = if a.buffer == 0 {
            let bytes = a.client.as_ref().ok_or(GlError::InvalidOperation)?;
            (bytes, None, 0)
        } else {
            let buf = ctx.objects.buffers.get(&a.buffer).ok_or(GlError::InvalidOperation)?;
            (&buf.data, buf.gpu.as_ref(), a.offset)
        };
        let elem = element_size(a.ty, a.size);
        let stride = if a.stride == 0 { elem } else { a.stride as usize };
        // The pointer and the stride are the client's: a sum past u64 reads past any buffer.
        let need = vertex_count
            .saturating_sub(1)
            .checked_mul(stride as u64)
            .and_then(|x| x.checked_add(offset))
            .and_then(|x| x.checked_add(elem as u64));
        let within = need.filter(|&n| n <= data.len() as u64);
        if within.is_none() && !robust {
            return Err(GlError::InvalidOperation);
        }
        let (need, offset) = (within.unwrap_or(0) as usize, offset as usize);
        match native_format(a.ty, a.size, a.normalized) {
            Some(fmt)
                if within.is_some() && order.is_none() && offset.is_multiple_of(4) && stride.is_multiple_of(4) =>
            {
                let source = match gpu {
                    Some(g) => Source::Buffer(g.clone(), offset as u64),
                    None => Source::Bytes(data[..need].to_vec()),
                };
                inputs.push(VertexInput {
                    location: *loc,
                    format: fmt,
                    stride: stride as u64,
                    source,
                    per_instance: false,
                });
            }
            _ => {
                let rows = order.map_or(vertex_count as usize, <[u32]>::len);
                // Overlapping elements (a stride below their size) can ask for more floats
                // than the buffer has bytes; beyond a bound that is an allocation failure.
                let bytes = rows.checked_mul(a.size as usize * 4).filter(|&b| b <= MAX_CONVERTED);
                let mut out = Vec::with_capacity(bytes.ok_or(GlError::OutOfMemory)?);
                let mut convert = |v: usize| {
                    let base = v.checked_mul(stride).and_then(|x| x.checked_add(offset));
                    match base.filter(|b| b.checked_add(elem).is_some_and(|end| end <= data.len())) {
                        Some(base) => element(&data[base..base + elem], a.ty, a.size, a.normalized, &mut out),
                        // Past the array: zeros, the components it lacks filled as for any.
                        None => out.extend(std::iter::repeat_n(0u8, a.size as usize * 4)),
                    }
                };
                match order {
                    Some(o) => o.iter().for_each(|&v| convert(v as usize)),
                    None => (0..vertex_count as usize).for_each(&mut convert),
                }
                inputs.push(VertexInput {
                    location: *loc,
                    format: float_format(a.size),
                    stride: a.size as u64 * 4,
                    source: Source::Bytes(out),
                    per_instance: false,
                });
            }
        }
    }
    Ok(inputs)
}

/// Plans a `GL_POINTS` draw: one instance per point (in index order for indexed draws, whose
/// arrays are gathered), four vertices each, which the program's points vertex stage expands
/// to a square; `strata_point` carries the viewport's pixel size and the instance's number
/// (`gl_InstanceIDEXT`).
pub(crate) fn plan_points(
    ctx: &Context,
    program: &LinkedProgram,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
    instance: u32,
) -> GlResult<(Vec<VertexInput>, (u32, u32))> {
    let order = match indices {
        Some((ty, i)) => {
            let mut v = index_values(ctx, ty, i, count)?.0;
            // Restart indices end points, which are primitives of one vertex: they draw nothing.
            if ctx.raster.primitive_restart {
                v.retain(|&i| i != ty.restart_index());
            }
            Some(v)
        }
        None => None,
    };
    let (vertex_count, instances) = match &order {
        Some(o) => (u64::from(o.iter().copied().max().unwrap_or(0)) + 1, (0, o.len() as u32)),
        None => (u64::from(first) + u64::from(count), (first, count)),
    };
    let mut inputs =
        plan_inputs(ctx, program, vertex_count, order.as_deref(), ctx.robust, InstanceReads::One(instance))?;
    let [_, _, w, h] = ctx.raster.viewport;
    let point = [1.0 / w.max(1) as f32, 1.0 / h.max(1) as f32, instance as f32, 0.0];
    inputs.push(VertexInput {
        location: program.info.point_input,
        format: wgpu::VertexFormat::Float32x4,
        stride: 0,
        source: Source::Bytes(bytemuck::cast_slice(&point).to_vec()),
        per_instance: false,
    });
    Ok((inputs, instances))
}

/// The uniform block with each sampler's wrap flags and border colour (`glsl::link`'s wrap
/// offsets) where its texture wraps by `GL_MIRROR_CLAMP_TO_EDGE_EXT` or
/// `GL_CLAMP_TO_BORDER_EXT`, and its swizzle where its texture has one; a shadow sampler's
/// comparison and levels; copied only where one does. `kinds`: each sampler's type.
pub(crate) fn with_sampler_params<'c>(
    mut data: Cow<'c, [u8]>,
    bound: &[Option<Bound<'_>>],
    offsets: &[u32],
    kinds: &[(Ty, u32)],
) -> Cow<'c, [u8]> {
    for ((b, &at), (ty, _)) in bound.iter().zip(offsets).zip(kinds) {
        let Some(Bound { texture: t, state, border: colour }) = b else { continue };
        let at = at as usize;
        if let Some(dst) = data.to_mut().get_mut(at + 48..at + 64).filter(|_| state.compare_mode != 0) {
            for (d, v) in dst.chunks_exact_mut(4).zip(shadow_params(t, state)) {
                d.copy_from_slice(&v.to_ne_bytes());
            }
        }
        if ty.is_shadow() {
            // Shadow lookups choose their levels themselves (`glsl::shadow`).
            if let Some(dst) = data.to_mut().get_mut(at + 16..at + 32) {
                for (d, v) in dst.chunks_exact_mut(4).zip(shadow_levels(t, state)) {
                    d.copy_from_slice(&v.to_ne_bytes());
                }
            }
            continue;
        }
        if t.swizzle != Default::default() {
            if let Some(dst) = data.to_mut().get_mut(at + 32..at + 48) {
                for (d, v) in dst.chunks_exact_mut(4).zip(t.swizzle.selectors()) {
                    d.copy_from_slice(&v.to_ne_bytes());
                }
            }
        }
        if let Some(img) = t.gpu.as_ref().filter(|img| img.storage.is_int()) {
            // Integer lookups fetch texel by texel (`glsl::int_samplers`): the wraps and the
            // levels they choose among (none but the base without a mipmap filter), and the
            // level-of-detail clamps.
            let code = |w: u32| match w {
                REPEAT => 0.0f32,
                MIRRORED_REPEAT => 2.0,
                MIRROR_CLAMP_TO_EDGE_EXT => 3.0,
                _ => 1.0,
            };
            let (base, max) = t.level_range(state);
            let last = max.min(img.levels.saturating_sub(1));
            let levels = if state.uses_mipmaps() { (last + 1).saturating_sub(base) as f32 } else { 0.0 };
            let k = [code(state.wrap_s), code(state.wrap_t), code(state.wrap_r), levels];
            let c = [f32::from_bits(state.min_lod), f32::from_bits(state.max_lod), 0.0, 0.0];
            for (range, values) in [(at + 48..at + 64, k), (at + 16..at + 32, c)] {
                if let Some(dst) = data.to_mut().get_mut(range) {
                    for (d, v) in dst.chunks_exact_mut(4).zip(values) {
                        d.copy_from_slice(&v.to_ne_bytes());
                    }
                }
            }
            continue;
        }
        // The r wrap counts only for 3D textures, whose lookup helpers read flag w.
        let three_d = t.target == TEXTURE_3D_OES;
        let [ms, mt, mr] = state.mirror_clamp();
        let mr = mr && three_d;
        let border = state.clamps_to_border(three_d);
        if !(ms || mt || mr || border) {
            continue;
        }
        let float =
            t.gpu.as_ref().is_some_and(|img| matches!(img.storage, Storage::Half | Storage::Float | Storage::Rg11b10));
        let color = if border { border_color(t.format, float, *colour) } else { [0.0; 4] };
        let flag = |on: bool| if on { 1.0f32 } else { 0.0 };
        let values = [flag(ms), flag(mt), flag(border), flag(mr), color[0], color[1], color[2], color[3]];
        if let Some(dst) = data.to_mut().get_mut(at..at + 32) {
            for (d, v) in dst.chunks_exact_mut(4).zip(values) {
                d.copy_from_slice(&v.to_ne_bytes());
            }
        }
    }
    data
}

/// The stencil reference a draw sets, and the back face's reference and masks where they
/// differ from the front's (wgpu has one reference and one pair of masks: back-facing
/// triangles then draw on their own, `Renderer::record`). Where only back faces are drawn
/// (front faces culled), theirs are the draw's.
fn stencil_faces(ctx: &Context, raster: &mut crate::render::RasterState) -> (u32, Option<(u32, u32, u32)>) {
    let values = |f: &crate::context::StencilFace| (f.reference.clamp(0, 255) as u32, f.mask & 0xff, f.write & 0xff);
    let (front, back) = (values(&ctx.depth_stencil.stencil[0]), values(&ctx.depth_stencil.stencil[1]));
    let triangles = !raster.points
        && matches!(raster.topology, wgpu::PrimitiveTopology::TriangleList | wgpu::PrimitiveTopology::TriangleStrip);
    let Some(stencil) = raster.stencil.as_mut().filter(|_| front != back && triangles) else {
        return (front.0, None);
    };
    match raster.cull {
        None => (front.0, Some(back)),
        Some(wgpu::Face::Front) => {
            (stencil.read_mask, stencil.write_mask) = (back.1, back.2);
            (back.0, None)
        }
        Some(wgpu::Face::Back) => (front.0, None),
    }
}

/// The blend constant a draw sets: the blend colour, clamped; but where the colour factors
/// read only `GL_CONSTANT_ALPHA` (wgpu's constant factor reads the constant per channel), its
/// alpha in every channel. Colour factors reading both the constant colour and its alpha
/// cannot be given one constant: the colour wins.
fn blend_constant(func: [u32; 4], color: [f32; 4]) -> [f64; 4] {
    let c = color.map(|c| f64::from(c.clamp(0.0, 1.0)));
    let alpha = |f: u32| matches!(f, CONSTANT_ALPHA | ONE_MINUS_CONSTANT_ALPHA);
    let colour = |f: u32| matches!(f, CONSTANT_COLOR | ONE_MINUS_CONSTANT_COLOR);
    let rgb = [func[0], func[1]];
    if rgb.iter().any(|&f| alpha(f)) && !rgb.iter().any(|&f| colour(f)) {
        [c[3]; 4]
    } else {
        c
    }
}

/// A shadow sampler's comparison as `glsl::link::SHADOW_FNS` reads it: the function (1 to 8,
/// `GL_NEVER` to `GL_ALWAYS`), the filters (1 where magnification is linear, 2 where
/// minification is), whether the reference is clamped to [0, 1] (every depth format but the
/// float ones) and 1 for comparing at all.
fn shadow_params(t: &crate::objects::texture::Texture, state: &SamplerState) -> [f32; 4] {
    let linear = |f: u32| f32::from(u8::from(matches!(f, LINEAR | LINEAR_MIPMAP_NEAREST | LINEAR_MIPMAP_LINEAR)));
    let float = matches!(if t.sized != 0 { t.sized } else { t.format }, DEPTH_COMPONENT32F | DEPTH32F_STENCIL8);
    let func = state.compare_func.wrapping_sub(NEVER) as f32 + 1.0;
    [func, linear(state.mag) + 2.0 * linear(state.min), f32::from(u8::from(!float)), 1.0]
}

/// A shadow sampler's levels as `glsl::shadow` reads them: the level-of-detail clamps
/// (`GL_TEXTURE_MIN_LOD`, `_MAX_LOD`), the last level it reads past the base level, and its
/// mipmap filter (0 none, 1 nearest, 2 linear).
fn shadow_levels(t: &crate::objects::texture::Texture, state: &SamplerState) -> [f32; 4] {
    let (base, max) = t.level_range(state);
    let last = t.gpu.as_ref().map_or(0, |img| max.min(img.mips.saturating_sub(1)).saturating_sub(base));
    let filter = match state.min {
        NEAREST_MIPMAP_NEAREST | LINEAR_MIPMAP_NEAREST => 1.0,
        NEAREST_MIPMAP_LINEAR | LINEAR_MIPMAP_LINEAR => 2.0,
        _ => 0.0,
    };
    [f32::from_bits(state.min_lod), f32::from_bits(state.max_lod), last as f32, filter]
}

/// Which instances one planned draw covers: points draw each instance on its own (`instance`);
/// other primitives draw all `instances` at once.
#[derive(Clone, Copy)]
pub(crate) struct Instancing {
    pub(crate) instance: u32,
    pub(crate) instances: u32,
    /// Draw each primitive's vertices on their own, gathered in order (a strip, fan or loop
    /// captured by transform feedback, which records independent primitives).
    pub(crate) unroll: bool,
}

/// Validates a draw of the current program into `target` (a reversed-Z framebuffer 0 with
/// `reversed`); `None` if it draws nothing.
#[allow(clippy::too_many_arguments)]
pub(crate) fn plan_draw<'c>(
    ctx: &'c Context,
    target: &Target,
    reversed: Option<ReversedZ>,
    prim: Primitive,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
    shape: Instancing,
) -> GlResult<Option<DrawSpec<'c>>> {
    let Some(exe) = ctx.executable() else { return Ok(None) };
    let program = exe.program.clone();
    if count == 0 {
        return Ok(None);
    }
    let (inputs, index, count, first, instances, topology) = if prim == Primitive::Points {
        let (inputs, instances) = plan_points(ctx, &program, count, indices, first, shape.instance)?;
        if instances.1 == 0 {
            return Ok(None);
        }
        (inputs, None, 4, 0, instances, prim.topology())
    } else {
        let flat = program.info.flat;
        let planned = if shape.unroll {
            // Straight to the gathered draw below.
            Err(GlError::InvalidOperation)
        } else {
            plan_indices(ctx, prim, count, indices, first, flat)
        };
        let planned = planned.and_then(|plan| {
            let reads = InstanceReads::Drawn(shape.instances);
            Ok((plan_inputs(ctx, &program, plan.vertex_count, None, false, reads)?, plan))
        });
        match planned {
            Ok((inputs, IndexPlan { index, count, topology, .. })) => {
                if count == 0 {
                    return Ok(None);
                }
                (inputs, index, count, first, (0, shape.instances), topology)
            }
            // Robust access, with an array too short for the draw: each vertex the draw reads
            // is gathered, what lies past an array as zeros, and drawn unindexed.
            Err(GlError::InvalidOperation) if ctx.robust || shape.unroll => {
                // Unrolled for a capture, in the order it records: GL's, not turned for flat.
                let (order, topology) = match shape.unroll {
                    true => unrolled(prim, first, count)?,
                    false => robust_order(ctx, prim, count, indices, first, flat)?,
                };
                if order.is_empty() {
                    return Ok(None);
                }
                let reads = InstanceReads::Drawn(shape.instances);
                let mut inputs = plan_inputs(ctx, &program, order.len() as u64, Some(&order), true, reads)?;
                if shape.unroll && program.info.reads_vertex_id() {
                    // Each gathered vertex's own number, for `gl_VertexID`.
                    inputs.push(VertexInput {
                        location: program.info.point_input,
                        format: wgpu::VertexFormat::Uint32,
                        stride: 4,
                        source: Source::Bytes(bytemuck::cast_slice(&order).to_vec()),
                        per_instance: false,
                    });
                }
                (inputs, None, order.len() as u32, 0, (0, shape.instances), topology)
            }
            Err(e) => return Err(e),
        }
    };
    let bound = bound_textures(ctx, &program, &exe.units);
    let textures = bound
        .iter()
        .zip(&program.info.samplers)
        .map(|(b, (ty, _))| {
            let b = b.as_ref()?;
            // Integers read by a float sampler, or floats by an integer one, are undefined
            // (ES 3.0 §3.8.14): the sampler reads as if no texture were there.
            let img = b.texture.gpu.as_ref()?;
            let kind = match img.storage {
                Storage::Int { signed, .. } => Some(signed),
                _ => None,
            };
            if kind != ty.int_sampler() {
                return None;
            }
            let (base, _) = b.texture.level_range(&b.state);
            // The sampler counts levels of detail from the base level, as the view does.
            let state = SamplerState { base_level: base, ..b.state };
            // Integer cube maps are fetched from their faces as a 2D array.
            let view = match ty.int_sampler().is_some() && img.layers() == 6 && !img.array {
                true => img.faces_view_from(base),
                false => img.view_from(base),
            };
            // A shadow sampler fetches texels unfiltered and filters its comparisons itself.
            Some((view, b.texture.uid, state, !img.filterable || ty.is_shadow()))
        })
        .collect();
    let uniforms = with_sampler_params(exe.data, &bound, &program.info.wrap_offsets, &program.info.samplers);
    let blocks = crate::uniform_blocks::block_buffers(ctx, &program, &exe.block_bindings);
    // GL_EXT_blend_func_extended: blending with the second colour allows one draw buffer.
    if ctx.blend.enabled && ctx.blend.func.iter().any(|f| reads_src1(*f)) && target.slots().len() > 1 {
        return Err(GlError::InvalidOperation);
    }
    let mut raster = raster_state(ctx, topology, target, program.info.dual);
    if matches!(topology, wgpu::PrimitiveTopology::LineStrip | wgpu::PrimitiveTopology::TriangleStrip) {
        raster.strip_index = index.as_ref().map(|i| i.1);
    }
    if prim == Primitive::Points {
        // A square of two triangles per point, never culled or offset (both were decided
        // for a point topology above), and front-facing as GL's points are.
        raster.topology = wgpu::PrimitiveTopology::TriangleStrip;
        raster.front_ccw = true;
        raster.points = true;
    }
    let mut depth_range = ctx.depth_stencil.depth_range;
    if let Some(r) = reversed {
        raster.depth = raster.depth.map(|(f, write)| (Mirror::compare(f), write));
        raster.bias = raster.bias.map(Mirror::bias);
        raster.reversed_z = Some((r.near.to_bits(), r.far.to_bits()));
        depth_range = Mirror::range(depth_range);
    }
    let Some(viewport) = viewport(ctx.raster.viewport, depth_range) else {
        return Ok(None);
    };
    // Floats written to an integer colour buffer, or integers to another, are undefined in
    // ES 3.0: such a draw does nothing (a pipeline could not be made for it).
    let kinds = &program.info.output_kinds;
    let unfit = target.slots().iter().zip(kinds).any(|(s, k)| s.is_some_and(|s| !k.fits(s.2)));
    if unfit {
        tracing::warn!("draw skipped: the program's output types do not fit the colour buffers' formats");
        return Ok(None);
    }
    let scissor = if ctx.raster.scissor_test {
        clip_rect(ctx.raster.scissor, target)
    } else {
        [0, 0, target.width, target.height]
    };
    let (stencil_ref, back_stencil) = stencil_faces(ctx, &mut raster);
    Ok(Some(DrawSpec {
        vs: program.vs.clone(),
        fs: None,
        program,
        uniforms,
        textures,
        blocks,
        inputs,
        index,
        count,
        first,
        instances,
        raster,
        viewport,
        scissor,
        stencil_ref,
        back_stencil,
        blend_color: blend_constant(ctx.blend.func, ctx.blend.color),
        capture: None,
    }))
}

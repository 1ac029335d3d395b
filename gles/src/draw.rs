//! Drawing: `glClear`, `glDrawArrays` and `glDrawElements` (with buffer or client-side
//! indices), `glFlush` and `glFinish`. A draw is validated against `&Context` into a draw plan
//! ([`DrawSpec`]), every read checked against the CPU shadows of the buffers involved, and the
//! plan is then lowered onto the renderer's open pass.

use std::borrow::Cow;

use strata_protocol::Blob;

use crate::context::{Context, StencilFace};
use crate::conv::{
    blend_component, clip_rect, color_writes, compare, component, float_format, native_format, reads_src1, stencil_op,
    type_size, viewport, Mirror,
};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::formats::{border_color, Storage};
use crate::glsl::types::Ty;
use crate::indices::{index_values, plan_indices, robust_order, IndexPlan, Indices};
use crate::limits::MAX_CONVERTED;
use crate::objects::program::LinkedProgram;
use crate::objects::surface::ReversedZ;
use crate::objects::texture::Texture;
use crate::render::{DrawSpec, RasterState, Source, Target, VertexInput};
use crate::typed::{IndexType, Primitive, TextureTarget};
use crate::GlesExecutor;

/// Validates the program's vertex inputs against their arrays for `vertex_count` vertices and
/// plans each: the buffer as wgpu reads it, or converted to float in the per-pass ring. With
/// `order` (indexed points), each array is gathered in that order and converted. With `robust`
/// what lies past an array reads as zeros (a vec4 of 2 components as (0, 0, 0, 1)), as on
/// Mesa, where it is otherwise `GL_INVALID_OPERATION`.
fn plan_inputs(
    ctx: &Context,
    program: &LinkedProgram,
    vertex_count: u64,
    order: Option<&[u32]>,
    robust: bool,
) -> GlResult<Vec<VertexInput>> {
    let mut inputs = Vec::with_capacity(program.info.attributes.len());
    for (_, loc) in &program.info.attributes {
        let a = &ctx.attribs[*loc as usize];
        if !a.enabled {
            inputs.push(VertexInput {
                location: *loc,
                format: wgpu::VertexFormat::Float32x4,
                stride: 0,
                source: Source::Bytes(bytemuck::cast_slice(&a.current).to_vec()),
            });
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
        let elem = type_size(a.ty).unwrap_or(4) * a.size as usize;
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
                inputs.push(VertexInput { location: *loc, format: fmt, stride: stride as u64, source });
            }
            _ => {
                let ts = type_size(a.ty).unwrap_or(4);
                let rows = order.map_or(vertex_count as usize, <[u32]>::len);
                // Overlapping elements (a stride below their size) can ask for more floats
                // than the buffer has bytes; beyond a bound that is an allocation failure.
                let bytes = rows.checked_mul(a.size as usize * 4).filter(|&b| b <= MAX_CONVERTED);
                let mut out = Vec::with_capacity(bytes.ok_or(GlError::OutOfMemory)?);
                let mut convert = |v: usize| {
                    let base = v.checked_mul(stride).and_then(|x| x.checked_add(offset));
                    match base.filter(|b| b.checked_add(elem).is_some_and(|end| end <= data.len())) {
                        Some(base) => {
                            for c in 0..a.size as usize {
                                let at = base + c * ts;
                                out.extend_from_slice(&component(&data[at..at + ts], a.ty, a.normalized).to_ne_bytes());
                            }
                        }
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
fn plan_points(
    ctx: &Context,
    program: &LinkedProgram,
    count: u32,
    indices: Option<(IndexType, Indices<'_>)>,
    first: u32,
    instance: u32,
) -> GlResult<(Vec<VertexInput>, (u32, u32))> {
    let order = match indices {
        Some((ty, i)) => Some(index_values(ctx, ty, i, count)?.0),
        None => None,
    };
    let (vertex_count, instances) = match &order {
        Some(o) => (u64::from(o.iter().copied().max().unwrap_or(0)) + 1, (0, count)),
        None => (u64::from(first) + u64::from(count), (first, count)),
    };
    let mut inputs = plan_inputs(ctx, program, vertex_count, order.as_deref(), ctx.robust)?;
    let [_, _, w, h] = ctx.raster.viewport;
    let point = [1.0 / w.max(1) as f32, 1.0 / h.max(1) as f32, instance as f32, 0.0];
    inputs.push(VertexInput {
        location: program.info.point_input,
        format: wgpu::VertexFormat::Float32x4,
        stride: 0,
        source: Source::Bytes(bytemuck::cast_slice(&point).to_vec()),
    });
    Ok((inputs, instances))
}

/// The fixed-function state of a draw with `topology` into `target` by a program that writes
/// a second colour (`dual`) or not.
fn raster_state(ctx: &Context, topology: wgpu::PrimitiveTopology, target: &Target, dual: bool) -> RasterState {
    let (raster, ds, blend) = (&ctx.raster, &ctx.depth_stencil, &ctx.blend);
    let triangles = matches!(topology, wgpu::PrimitiveTopology::TriangleList | wgpu::PrimitiveTopology::TriangleStrip);
    let cull = (raster.cull && triangles).then_some(match raster.cull_face {
        FRONT => Some(wgpu::Face::Front),
        BACK => Some(wgpu::Face::Back),
        _ => None,
    });
    // Culling both faces draws nothing; emulate with a never-passing depth test.
    let cull_all = cull == Some(None);
    let depth = if target.has_depth() && (ds.depth_test || cull_all) {
        let func = if cull_all { NEVER } else { ds.depth_func };
        Some((compare(func), ds.depth_mask && !cull_all))
    } else {
        None
    };
    let stencil = (ds.stencil_test && target.has_stencil()).then(|| {
        let face = |f: &StencilFace| wgpu::StencilFaceState {
            compare: compare(f.func),
            fail_op: stencil_op(f.fail),
            depth_fail_op: stencil_op(f.zfail),
            pass_op: stencil_op(f.zpass),
        };
        wgpu::StencilState {
            front: face(&ds.stencil[0]),
            back: face(&ds.stencil[1]),
            read_mask: ds.stencil[0].mask & 0xff,
            write_mask: ds.stencil[0].write & 0xff,
        }
    });
    let blend_state = blend.enabled.then(|| wgpu::BlendState {
        color: blend_component(blend.func[0], blend.func[1], blend.eq[0], dual),
        alpha: blend_component(blend.func[2], blend.func[3], blend.eq[1], dual),
    });
    let bias = (raster.polygon_offset_fill && triangles && target.has_depth()).then(|| {
        // GL's units are in minimum resolvable depth steps, as Vulkan's constant factor is.
        let [factor, units, clamp] = raster.polygon_offset;
        (factor.to_bits(), units as i32, clamp.to_bits())
    });
    RasterState {
        topology,
        strip_index: None,
        front_ccw: raster.front_face == CCW,
        cull: cull.flatten(),
        depth,
        stencil,
        bias,
        blend: blend_state,
        // Channels each colour buffer lacks keep their fixed values (the pipeline masks them).
        write_mask: color_writes(blend.color_mask),
        points: false,
        reversed_z: None,
        unclipped_depth: raster.depth_clamp,
        clip: raster.clip,
    }
}

/// The uniform block with each sampler's wrap flags and border colour (`glsl::link`'s wrap
/// offsets) where its texture wraps by `GL_MIRROR_CLAMP_TO_EDGE_EXT` or
/// `GL_CLAMP_TO_BORDER_EXT`; copied only where one does.
fn with_sampler_params<'c>(mut data: Cow<'c, [u8]>, bound: &[Option<&Texture>], offsets: &[u32]) -> Cow<'c, [u8]> {
    for (t, &at) in bound.iter().zip(offsets) {
        let Some(t) = t else { continue };
        // The r wrap counts only for 3D textures, whose lookup helpers read flag w.
        let three_d = t.target == TEXTURE_3D_OES;
        let [ms, mt, mr] = t.sampler.mirror_clamp();
        let mr = mr && three_d;
        let border = t.sampler.clamps_to_border(three_d);
        if !(ms || mt || mr || border) {
            continue;
        }
        let float = t.gpu.as_ref().is_some_and(|img| matches!(img.storage, Storage::Half | Storage::Float));
        let color = if border { border_color(t.format, float, t.border) } else { [0.0; 4] };
        let flag = |on: bool| if on { 1.0f32 } else { 0.0 };
        let values = [flag(ms), flag(mt), flag(border), flag(mr), color[0], color[1], color[2], color[3]];
        let at = at as usize;
        if let Some(dst) = data.to_mut().get_mut(at..at + 32) {
            for (d, v) in dst.chunks_exact_mut(4).zip(values) {
                d.copy_from_slice(&v.to_ne_bytes());
            }
        }
    }
    data
}

/// Which instances one planned draw covers: points draw each instance on its own (`instance`);
/// other primitives draw all `instances` at once.
#[derive(Clone, Copy)]
struct Instancing {
    instance: u32,
    instances: u32,
}

/// Validates a draw of the current program into `target` (a reversed-Z framebuffer 0 with
/// `reversed`); `None` if it draws nothing.
#[allow(clippy::too_many_arguments)]
fn plan_draw<'c>(
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
    let (inputs, index, count, first, instances) = if prim == Primitive::Points {
        let (inputs, instances) = plan_points(ctx, &program, count, indices, first, shape.instance)?;
        (inputs, None, 4, 0, instances)
    } else {
        let planned = plan_indices(ctx, prim, count, indices, first)
            .and_then(|plan| Ok((plan_inputs(ctx, &program, plan.vertex_count, None, false)?, plan)));
        match planned {
            Ok((inputs, IndexPlan { index, count, .. })) => {
                if count == 0 {
                    return Ok(None);
                }
                (inputs, index, count, first, (0, shape.instances))
            }
            // Robust access, with an array too short for the draw: each vertex the draw reads
            // is gathered, what lies past an array as zeros, and drawn unindexed.
            Err(GlError::InvalidOperation) if ctx.robust => {
                let order = robust_order(ctx, prim, count, indices, first)?;
                if order.is_empty() {
                    return Ok(None);
                }
                let inputs = plan_inputs(ctx, &program, order.len() as u64, Some(&order), true)?;
                (inputs, None, order.len() as u32, 0, (0, shape.instances))
            }
            Err(e) => return Err(e),
        }
    };
    let bound: Vec<Option<&Texture>> = program
        .info
        .samplers
        .iter()
        .zip(exe.units.iter())
        .map(|((ty, _), unit)| {
            let target = match ty {
                Ty::SamplerCube => TextureTarget::CubeMap,
                Ty::SamplerExternal => TextureTarget::External,
                Ty::Sampler3D => TextureTarget::ThreeD,
                _ => TextureTarget::TwoD,
            };
            let name = ctx.bindings.units.get(*unit as usize)?[target.slot()];
            let t = ctx.objects.textures.get(&name)?;
            (t.target == target.as_gl() && t.complete() && t.gpu.is_some()).then_some(t)
        })
        .collect();
    let textures = bound
        .iter()
        .map(|t| t.and_then(|t| t.gpu.as_ref().map(|img| (img.view.clone(), t.uid, t.sampler, !img.filterable))))
        .collect();
    let uniforms = with_sampler_params(exe.data, &bound, &program.info.wrap_offsets);
    // GL_EXT_blend_func_extended: blending with the second colour allows one draw buffer.
    if ctx.blend.enabled && ctx.blend.func.iter().any(|f| reads_src1(*f)) && target.slots().len() > 1 {
        return Err(GlError::InvalidOperation);
    }
    let topology = prim.topology();
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
    let scissor = if ctx.raster.scissor_test {
        clip_rect(ctx.raster.scissor, target)
    } else {
        [0, 0, target.width, target.height]
    };
    Ok(Some(DrawSpec {
        vs: program.vs.clone(),
        fs: None,
        program,
        uniforms,
        textures,
        inputs,
        index,
        count,
        first,
        instances,
        raster,
        viewport,
        scissor,
        stencil_ref: ctx.depth_stencil.stencil[0].reference.clamp(0, 255) as u32,
        blend_color: ctx.blend.color.map(|c| f64::from(c.clamp(0.0, 1.0))),
    }))
}

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
        let target = self.draw_target(ctx).map_err(|_| GlError::InvalidFramebufferOperation)?;
        self.prepare_pipeline(ctx)?;
        let reversed = self.reversed_target(ctx);
        let stages = match self.draw_stages(ctx, reversed, prim == Primitive::Points) {
            Ok(stages) => stages,
            Err(e) => {
                // GL has no error for this: the draw is dropped, and the reason logged.
                tracing::warn!("draw dropped: a variant of the program's stages failed: {e}");
                return Ok(());
            }
        };
        let renderer = &mut self.r;
        let plans = if prim == Primitive::Points { instances } else { instances.min(1) };
        for instance in 0..plans {
            let shape = Instancing { instance, instances };
            let Some(mut spec) = plan_draw(ctx, &target, reversed, prim, count, indices, first, shape)? else {
                return Ok(());
            };
            // Validated, and discarded by a conditional render whose query passed no sample.
            if ctx.conditional == Some(false) {
                return Ok(());
            }
            if let Some((vs, fs)) = stages.clone() {
                spec.vs = vs;
                spec.fs = fs;
            }
            renderer.draw(&target, spec);
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
        let color = (mask & COLOR_BUFFER_BIT != 0 && target.has_color() && !writes.is_empty())
            .then(|| (blend.clear_color.map(|c| c.clamp(0.0, 1.0)), writes));
        let clear_depth = if reversed { Mirror::depth(ds.clear_depth) } else { ds.clear_depth };
        let depth =
            (mask & DEPTH_BUFFER_BIT != 0 && target.has_depth() && ds.depth_mask).then_some((clear_depth, true));
        let stencil = (mask & STENCIL_BUFFER_BIT != 0 && target.has_stencil() && ds.stencil[0].write & 0xff != 0)
            .then_some((ds.clear_stencil as u32 & 0xff, ds.stencil[0].write & 0xff));
        let scissor = ctx.raster.scissor_test.then(|| clip_rect(ctx.raster.scissor, &target));
        if (color.is_none() && depth.is_none() && stencil.is_none()) || ctx.conditional == Some(false) {
            return Ok(());
        }
        renderer.clear(&target, color, depth, stencil, scissor);
        Ok(())
    }

    pub(super) fn glFlush(&mut self, _ctx: &mut Context) -> GlResult {
        self.r.flush();
        Ok(())
    }

    pub(super) fn glFinish(&mut self, _ctx: &mut Context) {
        self.r.finish();
        // Every command before it has completed, the swaps too: their frames are published.
        if let Some((scene, client, _)) = &self.scene {
            scene.wait_published(*client);
        }
    }
}

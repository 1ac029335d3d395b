//! ES 3.0's transform feedback: objects, the varyings a program captures, the buffer bindings,
//! begin, end, pause and resume, the draws' rules while capturing, the state and the limits,
//! each checked in Mesa's order. Capture itself is the vertex stage's (`glsl::capture`): each
//! capturing draw binds the buffers as storage and tells the stage where it writes. When the
//! capture ends, what it wrote is read back into the daemon's copies of the buffers, which
//! mapping and every later read of the contents use.

use strata_protocol::{ActiveVariable, Slice, Text};

use crate::context::{Context, RangeBinding};
use crate::error::{GlError, GlResult};
use crate::glsl::capture::{MAX_INTERLEAVED_COMPONENTS, MAX_SEPARATE_ATTRIBS, MAX_SEPARATE_COMPONENTS};
use crate::objects::xfb::{Capturing, TransformFeedback, MAX_BUFFERS};
use crate::typed::Primitive;
use crate::GlesExecutor;

/// `GL_TRANSFORM_FEEDBACK`: the object binding's target.
const TRANSFORM_FEEDBACK: u32 = 0x8E22;
/// `glTransformFeedbackVaryings`' buffer modes.
const INTERLEAVED_ATTRIBS: u32 = 0x8C8C;
const SEPARATE_ATTRIBS: u32 = 0x8C8D;
/// The state `glGet*` answers.
const TRANSFORM_FEEDBACK_BINDING: u32 = 0x8E25;
const TRANSFORM_FEEDBACK_ACTIVE: u32 = 0x8E24;
const TRANSFORM_FEEDBACK_PAUSED: u32 = 0x8E23;
/// The generic binding's name, and the indexed bindings' in `glGetIntegeri_v`.
pub(crate) const TRANSFORM_FEEDBACK_BUFFER_BINDING: u32 = 0x8C8F;
pub(crate) const TRANSFORM_FEEDBACK_BUFFER_START: u32 = 0x8C84;
pub(crate) const TRANSFORM_FEEDBACK_BUFFER_SIZE: u32 = 0x8C85;
/// The limits.
const MAX_INTERLEAVED_COMPONENTS_ENUM: u32 = 0x8C8A;
const MAX_SEPARATE_ATTRIBS_ENUM: u32 = 0x8C8B;
const MAX_SEPARATE_COMPONENTS_ENUM: u32 = 0x8C80;
/// `glGetProgramiv`'s names.
pub(crate) const TRANSFORM_FEEDBACK_BUFFER_MODE: u32 = 0x8C7F;
pub(crate) const TRANSFORM_FEEDBACK_VARYINGS: u32 = 0x8C83;
pub(crate) const TRANSFORM_FEEDBACK_VARYING_MAX_LENGTH: u32 = 0x8C76;
/// The objects a context may have, against a client that generates without end.
const MAX_OBJECTS: usize = 4096;

/// What a capturing draw writes: per instance, the vertices captured, and per buffer binding
/// the bytes each vertex takes.
pub(crate) struct CapturePlan {
    /// Vertices captured per instance (the draw's, less those of an unfinished primitive; a
    /// strip's, fan's or loop's unrolled into independent primitives).
    pub(crate) per_instance: u32,
    /// Whether the draw's vertices are unrolled into independent primitives first.
    pub(crate) unroll: bool,
    /// Per buffer binding: the bytes of one vertex's record.
    pub(crate) strides: Vec<u64>,
}

/// The vertices of one primitive of `mode`.
fn vertices_per(mode: Primitive) -> u32 {
    match mode {
        Primitive::Points => 1,
        Primitive::Lines => 2,
        _ => 3,
    }
}

/// Whether a draw of `draw` may be captured by a capture of `mode`: the same mode, or as Mesa
/// (and desktop GL) allows, a strip, fan or loop of the same primitive, recorded as independent
/// primitives. (ES 3.0 §2.15.2 asks for the same mode; Mesa, the oracle, takes the others.)
fn captures(mode: Primitive, draw: Primitive) -> bool {
    use Primitive::*;
    matches!(
        (mode, draw),
        (Points, Points) | (Lines, Lines | LineStrip | LineLoop) | (Triangles, Triangles | TriangleStrip | TriangleFan)
    )
}

/// The vertices a draw of `count` vertices of `draw` records: its whole primitives' (a strip's,
/// fan's or loop's unrolled).
fn recorded(draw: Primitive, count: u32) -> u32 {
    use Primitive::*;
    match draw {
        Points => count,
        Lines => count - count % 2,
        Triangles => count - count % 3,
        LineStrip => 2 * count.saturating_sub(1),
        LineLoop if count >= 2 => 2 * count,
        LineLoop => 0,
        TriangleStrip | TriangleFan => 3 * count.saturating_sub(2),
    }
}

/// A program's capture state for `glGetProgramiv` (`None`: not one of its names).
pub(crate) fn program_state(p: &crate::objects::program::Program, pname: u32) -> Option<i32> {
    let linked = p.linked.as_ref().and_then(|l| l.info.capture.as_ref()).map_or(0, |c| c.varyings.len());
    Some(match pname {
        TRANSFORM_FEEDBACK_BUFFER_MODE => (if p.xfb.1 { SEPARATE_ATTRIBS } else { INTERLEAVED_ATTRIBS }) as i32,
        // The linked varyings where there are any, else those asked for (Mesa's answer).
        TRANSFORM_FEEDBACK_VARYINGS => (if linked > 0 { linked } else { p.xfb.0.len() }) as i32,
        TRANSFORM_FEEDBACK_VARYING_MAX_LENGTH => p.xfb.0.iter().map(|n| n.len() as i32 + 1).max().unwrap_or(0),
        _ => return None,
    })
}

impl GlesExecutor {
    /// Transform feedback's state and limits (`None`: not one of them).
    pub(crate) fn xfb_state(&self, ctx: &Context, pname: u32) -> Option<Vec<i32>> {
        let active = ctx.xfb.active();
        Some(vec![match pname {
            TRANSFORM_FEEDBACK_BINDING => ctx.xfb.bound as i32,
            TRANSFORM_FEEDBACK_ACTIVE => i32::from(active.is_some()),
            TRANSFORM_FEEDBACK_PAUSED => i32::from(active.is_some_and(|a| a.paused)),
            TRANSFORM_FEEDBACK_BUFFER_BINDING => ctx.bindings.xfb_buffer as i32,
            MAX_INTERLEAVED_COMPONENTS_ENUM => MAX_INTERLEAVED_COMPONENTS as i32,
            MAX_SEPARATE_ATTRIBS_ENUM => MAX_SEPARATE_ATTRIBS as i32,
            MAX_SEPARATE_COMPONENTS_ENUM => MAX_SEPARATE_COMPONENTS as i32,
            _ => return None,
        }])
    }

    /// Binds `r` to indexed transform feedback binding `index` of the bound object, and
    /// `r.buffer` to the generic binding (`GL_INVALID_OPERATION` while capture is active).
    pub(crate) fn bind_xfb_range(&mut self, ctx: &mut Context, index: u32, r: RangeBinding) -> GlResult {
        if ctx.xfb.active().is_some() {
            return Err(GlError::InvalidOperation);
        }
        if index as usize >= MAX_BUFFERS {
            return Err(GlError::InvalidValue);
        }
        self.admit(ctx, strata_device::account::Kind::Buffer, ctx.objects.buffers.fresh([r.buffer]))?;
        ctx.objects.buffers.bind(r.buffer);
        if let Some(x) = ctx.xfb.current_mut() {
            x.buffers[index as usize] = r;
        }
        ctx.bindings.xfb_buffer = r.buffer;
        Ok(())
    }

    /// An indexed transform feedback binding's state (`None`: not one of its names).
    pub(crate) fn xfb_binding(&self, ctx: &Context, target: u32, index: u32) -> Option<GlResult<i64>> {
        if !matches!(
            target,
            TRANSFORM_FEEDBACK_BUFFER_BINDING | TRANSFORM_FEEDBACK_BUFFER_START | TRANSFORM_FEEDBACK_BUFFER_SIZE
        ) {
            return None;
        }
        let r = ctx.xfb.current().and_then(|x| x.buffers.get(index as usize).copied());
        Some(r.ok_or(GlError::InvalidValue).map(|r| match target {
            TRANSFORM_FEEDBACK_BUFFER_BINDING => i64::from(r.buffer),
            TRANSFORM_FEEDBACK_BUFFER_START => r.offset as i64,
            _ => r.size as i64,
        }))
    }

    /// Checks a draw of `count` vertices of `mode` (`indexed`: from indices), `instances`
    /// times, against an unpaused capture: its mode, no indices, and room in every buffer.
    /// `None` where nothing is captured.
    pub(crate) fn capture_plan(
        &self,
        ctx: &Context,
        mode: Primitive,
        count: u32,
        indexed: bool,
        instances: u32,
    ) -> GlResult<Option<CapturePlan>> {
        let Some(c) = ctx.xfb.capturing() else { return Ok(None) };
        if indexed || !captures(c.mode, mode) {
            return Err(GlError::InvalidOperation);
        }
        let Some(capture) = c.program.info.capture.as_ref() else { return Ok(None) };
        let per_instance = recorded(mode, count);
        let vertices = u64::from(per_instance) * u64::from(instances);
        let strides: Vec<u64> = (0..c.targets.len()).map(|b| u64::from(capture.stride(b)) * 4).collect();
        for (b, &(_, _, space)) in c.targets.iter().enumerate() {
            if c.written[b] + vertices * strides[b] > space {
                return Err(GlError::InvalidOperation);
            }
        }
        let unroll = !matches!(mode, Primitive::Points | Primitive::Lines | Primitive::Triangles);
        Ok(Some(CapturePlan { per_instance, strides, unroll }))
    }

    /// Counts what a capturing draw of `plan`, `instances` times, wrote.
    pub(crate) fn captured(&mut self, ctx: &mut Context, plan: &CapturePlan, instances: u32) {
        let vertices = u64::from(plan.per_instance) * u64::from(instances);
        let Some(c) = ctx.xfb.current_mut().and_then(|x| x.active.as_mut()) else { return };
        let primitives = vertices / u64::from(vertices_per(c.mode));
        for (w, s) in c.written.iter_mut().zip(&plan.strides) {
            *w += vertices * s;
        }
        if let Some((_, n)) = ctx.xfb.query.as_mut() {
            *n += primitives;
        }
    }

    /// The capturing vertex stage of the program capture draws with (`points`: its points
    /// variant), for the context's clip control and rasterizer discard.
    pub(crate) fn capture_stage(
        &self,
        ctx: &Context,
        points: bool,
        unrolled: bool,
    ) -> Result<wgpu::ShaderModule, String> {
        let c = ctx.xfb.capturing().ok_or("no capture")?;
        c.program.capture_vs(&self.gpu, points, ctx.raster.clip, (ctx.raster.discard, unrolled))
    }

    /// The capture block's bytes and buffers for a draw of `plan` from vertex `first`, after
    /// `done` instances of it drawn by earlier draws of the same call (points).
    pub(crate) fn capture_binding(
        &self,
        ctx: &Context,
        plan: &CapturePlan,
        first: u32,
        done: u32,
    ) -> Option<(Vec<u8>, Vec<wgpu::Buffer>)> {
        let c = ctx.xfb.capturing()?;
        // An unrolled draw's vertices are numbered from 0 in the order they are recorded.
        let first = if plan.unroll { 0 } else { first };
        let mut words = [first, plan.per_instance, plan.per_instance, 0, 0, 0, 0, 0];
        let mut buffers = Vec::new();
        for (b, &(name, offset, _)) in c.targets.iter().enumerate() {
            let before = u64::from(done) * u64::from(plan.per_instance) * plan.strides[b];
            words[4 + b] = u32::try_from((offset + c.written[b] + before) / 4).ok()?;
            buffers.push(ctx.objects.buffers.get(&name)?.gpu.clone()?);
        }
        Some((bytemuck::cast_slice(&words).to_vec(), buffers))
    }

    /// Reads what the capture `c` wrote back into the daemon's copies of its buffers.
    fn read_back(&mut self, ctx: &mut Context, c: &Capturing) {
        self.r.flush();
        for (&(name, offset, _), &written) in c.targets.iter().zip(&c.written) {
            let Some(b) = ctx.objects.buffers.get_mut(&name) else { continue };
            let Some(gpu) = b.gpu.as_ref() else { continue };
            let end = (offset + written).min(b.data.len() as u64);
            let Some(bytes) = self.gpu.read_buffer(&self.r.lane, gpu, offset, end.saturating_sub(offset)) else {
                tracing::warn!("reading back a transform feedback buffer failed");
                continue;
            };
            b.data[offset as usize..offset as usize + bytes.len()].copy_from_slice(&bytes);
            b.generation += 1;
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenTransformFeedbacks(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let fresh = names.iter().filter(|n| *n != 0 && !ctx.xfb.objects.contains_key(n)).count();
        if ctx.xfb.objects.len() + fresh > MAX_OBJECTS {
            return Err(GlError::OutOfMemory);
        }
        for n in names.iter().filter(|&n| n != 0) {
            ctx.xfb.objects.entry(n).or_default();
        }
        Ok(())
    }

    pub(super) fn glDeleteTransformFeedbacks(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in names.iter().filter(|&n| n != 0) {
            if ctx.xfb.objects.get(&n).is_some_and(|x| x.active.is_some()) {
                return Err(GlError::InvalidOperation);
            }
        }
        for n in names.iter().filter(|&n| n != 0) {
            if ctx.xfb.objects.remove(&n).is_some() && ctx.xfb.bound == n {
                ctx.xfb.bound = 0;
            }
        }
        Ok(())
    }

    pub(super) fn glIsTransformFeedback(&mut self, ctx: &mut Context, id: u32) -> bool {
        id != 0 && ctx.xfb.objects.get(&id).is_some_and(|x| x.bound_once)
    }

    pub(super) fn glBindTransformFeedback(&mut self, ctx: &mut Context, target: u32, id: u32) -> GlResult {
        if target != TRANSFORM_FEEDBACK {
            return Err(GlError::InvalidEnum);
        }
        if ctx.xfb.capturing().is_some() {
            return Err(GlError::InvalidOperation);
        }
        let x = ctx.xfb.objects.get_mut(&id).ok_or(GlError::InvalidOperation)?;
        x.bound_once = true;
        ctx.xfb.bound = id;
        Ok(())
    }

    pub(super) fn glBeginTransformFeedback(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        let mode = match Primitive::from_gl(mode) {
            Ok(m @ (Primitive::Points | Primitive::Lines | Primitive::Triangles)) => m,
            _ => return Err(GlError::InvalidEnum),
        };
        if ctx.xfb.active().is_some() {
            return Err(GlError::InvalidOperation);
        }
        let program = ctx.draw_program().ok_or(GlError::InvalidOperation)?;
        let capture = program.info.capture.as_ref().ok_or(GlError::InvalidOperation)?;
        let x: &TransformFeedback = ctx.xfb.current().ok_or(GlError::InvalidOperation)?;
        let mut targets = Vec::new();
        for b in 0..capture.strides.len() {
            let r = x.buffers[b];
            let len = ctx.objects.buffers.get(&r.buffer).filter(|_| r.buffer != 0).map(|b| b.data.len() as u64);
            let len = len.ok_or(GlError::InvalidOperation)?;
            let after = len.saturating_sub(r.offset);
            targets.push((r.buffer, r.offset, if r.size == 0 { after } else { r.size.min(after) }));
        }
        if !self.gpu.features.contains(wgpu::Features::VERTEX_WRITABLE_STORAGE) {
            tracing::warn!("the device cannot write buffers from the vertex stage: no transform feedback");
            return Err(GlError::InvalidOperation);
        }
        let written = vec![0; targets.len()];
        if let Some(x) = ctx.xfb.current_mut() {
            x.active = Some(Capturing { mode, paused: false, program, targets, written });
        }
        Ok(())
    }

    pub(super) fn glEndTransformFeedback(&mut self, ctx: &mut Context) -> GlResult {
        let c = ctx.xfb.current_mut().and_then(|x| x.active.take()).ok_or(GlError::InvalidOperation)?;
        self.read_back(ctx, &c);
        Ok(())
    }

    pub(super) fn glPauseTransformFeedback(&mut self, ctx: &mut Context) -> GlResult {
        let c = ctx.xfb.current_mut().and_then(|x| x.active.as_mut()).ok_or(GlError::InvalidOperation)?;
        if c.paused {
            return Err(GlError::InvalidOperation);
        }
        c.paused = true;
        Ok(())
    }

    pub(super) fn glResumeTransformFeedback(&mut self, ctx: &mut Context) -> GlResult {
        let program = ctx.draw_program();
        let c = ctx.xfb.current_mut().and_then(|x| x.active.as_mut()).ok_or(GlError::InvalidOperation)?;
        if !c.paused || program.is_none_or(|p| p.id != c.program.id) {
            return Err(GlError::InvalidOperation);
        }
        c.paused = false;
        Ok(())
    }

    pub(super) fn glTransformFeedbackVaryings(
        &mut self,
        ctx: &mut Context,
        program: u32,
        count: i32,
        names: Text<'_>,
        buffer_mode: u32,
    ) -> GlResult {
        let separate = match buffer_mode {
            INTERLEAVED_ATTRIBS => false,
            SEPARATE_ATTRIBS => true,
            _ => return Err(GlError::InvalidEnum),
        };
        if count < 0 || (separate && count as usize > MAX_SEPARATE_ATTRIBS) {
            return Err(GlError::InvalidValue);
        }
        let list: Vec<String> = names.as_str().lines().take(count as usize).map(str::to_string).collect();
        let p = ctx.objects.programs.get_mut(&program);
        let Some(p) = p else { return Err(ctx.objects.shader_or_program_error(program)) };
        p.xfb = (list, separate);
        Ok(())
    }

    pub(super) fn glGetTransformFeedbackVarying(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
    ) -> Option<ActiveVariable> {
        let r = match ctx.objects.programs.get(&program) {
            None => Err(ctx.objects.shader_or_program_error(program)),
            Some(p) => p
                .linked
                .as_ref()
                .and_then(|l| l.info.capture.as_ref())
                .and_then(|c| c.varyings.get(index as usize))
                .map(|v| ActiveVariable { size: v.size as i32, ty: v.ty.gl_enum(), name: v.name.clone() })
                .ok_or(GlError::InvalidValue),
        };
        r.map_err(|e| ctx.record(e)).ok()
    }
}

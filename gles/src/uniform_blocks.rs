//! OpenGL ES 3.0's uniform buffers: the indexed bindings (`glBindBufferBase`/`Range`), each
//! block's binding (`glUniformBlockBinding`), the block queries, the limits, and what a draw's
//! blocks read.

use std::sync::Arc;

use strata_protocol::Text;

use crate::context::{Context, RangeBinding};
use crate::error::{GlError, GlResult};
use crate::glsl::blocks::{MAX_COMBINED_UNIFORM_BLOCKS, MAX_STAGE_UNIFORM_BLOCKS, MAX_UNIFORM_BLOCK_SIZE};
use crate::linking::linked_for_query;
use crate::objects::program::LinkedProgram;
use crate::typed::UNIFORM_BUFFER;
use crate::GlesExecutor;
use strata_device::account::Kind;

/// `glGetActiveUniformBlockiv`'s names.
const UNIFORM_BLOCK_BINDING: u32 = 0x8A3F;
const UNIFORM_BLOCK_DATA_SIZE: u32 = 0x8A40;
const UNIFORM_BLOCK_NAME_LENGTH: u32 = 0x8A41;
const UNIFORM_BLOCK_ACTIVE_UNIFORMS: u32 = 0x8A42;
const UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES: u32 = 0x8A43;
const UNIFORM_BLOCK_REFERENCED_BY_VERTEX_SHADER: u32 = 0x8A44;
const UNIFORM_BLOCK_REFERENCED_BY_FRAGMENT_SHADER: u32 = 0x8A46;
/// `glGetIntegeri_v`'s names for the indexed bindings.
const UNIFORM_BUFFER_BINDING: u32 = 0x8A28;
const UNIFORM_BUFFER_START: u32 = 0x8A29;
const UNIFORM_BUFFER_SIZE: u32 = 0x8A2A;
/// The limits.
const MAX_VERTEX_UNIFORM_BLOCKS: u32 = 0x8A2B;
const MAX_FRAGMENT_UNIFORM_BLOCKS: u32 = 0x8A2D;
const MAX_COMBINED_UNIFORM_BLOCKS_ENUM: u32 = 0x8A2E;
const MAX_UNIFORM_BUFFER_BINDINGS: u32 = 0x8A2F;
const MAX_UNIFORM_BLOCK_SIZE_ENUM: u32 = 0x8A30;
const MAX_COMBINED_VERTEX_UNIFORM_COMPONENTS: u32 = 0x8A31;
const MAX_COMBINED_FRAGMENT_UNIFORM_COMPONENTS: u32 = 0x8A33;
const UNIFORM_BUFFER_OFFSET_ALIGNMENT: u32 = 0x8A34;
/// What `glGetUniformBlockIndex` answers for a name no block has.
const INVALID_INDEX: u32 = u32::MAX;

/// Per block of `program`: the buffer and offset it reads through the binding `bindings`
/// gives it, where a buffer is bound there with at least the block's bytes from that offset
/// (else `None`: it reads zeros, where GL leaves what it reads undefined).
pub(crate) fn block_buffers(
    ctx: &Context,
    program: &Arc<LinkedProgram>,
    bindings: &[u32],
) -> Vec<Option<(wgpu::Buffer, u64)>> {
    program
        .info
        .blocks
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let point = bindings.get(k).copied().unwrap_or(0) as usize;
            let r = ctx.bindings.uniform_buffers.get(point)?;
            let buffer = ctx.objects.buffers.get(&r.buffer)?;
            let gpu = buffer.gpu.as_ref()?;
            let len = buffer.data.len() as u64;
            let after = len.checked_sub(r.offset)?;
            let available = if r.size == 0 { after } else { r.size.min(after) };
            (available >= u64::from(b.block.size)).then(|| (gpu.clone(), r.offset))
        })
        .collect()
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// ES 3.0's uniform buffer state and limits (`None`: not one of them).
    pub(crate) fn uniform_block_state(&self, ctx: &Context, pname: u32) -> Option<Vec<i32>> {
        let stage = MAX_STAGE_UNIFORM_BLOCKS as i32;
        let components = |default: i32| default + stage * MAX_UNIFORM_BLOCK_SIZE as i32 / 4;
        Some(vec![match pname {
            UNIFORM_BUFFER_BINDING => ctx.bindings.uniform_buffer as i32,
            MAX_VERTEX_UNIFORM_BLOCKS | MAX_FRAGMENT_UNIFORM_BLOCKS => stage,
            MAX_COMBINED_UNIFORM_BLOCKS_ENUM | MAX_UNIFORM_BUFFER_BINDINGS => MAX_COMBINED_UNIFORM_BLOCKS as i32,
            MAX_UNIFORM_BLOCK_SIZE_ENUM => MAX_UNIFORM_BLOCK_SIZE as i32,
            // The default block's 256 vectors (`GL_MAX_*_UNIFORM_VECTORS`) and every block's.
            MAX_COMBINED_VERTEX_UNIFORM_COMPONENTS | MAX_COMBINED_FRAGMENT_UNIFORM_COMPONENTS => components(4 * 256),
            UNIFORM_BUFFER_OFFSET_ALIGNMENT => self.gpu.limits.min_uniform_buffer_offset_alignment as i32,
            _ => return None,
        }])
    }

    /// Binds `buffer` (its `offset`, `size` bytes; size 0: all of it) to uniform buffer binding
    /// `index` and to the generic binding.
    fn bind_range(&mut self, ctx: &mut Context, target: u32, index: u32, r: RangeBinding) -> GlResult {
        if target == crate::typed::TRANSFORM_FEEDBACK_BUFFER {
            return self.bind_xfb_range(ctx, index, r);
        }
        if target != UNIFORM_BUFFER {
            return Err(GlError::InvalidEnum);
        }
        let slot = ctx.bindings.uniform_buffers.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
        *slot = r;
        self.admit(ctx, Kind::Buffer, ctx.objects.buffers.fresh([r.buffer]))?;
        ctx.objects.buffers.bind(r.buffer);
        ctx.bindings.uniform_buffer = r.buffer;
        Ok(())
    }

    pub(super) fn glBindBufferBase(&mut self, ctx: &mut Context, target: u32, index: u32, buffer: u32) -> GlResult {
        self.bind_range(ctx, target, index, RangeBinding { buffer, offset: 0, size: 0 })
    }

    pub(super) fn glBindBufferRange(
        &mut self,
        ctx: &mut Context,
        target: u32,
        index: u32,
        buffer: u32,
        offset: i64,
        size: i64,
    ) -> GlResult {
        if buffer != 0 && size <= 0 {
            return Err(GlError::InvalidValue);
        }
        // Transform feedback writes words: its ranges start and end on them.
        let align = match target {
            crate::typed::TRANSFORM_FEEDBACK_BUFFER => 4,
            _ => i64::from(self.gpu.limits.min_uniform_buffer_offset_alignment),
        };
        if target == crate::typed::TRANSFORM_FEEDBACK_BUFFER && buffer != 0 && size % 4 != 0 {
            return Err(GlError::InvalidValue);
        }
        if buffer != 0 && (offset < 0 || offset % align != 0) {
            return Err(GlError::InvalidValue);
        }
        let r = if buffer == 0 {
            RangeBinding::default()
        } else {
            RangeBinding { buffer, offset: offset as u64, size: size as u64 }
        };
        self.bind_range(ctx, target, index, r)
    }

    pub(super) fn glUniformBlockBinding(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
        binding: u32,
    ) -> GlResult {
        let p = ctx.objects.programs.get_mut(&program);
        let Some(p) = p else { return Err(ctx.objects.shader_or_program_error(program)) };
        if index as usize >= p.block_bindings.len() || binding as usize >= MAX_COMBINED_UNIFORM_BLOCKS {
            return Err(GlError::InvalidValue);
        }
        p.block_bindings[index as usize] = binding;
        Ok(())
    }

    pub(super) fn glGetUniformBlockIndex(&mut self, ctx: &mut Context, program: u32, name: Text<'_>) -> u32 {
        match ctx.objects.programs.get(&program) {
            // An array of blocks' name alone names its first element (as ES 3.1's resource
            // queries have it, and Mesa).
            Some(p) => p.linked.as_ref().and_then(|l| {
                let first = format!("{}[0]", name.as_str());
                l.info.blocks.iter().position(|b| b.block.name == name.as_str() || b.block.name == first)
            }),
            None => {
                let e = ctx.objects.shader_or_program_error(program);
                ctx.record(e);
                None
            }
        }
        .map_or(INVALID_INDEX, |i| i as u32)
    }

    pub(super) fn glGetActiveUniformBlockiv(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
        pname: u32,
    ) -> Vec<i32> {
        let v = linked_for_query(&ctx.objects, program).and_then(|l| {
            let b = l.info.blocks.get(index as usize).ok_or(GlError::InvalidValue)?;
            let binding =
                ctx.objects.programs.get(&program).and_then(|p| p.block_bindings.get(index as usize).copied());
            if pname == UNIFORM_BLOCK_ACTIVE_UNIFORM_INDICES {
                return Ok(crate::active_uniforms::block_members(&l.info, index));
            }
            Ok(vec![match pname {
                UNIFORM_BLOCK_BINDING => binding.unwrap_or(0) as i32,
                UNIFORM_BLOCK_DATA_SIZE => b.block.size as i32,
                UNIFORM_BLOCK_NAME_LENGTH => b.block.name.len() as i32 + 1,
                UNIFORM_BLOCK_ACTIVE_UNIFORMS => b.block.members.len() as i32,
                UNIFORM_BLOCK_REFERENCED_BY_VERTEX_SHADER => i32::from(b.vertex),
                UNIFORM_BLOCK_REFERENCED_BY_FRAGMENT_SHADER => i32::from(b.fragment),
                _ => return Err(GlError::InvalidEnum),
            }])
        });
        v.unwrap_or_else(|e| {
            ctx.record(e);
            Vec::new()
        })
    }

    /// A block's whole name (the library truncates it to the application's buffer).
    pub(super) fn glGetActiveUniformBlockName(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
    ) -> Option<String> {
        let v = linked_for_query(&ctx.objects, program)
            .and_then(|l| l.info.blocks.get(index as usize).map(|b| b.block.name.clone()).ok_or(GlError::InvalidValue));
        v.map_err(|e| ctx.record(e)).ok()
    }

    /// An indexed binding's state (`GL_UNIFORM_BUFFER_BINDING`, `_START`, `_SIZE`).
    pub(super) fn glGetIntegeri_v(&mut self, ctx: &mut Context, target: u32, index: u32) -> Vec<i32> {
        self.glGetInteger64i_v(ctx, target, index).into_iter().map(|v| v as i32).collect()
    }

    pub(super) fn glGetInteger64i_v(&mut self, ctx: &mut Context, target: u32, index: u32) -> Vec<i64> {
        if let Some(r) = self.xfb_binding(ctx, target, index) {
            return r.map_err(|e| ctx.record(e)).ok().into_iter().collect();
        }
        if !matches!(target, UNIFORM_BUFFER_BINDING | UNIFORM_BUFFER_START | UNIFORM_BUFFER_SIZE) {
            ctx.record(GlError::InvalidEnum);
            return Vec::new();
        }
        let Some(r) = ctx.bindings.uniform_buffers.get(index as usize) else {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        };
        vec![match target {
            UNIFORM_BUFFER_BINDING => i64::from(r.buffer),
            UNIFORM_BUFFER_START => r.offset as i64,
            _ => r.size as i64,
        }]
    }
}

//! Buffer objects: names, bindings, data specification and queries. Each buffer keeps a CPU
//! shadow of its contents, against which draws are validated and from which attribute and
//! index data are converted.

use strata_protocol::{Blob, Slice};

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::objects::buffer::{write_words, Buffer};
use crate::typed::BufferTarget;
use crate::GlesExecutor;
use strata_device::account::Kind;

/// Checks `glBufferData`; the name of the buffer it replaces.
fn validate_buffer_data(ctx: &Context, target: u32, size: i64, data: Option<&Blob<'_>>, usage: u32) -> GlResult<u32> {
    let name = ctx.bindings.buffer(BufferTarget::from_gl(target)?);
    if !matches!(usage, STREAM_DRAW | STATIC_DRAW | DYNAMIC_DRAW) {
        return Err(GlError::InvalidEnum);
    }
    if size < 0 || data.is_some_and(|d| d.len() as i64 != size) {
        return Err(GlError::InvalidValue);
    }
    if name == 0 {
        return Err(GlError::InvalidOperation);
    }
    if size > (1 << 30) {
        return Err(GlError::OutOfMemory);
    }
    Ok(name)
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenBuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        self.admit(ctx, Kind::Buffer, ctx.objects.buffers.fresh(names.iter()))?;
        ctx.objects.buffers.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteBuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.objects.buffers.delete(names.iter()) {
            ctx.objects.forget_label(BUFFER_KHR, n);
            if ctx.bindings.array_buffer == n {
                ctx.bindings.array_buffer = 0;
            }
            if ctx.bindings.element_buffer == n {
                ctx.bindings.element_buffer = 0;
            }
            if ctx.bindings.pixel_pack == n {
                ctx.bindings.pixel_pack = 0;
            }
            if ctx.bindings.pixel_unpack == n {
                ctx.bindings.pixel_unpack = 0;
            }
            for a in &mut ctx.attribs {
                if a.buffer == n {
                    a.buffer = 0;
                }
            }
        }
        Ok(())
    }

    pub(super) fn glBindBuffer(&mut self, ctx: &mut Context, target: u32, buffer: u32) -> GlResult {
        let target = BufferTarget::from_gl(target)?;
        self.admit(ctx, Kind::Buffer, ctx.objects.buffers.fresh([buffer]))?;
        match target {
            BufferTarget::Array => ctx.bindings.array_buffer = buffer,
            BufferTarget::ElementArray => ctx.bindings.element_buffer = buffer,
            BufferTarget::PixelPack => ctx.bindings.pixel_pack = buffer,
            BufferTarget::PixelUnpack => ctx.bindings.pixel_unpack = buffer,
        }
        ctx.objects.buffers.bind(buffer);
        Ok(())
    }

    pub(super) fn glIsBuffer(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.buffers.is(name)
    }

    pub(super) fn glBufferData(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        size: i64,
        data: Option<Blob<'_>>,
        usage: u32,
    ) -> GlResult {
        let account = self.account.clone();
        let gpu = &self.gpu;
        let name = validate_buffer_data(ctx, target, size, data.as_ref(), usage)?;
        let b = ctx.objects.buffers.entry(name).or_default();
        // The old contents' memory is given back before the new contents' is reserved; a
        // mapping ends with them.
        *b = Buffer { generation: b.generation, usage: b.usage, ..Buffer::default() };
        let padded = (size as u64).div_ceil(4).max(1) * 4;
        b._reserved = Some(account.reserve(size as u64 + padded).map_err(|_| GlError::OutOfMemory)?);
        b.data = data.map(|d| d.as_bytes().to_vec()).unwrap_or_else(|| vec![0; size as usize]);
        b.usage = usage;
        b.generation += 1;
        let gbuf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gl buffer"),
            size: padded,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut padded_data = b.data.clone();
        padded_data.resize(padded as usize, 0);
        write_words(gpu, flushed, &gbuf, 0, &padded_data);
        b.gpu = Some(gbuf);
        Ok(())
    }

    pub(super) fn glBufferSubData(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        offset: i64,
        data: Blob<'_>,
    ) -> GlResult {
        let gpu = &self.gpu;
        let name = ctx.bindings.buffer(BufferTarget::from_gl(target)?);
        let b = ctx.objects.buffers.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
        if offset < 0 {
            return Err(GlError::InvalidValue);
        }
        // A mapped buffer is written only through its mapping.
        if b.map.is_some() {
            return Err(GlError::InvalidOperation);
        }
        let end = offset.checked_add(data.len() as i64);
        if end.is_none_or(|e| e as usize > b.data.len()) {
            return Err(GlError::InvalidValue);
        }
        b.write(gpu, flushed, offset as usize, data.as_bytes());
        Ok(())
    }

    pub(super) fn glGetBufferParameteriv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> i32 {
        let name = match BufferTarget::from_gl(target) {
            Ok(t) => ctx.bindings.buffer(t),
            Err(e) => {
                ctx.record(e);
                return 0;
            }
        };
        let Some(b) = ctx.objects.buffers.get(&name).filter(|_| name != 0) else {
            ctx.record(GlError::InvalidOperation);
            return 0;
        };
        if let Some(v) = crate::mapping::parameter(b, pname) {
            return v;
        }
        match pname {
            BUFFER_SIZE => b.data.len() as i32,
            BUFFER_USAGE => {
                if b.usage == 0 {
                    STATIC_DRAW as i32
                } else {
                    b.usage as i32
                }
            }
            _ => {
                ctx.record(GlError::InvalidEnum);
                0
            }
        }
    }
}

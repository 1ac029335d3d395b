//! Buffer objects: names, bindings, data specification and queries. Each buffer keeps a CPU
//! shadow of its contents, against which draws are validated and from which attribute and
//! index data are converted.
//!
//! Mapped buffers (`GL_OES_mapbuffer`, `GL_EXT_map_buffer_range`). The memory an application
//! writes through is the drop-in library's: a map is answered with the mapped bytes, and the
//! library sends back what the application changed, at `glFlushMappedBufferRangeEXT` and at
//! `glUnmapBufferOES`. The daemon keeps what GL says about the mapping (its range and access)
//! and validates every call in Mesa's order.

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::limits::MAX_MAP;
use crate::objects::buffer::Mapping;
use crate::objects::buffer::{write_words, Buffer};
use crate::typed::BufferTarget;
use crate::GlesExecutor;
use strata_device::account::Kind;
use strata_protocol::Bytes;
use strata_protocol::{Blob, Slice};

/// Checks `glBufferData`; the name of the buffer it replaces.
fn validate_buffer_data(ctx: &Context, target: u32, size: i64, data: Option<&Blob<'_>>, usage: u32) -> GlResult<u32> {
    let name = ctx.bindings.buffer(BufferTarget::from_gl(target, ctx.es3())?);
    // ES 3.0 adds the read and copy usages (`GL_STREAM_READ` … `GL_DYNAMIC_COPY`).
    let es3_usage = ctx.es3() && matches!(usage, 0x88E1 | 0x88E2 | 0x88E5 | 0x88E6 | 0x88E9 | 0x88EA);
    if !matches!(usage, STREAM_DRAW | STATIC_DRAW | DYNAMIC_DRAW) && !es3_usage {
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
            if ctx.bindings.uniform_buffer == n {
                ctx.bindings.uniform_buffer = 0;
            }
            for b in ctx.bindings.copy_buffers.iter_mut().filter(|b| **b == n) {
                *b = 0;
            }
            for b in ctx.bindings.uniform_buffers.iter_mut().filter(|b| b.buffer == n) {
                *b = crate::context::RangeBinding::default();
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
        let target = BufferTarget::from_gl(target, ctx.es3())?;
        self.admit(ctx, Kind::Buffer, ctx.objects.buffers.fresh([buffer]))?;
        match target {
            BufferTarget::Array => ctx.bindings.array_buffer = buffer,
            BufferTarget::ElementArray => ctx.bindings.element_buffer = buffer,
            BufferTarget::PixelPack => ctx.bindings.pixel_pack = buffer,
            BufferTarget::PixelUnpack => ctx.bindings.pixel_unpack = buffer,
            BufferTarget::Uniform => ctx.bindings.uniform_buffer = buffer,
            BufferTarget::CopyRead => ctx.bindings.copy_buffers[0] = buffer,
            BufferTarget::CopyWrite => ctx.bindings.copy_buffers[1] = buffer,
            BufferTarget::TransformFeedback => ctx.bindings.xfb_buffer = buffer,
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
        // A streamed blob is read from the ring straight into the shadow.
        b.data = vec![0; size as usize];
        if let Some(d) = &data {
            d.read_into(&mut b.data).map_err(|_| GlError::OutOfMemory)?;
        }
        b.usage = usage;
        b.generation += 1;
        let gbuf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("gl buffer"),
            size: padded,
            usage: wgpu::BufferUsages::VERTEX
                | wgpu::BufferUsages::INDEX
                | wgpu::BufferUsages::UNIFORM
                // Transform feedback writes its buffers from the vertex stage.
                | wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
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
        let b = bound(ctx, target)?;
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
        b.write_blob(gpu, flushed, offset as usize, &data).map_err(|_| GlError::OutOfMemory)
    }

    pub(super) fn glGetBufferParameteriv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> i32 {
        let name = match BufferTarget::from_gl(target, ctx.es3()) {
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
        if let Some(v) = crate::buffers::parameter(b, pname) {
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

/// `GL_MAP_READ_BIT_EXT`.
const READ: u32 = 0x1;
/// `GL_MAP_WRITE_BIT_EXT`.
const WRITE: u32 = 0x2;
/// `GL_MAP_INVALIDATE_RANGE_BIT_EXT`.
const INVALIDATE_RANGE: u32 = 0x4;
/// `GL_MAP_INVALIDATE_BUFFER_BIT_EXT`.
const INVALIDATE_BUFFER: u32 = 0x8;
/// `GL_MAP_FLUSH_EXPLICIT_BIT_EXT`.
const FLUSH_EXPLICIT: u32 = 0x10;
/// `GL_MAP_UNSYNCHRONIZED_BIT_EXT`.
const UNSYNCHRONIZED: u32 = 0x20;
/// `GL_MAP_PERSISTENT_BIT_EXT` and `GL_MAP_COHERENT_BIT_EXT`: buffer storage's, which a
/// buffer made by `glBufferData` cannot be mapped with.
const PERSISTENT_COHERENT: u32 = 0x40 | 0x80;
/// `GL_WRITE_ONLY_OES`, the one access `glMapBufferOES` takes.
const WRITE_ONLY: u32 = 0x88B9;
/// `GL_READ_ONLY`, `GL_BUFFER_ACCESS_OES` for a mapping that only reads.
const READ_ONLY: u32 = 0x88B8;
/// `GL_READ_WRITE`.
const READ_WRITE: u32 = 0x88BA;
/// `GL_BUFFER_ACCESS_OES`.
const BUFFER_ACCESS: u32 = 0x88BB;
/// `GL_BUFFER_MAPPED_OES`.
const BUFFER_MAPPED: u32 = 0x88BC;
/// `GL_BUFFER_ACCESS_FLAGS`.
const BUFFER_ACCESS_FLAGS: u32 = 0x911F;
/// `GL_BUFFER_MAP_LENGTH`.
const BUFFER_MAP_LENGTH: u32 = 0x9120;
/// `GL_BUFFER_MAP_OFFSET`.
const BUFFER_MAP_OFFSET: u32 = 0x9121;

/// The mapping queries of `glGetBufferParameteriv`; `None` for any other `pname`.
pub(crate) fn parameter(b: &Buffer, pname: u32) -> Option<i32> {
    let m = b.map;
    Some(match pname {
        BUFFER_MAPPED => i32::from(m.is_some()),
        BUFFER_ACCESS => {
            let access = match m.map_or(WRITE, |m| m.access) & (READ | WRITE) {
                READ => READ_ONLY,
                x if x == READ | WRITE => READ_WRITE,
                _ => WRITE_ONLY,
            };
            access as i32
        }
        BUFFER_ACCESS_FLAGS => m.map_or(0, |m| m.access) as i32,
        BUFFER_MAP_LENGTH => m.map_or(0, |m| m.length) as i32,
        BUFFER_MAP_OFFSET => m.map_or(0, |m| m.offset) as i32,
        _ => return None,
    })
}

/// The buffer bound to `target`: `GL_INVALID_ENUM` for a target that is not one, and
/// `GL_INVALID_OPERATION` where none is bound.
pub(crate) fn bound(ctx: &mut Context, target: u32) -> GlResult<&mut Buffer> {
    let name = ctx.bindings.buffer(BufferTarget::from_gl(target, ctx.es3())?);
    ctx.objects.buffers.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)
}

/// Checks a map of `length` bytes at `offset` with `access`, in Mesa's order.
fn validate_map(b: &Buffer, offset: i64, length: i64, access: u32) -> GlResult<Mapping> {
    if offset < 0 || length < 0 {
        return Err(GlError::InvalidValue);
    }
    if length == 0 {
        return Err(GlError::InvalidOperation);
    }
    let known = READ | WRITE | INVALIDATE_RANGE | INVALIDATE_BUFFER | FLUSH_EXPLICIT | UNSYNCHRONIZED;
    if access & !(known | PERSISTENT_COHERENT) != 0 {
        return Err(GlError::InvalidValue);
    }
    let read_invalidates = access & READ != 0 && access & (INVALIDATE_RANGE | INVALIDATE_BUFFER | UNSYNCHRONIZED) != 0;
    if access & (READ | WRITE) == 0
        || read_invalidates
        || (access & FLUSH_EXPLICIT != 0 && access & WRITE == 0)
        || access & PERSISTENT_COHERENT != 0
    {
        return Err(GlError::InvalidOperation);
    }
    if offset.checked_add(length).is_none_or(|end| end as usize > b.data.len()) {
        return Err(GlError::InvalidValue);
    }
    if b.map.is_some() {
        return Err(GlError::InvalidOperation);
    }
    if length as usize > MAX_MAP {
        return Err(GlError::OutOfMemory);
    }
    Ok(Mapping { offset: offset as usize, length: length as usize, access })
}

/// Maps the buffer bound to `target`; the mapped bytes, empty where `access` invalidates them.
fn map(ctx: &mut Context, target: u32, range: Option<(i64, i64)>, access: u32) -> GlResult<Bytes> {
    let b = bound(ctx, target)?;
    let (offset, length) = range.unwrap_or((0, b.data.len() as i64));
    let m = validate_map(b, offset, length, access)?;
    b.map = Some(m);
    if access & (INVALIDATE_RANGE | INVALIDATE_BUFFER) != 0 {
        return Ok(Bytes::default());
    }
    Ok(Bytes(b.data[m.offset..m.offset + m.length].to_vec()))
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glMapBufferOES(&mut self, ctx: &mut Context, target: u32, access: u32) -> Option<Bytes> {
        let r = if access == WRITE_ONLY {
            map(ctx, target, None, WRITE)
        } else {
            BufferTarget::from_gl(target, ctx.es3()).and(Err(GlError::InvalidEnum))
        };
        r.map_err(|e| ctx.record(e)).ok()
    }

    pub(super) fn glMapBufferRangeEXT(
        &mut self,
        ctx: &mut Context,
        target: u32,
        offset: i64,
        length: i64,
        access: u32,
    ) -> Option<Bytes> {
        map(ctx, target, Some((offset, length)), access).map_err(|e| ctx.record(e)).ok()
    }

    pub(super) fn glFlushMappedBufferRangeEXT(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        offset: i64,
        length: i64,
        data: Blob<'_>,
    ) -> GlResult {
        let gpu = &self.gpu;
        let b = bound(ctx, target)?;
        if offset < 0 || length < 0 {
            return Err(GlError::InvalidValue);
        }
        let m = b.map.ok_or(GlError::InvalidOperation)?;
        if m.access & FLUSH_EXPLICIT == 0 {
            return Err(GlError::InvalidOperation);
        }
        let end = offset.checked_add(length);
        if end.is_none_or(|e| e as usize > m.length) || data.len() as i64 != length {
            return Err(GlError::InvalidValue);
        }
        b.write(gpu, flushed, m.offset + offset as usize, data.as_bytes());
        Ok(())
    }

    pub(super) fn glUnmapBufferOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        offset: i64,
        data: Blob<'_>,
    ) -> GlResult {
        let gpu = &self.gpu;
        let b = bound(ctx, target)?;
        let m = b.map.take().ok_or(GlError::InvalidOperation)?;
        if data.is_empty() {
            return Ok(());
        }
        // What the library sends back lies within a mapping that writes, and is written
        // through `glFlushMappedBufferRangeEXT` where the mapping says so.
        let inside = usize::try_from(offset)
            .ok()
            .filter(|&o| o >= m.offset && o.checked_add(data.len()).is_some_and(|e| e <= m.offset + m.length));
        match inside {
            Some(o) if m.access & WRITE != 0 && m.access & FLUSH_EXPLICIT == 0 => {
                b.write(gpu, flushed, o, data.as_bytes())
            }
            _ => tracing::debug!(
                offset,
                len = data.len(),
                "glUnmapBufferOES: written bytes outside a writing mapping ignored"
            ),
        }
        Ok(())
    }
}

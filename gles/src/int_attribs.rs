//! ES 3.0's integer vertex attributes: arrays set by `glVertexAttribIPointer` (bytes, shorts
//! and ints, signed or not, never normalized), current values set by `glVertexAttribI4i`/`ui`,
//! and the integer inputs (`in ivecN`, `in uvecN`) of GLSL ES 3.00 vertex shaders that read
//! them. Each array is gathered into 32-bit integers, which wgpu reads for any size (GL's
//! missing components are Vulkan's: 0, 0, 1).

use crate::context::Context;
use crate::conv::component;
use crate::divisors::InstanceReads;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_CONVERTED;
use crate::objects::vertex_array::Attrib;
use crate::render::{Source, VertexInput};
use crate::vertex::{set_array, ArrayPointer, INT};

/// Bytes per component of an integer array's type (`GL_FLOAT` and the others of
/// `glVertexAttribPointer` too, read into an integer input as GL leaves undefined).
pub(crate) fn int_type_size(ty: u32) -> Option<usize> {
    match ty {
        BYTE | UNSIGNED_BYTE => Some(1),
        SHORT | UNSIGNED_SHORT | HALF_FLOAT_OES => Some(2),
        INT | UNSIGNED_INT | FLOAT | FIXED => Some(4),
        _ => None,
    }
}

/// One component as an integer: integer types as they are (sign- or zero-extended), anything
/// else converted as `glVertexAttribPointer` converts it, then truncated.
fn int_component(bytes: &[u8], ty: u32) -> u32 {
    match ty {
        BYTE => bytes[0] as i8 as i32 as u32,
        UNSIGNED_BYTE => u32::from(bytes[0]),
        SHORT => i16::from_ne_bytes([bytes[0], bytes[1]]) as i32 as u32,
        UNSIGNED_SHORT => u32::from(u16::from_ne_bytes([bytes[0], bytes[1]])),
        INT | UNSIGNED_INT => u32::from_ne_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]),
        _ => component(bytes, ty, false) as i32 as u32,
    }
}

/// The wgpu format of `size` 32-bit integers, signed or not.
fn int_format(size: i32, signed: bool) -> wgpu::VertexFormat {
    use wgpu::VertexFormat as F;
    match (size, signed) {
        (1, true) => F::Sint32,
        (2, true) => F::Sint32x2,
        (3, true) => F::Sint32x3,
        (_, true) => F::Sint32x4,
        (1, false) => F::Uint32,
        (2, false) => F::Uint32x2,
        (3, false) => F::Uint32x3,
        (_, false) => F::Uint32x4,
    }
}

/// Plans attribute `a` for an integer shader input at `location` (`signed`: `int`, else `uint`):
/// its current value where the array is disabled, else its array gathered for the draw's
/// `vertex_count` vertices (in `order` for gathered draws; per instance with a divisor), what
/// lies past it read as zeros where `robust`, else `GL_INVALID_OPERATION`.
pub(crate) fn plan_integer(
    ctx: &Context,
    a: &Attrib,
    location: u32,
    signed: bool,
    (vertex_count, order, robust): (u64, Option<&[u32]>, bool),
    reads: InstanceReads,
) -> GlResult<VertexInput> {
    if !a.enabled {
        let words = a.current_int.unwrap_or(a.current.map(|f| f as i32 as u32));
        let source = Source::Bytes(bytemuck::cast_slice(&words).to_vec());
        return Ok(VertexInput { location, format: int_format(4, signed), stride: 0, source, per_instance: false });
    }
    let (data, offset): (&[u8], u64) = if a.buffer == 0 {
        (a.client.as_ref().ok_or(GlError::InvalidOperation)?, 0)
    } else {
        (&ctx.objects.buffers.get(&a.buffer).ok_or(GlError::InvalidOperation)?.data, a.offset)
    };
    let ts = int_type_size(a.ty).ok_or(GlError::InvalidOperation)?;
    let elem = ts * a.size as usize;
    let stride = if a.stride == 0 { elem as u64 } else { a.stride as u64 };
    // The element each row reads: per vertex (in order), or per instance with a divisor.
    let (rows, per_instance): (Vec<u64>, bool) = match (a.divisor, reads) {
        (0, _) => {
            (order.map_or_else(|| (0..vertex_count).collect(), |o| o.iter().map(|&v| u64::from(v)).collect()), false)
        }
        (d, InstanceReads::Drawn(n)) => ((0..u64::from(n.max(1))).map(|i| i / u64::from(d)).collect(), true),
        (d, InstanceReads::One(i)) => (vec![u64::from(i) / u64::from(d)], false),
    };
    let bytes = rows.len().checked_mul(a.size as usize * 4).filter(|&b| b <= MAX_CONVERTED);
    let mut out = Vec::with_capacity(bytes.ok_or(GlError::OutOfMemory)?);
    for &e in &rows {
        let base = e.checked_mul(stride).and_then(|x| x.checked_add(offset));
        match base.filter(|b| b.checked_add(elem as u64).is_some_and(|end| end <= data.len() as u64)) {
            Some(base) => {
                for c in 0..a.size as usize {
                    let at = base as usize + c * ts;
                    out.extend_from_slice(&int_component(&data[at..at + ts], a.ty).to_ne_bytes());
                }
            }
            None if robust => out.extend(std::iter::repeat_n(0u8, a.size as usize * 4)),
            None => return Err(GlError::InvalidOperation),
        }
    }
    // One instance's element (points) is a constant over the draw.
    let stride = if matches!(reads, InstanceReads::One(_)) && a.divisor > 0 { 0 } else { a.size as u64 * 4 };
    Ok(VertexInput { location, format: int_format(a.size, signed), stride, source: Source::Bytes(out), per_instance })
}

#[allow(non_snake_case)]
impl crate::GlesExecutor {
    /// An integer array: as `glVertexAttribPointer`, for integer types only, never normalized.
    pub(super) fn glVertexAttribIPointer(
        &mut self,
        ctx: &mut Context,
        index: u32,
        size: i32,
        attrib_type: u32,
        stride: i32,
        offset: u64,
    ) -> GlResult {
        let p = ArrayPointer { index, size, ty: attrib_type, normalized: false, stride, offset, integer: true };
        set_array(ctx, p)
    }

    /// A current value of signed integers.
    pub(super) fn glVertexAttribI4i(
        &mut self,
        ctx: &mut Context,
        index: u32,
        x: i32,
        y: i32,
        z: i32,
        w: i32,
    ) -> GlResult {
        let a = ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
        a.current_int = Some([x as u32, y as u32, z as u32, w as u32]);
        a.current = [x, y, z, w].map(|v| v as f32);
        Ok(())
    }

    /// A current value of unsigned integers.
    pub(super) fn glVertexAttribI4ui(
        &mut self,
        ctx: &mut Context,
        index: u32,
        x: u32,
        y: u32,
        z: u32,
        w: u32,
    ) -> GlResult {
        let a = ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
        a.current_int = Some([x, y, z, w]);
        a.current = [x, y, z, w].map(|v| v as f32);
        Ok(())
    }

    /// An attribute's state as integers; the current value as its integers.
    pub(super) fn glGetVertexAttribIiv(&mut self, ctx: &mut Context, index: u32, pname: u32) -> Vec<i32> {
        self.glGetVertexAttribIuiv(ctx, index, pname).into_iter().map(|v| v as i32).collect()
    }

    /// The same, unsigned.
    pub(super) fn glGetVertexAttribIuiv(&mut self, ctx: &mut Context, index: u32, pname: u32) -> Vec<u32> {
        let Some(a) = ctx.attribs.get(index as usize) else {
            ctx.record(GlError::InvalidValue);
            return Vec::new();
        };
        match pname {
            CURRENT_VERTEX_ATTRIB => a.current_int.unwrap_or(a.current.map(|f| f as i32 as u32)).to_vec(),
            crate::vertex::VERTEX_ATTRIB_ARRAY_INTEGER => vec![u32::from(a.integer)],
            0x88FE => vec![a.divisor],
            _ => match crate::vertex::attrib_param(a, pname) {
                Some(v) => vec![v as u32],
                None => {
                    ctx.record(GlError::InvalidEnum);
                    Vec::new()
                }
            },
        }
    }
}

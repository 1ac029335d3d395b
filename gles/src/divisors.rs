//! Instanced vertex attributes (`glVertexAttribDivisor`, ES 3.0): an attribute with divisor d
//! advances once every d instances. wgpu steps a vertex buffer once per instance, so a buffer
//! array with divisor 1 in a format wgpu reads is bound as it is; any other is gathered, one
//! element per instance drawn (element ⌊i / d⌋ for instance i), and converted to floats.

use crate::context::Context;
use crate::conv::{element_size, float_format, native_format};
use crate::error::{GlError, GlResult};
use crate::limits::MAX_CONVERTED;
use crate::objects::vertex_array::Attrib;
use crate::render::{Source, VertexInput};

/// The instances one planned draw's per-instance attributes are read for.
#[derive(Clone, Copy, Debug)]
pub(crate) enum InstanceReads {
    /// wgpu draws instances 0 to n − 1 at once.
    Drawn(u32),
    /// One instance, by its number: `GL_POINTS`, whose wgpu instances are the points, draw each
    /// GL instance on its own, so its per-instance attributes are constants.
    One(u32),
}

/// Plans attribute `a` (enabled, with a divisor above 0) at shader location `location`.
pub(crate) fn plan_divided(ctx: &Context, a: &Attrib, location: u32, reads: InstanceReads) -> GlResult<VertexInput> {
    let divisor = u64::from(a.divisor.max(1));
    let (data, gpu, offset): (&[u8], Option<&wgpu::Buffer>, u64) = if a.buffer == 0 {
        (a.client.as_ref().ok_or(GlError::InvalidOperation)?, None, 0)
    } else {
        let buf = ctx.objects.buffers.get(&a.buffer).ok_or(GlError::InvalidOperation)?;
        (&buf.data, buf.gpu.as_ref(), a.offset)
    };
    let elem = element_size(a.ty, a.size);
    let stride = if a.stride == 0 { elem as u64 } else { a.stride as u64 };
    // The elements the draw reads: ⌈instances / d⌉, or the one instance's.
    let (first, elements) = match reads {
        InstanceReads::Drawn(n) => (0, u64::from(n).div_ceil(divisor).max(1)),
        InstanceReads::One(i) => (u64::from(i) / divisor, 1),
    };
    let end = (first + elements - 1)
        .checked_mul(stride)
        .and_then(|x| x.checked_add(offset))
        .and_then(|x| x.checked_add(elem as u64))
        .filter(|&n| n <= data.len() as u64)
        .ok_or(GlError::InvalidOperation)?;
    if let (InstanceReads::Drawn(_), 1, Some(g), Some(format)) =
        (reads, divisor, gpu, native_format(a.ty, a.size, a.normalized))
    {
        if offset.is_multiple_of(4) && stride.is_multiple_of(4) {
            return Ok(VertexInput {
                location,
                format,
                stride,
                source: Source::Buffer(g.clone(), offset),
                per_instance: true,
            });
        }
    }
    // Gathered: one element per instance drawn (or a constant for the one instance).
    let rows = match reads {
        InstanceReads::Drawn(n) => u64::from(n.max(1)),
        InstanceReads::One(_) => 1,
    };
    let bytes = (rows as usize).checked_mul(a.size as usize * 4).filter(|&b| b <= MAX_CONVERTED);
    let mut out = Vec::with_capacity(bytes.ok_or(GlError::OutOfMemory)?);
    for row in 0..rows {
        let element = match reads {
            InstanceReads::Drawn(_) => row / divisor,
            InstanceReads::One(_) => first,
        };
        let base = (element * stride + offset) as usize;
        debug_assert!(base as u64 + elem as u64 <= end);
        crate::conv::element(&data[base..base + elem], a.ty, a.size, a.normalized, &mut out);
    }
    let stride = match reads {
        InstanceReads::Drawn(_) => a.size as u64 * 4,
        InstanceReads::One(_) => 0,
    };
    Ok(VertexInput { location, format: float_format(a.size), stride, source: Source::Bytes(out), per_instance: true })
}

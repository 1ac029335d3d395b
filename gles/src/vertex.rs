//! Generic vertex attributes: array pointers (buffer objects or client-side arrays), enables,
//! current values, and their queries.
//!
//! Vertex array objects (`GL_OES_vertex_array_object`): named containers of the vertex attribute
//! arrays (enables, pointers, their buffers) and the element array buffer binding.
//!
//! The bound vertex array's state lives in the context itself (`Context::attribs` and
//! `Bindings::element_buffer`), where draws and the vertex and buffer calls use it; the ones
//! not bound keep theirs in `Objects::vertex_arrays` (vertex array 0, the default, included
//! while another is bound). Binding exchanges the two. Current attribute values
//! (`glVertexAttrib*`) are context state, not vertex array state, so they stay where they are.

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_ATTRIBS;
use crate::objects::vertex_array::Attrib;
use crate::objects::vertex_array::VertexArray;
use crate::GlesExecutor;
use strata_protocol::{Blob, Slice};

/// The component types a client may convert a `GL_FLOAT` array to for the wire.
fn wire_type(ty: u32) -> bool {
    matches!(ty, FLOAT | HALF_FLOAT_OES | FIXED)
}

/// An integer parameter of an attribute's array, `None` if `pname` is not one.
pub(crate) fn attrib_param(a: &Attrib, pname: u32) -> Option<i32> {
    let (ty, stride) = a.declared.unwrap_or((a.ty, a.stride));
    Some(match pname {
        VERTEX_ATTRIB_ARRAY_ENABLED => i32::from(a.enabled),
        VERTEX_ATTRIB_ARRAY_SIZE => a.size,
        VERTEX_ATTRIB_ARRAY_STRIDE => stride,
        VERTEX_ATTRIB_ARRAY_TYPE => ty as i32,
        VERTEX_ATTRIB_ARRAY_NORMALIZED => i32::from(a.normalized),
        VERTEX_ATTRIB_ARRAY_BUFFER_BINDING => a.buffer as i32,
        _ => return None,
    })
}

/// `GL_INT` (ES 3.0's integer arrays).
pub(crate) const INT: u32 = 0x1404;

/// What `glVertexAttribPointer` and `glVertexAttribIPointer` set.
pub(crate) struct ArrayPointer {
    pub(crate) index: u32,
    pub(crate) size: i32,
    pub(crate) ty: u32,
    pub(crate) normalized: bool,
    pub(crate) stride: i32,
    pub(crate) offset: u64,
    /// `glVertexAttribIPointer`'s: integer types only, read as integers.
    pub(crate) integer: bool,
}

/// Points attribute `p.index` at an array, checked in Mesa's order: index, size and stride
/// (`GL_INVALID_VALUE`), the type (`GL_INVALID_ENUM`), a client array in a vertex array object
/// (`GL_INVALID_OPERATION`).
pub(crate) fn set_array(ctx: &mut Context, p: ArrayPointer) -> GlResult {
    if p.index as usize >= MAX_ATTRIBS || !(1..=4).contains(&p.size) || p.stride < 0 {
        return Err(GlError::InvalidValue);
    }
    let typed = match p.integer {
        true => matches!(p.ty, BYTE | UNSIGNED_BYTE | SHORT | UNSIGNED_SHORT | UNSIGNED_INT | INT),
        false => crate::conv::attrib_type(p.ty, ctx.es3()),
    };
    if !typed {
        return Err(GlError::InvalidEnum);
    }
    // The packed types hold four components (ES 3.0 §2.9).
    if crate::conv::packed(p.ty) && p.size != 4 {
        return Err(GlError::InvalidOperation);
    }
    // With no array buffer bound the pointer names a client-side array, whose bytes arrive with
    // `strataVertexAttribData` before each draw. A vertex array object cannot hold one
    // (`GL_OES_vertex_array_object`); a null pointer detaches its buffer.
    let buffer = ctx.bindings.array_buffer;
    if buffer == 0 && p.offset != 0 && ctx.bindings.vertex_array != 0 {
        return Err(GlError::InvalidOperation);
    }
    let a = &mut ctx.attribs[p.index as usize];
    a.declared = None;
    a.integer = p.integer;
    (a.size, a.ty, a.normalized, a.stride, a.offset, a.buffer) =
        (p.size, p.ty, p.normalized, p.stride, p.offset, buffer);
    Ok(())
}

/// Sets attribute `index`'s current value.
fn set_current(ctx: &mut Context, index: u32, v: [f32; 4]) -> GlResult {
    let a = ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
    a.current = v;
    a.current_int = None;
    Ok(())
}

/// The first `n` of `values` as a current value (missing components from (0, 0, 0, 1)).
fn current_from(values: &Slice<'_, f32>, n: usize) -> GlResult<[f32; 4]> {
    if values.len() < n {
        return Err(GlError::InvalidValue);
    }
    let mut v = [0.0, 0.0, 0.0, 1.0];
    for (i, x) in values.iter().take(n).enumerate() {
        v[i] = x;
    }
    Ok(v)
}

/// `GL_VERTEX_ATTRIB_ARRAY_DIVISOR` (ES 3.0).
const VERTEX_ATTRIB_ARRAY_DIVISOR: u32 = 0x88FE;
/// `GL_VERTEX_ATTRIB_ARRAY_INTEGER` (ES 3.0).
pub(crate) const VERTEX_ATTRIB_ARRAY_INTEGER: u32 = 0x88FD;

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glVertexAttribPointer(
        &mut self,
        ctx: &mut Context,
        index: u32,
        size: i32,
        attrib_type: u32,
        normalized: bool,
        stride: i32,
        offset: u64,
    ) -> GlResult {
        set_array(ctx, ArrayPointer { index, size, ty: attrib_type, normalized, stride, offset, integer: false })
    }

    /// ES 3.0: attribute `index` advances once every `divisor` instances (0: per vertex).
    pub(super) fn glVertexAttribDivisor(&mut self, ctx: &mut Context, index: u32, divisor: u32) -> GlResult {
        let a = ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
        a.divisor = divisor;
        Ok(())
    }

    pub(super) fn strataVertexAttribData(&mut self, ctx: &mut Context, index: u32, data: Blob<'_>) -> GlResult {
        match ctx.attribs.get_mut(index as usize) {
            Some(a) if a.buffer == 0 => {
                a.restore_declared();
                a.client = Some(data.as_bytes().to_vec());
            }
            Some(_) => return Err(GlError::InvalidOperation),
            None => return Err(GlError::InvalidValue),
        }
        Ok(())
    }

    /// A `GL_FLOAT` client-side array converted for the wire: the next draw reads `data` as
    /// tightly packed `attrib_type` components; queries keep answering the application's type
    /// and stride. An unknown type is `GL_INVALID_ENUM`, an array that is not a client-side
    /// `GL_FLOAT` one `GL_INVALID_OPERATION`; either leaves the attribute as it was.
    pub(super) fn strataVertexAttribDataPacked(
        &mut self,
        ctx: &mut Context,
        index: u32,
        attrib_type: u32,
        data: Blob<'_>,
    ) -> GlResult {
        let a = ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?;
        if !wire_type(attrib_type) {
            return Err(GlError::InvalidEnum);
        }
        let declared = a.declared.unwrap_or((a.ty, a.stride));
        if a.buffer != 0 || declared.0 != FLOAT {
            return Err(GlError::InvalidOperation);
        }
        a.declared = Some(declared);
        a.ty = attrib_type;
        a.stride = 0;
        a.client = Some(data.as_bytes().to_vec());
        Ok(())
    }

    pub(super) fn glEnableVertexAttribArray(&mut self, ctx: &mut Context, index: u32) -> GlResult {
        ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?.enabled = true;
        Ok(())
    }

    pub(super) fn glDisableVertexAttribArray(&mut self, ctx: &mut Context, index: u32) -> GlResult {
        ctx.attribs.get_mut(index as usize).ok_or(GlError::InvalidValue)?.enabled = false;
        Ok(())
    }

    pub(super) fn glVertexAttrib1f(&mut self, ctx: &mut Context, index: u32, x: f32) -> GlResult {
        set_current(ctx, index, [x, 0.0, 0.0, 1.0])
    }

    pub(super) fn glVertexAttrib2f(&mut self, ctx: &mut Context, index: u32, x: f32, y: f32) -> GlResult {
        set_current(ctx, index, [x, y, 0.0, 1.0])
    }

    pub(super) fn glVertexAttrib3f(&mut self, ctx: &mut Context, index: u32, x: f32, y: f32, z: f32) -> GlResult {
        set_current(ctx, index, [x, y, z, 1.0])
    }

    pub(super) fn glVertexAttrib4f(
        &mut self,
        ctx: &mut Context,
        index: u32,
        x: f32,
        y: f32,
        z: f32,
        w: f32,
    ) -> GlResult {
        set_current(ctx, index, [x, y, z, w])
    }

    pub(super) fn glVertexAttrib1fv(&mut self, ctx: &mut Context, index: u32, values: Slice<'_, f32>) -> GlResult {
        set_current(ctx, index, current_from(&values, 1)?)
    }

    pub(super) fn glVertexAttrib2fv(&mut self, ctx: &mut Context, index: u32, values: Slice<'_, f32>) -> GlResult {
        set_current(ctx, index, current_from(&values, 2)?)
    }

    pub(super) fn glVertexAttrib3fv(&mut self, ctx: &mut Context, index: u32, values: Slice<'_, f32>) -> GlResult {
        set_current(ctx, index, current_from(&values, 3)?)
    }

    pub(super) fn glVertexAttrib4fv(&mut self, ctx: &mut Context, index: u32, values: Slice<'_, f32>) -> GlResult {
        set_current(ctx, index, current_from(&values, 4)?)
    }

    pub(super) fn glGetVertexAttribfv(&mut self, ctx: &mut Context, index: u32, pname: u32) -> Vec<f32> {
        let Some(a) = ctx.attribs.get(index as usize) else {
            ctx.record(GlError::InvalidValue);
            return vec![];
        };
        match pname {
            CURRENT_VERTEX_ATTRIB => a.current.to_vec(),
            _ => match attrib_param(a, pname) {
                Some(i) => vec![i as f32],
                None => {
                    ctx.record(GlError::InvalidEnum);
                    vec![]
                }
            },
        }
    }

    pub(super) fn glGetVertexAttribiv(&mut self, ctx: &mut Context, index: u32, pname: u32) -> Vec<i32> {
        let Some(a) = ctx.attribs.get(index as usize) else {
            ctx.record(GlError::InvalidValue);
            return vec![];
        };
        match pname {
            CURRENT_VERTEX_ATTRIB => a.current.iter().map(|f| *f as i32).collect(),
            VERTEX_ATTRIB_ARRAY_DIVISOR if ctx.es3() => vec![a.divisor as i32],
            VERTEX_ATTRIB_ARRAY_INTEGER if ctx.es3() => vec![i32::from(a.integer)],
            _ => match attrib_param(a, pname) {
                Some(i) => vec![i],
                None => {
                    ctx.record(GlError::InvalidEnum);
                    vec![]
                }
            },
        }
    }

    pub(super) fn glGetVertexAttribPointerv(&mut self, ctx: &mut Context, index: u32, pname: u32) -> u64 {
        if pname != VERTEX_ATTRIB_ARRAY_POINTER {
            ctx.record(GlError::InvalidEnum);
            return 0;
        }
        match ctx.attribs.get(index as usize) {
            Some(a) => a.offset,
            None => {
                ctx.record(GlError::InvalidValue);
                0
            }
        }
    }
}

/// Exchanges the context's vertex array state with `vao`'s, keeping the current values.
fn exchange(ctx: &mut Context, vao: &mut VertexArray) {
    for (bound, stored) in ctx.attribs.iter_mut().zip(vao.attribs.iter_mut()) {
        let current = bound.current;
        std::mem::swap(bound, stored);
        bound.current = current;
    }
    std::mem::swap(&mut ctx.bindings.element_buffer, &mut vao.element_buffer);
}

/// Binds vertex array `array`, which must exist (`GL_INVALID_OPERATION` otherwise).
fn bind(ctx: &mut Context, array: u32) -> GlResult {
    let old = ctx.bindings.vertex_array;
    if array == old {
        return Ok(());
    }
    let mut next = ctx.objects.vertex_arrays.remove(&array).ok_or(GlError::InvalidOperation)?;
    exchange(ctx, &mut next);
    next.ever_bound = true;
    ctx.objects.vertex_arrays.insert(old, next);
    ctx.bindings.vertex_array = array;
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenVertexArraysOES(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let bound = ctx.bindings.vertex_array;
        // The bound array is not in the table (its state is the context's) and stays as it is.
        let fresh = || names.iter().filter(move |&n| n != bound);
        self.admit(ctx, strata_device::account::Kind::VertexArray, ctx.objects.vertex_arrays.fresh(fresh()))?;
        ctx.objects.vertex_arrays.generate(fresh());
        Ok(())
    }

    pub(super) fn glBindVertexArrayOES(&mut self, ctx: &mut Context, array: u32) -> GlResult {
        bind(ctx, array)
    }

    /// Deleting the bound vertex array binds the default one; unknown names and 0 are ignored.
    pub(super) fn glDeleteVertexArraysOES(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let bound = ctx.bindings.vertex_array;
        if bound != 0 && names.iter().any(|n| n == bound) {
            bind(ctx, 0)?;
        }
        for n in ctx.objects.vertex_arrays.delete(names.iter()) {
            ctx.objects.forget_label(VERTEX_ARRAY_KHR, n);
        }
        Ok(())
    }

    pub(super) fn glIsVertexArrayOES(&mut self, ctx: &mut Context, array: u32) -> bool {
        array != 0
            && (array == ctx.bindings.vertex_array
                || ctx.objects.vertex_arrays.get(&array).is_some_and(|v| v.ever_bound))
    }
}

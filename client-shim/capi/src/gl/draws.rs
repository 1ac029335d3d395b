//! Element draws and multi-draws. `glDrawElements` and `GL_OES_draw_elements_base_vertex`'s
//! `glDrawElementsBaseVertexOES` (also by `GL_EXT_draw_elements_base_vertex`'s name) send the
//! client arrays their indices read (each index plus the base, if any) and the draw; the daemon
//! offsets the indices. `GL_EXT_multi_draw_arrays`' multi-draws go as one command where every
//! array is in a buffer, and draw by draw where client arrays must be sent for each.
//! `GL_EXT_draw_instanced`'s draws send what the single draw sends.

use std::ffi::c_void;

use strata_client::ClientError;
use strata_protocol::{Blob, Calls, Slice};

use super::{bytes, send_client_arrays, type_size, uses_client_arrays, vertex_count, with_gl, Gl};
use crate::types::*;

/// What an element draw adds to `glDrawElements`.
#[derive(Clone, Copy)]
pub(super) enum Extra {
    /// Nothing: `glDrawElements`.
    None,
    /// A base vertex added to each index (`glDrawElementsBaseVertexOES`).
    Base(GLint),
    /// Instances (`glDrawElementsInstancedEXT`).
    Instances(GLsizei),
}

/// An element draw of `count` indices of `ty` at `indices` (an offset into the bound element
/// buffer, or a client-side array, which is sent along), with what `extra` adds.
pub(super) fn draw_elements(
    gl: &mut Gl<'_>,
    mode: GLenum,
    count: GLsizei,
    ty: GLenum,
    indices: *const c_void,
    extra: Extra,
) -> Result<(), ClientError> {
    let draw_buffer = |gl: &mut Gl<'_>| {
        let offset = indices as usize as u64;
        match extra {
            Extra::None => gl.conn.glDrawElements(mode, count, ty, offset),
            Extra::Base(b) => gl.conn.glDrawElementsBaseVertexOES(mode, count, ty, offset, b),
            Extra::Instances(n) => gl.conn.glDrawElementsInstancedEXT(mode, count, ty, offset, n),
        }
    };
    let Some(size) = type_size(ty).filter(|_| count > 0) else {
        // The daemon validates and records the error.
        return draw_buffer(gl);
    };
    let len = size * count as usize;
    let instances = match extra {
        Extra::Instances(n) => n.max(0) as u64,
        _ => 1,
    };
    // The vertices the draw reads: up to the largest index, plus the base.
    let reach = |n: u64| match extra {
        Extra::Base(b) if n > 0 => (n as i64 + i64::from(b)).max(0) as u64,
        _ => n,
    };
    if gl.st.element_buffer != 0 {
        if uses_client_arrays(gl.st) {
            let offset = indices as usize;
            let n = gl
                .shadows
                .get(&gl.st.element_buffer)
                .and_then(|b| b.get(offset..offset.checked_add(len)?))
                .map_or(0, |d| vertex_count(d, ty, gl.st.restart));
            send_client_arrays(gl, reach(n), instances)?;
        }
        return draw_buffer(gl);
    }
    if indices.is_null() {
        gl.st.err(GL_INVALID_OPERATION);
        return Ok(());
    }
    // SAFETY: a client-side index array holds `count` indices.
    let data = unsafe { bytes(indices, len) };
    if uses_client_arrays(gl.st) {
        send_client_arrays(gl, reach(vertex_count(data, ty, gl.st.restart)), instances)?;
    }
    let data = Blob::borrowed(data);
    match extra {
        Extra::None => gl.conn.strataDrawElementsData(mode, count, ty, data),
        Extra::Base(b) => gl.conn.strataDrawElementsBaseVertexData(mode, count, ty, data, b),
        Extra::Instances(n) => gl.conn.strataDrawElementsInstancedData(mode, count, ty, data, n),
    }
}

/// A slice of the first `n` values at `ptr`, or none where the application passed no array.
fn values<'a, T>(ptr: *const T, n: GLsizei) -> &'a [T] {
    match usize::try_from(n) {
        // SAFETY: the application's array holds `drawcount` values.
        Ok(n) if n > 0 && !ptr.is_null() => unsafe { std::slice::from_raw_parts(ptr, n) },
        _ => &[],
    }
}

/// The errors the daemon gives a multi-draw, in its order: a negative draw count, a mode or
/// index type GL does not have, a negative count.
fn multi_draw_error(mode: GLenum, ty: Option<GLenum>, counts: &[GLsizei], drawcount: GLsizei) -> Option<GLenum> {
    if drawcount < 0 {
        Some(GL_INVALID_VALUE)
    } else if mode > 0x0006 /* TRIANGLE_FAN */ || ty.is_some_and(|t| !matches!(t, GL_UNSIGNED_BYTE | GL_UNSIGNED_SHORT | GL_UNSIGNED_INT))
    {
        Some(GL_INVALID_ENUM)
    } else if counts.iter().any(|&c| c < 0) {
        Some(GL_INVALID_VALUE)
    } else {
        None
    }
}

/// Element multi-draws: one command from the element buffer, or where client indices or
/// client arrays are involved, validated here and drawn one by one as `glDrawElements` draws.
fn multi_draw_elements(
    gl: &mut Gl<'_>,
    mode: GLenum,
    count: *const GLsizei,
    ty: GLenum,
    indices: *const *const c_void,
    drawcount: GLsizei,
    base: *const GLint,
) -> Result<(), ClientError> {
    let counts = values(count, drawcount);
    let pointers = values(indices, drawcount);
    let bases = (!base.is_null()).then(|| values(base, drawcount));
    if gl.st.element_buffer != 0 && !uses_client_arrays(gl.st) {
        let offsets: Vec<u64> = pointers.iter().map(|&p| p as usize as u64).collect();
        let (counts, offsets) = (Slice::new(counts), Slice::from_vec(offsets));
        return match bases {
            None => gl.conn.glMultiDrawElementsEXT(mode, counts, ty, offsets, drawcount),
            Some(b) => gl.conn.glMultiDrawElementsBaseVertexEXT(mode, counts, ty, offsets, drawcount, Slice::new(b)),
        };
    }
    if let Some(e) = multi_draw_error(mode, Some(ty), counts, drawcount) {
        gl.st.err(e);
        return Ok(());
    }
    for (i, (&c, &p)) in counts.iter().zip(pointers).enumerate().filter(|&(_, (&c, _))| c > 0) {
        let extra = bases.map_or(Extra::None, |b| Extra::Base(b.get(i).copied().unwrap_or(0)));
        draw_elements(gl, mode, c, ty, p, extra)?;
    }
    Ok(())
}

crate::entry::entry_points! {
    /// Indices from the bound element buffer, or a client-side index array sent along, each
    /// plus `basevertex`.
    fn glDrawElementsBaseVertexOES(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, basevertex: GLint) {
        with_gl("glDrawElementsBaseVertexOES", (), |gl| draw_elements(gl, mode, count, ty, indices, Extra::Base(basevertex)))
    }

    /// `GL_EXT_draw_elements_base_vertex`'s name for `glDrawElementsBaseVertexOES`.
    fn glDrawElementsBaseVertexEXT(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, basevertex: GLint) {
        with_gl("glDrawElementsBaseVertexEXT", (), |gl| draw_elements(gl, mode, count, ty, indices, Extra::Base(basevertex)))
    }

    /// One command: the client arrays the draws read (up to the furthest vertex), then the
    /// arrays of firsts and counts.
    fn glMultiDrawArraysEXT(mode: GLenum, first: *const GLint, count: *const GLsizei, drawcount: GLsizei) {
        with_gl("glMultiDrawArraysEXT", (), |gl| {
            let (firsts, counts) = (values(first, drawcount), values(count, drawcount));
            if uses_client_arrays(gl.st) && multi_draw_error(mode, None, counts, drawcount).is_none() {
                let reach = firsts.iter().zip(counts).filter(|&(&f, &c)| f >= 0 && c > 0);
                let reach = reach.map(|(&f, &c)| f as u64 + c as u64).max().unwrap_or(0);
                if reach > 0 {
                    send_client_arrays(gl, reach, 1)?;
                }
            }
            gl.conn.glMultiDrawArraysEXT(mode, Slice::new(firsts), Slice::new(counts), drawcount)
        })
    }

    /// Element draws, one per entry: see [`multi_draw_elements`].
    fn glMultiDrawElementsEXT(mode: GLenum, count: *const GLsizei, ty: GLenum, indices: *const *const c_void, drawcount: GLsizei) {
        with_gl("glMultiDrawElementsEXT", (), |gl| multi_draw_elements(gl, mode, count, ty, indices, drawcount, std::ptr::null()))
    }

    /// Element draws, one per entry, each with its base vertex: see [`multi_draw_elements`].
    fn glMultiDrawElementsBaseVertexEXT(
        mode: GLenum,
        count: *const GLsizei,
        ty: GLenum,
        indices: *const *const c_void,
        drawcount: GLsizei,
        basevertex: *const GLint,
    ) {
        with_gl("glMultiDrawElementsBaseVertexEXT", (), |gl| {
            // A base-vertex multi-draw always has its array of bases, even if empty.
            let base = if basevertex.is_null() { [0i32; 0].as_ptr() } else { basevertex };
            multi_draw_elements(gl, mode, count, ty, indices, drawcount, base)
        })
    }

    /// ES 3.0: `glDrawElements` whose indices the application says lie in [start, end]
    /// (`GL_INVALID_VALUE` where end < start, checked first, as on Mesa).
    fn glDrawRangeElements(mode: GLenum, start: GLuint, end: GLuint, count: GLsizei, ty: GLenum, indices: *const c_void) {
        with_gl("glDrawRangeElements", (), |gl| {
            if !gl.st.es3 {
                gl.st.err(GL_INVALID_OPERATION);
                return Ok(());
            }
            if end < start {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            draw_elements(gl, mode, count, ty, indices, Extra::None)
        })
    }

    /// `GL_EXT_draw_instanced`: the client arrays the draw reads (per vertex, or with a
    /// divisor per instance), then the draw.
    fn glDrawArraysInstancedEXT(mode: GLenum, first: GLint, count: GLsizei, primcount: GLsizei) {
        with_gl("glDrawArraysInstancedEXT", (), |gl| {
            if first >= 0 && count > 0 && primcount > 0 && uses_client_arrays(gl.st) {
                send_client_arrays(gl, first as u64 + count as u64, primcount as u64)?;
            }
            gl.conn.glDrawArraysInstancedEXT(mode, first, count, primcount)
        })
    }

    /// `GL_EXT_draw_instanced`: indices as `glDrawElements` takes them, drawn `primcount` times.
    fn glDrawElementsInstancedEXT(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, primcount: GLsizei) {
        with_gl("glDrawElementsInstancedEXT", (), |gl| draw_elements(gl, mode, count, ty, indices, Extra::Instances(primcount)))
    }
}

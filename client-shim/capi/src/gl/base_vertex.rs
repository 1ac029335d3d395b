//! Element draws: `glDrawElements` and `GL_OES_draw_elements_base_vertex`'s
//! `glDrawElementsBaseVertexOES` send the client arrays their indices read (each index plus the
//! base, if any) and the draw; the daemon offsets the indices.

use super::*;

/// An element draw of `count` indices of `ty` at `indices` (an offset into the bound element
/// buffer, or a client-side array, which is sent along), with `base` added to each index for
/// `glDrawElementsBaseVertexOES`.
pub(super) fn draw_elements(
    gl: &mut Gl<'_>,
    mode: GLenum,
    count: GLsizei,
    ty: GLenum,
    indices: *const c_void,
    base: Option<GLint>,
) -> Result<(), ClientError> {
    let draw_buffer = |gl: &mut Gl<'_>| {
        let offset = indices as usize as u64;
        match base {
            None => gl.conn.glDrawElements(mode, count, ty, offset),
            Some(b) => gl.conn.glDrawElementsBaseVertexOES(mode, count, ty, offset, b),
        }
    };
    let Some(size) = type_size(ty).filter(|_| count > 0) else {
        // The daemon validates and records the error.
        return draw_buffer(gl);
    };
    let len = size * count as usize;
    // The vertices the draw reads: up to the largest index, plus the base.
    let reach = |n: u64| match base {
        Some(b) if n > 0 => (n as i64 + i64::from(b)).max(0) as u64,
        _ => n,
    };
    if gl.st.element_buffer != 0 {
        if uses_client_arrays(gl.st) {
            let offset = indices as usize;
            let n = gl
                .st
                .buffers
                .get(&gl.st.element_buffer)
                .and_then(|b| b.get(offset..offset.checked_add(len)?))
                .map_or(0, |d| vertex_count(d, ty));
            send_client_arrays(gl, reach(n))?;
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
        send_client_arrays(gl, reach(vertex_count(data, ty)))?;
    }
    match base {
        None => gl.conn.strataDrawElementsData(mode, count, ty, Blob::borrowed(data)),
        Some(b) => gl.conn.strataDrawElementsBaseVertexData(mode, count, ty, Blob::borrowed(data), b),
    }
}

crate::entry_points! {
    /// Indices from the bound element buffer, or a client-side index array sent along, each
    /// plus `basevertex`.
    fn glDrawElementsBaseVertexOES(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, basevertex: GLint) {
        with_gl("glDrawElementsBaseVertexOES", (), |gl| draw_elements(gl, mode, count, ty, indices, Some(basevertex)))
    }
}

//! `GL_OES_draw_elements_base_vertex`: `glDrawElementsBaseVertexOES` sends the client arrays its
//! indices read (each index plus the base) and the draw; the daemon offsets the indices.

use super::*;

crate::entry_points! {
    /// Indices from the bound element buffer, or a client-side index array sent along, each
    /// plus `basevertex`.
    fn glDrawElementsBaseVertexOES(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, basevertex: GLint) {
        with_gl("glDrawElementsBaseVertexOES", (), |gl| {
            let Some(size) = type_size(ty).filter(|_| count > 0) else {
                // The daemon validates and records the error.
                return gl.conn.glDrawElementsBaseVertexOES(mode, count, ty, indices as usize as u64, basevertex);
            };
            let len = size * count as usize;
            // The vertices the draw reads: up to the largest index plus the base.
            let reach = |n: u64| if n == 0 { 0 } else { (n as i64 + i64::from(basevertex)).max(0) as u64 };
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
                return gl.conn.glDrawElementsBaseVertexOES(mode, count, ty, indices as usize as u64, basevertex);
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
            gl.conn.strataDrawElementsBaseVertexData(mode, count, ty, Blob::borrowed(data), basevertex)
        })
    }
}

//! ES 3.0's vertex attribute calls the library takes part in: integer arrays (client arrays
//! among them, copied at draw time as they are), integer current values from arrays, and
//! divisors (which size the client arrays it sends).

use std::ffi::c_void;

use strata_protocol::Calls;

use super::{values, with_gl};
use crate::gl_state::ClientArray;
use crate::types::*;

crate::entry::entry_points! {
    /// ES 3.0: an integer array; with no array buffer bound a client-side array, copied at
    /// draw time as it is.
    fn glVertexAttribIPointer(index: GLuint, size: GLint, ty: GLenum, stride: GLsizei, pointer: *const c_void) {
        with_gl("glVertexAttribIPointer", (), |gl| {
            let client = (gl.st.array_buffer == 0 && !pointer.is_null())
                .then_some(ClientArray { ptr: pointer as usize, size, ty, stride });
            let refused = client.is_some() && gl.st.vertex_array != 0;
            if let Some(a) = gl.st.attribs.get_mut(index as usize).filter(|_| !refused) {
                a.client = client;
            }
            gl.conn.glVertexAttribIPointer(index, size, ty, stride, pointer as usize as u64)
        })
    }

    /// ES 3.0: four signed integers from the application's array.
    fn glVertexAttribI4iv(index: GLuint, v: *const GLint) {
        with_gl("glVertexAttribI4iv", (), |gl| {
            // SAFETY: `v` holds four integers.
            let v = unsafe { values(v, 4) };
            match v {
                [x, y, z, w] => gl.conn.glVertexAttribI4i(index, *x, *y, *z, *w),
                _ => Ok(()),
            }
        })
    }

    /// ES 3.0: four unsigned integers from the application's array.
    fn glVertexAttribI4uiv(index: GLuint, v: *const GLuint) {
        with_gl("glVertexAttribI4uiv", (), |gl| {
            // SAFETY: `v` holds four integers.
            let v = unsafe { values(v, 4) };
            match v {
                [x, y, z, w] => gl.conn.glVertexAttribI4ui(index, *x, *y, *z, *w),
                _ => Ok(()),
            }
        })
    }

    /// ES 3.0: the divisor is the library's too (it sizes the client arrays it sends).
    fn glVertexAttribDivisor(index: GLuint, divisor: GLuint) {
        with_gl("glVertexAttribDivisor", (), |gl| {
            if let Some(a) = gl.st.attribs.get_mut(index as usize) {
                a.divisor = divisor;
            }
            gl.conn.glVertexAttribDivisor(index, divisor)
        })
    }
}

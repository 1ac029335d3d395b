//! ES 3.0's uniform buffers and blocks: the indexed bindings (which also set the generic
//! `GL_UNIFORM_BUFFER` binding the library follows, for mapping), and the queries that take or
//! give names.

use strata_protocol::{Calls, Text};

use super::{c_name, copy_string, with_gl};
use crate::types::*;

crate::entry::entry_points! {
    /// Binds the whole buffer to an indexed binding and to the generic one.
    fn glBindBufferBase(target: GLenum, index: GLuint, buffer: GLuint) {
        with_gl("glBindBufferBase", (), |gl| {
            if target == GL_UNIFORM_BUFFER && (index as usize) < 24 {
                gl.st.uniform_buffer = buffer;
            }
            gl.conn.glBindBufferBase(target, index, buffer)
        })
    }

    /// Binds a range of the buffer to an indexed binding and the buffer to the generic one.
    fn glBindBufferRange(target: GLenum, index: GLuint, buffer: GLuint, offset: GLintptr, size: GLsizeiptr) {
        with_gl("glBindBufferRange", (), |gl| {
            let c = gl.conn.glBindBufferRange(target, index, buffer, offset as i64, size as i64);
            // The daemon decides whether the binding changes: the generic one follows its answer
            // at the next query; here it follows a call that can succeed.
            if target == GL_UNIFORM_BUFFER && (index as usize) < 24 && (buffer == 0 || size > 0) {
                gl.st.uniform_buffer = buffer;
            }
            c
        })
    }

    /// A block's index by name (`GL_INVALID_INDEX` for none, or a name that is no string).
    fn glGetUniformBlockIndex(program: GLuint, name: *const GLchar) -> GLuint {
        with_gl("glGetUniformBlockIndex", u32::MAX, |gl| {
            // SAFETY: the application passes a NUL-terminated name.
            let Some(name) = (unsafe { c_name(name) }) else { return Ok(u32::MAX) };
            gl.conn.glGetUniformBlockIndex(program, Text::borrowed(name))
        })
    }

    /// A block's name, NUL-terminated and truncated to `buf_size`.
    fn glGetActiveUniformBlockName(program: GLuint, index: GLuint, buf_size: GLsizei, length: *mut GLsizei, name: *mut GLchar) {
        with_gl("glGetActiveUniformBlockName", (), |gl| {
            if buf_size < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            if let Some(s) = gl.conn.glGetActiveUniformBlockName(program, index)? {
                // SAFETY: `name` has room for `buf_size` bytes; `length` for one GLsizei.
                unsafe { copy_string(&s, buf_size, length, name) };
            }
            Ok(())
        })
    }
}

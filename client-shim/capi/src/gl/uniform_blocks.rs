//! ES 3.0's buffer calls the library takes part in: the indexed uniform buffer bindings (which
//! also set the generic `GL_UNIFORM_BUFFER` binding the library follows, for mapping), the
//! block queries that take or give names, copies between buffers (whose contents the library
//! keeps a copy of) and 64-bit buffer parameters.

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
            if target == GL_TRANSFORM_FEEDBACK_BUFFER && (index as usize) < 4 {
                gl.st.xfb_buffer = buffer;
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
            if target == GL_TRANSFORM_FEEDBACK_BUFFER && (index as usize) < 4 && (buffer == 0 || size > 0) {
                gl.st.xfb_buffer = buffer;
            }
            c
        })
    }

    /// The copy, on the daemon and in the library's copies of the contents, where the daemon's
    /// checks pass (both bound and unmapped, no negative value, both ranges within their
    /// buffers, no overlap within one).
    fn glCopyBufferSubData(read_target: GLenum, write_target: GLenum, read_offset: GLintptr, write_offset: GLintptr, size: GLsizeiptr) {
        with_gl("glCopyBufferSubData", (), |gl| {
            gl.conn.glCopyBufferSubData(read_target, write_target, read_offset as i64, write_offset as i64, size as i64)?;
            let (Some(src), Some(dst)) = (gl.st.bound(read_target), gl.st.bound(write_target)) else { return Ok(()) };
            let unmapped = !gl.maps.contains_key(&src) && !gl.maps.contains_key(&dst);
            if src == 0 || dst == 0 || !unmapped || read_offset < 0 || write_offset < 0 || size < 0 {
                return Ok(());
            }
            let (from, to, n) = (read_offset as usize, write_offset as usize, size as usize);
            if src == dst && from < to + n && to < from + n {
                return Ok(());
            }
            let bytes = gl.shadows.get(&src).and_then(|s| s.get(from..from.checked_add(n)?)).map(<[u8]>::to_vec);
            if let (Some(bytes), Some(d)) = (bytes, gl.shadows.get_mut(&dst)) {
                if let Some(range) = d.get_mut(to..to.saturating_add(n)) {
                    range.copy_from_slice(&bytes);
                }
            }
            Ok(())
        })
    }

    /// One 64-bit parameter.
    fn glGetBufferParameteri64v(target: GLenum, pname: GLenum, params: *mut GLint64) {
        with_gl("glGetBufferParameteri64v", (), |gl| {
            let v = gl.conn.glGetBufferParameteri64v(target, pname)?;
            // SAFETY: `params` points at one GLint64.
            unsafe { super::put(params, v) };
            Ok(())
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

    /// Each name's active uniform index (`GL_INVALID_INDEX` for none), sent as one text of lines.
    fn glGetUniformIndices(program: GLuint, count: GLsizei, names: *const *const GLchar, indices: *mut GLuint) {
        with_gl("glGetUniformIndices", (), |gl| {
            // SAFETY: the application passes `count` NUL-terminated names.
            let text = unsafe { super::name_lines(names, count) };
            let v = gl.conn.glGetUniformIndices(program, count, Text::borrowed(&text))?;
            // SAFETY: `indices` has room for `count` values.
            unsafe { super::write_out(indices, &v) };
            Ok(())
        })
    }

    /// One property of each active uniform `indices` names.
    fn glGetActiveUniformsiv(program: GLuint, count: GLsizei, indices: *const GLuint, pname: GLenum, params: *mut GLint) {
        with_gl("glGetActiveUniformsiv", (), |gl| {
            if count < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: the application passes `count` indices.
            let list = unsafe { super::values(indices, i64::from(count)) };
            let v = gl.conn.glGetActiveUniformsiv(program, strata_protocol::Slice::new(list), pname)?;
            // SAFETY: `params` has room for `count` values.
            unsafe { super::write_out(params, &v) };
            Ok(())
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

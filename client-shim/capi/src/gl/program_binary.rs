//! `GL_OES_get_program_binary`: the daemon makes and checks program binaries; the library
//! copies them between the application's memory and the wire.

use std::ffi::c_void;

use strata_protocol::{Blob, Calls};

use super::{bytes, put, with_gl, write_out};
use crate::types::*;

crate::entry::entry_points! {
    /// The binary of a linked program, if `buf_size` bytes hold it. As on Mesa, `length` is
    /// set to 0 before any error but a bad name or a negative size.
    fn glGetProgramBinaryOES(program: GLuint, buf_size: GLsizei, length: *mut GLsizei, binary_format: *mut GLenum, binary: *mut c_void) {
        with_gl("glGetProgramBinaryOES", (), |gl| {
            let Some(answer) = gl.conn.glGetProgramBinaryOES(program, buf_size)? else { return Ok(()) };
            let (format, data) = answer.map_or((None, Vec::new()), |(f, d)| (Some(f), d.0));
            // SAFETY: the daemon answered only a binary that `buf_size` bytes hold, and the
            // out-pointers are the application's, as the extension specifies.
            unsafe {
                write_out(binary.cast::<u8>(), &data);
                put(length, data.len() as GLsizei);
                if let Some(f) = format {
                    put(binary_format, f);
                }
            }
            Ok(())
        })
    }

    /// Links `program` from `length` bytes of a binary (the daemon refuses a negative length).
    fn glProgramBinaryOES(program: GLuint, binary_format: GLenum, binary: *const c_void, length: GLint) {
        with_gl("glProgramBinaryOES", (), |gl| {
            // SAFETY: `binary` holds `length` bytes.
            let b = unsafe { bytes(binary, usize::try_from(length).unwrap_or(0)) };
            gl.conn.glProgramBinaryOES(program, binary_format, length, Blob::borrowed(b))
        })
    }
}

//! ES 3.0 calls the library marshals by hand: `glClearBuffer*`, whose array holds four values
//! for a colour and one for the depth or the stencil, `glGetFragDataLocation`, which takes a
//! name, `glTransformFeedbackVaryings`, which takes a list of them, and
//! `glGetInternalformativ`, which writes at most the application's count.

use strata_protocol::{Calls, Slice, Text};

use super::{c_name, values, with_gl};
use crate::types::*;

/// `GL_COLOR`: the one buffer whose clear takes four values.
const GL_COLOR: GLenum = 0x1800;
/// `GL_DEPTH` and `GL_STENCIL`, whose clears take one.
const GL_DEPTH: GLenum = 0x1801;
const GL_STENCIL: GLenum = 0x1802;

/// How many values a `glClearBuffer*` of `buffer` reads from its array (none for a buffer it
/// refuses, which the daemon answers with `GL_INVALID_ENUM`).
fn clear_values(buffer: GLenum) -> i64 {
    match buffer {
        GL_COLOR => 4,
        GL_DEPTH | GL_STENCIL => 1,
        _ => 0,
    }
}

crate::entry::entry_points! {
    /// Clears a colour draw buffer or the depth to the application's floats.
    fn glClearBufferfv(buffer: GLenum, drawbuffer: GLint, value: *const GLfloat) {
        with_gl("glClearBufferfv", (), |gl| {
            // SAFETY: `value` holds as many values as `buffer` clears.
            let v = unsafe { values(value, clear_values(buffer)) };
            gl.conn.glClearBufferfv(buffer, drawbuffer, Slice::new(v))
        })
    }

    /// Clears an integer colour draw buffer or the stencil to the application's integers.
    fn glClearBufferiv(buffer: GLenum, drawbuffer: GLint, value: *const GLint) {
        with_gl("glClearBufferiv", (), |gl| {
            // SAFETY: `value` holds as many values as `buffer` clears.
            let v = unsafe { values(value, clear_values(buffer)) };
            gl.conn.glClearBufferiv(buffer, drawbuffer, Slice::new(v))
        })
    }

    /// Clears an unsigned integer colour draw buffer to the application's values.
    fn glClearBufferuiv(buffer: GLenum, drawbuffer: GLint, value: *const GLuint) {
        with_gl("glClearBufferuiv", (), |gl| {
            // SAFETY: `value` holds as many values as `buffer` clears.
            let v = unsafe { values(value, clear_values(buffer)) };
            gl.conn.glClearBufferuiv(buffer, drawbuffer, Slice::new(v))
        })
    }

    /// Clears the depth and the stencil together.
    fn glClearBufferfi(buffer: GLenum, drawbuffer: GLint, depth: GLfloat, stencil: GLint) {
        with_gl("glClearBufferfi", (), |gl| gl.conn.glClearBufferfi(buffer, drawbuffer, depth, stencil))
    }

    /// The varyings the next link captures, sent as one text of lines (`count` is checked by
    /// the daemon; a name that is no string is sent empty, which no varying has).
    fn glTransformFeedbackVaryings(program: GLuint, count: GLsizei, varyings: *const *const GLchar, buffer_mode: GLenum) {
        with_gl("glTransformFeedbackVaryings", (), |gl| {
            // SAFETY: the application passes `count` NUL-terminated names.
            let text = unsafe { super::name_lines(varyings, count) };
            gl.conn.glTransformFeedbackVaryings(program, count, Text::borrowed(&text), buffer_mode)
        })
    }

    /// A fragment output's location by name (-1 for none, or a name that is no string).
    fn glGetFragDataLocation(program: GLuint, name: *const GLchar) -> GLint {
        with_gl("glGetFragDataLocation", -1, |gl| {
            // SAFETY: the application passes a NUL-terminated name.
            let Some(name) = (unsafe { c_name(name) }) else { return Ok(-1) };
            gl.conn.glGetFragDataLocation(program, Text::borrowed(name))
        })
    }

    /// A format's sample counts (`GL_SAMPLES`) or how many there are (`GL_NUM_SAMPLE_COUNTS`):
    /// at most `buf_size` values written (the daemon checks `buf_size` with the rest).
    fn glGetInternalformativ(target: GLenum, internalformat: GLenum, pname: GLenum, buf_size: GLsizei, params: *mut GLint) {
        with_gl("glGetInternalformativ", (), |gl| {
            let v = gl.conn.glGetInternalformativ(target, internalformat, pname, buf_size)?;
            let n = v.len().min(usize::try_from(buf_size).unwrap_or(0));
            // SAFETY: `params` has room for `buf_size` values.
            unsafe { super::write_out(params, &v[..n]) };
            Ok(())
        })
    }
}

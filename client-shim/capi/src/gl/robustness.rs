//! `GL_EXT_robustness` and `GL_KHR_robustness`: the reset status (a lost daemon connection is a
//! reset whose cause the library cannot know), and reads bounded by the application's buffer
//! size. Each bounded read is validated by the daemon as the unbounded one is; a read the buffer
//! cannot hold is then `GL_INVALID_OPERATION` and writes nothing, as on Mesa.

use std::ffi::c_void;

use strata_protocol::Calls;

use super::pixels::read_pixels;
use super::{with_gl, write_out, Gl};
use crate::state::{self, process};
use crate::types::*;

/// `GL_UNKNOWN_CONTEXT_RESET_EXT`.
const UNKNOWN_CONTEXT_RESET: GLenum = 0x8255;

/// The reset status of the calling thread's context.
fn reset_status() -> GLenum {
    let Some(cur) = state::current() else { return GL_NO_ERROR };
    let p = process();
    if p.lost || p.conn.is_none() || p.live_context(cur.context).is_none() {
        UNKNOWN_CONTEXT_RESET
    } else {
        GL_NO_ERROR
    }
}

/// `glReadPixels` into `buf_size` bytes at `pixels`.
#[allow(clippy::too_many_arguments)]
fn read_bounded(
    name: &'static str,
    x: GLint,
    y: GLint,
    width: GLsizei,
    height: GLsizei,
    format: GLenum,
    ty: GLenum,
    buf_size: GLsizei,
    pixels: *mut c_void,
) {
    with_gl(name, (), |gl| {
        let limit = Some(usize::try_from(buf_size).unwrap_or(0));
        // SAFETY: the application's buffer holds `buf_size` bytes.
        unsafe { read_pixels(gl, [x, y, width, height], format, ty, pixels, limit) }
    })
}

/// Writes `values` (of 4 bytes each) to `params` if `buf_size` bytes hold them.
fn write_bounded<T: Copy>(gl: &mut Gl<'_>, values: &[T], buf_size: GLsizei, params: *mut T) {
    if values.len() * 4 > usize::try_from(buf_size).unwrap_or(0) {
        gl.st.err(GL_INVALID_OPERATION);
        return;
    }
    // SAFETY: the application's buffer holds `buf_size` bytes, which hold the values.
    unsafe { write_out(params, values) };
}

/// `glGetUniformfv` bounded by `bufSize`.
fn uniform_f(name: &'static str, program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLfloat) {
    with_gl(name, (), |gl| {
        let v = gl.conn.glGetUniformfv(program, location)?;
        write_bounded(gl, &v, buf_size, params);
        Ok(())
    })
}

/// `glGetUniformiv` bounded by `bufSize`, as `T` (ES 2.0 has no unsigned uniforms, so the
/// unsigned query answers what the signed one answers).
fn uniform_i<T: Copy>(name: &'static str, program: GLuint, location: GLint, buf_size: GLsizei, params: *mut T)
where
    GLint: Into<Bits<T>>,
{
    with_gl(name, (), |gl| {
        let v: Vec<T> = gl.conn.glGetUniformiv(program, location)?.into_iter().map(|x| x.into().0).collect();
        write_bounded(gl, &v, buf_size, params);
        Ok(())
    })
}

/// A 32-bit integer's bits as `T`.
struct Bits<T>(T);

impl From<GLint> for Bits<GLint> {
    fn from(v: GLint) -> Self {
        Bits(v)
    }
}

impl From<GLint> for Bits<GLuint> {
    fn from(v: GLint) -> Self {
        Bits(v as GLuint)
    }
}

crate::entry::entry_points! {
    /// `GL_EXT_robustness`: the reset status (an unknown reset once the daemon is gone).
    fn glGetGraphicsResetStatusEXT() -> GLenum {
        reset_status()
    }

    /// `GL_KHR_robustness`: as `glGetGraphicsResetStatusEXT`.
    fn glGetGraphicsResetStatusKHR() -> GLenum {
        reset_status()
    }

    /// `glReadPixels` bounded by `bufSize`.
    fn glReadnPixelsEXT(x: GLint, y: GLint, width: GLsizei, height: GLsizei, format: GLenum, ty: GLenum, buf_size: GLsizei, data: *mut c_void) {
        read_bounded("glReadnPixelsEXT", x, y, width, height, format, ty, buf_size, data)
    }

    /// `glReadPixels` bounded by `bufSize`.
    fn glReadnPixelsKHR(x: GLint, y: GLint, width: GLsizei, height: GLsizei, format: GLenum, ty: GLenum, buf_size: GLsizei, data: *mut c_void) {
        read_bounded("glReadnPixelsKHR", x, y, width, height, format, ty, buf_size, data)
    }

    /// `glGetUniformfv` bounded by `bufSize`.
    fn glGetnUniformfvEXT(program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLfloat) {
        uniform_f("glGetnUniformfvEXT", program, location, buf_size, params)
    }

    /// `glGetUniformfv` bounded by `bufSize`.
    fn glGetnUniformfvKHR(program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLfloat) {
        uniform_f("glGetnUniformfvKHR", program, location, buf_size, params)
    }

    /// `glGetUniformiv` bounded by `bufSize`.
    fn glGetnUniformivEXT(program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLint) {
        uniform_i("glGetnUniformivEXT", program, location, buf_size, params)
    }

    /// `glGetUniformiv` bounded by `bufSize`.
    fn glGetnUniformivKHR(program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLint) {
        uniform_i("glGetnUniformivKHR", program, location, buf_size, params)
    }

    /// `glGetUniformiv` bounded by `bufSize`, as unsigned values.
    fn glGetnUniformuivKHR(program: GLuint, location: GLint, buf_size: GLsizei, params: *mut GLuint) {
        uniform_i("glGetnUniformuivKHR", program, location, buf_size, params)
    }
}

//! The generated families of GLES 2.0 entry points that marshal pointers the same way:
//! uniform and vertex-attribute arrays, client-allocated names and their deletion, and
//! queries that write integers, arrays, strings or active-variable descriptions into the
//! application's memory. Each family is one macro; each module lists its members.

use strata_protocol::{Calls, Slice};

use super::{copy_string, put, values, with_gl, write_out, Call, ShowArg};
use crate::types::*;

/// `glUniform*v`: `count` elements of `n` values each.
macro_rules! uniform_v {
    ($( $name:ident : $t:ty , $n:literal ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies `count` × ", stringify!($n), " values.")]
                fn $name(location: GLint, count: GLsizei, value: *const $t) {
                    with_gl(stringify!($name), (), |gl| {
                        if count < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `count` elements.
                        let v = unsafe { values(value, i64::from(count) * $n) };
                        gl.conn.$name(location, Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// `glUniformMatrix*fv`: `count` matrices of `n` floats.
macro_rules! uniform_matrix {
    ($( $name:ident , $n:literal ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies `count` matrices of ", stringify!($n), " floats.")]
                fn $name(location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
                    with_gl(stringify!($name), (), |gl| {
                        if count < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `count` matrices.
                        let v = unsafe { values(value, i64::from(count) * $n) };
                        gl.conn.$name(location, transpose != 0, Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// `glVertexAttrib*fv`: `n` floats.
macro_rules! vertex_attrib_v {
    ($( $name:ident , $n:literal ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies ", stringify!($n), " floats.")]
                fn $name(index: GLuint, value: *const GLfloat) {
                    with_gl(stringify!($name), (), |gl| {
                        if value.is_null() {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `n` floats.
                        let v = unsafe { values(value, $n) };
                        gl.conn.$name(index, Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// `glGen*`: client-allocated names, written to the application's array and sent.
macro_rules! gen_names {
    ($( $name:ident ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: names are allocated here and sent to the daemon.")]
                fn $name(n: GLsizei, names: *mut GLuint) {
                    with_gl(stringify!($name), (), |gl| {
                        if n < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        if names.is_null() {
                            return Ok(());
                        }
                        let new = gl.names(n as usize);
                        // SAFETY: the application's array has room for `n` names.
                        unsafe { write_out(names, &new) };
                        gl.conn.$name(Slice::new(&new))
                    })
                }
            )*
        }
    };
}

/// `glDelete*` for textures, framebuffers and renderbuffers.
macro_rules! delete_names {
    ($( $name:ident ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies `n` names.")]
                fn $name(n: GLsizei, names: *const GLuint) {
                    with_gl(stringify!($name), (), |gl| {
                        if n < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `n` names.
                        let v = unsafe { values(names, i64::from(n)) };
                        gl.conn.$name(Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// Parameter queries that return one integer.
macro_rules! get_one_int {
    ($( $name:ident ( $( $arg:ident : $ty:ty ),* ) ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: writes one integer.")]
                fn $name( $( $arg : $ty, )* params: *mut GLint) {
                    let args = || -> String { Vec::<String>::from([$( ShowArg::show(&$arg) ),*]).join(", ") };
                    with_gl(Call { name: stringify!($name), args: &args }, (), |gl| {
                        let v = gl.conn.$name( $( $arg ),* )?;
                        // SAFETY: `params` points at one GLint.
                        unsafe { put(params, v) };
                        Ok(())
                    })
                }
            )*
        }
    };
}

/// Queries that return an array, written to the caller's.
macro_rules! get_array {
    ($( $name:ident ( $( $arg:ident : $ty:ty ),* ) -> $t:ty ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: writes the values the daemon returns.")]
                fn $name( $( $arg : $ty, )* params: *mut $t) {
                    let args = || -> String { Vec::<String>::from([$( ShowArg::show(&$arg) ),*]).join(", ") };
                    with_gl(Call { name: stringify!($name), args: &args }, (), |gl| {
                        let v = gl.conn.$name( $( $arg ),* )?;
                        // SAFETY: the caller's array has room for what the query returns.
                        unsafe { write_out(params, &v) };
                        Ok(())
                    })
                }
            )*
        }
    };
}

/// Info logs and sources, copied into the caller's buffer.
macro_rules! get_string {
    ($( $name:ident ( $obj:ident ) ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies the text, NUL-terminated and truncated.")]
                fn $name($obj: GLuint, buf_size: GLsizei, length: *mut GLsizei, out: *mut GLchar) {
                    with_gl(stringify!($name), (), |gl| {
                        if buf_size < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        let s = gl.conn.$name($obj)?;
                        // SAFETY: `out` has room for `buf_size` bytes.
                        unsafe { copy_string(&s, buf_size, length, out) };
                        Ok(())
                    })
                }
            )*
        }
    };
}

/// `glGetActiveAttrib` / `glGetActiveUniform`.
macro_rules! get_active {
    ($( $name:ident ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: size, type and name of one active variable.")]
                fn $name(
                    program: GLuint,
                    index: GLuint,
                    buf_size: GLsizei,
                    length: *mut GLsizei,
                    size: *mut GLint,
                    ty: *mut GLenum,
                    name: *mut GLchar,
                ) {
                    with_gl(stringify!($name), (), |gl| {
                        if buf_size < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        if let Some(v) = gl.conn.$name(program, index)? {
                            // SAFETY: out-pointers as GL specifies; `name` has `buf_size` bytes.
                            unsafe {
                                put(size, v.size);
                                put(ty, v.ty);
                                copy_string(&v.name, buf_size, length, name);
                            }
                        }
                        Ok(())
                    })
                }
            )*
        }
    };
}

/// Uniform arrays.
pub mod uniforms {
    use super::*;
    uniform_v! {
    glUniform1fv: GLfloat, 1;
    glUniform2fv: GLfloat, 2;
    glUniform3fv: GLfloat, 3;
    glUniform4fv: GLfloat, 4;
    glUniform1iv: GLint, 1;
    glUniform2iv: GLint, 2;
    glUniform3iv: GLint, 3;
    glUniform4iv: GLint, 4;
    glUniform1uiv: GLuint, 1;
    glUniform2uiv: GLuint, 2;
    glUniform3uiv: GLuint, 3;
    glUniform4uiv: GLuint, 4;
    }
}

/// Matrix uniforms.
pub mod matrix {
    use super::*;
    uniform_matrix! {
        glUniformMatrix2fv, 4;
        glUniformMatrix3fv, 9;
        glUniformMatrix4fv, 16;
        glUniformMatrix2x3fv, 6;
        glUniformMatrix3x2fv, 6;
        glUniformMatrix2x4fv, 8;
        glUniformMatrix4x2fv, 8;
        glUniformMatrix3x4fv, 12;
        glUniformMatrix4x3fv, 12;
    }
}

/// Current vertex attribute values from arrays.
pub mod attrib {
    use super::*;
    vertex_attrib_v! {
        glVertexAttrib1fv, 1;
        glVertexAttrib2fv, 2;
        glVertexAttrib3fv, 3;
        glVertexAttrib4fv, 4;
    }
}

/// Name allocation and deletion.
pub mod names {
    use super::*;
    gen_names! {
        glGenFramebuffers;
        glGenRenderbuffers;
        glGenTextures;
        glGenQueriesEXT;
        glGenProgramPipelinesEXT;
        glGenTransformFeedbacks;
        glGenSamplers;
    }
}

/// Name deletion.
pub mod delete {
    use super::*;
    delete_names! {
        glDeleteFramebuffers;
        glDeleteRenderbuffers;
        glDeleteTextures;
        glDeleteQueriesEXT;
        glDeleteProgramPipelinesEXT;
        glDeleteTransformFeedbacks;
        glDeleteSamplers;
    }
}

/// Integer parameter queries.
pub mod get_int {
    use super::*;
    get_one_int! {
        glGetFramebufferAttachmentParameteriv(target: GLenum, attachment: GLenum, pname: GLenum);
        glGetProgramiv(program: GLuint, pname: GLenum);
        glGetRenderbufferParameteriv(target: GLenum, pname: GLenum);
        glGetShaderiv(shader: GLuint, pname: GLenum);
    }
}

/// Array queries.
pub mod get_arrays {
    use super::*;
    get_array! {
        glGetFloatv(pname: GLenum) -> GLfloat;
        glGetIntegerv(pname: GLenum) -> GLint;
        glGetTexParameterfv(target: GLenum, pname: GLenum) -> GLfloat;
        glGetTexParameteriv(target: GLenum, pname: GLenum) -> GLint;
        glGetSamplerParameterfv(sampler: GLuint, pname: GLenum) -> GLfloat;
        glGetSamplerParameteriv(sampler: GLuint, pname: GLenum) -> GLint;
        glGetUniformfv(program: GLuint, location: GLint) -> GLfloat;
        glGetUniformiv(program: GLuint, location: GLint) -> GLint;
        glGetUniformuiv(program: GLuint, location: GLint) -> GLuint;
        glGetActiveUniformBlockiv(program: GLuint, index: GLuint, pname: GLenum) -> GLint;
        glGetIntegeri_v(target: GLenum, index: GLuint) -> GLint;
        glGetVertexAttribIiv(index: GLuint, pname: GLenum) -> GLint;
        glGetVertexAttribIuiv(index: GLuint, pname: GLenum) -> GLuint;
        glGetInteger64i_v(target: GLenum, index: GLuint) -> GLint64;
        glGetVertexAttribfv(index: GLuint, pname: GLenum) -> GLfloat;
        glGetVertexAttribiv(index: GLuint, pname: GLenum) -> GLint;
        glGetQueryivEXT(target: GLenum, pname: GLenum) -> GLint;
        glGetQueryObjectuivEXT(id: GLuint, pname: GLenum) -> GLuint;
        glGetQueryObjectivEXT(id: GLuint, pname: GLenum) -> GLint;
        glGetQueryObjecti64vEXT(id: GLuint, pname: GLenum) -> GLint64;
        glGetQueryObjectui64vEXT(id: GLuint, pname: GLenum) -> GLuint64;
        glGetInteger64vEXT(pname: GLenum) -> GLint64;
        glGetProgramPipelineivEXT(pipeline: GLuint, pname: GLenum) -> GLint;
    }
}

/// Logs and sources.
pub mod get_strings {
    use super::*;
    get_string! {
        glGetProgramInfoLog(program);
        glGetShaderInfoLog(shader);
        glGetShaderSource(shader);
        glGetProgramPipelineInfoLogEXT(pipeline);
    }
}

/// Active variables.
pub mod active {
    use super::*;
    get_active! {
        glGetActiveAttrib;
        glGetActiveUniform;
        glGetTransformFeedbackVarying;
    }
}

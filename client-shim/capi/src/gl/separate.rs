//! `GL_EXT_separate_shader_objects`: one-stage programs from source, and uniforms written to
//! a named program. The scalar forms travel as one-element arrays, which GL defines them as.

use std::ffi::CStr;

use strata_protocol::{Calls, Slice, Text};

use super::{values, with_gl};
use crate::types::*;

/// `glProgramUniform{1,2,3,4}{f,i}EXT`: sent as the `v` form with one element.
macro_rules! program_uniform {
    ($( $name:ident => $v:ident, $t:ty, ( $( $c:ident ),+ ); )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: one element of `", stringify!($v), "`.")]
                fn $name(program: GLuint, location: GLint, $( $c: $t ),+) {
                    with_gl(stringify!($name), (), |gl| gl.conn.$v(program, location, Slice::new(&[$( $c ),+])))
                }
            )*
        }
    };
}

/// `glProgramUniform{1,2,3,4}{f,i}vEXT`: `count` × `n` values.
macro_rules! program_uniform_v {
    ($( $name:ident : $t:ty , $n:literal ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies `count` × ", stringify!($n), " values.")]
                fn $name(program: GLuint, location: GLint, count: GLsizei, value: *const $t) {
                    with_gl(stringify!($name), (), |gl| {
                        if count < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `count` elements.
                        let v = unsafe { values(value, i64::from(count) * $n) };
                        gl.conn.$name(program, location, Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// `glProgramUniformMatrix{2,3,4}fvEXT`: `count` matrices of `n` floats.
macro_rules! program_uniform_matrix {
    ($( $name:ident , $n:literal ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: copies `count` matrices of ", stringify!($n), " floats.")]
                fn $name(program: GLuint, location: GLint, count: GLsizei, transpose: GLboolean, value: *const GLfloat) {
                    with_gl(stringify!($name), (), |gl| {
                        if count < 0 {
                            gl.st.err(GL_INVALID_VALUE);
                            return Ok(());
                        }
                        // SAFETY: the application passes `count` matrices.
                        let v = unsafe { values(value, i64::from(count) * $n) };
                        gl.conn.$name(program, location, transpose != 0, Slice::new(v))
                    })
                }
            )*
        }
    };
}

/// The scalar forms.
pub mod scalars {
    use super::*;
    program_uniform! {
        glProgramUniform1fEXT => glProgramUniform1fvEXT, GLfloat, (x);
        glProgramUniform2fEXT => glProgramUniform2fvEXT, GLfloat, (x, y);
        glProgramUniform3fEXT => glProgramUniform3fvEXT, GLfloat, (x, y, z);
        glProgramUniform4fEXT => glProgramUniform4fvEXT, GLfloat, (x, y, z, w);
        glProgramUniform1iEXT => glProgramUniform1ivEXT, GLint, (x);
        glProgramUniform2iEXT => glProgramUniform2ivEXT, GLint, (x, y);
        glProgramUniform3iEXT => glProgramUniform3ivEXT, GLint, (x, y, z);
        glProgramUniform4iEXT => glProgramUniform4ivEXT, GLint, (x, y, z, w);
    }
}

/// The array forms.
pub mod arrays {
    use super::*;
    program_uniform_v! {
        glProgramUniform1fvEXT: GLfloat, 1;
        glProgramUniform2fvEXT: GLfloat, 2;
        glProgramUniform3fvEXT: GLfloat, 3;
        glProgramUniform4fvEXT: GLfloat, 4;
        glProgramUniform1ivEXT: GLint, 1;
        glProgramUniform2ivEXT: GLint, 2;
        glProgramUniform3ivEXT: GLint, 3;
        glProgramUniform4ivEXT: GLint, 4;
    }
}

/// The matrix forms.
pub mod matrices {
    use super::*;
    program_uniform_matrix! {
        glProgramUniformMatrix2fvEXT, 4;
        glProgramUniformMatrix3fvEXT, 9;
        glProgramUniformMatrix4fvEXT, 16;
    }
}

crate::entry::entry_points! {
    /// A separable program of one stage, compiled from the `count` NUL-terminated `strings`
    /// and linked; its name is allocated here (0 for an invalid type or count).
    fn glCreateShaderProgramvEXT(shader_type: GLenum, count: GLsizei, strings: *const *const GLchar) -> GLuint {
        with_gl("glCreateShaderProgramvEXT", 0, |gl| {
            if !matches!(shader_type, 0x8B30 | 0x8B31) {
                gl.st.err(GL_INVALID_ENUM);
                return Ok(0);
            }
            if count < 0 || (count > 0 && strings.is_null()) {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(0);
            }
            let mut source = Vec::new();
            for i in 0..count as usize {
                // SAFETY: `strings` has `count` entries, each NUL-terminated or null.
                let s = unsafe { *strings.add(i) };
                if !s.is_null() {
                    // SAFETY: as above.
                    source.extend_from_slice(unsafe { CStr::from_ptr(s) }.to_bytes());
                }
            }
            let source = String::from_utf8_lossy(&source);
            let name = gl.names(1)[0];
            gl.conn.glCreateShaderProgramvEXT(shader_type, name, Text::borrowed(&source))?;
            Ok(name)
        })
    }
}

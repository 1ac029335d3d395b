//! The Mesa reference's arms for OpenGL ES 3.0's calls (in an ES 3.0 context; in an ES 2.0 one
//! Mesa records `GL_INVALID_OPERATION` for them, as Strata does).

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glGetUniformuiv(&mut self, program: &GLuint, location: &GLint) -> Result<Vec<GLuint>, ClientError> {
        let p = self.shader(*program);
        let mut v = [INT_SENTINEL as u32; 16];
        call!(self, "glGetUniformuiv", fn(u32, i32, *mut u32) -> (), p, *location, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL as u32).collect())
    }

    pub(super) fn glUniform1uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform1uiv", u32, location, values, 1)
    }

    pub(super) fn glUniform2uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform2uiv", u32, location, values, 2)
    }

    pub(super) fn glUniform3uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform3uiv", u32, location, values, 3)
    }

    pub(super) fn glUniform4uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform4uiv", u32, location, values, 4)
    }
}

/// Generates the non-square `glUniformMatrix*fv` arms: `count` matrices of `n` floats.
macro_rules! matrix_arms {
    ($( $gl:ident = $name:literal, $n:literal; )*) => {
        #[allow(non_snake_case)]
        impl Arms<'_> {
            $( pub(super) fn $gl(&mut self, location: &GLint, transpose: &bool, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
                uniform_matrices!(self, $name, location, transpose, values, $n)
            } )*
        }
    };
}

matrix_arms! {
    glUniformMatrix2x3fv = "glUniformMatrix2x3fv", 6;
    glUniformMatrix3x2fv = "glUniformMatrix3x2fv", 6;
    glUniformMatrix2x4fv = "glUniformMatrix2x4fv", 8;
    glUniformMatrix4x2fv = "glUniformMatrix4x2fv", 8;
    glUniformMatrix3x4fv = "glUniformMatrix3x4fv", 12;
    glUniformMatrix4x3fv = "glUniformMatrix4x3fv", 12;
}

//! The integer forms of `GL_EXT_texture_border_clamp` and `GL_OES_texture_border_clamp`.
//! They set and read the border of integer textures, which ES 2.0 has none of: each is
//! `GL_INVALID_OPERATION`, as on Mesa held to ES 2.0. The border colour itself travels through
//! `glTexParameterfv`/`iv`.

use super::*;

/// Records `GL_INVALID_OPERATION` for the call `name`.
fn refuse(name: &'static str) {
    with_gl(name, (), |gl| {
        gl.st.err(GL_INVALID_OPERATION);
        Ok(())
    })
}

crate::entry_points! {
    /// Refused: integer textures are ES 3.0's.
    fn glTexParameterIivEXT(_target: GLenum, _pname: GLenum, _params: *const GLint) {
        refuse("glTexParameterIivEXT")
    }

    /// Refused: integer textures are ES 3.0's.
    fn glTexParameterIuivEXT(_target: GLenum, _pname: GLenum, _params: *const GLuint) {
        refuse("glTexParameterIuivEXT")
    }

    /// Refused, writing nothing: integer textures are ES 3.0's.
    fn glGetTexParameterIivEXT(_target: GLenum, _pname: GLenum, _params: *mut GLint) {
        refuse("glGetTexParameterIivEXT")
    }

    /// Refused, writing nothing: integer textures are ES 3.0's.
    fn glGetTexParameterIuivEXT(_target: GLenum, _pname: GLenum, _params: *mut GLuint) {
        refuse("glGetTexParameterIuivEXT")
    }

    /// Refused: integer textures are ES 3.0's.
    fn glTexParameterIivOES(_target: GLenum, _pname: GLenum, _params: *const GLint) {
        refuse("glTexParameterIivOES")
    }

    /// Refused: integer textures are ES 3.0's.
    fn glTexParameterIuivOES(_target: GLenum, _pname: GLenum, _params: *const GLuint) {
        refuse("glTexParameterIuivOES")
    }

    /// Refused, writing nothing: integer textures are ES 3.0's.
    fn glGetTexParameterIivOES(_target: GLenum, _pname: GLenum, _params: *mut GLint) {
        refuse("glGetTexParameterIivOES")
    }

    /// Refused, writing nothing: integer textures are ES 3.0's.
    fn glGetTexParameterIuivOES(_target: GLenum, _pname: GLenum, _params: *mut GLuint) {
        refuse("glGetTexParameterIuivOES")
    }
}

//! The integer forms of `GL_EXT_texture_border_clamp` and `GL_OES_texture_border_clamp`.
//! They set and read the border of integer textures, which ES 2.0 has none of: each is
//! `GL_INVALID_OPERATION`, as on Mesa held to ES 2.0. The border colour itself travels through
//! `glTexParameterfv`/`iv`.

use super::with_gl;
use crate::types::*;

/// Records `GL_INVALID_OPERATION` for the call `name`.
fn refuse(name: &'static str) {
    with_gl(name, (), |gl| {
        gl.st.err(GL_INVALID_OPERATION);
        Ok(())
    })
}

/// The integer forms, each refused.
macro_rules! refused {
    ($( $name:ident($ptr:ty); )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`: refused (integer textures are ES 3.0's), writing nothing.")]
                fn $name(_target: GLenum, _pname: GLenum, _params: $ptr) {
                    refuse(stringify!($name))
                }
            )*
        }
    };
}

refused! {
    glTexParameterIivEXT(*const GLint);
    glTexParameterIuivEXT(*const GLuint);
    glGetTexParameterIivEXT(*mut GLint);
    glGetTexParameterIuivEXT(*mut GLuint);
    glTexParameterIivOES(*const GLint);
    glTexParameterIuivOES(*const GLuint);
    glGetTexParameterIivOES(*mut GLint);
    glGetTexParameterIuivOES(*mut GLuint);
}

//! `GL_EXT_blend_func_extended`'s entry points for user-defined fragment outputs. GLSL ES 1.00
//! has none (its second colour is the built-in `gl_SecondaryFragColorEXT`), so on an ES 2.0
//! context each is `GL_INVALID_OPERATION` and the queries answer 0, as on Mesa. The blend
//! factors and the built-ins are the daemon's.

use super::{with_gl, Call};
use crate::types::*;

crate::entry::entry_points! {
    /// Binds a fragment output's colour number and index: none on ES 2.0.
    fn glBindFragDataLocationIndexedEXT(program: GLuint, color: GLuint, index: GLuint, _name: *const GLchar) {
        let args = || format!("{program}, {color}, {index}");
        with_gl(Call { name: "glBindFragDataLocationIndexedEXT", args: &args }, (), |gl| {
            gl.st.err(GL_INVALID_OPERATION);
            Ok(())
        })
    }

    /// Binds a fragment output's colour number: none on ES 2.0.
    fn glBindFragDataLocationEXT(program: GLuint, color: GLuint, _name: *const GLchar) {
        let args = || format!("{program}, {color}");
        with_gl(Call { name: "glBindFragDataLocationEXT", args: &args }, (), |gl| {
            gl.st.err(GL_INVALID_OPERATION);
            Ok(())
        })
    }

    /// A fragment output's index: none on ES 2.0.
    fn glGetFragDataIndexEXT(program: GLuint, _name: *const GLchar) -> GLint {
        let args = || format!("{program}");
        with_gl(Call { name: "glGetFragDataIndexEXT", args: &args }, 0, |gl| {
            gl.st.err(GL_INVALID_OPERATION);
            Ok(0)
        })
    }

    /// A program resource's index (an ES 3.1 interface): none on ES 2.0.
    fn glGetProgramResourceLocationIndexEXT(program: GLuint, interface: GLenum, _name: *const GLchar) -> GLint {
        let args = || format!("{program}, {interface:#x}");
        with_gl(Call { name: "glGetProgramResourceLocationIndexEXT", args: &args }, 0, |gl| {
            gl.st.err(GL_INVALID_OPERATION);
            Ok(0)
        })
    }
}

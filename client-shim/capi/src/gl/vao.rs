//! `GL_OES_vertex_array_object`: the four entry points, and binding, which switches the
//! client-side state along with the bound vertex array.
//!
//! The library keeps per vertex array what it needs at draw time: which attributes are enabled,
//! which of them are client-side arrays (only the default vertex array can have those: the
//! extension refuses a client pointer while another is bound), and the element array buffer binding
//! (client-side index arrays are allowed with any vertex array). As in the daemon, the bound vertex
//! array's state is `GlState::attribs` / `element_buffer`, the others wait in
//! `GlState::vertex_arrays` (each a `VertexArray`), and binding exchanges them. Names are allocated
//! here, like every other object name; a name that was not generated (or was deleted) leaves the
//! state as it is, and the daemon records the `GL_INVALID_OPERATION`.

use strata_protocol::{Calls, Slice};

use super::with_gl;
use crate::gl_state::{GlState, VertexArray};
use crate::types::*;

/// Makes `array` the bound vertex array if the library knows it; whether it did.
pub(crate) fn bind(st: &mut GlState, array: u32) -> bool {
    if array == st.vertex_array {
        return true;
    }
    let Some(mut next) = st.vertex_arrays.remove(&array) else { return false };
    std::mem::swap(&mut st.attribs, &mut next.attribs);
    std::mem::swap(&mut st.element_buffer, &mut next.element_buffer);
    st.vertex_arrays.insert(st.vertex_array, next);
    st.vertex_array = array;
    true
}

/// Borrows `n` names of application memory (none for a null pointer or a negative count).
///
/// # Safety
/// A non-null `ptr` must be valid for `n` names.
unsafe fn names<'a>(ptr: *const GLuint, n: GLsizei) -> &'a [GLuint] {
    if ptr.is_null() || n <= 0 {
        &[]
    } else {
        // SAFETY: see the function's contract.
        unsafe { std::slice::from_raw_parts(ptr, n as usize) }
    }
}

crate::entry::entry_points! {
    /// Names allocated here, as for every object.
    fn glGenVertexArraysOES(n: GLsizei, arrays: *mut GLuint) {
        with_gl("glGenVertexArraysOES", (), |gl| {
            if n < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            if arrays.is_null() {
                return Ok(());
            }
            let new = gl.names(n as usize);
            for &a in &new {
                gl.st.vertex_arrays.insert(a, VertexArray::default());
            }
            // SAFETY: the application's array has room for `n` names.
            unsafe { std::ptr::copy_nonoverlapping(new.as_ptr(), arrays, new.len()) };
            gl.conn.glGenVertexArraysOES(Slice::new(&new))
        })
    }

    /// Switches the client-side arrays and element binding along with the daemon's.
    fn glBindVertexArrayOES(array: GLuint) {
        with_gl("glBindVertexArrayOES", (), |gl| {
            bind(gl.st, array);
            gl.conn.glBindVertexArrayOES(array)
        })
    }

    /// Deleting the bound vertex array binds the default one.
    fn glDeleteVertexArraysOES(n: GLsizei, arrays: *const GLuint) {
        with_gl("glDeleteVertexArraysOES", (), |gl| {
            if n < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: the application passes `n` names.
            let v = unsafe { names(arrays, n) };
            for &a in v.iter().filter(|&&a| a != 0) {
                if a == gl.st.vertex_array {
                    bind(gl.st, 0);
                }
                gl.st.vertex_arrays.remove(&a);
            }
            gl.conn.glDeleteVertexArraysOES(Slice::new(v))
        })
    }

    /// Whether `array` names a vertex array object (one that has been bound).
    fn glIsVertexArrayOES(array: GLuint) -> GLboolean {
        with_gl("glIsVertexArrayOES", 0, |gl| Ok(GLboolean::from(gl.conn.glIsVertexArrayOES(array)?)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binding_exchanges_the_client_state_and_unknown_names_change_nothing() {
        let mut st = GlState::default();
        st.attribs[0].enabled = true;
        st.element_buffer = 7;
        st.vertex_arrays.insert(5, VertexArray::default());
        assert!(!bind(&mut st, 6), "a name never generated");
        assert_eq!((st.vertex_array, st.element_buffer), (0, 7));
        assert!(bind(&mut st, 5));
        assert_eq!((st.vertex_array, st.element_buffer, st.attribs[0].enabled), (5, 0, false));
        assert!(bind(&mut st, 0));
        assert_eq!((st.vertex_array, st.element_buffer, st.attribs[0].enabled), (0, 7, true));
    }
}

//! `GL_EXT_discard_framebuffer` and ES 3.0's invalidation: the application's attachment list,
//! forwarded to the daemon, which validates it (and treats the discard as a hint).

use strata_protocol::{Calls, Slice};

use super::{values, with_gl, Call, ShowArg};
use crate::types::*;

crate::entry::entry_points! {
    /// A negative count is `GL_INVALID_VALUE` here; the rest is validated by the daemon.
    fn glDiscardFramebufferEXT(target: GLenum, num_attachments: GLsizei, attachments: *const GLenum) {
        let args = || format!("{}, {num_attachments}", target.show());
        with_gl(Call { name: "glDiscardFramebufferEXT", args: &args }, (), |gl| {
            if num_attachments < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: `attachments` holds `num_attachments` enums, as the extension requires.
            let list = unsafe { values(attachments, i64::from(num_attachments)) };
            gl.conn.glDiscardFramebufferEXT(target, Slice::new(list))
        })
    }

    /// ES 3.0: as `glDiscardFramebufferEXT`, by ES 3.0's rules (the daemon's).
    fn glInvalidateFramebuffer(target: GLenum, num_attachments: GLsizei, attachments: *const GLenum) {
        with_gl("glInvalidateFramebuffer", (), |gl| {
            if num_attachments < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: `attachments` holds `num_attachments` enums.
            let list = unsafe { values(attachments, i64::from(num_attachments)) };
            gl.conn.glInvalidateFramebuffer(target, Slice::new(list))
        })
    }

    /// ES 3.0: the same for a region.
    fn glInvalidateSubFramebuffer(
        target: GLenum,
        num_attachments: GLsizei,
        attachments: *const GLenum,
        x: GLint,
        y: GLint,
        width: GLsizei,
        height: GLsizei,
    ) {
        with_gl("glInvalidateSubFramebuffer", (), |gl| {
            if num_attachments < 0 {
                gl.st.err(GL_INVALID_VALUE);
                return Ok(());
            }
            // SAFETY: `attachments` holds `num_attachments` enums.
            let list = unsafe { values(attachments, i64::from(num_attachments)) };
            gl.conn.glInvalidateSubFramebuffer(target, Slice::new(list), x, y, width, height)
        })
    }
}

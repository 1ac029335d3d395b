//! `GL_EXT_draw_buffers` and `GL_NV_draw_buffers`: the application's list of draw buffers,
//! forwarded to the daemon, which validates it.

use strata_client::ClientError;
use strata_protocol::commands::MAX_DRAW_BUFFERS;
use strata_protocol::{Calls, Slice};

use super::{values, with_gl, Call, Gl};
use crate::types::*;

/// A count outside `0..=GL_MAX_DRAW_BUFFERS_EXT` is `GL_INVALID_VALUE` here, before the list
/// is read (it may be shorter than the count); the rest is validated by the daemon.
fn draw_buffers(gl: &mut Gl<'_>, n: GLsizei, bufs: *const GLenum) -> Result<(), ClientError> {
    if !(0..=MAX_DRAW_BUFFERS).contains(&n) {
        gl.st.err(GL_INVALID_VALUE);
        return Ok(());
    }
    // SAFETY: `bufs` holds `n` enums, as the extension requires.
    let list = unsafe { values(bufs, i64::from(n)) };
    gl.conn.glDrawBuffersEXT(Slice::new(list))
}

crate::entry::entry_points! {
    /// `GL_EXT_draw_buffers`: what each fragment output writes.
    fn glDrawBuffersEXT(n: GLsizei, bufs: *const GLenum) {
        let args = || format!("{n}");
        with_gl(Call { name: "glDrawBuffersEXT", args: &args }, (), |gl| draw_buffers(gl, n, bufs))
    }

    /// `GL_NV_draw_buffers`: the same call.
    fn glDrawBuffersNV(n: GLsizei, bufs: *const GLenum) {
        let args = || format!("{n}");
        with_gl(Call { name: "glDrawBuffersNV", args: &args }, (), |gl| draw_buffers(gl, n, bufs))
    }
}

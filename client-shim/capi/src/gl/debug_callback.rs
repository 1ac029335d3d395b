//! `GL_KHR_debug`'s callback: delivering the daemon's debug messages to the application.
//!
//! The daemon generates the messages (the GL errors it records, messages the application
//! inserts, debug groups), filters them and keeps the message log. The callback, though, is the
//! application's code and runs here. While one is installed the daemon keeps new messages for
//! it, and the library fetches them with `strataDebugMessages` and calls the callback on the
//! application's thread, outside the library's lock:
//!
//! - with `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR` enabled, after every GL call, before it returns, as
//!   the extension requires (one round trip per call, the price of synchronous output);
//! - otherwise only where the application waits for the daemon anyway: `glFinish`, `glFlush`,
//!   `glGetError`, `glReadPixels`, `glGetDebugMessageLogKHR` and `eglSwapBuffers`. Messages then
//!   arrive after the call that caused them, which asynchronous output allows, and a frame costs
//!   no extra round trips.
//!
//! Nothing is fetched while no callback is installed or `GL_DEBUG_OUTPUT_KHR` is disabled, so
//! an application that does not use the extension pays nothing. The callback and the enables
//! are the context's [`DebugClient`](crate::gl_state::DebugClient); the entry points that set
//! them are in `gl/debug.rs`.

use std::ffi::c_void;

use strata_client::{ClientError, Connection};
use strata_protocol::commands::DebugMessage;
use strata_protocol::Calls;

use crate::gl_state::GlState;
use crate::state::{self, process};
use crate::surface::ensure_bound;
use crate::types::*;

/// The calls after which pending messages are fetched when output is asynchronous: the ones
/// that wait for the daemon anyway.
const SYNC_POINTS: &[&str] =
    &["glFinish", "glFlush", "glGetError", "glReadPixels", "glGetDebugMessageLogKHR", "eglSwapBuffers"];

/// Messages fetched for a callback, delivered once the library's lock is released.
pub(crate) struct Delivery {
    callback: unsafe extern "C" fn(GLenum, GLenum, GLuint, GLenum, GLsizei, *const GLchar, *const c_void),
    user: usize,
    messages: Vec<DebugMessage>,
}

impl Delivery {
    /// Calls the callback once per message, in order, on this thread.
    pub(crate) fn deliver(self) {
        for m in self.messages {
            let mut text = m.text.0;
            let len = text.len() as GLsizei;
            text.push(0);
            // SAFETY: the application's callback, with the prototype GLDEBUGPROCKHR declares; the
            // text is NUL-terminated and lives through the call, as the extension specifies.
            unsafe {
                (self.callback)(m.source, m.ty, m.id, m.severity, len, text.as_ptr().cast(), self.user as *const c_void)
            };
        }
    }
}

/// After the GL call `call`: the messages waiting for the application's callback, if it has
/// one, output is enabled, and `call` is a point where they are fetched.
pub(crate) fn pull(conn: &mut Connection, st: &GlState, call: &str) -> Result<Option<Delivery>, ClientError> {
    let d = &st.debug;
    let Some(callback) = d.callback.filter(|_| d.output) else { return Ok(None) };
    if !d.synchronous && !SYNC_POINTS.contains(&call) {
        return Ok(None);
    }
    let messages = conn.strataDebugMessages()?;
    Ok((!messages.is_empty()).then_some(Delivery { callback, user: d.user, messages }))
}

/// Fetches and delivers the messages waiting at the sync point `call` (one the library does
/// not route through a GL entry point, such as `eglSwapBuffers`).
pub(crate) fn sync_point(call: &'static str) {
    let Some(cur) = state::current() else { return };
    let fetched = {
        let mut guard = process();
        let p = &mut *guard;
        let wanted = p.contexts.get(&cur.context).is_some_and(|c| c.gl.debug.callback.is_some() && c.gl.debug.output);
        if !wanted || ensure_bound(p, &cur).is_err() {
            return;
        }
        let state::Process { conn: Some(conn), contexts, .. } = p else { return };
        let Some(ctx) = contexts.get(&cur.context) else { return };
        let fetched = pull(conn, &ctx.gl, call);
        if let Err(e) = &fetched {
            p.lose(e);
        }
        fetched
    };
    if let Ok(Some(d)) = fetched {
        d.deliver();
    }
}

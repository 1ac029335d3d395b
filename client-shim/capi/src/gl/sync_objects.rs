//! ES 3.0's sync objects: `glFenceSync` and the calls on what it makes. They are the fences
//! of `EGL_KHR_fence_sync` (`crate::sync`), made, polled and waited for the same way: a fence
//! is signalled once the daemon publishes that the GPU completed the commands before it, which
//! a poll reads from shared memory with no round trip. GL's calls check their arguments in
//! Mesa's order and record GL's errors; in an ES 2.0 context each is `GL_INVALID_OPERATION`.
//! Waiting in the server (`glWaitSync`) needs nothing: the daemon never runs a later command
//! before an earlier one.

use std::ffi::c_void;

use super::{put, with_gl};
use crate::sync::{gl_client_wait, gl_delete_sync, gl_fence_sync, gl_signalled, gl_sync, GlFence, Waited};
use crate::types::*;

/// `GLsync`.
pub type GLsync = *mut c_void;

const GL_SYNC_GPU_COMMANDS_COMPLETE: GLenum = 0x9117;
const GL_SYNC_FLUSH_COMMANDS_BIT: GLbitfield = 0x1;
const GL_TIMEOUT_IGNORED: u64 = u64::MAX;
const GL_OBJECT_TYPE: GLenum = 0x9112;
const GL_SYNC_CONDITION: GLenum = 0x9113;
const GL_SYNC_STATUS: GLenum = 0x9114;
const GL_SYNC_FLAGS: GLenum = 0x9115;
const GL_SYNC_FENCE: GLint = 0x9116;
const GL_UNSIGNALED: GLint = 0x9118;
const GL_SIGNALED: GLint = 0x9119;
const GL_ALREADY_SIGNALED: GLenum = 0x911A;
const GL_TIMEOUT_EXPIRED: GLenum = 0x911B;
const GL_CONDITION_SATISFIED: GLenum = 0x911C;
const GL_WAIT_FAILED: GLenum = 0x911D;

/// What `glGetSynciv` answers, once the sync and the name are checked.
enum Answer {
    /// A value known without looking at the fence.
    Value(GLint),
    /// The status, which a poll gives.
    Status(GlFence),
}

crate::entry::entry_points! {
    /// A fence after the commands so far (which are flushed); null on error.
    fn glFenceSync(condition: GLenum, flags: GLbitfield) -> GLsync {
        with_gl("glFenceSync", std::ptr::null_mut(), |gl| {
            let e = if !gl.st.es3 {
                GL_INVALID_OPERATION
            } else if condition != GL_SYNC_GPU_COMMANDS_COMPLETE {
                GL_INVALID_ENUM
            } else if flags != 0 {
                GL_INVALID_VALUE
            } else {
                return Ok(gl_fence_sync(gl)? as GLsync);
            };
            gl.st.err(e);
            Ok(std::ptr::null_mut())
        })
    }

    /// Whether `sync` is a sync object.
    fn glIsSync(sync: GLsync) -> GLboolean {
        with_gl("glIsSync", 0, |gl| {
            if !gl.st.es3 {
                gl.st.err(GL_INVALID_OPERATION);
                return Ok(0);
            }
            Ok(if gl_sync(sync as usize).is_some() { 1 } else { 0 })
        })
    }

    /// Deletes a sync object (null is no error); a wait on it still ends when its fence signals.
    fn glDeleteSync(sync: GLsync) {
        with_gl("glDeleteSync", (), |gl| {
            if !gl.st.es3 {
                gl.st.err(GL_INVALID_OPERATION);
            } else if !sync.is_null() && !gl_delete_sync(sync as usize) {
                gl.st.err(GL_INVALID_VALUE);
            }
            Ok(())
        })
    }

    /// Waits up to `timeout` ns for a sync: `GL_ALREADY_SIGNALED` if it was signalled when
    /// asked, `GL_CONDITION_SATISFIED` if it became so, `GL_TIMEOUT_EXPIRED`, or
    /// `GL_WAIT_FAILED` for wrong arguments (0 in an ES 2.0 context).
    fn glClientWaitSync(sync: GLsync, flags: GLbitfield, timeout: u64) -> GLenum {
        // On error, the answer: 0 where the call does not exist (as Mesa's dispatch answers),
        // `GL_WAIT_FAILED` where its arguments are wrong.
        let fence = with_gl("glClientWaitSync", Err(0), |gl| {
            let (e, answer) = if !gl.st.es3 {
                (GL_INVALID_OPERATION, 0)
            } else if flags & !GL_SYNC_FLUSH_COMMANDS_BIT != 0 {
                (GL_INVALID_VALUE, GL_WAIT_FAILED)
            } else if let Some(f) = gl_sync(sync as usize) {
                return Ok(Ok(f));
            } else {
                (GL_INVALID_VALUE, GL_WAIT_FAILED)
            };
            gl.st.err(e);
            Ok(Err(answer))
        });
        // The wait holds none of the library's locks.
        match fence.map(|f| gl_client_wait(sync as usize, f, timeout)) {
            Err(answer) => answer,
            Ok(Waited::Already) => GL_ALREADY_SIGNALED,
            Ok(Waited::Satisfied) => GL_CONDITION_SATISFIED,
            Ok(Waited::TimedOut) => GL_TIMEOUT_EXPIRED,
        }
    }

    /// Makes the daemon wait for a sync before later commands: it already runs them in order.
    fn glWaitSync(sync: GLsync, flags: GLbitfield, timeout: u64) {
        with_gl("glWaitSync", (), |gl| {
            let e = if !gl.st.es3 {
                GL_INVALID_OPERATION
            } else if flags != 0 || timeout != GL_TIMEOUT_IGNORED || gl_sync(sync as usize).is_none() {
                GL_INVALID_VALUE
            } else {
                return Ok(());
            };
            gl.st.err(e);
            Ok(())
        })
    }

    /// A sync's type, condition, flags or status (polled), at most `buf_size` values.
    fn glGetSynciv(sync: GLsync, pname: GLenum, buf_size: GLsizei, length: *mut GLsizei, values: *mut GLint) {
        let answer = with_gl("glGetSynciv", None, |gl| {
            let fence = match gl_sync(sync as usize) {
                _ if !gl.st.es3 => Err(GL_INVALID_OPERATION),
                None => Err(GL_INVALID_VALUE),
                Some(f) => match pname {
                    GL_OBJECT_TYPE => Ok(Answer::Value(GL_SYNC_FENCE)),
                    GL_SYNC_CONDITION => Ok(Answer::Value(GL_SYNC_GPU_COMMANDS_COMPLETE as GLint)),
                    GL_SYNC_FLAGS => Ok(Answer::Value(0)),
                    GL_SYNC_STATUS => Ok(Answer::Status(f)),
                    _ => Err(GL_INVALID_ENUM),
                },
            };
            match fence {
                // A negative size: an error, and still the length, as on Mesa.
                Ok(a) if buf_size < 0 => {
                    gl.st.err(GL_INVALID_VALUE);
                    Ok(Some((a, false)))
                }
                Ok(a) => Ok(Some((a, true))),
                Err(e) => {
                    gl.st.err(e);
                    Ok(None)
                }
            }
        });
        let Some((answer, write)) = answer else { return };
        let v = match answer {
            Answer::Value(v) => v,
            Answer::Status(f) if gl_signalled(sync as usize, f) => GL_SIGNALED,
            Answer::Status(_) => GL_UNSIGNALED,
        };
        // SAFETY: `values` has room for `buf_size` values, `length` for one.
        unsafe {
            if write && buf_size > 0 {
                put(values, v);
            }
            put(length, 1);
        }
    }
}

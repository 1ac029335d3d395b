//! `EGL_KHR_fence_sync` and `EGL_KHR_wait_sync` (with `GL_OES_EGL_sync` on the GL side): fence
//! syncs, and `glFinish`, which signals them.
//!
//! A fence is signalled once the GL commands before it have completed. The daemon runs each
//! process's commands in order on one connection, and its `glFinish` waits until the GPU has
//! finished everything the process submitted: so a fence is signalled by any `glFinish`
//! completed after it was created (the application's, or one a wait sends). Creating a fence
//! flushes; a wait with no timeout polls; a wait with a timeout finishes (bounded by the
//! daemon, whose GPU waits are bounded). Waiting in the server (`eglWaitSyncKHR`) needs
//! nothing: the daemon never runs a later command before an earlier one. A fence waited on
//! after the daemon connection was lost is signalled, so that the wait returns.

use std::collections::HashMap;
use std::ffi::c_void;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, PoisonError};

use strata_protocol::Calls;

use crate::display::initialized;
use crate::gl::with_gl;
use crate::state::{self, process};
use crate::types::*;

/// `EGLSyncKHR`.
pub type EGLSyncKHR = *mut c_void;
/// `EGLTimeKHR`: nanoseconds.
pub type EGLTimeKHR = u64;

const EGL_SYNC_FENCE_KHR: EGLint = 0x30F9;
const EGL_SYNC_TYPE_KHR: EGLint = 0x30F7;
const EGL_SYNC_STATUS_KHR: EGLint = 0x30F1;
const EGL_SYNC_CONDITION_KHR: EGLint = 0x30F8;
const EGL_SIGNALED_KHR: EGLint = 0x30F2;
const EGL_UNSIGNALED_KHR: EGLint = 0x30F3;
const EGL_SYNC_PRIOR_COMMANDS_COMPLETE_KHR: EGLint = 0x30F0;
const EGL_TIMEOUT_EXPIRED_KHR: EGLint = 0x30F5;
const EGL_CONDITION_SATISFIED_KHR: EGLint = 0x30F6;

/// `glFinish` calls completed in this process (the application's and the waits').
static FINISHES: AtomicU64 = AtomicU64::new(0);

/// A fence sync.
struct Fence {
    /// The shim's display number it belongs to.
    display: usize,
    /// [`FINISHES`] when it was created: any later finish signals it.
    finishes: u64,
}

/// The live fences by handle; handles are never reused.
static FENCES: Mutex<(usize, Option<HashMap<usize, Fence>>)> = Mutex::new((0, None));

/// Runs `f` on the fence table, and the next handle.
fn fences<R>(f: impl FnOnce(&mut usize, &mut HashMap<usize, Fence>) -> R) -> R {
    let mut g = FENCES.lock().unwrap_or_else(PoisonError::into_inner);
    let (next, map) = &mut *g;
    f(next, map.get_or_insert_with(HashMap::new))
}

/// Whether fence `f` is signalled.
fn signaled(f: &Fence) -> bool {
    FINISHES.load(Ordering::SeqCst) > f.finishes
}

/// Checks `dpy` and that `sync` is one of its fences; `f` runs on it.
fn with_fence<R>(dpy: EGLDisplay, sync: EGLSyncKHR, f: impl FnOnce(&Fence) -> R) -> Result<R, EGLint> {
    let d = initialized(&mut process(), dpy)?;
    fences(|_, map| map.get(&(sync as usize)).filter(|s| s.display == d).map(f)).ok_or(EGL_BAD_PARAMETER)
}

/// Waits until everything the process submitted has completed: the daemon's `glFinish` on the
/// context it has current; with none current nothing can be pending. A lost connection
/// returns at once.
fn finish_everything() {
    let mut p = process();
    if p.daemon_current.is_some() {
        if let Some(conn) = p.conn.as_mut() {
            let _ = conn.glFinish();
        }
    }
    FINISHES.fetch_add(1, Ordering::SeqCst);
}

/// Sets the thread's EGL error from `r`, giving its value or `fail`.
fn answer<T>(r: Result<T, EGLint>, fail: T) -> T {
    match r {
        Ok(v) => {
            state::set_egl_error(EGL_SUCCESS);
            v
        }
        Err(e) => {
            state::set_egl_error(e);
            fail
        }
    }
}

/// `eglCreateSyncKHR`: a fence after the current context's commands, which are flushed.
fn create(dpy: EGLDisplay, ty: EGLenum, attribs: *const EGLint) -> Result<EGLSyncKHR, EGLint> {
    let d = initialized(&mut process(), dpy)?;
    // SAFETY: a non-null list is EGL_NONE-terminated, as EGL requires.
    if ty as EGLint != EGL_SYNC_FENCE_KHR || (!attribs.is_null() && unsafe { *attribs } != EGL_NONE) {
        return Err(EGL_BAD_ATTRIBUTE);
    }
    if state::current().is_none_or(|c| c.display != d) {
        return Err(EGL_BAD_MATCH);
    }
    // SAFETY: glFlush takes no arguments.
    unsafe { crate::gl::simple::glFlush() };
    let finishes = FINISHES.load(Ordering::SeqCst);
    Ok(fences(|next, map| {
        *next += 1;
        // Handles far from small integers and null, and never reused.
        let handle = 0x5E70_0000 + *next * 16;
        map.insert(handle, Fence { display: d, finishes });
        handle as EGLSyncKHR
    }))
}

crate::entry_points! {
    /// Waits for every command of the process (`glFinish`); completes the fences before it.
    fn glFinish() {
        let args = String::new;
        with_gl(crate::gl::Call { name: "glFinish", args: &args }, (), |gl| {
            gl.conn.glFinish()?;
            FINISHES.fetch_add(1, Ordering::SeqCst);
            Ok(())
        })
    }

    /// A fence sync (`EGL_SYNC_FENCE_KHR`, no attributes) after the current context's commands.
    fn eglCreateSyncKHR(dpy: EGLDisplay, ty: EGLenum, attribs: *const EGLint) -> EGLSyncKHR {
        answer(create(dpy, ty, attribs), std::ptr::null_mut())
    }

    /// Destroys a fence.
    fn eglDestroySyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR) -> EGLBoolean {
        let r = with_fence(dpy, sync, |_| ()).map(|()| {
            fences(|_, map| map.remove(&(sync as usize)));
            EGL_TRUE
        });
        answer(r, EGL_FALSE)
    }

    /// Waits for a fence: a zero timeout polls, any other finishes the process's commands.
    fn eglClientWaitSyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR, _flags: EGLint, timeout: EGLTimeKHR) -> EGLint {
        let r = with_fence(dpy, sync, signaled).map(|done| {
            if !done && timeout == 0 {
                return EGL_TIMEOUT_EXPIRED_KHR;
            }
            if !done {
                finish_everything();
            }
            EGL_CONDITION_SATISFIED_KHR
        });
        answer(r, EGL_FALSE as EGLint)
    }

    /// A fence's type, status or condition.
    fn eglGetSyncAttribKHR(dpy: EGLDisplay, sync: EGLSyncKHR, attribute: EGLint, value: *mut EGLint) -> EGLBoolean {
        let r = with_fence(dpy, sync, signaled).and_then(|done| {
            let v = match attribute {
                EGL_SYNC_TYPE_KHR => EGL_SYNC_FENCE_KHR,
                EGL_SYNC_STATUS_KHR if done => EGL_SIGNALED_KHR,
                EGL_SYNC_STATUS_KHR => EGL_UNSIGNALED_KHR,
                EGL_SYNC_CONDITION_KHR => EGL_SYNC_PRIOR_COMMANDS_COMPLETE_KHR,
                _ => return Err(EGL_BAD_ATTRIBUTE),
            };
            if value.is_null() {
                return Err(EGL_BAD_PARAMETER);
            }
            // SAFETY: the application's out-pointer for one value.
            unsafe { *value = v };
            Ok(EGL_TRUE)
        });
        answer(r, EGL_FALSE)
    }

    /// Makes the current context's later commands wait for a fence: they already run after
    /// every earlier command.
    fn eglWaitSyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR, flags: EGLint) -> EGLint {
        let r = with_fence(dpy, sync, |_| ()).and_then(|()| {
            if flags != 0 {
                return Err(EGL_BAD_PARAMETER);
            }
            if state::current().is_none() {
                return Err(EGL_BAD_MATCH);
            }
            Ok(EGL_TRUE as EGLint)
        });
        answer(r, EGL_FALSE as EGLint)
    }
}

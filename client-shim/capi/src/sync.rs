//! `EGL_KHR_fence_sync`, `EGL_KHR_reusable_sync` and `EGL_KHR_wait_sync` (with
//! `GL_OES_EGL_sync` on the GL side): fence syncs, `glFinish`, which signals them, and reusable
//! syncs, which only the application signals (`eglSignalSyncKHR`) and a wait blocks on.
//!
//! A fence is signalled once the GL commands before it have completed. Creating one flushes
//! the context's commands and has the daemon mark the point after them (`strataFence`). The
//! daemon publishes the newest mark whose work has completed in the client's segment as soon as
//! the GPU completes it, whether or not anyone asks; so a poll (a wait with no timeout, or the
//! fence's status) is one read of shared memory, no round trip, and a program that flushes and
//! then polls sees its fence signalled as soon as the work is done, as on Mesa. A wait with a
//! timeout reads the same word until the mark comes, the fence is destroyed, or the time is up.
//! A poll that finds the mark missing also looks at the daemon's socket: a daemon that died
//! publishes nothing more, so its fences are signalled and the connection is lost.
//! A `glFinish` completed after a fence was created signals it too (the daemon's `glFinish`
//! waits for everything the process submitted). Waiting in the server (`eglWaitSyncKHR`) needs
//! nothing: the daemon never runs a later command before an earlier one. A fence waited on
//! after the daemon connection was lost is signalled, so that the wait returns.
//!
//! ES 3.0's sync objects (`gl/sync_objects.rs`) are these fences too, in the same table under
//! a display number of their own, so that neither API finds the other's.

use std::collections::HashMap;
use std::ffi::c_void;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, PoisonError};
use std::time::{Duration, Instant};

use strata_client::ClientError;
use strata_protocol::Calls;

use crate::display::initialized;
use crate::gl::{with_gl, Call, Gl};
use crate::state::{self, answer, process};
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
const EGL_SYNC_REUSABLE_KHR: EGLint = 0x30FA;
const EGL_FOREVER_KHR: EGLTimeKHR = u64::MAX;

/// `glFinish` calls completed in this process (the application's and the waits').
static FINISHES: AtomicU64 = AtomicU64::new(0);

/// A sync object.
struct Fence {
    /// The shim's display number it belongs to.
    display: usize,
    /// What signals it.
    kind: Kind,
}

/// What signals a sync.
#[derive(Clone, Copy)]
enum Kind {
    /// A fence: any finish after [`FINISHES`] had the value `finishes`, the daemon's word that
    /// the GPU has completed the work before `mark` (`None`: the daemon gave no mark), which
    /// `reached` keeps, or the loss of the connection it was made on (`state::LOSSES` past
    /// `losses`).
    Fence { finishes: u64, mark: Option<u64>, reached: bool, losses: u64 },
    /// A reusable sync: the application, and this is its state.
    Reusable(bool),
}

/// Woken whenever a reusable sync is signalled.
static SIGNALLED: Condvar = Condvar::new();

/// The live fences by handle; handles are never reused.
static FENCES: Mutex<(usize, Option<HashMap<usize, Fence>>)> = Mutex::new((0, None));

/// Runs `f` on the fence table, and the next handle.
fn fences<R>(f: impl FnOnce(&mut usize, &mut HashMap<usize, Fence>) -> R) -> R {
    let mut g = FENCES.lock().unwrap_or_else(PoisonError::into_inner);
    let (next, map) = &mut *g;
    f(next, map.get_or_insert_with(HashMap::new))
}

/// Whether sync `f` is signalled.
fn signaled(f: &Fence) -> bool {
    match f.kind {
        Kind::Fence { finishes, reached, .. } => reached || FINISHES.load(Ordering::SeqCst) > finishes,
        Kind::Reusable(signalled) => signalled,
    }
}

/// Whether sync `sync` (of `kind`, not yet signalled) is signalled now: for a fence with a
/// mark, the mark the daemon published in the segment is read (no round trip), and a yes is
/// kept. A lost connection signals, and so does a daemon found gone (its socket closed).
fn poll(sync: usize, kind: Kind) -> bool {
    let Kind::Fence { mark: Some(mark), losses, .. } = kind else { return false };
    let reached = {
        let mut p = process();
        match p.conn.as_ref() {
            _ if state::LOSSES.load(Ordering::SeqCst) > losses => true,
            None => true,
            Some(c) if c.fences_reached() >= mark => true,
            // A daemon that died publishes nothing more: the connection is lost, and the fence
            // signalled (its work will never complete).
            Some(c) if !c.daemon_alive() => {
                p.lose(&ClientError::Unexpected("the daemon closed the connection".into()));
                true
            }
            Some(_) => false,
        }
    };
    if reached {
        fences(|_, map| {
            if let Some(Fence { kind: Kind::Fence { reached, .. }, .. }) = map.get_mut(&sync) {
                *reached = true;
            }
        });
    }
    reached
}

/// Blocks until fence `sync` (of `kind`, with a mark) is signalled or `timeout` (ns) has passed,
/// reading the published mark with growing pauses (50 µs to 1 ms); whether it was signalled.
/// A fence destroyed meanwhile is still waited for, by its mark, as Mesa waits on its fence.
/// Holds no lock while it sleeps.
fn wait_fence(sync: usize, kind: Kind, timeout: EGLTimeKHR) -> bool {
    let deadline =
        if timeout == EGL_FOREVER_KHR { None } else { Instant::now().checked_add(Duration::from_nanos(timeout)) };
    let mut pause = Duration::from_micros(50);
    loop {
        if poll(sync, kind) {
            return true;
        }
        let left = deadline.map(|d| d.saturating_duration_since(Instant::now()));
        if left.is_some_and(|l| l.is_zero()) {
            return false;
        }
        std::thread::sleep(left.map_or(pause, |l| l.min(pause)));
        pause = (pause * 2).min(Duration::from_millis(1));
    }
}

/// Blocks until reusable sync `sync` is signalled, destroyed, or `timeout` (ns) has passed;
/// `eglClientWaitSyncKHR`'s answer for each.
fn wait_reusable(sync: usize, timeout: EGLTimeKHR) -> EGLint {
    let deadline =
        if timeout == EGL_FOREVER_KHR { None } else { Instant::now().checked_add(Duration::from_nanos(timeout)) };
    let mut g = FENCES.lock().unwrap_or_else(PoisonError::into_inner);
    loop {
        match g.1.as_ref().and_then(|m| m.get(&sync)).map(|f| f.kind) {
            Some(Kind::Reusable(false)) => {}
            Some(Kind::Reusable(true)) => return EGL_CONDITION_SATISFIED_KHR,
            // Destroyed while waited on: the wait returns at once, as if it had been signalled
            // (EGL_KHR_reusable_sync).
            _ => return EGL_CONDITION_SATISFIED_KHR,
        }
        g = match deadline {
            None => SIGNALLED.wait(g).unwrap_or_else(PoisonError::into_inner),
            Some(d) => {
                let left = d.saturating_duration_since(Instant::now());
                if left.is_zero() {
                    return EGL_TIMEOUT_EXPIRED_KHR;
                }
                SIGNALLED.wait_timeout(g, left).unwrap_or_else(PoisonError::into_inner).0
            }
        };
    }
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

/// `eglCreateSyncKHR`: a fence after the current context's commands, which are flushed, or an
/// unsignalled reusable sync.
fn create(dpy: EGLDisplay, ty: EGLenum, attribs: *const EGLint) -> Result<EGLSyncKHR, EGLint> {
    let d = initialized(&mut process(), dpy)?;
    // SAFETY: a non-null list is EGL_NONE-terminated, as EGL requires.
    if !attribs.is_null() && unsafe { *attribs } != EGL_NONE {
        return Err(EGL_BAD_ATTRIBUTE);
    }
    let kind = match ty as EGLint {
        EGL_SYNC_FENCE_KHR => {
            if state::current().is_none_or(|c| c.display != d) {
                return Err(EGL_BAD_MATCH);
            }
            let args = String::new;
            with_gl(Call { name: "eglCreateSyncKHR", args: &args }, unmarked(), fence)
        }
        EGL_SYNC_REUSABLE_KHR => Kind::Reusable(false),
        _ => return Err(EGL_BAD_ATTRIBUTE),
    };
    Ok(fences(|next, map| {
        *next += 1;
        // Handles far from small integers and null, and never reused.
        let handle = 0x5E70_0000 + *next * 16;
        map.insert(handle, Fence { display: d, kind });
        handle as EGLSyncKHR
    }))
}

/// A fence after the commands so far with no mark from the daemon: signalled by a finish
/// (or the connection's loss).
fn unmarked() -> Kind {
    let finishes = FINISHES.load(Ordering::SeqCst);
    Kind::Fence { finishes, mark: None, reached: false, losses: state::LOSSES.load(Ordering::SeqCst) }
}

/// Flushes the current context's commands and makes a fence after them.
fn fence(gl: &mut Gl<'_>) -> Result<Kind, ClientError> {
    let mut kind = unmarked();
    let mark = match gl.conn.strataFence() {
        Ok(mark) => Some(mark),
        // A daemon without fences: a flush, and the fence waits for a finish.
        Err(ClientError::Unsupported(_)) => gl.conn.glFlush().map(|()| None)?,
        Err(e) => return Err(e),
    };
    if let Kind::Fence { mark: m, .. } = &mut kind {
        *m = mark;
    }
    Ok(kind)
}

/// The display number GL's sync objects (`glFenceSync`) carry: EGL's calls never find them,
/// nor GL's EGL's.
const GL_SYNCS: usize = usize::MAX;

/// A GL sync object's fence, as a wait or a status query needs it.
#[derive(Clone, Copy)]
pub(crate) struct GlFence(Kind);

/// `glFenceSync`: a fence after the current context's commands, which are flushed; its handle.
pub(crate) fn gl_fence_sync(gl: &mut Gl<'_>) -> Result<usize, ClientError> {
    let kind = fence(gl)?;
    Ok(fences(|next, map| {
        *next += 1;
        let handle = 0x5E70_0000 + *next * 16;
        map.insert(handle, Fence { display: GL_SYNCS, kind });
        handle
    }))
}

/// GL's sync object `sync`, if it is one.
pub(crate) fn gl_sync(sync: usize) -> Option<GlFence> {
    fences(|_, map| map.get(&sync).filter(|f| f.display == GL_SYNCS).map(|f| GlFence(f.kind)))
}

/// Deletes GL's sync object `sync`; whether it was one.
pub(crate) fn gl_delete_sync(sync: usize) -> bool {
    fences(|_, map| {
        let found = map.get(&sync).is_some_and(|f| f.display == GL_SYNCS);
        if found {
            map.remove(&sync);
        }
        found
    })
}

/// Whether GL's sync `sync` is signalled now (polled, as [`poll`]). Not under the library's lock.
pub(crate) fn gl_signalled(sync: usize, f: GlFence) -> bool {
    signaled(&Fence { display: GL_SYNCS, kind: f.0 }) || poll(sync, f.0)
}

/// `glClientWaitSync`'s wait (not under the library's lock): whether the sync was signalled
/// when asked, became signalled within `timeout` ns, or was not.
pub(crate) fn gl_client_wait(sync: usize, f: GlFence, timeout: u64) -> Waited {
    if gl_signalled(sync, f) {
        return Waited::Already;
    }
    if timeout == 0 {
        return Waited::TimedOut;
    }
    match f.0 {
        Kind::Fence { mark: Some(_), .. } if wait_fence(sync, f.0, timeout) => Waited::Satisfied,
        Kind::Fence { mark: Some(_), .. } => Waited::TimedOut,
        _ => {
            finish_everything();
            Waited::Satisfied
        }
    }
}

/// How a `glClientWaitSync` ended.
pub(crate) enum Waited {
    /// Signalled before the wait (`GL_ALREADY_SIGNALED`).
    Already,
    /// Signalled during it (`GL_CONDITION_SATISFIED`).
    Satisfied,
    /// Not signalled in time (`GL_TIMEOUT_EXPIRED`).
    TimedOut,
}

crate::entry::entry_points! {
    /// Waits for every command of the process (`glFinish`); completes the fences before it,
    /// and fills the pixmap of a pixmap surface drawn to.
    fn glFinish() {
        let args = String::new;
        let pixmap = crate::pixmap::current();
        with_gl(Call { name: "glFinish", args: &args }, (), |gl| {
            gl.conn.glFinish()?;
            FINISHES.fetch_add(1, Ordering::SeqCst);
            match pixmap {
                Some(px) => crate::pixmap::fill(gl.conn, px),
                None => Ok(()),
            }
        })
    }

    /// A fence sync (`EGL_SYNC_FENCE_KHR`, no attributes) after the current context's commands,
    /// or a reusable sync (`EGL_SYNC_REUSABLE_KHR`).
    fn eglCreateSyncKHR(dpy: EGLDisplay, ty: EGLenum, attribs: *const EGLint) -> EGLSyncKHR {
        answer(create(dpy, ty, attribs), std::ptr::null_mut())
    }

    /// Destroys a sync; a wait blocked on it returns.
    fn eglDestroySyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR) -> EGLBoolean {
        let r = with_fence(dpy, sync, |_| ()).map(|()| {
            fences(|_, map| map.remove(&(sync as usize)));
            SIGNALLED.notify_all();
            EGL_TRUE
        });
        answer(r, EGL_FALSE)
    }

    /// Waits for a sync: a zero timeout polls (a fence reads the mark the daemon published);
    /// otherwise a fence is waited for until its mark is published, it is destroyed, or the
    /// timeout passes (one the daemon gave no mark: by finishing the process's commands), a
    /// reusable sync until it is signalled, destroyed, or the timeout passes.
    fn eglClientWaitSyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR, _flags: EGLint, timeout: EGLTimeKHR) -> EGLint {
        let r = with_fence(dpy, sync, |f| (signaled(f), f.kind)).map(|(done, kind)| {
            if done || poll(sync as usize, kind) {
                return EGL_CONDITION_SATISFIED_KHR;
            }
            if timeout == 0 {
                return EGL_TIMEOUT_EXPIRED_KHR;
            }
            match kind {
                Kind::Fence { mark: Some(_), .. } if !wait_fence(sync as usize, kind, timeout) => {
                    return EGL_TIMEOUT_EXPIRED_KHR
                }
                Kind::Fence { mark: Some(_), .. } => {}
                Kind::Fence { mark: None, .. } => finish_everything(),
                Kind::Reusable(_) => return wait_reusable(sync as usize, timeout),
            }
            EGL_CONDITION_SATISFIED_KHR
        });
        answer(r, EGL_FALSE as EGLint)
    }

    /// Signals or unsignals a reusable sync, waking its waiters.
    fn eglSignalSyncKHR(dpy: EGLDisplay, sync: EGLSyncKHR, mode: EGLenum) -> EGLBoolean {
        let r = with_fence(dpy, sync, |f| f.kind).and_then(|kind| {
            if !matches!(kind, Kind::Reusable(_)) {
                return Err(EGL_BAD_MATCH);
            }
            let on = match mode as EGLint {
                EGL_SIGNALED_KHR => true,
                EGL_UNSIGNALED_KHR => false,
                _ => return Err(EGL_BAD_ATTRIBUTE),
            };
            fences(|_, map| {
                if let Some(f) = map.get_mut(&(sync as usize)) {
                    f.kind = Kind::Reusable(on);
                }
            });
            SIGNALLED.notify_all();
            Ok(EGL_TRUE)
        });
        answer(r, EGL_FALSE)
    }

    /// A fence's type, status (a fence's polled, as a wait with no timeout) or condition.
    fn eglGetSyncAttribKHR(dpy: EGLDisplay, sync: EGLSyncKHR, attribute: EGLint, value: *mut EGLint) -> EGLBoolean {
        let r = with_fence(dpy, sync, |f| (signaled(f), f.kind)).and_then(|(done, kind)| {
            let fence = matches!(kind, Kind::Fence { .. });
            let done = done || (attribute == EGL_SYNC_STATUS_KHR && poll(sync as usize, kind));
            let v = match attribute {
                EGL_SYNC_TYPE_KHR if fence => EGL_SYNC_FENCE_KHR,
                EGL_SYNC_TYPE_KHR => EGL_SYNC_REUSABLE_KHR,
                EGL_SYNC_STATUS_KHR if done => EGL_SIGNALED_KHR,
                EGL_SYNC_STATUS_KHR => EGL_UNSIGNALED_KHR,
                // A reusable sync has no condition.
                EGL_SYNC_CONDITION_KHR if fence => EGL_SYNC_PRIOR_COMMANDS_COMPLETE_KHR,
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

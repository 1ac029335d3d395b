//! Contexts and current bindings: `eglCreateContext`, `eglDestroyContext`, `eglQueryContext`,
//! `eglMakeCurrent` and releasing a thread's context.
//!
//! The application's context handles are the shim's own, each backed by a daemon context (see
//! [`crate::state::ContextInfo`]); a context whose connection was lost keeps its handle only
//! while a thread still has it current, and every EGL call naming it fails with
//! `EGL_BAD_CONTEXT`.

use strata_protocol::{Calls, Slice};

use crate::display::{daemon, initialized};
use crate::gl_state::GlState;
use crate::state::{self, process, ContextInfo, Current, Process};
use crate::surface;
use crate::types::*;

/// Releases this thread's current context (if any), on the daemon too when it is the one
/// the daemon has current.
pub(crate) fn release_current(p: &mut Process) -> Result<(), EGLint> {
    let Some(cur) = state::current() else { return Ok(()) };
    let on_daemon = p.daemon_context(cur.context);
    p.release_context(cur.context);
    state::set_current(None);
    if on_daemon.is_some() && p.daemon_current.map(|(c, _, _)| c) == on_daemon {
        p.daemon_current = None;
        daemon(p, |c, dd| c.eglMakeCurrent(dd, 0, 0, 0))?;
    }
    Ok(())
}

/// `eglMakeCurrent`, with application handles.
pub(crate) fn make_current(dpy: EGLDisplay, draw: u32, read: u32, ctx: u32) -> Result<(), EGLint> {
    let mut p = process();
    if ctx == 0 {
        if draw != 0 || read != 0 {
            return Err(EGL_BAD_MATCH);
        }
        // Releasing works on any valid display, even a terminated one.
        p.display(dpy as usize).ok_or(EGL_BAD_DISPLAY)?;
        return release_current(&mut p);
    }
    let d = initialized(&mut p, dpy)?;
    let me = std::thread::current().id();
    let c = p.live_context(ctx).ok_or(EGL_BAD_CONTEXT)?;
    if c.owner.is_some_and(|o| o != me) {
        return Err(EGL_BAD_ACCESS);
    }
    let d_ctx = c.daemon.ok_or(EGL_BAD_CONTEXT)?;
    // EGL_KHR_surfaceless_context: no surface at all is a binding; one of two is not.
    if (draw == 0) != (read == 0) {
        return Err(EGL_BAD_MATCH);
    }
    let known = |s: u32| s == 0 || p.surfaces.contains_key(&s);
    if !known(draw) || !known(read) {
        return Err(EGL_BAD_SURFACE);
    }
    surface::follow_window(&mut p, draw);
    if read != draw {
        surface::follow_window(&mut p, read);
    }
    let (d_draw, d_read) = (p.bound_surface(draw), p.bound_surface(read));
    let (Some(d_draw), Some(d_read)) = (d_draw, d_read) else { return Err(EGL_BAD_SURFACE) };
    surface::bind_daemon(&mut p, d_ctx, d_draw, d_read)?;
    if let Some(old) = state::current() {
        p.release_context(old.context);
    }
    if let Some(c) = p.contexts.get_mut(&ctx) {
        c.owner = Some(me);
    }
    state::set_current(Some(Current { display: d, draw, read, context: ctx }));
    Ok(())
}

/// `eglCreateContext`: returns the application's handle.
/// `attribs` with the class `STRATA_PRIORITY` (`high`, `normal` or `low`, what
/// `stratad run --priority` sets) asks for, unless the application asks for one itself. A
/// malformed value is `EGL_BAD_ATTRIBUTE`, and says why.
fn with_env_priority(mut attribs: Vec<EGLint>) -> Result<Vec<EGLint>, EGLint> {
    use strata_protocol::control::{Priority, EGL_CONTEXT_PRIORITY_LEVEL_IMG, PRIORITY_ENV};
    let Ok(name) = std::env::var(PRIORITY_ENV) else { return Ok(attribs) };
    let class: Priority = name.parse().map_err(|e| {
        state::log_once(&format!("{PRIORITY_ENV}: {e}"));
        EGL_BAD_ATTRIBUTE
    })?;
    let pairs = attribs.chunks_exact(2).take_while(|p| p[0] != EGL_NONE);
    if pairs.clone().any(|p| p[0] == EGL_CONTEXT_PRIORITY_LEVEL_IMG) {
        return Ok(attribs);
    }
    let end = pairs.count() * 2;
    attribs.truncate(end);
    attribs.extend([EGL_CONTEXT_PRIORITY_LEVEL_IMG, class.egl_level(), EGL_NONE]);
    Ok(attribs)
}

pub(crate) fn create_context(dpy: EGLDisplay, config: u32, share: u32, attribs: Vec<EGLint>) -> Result<u32, EGLint> {
    if state::api() != EGL_OPENGL_ES_API {
        return Err(EGL_BAD_MATCH);
    }
    let mut p = process();
    let d = initialized(&mut p, dpy)?;
    let (share, group) = match share {
        0 => (0, None),
        s => (p.daemon_context(s).ok_or(EGL_BAD_CONTEXT)?, p.contexts.get(&s).map(|c| c.group)),
    };
    let attribs = with_env_priority(attribs)?;
    let ctx = daemon(&mut p, |c, dd| c.eglCreateContext(dd, config, share, Slice::new(&attribs)))?;
    let mut gl = GlState::default();
    // KHR_debug: a debug context starts with debug output enabled, on the daemon (which has
    // accepted the list) and so here, where the callback is called.
    gl.debug.output = asks_debug(&attribs);
    // The version the daemon gave: a request for 2.0 may get 3.0 (`--es3-for-es2`).
    gl.es3 = match daemon(&mut p, |c, dd| c.eglQueryContext(dd, ctx, EGL_CONTEXT_CLIENT_VERSION)) {
        Ok(v) => v == 3,
        Err(_) => asks_es3(&attribs),
    };
    let handle = p.add_context(ContextInfo { daemon: Some(ctx), display: d, config, owner: None, gl, group: 0 });
    // A new group is named after its first context.
    if let Some(c) = p.contexts.get_mut(&handle) {
        c.group = group.unwrap_or(handle);
    }
    Ok(handle)
}

/// `EGL_CONTEXT_FLAGS_KHR`.
const EGL_CONTEXT_FLAGS_KHR: EGLint = 0x30FC;
/// `EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR`.
const EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR: EGLint = 0x1;

/// `EGL_CONTEXT_CLIENT_VERSION`, which is `EGL_CONTEXT_MAJOR_VERSION_KHR` too.
const EGL_CONTEXT_CLIENT_VERSION: EGLint = 0x3098;

/// Whether an attribute list the daemon accepted asks for ES 3.0 (which it gives only as
/// asked).
fn asks_es3(attribs: &[EGLint]) -> bool {
    let pairs = attribs.chunks_exact(2).take_while(|p| p[0] != EGL_NONE);
    pairs.filter(|p| p[0] == EGL_CONTEXT_CLIENT_VERSION).last().is_some_and(|p| p[1] == 3)
}

/// Whether an attribute list the daemon accepted asks for a debug context.
fn asks_debug(attribs: &[EGLint]) -> bool {
    attribs
        .chunks_exact(2)
        .take_while(|p| p[0] != EGL_NONE)
        .any(|p| p[0] == EGL_CONTEXT_FLAGS_KHR && p[1] & EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR != 0)
}

/// `eglDestroyContext`.
pub(crate) fn destroy_context(dpy: EGLDisplay, ctx: u32) -> Result<(), EGLint> {
    let mut p = process();
    initialized(&mut p, dpy)?;
    let d_ctx = p.daemon_context(ctx).ok_or(EGL_BAD_CONTEXT)?;
    daemon(&mut p, |c, dd| c.eglDestroyContext(dd, d_ctx))?;
    if let Some(gone) = p.contexts.remove(&ctx) {
        // The group's buffers' copies go with its last context.
        if !p.contexts.values().any(|c| c.group == gone.group) {
            p.shadows.remove(&gone.group);
        }
    }
    if p.daemon_current.is_some_and(|(c, _, _)| c == d_ctx) {
        p.daemon_current = None;
    }
    if state::current().is_some_and(|c| c.context == ctx) {
        state::set_current(None);
    }
    Ok(())
}

/// `eglQueryContext`.
pub(crate) fn query_context(dpy: EGLDisplay, ctx: u32, attribute: EGLint, value: *mut EGLint) -> Result<(), EGLint> {
    if value.is_null() {
        return Err(EGL_BAD_PARAMETER);
    }
    let mut p = process();
    initialized(&mut p, dpy)?;
    let c = p.live_context(ctx).ok_or(EGL_BAD_CONTEXT)?;
    if attribute == EGL_CONTEXT_PRIORITY_LEVEL_IMG {
        // The class the daemon schedules the client in: its configuration may override what
        // the context asked for.
        let d_ctx = c.daemon.ok_or(EGL_BAD_CONTEXT)?;
        let v = daemon(&mut p, |conn, dd| conn.eglQueryContext(dd, d_ctx, attribute))?;
        // SAFETY: checked non-null above.
        unsafe { *value = v };
        return Ok(());
    }
    let v = match attribute {
        EGL_CONFIG_ID => c.config as EGLint,
        EGL_CONTEXT_CLIENT_TYPE => EGL_OPENGL_ES_API as EGLint,
        EGL_CONTEXT_CLIENT_VERSION => {
            if c.gl.es3 {
                3
            } else {
                2
            }
        }
        EGL_RENDER_BUFFER => match state::current() {
            Some(cur) if cur.context == ctx => EGL_BACK_BUFFER,
            _ => EGL_NONE,
        },
        _ => return Err(EGL_BAD_ATTRIBUTE),
    };
    // SAFETY: checked non-null above.
    unsafe { *value = v };
    Ok(())
}

//! Window surfaces: where they go (`STRATA_WINDOW`), how big they are (their X window), and
//! following that window when it is resized.
//!
//! EGL window surfaces track their native window's size: a surface is resized when its window
//! is (EGL 1.4 §3.9.1), and applications such as trace replayers create a small window and grow
//! it before they draw. When the window's size changes the shim has the daemon resize the
//! surface in place (`strataResizeSurface`), which keeps its id, its placement (including one
//! `stratad ctl move` gave it), its swap interval and pacing. Like Mesa's X11 platform, the
//! shim looks at the window's size when a surface is made current, after each swap, when the
//! application sets a viewport (what applications do after a resize) and when it queries the
//! surface's size.

use std::ffi::c_ulong;

use strata_protocol::window::WindowPlacement;
use strata_protocol::{Calls, Slice};

use crate::display::{daemon, explicit_placement, initialized};
use crate::state::{self, Current, Process, WindowInfo};
use crate::types::*;
use crate::x11;

/// A native window id as the protocol carries it (`c_ulong` is 32 bits on some targets).
#[allow(clippy::useless_conversion)]
pub(crate) fn window_id(w: EGLNativeWindowType) -> u64 {
    u64::from(w)
}

/// Where a window surface goes: `STRATA_WINDOW`, else the origin at z 0 (the daemon's layout
/// may still place it, by client name).
fn placement() -> WindowPlacement {
    explicit_placement().unwrap_or(WindowPlacement { x: 0, y: 0, z: 0.0, size: None })
}

/// The X display behind the shim's display `d`: the application's, or one the shim opens.
pub(crate) fn x_display(p: &mut Process, d: usize) -> Option<usize> {
    let info = p.display(d)?;
    if info.native != 0 {
        return Some(info.native);
    }
    if info.own_x11.is_none() && std::env::var_os("DISPLAY").is_some() {
        info.own_x11 = crate::x11::open_default();
    }
    info.own_x11
}

/// The size of the X window `win` on the shim's display `d`, if it is one.
fn window_size(p: &mut Process, d: usize, win: u64) -> Option<(i32, i32)> {
    let xd = x_display(p, d)?;
    x11::window_size(xd, c_ulong::try_from(win).ok()?)
}

/// `eglCreateWindowSurface`: a daemon surface sized like the X window (or as `STRATA_WINDOW`
/// says when there is no X window), placed by `STRATA_WINDOW`. Returns the application's handle.
/// Window surfaces this process has created: which of `STRATA_SURFACE_ID`'s IDs the next one
/// takes.
static WINDOWS_MADE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);

/// `attribs` with the stable ID `STRATA_SURFACE_ID` gives this process's next window surface
/// (`"1000"`, or `"1000,1001"` for its first, second…): it wins over the application's own
/// `EGL_SURFACE_ID_STRATA`. A malformed value is `EGL_BAD_ATTRIBUTE`, and says why.
fn with_env_id(attribs: Vec<EGLint>) -> Result<Vec<EGLint>, EGLint> {
    use strata_protocol::surface_id;
    let Ok(list) = std::env::var(surface_id::ENV) else { return Ok(attribs) };
    let n = WINDOWS_MADE.load(std::sync::atomic::Ordering::Relaxed);
    let Some(text) = list.split(',').nth(n) else { return Ok(attribs) };
    match surface_id::parse(text) {
        Ok(id) => Ok(surface_id::with_id(&attribs, id)),
        Err(e) => {
            state::log_once(&format!("{}={list:?}: {e}", surface_id::ENV));
            Err(EGL_BAD_ATTRIBUTE)
        }
    }
}

pub(crate) fn create_window(dpy: EGLDisplay, config: u32, win: u64, attribs: Vec<EGLint>) -> Result<u32, EGLint> {
    let attribs = with_env_id(attribs)?;
    let mut p = crate::state::process();
    let d = initialized(&mut p, dpy)?;
    let place = placement();
    let from_x = window_size(&mut p, d, win);
    let Some((w, h)) = from_x.or(place.size) else {
        state::log_once("cannot size a window surface: not an X11 window, and STRATA_WINDOW gives no WxH");
        return Err(EGL_BAD_NATIVE_WINDOW);
    };
    let s = daemon(&mut p, |c, dd| {
        c.eglCreateWindowSurface(dd, config, win, place.x, place.y, place.z, w, h, Slice::new(&attribs))
    })?;
    WINDOWS_MADE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    if from_x.is_some() {
        // Input for the surface goes to its X window.
        let id = daemon(&mut p, |c, dd| c.eglQuerySurface(dd, s, strata_protocol::surface_id::EGL_SURFACE_ID_STRATA));
        match id.ok().and_then(|id| u64::try_from(id).ok()) {
            Some(id) => crate::input::remember(id, win),
            None => tracing::debug!("strata-egl: no surface ID for window {win:#x}; it gets no input"),
        }
    }
    // Only a surface sized from its X window follows that window.
    let window = from_x.map(|size| WindowInfo { native: win, size });
    Ok(p.add_surface(d, s, window, false))
}

/// Makes `(context, draw, read)` (daemon handles) current on the daemon.
pub(crate) fn bind_daemon(p: &mut Process, context: u32, draw: u32, read: u32) -> Result<(), EGLint> {
    daemon(p, |c, dd| c.eglMakeCurrent(dd, draw, read, context))?;
    p.daemon_current = Some((context, draw, read));
    Ok(())
}

/// Makes the daemon's current binding the one `cur` (this thread's) names, if it is not.
/// A binding whose surface is gone stays as it is when its context is the daemon's current one.
pub(crate) fn ensure_bound(p: &mut Process, cur: &Current) -> Result<(), EGLint> {
    match p.binding(cur) {
        Some(want) if p.daemon_current == Some(want) => Ok(()),
        Some((c, d, r)) => bind_daemon(p, c, d, r),
        None if p.daemon_current.is_some_and(|(c, _, _)| Some(c) == p.daemon_context(cur.context)) => Ok(()),
        None => Err(EGL_BAD_SURFACE),
    }
}

/// Resizes the window surface `s` (an application handle) to its window's current size, if
/// that size changed; nothing for other surfaces. A failure is logged and leaves the surface as
/// it was.
pub(crate) fn follow_window(p: &mut Process, s: u32) {
    let Some(info) = p.surfaces.get(&s) else { return };
    let Some(w) = &info.window else { return };
    let (d, native, old_size, surface) = (info.display, w.native, w.size, info.daemon);
    let Some(size) = window_size(p, d, native) else { return };
    if size == old_size {
        return;
    }
    let resized = daemon(p, |c, dd| c.strataResizeSurface(dd, surface, size.0, size.1));
    // Either way this size has been dealt with: a failure is not retried every frame.
    if let Some(w) = p.surfaces.get_mut(&s).and_then(|i| i.window.as_mut()) {
        w.size = size;
    }
    match resized {
        Ok(()) => {
            tracing::debug!("strata-egl: window {native:#x} is now {}x{}: surface {surface} resized", size.0, size.1)
        }
        Err(e) => state::log_once(&format!(
            "cannot follow a window resized to {}x{}: stratad refused that size (EGL error {e:#x})",
            size.0, size.1
        )),
    }
}

/// Follows the calling thread's current draw surface's window (see [`follow_window`]).
pub(crate) fn follow_current_window(p: &mut Process) {
    if let Some(cur) = state::current() {
        follow_window(p, cur.draw);
    }
}

//! Displays and the daemon connection's lifetime: `eglGetDisplay`, `eglInitialize` (which
//! connects, and connects again after the daemon went away), `eglTerminate`, and running a call
//! on the connection with transport failures turned into `EGL_CONTEXT_LOST`.
//!
//! A lost connection is replaced by the next `eglInitialize`, on any display, whether or not
//! the application called `eglTerminate` first. The lost connection's contexts and surfaces are
//! not carried over: their handles stay invalid (`EGL_BAD_CONTEXT`, `EGL_BAD_SURFACE`), and the
//! shim never reuses a handle, so none of them names an object of the new connection. A lost
//! context still current to a thread stays that thread's current context (its GL calls record
//! `GL_CONTEXT_LOST`) until the thread makes another current or releases it.

use strata_client::{ClientError, ConnectOptions, Connection};
use strata_protocol::handshake::Placement;
use strata_protocol::window::WindowPlacement;
use strata_protocol::{Calls, EglResult};

use crate::input;
use crate::state::{self, process, DisplayInfo, Process};
use crate::types::*;

/// Runs a daemon call on the process's connection, mapping transport failures to EGL errors.
pub(crate) fn daemon<T>(
    p: &mut Process,
    call: impl FnOnce(&mut Connection, u32) -> Result<EglResult<T>, ClientError>,
) -> Result<T, EGLint> {
    let dd = p.daemon_display;
    let Some(conn) = p.conn.as_mut() else {
        return Err(if p.lost { EGL_CONTEXT_LOST } else { EGL_NOT_INITIALIZED });
    };
    match call(conn, dd) {
        Ok(r) => r,
        Err(ClientError::Unsupported(why)) => {
            state::log_once(&format!("stratad does not support a call: {why}"));
            Err(EGL_BAD_ACCESS)
        }
        Err(e) => {
            p.lose(&e);
            Err(EGL_CONTEXT_LOST)
        }
    }
}

/// Checks that `dpy` is one of the shim's displays and is initialized; returns its number.
pub(crate) fn initialized(p: &mut Process, dpy: EGLDisplay) -> Result<usize, EGLint> {
    let d = dpy as usize;
    let info = p.display(d).ok_or(EGL_BAD_DISPLAY)?;
    if !info.initialized {
        return Err(EGL_NOT_INITIALIZED);
    }
    if p.lost {
        return Err(EGL_CONTEXT_LOST);
    }
    Ok(d)
}

/// `eglGetDisplay`: the shim's display for `native`, numbered from 1.
pub(crate) fn get_display(native: usize) -> EGLDisplay {
    let mut p = process();
    let n = match p.displays.iter().position(|d| d.native == native) {
        Some(i) => i + 1,
        None => {
            p.displays.push(DisplayInfo { native, initialized: false, own_x11: None });
            p.displays.len()
        }
    };
    state::set_egl_error(EGL_SUCCESS);
    n as EGLDisplay
}

/// `eglGetPlatformDisplay`: X11 only.
pub(crate) fn platform_display(platform: EGLenum, native: *mut std::ffi::c_void) -> EGLDisplay {
    if platform != EGL_PLATFORM_X11_KHR {
        state::log_once(&format!("EGL platform {platform:#x} is not supported (only X11)"));
        state::set_egl_error(EGL_BAD_PARAMETER);
        return std::ptr::null_mut();
    }
    get_display(native as usize)
}

/// The placement `STRATA_WINDOW` states, if it is set and valid: the connection's, and each
/// window surface's.
pub(crate) fn explicit_placement() -> Option<WindowPlacement> {
    let s = std::env::var(strata_protocol::window::ENV).ok()?;
    s.parse().map_err(|e| state::log_once(&format!("ignoring {e}"))).ok()
}

/// How the shim introduces itself: the socket from `STRATA_SOCKET` (read at each connection),
/// the name from `STRATA_NAME` and the placement from `STRATA_WINDOW`.
fn connect_options() -> ConnectOptions {
    let mut opts = ConnectOptions::default();
    // The daemon's layout matches clients by name (the process name unless STRATA_NAME says
    // otherwise); a placement from STRATA_WINDOW takes precedence over the layout.
    if let Some(name) = std::env::var("STRATA_NAME").ok().filter(|n| !n.is_empty()) {
        opts.name = name;
    }
    opts.placement = explicit_placement().map(|p| Placement {
        x: p.x,
        y: p.y,
        z: p.z,
        width: p.size.map_or(0, |s| s.0 as u32),
        height: p.size.map_or(0, |s| s.1 as u32),
    });
    opts
}

/// Connects to the daemon and installs the connection; after a loss, this replaces the lost
/// one. A failure is logged and leaves the process as it was (still lost, if it was).
fn connect(p: &mut Process) -> Result<(), EGLint> {
    let opts = connect_options();
    let mut conn = Connection::connect(&opts).map_err(|e| {
        tracing::error!("strata-egl: eglInitialize failed: {e}");
        EGL_NOT_INITIALIZED
    })?;
    let dd = conn.eglGetDisplay(0).map_err(|e| {
        tracing::error!("strata-egl: eglInitialize failed: stratad did not answer eglGetDisplay: {e}");
        EGL_NOT_INITIALIZED
    })?;
    let reconnect = p.lost;
    // Input events for the application's windows are read, and sent on as X11 events, by a
    // thread of their own.
    if let Some(reader) = conn.take_input_reader() {
        input::start(reader);
    }
    let (contexts, surfaces) = p.install_connection(conn, dd);
    if reconnect {
        tracing::warn!(
            "strata-egl: connected to stratad again at {}; the lost connection's {contexts} context(s) and \
             {surfaces} surface(s) are gone (a lost context still current to a thread goes when it is released)",
            opts.socket.display()
        );
    }
    Ok(())
}

/// `eglInitialize`: connects (once per process, and again after a loss), then initializes the
/// daemon's display.
pub(crate) fn initialize(dpy: EGLDisplay, major: *mut EGLint, minor: *mut EGLint) -> Result<(), EGLint> {
    let mut p = process();
    let d = dpy as usize;
    p.display(d).ok_or(EGL_BAD_DISPLAY)?;
    if p.conn.is_none() {
        connect(&mut p)?;
    }
    let (ma, mi) = daemon(&mut p, |c, dd| c.eglInitialize(dd)).map_err(|e| match e {
        EGL_CONTEXT_LOST => EGL_NOT_INITIALIZED,
        e => e,
    })?;
    if let Some(info) = p.display(d) {
        info.initialized = true;
    }
    // SAFETY: both out-pointers are optional; non-null ones point at an EGLint.
    unsafe {
        if !major.is_null() {
            *major = ma;
        }
        if !minor.is_null() {
            *minor = mi;
        }
    }
    Ok(())
}

/// `eglTerminate`: marks the display uninitialized; with the last one, the daemon's display goes
/// down and the handles of contexts current to no thread and of surfaces become invalid.
pub(crate) fn terminate(dpy: EGLDisplay) -> Result<(), EGLint> {
    let mut p = process();
    let d = dpy as usize;
    let info = p.display(d).ok_or(EGL_BAD_DISPLAY)?;
    if !info.initialized {
        return Ok(());
    }
    info.initialized = false;
    if p.displays.iter().all(|d| !d.initialized) && (p.conn.is_some() || p.lost) {
        // The daemon's state is per connection; its display goes down with the last one here.
        if p.conn.is_some() {
            if let Err(e) = daemon(&mut p, |c, dd| c.eglTerminate(dd)) {
                tracing::debug!("strata-egl: eglTerminate: stratad answered EGL error {e:#x}");
            }
        }
        p.contexts.retain(|_, c| c.display != d || c.owner.is_some());
        p.surfaces.retain(|_, s| s.display != d);
    }
    Ok(())
}

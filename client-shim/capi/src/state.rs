//! The shim's state: one daemon connection per process (behind a mutex), the EGL objects (each
//! context holding its client-side GL state, see [`crate::gl_state`]), and each thread's current
//! context and EGL error.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};
use std::sync::{LazyLock, Mutex, MutexGuard};
use std::thread::ThreadId;

use strata_client::{ClientError, Connection};

use crate::gl_state::{GlState, Mapping};
use crate::glvnd;
use crate::types::*;

/// An EGL display as the application sees it.
#[derive(Debug)]
pub(crate) struct DisplayInfo {
    /// The native display the application passed (an X11 `Display *`, or null).
    pub native: usize,
    /// Whether `eglInitialize` succeeded (and `eglTerminate` has not been called since).
    pub initialized: bool,
    /// An X11 display the shim opened itself for `EGL_DEFAULT_DISPLAY`.
    pub own_x11: Option<usize>,
}

/// A context as the application holds it: the shim numbers contexts itself, so that a handle
/// from a lost connection never names a context of a later one.
#[derive(Debug)]
pub(crate) struct ContextInfo {
    /// The daemon's handle for it; `None` once the connection it was made on is lost.
    pub daemon: Option<u32>,
    /// The shim's display number.
    pub display: usize,
    /// Config it was created with.
    pub config: u32,
    /// The thread it is current to.
    pub owner: Option<ThreadId>,
    /// Client-side GL state.
    pub gl: GlState,
    /// Its share group: the handle of the group's first context.
    pub group: u32,
}

/// A surface as the application holds it: the shim numbers surfaces itself (a handle of its own
/// per `EGLSurface`, backed by one daemon surface).
#[derive(Debug)]
pub(crate) struct SurfaceInfo {
    /// The shim's display number.
    pub display: usize,
    /// The daemon's surface behind it now.
    pub daemon: u32,
    /// For a window surface sized from its X window: what following that window needs.
    pub window: Option<WindowInfo>,
    /// Whether it is a pbuffer, whose swaps show nothing (and so need no reply).
    pub pbuffer: bool,
    /// For a pixmap surface (a pbuffer in the daemon): the X pixmap its contents go to.
    pub pixmap: Option<PixmapInfo>,
}

/// The X pixmap behind a pixmap surface, which `glFinish` (and so `eglWaitClient`) fills.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PixmapInfo {
    /// The X connection (an address; the library never frees it).
    pub x_display: usize,
    /// The pixmap.
    pub native: u64,
    /// Its width.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// Its depth (24 or 32).
    pub depth: u32,
}

/// What the shim remembers of a window surface to follow its window's size.
#[derive(Debug)]
pub(crate) struct WindowInfo {
    /// The native (X11) window.
    pub native: u64,
    /// The window's size the daemon surface has.
    pub size: (i32, i32),
}

/// Everything shared by the process's threads.
pub(crate) struct Process {
    /// The daemon connection, made by the first successful `eglInitialize`.
    pub conn: Option<Connection>,
    /// Set once the daemon went away: calls fail with a context-lost error until an
    /// `eglInitialize` connects again.
    pub lost: bool,
    /// Displays, numbered from 1 (the `EGLDisplay` value).
    pub displays: Vec<DisplayInfo>,
    /// The daemon's display handle.
    pub daemon_display: u32,
    /// Contexts by the application's handle.
    pub contexts: HashMap<u32, ContextInfo>,
    /// The next application context handle (never reused within the process).
    pub next_context: u32,
    /// Surfaces by the application's handle.
    pub surfaces: HashMap<u32, SurfaceInfo>,
    /// The next application surface handle.
    pub next_surface: u32,
    /// What the daemon has as current: (context, draw, read), in daemon handles.
    pub daemon_current: Option<(u32, u32, u32)>,
    /// The next GL object name (names are allocated by the client).
    pub next_name: u32,
    /// Mapped buffers, by name: the memory handed to the application.
    pub maps: HashMap<u32, Mapping>,
    /// A copy of every buffer's contents, by share group and name: index ranges of
    /// client-array draws read it, uploads from an unpack buffer read it, and reads into a
    /// pack buffer write it. A group's go with its last context.
    pub shadows: HashMap<u32, HashMap<u32, Vec<u8>>>,
}

static PROCESS: LazyLock<Mutex<Process>> = LazyLock::new(|| {
    Mutex::new(Process {
        conn: None,
        lost: false,
        displays: Vec::new(),
        daemon_display: 0,
        contexts: HashMap::new(),
        next_context: 1,
        surfaces: HashMap::new(),
        next_surface: 1,
        daemon_current: None,
        next_name: 1,
        maps: HashMap::new(),
        shadows: HashMap::new(),
    })
});

/// Locks the process state. A panic in another entry point does not make it unusable.
pub(crate) fn process() -> MutexGuard<'static, Process> {
    PROCESS.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// How many times the process has lost its daemon connection: a fence made before a loss is
/// signalled, since the work before it will never complete anywhere else.
pub(crate) static LOSSES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl Process {
    /// Records that the daemon went away: logged once, the connection is dropped and every
    /// context is lost (each records `GL_CONTEXT_LOST`).
    pub fn lose(&mut self, e: &ClientError) {
        if !self.lost {
            tracing::error!(
                "strata-egl: lost the connection to stratad ({e}); calls fail with context lost until eglInitialize \
                 connects again"
            );
        }
        if !self.lost {
            LOSSES.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        }
        self.lost = true;
        self.conn = None;
        self.daemon_current = None;
        for c in self.contexts.values_mut() {
            c.daemon = None;
            c.gl.err(GL_CONTEXT_LOST);
        }
    }

    /// Installs a new connection. After a loss, the lost connection's surfaces are forgotten, and
    /// so are its contexts, except those still current to a thread, which stay lost until that
    /// thread releases them. Returns how many contexts and surfaces were forgotten.
    pub fn install_connection(&mut self, conn: Connection, daemon_display: u32) -> (usize, usize) {
        let (contexts, surfaces) = (self.contexts.len(), self.surfaces.len());
        if self.lost {
            self.contexts.retain(|_, c| c.owner.is_some());
            self.surfaces.clear();
        }
        self.conn = Some(conn);
        self.daemon_display = daemon_display;
        self.daemon_current = None;
        self.lost = false;
        (contexts - self.contexts.len(), surfaces - self.surfaces.len())
    }

    /// Registers a context the daemon created; returns the application's handle for it.
    pub fn add_context(&mut self, info: ContextInfo) -> u32 {
        let mut c = self.next_context.max(1);
        while self.contexts.contains_key(&c) {
            c = c.wrapping_add(1).max(1);
        }
        self.next_context = c.wrapping_add(1);
        self.contexts.insert(c, info);
        c
    }

    /// The context `c` (an application handle), unless it does not exist or is lost.
    pub fn live_context(&self, c: u32) -> Option<&ContextInfo> {
        self.contexts.get(&c).filter(|i| i.daemon.is_some())
    }

    /// The daemon's handle for the application's context `c`, if it is live.
    pub fn daemon_context(&self, c: u32) -> Option<u32> {
        self.contexts.get(&c).and_then(|i| i.daemon)
    }

    /// Marks context `c` current to no thread; a lost context is forgotten then.
    pub fn release_context(&mut self, c: u32) {
        if let Some(info) = self.contexts.get_mut(&c) {
            info.owner = None;
            if info.daemon.is_none() {
                self.contexts.remove(&c);
            }
        }
    }

    /// The display numbered `d`, if it exists.
    pub fn display(&mut self, d: usize) -> Option<&mut DisplayInfo> {
        d.checked_sub(1).and_then(|i| self.displays.get_mut(i))
    }

    /// Registers a daemon surface; returns the application's handle for it.
    pub fn add_surface(&mut self, display: usize, daemon: u32, window: Option<WindowInfo>, pbuffer: bool) -> u32 {
        let mut s = self.next_surface.max(1);
        while self.surfaces.contains_key(&s) {
            s = s.wrapping_add(1).max(1);
        }
        self.next_surface = s.wrapping_add(1);
        self.surfaces.insert(s, SurfaceInfo { display, daemon, window, pbuffer, pixmap: None });
        s
    }

    /// The daemon surface behind the application's surface `s`.
    pub fn daemon_surface(&self, s: u32) -> Option<u32> {
        self.surfaces.get(&s).map(|i| i.daemon)
    }

    /// The daemon surface a binding of the application's surface `s` names: none (0) for no
    /// surface (`EGL_KHR_surfaceless_context`).
    pub fn bound_surface(&self, s: u32) -> Option<u32> {
        if s == 0 {
            return Some(0);
        }
        self.daemon_surface(s)
    }

    /// What the daemon must have current for `cur` (daemon handles), if its context is live and
    /// both its surfaces (if any) still exist.
    pub fn binding(&self, cur: &Current) -> Option<(u32, u32, u32)> {
        Some((self.daemon_context(cur.context)?, self.bound_surface(cur.draw)?, self.bound_surface(cur.read)?))
    }
}

/// A thread's current EGL binding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Current {
    /// The shim's display number.
    pub display: usize,
    /// Draw surface (the application's handle).
    pub draw: u32,
    /// Read surface (the application's handle).
    pub read: u32,
    /// Context (the application's handle).
    pub context: u32,
}

/// Per-thread EGL state.
struct ThreadState {
    error: EGLint,
    current: Option<Current>,
    api: EGLenum,
}

thread_local! {
    static THREAD: RefCell<ThreadState> =
        const { RefCell::new(ThreadState { error: EGL_SUCCESS, current: None, api: EGL_OPENGL_ES_API }) };
}

/// Sets this thread's EGL error.
pub(crate) fn set_egl_error(e: EGLint) {
    let _ = THREAD.try_with(|t| t.borrow_mut().error = e);
}

/// Sets the thread's EGL error from `r` (`EGL_SUCCESS` for a value); the value, or `fail`.
pub(crate) fn answer<T>(r: Result<T, EGLint>, fail: T) -> T {
    match r {
        Ok(v) => {
            set_egl_error(EGL_SUCCESS);
            v
        }
        Err(e) => {
            set_egl_error(e);
            fail
        }
    }
}

/// Returns and clears this thread's EGL error.
pub(crate) fn take_egl_error() -> EGLint {
    THREAD.try_with(|t| std::mem::replace(&mut t.borrow_mut().error, EGL_SUCCESS)).unwrap_or(EGL_SUCCESS)
}

/// This thread's current binding.
pub(crate) fn current() -> Option<Current> {
    THREAD.try_with(|t| t.borrow().current).ok().flatten()
}

/// Changes this thread's current binding (and tells glvnd's dispatch, when the process has it).
pub(crate) fn set_current(c: Option<Current>) {
    let _ = THREAD.try_with(|t| t.borrow_mut().current = c);
    glvnd::follow_current(c.is_some());
}

/// This thread's bound API.
pub(crate) fn api() -> EGLenum {
    THREAD.try_with(|t| t.borrow().api).unwrap_or(EGL_OPENGL_ES_API)
}

/// Changes this thread's bound API.
pub(crate) fn set_api(api: EGLenum) {
    let _ = THREAD.try_with(|t| t.borrow_mut().api = api);
}

/// Logs `what` the first time it happens in this process.
pub(crate) fn log_once(what: &str) {
    static SEEN: LazyLock<Mutex<HashSet<String>>> = LazyLock::new(|| Mutex::new(HashSet::new()));
    let mut seen = SEEN.lock().unwrap_or_else(|p| p.into_inner());
    if seen.insert(what.to_string()) {
        tracing::warn!("strata-egl: {what}");
    }
}

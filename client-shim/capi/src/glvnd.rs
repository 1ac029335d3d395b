//! Sharing the current context with glvnd's GL dispatch, when a process has it.
//!
//! On a glvnd system `libGL.so.1`, `libOpenGL.so.0` and glvnd's GLES libraries export each GL
//! function as a stub that jumps through a per-thread table kept by `libGLdispatch.so.0`; glvnd's
//! libEGL and libGLX set that table when they make a context current (Mesa's own builds without
//! glvnd share `libglapi` the same way). The drop-in libEGL replaces glvnd's libEGL, but a process
//! may still load those libraries: piglit's programs link `libGL.so.1`, for one. A tracer such as
//! apitrace looks up the `gl*` functions it forwards to with `dlsym(RTLD_NEXT, ...)`, which
//! returns the first definition in load order, and that is libGL.so.1's stub whenever the program
//! linked libGL.so.1 before libEGL.so.1. With no table set, the stub does nothing and returns
//! zero: `glGetString(GL_VERSION)` was NULL inside the traced `eglMakeCurrent`, and apitrace
//! aborted. (glmark2 links no libGL.so.1, so there the lookup found the library's own function.)
//!
//! So while libGLdispatch is loaded in the process (the library never loads it itself), making a
//! context current also makes a table of the library's own entry points current in libGLdispatch
//! for that thread, through the interface glvnd's libEGL uses for its vendors (ABI version 1), and
//! releasing the context releases it. A thread with a GLX context current through glvnd is left
//! alone.
//!
//! The table answers libGLdispatch from the lookup `eglGetProcAddress` answers from. That lookup
//! lists every entry point, those that make a context current (and so come here) among them, so
//! this module cannot name it: the registry installs it ([`install_lookup`]) as the library is
//! loaded.

use std::cell::Cell;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::sync::{Mutex, OnceLock};

/// The libGLdispatch interface version this code speaks (`GLDISPATCH_ABI_VERSION`).
const ABI_VERSION: c_int = 1;
/// `GLDISPATCH_API_EGL`: the thread state belongs to an EGL implementation.
const API_EGL: c_int = 1;

/// `__GLdispatchThreadState`: owned by the caller while it is current.
#[repr(C)]
struct ThreadState {
    tag: c_int,
    thread_destroyed: Option<unsafe extern "C" fn(*mut ThreadState)>,
    private: *mut c_void,
}

/// The libGLdispatch functions used, and the library's dispatch table and vendor id.
#[derive(Clone, Copy)]
struct Dispatch {
    current_state: unsafe extern "C" fn() -> *mut ThreadState,
    make_current: unsafe extern "C" fn(*mut ThreadState, *mut c_void, c_int, *const c_void) -> u8,
    lose_current: unsafe extern "C" fn(),
    /// The `__GLdispatchTable *`, as an address.
    table: usize,
    vendor: c_int,
}

/// Whether libGLdispatch has been looked for and found.
enum Found {
    NotYet,
    Yes(Dispatch),
    Unusable,
}

static DISPATCH: Mutex<Found> = Mutex::new(Found::NotYet);

/// The address of one of the library's entry points, by name.
pub(crate) type Lookup = fn(&[u8]) -> Option<*const c_void>;

/// The lookup the library's dispatch table answers with (see [`install_lookup`]).
static LOOKUP: OnceLock<Lookup> = OnceLock::new();

/// Sets the lookup the library's dispatch table answers libGLdispatch with; until it is set,
/// libGLdispatch is not used.
pub(crate) fn install_lookup(lookup: Lookup) {
    let _ = LOOKUP.set(lookup);
}

thread_local! {
    /// This thread's state while the library's table is current in libGLdispatch.
    static MINE: Cell<*mut ThreadState> = const { Cell::new(std::ptr::null_mut()) };
}

/// libGLdispatch's `getProcAddress` callback: the library's own entry point named `name`.
unsafe extern "C" fn proc_address(name: *const c_char, _param: *mut c_void) -> *mut c_void {
    if name.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: libGLdispatch passes NUL-terminated entry point names.
    let name = unsafe { CStr::from_ptr(name) };
    LOOKUP.get().and_then(|lookup| lookup(name.to_bytes())).map_or(std::ptr::null_mut(), |p| p.cast_mut())
}

/// Frees a thread state after libGLdispatch released it for a thread that ended.
unsafe extern "C" fn thread_destroyed(state: *mut ThreadState) {
    if !state.is_null() {
        // SAFETY: every state given to libGLdispatch came from `Box::into_raw` below, and it
        // hands each back once, when its thread ends while current.
        drop(unsafe { Box::from_raw(state) });
    }
}

/// Looks up `name` in `lib` as a function of type `F`.
///
/// # Safety
/// `F` must be the function's C prototype.
unsafe fn symbol<F: Copy>(lib: *mut c_void, name: &CStr) -> Option<F> {
    // SAFETY: `lib` is a handle dlopen returned; the caller vouches for the type.
    let p = unsafe { libc::dlsym(lib, name.as_ptr()) };
    // SAFETY: as above; a function pointer has the size of a data pointer here.
    (!p.is_null()).then(|| unsafe { std::mem::transmute_copy::<*mut c_void, F>(&p) })
}

/// Connects to libGLdispatch if the process has loaded it: checks its interface version,
/// registers as a client and vendor, and creates the library's dispatch table.
fn connect() -> Option<Found> {
    // SAFETY: RTLD_NOLOAD only returns a handle to a library that is already loaded.
    let lib = unsafe { libc::dlopen(c"libGLdispatch.so.0".as_ptr(), libc::RTLD_LAZY | libc::RTLD_NOLOAD) };
    if lib.is_null() {
        return None;
    }
    // SAFETY: the prototypes of glvnd's GLdispatch.h for ABI version 1.
    unsafe {
        let version: unsafe extern "C" fn() -> c_int = symbol(lib, c"__glDispatchGetABIVersion")?;
        if version() != ABI_VERSION {
            tracing::debug!("strata-egl: libGLdispatch speaks ABI {}, not {ABI_VERSION}: not sharing", version());
            return Some(Found::Unusable);
        }
        let init: unsafe extern "C" fn() = symbol(lib, c"__glDispatchInit")?;
        let new_vendor: unsafe extern "C" fn() -> c_int = symbol(lib, c"__glDispatchNewVendorID")?;
        type GetProc = unsafe extern "C" fn(*const c_char, *mut c_void) -> *mut c_void;
        let create: unsafe extern "C" fn(GetProc, *mut c_void) -> *mut c_void =
            symbol(lib, c"__glDispatchCreateTable")?;
        let d = Dispatch {
            current_state: symbol(lib, c"__glDispatchGetCurrentThreadState")?,
            make_current: symbol(lib, c"__glDispatchMakeCurrent")?,
            lose_current: symbol(lib, c"__glDispatchLoseCurrent")?,
            table: 0,
            vendor: 0,
        };
        // A client for the rest of the process: never finalised.
        init();
        let table = create(proc_address, std::ptr::null_mut());
        if table.is_null() {
            return Some(Found::Unusable);
        }
        Some(Found::Yes(Dispatch { table: table as usize, vendor: new_vendor(), ..d }))
    }
}

/// libGLdispatch, if the process has loaded it (looked for again until it has, and until the
/// lookup is installed).
fn dispatch() -> Option<Dispatch> {
    let mut found = DISPATCH.lock().unwrap_or_else(|p| p.into_inner());
    if let Found::NotYet = *found {
        LOOKUP.get()?;
        match connect() {
            Some(f) => *found = f,
            None => return None,
        }
    }
    match *found {
        Found::Yes(d) => Some(d),
        _ => None,
    }
}

/// Makes the library's dispatch table current in libGLdispatch for this thread when it has a
/// context current (`current`), and releases it when it has none.
pub(crate) fn follow_current(current: bool) {
    let Some(d) = dispatch() else { return };
    let Ok(mine) = MINE.try_with(Cell::get) else { return };
    // SAFETY: libGLdispatch's functions, called as glvnd's libEGL calls them.
    unsafe {
        let state = (d.current_state)();
        if current {
            // Already current (one table serves every context), or another API's context is.
            if !state.is_null() {
                return;
            }
            let st = Box::into_raw(Box::new(ThreadState {
                tag: API_EGL,
                thread_destroyed: Some(thread_destroyed),
                private: std::ptr::null_mut(),
            }));
            if (d.make_current)(st, d.table as *mut c_void, d.vendor, std::ptr::null()) != 0 {
                let _ = MINE.try_with(|m| m.set(st));
            } else {
                drop(Box::from_raw(st));
            }
        } else if !state.is_null() && state == mine {
            (d.lose_current)();
            let _ = MINE.try_with(|m| m.set(std::ptr::null_mut()));
            drop(Box::from_raw(state));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_answers_with_every_entry_point_as_soon_as_the_library_is_loaded() {
        assert!(LOOKUP.get().is_some(), "the lookup is installed before any entry point runs");
        for name in [c"glClear", c"glFinish", c"glEGLImageTargetTexture2DOES", c"eglMakeCurrent"] {
            // SAFETY: a NUL-terminated name.
            let p = unsafe { proc_address(name.as_ptr(), std::ptr::null_mut()) };
            assert!(!p.is_null(), "{name:?}");
        }
        // SAFETY: as above.
        assert!(unsafe { proc_address(c"glNoSuchCall".as_ptr(), std::ptr::null_mut()) }.is_null());
    }
}

//! The few Xlib calls the shim needs (window size, a visual for `EGL_NATIVE_VISUAL_ID`),
//! with libX11 loaded at run time so that the shim works without X.

use std::ffi::{c_char, c_int, c_uint, c_ulong, c_void};
use std::sync::{Mutex, OnceLock};

type Display = c_void;

/// `XVisualInfo` from `X11/Xutil.h`.
#[repr(C)]
struct XVisualInfo {
    visual: *mut c_void,
    visualid: c_ulong,
    screen: c_int,
    depth: c_int,
    class: c_int,
    red_mask: c_ulong,
    green_mask: c_ulong,
    blue_mask: c_ulong,
    colormap_size: c_int,
    bits_per_rgb: c_int,
}

const TRUE_COLOR: c_int = 4;

type ErrorHandler = Option<unsafe extern "C" fn(*mut Display, *mut c_void) -> c_int>;

struct Xlib {
    open_display: unsafe extern "C" fn(*const c_char) -> *mut Display,
    default_screen: unsafe extern "C" fn(*mut Display) -> c_int,
    default_depth: unsafe extern "C" fn(*mut Display, c_int) -> c_int,
    default_visual: unsafe extern "C" fn(*mut Display, c_int) -> *mut c_void,
    visual_id: unsafe extern "C" fn(*mut c_void) -> c_ulong,
    match_visual_info: unsafe extern "C" fn(*mut Display, c_int, c_int, c_int, *mut XVisualInfo) -> c_int,
    #[allow(clippy::type_complexity)]
    get_geometry: unsafe extern "C" fn(
        *mut Display,
        c_ulong,
        *mut c_ulong,
        *mut c_int,
        *mut c_int,
        *mut c_uint,
        *mut c_uint,
        *mut c_uint,
        *mut c_uint,
    ) -> c_int,
    set_error_handler: unsafe extern "C" fn(ErrorHandler) -> ErrorHandler,
    next_request: unsafe extern "C" fn(*mut Display) -> c_ulong,
}

fn xlib() -> Option<&'static Xlib> {
    static XLIB: OnceLock<Option<Xlib>> = OnceLock::new();
    XLIB.get_or_init(|| {
        // SAFETY: loading libX11 runs its (well-behaved) initialisers; the library is never unloaded.
        let lib = unsafe { libloading::Library::new("libX11.so.6") }
            .map_err(|e| tracing::debug!("strata-egl: libX11 not available: {e}"))
            .ok()?;
        let lib: &'static libloading::Library = Box::leak(Box::new(lib));
        macro_rules! sym {
            ($name:literal) => {
                // SAFETY: the declared type is the Xlib prototype of this symbol.
                *unsafe { lib.get($name) }.map_err(|e| tracing::warn!("strata-egl: libX11 lacks a symbol: {e}")).ok()?
            };
        }
        Some(Xlib {
            open_display: sym!("XOpenDisplay"),
            default_screen: sym!("XDefaultScreen"),
            default_depth: sym!("XDefaultDepth"),
            default_visual: sym!("XDefaultVisual"),
            visual_id: sym!("XVisualIDFromVisual"),
            match_visual_info: sym!("XMatchVisualInfo"),
            get_geometry: sym!("XGetGeometry"),
            set_error_handler: sym!("XSetErrorHandler"),
            next_request: sym!("XNextRequest"),
        })
    })
    .as_ref()
}

/// Opens the display named by `$DISPLAY`, if there is an X server.
pub(crate) fn open_default() -> Option<usize> {
    let x = xlib()?;
    // SAFETY: XOpenDisplay(NULL) reads $DISPLAY; a null result means no server.
    let d = unsafe { (x.open_display)(std::ptr::null()) };
    (!d.is_null()).then_some(d as usize)
}

/// A depth-24 TrueColor visual of the display's default screen (the default visual when it is
/// one), as the visual id X clients create windows with.
pub(crate) fn visual_id(display: usize) -> Option<u32> {
    let x = xlib()?;
    let d = display as *mut Display;
    // SAFETY: `d` is a live Display the application (or the shim) opened; these calls only
    // read it.
    unsafe {
        let screen = (x.default_screen)(d);
        let mut info: XVisualInfo = std::mem::zeroed();
        let default = (x.visual_id)((x.default_visual)(d, screen));
        if (x.default_depth)(d, screen) == 24 && (x.match_visual_info)(d, screen, 24, TRUE_COLOR, &mut info) != 0 {
            return Some(default as u32);
        }
        for depth in [24, 32] {
            if (x.match_visual_info)(d, screen, depth, TRUE_COLOR, &mut info) != 0 {
                return Some(info.visualid as u32);
            }
        }
        Some(default as u32)
    }
}

/// `XErrorEvent` from `X11/Xlib.h`.
#[repr(C)]
struct XErrorEvent {
    kind: c_int,
    display: *mut Display,
    resource_id: c_ulong,
    serial: c_ulong,
    error_code: u8,
    request_code: u8,
    minor_code: u8,
}

/// The one request whose error the shim is waiting for, and the handler it displaced.
struct Pending {
    /// The connection the request went out on (an address; the pointer is never read).
    display: usize,
    /// The request's serial number.
    serial: c_ulong,
    /// Whether the X server answered it with an error.
    failed: bool,
    /// The application's handler, which gets every other error.
    previous: ErrorHandler,
}

static PENDING: Mutex<Option<Pending>> = Mutex::new(None);

unsafe extern "C" fn record_error(d: *mut Display, ev: *mut c_void) -> c_int {
    let mut pending = PENDING.lock().unwrap_or_else(|p| p.into_inner());
    let Some(p) = pending.as_mut() else { return 0 };
    // SAFETY: Xlib passes an XErrorEvent.
    let e = unsafe { &*ev.cast::<XErrorEvent>() };
    if e.display as usize == p.display && e.serial == p.serial {
        p.failed = true;
        return 0;
    }
    // An error of one of the application's own requests: its handler decides.
    let previous = p.previous;
    drop(pending);
    match previous {
        // SAFETY: the handler the application installed, called as Xlib would.
        Some(h) => unsafe { h(d, ev) },
        None => 0,
    }
}

/// The size of an X window, or `None` if it is not a window of `display`. One round trip.
pub(crate) fn window_size(display: usize, window: c_ulong) -> Option<(i32, i32)> {
    let x = xlib()?;
    let d = display as *mut Display;
    let (mut root, mut px, mut py) = (0, 0, 0);
    let (mut w, mut h, mut border, mut depth) = (0, 0, 0, 0);
    // SAFETY: `d` is a live Display; the temporary error handler turns a BadWindow/BadDrawable
    // of this request into a failed call instead of Xlib's default exit, passes every other
    // error to the previous handler, and that handler is restored.
    let (status, failed) = unsafe {
        let serial = (x.next_request)(d);
        let previous = (x.set_error_handler)(Some(record_error));
        *PENDING.lock().unwrap_or_else(|p| p.into_inner()) = Some(Pending { display, serial, failed: false, previous });
        let s = (x.get_geometry)(d, window, &mut root, &mut px, &mut py, &mut w, &mut h, &mut border, &mut depth);
        (x.set_error_handler)(previous);
        let failed = PENDING.lock().unwrap_or_else(|p| p.into_inner()).take().is_some_and(|p| p.failed);
        (s, failed)
    };
    (status != 0 && !failed && w > 0 && h > 0).then_some((w as i32, h as i32))
}

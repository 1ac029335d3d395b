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
    sync: unsafe extern "C" fn(*mut Display, c_int) -> c_int,
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
            sync: sym!("XSync"),
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

static FAILED: Mutex<bool> = Mutex::new(false);

unsafe extern "C" fn record_error(_: *mut Display, _: *mut c_void) -> c_int {
    *FAILED.lock().unwrap_or_else(|p| p.into_inner()) = true;
    0
}

/// The size of an X window, or `None` if it is not a window of `display`.
pub(crate) fn window_size(display: usize, window: c_ulong) -> Option<(i32, i32)> {
    let x = xlib()?;
    let d = display as *mut Display;
    let (mut root, mut px, mut py) = (0, 0, 0);
    let (mut w, mut h, mut border, mut depth) = (0, 0, 0, 0);
    *FAILED.lock().unwrap_or_else(|p| p.into_inner()) = false;
    // SAFETY: `d` is a live Display; the temporary error handler turns a BadWindow/BadDrawable
    // into a failed call instead of Xlib's default exit, and the previous handler is restored.
    let status = unsafe {
        (x.sync)(d, 0);
        let previous = (x.set_error_handler)(Some(record_error));
        let s = (x.get_geometry)(d, window, &mut root, &mut px, &mut py, &mut w, &mut h, &mut border, &mut depth);
        (x.sync)(d, 0);
        (x.set_error_handler)(previous);
        s
    };
    let failed = *FAILED.lock().unwrap_or_else(|p| p.into_inner());
    (status != 0 && !failed && w > 0 && h > 0).then_some((w as i32, h as i32))
}

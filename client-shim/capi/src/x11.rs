//! The few Xlib calls the shim needs (a drawable's size and depth, a visual for
//! `EGL_NATIVE_VISUAL_ID`, a pixmap surface's pixels put into its pixmap), with libX11 loaded
//! at run time so that the shim works without X. The shim's own requests never reach the
//! application's X error handler or Xlib's default one, which exits: their errors are trapped.

use std::ffi::{c_char, c_int, c_uint, c_ulong, c_void};
use std::sync::{Mutex, OnceLock};

use x11_dl::xlib::XImage;

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
    #[allow(clippy::type_complexity)]
    create_image: unsafe extern "C" fn(
        *mut Display,
        *mut c_void,
        c_uint,
        c_int,
        c_int,
        *mut c_char,
        c_uint,
        c_uint,
        c_int,
        c_int,
    ) -> *mut XImage,
    #[allow(clippy::type_complexity)]
    put_image: unsafe extern "C" fn(
        *mut Display,
        c_ulong,
        *mut c_void,
        *mut XImage,
        c_int,
        c_int,
        c_int,
        c_int,
        c_uint,
        c_uint,
    ) -> c_int,
    create_gc: unsafe extern "C" fn(*mut Display, c_ulong, c_ulong, *mut c_void) -> *mut c_void,
    free_gc: unsafe extern "C" fn(*mut Display, *mut c_void) -> c_int,
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
            next_request: sym!("XNextRequest"),
            create_image: sym!("XCreateImage"),
            put_image: sym!("XPutImage"),
            create_gc: sym!("XCreateGC"),
            free_gc: sym!("XFreeGC"),
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

/// The shim's requests whose errors it is waiting for (those from `serial` on, on `display`),
/// and the handler it displaced.
struct Pending {
    /// The connection the requests went out on (an address; the pointer is never read).
    display: usize,
    /// The serial number of the first of them.
    serial: c_ulong,
    /// Whether the X server answered one of them with an error.
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
    if e.display as usize == p.display && e.serial >= p.serial {
        p.failed = true;
        return 0;
    }
    // An error of one of the application's own earlier requests: its handler decides.
    let previous = p.previous;
    drop(pending);
    match previous {
        // SAFETY: the handler the application installed, called as Xlib would.
        Some(h) => unsafe { h(d, ev) },
        None => 0,
    }
}

/// Runs `requests` on `display` with their X errors trapped; what they returned, and whether
/// any failed. `requests` must end with a round trip, so that their errors have come.
///
/// # Safety
/// `display` is a live Display.
unsafe fn trapped<R>(x: &Xlib, display: usize, requests: impl FnOnce(*mut Display) -> R) -> (R, bool) {
    let d = display as *mut Display;
    // SAFETY: see the function's contract; the handler is restored before returning.
    unsafe {
        let serial = (x.next_request)(d);
        let previous = (x.set_error_handler)(Some(record_error));
        *PENDING.lock().unwrap_or_else(|p| p.into_inner()) = Some(Pending { display, serial, failed: false, previous });
        let r = requests(d);
        (x.set_error_handler)(previous);
        let failed = PENDING.lock().unwrap_or_else(|p| p.into_inner()).take().is_some_and(|p| p.failed);
        (r, failed)
    }
}

/// The size and depth of an X drawable (window or pixmap), or `None` if it is not a drawable
/// of `display`. One round trip.
pub(crate) fn drawable_geometry(display: usize, drawable: c_ulong) -> Option<(u32, u32, u32)> {
    let x = xlib()?;
    let (mut root, mut px, mut py) = (0, 0, 0);
    let (mut w, mut h, mut border, mut depth) = (0, 0, 0, 0);
    // SAFETY: `display` is a live Display; GetGeometry is a round trip.
    let (status, failed) = unsafe {
        trapped(x, display, |d| {
            (x.get_geometry)(d, drawable, &mut root, &mut px, &mut py, &mut w, &mut h, &mut border, &mut depth)
        })
    };
    (status != 0 && !failed && w > 0 && h > 0).then_some((w, h, depth))
}

/// The size of an X window, or `None` if it is not a window of `display`. One round trip.
pub(crate) fn window_size(display: usize, window: c_ulong) -> Option<(i32, i32)> {
    drawable_geometry(display, window).map(|(w, h, _)| (w as i32, h as i32))
}

/// Puts `rgba` (RGBA8 rows from the bottom, `width` × `height`) into X pixmap `pixmap` of
/// `depth` bits (24 or 32, TrueColor), top row first as X lays it out. Whether the X server
/// took it (a pixmap freed meanwhile fails, trapped). One round trip.
pub(crate) fn put_rgba(display: usize, pixmap: c_ulong, width: u32, height: u32, depth: u32, rgba: &[u8]) -> bool {
    let Some(x) = xlib() else { return false };
    let (w, h) = (width as usize, height as usize);
    if rgba.len() < w * h * 4 {
        return false;
    }
    let d = display as *mut Display;
    // SAFETY: `display` is live; the image's data is ours, outlives the request (XSync), and is
    // detached before Xlib frees the image structure.
    unsafe {
        let screen = (x.default_screen)(d);
        let mut info: XVisualInfo = std::mem::zeroed();
        if (x.match_visual_info)(d, screen, depth as c_int, TRUE_COLOR, &mut info) == 0 {
            return false;
        }
        let shift = |mask: c_ulong| mask.trailing_zeros();
        let (rs, gs, bs) = (shift(info.red_mask), shift(info.green_mask), shift(info.blue_mask));
        let mut data: Vec<u32> = Vec::with_capacity(w * h);
        for row in (0..h).rev() {
            for p in rgba[row * w * 4..(row + 1) * w * 4].chunks_exact(4) {
                let a = if depth == 32 { u32::from(p[3]) << 24 } else { 0 };
                data.push(u32::from(p[0]) << rs | u32::from(p[1]) << gs | u32::from(p[2]) << bs | a);
            }
        }
        let img = (x.create_image)(d, info.visual, depth, 2, 0, data.as_mut_ptr().cast(), width, height, 32, 0);
        if img.is_null() {
            return false;
        }
        let ((), failed) = trapped(x, display, |d| {
            let gc = (x.create_gc)(d, pixmap, 0, std::ptr::null_mut());
            (x.put_image)(d, pixmap, gc, img, 0, 0, 0, 0, width, height);
            (x.free_gc)(d, gc);
            (x.sync)(d, 0);
        });
        (*img).data = std::ptr::null_mut();
        if let Some(destroy) = (*img).funcs.destroy_image {
            destroy(img);
        }
        !failed
    }
}

//! Window surfaces of the drop-in libEGL follow their X window's size, as EGL requires (EGL 1.4
//! §3.9.1; Mesa's X11 platform does the same): after the window is resized, the surface has
//! the X server's new size when it is queried, after `eglSwapBuffers`, after `glViewport` and
//! after `eglMakeCurrent`, and a clear covers the whole new size. The expected sizes are the
//! X server's (`XGetGeometry`), never the library's. The daemon keeps one surface per window.
//!
//! Also: a window id that is not a window fails with `EGL_BAD_NATIVE_WINDOW` instead of
//! Xlib's default exit, and the application's own X errors still reach its own handler.
//!
//! Its own test binary: it points the library at the daemon through the process environment.

mod support;

use std::ffi::{c_int, c_void};
use std::sync::atomic::{AtomicUsize, Ordering};

use support::{Daemon, TempDir, Xvfb};
use x11_dl::xlib;

type Ptr = *mut c_void;

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_WINDOW_BIT: i32 = 0x0004;
const EGL_RENDERABLE_TYPE: i32 = 0x3040;
const EGL_OPENGL_ES2_BIT: i32 = 0x0004;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const EGL_DRAW: i32 = 0x3059;
const EGL_BAD_NATIVE_WINDOW: i32 = 0x300B;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

/// The entry points the test calls, resolved from the shared object.
struct Egl {
    get_display: unsafe extern "C" fn(Ptr) -> Ptr,
    initialize: unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32,
    choose_config: unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32,
    create_window: unsafe extern "C" fn(Ptr, Ptr, u64, *const i32) -> Ptr,
    create_context: unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr,
    make_current: unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32,
    current_surface: unsafe extern "C" fn(i32) -> Ptr,
    query_surface: unsafe extern "C" fn(Ptr, Ptr, i32, *mut i32) -> u32,
    swap_buffers: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    get_error: unsafe extern "C" fn() -> i32,
    viewport: unsafe extern "C" fn(i32, i32, i32, i32),
    clear_color: unsafe extern "C" fn(f32, f32, f32, f32),
    clear: unsafe extern "C" fn(u32),
    read_pixels: unsafe extern "C" fn(i32, i32, i32, i32, u32, u32, *mut c_void),
    gl_error: unsafe extern "C" fn() -> u32,
}

fn load(lib: &libloading::Library) -> Egl {
    // SAFETY: each symbol is declared with its C prototype from egl.h / gl2.h (on x86-64 an
    // EGLNativeWindowType is an X11 Window, a 64-bit integer).
    unsafe {
        Egl {
            get_display: support::egl::sym(lib, b"eglGetDisplay"),
            initialize: support::egl::sym(lib, b"eglInitialize"),
            choose_config: support::egl::sym(lib, b"eglChooseConfig"),
            create_window: support::egl::sym(lib, b"eglCreateWindowSurface"),
            create_context: support::egl::sym(lib, b"eglCreateContext"),
            make_current: support::egl::sym(lib, b"eglMakeCurrent"),
            current_surface: support::egl::sym(lib, b"eglGetCurrentSurface"),
            query_surface: support::egl::sym(lib, b"eglQuerySurface"),
            swap_buffers: support::egl::sym(lib, b"eglSwapBuffers"),
            get_error: support::egl::sym(lib, b"eglGetError"),
            viewport: support::egl::sym(lib, b"glViewport"),
            clear_color: support::egl::sym(lib, b"glClearColor"),
            clear: support::egl::sym(lib, b"glClear"),
            read_pixels: support::egl::sym(lib, b"glReadPixels"),
            gl_error: support::egl::sym(lib, b"glGetError"),
        }
    }
}

/// X errors the application's own handler saw.
static APP_ERRORS: AtomicUsize = AtomicUsize::new(0);

unsafe extern "C" fn app_handler(_: *mut xlib::Display, _: *mut xlib::XErrorEvent) -> c_int {
    APP_ERRORS.fetch_add(1, Ordering::SeqCst);
    0
}

/// The surfaces the daemon lists for `client`.
fn daemon_surfaces(socket: &std::path::Path, client: &str) -> usize {
    let out = std::process::Command::new(support::stratad())
        .args(["ctl", "--json", "--socket"])
        .arg(socket)
        .arg("list")
        .output()
        .expect("stratad ctl");
    let list: serde_json::Value = serde_json::from_slice(&out.stdout).expect("ctl list JSON");
    list["surfaces"].as_array().map_or(0, |s| s.iter().filter(|s| s["client"] == client).count())
}

#[test]
fn window_surfaces_follow_their_x_window() {
    let Some(x) = Xvfb::start_or_skip(320, 240) else { return };
    let daemon = Daemon::start("egl-window", &["--output", "headless:w=64x64"]);
    // SAFETY: set before this test binary's only test starts any thread that reads the
    // environment; the library reads it at eglInitialize.
    unsafe {
        std::env::set_var("STRATA_SOCKET", &daemon.socket);
        std::env::set_var("STRATA_NAME", "egl-window");
        std::env::remove_var("STRATA_WINDOW");
    }
    let tmp = TempDir::new("egl-window");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    let xl = xlib::Xlib::open().expect("libX11");
    let name = std::ffi::CString::new(x.display.as_str()).expect("display name");
    // SAFETY: Xlib and EGL/GL calls with the arguments their headers describe, on a display
    // and window this test owns; every out-pointer is valid.
    unsafe {
        let xd = (xl.XOpenDisplay)(name.as_ptr());
        assert!(!xd.is_null(), "XOpenDisplay");
        (xl.XSetErrorHandler)(Some(app_handler));
        let win = (xl.XCreateSimpleWindow)(xd, (xl.XDefaultRootWindow)(xd), 0, 0, 64, 48, 0, 0, 0);
        (xl.XSync)(xd, 0);
        let x_size = |w: u64| {
            let (mut root, mut px, mut py, mut ww, mut hh, mut b, mut depth) = (0, 0, 0, 0, 0, 0, 0);
            (xl.XGetGeometry)(xd, w, &mut root, &mut px, &mut py, &mut ww, &mut hh, &mut b, &mut depth);
            (ww as i32, hh as i32)
        };
        let resize = |w: i32, h: i32| {
            (xl.XResizeWindow)(xd, win, w as u32, h as u32);
            (xl.XSync)(xd, 0);
            x_size(win)
        };

        let dpy = (egl.get_display)(xd.cast());
        assert_eq!((egl.initialize)(dpy, std::ptr::null_mut(), std::ptr::null_mut()), 1, "eglInitialize");
        let attribs = [EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, attribs.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");

        // Not a window: an EGL error, and the process lives on.
        let none = [EGL_NONE];
        let bogus = win + 0x1000;
        assert!((egl.create_window)(dpy, config, bogus, none.as_ptr()).is_null());
        assert_eq!((egl.get_error)(), EGL_BAD_NATIVE_WINDOW);
        // An error of the application's own request, pending while the library asks the X
        // server about a window, reaches the application's handler.
        (xl.XMapWindow)(xd, bogus);
        let surface = (egl.create_window)(dpy, config, win, none.as_ptr());
        assert!(!surface.is_null(), "eglCreateWindowSurface: {:#x}", (egl.get_error)());
        (xl.XSync)(xd, 0);
        assert_eq!(APP_ERRORS.load(Ordering::SeqCst), 1, "the application's X error did not reach its handler");

        let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), ctx_attribs.as_ptr());
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent");
        let egl_size = || {
            let (mut w, mut h) = (0, 0);
            (egl.query_surface)(dpy, surface, EGL_WIDTH, &mut w);
            (egl.query_surface)(dpy, surface, EGL_HEIGHT, &mut h);
            (w, h)
        };
        // The pixel in the surface's top right corner after a clear to `rgb`.
        let corner = |(w, h): (i32, i32), rgb: [u8; 3]| {
            let f = |c: u8| f32::from(c) / 255.0;
            (egl.clear_color)(f(rgb[0]), f(rgb[1]), f(rgb[2]), 1.0);
            (egl.clear)(GL_COLOR_BUFFER_BIT);
            let mut px = [0u8; 4];
            (egl.read_pixels)(w - 1, h - 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.as_mut_ptr().cast());
            assert_eq!((egl.gl_error)(), 0, "GL error drawing at {w}x{h}");
            px
        };
        assert_eq!(egl_size(), x_size(win), "a new surface has its window's size");

        // glViewport after a resize, as applications do.
        let size = resize(100, 70);
        (egl.viewport)(0, 0, size.0, size.1);
        assert_eq!(corner(size, [0, 255, 0]), [0, 255, 0, 255], "glViewport did not follow the window to {size:?}");
        assert_eq!(egl_size(), size);

        // The frame after eglSwapBuffers.
        let size = resize(120, 90);
        assert_eq!((egl.swap_buffers)(dpy, surface), 1, "eglSwapBuffers");
        assert_eq!(corner(size, [0, 0, 255]), [0, 0, 255, 255], "eglSwapBuffers did not follow the window to {size:?}");

        // eglQuerySurface.
        let size = resize(30, 20);
        assert_eq!(egl_size(), size, "eglQuerySurface did not follow the window");

        // eglMakeCurrent.
        let size = resize(40, 30);
        let nothing = std::ptr::null_mut();
        assert_eq!((egl.make_current)(dpy, nothing, nothing, nothing), 1, "release");
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent again");
        assert_eq!(corner(size, [255, 0, 0]), [255, 0, 0, 255], "eglMakeCurrent did not follow the window to {size:?}");

        // The application's handle never changed, and the daemon holds one surface for it.
        assert_eq!((egl.current_surface)(EGL_DRAW), surface);
        assert_eq!(daemon_surfaces(&daemon.socket, "egl-window"), 1, "the daemon kept the resized-away surfaces");
        (xl.XCloseDisplay)(xd);
    }
    drop(lib);
}

//! Pixmap surfaces of the drop-in libEGL on X11 (EGL 1.4 §3.5.4, §3.8): every config renders to
//! pixmaps, as Mesa's X11 configs do; a surface made for a pixmap of depth 24 or 32 has the
//! pixmap's size; what is drawn into it is in the pixmap once the application has waited for
//! it (`glFinish`, `eglWaitClient`), read back with `XGetImage`, top row first: whatever
//! framebuffer is bound and however the pack state is set, and what is drawn into another
//! framebuffer stays out of it; a swap does nothing and succeeds; an id that is no drawable is
//! `EGL_BAD_NATIVE_PIXMAP` and the process lives on; another depth is `EGL_BAD_MATCH`; an
//! attribute other than the colour space is `EGL_BAD_ATTRIBUTE`; EGL 1.5's
//! `eglCreatePlatformPixmapSurface` makes one too. `eglCopyBuffers` puts a pbuffer's pixels
//! into a pixmap of its size; another size is `EGL_BAD_MATCH`, no drawable
//! `EGL_BAD_NATIVE_PIXMAP`.
//!
//! Held to EGL's words, not to Mesa: on Xvfb, Mesa's llvmpipe leaves the pixmap as it was after
//! `glFinish` and `eglWaitClient`, and crashes on an id that is no drawable.
//!
//! Its own test binary: it points the library at the daemon through the process environment.

mod support;

use std::ffi::c_void;

use support::{Daemon, TempDir, Xvfb};
use x11_dl::xlib;

type Ptr = *mut c_void;

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_PIXMAP_BIT: i32 = 0x0002;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const EGL_SUCCESS: i32 = 0x3000;
const EGL_BAD_ATTRIBUTE: i32 = 0x3004;
const EGL_BAD_MATCH: i32 = 0x3009;
const EGL_BAD_NATIVE_PIXMAP: i32 = 0x300A;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
const EGL_OPENGL_ES_API: u32 = 0x30A0;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_SCISSOR_TEST: u32 = 0x0C11;
const GL_PACK_ALIGNMENT: u32 = 0x0D05;
const GL_FRAMEBUFFER: u32 = 0x8D40;
const GL_COLOR_ATTACHMENT0: u32 = 0x8CE0;
const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

/// The entry points the test calls, resolved from the shared object.
struct Api {
    get_display: unsafe extern "C" fn(Ptr) -> Ptr,
    initialize: unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32,
    bind_api: unsafe extern "C" fn(u32) -> u32,
    get_configs: unsafe extern "C" fn(Ptr, *mut Ptr, i32, *mut i32) -> u32,
    choose_config: unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32,
    create_pixmap: unsafe extern "C" fn(Ptr, Ptr, u64, *const i32) -> Ptr,
    create_platform_pixmap: unsafe extern "C" fn(Ptr, Ptr, *mut c_void, *const isize) -> Ptr,
    create_pbuffer: unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr,
    copy_buffers: unsafe extern "C" fn(Ptr, Ptr, u64) -> u32,
    create_context: unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr,
    make_current: unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32,
    query_surface: unsafe extern "C" fn(Ptr, Ptr, i32, *mut i32) -> u32,
    swap_buffers: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    destroy_surface: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    wait_client: unsafe extern "C" fn() -> u32,
    get_error: unsafe extern "C" fn() -> i32,
    clear_color: unsafe extern "C" fn(f32, f32, f32, f32),
    clear: unsafe extern "C" fn(u32),
    enable: unsafe extern "C" fn(u32),
    disable: unsafe extern "C" fn(u32),
    scissor: unsafe extern "C" fn(i32, i32, i32, i32),
    pixel_store: unsafe extern "C" fn(u32, i32),
    finish: unsafe extern "C" fn(),
    gen_framebuffers: unsafe extern "C" fn(i32, *mut u32),
    bind_framebuffer: unsafe extern "C" fn(u32, u32),
    gen_textures: unsafe extern "C" fn(i32, *mut u32),
    bind_texture: unsafe extern "C" fn(u32, u32),
    tex_image: unsafe extern "C" fn(u32, i32, i32, i32, i32, i32, u32, u32, *const c_void),
    framebuffer_texture: unsafe extern "C" fn(u32, u32, u32, u32, i32),
    gl_error: unsafe extern "C" fn() -> u32,
}

fn load(lib: &libloading::Library) -> Api {
    use support::egl::sym;
    // SAFETY: each symbol is declared with its C prototype from egl.h / gl2.h (on x86-64 an
    // EGLNativePixmapType is an X11 Pixmap, a 64-bit integer).
    unsafe {
        Api {
            get_display: sym(lib, b"eglGetDisplay"),
            initialize: sym(lib, b"eglInitialize"),
            bind_api: sym(lib, b"eglBindAPI"),
            get_configs: sym(lib, b"eglGetConfigs"),
            choose_config: sym(lib, b"eglChooseConfig"),
            create_pixmap: sym(lib, b"eglCreatePixmapSurface"),
            create_platform_pixmap: sym(lib, b"eglCreatePlatformPixmapSurface"),
            create_pbuffer: sym(lib, b"eglCreatePbufferSurface"),
            copy_buffers: sym(lib, b"eglCopyBuffers"),
            create_context: sym(lib, b"eglCreateContext"),
            make_current: sym(lib, b"eglMakeCurrent"),
            query_surface: sym(lib, b"eglQuerySurface"),
            swap_buffers: sym(lib, b"eglSwapBuffers"),
            destroy_surface: sym(lib, b"eglDestroySurface"),
            wait_client: sym(lib, b"eglWaitClient"),
            get_error: sym(lib, b"eglGetError"),
            clear_color: sym(lib, b"glClearColor"),
            clear: sym(lib, b"glClear"),
            enable: sym(lib, b"glEnable"),
            disable: sym(lib, b"glDisable"),
            scissor: sym(lib, b"glScissor"),
            pixel_store: sym(lib, b"glPixelStorei"),
            finish: sym(lib, b"glFinish"),
            gen_framebuffers: sym(lib, b"glGenFramebuffers"),
            bind_framebuffer: sym(lib, b"glBindFramebuffer"),
            gen_textures: sym(lib, b"glGenTextures"),
            bind_texture: sym(lib, b"glBindTexture"),
            tex_image: sym(lib, b"glTexImage2D"),
            framebuffer_texture: sym(lib, b"glFramebufferTexture2D"),
            gl_error: sym(lib, b"glGetError"),
        }
    }
}

const W: u32 = 10;
const H: u32 = 7;

#[test]
fn pixmap_surfaces_fill_their_pixmap_when_waited_for() {
    let Some(x) = Xvfb::start_or_skip(64, 64) else { return };
    let daemon = Daemon::start("egl-pixmap", &["--output", "headless:p=64x64"]);
    // SAFETY: set before this test binary's only test starts any thread that reads the
    // environment; the library reads it at eglInitialize.
    unsafe { std::env::set_var("STRATA_SOCKET", &daemon.socket) };
    let tmp = TempDir::new("egl-pixmap");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen");
    let gl = load(&lib);
    let xl = xlib::Xlib::open().expect("libX11");
    let name = std::ffi::CString::new(x.display.as_str()).expect("display name");
    // SAFETY: Xlib and EGL/GL calls with the arguments their headers describe, on a display and
    // pixmaps this test owns; every out-pointer is valid.
    unsafe {
        let xd = (xl.XOpenDisplay)(name.as_ptr());
        assert!(!xd.is_null(), "XOpenDisplay");
        let root = (xl.XDefaultRootWindow)(xd);
        // The pixel at (x, y) of a pixmap, y from the top, as 0xRRGGBB.
        let pixel = |pm: u64, x: i32, y: i32| {
            let img = (xl.XGetImage)(xd, pm, 0, 0, W, H, !0, xlib::ZPixmap);
            assert!(!img.is_null(), "XGetImage");
            let get = (*img).funcs.get_pixel.expect("XGetPixel");
            let v = get(img, x, y) & 0xFF_FFFF;
            (*img).funcs.destroy_image.expect("XDestroyImage")(img);
            v
        };

        let dpy = (gl.get_display)(xd.cast());
        assert_eq!((gl.initialize)(dpy, std::ptr::null_mut(), std::ptr::null_mut()), 1, "eglInitialize");
        assert_eq!((gl.bind_api)(EGL_OPENGL_ES_API), 1);
        let (mut all, mut pixmap_capable) = (0, 0);
        (gl.get_configs)(dpy, std::ptr::null_mut(), 0, &mut all);
        let want = [EGL_SURFACE_TYPE, EGL_PIXMAP_BIT, EGL_NONE];
        (gl.choose_config)(dpy, want.as_ptr(), std::ptr::null_mut(), 0, &mut pixmap_capable);
        assert!(all > 0 && pixmap_capable == all, "{pixmap_capable} of {all} configs render to pixmaps");
        let mut config = std::ptr::null_mut();
        let mut n = 0;
        (gl.choose_config)(dpy, want.as_ptr(), &mut config, 1, &mut n);
        let none = [EGL_NONE];
        let ctx =
            (gl.create_context)(dpy, config, std::ptr::null_mut(), [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE].as_ptr());
        assert!(!ctx.is_null(), "eglCreateContext: {:#x}", (gl.get_error)());

        for depth in [24, 32] {
            let pm = (xl.XCreatePixmap)(xd, root, W, H, depth);
            (xl.XSync)(xd, 0);
            let s = (gl.create_pixmap)(dpy, config, pm, none.as_ptr());
            assert!(!s.is_null(), "depth {depth}: eglCreatePixmapSurface: {:#x}", (gl.get_error)());
            let (mut w, mut h) = (0, 0);
            (gl.query_surface)(dpy, s, EGL_WIDTH, &mut w);
            (gl.query_surface)(dpy, s, EGL_HEIGHT, &mut h);
            assert_eq!((w, h), (W as i32, H as i32), "depth {depth}: the surface has the pixmap's size");
            assert_eq!((gl.make_current)(dpy, s, s, ctx), 1, "eglMakeCurrent");

            // Blue, with the bottom left corner (GL's rows from the bottom) red: after glFinish
            // the pixmap shows it, red in its last rows.
            (gl.clear_color)(0.0, 0.0, 1.0, 1.0);
            (gl.clear)(GL_COLOR_BUFFER_BIT);
            (gl.enable)(GL_SCISSOR_TEST);
            (gl.scissor)(0, 0, 3, 2);
            (gl.clear_color)(1.0, 0.0, 0.0, 1.0);
            (gl.clear)(GL_COLOR_BUFFER_BIT);
            (gl.disable)(GL_SCISSOR_TEST);
            (gl.finish)();
            let (top, bottom) = (pixel(pm, 1, 1), pixel(pm, 1, H as i32 - 1));
            assert_eq!(
                (top, bottom),
                (0x0000FF, 0xFF0000),
                "depth {depth}: after glFinish, top {top:#08x} bottom {bottom:#08x}"
            );

            // eglWaitClient, with a pack alignment and a framebuffer of the application's bound:
            // what went to the surface before the binding is in the pixmap, and what went to the
            // framebuffer is not.
            (gl.clear_color)(0.2, 0.4, 0.6, 1.0);
            (gl.clear)(GL_COLOR_BUFFER_BIT);
            (gl.pixel_store)(GL_PACK_ALIGNMENT, 8);
            let (mut fb, mut tex) = (0, 0);
            (gl.gen_framebuffers)(1, &mut fb);
            (gl.bind_framebuffer)(GL_FRAMEBUFFER, fb);
            (gl.gen_textures)(1, &mut tex);
            (gl.bind_texture)(GL_TEXTURE_2D, tex);
            (gl.tex_image)(GL_TEXTURE_2D, 0, GL_RGBA as i32, 4, 4, 0, GL_RGBA, GL_UNSIGNED_BYTE, std::ptr::null());
            (gl.framebuffer_texture)(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
            (gl.clear_color)(0.0, 1.0, 0.0, 1.0);
            (gl.clear)(GL_COLOR_BUFFER_BIT);
            assert_eq!((gl.wait_client)(), 1, "eglWaitClient");
            let got = pixel(pm, 5, 3);
            assert_eq!(got, 0x336699, "depth {depth}: after eglWaitClient {got:#08x}");
            assert_eq!((gl.gl_error)(), 0, "depth {depth}: the copy left a GL error");
            (gl.bind_framebuffer)(GL_FRAMEBUFFER, 0);
            (gl.pixel_store)(GL_PACK_ALIGNMENT, 4);

            // A swap of a pixmap surface does nothing.
            assert_eq!((gl.swap_buffers)(dpy, s), 1, "eglSwapBuffers on a pixmap surface");
            assert_eq!((gl.get_error)(), EGL_SUCCESS);
            (gl.make_current)(dpy, std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut());
            assert_eq!((gl.destroy_surface)(dpy, s), 1, "eglDestroySurface");
            (xl.XFreePixmap)(xd, pm);
        }

        // No drawable: an EGL error, and the process lives on.
        let s = (gl.create_pixmap)(dpy, config, root + 0x0F00_0000, none.as_ptr());
        assert!(s.is_null());
        assert_eq!((gl.get_error)(), EGL_BAD_NATIVE_PIXMAP, "an id that is no drawable");
        // Another depth, and an attribute a pixmap surface does not have.
        let pm16 = (xl.XCreatePixmap)(xd, root, W, H, 16);
        let s = (gl.create_pixmap)(dpy, config, pm16, none.as_ptr());
        assert!(s.is_null());
        assert_eq!((gl.get_error)(), EGL_BAD_MATCH, "a pixmap of depth 16");
        let pm = (xl.XCreatePixmap)(xd, root, W, H, 24);
        let s = (gl.create_pixmap)(dpy, config, pm, [EGL_WIDTH, 4, EGL_NONE].as_ptr());
        assert!(s.is_null());
        assert_eq!((gl.get_error)(), EGL_BAD_ATTRIBUTE, "EGL_WIDTH on a pixmap surface");
        // EGL 1.5's form, given a pointer to the pixmap.
        let mut native = pm;
        let s =
            (gl.create_platform_pixmap)(dpy, config, (&mut native as *mut u64).cast(), [EGL_NONE as isize].as_ptr());
        assert!(!s.is_null(), "eglCreatePlatformPixmapSurface: {:#x}", (gl.get_error)());
        (gl.destroy_surface)(dpy, s);

        // eglCopyBuffers: a pbuffer's pixels into a pixmap of its size.
        let pb = (gl.create_pbuffer)(dpy, config, [EGL_WIDTH, W as i32, EGL_HEIGHT, H as i32, EGL_NONE].as_ptr());
        assert_eq!((gl.make_current)(dpy, pb, pb, ctx), 1, "eglMakeCurrent on a pbuffer");
        (gl.clear_color)(0.6, 0.2, 0.4, 1.0);
        (gl.clear)(GL_COLOR_BUFFER_BIT);
        assert_eq!((gl.copy_buffers)(dpy, pb, pm), 1, "eglCopyBuffers: {:#x}", (gl.get_error)());
        let got = pixel(pm, 2, 2);
        assert_eq!(got, 0x993366, "after eglCopyBuffers {got:#08x}");
        let small = (xl.XCreatePixmap)(xd, root, W - 1, H, 24);
        assert_eq!((gl.copy_buffers)(dpy, pb, small), 0);
        assert_eq!((gl.get_error)(), EGL_BAD_MATCH, "eglCopyBuffers into a pixmap of another size");
        assert_eq!((gl.copy_buffers)(dpy, pb, root + 0x0F00_0000), 0);
        assert_eq!((gl.get_error)(), EGL_BAD_NATIVE_PIXMAP, "eglCopyBuffers into no drawable");
        (xl.XSync)(xd, 0);
        (xl.XCloseDisplay)(xd);
    }
    drop(lib);
}

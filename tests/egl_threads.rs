//! The drop-in libEGL/libGLESv2 keep one current context per thread, as EGL requires: two
//! threads, each with its own context and pbuffer, draw and read back at the same time through
//! one daemon connection, and each sees only its own context's results; a thread that made
//! nothing current has no current context, and its GL calls do nothing. And a sync destroyed
//! by one thread while another waits on it ends the wait as if it had been signalled, as
//! `EGL_KHR_fence_sync` and `EGL_KHR_reusable_sync` say (compared with the extensions' words,
//! not with Mesa, whose wait reads the sync after another thread freed it); a fence waited on
//! forever when the daemon is killed before its work is done is signalled, and the wait
//! returns.
//!
//! Its own test binary: it points the library at the daemon through the process environment.

mod support;

use std::ffi::c_void;
use std::sync::{Arc, Barrier};

use support::egl::{load, Ptr};
use support::{Daemon, TempDir};

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_PBUFFER_BIT: i32 = 0x0001;
const EGL_RENDERABLE_TYPE: i32 = 0x3040;
const EGL_OPENGL_ES2_BIT: i32 = 0x0004;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
const EGL_OPENGL_ES_API: u32 = 0x30A0;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

#[test]
fn each_thread_has_its_own_current_context() {
    let daemon = Daemon::start("egl-threads", &["--output", "t=64x64"]);
    // SAFETY: set before this test binary's only test starts any thread that reads the
    // environment; the library reads it at eglInitialize.
    unsafe {
        std::env::set_var("STRATA_SOCKET", &daemon.socket);
        std::env::remove_var("DISPLAY");
    }
    let tmp = TempDir::new("egl-threads");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    // SAFETY: EGL calls with the arguments egl.h describes; every out-pointer is valid.
    let (dpy, config) = unsafe {
        let dpy = (egl.get_display)(std::ptr::null_mut());
        assert!(!dpy.is_null(), "eglGetDisplay");
        let (mut major, mut minor) = (0, 0);
        assert_eq!((egl.initialize)(dpy, &mut major, &mut minor), 1, "eglInitialize");
        assert_eq!((egl.bind_api)(EGL_OPENGL_ES_API), 1, "eglBindAPI");
        let attribs = [EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, attribs.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");
        assert_eq!(n, 1, "no config");
        (dpy as usize, config as usize)
    };
    let barrier = Arc::new(Barrier::new(2));
    let threads: Vec<_> = (0..2u8)
        .map(|t| {
            let barrier = barrier.clone();
            std::thread::spawn(move || {
                let (dpy, config) = (dpy as Ptr, config as Ptr);
                let mut wrong = Vec::new();
                // SAFETY: as above; the read-back buffer holds the 4 bytes one pixel needs.
                unsafe {
                    let size = [EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE];
                    let surface = (egl.create_pbuffer)(dpy, config, size.as_ptr());
                    let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
                    let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), ctx_attribs.as_ptr());
                    let ready =
                        !surface.is_null() && !ctx.is_null() && (egl.make_current)(dpy, surface, surface, ctx) == 1;
                    if !ready {
                        wrong.push(format!("thread {t}: no pbuffer, context or current context"));
                    }
                    for round in 0..20u8 {
                        // Both threads are current at once; their calls interleave.
                        barrier.wait();
                        if !ready {
                            barrier.wait();
                            continue;
                        }
                        let v = [t * 100 + round, 255 - round, t * 200];
                        let f = |c: u8| f32::from(c) / 255.0;
                        (egl.clear_color)(f(v[0]), f(v[1]), f(v[2]), 1.0);
                        (egl.clear)(GL_COLOR_BUFFER_BIT);
                        barrier.wait();
                        (egl.finish)();
                        let mut px = [0u8; 4];
                        (egl.read_pixels)(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.as_mut_ptr().cast());
                        // Recorded, not asserted here: a panic would leave the other thread
                        // waiting at the barrier.
                        if px != [v[0], v[1], v[2], 255] {
                            wrong.push(format!("thread {t}, round {round}: read {px:?}, drew {v:?}"));
                        }
                        if (egl.current_context)() != ctx {
                            wrong.push(format!("thread {t}, round {round}: eglGetCurrentContext is not its context"));
                        }
                    }
                }
                wrong
            })
        })
        .collect();
    let wrong: Vec<String> = threads.into_iter().flat_map(|t| t.join().expect("thread")).collect();
    assert!(wrong.is_empty(), "{} mismatches:\n{}", wrong.len(), wrong.join("\n"));
    // SAFETY: as above.
    unsafe {
        assert!((egl.current_context)().is_null(), "the main thread made nothing current");
        // No current context: a GL call is a no-op, not a crash.
        (egl.clear)(GL_COLOR_BUFFER_BIT);
    }
    destroyed_while_waited_on(&lib, &egl, dpy as Ptr, config as Ptr);
    waited_on_when_the_daemon_dies(&lib, &egl, dpy as Ptr, config as Ptr, daemon);
    drop(lib);
}

const EGL_SYNC_FENCE_KHR: u32 = 0x30F9;
const EGL_SYNC_REUSABLE_KHR: u32 = 0x30FA;
const EGL_CONDITION_SATISFIED_KHR: i32 = 0x30F6;
const EGL_TIMEOUT_EXPIRED_KHR: i32 = 0x30F5;

/// A reusable sync and a fence, each destroyed by a second thread 50 ms into a 10 s wait on
/// it: the reusable sync's wait returns at once, as if signalled; the fence's wait goes on to
/// the fence's work, which is done well before the timeout.
fn destroyed_while_waited_on(lib: &libloading::Library, egl: &support::egl::Egl, dpy: Ptr, config: Ptr) {
    type Create = unsafe extern "C" fn(Ptr, u32, *const i32) -> Ptr;
    type Destroy = unsafe extern "C" fn(Ptr, Ptr) -> u32;
    type Wait = unsafe extern "C" fn(Ptr, Ptr, i32, u64) -> i32;
    // SAFETY: the extensions' prototypes; a pbuffer context is made current on this thread.
    unsafe {
        let create: Create = support::egl::sym(lib, b"eglCreateSyncKHR\0");
        let destroy: Destroy = support::egl::sym(lib, b"eglDestroySyncKHR\0");
        let wait: Wait = support::egl::sym(lib, b"eglClientWaitSyncKHR\0");
        let size = [EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE];
        let surface = (egl.create_pbuffer)(dpy, config, size.as_ptr());
        let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), ctx_attribs.as_ptr());
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent");
        for (what, ty) in [("reusable sync", EGL_SYNC_REUSABLE_KHR), ("fence", EGL_SYNC_FENCE_KHR)] {
            (egl.clear)(GL_COLOR_BUFFER_BIT);
            let sync = create(dpy, ty, std::ptr::null());
            assert!(!sync.is_null(), "eglCreateSyncKHR ({what})");
            let (d, s) = (dpy as usize, sync as usize);
            let other = std::thread::spawn(move || {
                std::thread::sleep(std::time::Duration::from_millis(50));
                // The display and sync of this test (inside the unsafe block above).
                destroy(d as Ptr, s as Ptr)
            });
            let start = std::time::Instant::now();
            let answer = wait(dpy, sync, 0, 10_000_000_000);
            let took = start.elapsed();
            assert_eq!(other.join().expect("destroying thread"), 1, "eglDestroySyncKHR ({what})");
            assert_eq!(
                answer, EGL_CONDITION_SATISFIED_KHR,
                "{what} destroyed while waited on: the wait answered {answer:#x} ({EGL_TIMEOUT_EXPIRED_KHR:#x} is a timeout)"
            );
            assert!(took < std::time::Duration::from_secs(5), "{what}: the wait took {took:?}");
        }
        (egl.make_current)(dpy, std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut());
        (egl.destroy_context)(dpy, ctx);
        (egl.destroy_surface)(dpy, surface);
    }
}

/// A fence after slow work, the daemon killed before that work is done, and a wait with no
/// timeout: the library finds the daemon gone (its socket closed) and the wait returns, the
/// fence signalled, within seconds (a watchdog fails the test if it does not).
fn waited_on_when_the_daemon_dies(
    lib: &libloading::Library,
    egl: &support::egl::Egl,
    dpy: Ptr,
    config: Ptr,
    daemon: Daemon,
) {
    use support::egl::sym;
    type Create = unsafe extern "C" fn(Ptr, u32, *const i32) -> Ptr;
    type Wait = unsafe extern "C" fn(Ptr, Ptr, i32, u64) -> i32;
    const SLOW_FS: &[u8] = b"precision highp float; void main() { float x = gl_FragCoord.x * 0.001;
        for (int i = 0; i < 400; i++) { x = fract(sin(x * 12.9898 + float(i)) * 43758.5453); }
        gl_FragColor = vec4(x, 0.0, 0.0, 1.0); }\0";
    const VS: &[u8] = b"attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }\0";
    // SAFETY: EGL's and GL's prototypes; a pbuffer context is made current on this thread, and
    // every pointer passed lives across the call.
    unsafe {
        let create: Create = sym(lib, b"eglCreateSyncKHR");
        let wait: Wait = sym(lib, b"eglClientWaitSyncKHR");
        let create_shader: unsafe extern "C" fn(u32) -> u32 = sym(lib, b"glCreateShader");
        let shader_source: unsafe extern "C" fn(u32, i32, *const *const u8, *const i32) = sym(lib, b"glShaderSource");
        let compile: unsafe extern "C" fn(u32) = sym(lib, b"glCompileShader");
        let create_program: unsafe extern "C" fn() -> u32 = sym(lib, b"glCreateProgram");
        let attach: unsafe extern "C" fn(u32, u32) = sym(lib, b"glAttachShader");
        let link: unsafe extern "C" fn(u32) = sym(lib, b"glLinkProgram");
        let use_program: unsafe extern "C" fn(u32) = sym(lib, b"glUseProgram");
        let attrib: unsafe extern "C" fn(u32, i32, u32, u8, i32, *const c_void) = sym(lib, b"glVertexAttribPointer");
        let enable_attrib: unsafe extern "C" fn(u32) = sym(lib, b"glEnableVertexAttribArray");
        let draw: unsafe extern "C" fn(u32, i32, i32) = sym(lib, b"glDrawArrays");
        let viewport: unsafe extern "C" fn(i32, i32, i32, i32) = sym(lib, b"glViewport");
        let size = [EGL_WIDTH, 512, EGL_HEIGHT, 512, EGL_NONE];
        let surface = (egl.create_pbuffer)(dpy, config, size.as_ptr());
        let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), ctx_attribs.as_ptr());
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent");
        let program = create_program();
        for (ty, src) in [(0x8B31, VS), (0x8B30, SLOW_FS)] {
            let sh = create_shader(ty);
            shader_source(sh, 1, &src.as_ptr(), std::ptr::null());
            compile(sh);
            attach(program, sh);
        }
        link(program);
        use_program(program);
        let quad: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        attrib(0, 2, 0x1406, 0, 0, quad.as_ptr().cast());
        enable_attrib(0);
        viewport(0, 0, 512, 512);
        (egl.finish)();
        for _ in 0..8 {
            draw(0x0005, 0, 4);
        }
        let fence = create(dpy, EGL_SYNC_FENCE_KHR, std::ptr::null());
        assert!(!fence.is_null(), "eglCreateSyncKHR");
        let _ = daemon.kill();
        let (d, f) = (dpy as usize, fence as usize);
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            // The display and fence of this test (inside the unsafe block above).
            let _ = tx.send(wait(d as Ptr, f as Ptr, 0, u64::MAX));
        });
        let answer = rx.recv_timeout(std::time::Duration::from_secs(20));
        assert_eq!(
            answer,
            Ok(EGL_CONDITION_SATISFIED_KHR),
            "a fence waited on forever after the daemon died (Err: the wait never returned)"
        );
    }
}

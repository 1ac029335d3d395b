//! The drop-in libEGL/libGLESv2 outlive the daemon: when `stratad` goes away (killed outright,
//! or stopped cleanly), EGL calls report `EGL_CONTEXT_LOST` and GL calls record
//! `GL_CONTEXT_LOST`; once a new daemon listens on the same socket, `eglInitialize` (after
//! `eglTerminate`, or on the lost display as it is) connects again and the process renders.
//! The lost connection's context and surface handles stay invalid; another thread that had a
//! lost context current keeps running, sees `GL_CONTEXT_LOST`, and renders with new objects.
//!
//! Its own test binary: it points the library at the daemon through the process environment,
//! and the library keeps one connection per process.

mod support;

use std::path::Path;
use std::sync::{Arc, Barrier};

use support::egl::{load, Egl, Ptr};
use support::{Daemon, TempDir};

const EGL_FALSE: u32 = 0;
const EGL_TRUE: u32 = 1;
const EGL_SUCCESS: i32 = 0x3000;
const EGL_NOT_INITIALIZED: i32 = 0x3001;
const EGL_BAD_CONTEXT: i32 = 0x3006;
const EGL_CONTEXT_LOST: i32 = 0x300E;
const EGL_BAD_SURFACE: i32 = 0x300D;
const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_PBUFFER_BIT: i32 = 0x0001;
const EGL_RENDERABLE_TYPE: i32 = 0x3040;
const EGL_OPENGL_ES2_BIT: i32 = 0x0004;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
const EGL_CONFIG_ID: i32 = 0x3028;
const EGL_OPENGL_ES_API: u32 = 0x30A0;
const GL_NO_ERROR: u32 = 0;
const GL_CONTEXT_LOST: u32 = 0x0507;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

/// A pbuffer and a context current on the calling thread.
#[derive(Clone, Copy, Debug)]
struct Target {
    surface: usize,
    context: usize,
}

/// What an EGL call returned and the EGL error it left.
fn outcome(egl: &Egl, r: u32) -> (u32, i32) {
    // SAFETY: eglGetError takes no arguments.
    (r, unsafe { (egl.get_error)() })
}

impl Egl {
    /// eglInitialize on `dpy`: (result, EGL error).
    fn init(&self, dpy: Ptr) -> (u32, i32) {
        let (mut major, mut minor) = (0, 0);
        // SAFETY: valid out-pointers.
        outcome(self, unsafe { (self.initialize)(dpy, &mut major, &mut minor) })
    }

    /// A pbuffer-capable ES2 config.
    fn config(&self, dpy: Ptr) -> Ptr {
        let attribs = [EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        // SAFETY: an EGL_NONE-terminated list and valid out-pointers.
        let ok = unsafe { (self.choose_config)(dpy, attribs.as_ptr(), &mut config, 1, &mut n) };
        assert_eq!((ok, n), (EGL_TRUE, 1), "eglChooseConfig: EGL error {:#x}", unsafe { (self.get_error)() });
        config
    }

    /// Creates a `size`x`size` pbuffer and a context, and makes them current on this thread.
    fn target(&self, dpy: Ptr, size: i32) -> Target {
        let config = self.config(dpy);
        // SAFETY: EGL calls with EGL_NONE-terminated attribute lists.
        unsafe {
            assert_eq!((self.bind_api)(EGL_OPENGL_ES_API), EGL_TRUE, "eglBindAPI");
            let attribs = [EGL_WIDTH, size, EGL_HEIGHT, size, EGL_NONE];
            let surface = (self.create_pbuffer)(dpy, config, attribs.as_ptr());
            assert!(!surface.is_null(), "eglCreatePbufferSurface: EGL error {:#x}", (self.get_error)());
            let attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
            let context = (self.create_context)(dpy, config, std::ptr::null_mut(), attribs.as_ptr());
            assert!(!context.is_null(), "eglCreateContext: EGL error {:#x}", (self.get_error)());
            let made = outcome(self, (self.make_current)(dpy, surface, surface, context));
            assert_eq!(made, (EGL_TRUE, EGL_SUCCESS), "eglMakeCurrent");
            Target { surface: surface as usize, context: context as usize }
        }
    }

    /// A context that is never made current.
    fn spare_context(&self, dpy: Ptr) -> usize {
        let attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        // SAFETY: an EGL_NONE-terminated attribute list.
        let c = unsafe { (self.create_context)(dpy, self.config(dpy), std::ptr::null_mut(), attribs.as_ptr()) };
        assert!(!c.is_null(), "eglCreateContext: EGL error {:#x}", unsafe { (self.get_error)() });
        c as usize
    }

    /// Clears the current surface to `rgb` and reads back its corner pixel.
    fn draw_and_read(&self, rgb: [u8; 3]) -> [u8; 4] {
        let f = |c: u8| f32::from(c) / 255.0;
        let mut px = [0xABu8; 4];
        // SAFETY: GL calls on the current context; the buffer holds one RGBA8 pixel.
        unsafe {
            (self.clear_color)(f(rgb[0]), f(rgb[1]), f(rgb[2]), 1.0);
            (self.clear)(GL_COLOR_BUFFER_BIT);
            (self.finish)();
            (self.read_pixels)(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px.as_mut_ptr().cast());
        }
        px
    }

    /// Checks that every EGL call naming a handle of the lost connection fails as invalid,
    /// with `fresh` (objects of the new connection) as the other arguments.
    /// `spare` is a lost context that was current to no thread.
    fn assert_stale(&self, dpy: Ptr, old: Target, spare: usize, fresh: Target, who: &str) {
        let (os, oc) = (old.surface as Ptr, old.context as Ptr);
        let (ns, nc) = (fresh.surface as Ptr, fresh.context as Ptr);
        assert_ne!(old.surface, fresh.surface, "{who}: a new surface reuses a lost handle");
        assert_ne!(old.context, fresh.context, "{who}: a new context reuses a lost handle");
        assert_ne!(spare, fresh.context, "{who}: a new context reuses a lost handle");
        let spare = spare as Ptr;
        let mut v = 0;
        // SAFETY: EGL calls with handles the application holds; `v` is a valid out-pointer.
        let checks = unsafe {
            [
                ("eglMakeCurrent(old, old, old)", outcome(self, (self.make_current)(dpy, os, os, oc)), EGL_BAD_CONTEXT),
                ("eglMakeCurrent(new, new, old)", outcome(self, (self.make_current)(dpy, ns, ns, oc)), EGL_BAD_CONTEXT),
                ("eglMakeCurrent(old, old, new)", outcome(self, (self.make_current)(dpy, os, os, nc)), EGL_BAD_SURFACE),
                ("eglSwapBuffers(old)", outcome(self, (self.swap_buffers)(dpy, os)), EGL_BAD_SURFACE),
                (
                    "eglQuerySurface(old)",
                    outcome(self, (self.query_surface)(dpy, os, EGL_WIDTH, &mut v)),
                    EGL_BAD_SURFACE,
                ),
                (
                    "eglQueryContext(old)",
                    outcome(self, (self.query_context)(dpy, oc, EGL_CONFIG_ID, &mut v)),
                    EGL_BAD_CONTEXT,
                ),
                ("eglDestroySurface(old)", outcome(self, (self.destroy_surface)(dpy, os)), EGL_BAD_SURFACE),
                ("eglDestroyContext(old)", outcome(self, (self.destroy_context)(dpy, oc)), EGL_BAD_CONTEXT),
                (
                    "eglMakeCurrent(new, new, spare)",
                    outcome(self, (self.make_current)(dpy, ns, ns, spare)),
                    EGL_BAD_CONTEXT,
                ),
                ("eglDestroyContext(spare)", outcome(self, (self.destroy_context)(dpy, spare)), EGL_BAD_CONTEXT),
            ]
        };
        for (what, got, want) in checks {
            assert_eq!(got, (EGL_FALSE, want), "{who}: {what} after reconnecting");
        }
    }
}

/// How the daemon goes away.
#[derive(Clone, Copy, Debug)]
enum Death {
    /// SIGKILL: no clean-up; the socket file stays behind.
    Kill,
    /// SIGTERM: the daemon closes every session and removes its socket.
    Term,
}

/// How the application connects again.
#[derive(Clone, Copy, Debug)]
enum Again {
    /// `eglInitialize` on the lost display as it is.
    Initialize,
    /// `eglTerminate`, then `eglInitialize`.
    TerminateInitialize,
}

fn start_daemon(socket: &Path, round: usize) -> Daemon {
    Daemon::start_at(&format!("restart-{round}"), socket, &["--output", "t=64x64"])
}

/// What the second thread found, as failures (not asserted there: a panic would leave the main
/// thread waiting at the barrier).
type Findings = Vec<String>;

/// The second thread: a context current before the daemon goes away, checked after the main
/// thread reconnected, then released and replaced by a new one.
fn other_thread(egl: Egl, dpy: usize, rgb: [u8; 3], barrier: Arc<Barrier>) -> Findings {
    let dpy = dpy as Ptr;
    let mut wrong = Findings::new();
    let old = egl.target(dpy, 8);
    let px = egl.draw_and_read(rgb);
    if px != [rgb[0], rgb[1], rgb[2], 255] {
        wrong.push(format!("other thread, first daemon: read {px:?}, drew {rgb:?}"));
    }
    // The main thread kills the daemon and connects again.
    barrier.wait();
    barrier.wait();
    // SAFETY: EGL and GL calls with handles this thread holds.
    unsafe {
        if (egl.current_context)() as usize != old.context {
            wrong.push("other thread: its lost context is no longer its current one".into());
        }
        // GL calls on a lost context do nothing: no crash, no read-back, GL_CONTEXT_LOST.
        let px = egl.draw_and_read([1, 2, 3]);
        if px != [0xAB; 4] {
            wrong.push(format!("other thread: glReadPixels on a lost context wrote {px:?}"));
        }
        let e = (egl.gl_get_error)();
        if e != GL_CONTEXT_LOST {
            wrong.push(format!("other thread: glGetError on a lost context is {e:#x}, not GL_CONTEXT_LOST"));
        }
        let swapped = outcome(&egl, (egl.swap_buffers)(dpy, old.surface as Ptr));
        if swapped != (EGL_FALSE, EGL_BAD_SURFACE) {
            wrong.push(format!("other thread: eglSwapBuffers(lost surface) gave {swapped:?}"));
        }
        let fresh = egl.target(dpy, 8);
        let px = egl.draw_and_read([rgb[2], rgb[0], rgb[1]]);
        if px != [rgb[2], rgb[0], rgb[1], 255] {
            wrong.push(format!("other thread, new daemon: read {px:?}"));
        }
        let released =
            outcome(&egl, (egl.make_current)(dpy, std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut()));
        if released != (EGL_TRUE, EGL_SUCCESS) {
            wrong.push(format!("other thread: releasing gave {released:?}"));
        }
        for (what, r) in [
            ("eglDestroySurface", (egl.destroy_surface)(dpy, fresh.surface as Ptr)),
            ("eglDestroyContext", (egl.destroy_context)(dpy, fresh.context as Ptr)),
        ] {
            if r != EGL_TRUE {
                wrong.push(format!("other thread: {what} of its new object failed"));
            }
        }
    }
    wrong
}

/// Renders, loses the daemon, connects to a new one, renders again: for each way the daemon can
/// go and each way the application can connect again, one after another in one process.
#[test]
fn rendering_resumes_after_the_daemon_restarts() {
    let sockets = TempDir::new("restart");
    let socket = sockets.0.join("strata.sock");
    // SAFETY: set before this test binary's only test starts any thread that reads the
    // environment; the library reads it at each eglInitialize.
    unsafe {
        std::env::set_var("STRATA_SOCKET", &socket);
        std::env::remove_var("DISPLAY");
    }
    let tmp = TempDir::new("restart-shim");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    // SAFETY: eglGetDisplay(EGL_DEFAULT_DISPLAY).
    let dpy = unsafe { (egl.get_display)(std::ptr::null_mut()) };
    assert!(!dpy.is_null(), "eglGetDisplay");
    let mut daemon = start_daemon(&socket, 0);
    assert_eq!(egl.init(dpy), (EGL_TRUE, EGL_SUCCESS), "first eglInitialize");

    let rounds = [
        (Death::Kill, Again::Initialize),
        (Death::Term, Again::TerminateInitialize),
        (Death::Kill, Again::TerminateInitialize),
        (Death::Term, Again::Initialize),
    ];
    for (round, (death, again)) in rounds.into_iter().enumerate() {
        let who = format!("round {round} ({death:?}, then {again:?})");
        let r = round as u8;
        let (before, after) = ([200, 10 + r, 30], [20 + r, 150, 240]);
        let old = egl.target(dpy, 16);
        let spare = egl.spare_context(dpy);
        assert_eq!(egl.draw_and_read(before), [before[0], before[1], before[2], 255], "{who}: first daemon");
        let barrier = Arc::new(Barrier::new(2));
        let other = {
            let barrier = barrier.clone();
            let dpy = dpy as usize;
            std::thread::spawn(move || other_thread(egl, dpy, [40 + r, 90, 160], barrier))
        };
        barrier.wait();

        let status = match death {
            Death::Kill => daemon.kill(),
            Death::Term => daemon.stop(),
        };
        assert!(matches!(death, Death::Kill) || status.success(), "{who}: stratad stopped with {status}");
        // SAFETY: EGL and GL calls with handles this thread holds.
        unsafe {
            // Odd rounds find the loss with glGetError itself, which must report it at once.
            let gl_first = round % 2 == 1;
            if gl_first {
                assert_eq!((egl.gl_get_error)(), GL_CONTEXT_LOST, "{who}: glGetError finding the loss");
            }
            let swapped = outcome(&egl, (egl.swap_buffers)(dpy, old.surface as Ptr));
            assert_eq!(swapped, (EGL_FALSE, EGL_CONTEXT_LOST), "{who}: eglSwapBuffers after the daemon went away");
            let (os, oc) = (old.surface as Ptr, old.context as Ptr);
            let made = outcome(&egl, (egl.make_current)(dpy, os, os, oc));
            assert_eq!(made, (EGL_FALSE, EGL_CONTEXT_LOST), "{who}: eglMakeCurrent after the daemon went away");
            if !gl_first {
                assert_eq!((egl.gl_get_error)(), GL_CONTEXT_LOST, "{who}: glGetError after the daemon went away");
            }
            assert_eq!((egl.gl_get_error)(), GL_NO_ERROR, "{who}: GL_CONTEXT_LOST is reported once per call");
            (egl.clear)(GL_COLOR_BUFFER_BIT);
            assert_eq!((egl.gl_get_error)(), GL_CONTEXT_LOST, "{who}: a GL call on a lost context records it");
        }
        // No daemon listens yet: connecting fails and leaves the process lost.
        if let Again::TerminateInitialize = again {
            // SAFETY: eglTerminate on the application's display.
            assert_eq!(outcome(&egl, unsafe { (egl.terminate)(dpy) }), (EGL_TRUE, EGL_SUCCESS), "{who}: eglTerminate");
        }
        assert_eq!(egl.init(dpy), (EGL_FALSE, EGL_NOT_INITIALIZED), "{who}: eglInitialize with no daemon");

        daemon = start_daemon(&socket, round + 1);
        assert_eq!(egl.init(dpy), (EGL_TRUE, EGL_SUCCESS), "{who}: eglInitialize with the new daemon");
        let fresh = egl.target(dpy, 12);
        assert_eq!(egl.draw_and_read(after), [after[0], after[1], after[2], 255], "{who}: new daemon");
        // Meanwhile the other thread still has its lost context current.
        barrier.wait();
        let wrong = other.join().expect("the other thread panicked");
        assert!(wrong.is_empty(), "{who}:\n{}", wrong.join("\n"));

        egl.assert_stale(dpy, old, spare, fresh, &who);
        // The failed calls changed nothing: the new context is still current and draws.
        // SAFETY: eglGetCurrentContext takes no arguments.
        assert_eq!(unsafe { (egl.current_context)() } as usize, fresh.context, "{who}: current context");
        assert_eq!(egl.draw_and_read(before), [before[0], before[1], before[2], 255], "{who}: new daemon, again");
        daemon.assert_running();
    }
    drop(daemon);
    drop(lib);
}

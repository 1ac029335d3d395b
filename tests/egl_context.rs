//! `EGL_KHR_create_context` against Mesa's EGL held to ES 2.0: each attribute list below is given
//! to Mesa's `eglCreateContext` (surfaceless, an ES 2 pbuffer config) and to the daemon's, and both must
//! answer alike: a context, or the same EGL error; and each context made must behave alike
//! (`EGL_KHR_create_context_no_error`, `EGL_KHR_context_flush_control`). An ES 3 context is
//! refused by both (`EGL_BAD_MATCH`: held to ES 2.0, Mesa keeps the ES 3 bit on its configs).
//! Mesa also offers ES 1 contexts, which Strata has no config for; those lists are answered
//! `EGL_BAD_CONFIG` here, as EGL answers a version the config cannot render, and are checked
//! apart.

mod support;

use std::ffi::c_void;

use libloading::Library;
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::Slice;
use support::Daemon;

type Ptr = *const c_void;

const NONE: i32 = 0x3038;
const SUCCESS: i32 = 0x3000;
const BAD_CONFIG: i32 = 0x3005;
const VERSION: i32 = 0x3098;
const MINOR: i32 = 0x30FB;
const FLAGS: i32 = 0x30FC;
const PROFILE: i32 = 0x30FD;
const RESET: i32 = 0x31BD;
const NO_ERROR: i32 = 0x31B3;
const RELEASE: i32 = 0x2097;

/// Attribute lists both must answer alike, each ended by `EGL_NONE`.
fn lists() -> Vec<Vec<i32>> {
    vec![
        vec![VERSION, 2, NONE],
        vec![VERSION, 2, MINOR, 0, NONE],
        vec![VERSION, 2, MINOR, 1, NONE],
        vec![VERSION, 2, MINOR, -1, NONE],
        vec![VERSION, 0, NONE],
        vec![VERSION, 3, NONE],
        vec![VERSION, 4, NONE],
        // Flags: none, debug, debug then none, forward-compatible, robust access, undefined.
        vec![VERSION, 2, FLAGS, 0, NONE],
        vec![VERSION, 2, FLAGS, 1, NONE],
        vec![VERSION, 2, FLAGS, 1, FLAGS, 0, NONE],
        vec![VERSION, 2, FLAGS, 2, NONE],
        vec![VERSION, 2, FLAGS, 4, NONE],
        vec![VERSION, 2, FLAGS, 8, NONE],
        // Desktop OpenGL's profile mask, the reset strategies, an unknown attribute.
        vec![VERSION, 2, PROFILE, 1, NONE],
        vec![VERSION, 2, PROFILE, 0, NONE],
        vec![VERSION, 2, RESET, 0x31BE, NONE],
        vec![VERSION, 2, RESET, 0x31BF, NONE],
        vec![VERSION, 2, RESET, 5, NONE],
        vec![VERSION, 2, 0x1234, 0, NONE],
        // EGL_KHR_create_context_no_error.
        vec![VERSION, 2, NO_ERROR, 1, NONE],
        vec![VERSION, 2, NO_ERROR, 0, NONE],
        vec![VERSION, 2, NO_ERROR, 2, NONE],
        vec![VERSION, 2, NO_ERROR, 1, FLAGS, 1, NONE],
        vec![VERSION, 2, FLAGS, 1, NO_ERROR, 1, NONE],
        vec![VERSION, 2, NO_ERROR, 1, RESET, 0x31BF, NONE],
        // EGL_KHR_context_flush_control.
        vec![VERSION, 2, RELEASE, 0, NONE],
        vec![VERSION, 2, RELEASE, 0x2098, NONE],
        vec![VERSION, 2, RELEASE, 5, NONE],
    ]
}

/// What a context made from a list does: `GL_CONTEXT_RELEASE_BEHAVIOR_KHR`
/// (`GL_KHR_context_flush_control`), and the errors `glGetError` reports after a draw with an
/// unknown mode and after a query of an unknown name (none in a `GL_KHR_no_error` context).
type Behaviour = [i32; 3];

/// The GL calls that find a context's [`Behaviour`].
fn behaviour(
    get_integer: &mut dyn FnMut(u32) -> i32,
    draw: &mut dyn FnMut(),
    error: &mut dyn FnMut() -> i32,
) -> Behaviour {
    while error() != 0 {}
    let release = get_integer(0x82FB);
    draw();
    let after_draw = error();
    get_integer(0x1234);
    [release, after_draw, error()]
}

/// Mesa's answers: `EGL_SUCCESS` where it made a context, else its error; and the behaviour
/// of each context it made.
fn mesa_answers(lists: &[Vec<i32>]) -> Result<Vec<(i32, Option<Behaviour>)>, String> {
    // Held to ES 2.0 (before Mesa is first loaded in this process).
    std::env::set_var("MESA_GLES_VERSION_OVERRIDE", "2.0");
    let dir = support::mesa::lib_dir();
    // SAFETY: loading the system's EGL; calls below use its entry points' C prototypes.
    unsafe {
        let egl = Library::new(format!("{dir}/libEGL.so.1")).map_err(|e| format!("libEGL: {e}"))?;
        let sym = |name: &[u8]| -> Result<Ptr, String> {
            egl.get::<Ptr>(name).map(|s| *s).map_err(|e| format!("{}: {e}", String::from_utf8_lossy(name)))
        };
        let get_proc: unsafe extern "C" fn(*const u8) -> Ptr = std::mem::transmute(sym(b"eglGetProcAddress\0")?);
        let gpd = get_proc(c"eglGetPlatformDisplayEXT".as_ptr().cast());
        if gpd.is_null() {
            return Err("eglGetPlatformDisplayEXT unavailable".into());
        }
        let gpd: unsafe extern "C" fn(u32, Ptr, *const i32) -> Ptr = std::mem::transmute(gpd);
        let display = gpd(0x31DD, std::ptr::null(), std::ptr::null());
        let init: unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32 = std::mem::transmute(sym(b"eglInitialize\0")?);
        if display.is_null() || init(display, std::ptr::null_mut(), std::ptr::null_mut()) == 0 {
            return Err("no surfaceless display".into());
        }
        let bind: unsafe extern "C" fn(u32) -> u32 = std::mem::transmute(sym(b"eglBindAPI\0")?);
        bind(0x30A0);
        let choose: unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32 =
            std::mem::transmute(sym(b"eglChooseConfig\0")?);
        let attribs = [0x3033, 1, 0x3040, 4, 0x3024, 8, NONE];
        let (mut config, mut n): (Ptr, i32) = (std::ptr::null(), 0);
        if choose(display, attribs.as_ptr(), &mut config, 1, &mut n) == 0 || n < 1 {
            return Err("no ES 2 pbuffer config".into());
        }
        let create: unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr =
            std::mem::transmute(sym(b"eglCreateContext\0")?);
        let pbuffer: unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr =
            std::mem::transmute(sym(b"eglCreatePbufferSurface\0")?);
        let make_current: unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32 =
            std::mem::transmute(sym(b"eglMakeCurrent\0")?);
        let surface = pbuffer(display, config, [0x3057, 8, 0x3056, 8, NONE].as_ptr());
        let gles = Library::new(format!("{dir}/libGLESv2.so.2")).map_err(|e| format!("libGLESv2: {e}"))?;
        let gl = |name: &[u8]| -> Result<Ptr, String> {
            gles.get::<Ptr>(name).map(|s| *s).map_err(|e| format!("{}: {e}", String::from_utf8_lossy(name)))
        };
        let get_integerv: unsafe extern "C" fn(u32, *mut i32) = std::mem::transmute(gl(b"glGetIntegerv\0")?);
        let draw_arrays: unsafe extern "C" fn(u32, i32, i32) = std::mem::transmute(gl(b"glDrawArrays\0")?);
        let gl_error: unsafe extern "C" fn() -> u32 = std::mem::transmute(gl(b"glGetError\0")?);
        let destroy: unsafe extern "C" fn(Ptr, Ptr) -> u32 = std::mem::transmute(sym(b"eglDestroyContext\0")?);
        let error: unsafe extern "C" fn() -> i32 = std::mem::transmute(sym(b"eglGetError\0")?);
        let answers = lists
            .iter()
            .map(|l| {
                let ctx = create(display, config, std::ptr::null(), l.as_ptr());
                if ctx.is_null() {
                    return (error(), None);
                }
                make_current(display, surface, surface, ctx);
                let b = behaviour(
                    &mut |pname| {
                        let mut v = -7;
                        get_integerv(pname, &mut v);
                        v
                    },
                    &mut || draw_arrays(0x20, 0, 3),
                    &mut || gl_error() as i32,
                );
                make_current(display, std::ptr::null(), std::ptr::null(), std::ptr::null());
                destroy(display, ctx);
                (SUCCESS, Some(b))
            })
            .collect();
        let terminate: unsafe extern "C" fn(Ptr) -> u32 = std::mem::transmute(sym(b"eglTerminate\0")?);
        terminate(display);
        Ok(answers)
    }
}

/// The daemon's answers, through the protocol (the drop-in library passes the list on as is).
fn strata_answers(daemon: &Daemon, lists: &[Vec<i32>]) -> Vec<(i32, Option<Behaviour>)> {
    let opts = ConnectOptions { socket: daemon.socket.clone(), name: "egl-context".into(), ..Default::default() };
    let mut c = Connection::connect(&opts).expect("connect");
    let d = c.eglGetDisplay(0).expect("io");
    c.eglInitialize(d).expect("io").expect("eglInitialize");
    let config = c.eglChooseConfig(d, Slice::new(&[0x3033, 1, 0x3040, 4, 0x3024, 8, NONE]), 1).expect("io");
    let config = *config.expect("eglChooseConfig").first().expect("a config");
    let surface = c.eglCreatePbufferSurface(d, config, Slice::new(&[0x3057, 8, 0x3056, 8, NONE])).expect("io");
    let surface = surface.expect("eglCreatePbufferSurface");
    let mut answers = Vec::new();
    for l in lists {
        let ctx = match c.eglCreateContext(d, config, 0, Slice::new(l)).expect("io") {
            Ok(ctx) => ctx,
            Err(e) => {
                answers.push((e, None));
                continue;
            }
        };
        c.eglMakeCurrent(d, surface, surface, ctx).expect("io").expect("eglMakeCurrent");
        let c = std::cell::RefCell::new(&mut c);
        let b = behaviour(
            &mut |pname| c.borrow_mut().glGetIntegerv(pname).expect("io").first().copied().unwrap_or(-7),
            &mut || c.borrow_mut().glDrawArrays(0x20, 0, 3).expect("io"),
            &mut || c.borrow_mut().glGetError().expect("io") as i32,
        );
        let c = c.into_inner();
        c.eglMakeCurrent(d, 0, 0, 0).expect("io").expect("release");
        c.eglDestroyContext(d, ctx).expect("io").expect("eglDestroyContext");
        answers.push((SUCCESS, Some(b)));
    }
    answers
}

#[test]
fn context_attributes_are_answered_as_mesa_answers_them() {
    let lists = lists();
    let mesa = match mesa_answers(&lists) {
        Ok(a) => a,
        Err(e) if support::oracles_required() => panic!("Mesa's EGL unavailable: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: Mesa's EGL unavailable ({e})");
            return;
        }
    };
    let daemon = Daemon::start("egl-context", &[]);
    let strata = strata_answers(&daemon, &lists);
    let differ: Vec<String> = lists
        .iter()
        .zip(mesa.iter().zip(&strata))
        .filter(|(_, (m, s))| m != s)
        .map(|(l, (m, s))| format!("{l:#x?}: Mesa {m:#x?}, Strata {s:#x?}"))
        .collect();
    assert!(differ.is_empty(), "eglCreateContext answers differ:\n{}", differ.join("\n"));
    let made = mesa.iter().filter(|a| a.0 == SUCCESS).count();
    assert!(made >= 5 && made < lists.len() - 5, "the lists must both make and refuse contexts ({made} made)");
    // ES 1 (no version given, or 1): Mesa makes them; Strata has no config for them.
    let other_versions = vec![vec![NONE], vec![VERSION, 1, NONE]];
    assert_eq!(strata_answers(&daemon, &other_versions), [(BAD_CONFIG, None); 2]);
    // The lists that ask for these behaviours must have been made on both sides.
    for want in [[0, 0x500, 0x500], [0x82FC, 0, 0]] {
        assert!(mesa.iter().any(|a| a.1 == Some(want)), "no context behaved as {want:#x?}");
    }
}

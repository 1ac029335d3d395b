//! `EGL_STRATA_surface_projection` at the boundary: the drop-in libEGL names the extension and
//! passes a window surface's declaration through to the daemon, `eglQuerySurface` reports it
//! (and the raw-depth defaults when nothing is declared), an invalid declaration fails with
//! `EGL_BAD_ATTRIBUTE` and a log line naming the problem, the configuration's `projection`
//! wins over a surface's declaration even for a client that states its own placement,
//! `ctl list` shows the projection in effect, and a bad `projection` in the configuration
//! stops the daemon naming the client and the problem.
//!
//! Its own test binary, with one test: it points the library at the daemon through the process
//! environment.

mod support;

use std::ffi::{c_char, CStr};
use std::process::Command;

use strata_client::setup::{egl_context_with, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::control::SurfaceRow;
use strata_protocol::handshake::Placement;
use strata_protocol::projection::*;
use strata_protocol::Slice;
use support::egl::{load, Ptr};
use support::{Daemon, TempDir};

const EGL_NONE: i32 = 0x3038;
const EGL_FALSE: i32 = 0;
const EGL_TRUE: i32 = 1;
const EGL_EXTENSIONS: i32 = 0x3055;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_WINDOW_BIT: i32 = 0x0004;
const EGL_RENDERABLE_TYPE: i32 = 0x3040;
const EGL_OPENGL_ES2_BIT: i32 = 0x0004;
const EGL_DEPTH_SIZE: i32 = 0x3025;
const EGL_WIDTH: i32 = 0x3057;
const EGL_HEIGHT: i32 = 0x3056;
const EGL_BAD_ATTRIBUTE: i32 = 0x3004;
const EGL_SUCCESS: i32 = 0x3000;

/// The four attributes `eglQuerySurface` answers for the extension, in order.
const QUERIED: [i32; 4] =
    [EGL_PROJECTION_STRATA, EGL_PROJECTION_NEAR_STRATA, EGL_PROJECTION_FAR_STRATA, EGL_PROJECTION_REVERSED_Z_STRATA];

fn bits(v: f32) -> i32 {
    v.to_bits() as i32
}

/// What `eglQuerySurface` should answer for `QUERIED` on a surface declaring `kind`.
fn answers(kind: i32, near: f32, far: f32, reversed: bool) -> [i32; 4] {
    [kind, bits(near), bits(far), if reversed { EGL_TRUE } else { EGL_FALSE }]
}

/// `stratad serve --config` with `config`: it must refuse to start; its stderr.
fn refused(dir: &TempDir, config: &str) -> String {
    let file = dir.0.join("bad.toml");
    std::fs::write(&file, config).expect("config");
    let out = Command::new(support::stratad())
        .args(["serve", "--output", "headless:main=64x64", "--socket"])
        .arg(dir.0.join("bad.sock"))
        .arg("--config")
        .arg(&file)
        .output()
        .expect("run stratad");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "stratad started with {config}");
    err
}

fn ctl(socket: &std::path::Path, json: bool) -> String {
    let mut cmd = Command::new(support::stratad());
    cmd.arg("ctl");
    if json {
        cmd.arg("--json");
    }
    let out = cmd.arg("--socket").arg(socket).arg("list").output().expect("ctl list");
    assert!(out.status.success(), "ctl list: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("utf-8")
}

#[test]
fn surfaces_declare_their_projection_and_the_configuration_wins() {
    let dir = TempDir::new("projection");
    // A bad projection in the configuration stops the daemon, naming the client and the
    // problem; an unknown kind names the valid ones. (Before the environment changes below.)
    let entry = |client: &str, p: &str| {
        format!("[[layout]]\nclient = \"{client}\"\nx = 0\ny = 0\nz = 0.5\nprojection = {p}\n\n")
    };
    let err = refused(&dir, &entry("cluster", "{ kind = \"perspective\", near = 5.0, far = 1.0 }"));
    assert!(err.contains("cluster") && err.contains("near 5 must be less than far 1"), "{err}");
    let err = refused(&dir, &entry("cluster", "{ kind = \"fisheye\", near = 1.0, far = 2.0 }"));
    assert!(err.contains("fisheye") && err.contains("perspective") && err.contains("orthographic"), "{err}");

    // "hu" is given a reversed perspective projection by the configuration.
    let config = dir.0.join("config.toml");
    std::fs::write(&config, entry("hu", "{ kind = \"perspective\", near = 0.5, far = 50.0, reversed = true }"))
        .expect("config");
    let daemon = Daemon::start("projection", &["--output", "t=64x64", "--config", config.to_str().expect("utf-8")]);
    let socket = &daemon.socket;

    // The drop-in library, as the application "app" (not in the configuration).
    // SAFETY: set before this test binary's only test starts any thread that reads the
    // environment; the library reads it at eglInitialize and eglCreateWindowSurface.
    unsafe {
        std::env::set_var("STRATA_SOCKET", socket);
        std::env::set_var("STRATA_NAME", "app");
        std::env::set_var("STRATA_WINDOW", "0,0,0.5,16x16");
        std::env::remove_var("DISPLAY");
    }
    let tmp = TempDir::new("projection-shim");
    // SAFETY: loading the shim runs no initialisers that need anything from the test.
    let lib = unsafe { libloading::Library::new(support::shim_dir(&tmp).join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    // SAFETY: the C prototypes of eglQueryString and eglCreateWindowSurface (a 64-bit X11
    // window on x86-64).
    let (query_string, create_window) = unsafe {
        let q: unsafe extern "C" fn(Ptr, i32) -> *const c_char = *lib.get(b"eglQueryString").expect("eglQueryString");
        let c: unsafe extern "C" fn(Ptr, Ptr, u64, *const i32) -> Ptr =
            *lib.get(b"eglCreateWindowSurface").expect("eglCreateWindowSurface");
        (q, c)
    };
    let declared = Projection { kind: ProjectionKind::Perspective, near: 0.1, far: f32::INFINITY, reversed: false };
    // SAFETY: EGL calls with the arguments egl.h describes; every out-pointer is valid and
    // every attribute list is EGL_NONE-terminated.
    unsafe {
        let dpy = (egl.get_display)(std::ptr::null_mut());
        let (mut major, mut minor) = (0, 0);
        assert_eq!((egl.initialize)(dpy, &mut major, &mut minor), 1, "eglInitialize");
        let ext = query_string(dpy, EGL_EXTENSIONS);
        assert!(!ext.is_null(), "eglQueryString: {:#x}", (egl.get_error)());
        let ext = CStr::from_ptr(ext).to_string_lossy().into_owned();
        assert!(ext.split(' ').any(|e| e == EXTENSION), "{ext}");
        let want =
            [EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT, EGL_DEPTH_SIZE, 16, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, want.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");
        let query = |s: Ptr| {
            QUERIED.map(|a| {
                let mut v = 0x7777;
                assert_eq!(
                    (egl.query_surface)(dpy, s, a, &mut v),
                    1,
                    "eglQuerySurface({a:#x}): {:#x}",
                    (egl.get_error)()
                );
                v
            })
        };
        // Declared: an infinite perspective, with an attribute the extension does not know
        // before it (passed through, ignored).
        let mut attribs = vec![0x7777, 1];
        attribs.extend(declared.to_egl_attribs());
        attribs.push(EGL_NONE);
        let s = create_window(dpy, config, 0, attribs.as_ptr());
        assert!(!s.is_null(), "eglCreateWindowSurface: {:#x}", (egl.get_error)());
        assert_eq!(query(s), answers(EGL_PROJECTION_PERSPECTIVE_STRATA, 0.1, f32::INFINITY, false));
        // Undeclared: EGL_NONE and the raw-depth planes.
        let plain = create_window(dpy, config, 0, [EGL_NONE].as_ptr());
        assert!(!plain.is_null(), "eglCreateWindowSurface: {:#x}", (egl.get_error)());
        assert_eq!(query(plain), answers(EGL_NONE, 0.0, 1.0, false));
        // Invalid: a perspective near plane at 0.
        let bad = [
            EGL_PROJECTION_STRATA,
            EGL_PROJECTION_PERSPECTIVE_STRATA,
            EGL_PROJECTION_NEAR_STRATA,
            bits(0.0),
            EGL_PROJECTION_FAR_STRATA,
            bits(10.0),
            EGL_NONE,
        ];
        assert!(create_window(dpy, config, 0, bad.as_ptr()).is_null(), "an invalid declaration was accepted");
        assert_eq!((egl.get_error)(), EGL_BAD_ATTRIBUTE);
        assert_eq!((egl.get_error)(), EGL_SUCCESS);
        daemon.wait_log("a perspective projection needs near > 0, not 0");
    }

    // "hu" declares an orthographic projection and states its own placement: the
    // configuration's projection still wins, and eglQuerySurface reports it.
    let mut hu = Connection::connect(&ConnectOptions {
        socket: socket.into(),
        name: "hu".into(),
        placement: Some(Placement { x: 32, y: 0, z: 0.25, width: 16, height: 16 }),
        ..Default::default()
    })
    .expect("connect");
    let ortho = Projection { kind: ProjectionKind::Orthographic, near: 0.0, far: 1.0, reversed: false };
    let kind = SurfaceKind::Window { rect: [32, 0, 16, 16], z: 0.25 };
    let cur = egl_context_with(&mut hu, 16, 0, kind, &ortho.to_egl_attribs()).expect("window");
    let got = QUERIED.map(|a| hu.eglQuerySurface(cur.display, cur.surface, a).expect("io").expect("eglQuerySurface"));
    assert_eq!(got, answers(EGL_PROJECTION_PERSPECTIVE_STRATA, 0.5, 50.0, true));
    // A pbuffer keeps its own declaration (the layout is for window surfaces); a bad one is
    // refused there too.
    let mut pb = vec![EGL_WIDTH, 8, EGL_HEIGHT, 8];
    pb.extend(ortho.to_egl_attribs());
    pb.push(EGL_NONE);
    let configs = hu.eglChooseConfig(cur.display, Slice::new(&[EGL_NONE]), 1).expect("io").expect("configs");
    let p = hu.eglCreatePbufferSurface(cur.display, configs[0], Slice::new(&pb)).expect("io").expect("pbuffer");
    let got = hu.eglQuerySurface(cur.display, p, EGL_PROJECTION_STRATA).expect("io");
    assert_eq!(got, Ok(EGL_PROJECTION_ORTHOGRAPHIC_STRATA));
    let bad = [EGL_WIDTH, 8, EGL_HEIGHT, 8, EGL_PROJECTION_STRATA, 0x1234, EGL_NONE];
    let refused = hu.eglCreatePbufferSurface(cur.display, configs[0], Slice::new(&bad)).expect("io");
    assert_eq!(refused, Err(EGL_BAD_ATTRIBUTE));

    // `ctl list --json` carries the projection in effect with each surface (an infinite far
    // plane included, which JSON writes as null); the table shows it compactly.
    let list: serde_json::Value = serde_json::from_str(&ctl(socket, true)).expect("ctl list JSON");
    let rows: Vec<SurfaceRow> = serde_json::from_value(list["surfaces"].clone()).expect("surface rows");
    let of = |client: &str| rows.iter().filter(|r| r.client == client).map(|r| r.projection).collect::<Vec<_>>();
    assert_eq!(of("app"), vec![Some(declared), None], "{rows:?}");
    let fixed = Projection { kind: ProjectionKind::Perspective, near: 0.5, far: 50.0, reversed: true };
    assert_eq!(of("hu"), vec![Some(fixed)], "{rows:?}");
    // A row from a daemon that predates the field reads as undeclared.
    let mut old = list["surfaces"][0].clone();
    assert!(old.as_object_mut().and_then(|o| o.remove("projection")).is_some(), "{old}");
    let old: SurfaceRow = serde_json::from_value(old).expect("a row without projection");
    assert_eq!(old.projection, None);
    let table = ctl(socket, false);
    let line = |client: &str| {
        table.lines().filter(|l| l.contains(&format!(" {client} ("))).map(str::to_string).collect::<Vec<_>>()
    };
    let app = line("app");
    assert_eq!(app.len(), 2, "{table}");
    assert!(app[0].ends_with("  persp 0.1..inf") && app[1].ends_with("  -"), "{table}");
    let hu = line("hu");
    assert!(hu.len() == 1 && hu[0].ends_with("  persp 0.5..50 rev"), "{table}");
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")));
}

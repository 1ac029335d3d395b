//! Stable surface IDs with real client processes: the layout's `id` (one, or a list in the
//! order a client creates its window surfaces) wins, then `STRATA_SURFACE_ID` in the client's
//! environment, then the application's own `EGL_SURFACE_ID_STRATA`; a surface without one
//! gets a runtime ID that none of those can be. `eglQuerySurface` and `ctl list` report the
//! ID, `ctl move` addresses it, a second live surface claiming an ID fails with
//! `EGL_BAD_MATCH` and a log line naming the holder, a malformed `STRATA_SURFACE_ID` fails with
//! `EGL_BAD_ATTRIBUTE`, and a client that restarts gets its ID back.
//!
//! Each client is this test binary run again as `client_process`, which loads the drop-in
//! libEGL, creates window surfaces, prints what it got and keeps them until its stdin closes.

mod support;

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use strata_protocol::control::SurfaceRow;
use strata_protocol::surface_id::EGL_SURFACE_ID_STRATA;
use support::egl::{load, Ptr};
use support::{Daemon, TempDir};

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_WINDOW_BIT: i32 = 0x0004;
const EGL_BAD_MATCH: i32 = 0x3009;
const EGL_BAD_ATTRIBUTE: i32 = 0x3004;

/// Set in a client process's environment: how many window surfaces to create.
const WINDOWS: &str = "SURFACE_IDS_WINDOWS";
/// Set in a client process's environment: the ID its application asks for itself.
const ASKS: &str = "SURFACE_IDS_ASKS";
/// Set in a client process's environment: draw one frame into its first surface (the bottom
/// half red, the top half green, in GL's coordinates) and swap it.
const DRAWS: &str = "SURFACE_IDS_DRAWS";
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_SCISSOR_TEST: u32 = 0x0C11;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;

/// A running client process and what each of its `eglCreateWindowSurface` calls got: the ID,
/// or the EGL error.
struct Client {
    child: Child,
    stdin: Option<ChildStdin>,
    /// The rest of its output, read to the end when it stops.
    out: BufReader<ChildStdout>,
    got: Vec<Result<i32, i32>>,
}

impl Client {
    /// Starts a client named `name` on `socket` creating `windows` window surfaces, with
    /// `STRATA_SURFACE_ID` set to `env` and its application asking for `asks`; with `draws`, it
    /// swaps one frame into its first surface.
    fn start(
        socket: &std::path::Path,
        shim: &std::path::Path,
        name: &str,
        windows: usize,
        env: Option<&str>,
        asks: Option<i32>,
        draws: bool,
    ) -> Client {
        let mut cmd = Command::new(std::env::current_exe().expect("test binary"));
        cmd.args(["--exact", "client_process", "--nocapture", "--test-threads", "1"])
            .env("STRATA_SOCKET", socket)
            .env("STRATA_NAME", name)
            .env("STRATA_WINDOW", "0,0,0.5,16x16")
            .env("SURFACE_IDS_SHIM", shim)
            .env(WINDOWS, windows.to_string())
            .env_remove("DISPLAY")
            .env_remove("STRATA_SURFACE_ID")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped());
        if let Some(v) = env {
            cmd.env("STRATA_SURFACE_ID", v);
        }
        if let Some(id) = asks {
            cmd.env(ASKS, id.to_string());
        }
        if draws {
            cmd.env(DRAWS, "1");
        }
        let mut child = cmd.spawn().expect("client process");
        let stdin = child.stdin.take();
        let mut out = BufReader::new(child.stdout.take().expect("stdout"));
        let mut got = Vec::new();
        let mut line = String::new();
        while {
            line.clear();
            out.read_line(&mut line).expect("client output") > 0
        } {
            let line = line.trim_end();
            // libtest writes its "test client_process ... " before the first line.
            if let Some((_, v)) = line.split_once("surface id ") {
                got.push(Ok(v.parse().expect("id")));
            } else if let Some((_, e)) = line.split_once("surface error ") {
                got.push(Err(i32::from_str_radix(e.trim_start_matches("0x"), 16).expect("error")));
            }
            if line.ends_with("ready") {
                break;
            }
        }
        assert_eq!(got.len(), windows, "{name}: the client stopped early");
        Client { child, stdin, out, got }
    }

    /// Closes its stdin and waits for it to leave.
    fn stop(mut self) {
        drop(self.stdin.take());
        let _ = std::io::copy(&mut self.out, &mut std::io::sink());
        let status = self.child.wait().expect("wait");
        assert!(status.success(), "client: {status}");
    }
}

/// Not a test of its own: the client process the test starts (does nothing when run as part of
/// the suite).
#[test]
fn client_process() {
    let Ok(windows) = std::env::var(WINDOWS) else { return };
    let windows: usize = windows.parse().expect("count");
    let shim = std::env::var("SURFACE_IDS_SHIM").expect("shim dir");
    // SAFETY: loading the shim runs no initialisers that need anything from this process.
    let lib = unsafe { libloading::Library::new(std::path::Path::new(&shim).join("libEGL.so.1")) }.expect("dlopen");
    let egl = load(&lib);
    // SAFETY: the C prototype of eglCreateWindowSurface (a 64-bit X11 window on x86-64).
    let create_window: unsafe extern "C" fn(Ptr, Ptr, u64, *const i32) -> Ptr =
        unsafe { *lib.get(b"eglCreateWindowSurface").expect("eglCreateWindowSurface") };
    let mut attribs = Vec::new();
    if let Ok(id) = std::env::var(ASKS) {
        attribs.extend([EGL_SURFACE_ID_STRATA, id.parse().expect("id")]);
    }
    attribs.push(EGL_NONE);
    let mut out = std::io::stdout();
    // SAFETY: EGL calls with the arguments egl.h describes; every out-pointer is valid and
    // every attribute list is EGL_NONE-terminated.
    unsafe {
        let dpy = (egl.get_display)(std::ptr::null_mut());
        let (mut major, mut minor) = (0, 0);
        assert_eq!((egl.initialize)(dpy, &mut major, &mut minor), 1, "eglInitialize");
        let want = [EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, want.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");
        let mut first = None;
        for _ in 0..windows {
            let s = create_window(dpy, config, 0, attribs.as_ptr());
            if s.is_null() {
                writeln!(out, "surface error {:#x}", (egl.get_error)()).expect("stdout");
                continue;
            }
            first = first.or(Some(s));
            let mut id = 0;
            assert_eq!((egl.query_surface)(dpy, s, EGL_SURFACE_ID_STRATA, &mut id), 1, "eglQuerySurface");
            writeln!(out, "surface id {id}").expect("stdout");
        }
        if let (Some(s), true) = (first, std::env::var_os(DRAWS).is_some()) {
            let ctx = (egl.create_context)(
                dpy,
                config,
                std::ptr::null_mut(),
                [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE].as_ptr(),
            );
            assert_eq!((egl.make_current)(dpy, s, s, ctx), 1, "eglMakeCurrent");
            let enable: unsafe extern "C" fn(u32) = *lib.get(b"glEnable").expect("glEnable");
            let scissor: unsafe extern "C" fn(i32, i32, i32, i32) = *lib.get(b"glScissor").expect("glScissor");
            enable(GL_SCISSOR_TEST);
            for (y, color) in [(0, [1.0, 0.0, 0.0]), (8, [0.0, 1.0, 0.0])] {
                scissor(0, y, 16, 8);
                (egl.clear_color)(color[0], color[1], color[2], 1.0);
                (egl.clear)(GL_COLOR_BUFFER_BIT);
            }
            assert_eq!((egl.swap_buffers)(dpy, s), 1, "eglSwapBuffers");
            (egl.finish)();
        }
        writeln!(out, "ready").expect("stdout");
        out.flush().expect("stdout");
    }
    // Keep the surfaces until the test closes stdin.
    let _ = std::io::stdin().lines().count();
    // Applications never unload libEGL: the library's threads outlive an unload.
    std::mem::forget(lib);
}

fn ctl(socket: &std::path::Path, args: &[&str]) -> String {
    let out = Command::new(support::stratad()).arg("ctl").args(args).arg("--socket").arg(socket).output().expect("ctl");
    assert!(out.status.success(), "ctl {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("utf-8")
}

fn rows(socket: &std::path::Path) -> Vec<SurfaceRow> {
    let v: serde_json::Value = serde_json::from_str(&ctl(socket, &["list", "--json"])).expect("json");
    serde_json::from_value(v["surfaces"].clone()).expect("surface rows")
}

#[test]
fn surfaces_keep_the_ids_the_layout_the_environment_or_the_application_give() {
    let dir = TempDir::new("surface-ids");
    let config = dir.0.join("config.toml");
    let entry =
        |client: &str, id: &str| format!("[[layout]]\nclient = \"{client}\"\nx = 0\ny = 0\nz = 0.5\nid = {id}\n\n");
    std::fs::write(&config, entry("ic", "1000") + &entry("hu", "[2000, 2001]")).expect("config");
    let daemon = Daemon::start("surface-ids", &["--output", "t=64x64", "--config", config.to_str().expect("utf-8")]);
    let socket = daemon.socket.clone();
    let shim = support::shim_dir(&dir);

    // The layout wins over the environment; a list is taken in creation order, and a surface
    // beyond it gets a runtime ID, which is never one the layout gives.
    let ic = Client::start(&socket, &shim, "ic", 1, Some("5"), None, false);
    assert_eq!(ic.got, vec![Ok(1000)]);
    let hu = Client::start(&socket, &shim, "hu", 3, None, None, false);
    assert_eq!(hu.got[..2], [Ok(2000), Ok(2001)]);
    let runtime = hu.got[2].expect("a runtime id");
    assert!(![1000, 2000, 2001].contains(&runtime), "runtime id {runtime}");

    // The environment, then the application's own attribute; a second live claim is refused.
    let app = Client::start(&socket, &shim, "app", 1, Some("3000"), Some(3500), false);
    assert_eq!(app.got, vec![Ok(3000)], "STRATA_SURFACE_ID wins over the application's attribute");
    let own = Client::start(&socket, &shim, "own", 1, None, Some(4000), false);
    assert_eq!(own.got, vec![Ok(4000)]);
    // A refused claim does not use the ID up: the same window asks for it again.
    let twin = Client::start(&socket, &shim, "twin", 2, Some("3000,4001"), None, false);
    assert_eq!(twin.got, vec![Err(EGL_BAD_MATCH), Err(EGL_BAD_MATCH)], "3000 is app's");
    daemon.wait_log("surface id 3000 is already held by a surface of client \"app\"");
    let bad = Client::start(&socket, &shim, "bad", 1, Some("cluster"), None, false);
    assert_eq!(bad.got, vec![Err(EGL_BAD_ATTRIBUTE)]);
    let zero = Client::start(&socket, &shim, "zero", 1, None, Some(0), false);
    assert_eq!(zero.got, vec![Err(EGL_BAD_ATTRIBUTE)]);
    daemon.wait_log("surface id 0 is outside 1..=");

    // ctl list reports the IDs, in creation order; ctl move addresses a stable one.
    let ids: Vec<(u64, String)> = rows(&socket).into_iter().map(|r| (r.id, r.client)).collect();
    let want: Vec<(u64, String)> =
        [(1000, "ic"), (2000, "hu"), (2001, "hu"), (runtime as u64, "hu"), (3000, "app"), (4000, "own")]
            .into_iter()
            .map(|(id, c)| (id, c.to_string()))
            .collect();
    assert_eq!(ids, want);
    ctl(&socket, &["move", "1000", "8", "4", "0.25"]);
    let moved = rows(&socket).into_iter().find(|r| r.id == 1000).expect("ic's surface");
    assert_eq!((moved.rect[0], moved.rect[1], moved.z), (8, 4, 0.25));

    // A surface's newest frame, as its client drew it (top row first in the PNG); a surface
    // that never swapped, and an unknown one, are clear errors.
    let painter = Client::start(&socket, &shim, "painter", 1, Some("5000"), None, true);
    assert_eq!(painter.got, vec![Ok(5000)]);
    let png = dir.0.join("surface.png");
    ctl(&socket, &["screenshot", "--surface", "5000", png.to_str().expect("utf-8")]);
    let img = image::open(&png).expect("png").to_rgba8();
    assert_eq!(img.dimensions(), (16, 16));
    assert_eq!((img.get_pixel(8, 2).0, img.get_pixel(8, 13).0), ([0, 255, 0, 255], [255, 0, 0, 255]), "green on top");
    for (id, says) in [("1000", "surface 1000 has not swapped a frame yet"), ("777", "no surface 777")] {
        let out = Command::new(support::stratad())
            .args(["ctl", "screenshot", "--surface", id, png.to_str().expect("utf-8"), "--socket"])
            .arg(&socket)
            .output()
            .expect("ctl");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(says), "{id}: {err}");
    }
    painter.stop();

    // The instrument cluster restarts: its surface gets its ID back; the claim that failed
    // succeeds once the holder is gone.
    ic.stop();
    app.stop();
    let ic = Client::start(&socket, &shim, "ic", 1, None, None, false);
    assert_eq!(ic.got, vec![Ok(1000)]);
    let twin2 = Client::start(&socket, &shim, "twin2", 1, Some("3000"), None, false);
    assert_eq!(twin2.got, vec![Ok(3000)]);
    for c in [ic, hu, own, twin, bad, zero, twin2] {
        c.stop();
    }
}

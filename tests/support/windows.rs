//! Client processes that create window surfaces through the drop-in libEGL: the test binary
//! runs itself again as `client_process`, which creates window surfaces, prints what each got,
//! optionally draws one frame, and keeps them until its stdin closes.

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use strata_protocol::surface_id::EGL_SURFACE_ID_STRATA;

use super::egl::{load, Ptr};

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_WINDOW_BIT: i32 = 0x0004;
pub const EGL_BAD_MATCH: i32 = 0x3009;
pub const EGL_BAD_ATTRIBUTE: i32 = 0x3004;

/// Set in a client process's environment: how many window surfaces to create.
const WINDOWS: &str = "SURFACE_IDS_WINDOWS";
/// Set in a client process's environment: the ID its application asks for itself.
const ASKS: &str = "SURFACE_IDS_ASKS";
/// Set in a client process's environment: draw one frame into its first surface, its depth
/// cleared to 1, the bottom half (in GL's coordinates) of one colour and the top half of
/// another: `R,G,B/R,G,B` in [0, 1], or anything else for red under green; then swap it.
const DRAWS: &str = "SURFACE_IDS_DRAWS";
const GL_DEPTH_BUFFER_BIT: u32 = 0x0100;
const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_SCISSOR_TEST: u32 = 0x0C11;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;

/// How a client process is started.
struct Spawn<'a> {
    windows: usize,
    env: Option<&'a str>,
    asks: Option<i32>,
    draws: Option<&'a str>,
    window: &'a str,
    user: Option<(u32, u32)>,
}

/// A running client process and what each of its `eglCreateWindowSurface` calls got: the ID,
/// or the EGL error.
pub struct Client {
    child: Child,
    stdin: Option<ChildStdin>,
    /// The rest of its output, read to the end when it stops.
    out: BufReader<ChildStdout>,
    pub got: Vec<Result<i32, i32>>,
}

impl Client {
    /// Starts a client named `name` on `socket` whose one window surface takes ID `env`, is
    /// placed at `window` (`STRATA_WINDOW`: X,Y,Z,WxH) and shows one frame: `colors[0]` in its
    /// bottom half, `colors[1]` in its top half.
    pub fn start_painting(
        socket: &std::path::Path,
        shim: &std::path::Path,
        name: &str,
        env: &str,
        window: &str,
        colors: [[f32; 3]; 2],
    ) -> Client {
        Client::start_painting_as(socket, shim, name, Some(env), window, colors, None)
    }

    /// As [`Client::start_painting`], with or without a surface ID, and running as user and
    /// group `user` where given (the test must be root to start it so).
    pub fn start_painting_as(
        socket: &std::path::Path,
        shim: &std::path::Path,
        name: &str,
        env: Option<&str>,
        window: &str,
        colors: [[f32; 3]; 2],
        user: Option<(u32, u32)>,
    ) -> Client {
        let c = colors.map(|c| format!("{},{},{}", c[0], c[1], c[2]));
        let draws = format!("{}/{}", c[0], c[1]);
        let spawn = Spawn { windows: 1, env, asks: None, draws: Some(&draws), window, user };
        Client::spawn(socket, shim, name, spawn)
    }

    /// Starts a client named `name` on `socket` as user and group `user`, creating `windows`
    /// window surfaces whose application asks for `asks` (the test must be root).
    pub fn start_as(
        socket: &std::path::Path,
        shim: &std::path::Path,
        name: &str,
        windows: usize,
        asks: Option<i32>,
        user: (u32, u32),
    ) -> Client {
        let spawn = Spawn { windows, env: None, asks, draws: None, window: "0,0,0.5,16x16", user: Some(user) };
        Client::spawn(socket, shim, name, spawn)
    }

    /// Starts a client named `name` on `socket` creating `windows` window surfaces, with
    /// `STRATA_SURFACE_ID` set to `env` and its application asking for `asks`; with `draws`, it
    /// swaps one frame into its first surface (red under green).
    pub fn start(
        socket: &std::path::Path,
        shim: &std::path::Path,
        name: &str,
        windows: usize,
        env: Option<&str>,
        asks: Option<i32>,
        draws: bool,
    ) -> Client {
        let spawn = Spawn { windows, env, asks, draws: draws.then_some("1"), window: "0,0,0.5,16x16", user: None };
        Client::spawn(socket, shim, name, spawn)
    }

    fn spawn(socket: &std::path::Path, shim: &std::path::Path, name: &str, how: Spawn<'_>) -> Client {
        let Spawn { windows, env, asks, draws, window, user } = how;
        let mut cmd = Command::new(std::env::current_exe().expect("test binary"));
        if let Some((uid, gid)) = user {
            use std::os::unix::process::CommandExt;
            cmd.uid(uid).gid(gid);
        }
        cmd.args(["--exact", "client_process", "--nocapture", "--test-threads", "1"])
            .env("STRATA_SOCKET", socket)
            .env("STRATA_NAME", name)
            .env("STRATA_WINDOW", window)
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
        if let Some(d) = draws {
            cmd.env(DRAWS, d);
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

    /// Its process ID.
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// Closes its stdin and waits for it to leave.
    pub fn stop(mut self) {
        drop(self.stdin.take());
        let _ = std::io::copy(&mut self.out, &mut std::io::sink());
        let status = self.child.wait().expect("wait");
        assert!(status.success(), "client: {status}");
    }
}

/// The client process a test starts: each test binary that uses [`Client`] has a test named
/// `client_process` that calls this (which does nothing when run as part of the suite).
pub fn serve() {
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
        if let (Some(s), Ok(draws)) = (first, std::env::var(DRAWS)) {
            let parse = |v: &str| -> Option<[f32; 3]> {
                let v: Vec<f32> = v.split(',').map(str::parse).collect::<Result<_, _>>().ok()?;
                v.try_into().ok()
            };
            let colors = draws
                .split_once('/')
                .and_then(|(a, b)| Some([parse(a)?, parse(b)?]))
                .unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
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
            (egl.clear)(GL_DEPTH_BUFFER_BIT);
            for (y, color) in [(0, colors[0]), (8, colors[1])] {
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

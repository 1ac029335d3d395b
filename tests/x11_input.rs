//! An Xlib program that knows nothing of Strata (an X window, EGL on it through the drop-in
//! libEGL, and an `XNextEvent` loop) receives `ctl input` taps, drags, keys and text as its own
//! X11 events, at the exact coordinates of its window: the output point less the surface's
//! placement. Each test binary that runs it names the program `xlib_program`.

mod support;

use std::ffi::{c_char, CStr};
use std::io::{BufRead, BufReader, Write};
use std::process::{Command, Stdio};
use std::sync::mpsc::Receiver;
use std::time::Duration;

use strata_client::ControlConnection;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{Action, Device, InputRequest};
use support::{Daemon, TempDir, Xvfb};
use x11_dl::xlib;

const EGL_NONE: i32 = 0x3038;
const EGL_SURFACE_TYPE: i32 = 0x3033;
const EGL_WINDOW_BIT: i32 = 0x0004;
const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;

/// Where the program's window surface is placed (`STRATA_WINDOW`: x, y, z).
const AT: (i32, i32) = (40, 30);

/// The program: a 200×120 window drawn once in blue, then every button, motion, key and focus
/// event printed as a line until its stdin closes.
#[test]
fn xlib_program() {
    let Ok(shim) = std::env::var("XLIB_PROGRAM_SHIM") else { return };
    // SAFETY: loading the drop-in library, as the dynamic linker would for a program linked
    // against libEGL.
    let lib = unsafe { libloading::Library::new(std::path::Path::new(&shim).join("libEGL.so.1")) }.expect("dlopen");
    let egl = support::egl::load(&lib);
    let xl = xlib::Xlib::open().expect("libX11");
    // SAFETY: create_window's C prototype (a 64-bit X11 Window on x86-64).
    let create_window: unsafe extern "C" fn(
        support::egl::Ptr,
        support::egl::Ptr,
        u64,
        *const i32,
    ) -> support::egl::Ptr = unsafe { support::egl::sym(&lib, b"eglCreateWindowSurface") };
    let (tx, stdin_closed) = std::sync::mpsc::channel::<()>();
    std::thread::spawn(move || {
        let _ = std::io::stdin().lines().count();
        let _ = tx.send(());
    });
    let mut out = std::io::stdout();
    // SAFETY: Xlib and EGL/GL calls with the arguments their headers describe, on a display
    // and window this program owns; every out-pointer is valid.
    unsafe {
        let d = (xl.XOpenDisplay)(std::ptr::null());
        assert!(!d.is_null(), "XOpenDisplay");
        let win = (xl.XCreateSimpleWindow)(d, (xl.XDefaultRootWindow)(d), 0, 0, 200, 120, 0, 0, 0);
        let mask = xlib::ButtonPressMask
            | xlib::ButtonReleaseMask
            | xlib::PointerMotionMask
            | xlib::KeyPressMask
            | xlib::KeyReleaseMask
            | xlib::FocusChangeMask;
        (xl.XSelectInput)(d, win, mask);
        (xl.XMapWindow)(d, win);
        (xl.XSync)(d, 0);
        let dpy = (egl.get_display)(d.cast());
        assert_eq!((egl.initialize)(dpy, std::ptr::null_mut(), std::ptr::null_mut()), 1, "eglInitialize");
        let want = [EGL_SURFACE_TYPE, EGL_WINDOW_BIT, EGL_NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        assert_eq!((egl.choose_config)(dpy, want.as_ptr(), &mut config, 1, &mut n), 1, "eglChooseConfig");
        let none = [EGL_NONE];
        let surface = create_window(dpy, config, win, none.as_ptr());
        assert!(!surface.is_null(), "eglCreateWindowSurface {:#x}", (egl.get_error)());
        let ctx_attribs = [EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE];
        let ctx = (egl.create_context)(dpy, config, std::ptr::null_mut(), ctx_attribs.as_ptr());
        assert_eq!((egl.make_current)(dpy, surface, surface, ctx), 1, "eglMakeCurrent");
        (egl.clear_color)(0.0, 0.2, 1.0, 1.0);
        (egl.clear)(0x4000);
        assert_eq!((egl.swap_buffers)(dpy, surface), 1, "eglSwapBuffers");
        (egl.finish)();
        writeln!(out, "ready").expect("stdout");
        let mut ev: xlib::XEvent = std::mem::zeroed();
        while stdin_closed.try_recv().is_err() {
            if (xl.XPending)(d) == 0 {
                std::thread::sleep(Duration::from_millis(2));
                continue;
            }
            (xl.XNextEvent)(d, &mut ev);
            let line = match ev.get_type() {
                xlib::ButtonPress => format!("press {} {} {}", ev.button.button, ev.button.x, ev.button.y),
                xlib::ButtonRelease => format!("release {} {} {}", ev.button.button, ev.button.x, ev.button.y),
                xlib::MotionNotify => format!("motion {} {} {:#x}", ev.motion.x, ev.motion.y, ev.motion.state),
                xlib::KeyPress => {
                    let mut text = [0 as c_char; 16];
                    let mut keysym = 0;
                    let n = (xl.XLookupString)(&mut ev.key, text.as_mut_ptr(), 15, &mut keysym, std::ptr::null_mut());
                    let text = if n > 0 {
                        CStr::from_ptr(text.as_ptr()).to_string_lossy().into_owned()
                    } else {
                        String::new()
                    };
                    format!("key {keysym:#x} {text:?}")
                }
                xlib::KeyRelease => continue,
                xlib::FocusIn => "focus in".to_string(),
                xlib::FocusOut => "focus out".to_string(),
                _ => continue,
            };
            writeln!(out, "{line}").expect("stdout");
            out.flush().expect("stdout");
        }
    }
}

/// The program's output lines, as they come.
fn lines(child: &mut std::process::Child) -> Receiver<String> {
    let out = BufReader::new(child.stdout.take().expect("stdout"));
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for l in out.lines().map_while(Result::ok) {
            // libtest writes its "running 1 test" lines first.
            if tx.send(l.trim_start_matches("test xlib_program ... ").to_string()).is_err() {
                return;
            }
        }
    });
    rx
}

/// Lines until one equal to `want` (panics after 10 s), the others returned.
fn expect(rx: &Receiver<String>, want: &str) -> Vec<String> {
    let mut seen = Vec::new();
    loop {
        match rx.recv_timeout(Duration::from_secs(10)) {
            Ok(l) if l == want => return seen,
            Ok(l) => seen.push(l),
            Err(_) => panic!("the program did not print {want:?}; it printed {seen:?}"),
        }
    }
}

#[test]
fn an_unmodified_xlib_program_gets_input_at_its_own_coordinates() {
    let Some(x) = Xvfb::start_or_skip(320, 240) else { return };
    let daemon = Daemon::start("x11-input", &["--lighting", "off", "--output", "headless:main=320x240"]);
    let tmp = TempDir::new("x11-input");
    let mut child = Command::new(std::env::current_exe().expect("test binary"))
        .args(["--exact", "xlib_program", "--nocapture", "--test-threads", "1"])
        .env("DISPLAY", &x.display)
        .env("STRATA_SOCKET", &daemon.socket)
        .env("STRATA_NAME", "xlib-program")
        .env("STRATA_WINDOW", format!("{},{},0.5", AT.0, AT.1))
        .env("XLIB_PROGRAM_SHIM", support::shim_dir(&tmp))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("the program");
    let rx = lines(&mut child);
    expect(&rx, "ready");
    let mut c = ControlConnection::connect_beside(&daemon.socket).expect("control");
    let mut input =
        |action: Action| match c.request(&ControlRequest::Input(InputRequest { output: "main".into(), action })) {
            Ok(ControlReply::Input(o)) => assert!(o.surface.is_some(), "{o:?}"),
            other => panic!("{other:?}"),
        };
    // A tap: the window's own coordinates are the output's less the placement.
    input(Action::Tap { x: 100.5, y: 70.5 });
    expect(&rx, "focus in");
    expect(&rx, &format!("press 1 {} {}", 100 - AT.0, 70 - AT.1));
    expect(&rx, &format!("release 1 {} {}", 100 - AT.0, 70 - AT.1));
    // A drag with the right button: motion carries the button's state.
    input(Action::Press { device: Device::Pointer, id: 3, x: 50.0, y: 50.0 });
    input(Action::Move { device: Device::Pointer, id: 3, x: 61.0, y: 55.0 });
    input(Action::Release { device: Device::Pointer, id: 3 });
    expect(&rx, "press 3 10 20");
    expect(&rx, &format!("motion 21 25 {:#x}", xlib::Button3Mask));
    expect(&rx, "release 3 21 25");
    // Keys and text, with Shift where the keyboard map needs it.
    input(Action::Key { name: "Return".into() });
    expect(&rx, "key 0xff0d \"\\r\"");
    input(Action::Text { text: "Hi!".into() });
    expect(&rx, "key 0x48 \"H\"");
    expect(&rx, "key 0x69 \"i\"");
    expect(&rx, "key 0x21 \"!\"");
    drop(child.stdin.take());
    let status = child.wait().expect("wait");
    assert!(status.success(), "the program: {status}");
}

//! A window output on a real X server (Xvfb): the pixels the X server holds for the output's
//! window equal the output's composited image, as `stratad ctl screenshot` returns it.

mod support;

use std::ffi::CString;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{InputEvent, Phase};
use support::{Daemon, Xvfb};
use x11_dl::xlib;

const W: u32 = 320;
const H: u32 = 200;

/// The top-level window named `name`.
///
/// # Safety
/// `dpy` is an open display of `x`.
unsafe fn find_window(x: &xlib::Xlib, dpy: *mut xlib::Display, name: &str) -> Option<xlib::Window> {
    // SAFETY: Xlib queries on an open display; what Xlib returns is checked and freed.
    unsafe {
        let root = (x.XDefaultRootWindow)(dpy);
        let (mut r, mut p, mut kids, mut n) = (0, 0, std::ptr::null_mut(), 0u32);
        (x.XQueryTree)(dpy, root, &mut r, &mut p, &mut kids, &mut n);
        let mut found = None;
        for i in 0..n as usize {
            let w = *kids.add(i);
            let mut wname: *mut std::os::raw::c_char = std::ptr::null_mut();
            if (x.XFetchName)(dpy, w, &mut wname) != 0 && !wname.is_null() {
                if std::ffi::CStr::from_ptr(wname).to_bytes() == name.as_bytes() {
                    found = Some(w);
                }
                (x.XFree)(wname.cast());
            }
        }
        if !kids.is_null() {
            (x.XFree)(kids.cast());
        }
        found
    }
}

/// Runs `f` on the top-level window named `name` of `display`, through a display connection
/// opened for it and closed after.
fn with_window<R>(
    display: &str,
    name: &str,
    f: impl FnOnce(&xlib::Xlib, *mut xlib::Display, xlib::Window) -> Result<R, String>,
) -> Result<R, String> {
    let x = xlib::Xlib::open().map_err(|e| format!("libX11: {e}"))?;
    let disp_name = CString::new(display).map_err(|e| e.to_string())?;
    // SAFETY: a display this function opens, used by `f` while open, and closed once.
    unsafe {
        let dpy = (x.XOpenDisplay)(disp_name.as_ptr());
        if dpy.is_null() {
            return Err(format!("cannot open display {display}"));
        }
        let r = match find_window(&x, dpy, name) {
            Some(win) => f(&x, dpy, win),
            None => Err(format!("no window named {name}")),
        };
        (x.XCloseDisplay)(dpy);
        r
    }
}

/// Clicks button 1 at (`at`) in the window named `name` through the X server's XTEST extension,
/// as a user's pointer would.
fn click_in_window(display: &str, name: &str, at: (i32, i32)) -> Result<(), String> {
    let xt = x11_dl::xtest::Xf86vmode::open().map_err(|e| format!("libXtst: {e}"))?;
    with_window(display, name, |x, dpy, win| {
        // SAFETY: Xlib and XTEST calls on the open display `with_window` gives.
        unsafe {
            let (mut rx, mut ry, mut child) = (0, 0, 0);
            (x.XTranslateCoordinates)(dpy, win, (x.XDefaultRootWindow)(dpy), at.0, at.1, &mut rx, &mut ry, &mut child);
            (xt.XTestFakeMotionEvent)(dpy, -1, rx, ry, 0);
            (x.XSync)(dpy, 0);
            std::thread::sleep(Duration::from_millis(100));
            (xt.XTestFakeButtonEvent)(dpy, 1, 1, 0);
            (xt.XTestFakeButtonEvent)(dpy, 1, 0, 0);
            (x.XSync)(dpy, 0);
        }
        Ok(())
    })
}

/// The RGB pixels of the top-level window named `name` on `display`, read from the X server.
fn x_window_pixels(display: &str, name: &str) -> Result<Vec<[u8; 3]>, String> {
    with_window(display, name, |x, dpy, win| {
        // SAFETY: Xlib calls on the open display `with_window` gives; the image Xlib returns is
        // checked before use and freed with the matching Xlib call.
        unsafe {
            let img = (x.XGetImage)(dpy, win, 0, 0, W, H, !0, xlib::ZPixmap);
            if img.is_null() {
                return Err("XGetImage failed".into());
            }
            let im = &*img;
            let mut out = Vec::with_capacity((W * H) as usize);
            let ok =
                im.bits_per_pixel == 32 && im.red_mask == 0xff0000 && im.green_mask == 0xff00 && im.blue_mask == 0xff;
            if ok {
                for y in 0..H as usize {
                    let row = im.data.cast::<u8>().add(y * im.bytes_per_line as usize);
                    for xx in 0..W as usize {
                        let px = std::slice::from_raw_parts(row.add(xx * 4), 4);
                        out.push([px[2], px[1], px[0]]);
                    }
                }
            }
            let fmt = (im.bits_per_pixel, im.red_mask);
            (x.XDestroyImage)(img);
            if ok {
                Ok(out)
            } else {
                Err(format!("unexpected X image format {fmt:?}"))
            }
        }
    })
}

#[test]
fn window_output_shows_the_composited_image() {
    let Some(xvfb) = Xvfb::start_or_skip(640, 480) else { return };
    let daemon = Daemon::start_with_env(
        "window",
        &["--output", &format!("window:win={W}x{H}")],
        &[("DISPLAY", xvfb.display.as_str())],
    );
    let mut clients = Vec::new();
    // Two lit surfaces at one z that overlap, with different depths: a non-trivial image.
    for (i, (rect, color, depth)) in
        [([40, 30, 160, 100], [0.9, 0.4, 0.1], 0.3), ([120, 60, 160, 120], [0.2, 0.5, 0.9], 0.6)]
            .into_iter()
            .enumerate()
    {
        let mut gl = Connection::connect(&ConnectOptions {
            socket: daemon.socket.clone(),
            name: format!("w{i}"),
            ..Default::default()
        })
        .expect("connect");
        let cur = egl_context(&mut gl, 24, 0, SurfaceKind::Window { rect, z: 0.5 }).expect("context");
        gl.glClearColor(color[0], color[1], color[2], 1.0).expect("io");
        gl.glClearDepthf(depth).expect("io");
        gl.glClear(0x4000 | 0x0100).expect("io");
        gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
        gl.glFinish().expect("io");
        clients.push(gl);
    }
    let mut ctl = ControlConnection::connect_beside(&daemon.socket).expect("control");
    match ctl.request(&ControlRequest::List).expect("list") {
        ControlReply::List { outputs, .. } => assert_eq!(outputs[0].kind, "window"),
        other => panic!("{other:?}"),
    }
    // A click in the window reaches the client whose surface is shown there, at the point in
    // its own pixels: (60, 50) lies on w0 alone, 20 and 20 pixels into it.
    let got = (|| {
        click_in_window(&xvfb.display, "win", (60, 50))?;
        let deadline = Instant::now() + Duration::from_secs(10);
        let mut seen = Vec::new();
        while Instant::now() < deadline {
            match clients[0].next_input(Duration::from_millis(100)) {
                Ok(Some(e @ InputEvent::Point { phase: Phase::Down, .. })) => return Ok(e),
                Ok(Some(e)) => seen.push(e),
                Ok(None) => {}
                Err(e) => return Err(e.to_string()),
            }
        }
        Err(format!("no press reached the client; it got {seen:?}"))
    })();
    match got {
        Ok(e) => assert!(matches!(e, InputEvent::Point { x: 20.0, y: 20.0, .. }), "{e:?}"),
        Err(e) => panic!("{e}"),
    }
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let shot = match ctl.request(&ControlRequest::Screenshot { output: "win".into() }).expect("screenshot") {
            ControlReply::Image { rgba, .. } => rgba.0,
            other => panic!("{other:?}"),
        };
        let expected: Vec<[u8; 3]> = shot.chunks(4).map(|p| [p[0], p[1], p[2]]).collect();
        // The surfaces are visible: the output is not blank.
        assert!(expected.iter().filter(|p| p[0] > 100 && p[2] < 100).count() > 1000, "the orange surface is missing");
        assert!(expected.iter().filter(|p| p[2] > 100 && p[0] < 100).count() > 1000, "the blue surface is missing");
        match x_window_pixels(&xvfb.display, "win") {
            Ok(shown) if shown == expected => break,
            Ok(shown) => {
                let bad = shown.iter().zip(&expected).filter(|(a, b)| a != b).count();
                assert!(Instant::now() < deadline, "{bad} of {} window pixels differ from the output", W * H);
            }
            Err(e) => assert!(Instant::now() < deadline, "reading the window: {e}"),
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    drop(clients);
}

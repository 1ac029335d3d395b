//! `EGL_KHR_gl_colorspace` on window surfaces: a linear and an sRGB window side by side, both
//! cleared to mid grey, show on the output as the bytes each stores, 128 and 188 (the sRGB
//! encoding of 0.5), however frames reach the compositor; the sRGB window keeps its colour
//! space through the buffers a swap interval of 0 adds and through a resize; and the surface
//! says which it has.

mod support;

use std::path::Path;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context_with, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use support::Daemon;

const COLORSPACE: i32 = 0x309D;
const SRGB: i32 = 0x3089;
const LINEAR: i32 = 0x308A;
const SIZE: i32 = 64;

/// The output's pixel (x, y) once `want` shows there (the composite follows the swap).
fn shows(socket: &Path, (x, y): (u32, u32), want: [u8; 3]) -> [u8; 3] {
    let start = Instant::now();
    loop {
        let reply = ControlConnection::connect_beside(socket)
            .expect("control")
            .request(&ControlRequest::Screenshot { output: "d".into() })
            .expect("control request");
        let ControlReply::Image { width, height, rgba } = reply else { panic!("screenshot: {reply:?}") };
        let p = image::RgbaImage::from_raw(width, height, rgba.0).expect("size").get_pixel(x, y).0;
        let got = [p[0], p[1], p[2]];
        if got == want || start.elapsed() > Duration::from_secs(5) {
            return got;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A client with a window over `rect` of colour space `space`, current.
fn window(socket: &Path, name: &str, rect: [i32; 4], space: i32) -> (Connection, Current) {
    let options = ConnectOptions { socket: socket.to_path_buf(), name: name.into(), ..Default::default() };
    let mut gl = Connection::connect(&options).expect("connect");
    let kind = SurfaceKind::Window { rect, z: 0.5 };
    let cur = egl_context_with(&mut gl, 0, 0, kind, &[COLORSPACE, space]).expect("context");
    (gl, cur)
}

/// Clears to mid grey and swaps.
fn grey_frame(gl: &mut Connection, cur: Current) {
    gl.glClearColor(0.5, 0.5, 0.5, 1.0).expect("io");
    gl.glClear(0x4000).expect("io");
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
}

/// Every way frames reach the compositor: the same memory exported and imported (where the
/// driver shares it), one device for everyone, and copies through host memory.
#[test]
fn srgb_windows_show_the_encoded_colour_they_store() {
    for (tag, mode) in [("export", None), ("shared", Some("--devices=shared")), ("copy", Some("--frame-transfer=copy"))]
    {
        eprintln!("frames by {tag}");
        colour_spaces(tag, mode);
    }
}

fn colour_spaces(tag: &str, mode: Option<&str>) {
    let output = format!("d={SIZE}x{SIZE}");
    let mut args = vec!["--lighting", "off", "--output", &output];
    args.extend(mode);
    let daemon = Daemon::start(&format!("colorspace-{tag}"), &args);
    let socket = daemon.socket.clone();
    let (mut lin, lin_cur) = window(&socket, "linear", [0, 0, SIZE / 2, SIZE], LINEAR);
    let (mut srgb, srgb_cur) = window(&socket, "srgb", [SIZE / 2, 0, SIZE / 2, SIZE], SRGB);
    for (gl, cur, want) in [(&mut lin, lin_cur, LINEAR), (&mut srgb, srgb_cur, SRGB)] {
        let got = gl.eglQuerySurface(cur.display, cur.surface, COLORSPACE).expect("io");
        assert_eq!(got, Ok(want), "the surface's colour space");
    }
    grey_frame(&mut lin, lin_cur);
    grey_frame(&mut srgb, srgb_cur);
    assert_eq!(shows(&socket, (16, 32), [128; 3]), [128; 3], "the linear window stores 0.5 as 128");
    assert_eq!(shows(&socket, (48, 32), [188; 3]), [188; 3], "the sRGB window stores 0.5 encoded, as 188");

    // More buffers at swap interval 0, each cleared to a new grey: still encoded.
    srgb.eglSwapInterval(srgb_cur.display, 0).expect("io").expect("interval");
    for k in 1..=5 {
        let v = 0.1 * k as f32;
        srgb.glClearColor(v, v, v, 1.0).expect("io");
        srgb.glClear(0x4000).expect("io");
        srgb.eglSwapBuffers(srgb_cur.display, srgb_cur.surface).expect("io").expect("swap");
    }
    // 0.5 again after a resize (the window's placement fixes where it shows).
    srgb.strataResizeSurface(srgb_cur.display, srgb_cur.surface, SIZE / 2 - 2, SIZE).expect("io").expect("resize");
    grey_frame(&mut srgb, srgb_cur);
    assert_eq!(shows(&socket, (48, 32), [188; 3]), [188; 3], "still sRGB after new buffers and a resize");

    // A colour space that is neither.
    let e = srgb.eglCreateWindowSurface(
        srgb_cur.display,
        1,
        0,
        0,
        0,
        0.5,
        8,
        8,
        strata_protocol::Slice::new(&[COLORSPACE, 7, 0x3038]),
    );
    assert_eq!(e.expect("io"), Err(0x3004), "EGL_BAD_ATTRIBUTE");
    assert!(!daemon.log_text().contains("panicked"), "daemon panicked:\n{}", daemon.log_text());
}

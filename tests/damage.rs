//! `EGL_KHR_swap_buffers_with_damage` and `EGL_EXT_buffer_age` on a window surface: the
//! compositor redraws only what a client says changed, so a frame drawn all green but swapped
//! with damage over its left half shows green there and the previous frame's red on the right,
//! until a plain swap shows all of it; each back buffer reports how many frames ago it was the
//! newest; and the calls' errors.

mod support;

use std::path::Path;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::Slice;
use support::Daemon;

const EGL_BUFFER_AGE: i32 = 0x313D;
const EGL_BAD_PARAMETER: i32 = 0x300C;
const EGL_BAD_SURFACE: i32 = 0x300D;
const SIZE: i32 = 64;

fn screenshot(socket: &Path) -> image::RgbaImage {
    let reply = ControlConnection::connect_beside(socket)
        .expect("control")
        .request(&ControlRequest::Screenshot { output: "d".into() })
        .expect("control request");
    match reply {
        ControlReply::Image { width, height, rgba } => image::RgbaImage::from_raw(width, height, rgba.0).expect("size"),
        other => panic!("screenshot: {other:?}"),
    }
}

/// The output's pixel (x, y) once `want` shows there (the composite follows the swap).
fn shows(socket: &Path, (x, y): (u32, u32), want: [u8; 3]) -> [u8; 3] {
    let start = Instant::now();
    loop {
        let p = screenshot(socket).get_pixel(x, y).0;
        let got = [p[0], p[1], p[2]];
        if got == want || start.elapsed() > Duration::from_secs(5) {
            return got;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn clear(gl: &mut Connection, c: [f32; 3]) {
    gl.glClearColor(c[0], c[1], c[2], 1.0).expect("io");
    gl.glClear(0x4000).expect("io");
}

fn age(gl: &mut Connection, cur: Current) -> i32 {
    gl.eglQuerySurface(cur.display, cur.surface, EGL_BUFFER_AGE).expect("io").expect("buffer age")
}

#[test]
fn stated_damage_limits_the_composite_and_buffers_know_their_age() {
    let daemon = Daemon::start("damage", &["--lighting", "off", "--output", &format!("d={SIZE}x{SIZE}")]);
    let socket = daemon.socket.clone();
    let mut gl =
        Connection::connect(&ConnectOptions { socket: socket.clone(), name: "damage".into(), ..Default::default() })
            .expect("connect");
    let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Window { rect: [0, 0, SIZE, SIZE], z: 0.5 }).expect("context");
    assert_eq!(age(&mut gl, cur), 0, "a buffer that holds no frame");

    // A red frame, shown whole.
    clear(&mut gl, [1.0, 0.0, 0.0]);
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
    assert_eq!(shows(&socket, (48, 32), [255, 0, 0]), [255, 0, 0], "the red frame");
    let first = age(&mut gl, cur);

    // All green, but only the left half stated: the right half keeps the red frame.
    clear(&mut gl, [0.0, 1.0, 0.0]);
    let left = [0, 0, SIZE / 2, SIZE];
    gl.eglSwapBuffersWithDamageKHR(cur.display, cur.surface, Slice::new(&left)).expect("io").expect("swap with damage");
    assert_eq!(shows(&socket, (8, 32), [0, 255, 0]), [0, 255, 0], "the stated half");
    std::thread::sleep(Duration::from_millis(200));
    let p = screenshot(&socket).get_pixel(48, 32).0;
    assert_eq!([p[0], p[1], p[2]], [255, 0, 0], "the half not stated is not redrawn");

    // Buffer ages: a back buffer whose age is a > 0 holds the frame drawn a frames ago (its
    // pixels are read before anything is drawn); 0 is a buffer that holds no frame yet.
    let colour = |k: usize| [0.0, 0.0, (k * 20) as f32 / 255.0];
    let byte = |v: f32| (v * 255.0).round() as u8;
    let mut drawn = 0;
    let mut aged = 0;
    for k in 2..10 {
        let a = age(&mut gl, cur) as usize;
        if a > 0 {
            assert!(a <= k, "frame {k}: age {a} is older than the surface");
            let px = gl.glReadPixels(1, 1, 1, 1, 0x1908, 0x1401).expect("io").0;
            let want = if k - a >= 2 { colour(k - a).map(byte) } else { [px[0], px[1], px[2]] };
            assert_eq!(&px[..3], &want[..], "frame {k}: a buffer of age {a} holds frame {}", k - a);
            aged += 1;
        }
        clear(&mut gl, colour(k));
        gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
        drawn += 1;
    }
    assert!(aged >= drawn / 2, "most frames reuse a buffer: {aged} of {drawn}");
    let _ = (first, colour(0));
    let last = colour(9).map(byte);
    assert_eq!(shows(&socket, (48, 32), last), last, "a plain swap redraws all of it");

    // Errors: a negative size; the age of a surface not current.
    let bad = [0, 0, -1, 4];
    let e = gl.eglSwapBuffersWithDamageKHR(cur.display, cur.surface, Slice::new(&bad)).expect("io");
    assert_eq!(e, Err(EGL_BAD_PARAMETER));
    let configs = gl.eglChooseConfig(cur.display, Slice::new(&[0x3033, 1, 0x3038]), 1).expect("io").expect("configs");
    let config = *configs.first().expect("a pbuffer config");
    let pbuffer = gl.eglCreatePbufferSurface(cur.display, config, Slice::new(&[0x3057, 4, 0x3056, 4, 0x3038]));
    let pbuffer = pbuffer.expect("io").expect("pbuffer");
    let e = gl.eglQuerySurface(cur.display, pbuffer, EGL_BUFFER_AGE).expect("io");
    assert_eq!(e, Err(EGL_BAD_SURFACE), "not the current draw surface");
}

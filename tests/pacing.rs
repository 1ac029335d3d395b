//! The compositor thread against real clients: frames are never shown torn, swaps are paced
//! (K frames in flight, `eglSwapInterval`), a stalled client stays visible, a departed one
//! goes, and `stratad ctl move|light|screenshot|list` act on a running daemon, recompositing
//! only when something changed.

mod support;

use std::path::Path;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_compositor::{reference, Lighting};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use support::Daemon;

const GL_COLOR_BUFFER_BIT: u32 = 0x4000;
const GL_DEPTH_BUFFER_BIT: u32 = 0x0100;
const GL_SCISSOR_TEST: u32 = 0x0C11;

fn connect(socket: &Path, name: &str) -> Connection {
    Connection::connect(&ConnectOptions { socket: socket.into(), name: name.into(), ..Default::default() })
        .expect("connect")
}

fn window(gl: &mut Connection, rect: [i32; 4], z: f32, interval: i32) -> Current {
    let cur = egl_context(gl, 24, 0, SurfaceKind::Window { rect, z }).expect("context");
    gl.eglSwapInterval(cur.display, interval).expect("io").expect("eglSwapInterval");
    cur
}

fn clear(gl: &mut Connection, c: [u8; 3]) {
    let f = |v: u8| f32::from(v) / 255.0;
    gl.glClearColor(f(c[0]), f(c[1]), f(c[2]), 1.0).expect("io");
    gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT).expect("io");
}

fn swap(gl: &mut Connection, cur: Current) {
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("eglSwapBuffers");
}

/// Frame `f`'s colour: distinct for every frame the tests draw, never black.
fn frame_color(f: u32) -> [u8; 3] {
    [(f * 37 % 200 + 40) as u8, (f * 91 % 200 + 40) as u8, (f / 200 * 50 % 200 + 40) as u8]
}

/// Draws frame `f` in two halves, with the first half submitted to the GPU on its own
/// (`glFinish`) before the second is drawn: a compositor that sampled a back buffer, or a
/// front buffer before its frame was complete, would show two colours.
fn two_half_frame(gl: &mut Connection, cur: Current, size: i32, f: u32) {
    let c = frame_color(f);
    gl.glEnable(GL_SCISSOR_TEST).expect("io");
    gl.glScissor(0, 0, size, size / 2).expect("io");
    clear(gl, c);
    gl.glFinish().expect("io");
    gl.glScissor(0, size / 2, size, size - size / 2).expect("io");
    clear(gl, c);
    gl.glDisable(GL_SCISSOR_TEST).expect("io");
    swap(gl, cur);
}

fn control(socket: &Path, req: ControlRequest) -> ControlReply {
    ControlConnection::connect_beside(socket).expect("control").request(&req).expect("control request")
}

fn screenshot(socket: &Path, output: &str) -> image::RgbaImage {
    match control(socket, ControlRequest::Screenshot { output: output.into() }) {
        ControlReply::Image { width, height, rgba } => image::RgbaImage::from_raw(width, height, rgba.0).expect("size"),
        other => panic!("screenshot: {other:?}"),
    }
}

fn rgb(img: &image::RgbaImage, x: u32, y: u32) -> [u8; 3] {
    let p = img.get_pixel(x, y).0;
    [p[0], p[1], p[2]]
}

fn list(socket: &Path) -> (Vec<strata_protocol::control::OutputRow>, Vec<strata_protocol::control::SurfaceRow>) {
    match control(socket, ControlRequest::List) {
        ControlReply::List { outputs, surfaces, .. } => (outputs, surfaces),
        other => panic!("list: {other:?}"),
    }
}

#[test]
fn fast_clients_never_show_a_torn_frame() {
    let daemon = Daemon::start("torn", &["--lighting", "off", "--output", "t=256x128", "--refresh-hz", "240"]);
    let socket = daemon.socket.clone();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    // One unthrottled client and one paced by the default interval of 1.
    let clients: Vec<_> = [(0, 0), (128, 1)]
        .into_iter()
        .map(|(x, interval)| {
            let socket = socket.clone();
            let stop = stop.clone();
            std::thread::spawn(move || {
                let mut gl = connect(&socket, &format!("fast-{interval}"));
                let cur = window(&mut gl, [x, 0, 128, 128], 0.5, interval);
                let mut f = 1;
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    two_half_frame(&mut gl, cur, 128, f);
                    f += 1;
                }
                f - 1
            })
        })
        .collect();
    let mut seen = std::collections::HashSet::new();
    for _ in 0..40 {
        let img = screenshot(&socket, "t");
        for x0 in [0u32, 128] {
            let (bottom, top) = (rgb(&img, x0 + 64, 100), rgb(&img, x0 + 64, 20));
            assert_eq!(bottom, top, "surface at x {x0}: a torn frame (two halves differ)");
            if bottom != [0, 0, 0] {
                assert!((1..5000).any(|f| frame_color(f) == bottom), "{bottom:?} is no frame's colour");
                seen.insert((x0, bottom));
            }
        }
        std::thread::sleep(Duration::from_millis(15));
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let frames: Vec<u32> = clients.into_iter().map(|c| c.join().expect("client")).collect();
    assert!(frames.iter().all(|&f| f > 5), "clients drew too few frames: {frames:?}");
    // The screenshots caught the clients in several different frames, so the check above
    // looked at frames being replaced, not at one frame standing still.
    for x0 in [0u32, 128] {
        let n = seen.iter().filter(|(x, _)| *x == x0).count();
        assert!(n >= 3, "surface at x {x0}: only {n} distinct frames seen");
    }
}

#[test]
fn swaps_are_paced_by_frames_in_flight_and_interval() {
    let daemon = Daemon::start(
        "paced",
        &["--lighting", "off", "--output", "p=128x128", "--refresh-hz", "30", "--frames-in-flight", "2"],
    );
    let socket = daemon.socket.clone();
    let mut gl = connect(&socket, "paced");
    let cur = window(&mut gl, [0, 0, 64, 64], 0.5, 1);
    // Interval 1: at most one swap per refresh, never more than K = 2 frames unshown.
    let start = Instant::now();
    for f in 1..=20 {
        clear(&mut gl, frame_color(f));
        swap(&mut gl, cur);
        let (_, s) = list(&socket);
        assert!(s[0].frames - s[0].shown <= 2, "{} frames in flight, K is 2", s[0].frames - s[0].shown);
    }
    let paced = start.elapsed();
    // 20 swaps need at least 17 refreshes after the first at 30 Hz.
    assert!(paced >= Duration::from_secs_f64(17.0 / 30.0), "20 paced swaps took only {paced:?}");
    // Interval 0: swaps do not wait for the compositor, which skips to the newest frame.
    gl.eglSwapInterval(cur.display, 0).expect("io").expect("eglSwapInterval");
    let (o, _) = list(&socket);
    let before = o[0].composites;
    for f in 21..=220 {
        clear(&mut gl, frame_color(f));
        swap(&mut gl, cur);
    }
    gl.glFinish().expect("io");
    let (o, s) = list(&socket);
    assert_eq!(s[0].frames, 220);
    let composites = o[0].composites - before;
    assert!(composites < 150, "200 unthrottled swaps were each composited ({composites} composites)");
    // The compositor catches up with the newest frame.
    let img = screenshot(&socket, "p");
    assert_eq!(rgb(&img, 32, 32), frame_color(220));
    assert_eq!(list(&socket).1[0].shown, 220);
}

#[test]
fn stalled_client_stays_visible_and_a_departed_one_goes() {
    let daemon = Daemon::start("stall", &["--lighting", "off", "--output", "s=128x64"]);
    let socket = daemon.socket.clone();
    let mut stalled = connect(&socket, "stalled");
    let cs = window(&mut stalled, [0, 0, 64, 64], 0.5, 1);
    for f in 1..=3 {
        clear(&mut stalled, frame_color(f));
        swap(&mut stalled, cs);
    }
    // It starts a fourth frame and then stops swapping.
    clear(&mut stalled, [255, 0, 0]);
    stalled.glFinish().expect("io");
    let runner = {
        let socket = socket.clone();
        std::thread::spawn(move || {
            let mut gl = connect(&socket, "runner");
            let cur = window(&mut gl, [64, 0, 64, 64], 0.5, 0);
            let start = Instant::now();
            let mut f = 100;
            while start.elapsed() < Duration::from_millis(800) {
                clear(&mut gl, frame_color(f));
                swap(&mut gl, cur);
                f += 1;
            }
            // Its last swap is published once its work completes: glFinish waits for that,
            // so that the screenshot below cannot race the frame-waiter under load.
            gl.glFinish().expect("io");
            // Hand the connection back: the surface lives as long as its client.
            (gl, f - 1)
        })
    };
    for _ in 0..10 {
        let img = screenshot(&socket, "s");
        assert_eq!(rgb(&img, 32, 32), frame_color(3), "the stalled client's last complete frame must stay");
        std::thread::sleep(Duration::from_millis(50));
    }
    let (_runner, last) = runner.join().expect("runner");
    let img = screenshot(&socket, "s");
    assert_eq!(rgb(&img, 96, 32), frame_color(last));
    // The stalled client disconnects mid-frame: its surface is gone at the next composite,
    // and nothing else changes.
    drop(stalled);
    let deadline = Instant::now() + Duration::from_secs(10);
    while !list(&socket).1.iter().all(|s| s.client != "stalled") {
        assert!(Instant::now() < deadline, "the departed client's surface stayed listed");
        std::thread::sleep(Duration::from_millis(20));
    }
    let img = screenshot(&socket, "s");
    assert_eq!(rgb(&img, 32, 32), [0, 0, 0], "the departed client's surface is still composited");
    assert_eq!(rgb(&img, 96, 32), frame_color(last));
}

fn ctl(socket: &Path, args: &[&str]) -> Result<serde_json::Value, String> {
    let out = std::process::Command::new(support::stratad())
        .args(["ctl", "--json", "--socket"])
        .arg(socket)
        .args(args)
        .output()
        .expect("stratad ctl");
    if out.status.success() {
        serde_json::from_slice(&out.stdout)
            .map_err(|e| format!("not JSON ({e}): {}", String::from_utf8_lossy(&out.stdout)))
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

fn composites(socket: &Path, output: usize) -> u64 {
    ctl(socket, &["list"]).expect("list")["outputs"][output]["composites"].as_u64().expect("composites")
}

#[test]
fn ctl_moves_lights_and_screenshots_and_recomposites_only_on_change() {
    // Two outputs side by side in one output space.
    let daemon = Daemon::start("ctl", &["--lighting", "off", "--output", "a=128x64", "--output", "b=128x64+128+0"]);
    let socket = daemon.socket.clone();
    let mut gl = connect(&socket, "mover");
    let cur = window(&mut gl, [16, 8, 32, 32], 0.5, 1);
    let color = [200, 120, 40];
    clear(&mut gl, color);
    swap(&mut gl, cur);
    gl.glFinish().expect("io");
    let list = ctl(&socket, &["list"]).expect("list");
    let id = list["surfaces"][0]["id"].as_u64().expect("surface id");
    assert_eq!(list["surfaces"][0]["client"], "mover");
    assert_eq!(list["outputs"][1]["rect"], serde_json::json!([128, 0, 128, 64]));
    let a = screenshot(&socket, "a");
    assert_eq!(rgb(&a, 20, 20), color);
    // The client's command stream is counted: another frame adds to it.
    let streamed = |socket: &Path| ctl(socket, &["list"]).expect("list")["surfaces"][0]["stream_bytes"].as_u64();
    let sent = streamed(&socket).expect("ctl list reports the stream bytes");
    assert!(sent > 0, "the client's commands were not counted");
    clear(&mut gl, color);
    swap(&mut gl, cur);
    gl.glFinish().expect("io");
    assert!(streamed(&socket).is_some_and(|now| now > sent), "a frame's commands were not counted");
    // That frame is composited before the idle check below.
    screenshot(&socket, "a");

    // Nothing changes: nothing is recomposited, and no compositing time is spent.
    let idle = composites(&socket, 0);
    let busy = |socket: &Path| ctl(socket, &["list"]).expect("list")["outputs"][0]["composite_us"].as_u64();
    let idle_us = busy(&socket).expect("ctl list reports the time spent compositing");
    assert!(idle_us > 0, "composites so far took no time");
    std::thread::sleep(Duration::from_millis(300));
    assert_eq!(composites(&socket, 0), idle, "the compositor redrew an unchanged scene");
    assert_eq!(busy(&socket), Some(idle_us), "time was spent compositing an unchanged scene");

    // Move it across the boundary between the outputs.
    let moved = ctl(&socket, &["move", &id.to_string(), "112", "20", "0.25"]).expect("move");
    assert_eq!(moved["rect"], serde_json::json!([112, 20, 32, 32]));
    assert_eq!(moved["z"], 0.25);
    let (a, b) = (screenshot(&socket, "a"), screenshot(&socket, "b"));
    assert!(composites(&socket, 0) > idle, "a move must recomposite");
    // Only what changed was redrawn: the old and new places' bounding box, in each output.
    let outputs = ctl(&socket, &["list"]).expect("list")["outputs"].clone();
    assert_eq!(outputs[0]["region"], serde_json::json!([16, 8, 112, 44]));
    assert_eq!(outputs[1]["region"], serde_json::json!([0, 8, 16, 44]));
    assert_eq!(rgb(&a, 20, 20), [0, 0, 0], "the old position is still drawn");
    assert_eq!(rgb(&a, 120, 30), color, "output a shows the left part");
    assert_eq!(rgb(&b, 10, 30), color, "output b shows the right part");
    assert_eq!(rgb(&b, 20, 30), [0, 0, 0]);

    // Lighting on and off at run time.
    let on = ctl(&socket, &["light", "on"]).expect("light on");
    assert_eq!(on["enabled"], true);
    let lit = rgb(&screenshot(&socket, "a"), 120, 30);
    assert_ne!(lit, color, "lighting on changed nothing");
    // Per-surface normals: tilting this surface's normal changes its lighting, and both
    // colours follow the f64 reference compositor.
    let tilted_normal = [0.6f32, -0.3, 1.0];
    let n = ctl(&socket, &["normal", &id.to_string(), "0.6,-0.3,1"]).expect("normal");
    assert_eq!(n["id"], id);
    let tilted = rgb(&screenshot(&socket, "a"), 120, 30);
    assert_ne!(tilted, lit, "a tilted normal changed nothing");
    for (normal, got) in [([0.0, 0.0, 1.0], lit), (tilted_normal, tilted)] {
        let layer = reference::RefLayer {
            rect: [112, 20, 32, 32],
            z: 0.25,
            color: [color[0], color[1], color[2], 255].repeat(32 * 32),
            depth: None,
            normal,
            projection: None,
            props: Default::default(),
        };
        let want = reference::composite(&[layer], 128, 64, [0.0, 0.0, 0.0, 1.0], &Lighting::default());
        let p = ((30 * 128 + 120) * 4) as usize;
        for c in 0..3 {
            assert!(got[c].abs_diff(want[p + c]) <= 1, "normal {normal:?}: {got:?}, reference {:?}", &want[p..p + 3]);
        }
    }
    let e = ctl(&socket, &["normal", &id.to_string(), "0,0,0"]).expect_err("zero normal");
    assert!(e.contains("must be finite and not zero"), "{e}");
    let set = ctl(&socket, &["light", "set", "--ambient", "1", "--position", "-1,0.5,3"]).expect("light set");
    assert_eq!(set["ambient"], 1.0);
    assert_eq!(set["position"], serde_json::json!([-1.0, 0.5, 3.0]));
    let off = ctl(&socket, &["light", "off"]).expect("light off");
    assert_eq!(off["ambient"], 1.0, "turning lighting off must keep its settings");
    assert_eq!(rgb(&screenshot(&socket, "a"), 120, 30), color);

    // Bad requests get clear errors and change nothing.
    let e = ctl(&socket, &["move", "999", "0", "0", "0"]).expect_err("no surface 999");
    assert!(e.contains("no surface 999"), "{e}");
    let e = ctl(&socket, &["light", "set", "--ambient", "2"]).expect_err("ambient 2");
    assert!(e.contains("ambient 2 must lie in [0, 1]"), "{e}");
    let e = ctl(&socket, &["move", &id.to_string(), "0", "0", "NaN"]).expect_err("NaN z");
    assert!(e.contains("not a finite number"), "{e}");
    let png = daemon.dir.0.join("x.png");
    let e = ctl(&socket, &["screenshot", "nosuch", png.to_str().expect("utf-8")]).expect_err("no output");
    assert!(e.contains("outputs: a, b"), "{e}");
    let ok = ctl(&socket, &["screenshot", "b", png.to_str().expect("utf-8")]).expect("screenshot");
    assert_eq!(ok["width"], 128);
    assert_eq!(rgb(&image::open(&png).expect("png").to_rgba8(), 10, 30), color);
}

#[test]
fn bad_window_surfaces_get_egl_errors() {
    let daemon = Daemon::start("badwin", &["--output", "w=64x64"]);
    let mut gl = connect(&daemon.socket, "badwin");
    let d = gl.eglGetDisplay(0).expect("io");
    gl.eglInitialize(d).expect("io").expect("eglInitialize");
    let attribs = [0x3033, 0x0004, 0x3038];
    let config = gl.eglChooseConfig(d, strata_protocol::Slice::new(&attribs), 1).expect("io").expect("config")[0];
    const EGL_BAD_NATIVE_WINDOW: i32 = 0x300B;
    let none = [0x3038];
    for (what, w, h, z) in [
        ("zero width", 0, 16, 0.0),
        ("negative height", 16, -1, 0.0),
        ("wider than the largest texture", 8193, 16, 0.0),
        ("taller than the largest texture", 16, 1 << 20, 0.0),
        ("NaN z", 16, 16, f32::NAN),
        ("infinite z", 16, 16, f32::INFINITY),
    ] {
        let r = gl.eglCreateWindowSurface(d, config, 0, 0, 0, z, w, h, strata_protocol::Slice::new(&none)).expect("io");
        assert_eq!(r, Err(EGL_BAD_NATIVE_WINDOW), "{what}");
    }
    assert!(list(&daemon.socket).1.is_empty(), "a refused surface was listed");
    // The connection is still good.
    let ok = gl.eglCreateWindowSurface(d, config, 0, 0, 0, 0.5, 8192, 16, strata_protocol::Slice::new(&none));
    assert!(ok.expect("io").is_ok(), "the largest allowed window was refused");
    assert_eq!(list(&daemon.socket).1.len(), 1);
}

#[test]
fn daemon_layout_places_clients_by_name() {
    let dir = support::TempDir::new("layout-config");
    let config = dir.0.join("stratad.toml");
    std::fs::write(&config, "[[layout]]\nclient = \"hu-app\"\nx = 300\ny = 10\nz = 0.75\nwidth = 64\nheight = 32\n")
        .expect("config");
    let cfg = config.to_str().expect("utf-8");
    let daemon = Daemon::start("layout", &["--output", "l=512x256", "--layout", "ic-app=100,50,0.25", "--config", cfg]);
    let open = |name: &str, placement: Option<strata_protocol::handshake::Placement>| {
        let mut gl = Connection::connect(&ConnectOptions {
            socket: daemon.socket.clone(),
            name: name.into(),
            placement,
            ..Default::default()
        })
        .expect("connect");
        window(&mut gl, [0, 0, 40, 40], 0.9, 1);
        gl
    };
    let _ic = open("ic-app", None);
    let _hu = open("hu-app", None);
    let _other = open("other", None);
    // A client that states its placement keeps it, even when the layout names it.
    let stated = strata_protocol::handshake::Placement { x: 5, y: 6, z: 0.9, width: 40, height: 40 };
    let _pinned = open("ic-app", Some(stated));
    let rows = list(&daemon.socket).1;
    let by = |i: usize| (rows[i].client.as_str(), rows[i].rect, rows[i].z);
    assert_eq!(by(0), ("ic-app", [100, 50, 40, 40], 0.25));
    assert_eq!(by(1), ("hu-app", [300, 10, 64, 32], 0.75));
    assert_eq!(by(2), ("other", [0, 0, 40, 40], 0.9));
    assert_eq!(by(3), ("ic-app", [0, 0, 40, 40], 0.9));

    // Bad layouts stop the daemon before it serves, saying why.
    for (args, why) in [
        (vec!["--layout", "ic=1,2"], "is not CLIENT=X,Y,Z[,WxH]"),
        (vec!["--config", "/nonexistent/stratad.toml"], "reading /nonexistent/stratad.toml"),
    ] {
        let out = std::process::Command::new(support::stratad())
            .args(["serve", "--socket"])
            .arg(dir.0.join("never.sock"))
            .args(&args)
            .output()
            .expect("stratad");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(why), "{args:?}: {err}");
    }
}

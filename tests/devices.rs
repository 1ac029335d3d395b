//! A device per client: each client renders on a device (and instance) of its own, so one
//! client's long frame never holds another's up; the device's driver threads run at the
//! client's class's nice value; at swap interval 0 a swap never waits for the compositor (the
//! compositor takes the newest complete frame); and a client whose device is lost is
//! disconnected alone while the others go on.

mod support;

use std::path::Path;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::Calls;
use strata_protocol::control::{ClientStats, DaemonStats};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use support::gl::{clear, connect, control, window, GL_SCISSOR_TEST};
use support::{stats, Daemon};

fn client<'a>(s: &'a DaemonStats, name: &str) -> &'a ClientStats {
    s.clients.iter().find(|c| c.name == name).unwrap_or_else(|| panic!("no client {name} in {s:?}"))
}

/// The client's device threads, once its session has opened the device.
fn device_threads(socket: &Path, name: &str) -> Vec<strata_protocol::control::DeviceThread> {
    let start = Instant::now();
    loop {
        let s = stats(socket);
        if let Some(d) = s.clients.iter().find(|c| c.name == name).and_then(|c| c.device.clone()) {
            return d.threads;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "client {name} never opened a device");
        std::thread::sleep(Duration::from_millis(20));
    }
}

fn screenshot(socket: &Path) -> image::RgbaImage {
    match control(socket, ControlRequest::Screenshot { output: String::new() }) {
        ControlReply::Image { width, height, rgba } => image::RgbaImage::from_raw(width, height, rgba.0).expect("size"),
        other => panic!("screenshot: {other:?}"),
    }
}

fn rgb(img: &image::RgbaImage, x: u32, y: u32) -> [u8; 3] {
    let p = img.get_pixel(x, y).0;
    [p[0], p[1], p[2]]
}

/// Waits until the output shows `want` at (x, y).
fn wait_for_pixel(socket: &Path, x: u32, y: u32, want: [u8; 3]) {
    let start = Instant::now();
    loop {
        let got = rgb(&screenshot(socket), x, y);
        if got == want {
            return;
        }
        assert!(start.elapsed() < Duration::from_secs(20), "({x}, {y}) shows {got:?}, never {want:?}");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The nice value of thread `tid` of process `pid`, read from /proc.
fn nice(pid: u32, tid: i32) -> Option<i32> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/task/{tid}/stat")).ok()?;
    stat.rsplit_once(')')?.1.split_whitespace().nth(16)?.parse().ok()
}

/// The scheduler slice (ns) of thread `tid` of process `pid`, where the kernel shows it.
fn slice(pid: u32, tid: i32) -> Option<u64> {
    let sched = std::fs::read_to_string(format!("/proc/{pid}/task/{tid}/sched")).ok()?;
    sched.lines().find(|l| l.starts_with("se.slice"))?.split(':').nth(1)?.trim().parse().ok()
}

/// Whether this kernel takes a thread's own slice (Linux 6.12 and later show and honour it).
fn kernel_takes_slices() -> bool {
    std::thread::spawn(|| {
        // SAFETY: gettid has no preconditions.
        let tid = unsafe { libc::gettid() };
        strata_device::set_thread_slice(0, Some(strata_device::HIGH_SLICE))
            && slice(std::process::id(), tid) == Some(strata_device::HIGH_SLICE.as_nanos() as u64)
    })
    .join()
    .unwrap_or(false)
}

/// The ids of process `pid`'s threads named `name`.
fn threads_named(pid: u32, name: &str) -> Vec<i32> {
    std::fs::read_dir(format!("/proc/{pid}/task"))
        .map(|d| {
            d.filter_map(|e| e.ok()?.file_name().to_str()?.parse().ok())
                .filter(|t: &i32| {
                    std::fs::read_to_string(format!("/proc/{pid}/task/{t}/comm")).is_ok_and(|c| c.trim_end() == name)
                })
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn one_clients_long_frame_never_holds_up_another() {
    let daemon = Daemon::start("parallel", &["--lighting", "off", "--output", "headless:p=128x64"]);
    let socket = daemon.socket.clone();
    // A: one long frame (hundreds of scissored clears of a large window, each a quad).
    let long = {
        let socket = socket.clone();
        std::thread::spawn(move || {
            let mut gl = connect(&socket, "long");
            egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 1024, height: 1024 }).expect("pbuffer");
            gl.glEnable(GL_SCISSOR_TEST).expect("io");
            gl.glScissor(0, 0, 1023, 1024).expect("io");
            for i in 0..600u32 {
                clear(&mut gl, [(i % 200) as u8, 10, 10]);
            }
            let start = Instant::now();
            gl.glFinish().expect("io");
            // The connection stays open until its device's figures are read.
            (start.elapsed(), gl)
        })
    };
    // B: short frames, each waited for, counted while A's frame runs.
    let mut gl = connect(&socket, "short");
    let cur = window(&mut gl, [64, 0, 64, 64], 0);
    let mut during = 0;
    let start = Instant::now();
    while !long.is_finished() {
        clear(&mut gl, [20, 200, 20]);
        gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
        gl.glFinish().expect("io");
        during += 1;
        assert!(start.elapsed() < Duration::from_secs(120), "the long frame never finished");
    }
    let (took, _long) = long.join().expect("long client");
    // On one shared queue every glFinish of B waits behind A's frame: B finishes at most a
    // frame or two while it runs. On devices of their own, B goes on.
    assert!(during >= 10, "the short client finished only {during} frames while the long one took {took:?}");
    wait_for_pixel(&socket, 96, 32, [20, 200, 20]);
    let s = stats(&socket);
    let (a, b) =
        (client(&s, "long").device.clone().expect("device"), client(&s, "short").device.clone().expect("device"));
    assert!(a.own && b.own, "each client has a device of its own");
    let tids = |d: &strata_protocol::control::DeviceStats| d.threads.iter().map(|t| t.tid).collect::<Vec<_>>();
    assert!(!tids(&a).is_empty(), "the device's driver threads are known");
    assert!(tids(&a).iter().all(|t| !tids(&b).contains(t)), "two clients share device threads");
    // Each device's busy time is its own client's work.
    assert!(
        a.busy_us > b.busy_us,
        "the long frame's device was busy {} µs, the short ones' {} µs",
        a.busy_us,
        b.busy_us
    );
}

#[test]
fn a_class_sets_the_nice_value_of_its_device_threads() {
    let dir = support::TempDir::new("nice");
    let config = dir.0.join("strata.toml");
    std::fs::write(
        &config,
        "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\npriority = \"high\"\n\n\
         [[layout]]\nclient = \"hu\"\nx = 64\ny = 0\nz = 0.5\npriority = \"low\"\n",
    )
    .expect("config");
    let daemon = Daemon::start("nice", &["--output", "headless:n=128x64", "--config", config.to_str().expect("path")]);
    let socket = daemon.socket.clone();
    let pid = daemon.child.id();
    let _ic = connect(&socket, "ic");
    let _hu = connect(&socket, "hu");
    // Mesa's own shader-cache thread lowers itself; the rasterizer and queue threads inherit.
    let driver = |t: &&strata_protocol::control::DeviceThread| !t.name.contains(":disk");
    let niced = |name: &str| -> Vec<i32> {
        let threads = device_threads(&socket, name);
        let own: Vec<i32> = threads.iter().filter(driver).map(|t| nice(pid, t.tid).expect("thread alive")).collect();
        assert!(!own.is_empty(), "{name}'s device has no driver threads: {threads:?}");
        own
    };
    let hu = niced("hu");
    assert!(hu.iter().all(|&n| n == 19), "the low-priority client's device threads run at {hu:?}, not 19");
    let ic = niced("ic");
    assert!(ic.iter().all(|&n| n <= 0), "the high-priority client's device threads run at {ic:?}");
    let comp = stats(&socket).compositor_device.expect("compositor device");
    let comp_threads: Vec<i32> = comp.threads.iter().filter(driver).map(|t| t.tid).collect();
    let comp: Vec<i32> = comp_threads.iter().map(|&t| nice(pid, t).expect("alive")).collect();
    assert!(!comp.is_empty() && comp.iter().all(|&n| n <= 0), "the compositor's device threads run at {comp:?}");
    // The high class's threads ask for the short slice: the compositor's thread and device
    // threads, and the high-priority client's device threads; the low class's do not.
    if !kernel_takes_slices() {
        eprintln!("SKIPPED the slice checks: this kernel does not take a thread's own slice");
        return;
    }
    let short = strata_device::HIGH_SLICE.as_nanos() as u64;
    let compositor = threads_named(pid, "compositor");
    assert_eq!(compositor.len(), 1, "one compositor thread");
    let ic_threads: Vec<i32> = device_threads(&socket, "ic").iter().filter(driver).map(|t| t.tid).collect();
    for &t in compositor.iter().chain(&comp_threads).chain(&ic_threads) {
        assert_eq!(slice(pid, t), Some(short), "high-class thread {t} runs with the kernel's slice");
    }
    let hu_threads: Vec<i32> = device_threads(&socket, "hu").iter().filter(driver).map(|t| t.tid).collect();
    for &t in &hu_threads {
        assert_ne!(slice(pid, t), Some(short), "low-class thread {t} has the high class's slice");
    }
}

#[test]
fn at_interval_0_a_swap_never_waits_for_the_compositor() {
    // One composite a second: a swap that waited for the compositor would take a second.
    let daemon = Daemon::start("mailbox", &["--lighting", "off", "--output", "headless:m=64x64", "--refresh-hz", "1"]);
    let socket = daemon.socket.clone();
    let mut gl = connect(&socket, "mailbox");
    let cur = window(&mut gl, [0, 0, 64, 64], 0);
    clear(&mut gl, [1, 2, 3]);
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
    wait_for_pixel(&socket, 32, 32, [1, 2, 3]);
    let composites = |s: &Path| match control(s, ControlRequest::List) {
        ControlReply::List { outputs, .. } => outputs[0].composites,
        other => panic!("list: {other:?}"),
    };
    let before = composites(&socket);
    let frames = 60u32;
    for f in 0..frames {
        clear(&mut gl, [(f * 3 % 250) as u8 + 1, 100, 50]);
        gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
    }
    gl.glFinish().expect("io");
    let during = composites(&socket) - before;
    // Swaps that waited for composites (one a second) would have let at least one happen for
    // every few frames; swaps that never wait are done before more than a few are due.
    assert!(during < 10, "{during} composites for {frames} swaps: swaps waited for the compositor");
    // The newest frame is what shows; frames the compositor never took were dropped.
    let last = [((frames - 1) * 3 % 250) as u8 + 1, 100, 50];
    wait_for_pixel(&socket, 32, 32, last);
    let rows = match control(&socket, ControlRequest::List) {
        ControlReply::List { surfaces, .. } => surfaces,
        other => panic!("list: {other:?}"),
    };
    assert_eq!(rows[0].frames, u64::from(frames) + 1, "every swapped frame completed and was published");
}

#[test]
fn a_lost_device_ends_its_client_alone() {
    let daemon =
        Daemon::start("lost", &["--lighting", "off", "--output", "headless:l=192x64", "--allow-fault-injection"]);
    let socket = daemon.socket.clone();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    // Three clients draw their own colour, frame after frame.
    let colours = [[200u8, 0, 0], [0, 200, 0], [0, 0, 200]];
    let clients: Vec<_> = colours
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            let (socket, stop) = (socket.clone(), stop.clone());
            std::thread::spawn(move || {
                let mut gl = connect(&socket, &format!("c{i}"));
                let cur = window(&mut gl, [64 * i as i32, 0, 64, 64], 1);
                let mut frames = 0u64;
                while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    clear(&mut gl, c);
                    match gl.eglSwapBuffers(cur.display, cur.surface) {
                        Ok(Ok(())) => frames += 1,
                        Ok(Err(e)) => return Err(format!("EGL error {e:#x} after {frames} frames")),
                        Err(e) => return Err(format!("connection: {e} after {frames} frames")),
                    }
                }
                Ok(frames)
            })
        })
        .collect();
    for (i, c) in colours.iter().enumerate() {
        wait_for_pixel(&socket, 64 * i as u32 + 32, 32, *c);
    }
    let victim = client(&stats(&socket), "c1").id;
    match control(&socket, ControlRequest::LoseDevice { client: victim }) {
        ControlReply::Stats(_) => {}
        other => panic!("lose-device: {other:?}"),
    }
    // The victim's session ends and its surface goes; the others keep drawing and showing.
    let start = Instant::now();
    while stats(&socket).clients.iter().any(|c| c.id == victim) {
        assert!(start.elapsed() < Duration::from_secs(20), "the client of the lost device was never disconnected");
        std::thread::sleep(Duration::from_millis(20));
    }
    wait_for_pixel(&socket, 96, 32, [0, 0, 0]);
    let frames = |name: &str| {
        let s = stats(&socket);
        let id = client(&s, name).id;
        match control(&socket, ControlRequest::List) {
            ControlReply::List { surfaces, .. } => surfaces.iter().find(|r| r.client_id == id).map_or(0, |r| r.frames),
            other => panic!("list: {other:?}"),
        }
    };
    let before = (frames("c0"), frames("c2"));
    std::thread::sleep(Duration::from_millis(300));
    let after = (frames("c0"), frames("c2"));
    assert!(after.0 > before.0 && after.1 > before.1, "the other clients stopped: {before:?} → {after:?}");
    for i in [0, 2] {
        wait_for_pixel(&socket, 64 * i as u32 + 32, 32, colours[i]);
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let ends: Vec<Result<u64, String>> = clients.into_iter().map(|h| h.join().expect("client thread")).collect();
    assert!(ends[0].is_ok() && ends[2].is_ok(), "a bystander failed: {ends:?}");
    assert!(ends[1].is_err(), "the client of the lost device was not told: {ends:?}");
    assert!(daemon.log_text().contains("its GPU device was lost"), "the log does not say why");
}

/// The output of `stratad demo`'s two clients (a dial and a map block intersecting per
/// fragment) under a daemon started with `extra`.
fn demo_image(tag: &str, extra: &[&str]) -> (image::RgbaImage, String) {
    use std::io::BufRead;
    let (w, h) = strata_server::demo::OUTPUT;
    let output = format!("headless:demo={w}x{h}");
    let mut args = vec!["--output", output.as_str()];
    args.extend_from_slice(extra);
    let daemon = Daemon::start(tag, &args);
    let mut kids: Vec<std::process::Child> = ["ic", "hu"]
        .iter()
        .map(|role| {
            std::process::Command::new(support::stratad())
                .args(["demo-client", "--role", role, "--frames", "2", "--socket"])
                .arg(&daemon.socket)
                .stdin(std::process::Stdio::piped())
                .stdout(std::process::Stdio::piped())
                .spawn()
                .expect("demo client")
        })
        .collect();
    for k in &mut kids {
        let mut line = String::new();
        std::io::BufReader::new(k.stdout.take().expect("stdout")).read_line(&mut line).expect("read");
        assert_eq!(line.trim(), "ready", "a demo client failed");
    }
    let img = screenshot(&daemon.socket);
    for mut k in kids {
        drop(k.stdin.take());
        let _ = k.wait();
    }
    (img, daemon.log_text())
}

#[test]
fn frames_copied_through_host_memory_composite_as_shared_ones_do() {
    let (shared, log) = demo_image("transfer-auto", &[]);
    assert!(!log.contains("copied through host memory"), "lavapipe shares images, yet frames were copied:\n{log}");
    let (copied, log) = demo_image("transfer-copy", &["--frame-transfer", "copy"]);
    assert!(log.contains("copied through host memory"), "the copy was not logged:\n{log}");
    let differ = shared.pixels().zip(copied.pixels()).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} pixels differ between shared and copied frames");
    // Both clients show, and they meet per fragment: the dial's orange and the map's blue.
    let orange = shared.pixels().filter(|p| u16::from(p[0]) > u16::from(p[2]) + 40).count();
    let blue = shared.pixels().filter(|p| u16::from(p[2]) > u16::from(p[0]) + 40).count();
    assert!(orange > 1000 && blue > 1000, "orange {orange}, blue {blue}");
}

#[test]
fn clients_beyond_the_device_limit_share_the_compositors_device() {
    let daemon =
        Daemon::start("limit", &["--lighting", "off", "--output", "headless:m=128x64", "--max-client-devices", "1"]);
    let socket = daemon.socket.clone();
    let own = |name: &str| {
        let start = Instant::now();
        loop {
            let s = stats(&socket);
            if let Some(d) = s.clients.iter().find(|c| c.name == name).and_then(|c| c.device.clone()) {
                return d.own;
            }
            assert!(start.elapsed() < Duration::from_secs(20), "{name} never got a device");
            std::thread::sleep(Duration::from_millis(20));
        }
    };
    let mut a = connect(&socket, "a");
    let ca = window(&mut a, [0, 0, 64, 64], 1);
    assert!(own("a"), "the first client has a device of its own");
    let mut b = connect(&socket, "b");
    let cb = window(&mut b, [64, 0, 64, 64], 1);
    assert!(!own("b"), "the second client shares the compositor's device");
    for (gl, cur, c) in [(&mut a, ca, [200, 40, 40]), (&mut b, cb, [40, 200, 40])] {
        clear(gl, c);
        gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
    }
    wait_for_pixel(&socket, 32, 32, [200, 40, 40]);
    wait_for_pixel(&socket, 96, 32, [40, 200, 40]);
    assert!(daemon.log_text().contains("shares the compositor's device"), "the fallback is not logged");
    // The first client's place is free again once it leaves.
    drop(a);
    let start = Instant::now();
    while stats(&socket).clients.len() > 1 {
        assert!(start.elapsed() < Duration::from_secs(20), "the first client never left");
        std::thread::sleep(Duration::from_millis(20));
    }
    let _c = connect(&socket, "c");
    assert!(own("c"), "a later client takes the freed place");
}

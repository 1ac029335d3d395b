//! Devices under bad input: clients that connect and never draw, 64 clients connecting at
//! once, clients killed with SIGKILL while the compositor reads their frames, and 200 sessions
//! come and gone. A bystander's every checked frame shows as it drew it, and afterwards the
//! daemon holds no more file descriptors, devices or shared images than before.

mod support;

use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, Current, SurfaceKind};
use strata_client::{Calls, Connection};
use strata_protocol::handshake::{ControlReply, ControlRequest};
use support::gl::{clear, connect, control};
use support::{stats, Daemon};

fn window(gl: &mut Connection, rect: [i32; 4]) -> Current {
    egl_context(gl, 24, 0, SurfaceKind::Window { rect, z: 0.5 }).expect("context")
}

fn frame(gl: &mut Connection, cur: Current, c: [u8; 3]) {
    clear(gl, c);
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
}

fn pixel(socket: &Path, x: u32, y: u32) -> [u8; 3] {
    match control(socket, ControlRequest::Screenshot { output: String::new() }) {
        ControlReply::Image { width, rgba, .. } => {
            let i = ((y * width + x) * 4) as usize;
            [rgba.0[i], rgba.0[i + 1], rgba.0[i + 2]]
        }
        other => panic!("screenshot: {other:?}"),
    }
}

/// Waits until the output shows `want` at (x, y).
fn wait_for_pixel(socket: &Path, x: u32, y: u32, want: [u8; 3]) {
    let start = Instant::now();
    while pixel(socket, x, y) != want {
        assert!(start.elapsed() < Duration::from_secs(30), "({x}, {y}) never showed {want:?}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Open file descriptors of process `pid`.
fn fds(pid: u32) -> usize {
    std::fs::read_dir(format!("/proc/{pid}/fd")).map(|d| d.count()).unwrap_or(0)
}

/// One client that makes a window, draws a frame and leaves: what the first session creates
/// once (the compositor's first composite, the disk cache) is then in place.
fn warm_up(socket: &Path) {
    let mut gl = connect(socket, "warm-up");
    let cur = window(&mut gl, [200, 0, 16, 16]);
    frame(&mut gl, cur, [1, 1, 1]);
    gl.glFinish().expect("io");
    let _ = pixel(socket, 0, 0);
}

/// Waits until the daemon has let every client but `keep` go, then returns its descriptors.
fn settled(daemon: &Daemon, keep: usize) -> usize {
    let start = Instant::now();
    while stats(&daemon.socket).clients.len() > keep {
        assert!(start.elapsed() < Duration::from_secs(60), "clients never left: {:?}", stats(&daemon.socket).clients);
        std::thread::sleep(Duration::from_millis(20));
    }
    // Departed sessions' threads close what they held as they end.
    std::thread::sleep(Duration::from_millis(300));
    fds(daemon.child.id())
}

/// A bystander drawing its frame number's colour into the left 32×32 pixels, checked by the
/// caller through screenshots.
struct Bystander {
    gl: Connection,
    cur: Current,
    frame: u32,
}

impl Bystander {
    fn new(socket: &Path) -> Bystander {
        let mut gl = connect(socket, "bystander");
        let cur = window(&mut gl, [0, 0, 32, 32]);
        Bystander { gl, cur, frame: 0 }
    }

    fn colour(f: u32) -> [u8; 3] {
        [(f * 37 % 200 + 40) as u8, (f * 91 % 200 + 40) as u8, 77]
    }

    /// Draws the next frame and checks the output shows it.
    fn step(&mut self, socket: &Path) {
        self.frame += 1;
        let c = Bystander::colour(self.frame);
        frame(&mut self.gl, self.cur, c);
        wait_for_pixel(socket, 16, 16, c);
    }
}

/// `stratad demo-client` drawing its window until killed.
fn demo_client(socket: &Path, role: &str) -> Child {
    Command::new(support::stratad())
        .args(["demo-client", "--role", role, "--frames", "100000", "--socket"])
        .arg(socket)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("demo client")
}

#[test]
fn clients_that_never_draw_or_all_come_at_once_leave_nothing_behind() {
    let daemon = Daemon::start("crowd", &["--lighting", "off", "--output", "headless:c=256x256"]);
    let socket = daemon.socket.clone();
    warm_up(&socket);
    let before = settled(&daemon, 0);
    let mut bystander = Bystander::new(&socket);
    bystander.step(&socket);
    let devices_before = stats(&socket).compositor_device.expect("compositor").threads.len();
    // A client that connects, makes a window surface and a context, and never draws.
    let mut idle = connect(&socket, "idle");
    let _idle_cur = window(&mut idle, [32, 0, 64, 64]);
    bystander.step(&socket);
    // 64 clients at once, each a window and one frame.
    let crowd: Vec<_> = (0..64)
        .map(|i| {
            let socket = socket.clone();
            std::thread::spawn(move || {
                let mut gl = connect(&socket, &format!("crowd-{i}"));
                let cur = window(&mut gl, [96 + (i % 8) * 16, (i / 8) * 16, 16, 16]);
                frame(&mut gl, cur, [200, 10, (i * 3) as u8]);
                gl.glFinish().expect("io");
                gl
            })
        })
        .collect();
    let crowd: Vec<Connection> = crowd.into_iter().map(|h| h.join().expect("a crowd client failed")).collect();
    let s = stats(&socket);
    assert_eq!(s.clients.len(), 66, "every client is connected");
    assert!(s.clients.iter().all(|c| c.device.as_ref().is_some_and(|d| d.own)), "each has a device of its own");
    for _ in 0..3 {
        bystander.step(&socket);
    }
    drop(crowd);
    drop(idle);
    bystander.step(&socket);
    settled(&daemon, 1);
    bystander.step(&socket);
    drop(bystander);
    let after = settled(&daemon, 0);
    assert_eq!(after, before, "descriptors before and after 66 clients came and went");
    let s = stats(&socket);
    assert_eq!(s.compositor_device.expect("compositor").threads.len(), devices_before);
    assert_eq!(s.gpu_bytes, 0, "memory still accounted to departed clients");
}

#[test]
fn clients_killed_while_their_frames_are_read_leave_nothing_behind() {
    let daemon = Daemon::start("killed", &["--lighting", "off", "--output", "headless:k=1920x720"]);
    let socket = daemon.socket.clone();
    warm_up(&socket);
    let before = settled(&daemon, 0);
    let mut bystander = Bystander::new(&socket);
    bystander.step(&socket);
    for round in 0..6u32 {
        let mut kids: Vec<Child> = ["ic", "hu"].iter().map(|r| demo_client(&socket, r)).collect();
        // Screenshots composite while the clients' frames arrive; kill them in between.
        let until = Instant::now() + Duration::from_millis(150 + 100 * u64::from(round % 3));
        while Instant::now() < until {
            bystander.step(&socket);
        }
        for k in &mut kids {
            let _ = k.kill();
            let _ = k.wait();
        }
        bystander.step(&socket);
    }
    drop(bystander);
    let after = settled(&daemon, 0);
    assert_eq!(after, before, "descriptors before and after clients were killed mid-frame");
}

#[test]
fn two_hundred_sessions_leak_no_descriptor_and_no_memory() {
    let daemon = Daemon::start("churn", &["--lighting", "off", "--output", "headless:s=256x64"]);
    let socket = daemon.socket.clone();
    let session = |i: u32| {
        let mut gl = connect(&socket, &format!("s{i}"));
        let cur = window(&mut gl, [64 + (i % 8) as i32 * 16, 0, 16, 16]);
        frame(&mut gl, cur, [10, (i % 250) as u8, 10]);
        if i.is_multiple_of(2) {
            frame(&mut gl, cur, [20, (i % 250) as u8, 20]);
        }
        gl.glFinish().expect("io");
    };
    let run = |from: u32, to: u32| {
        std::thread::scope(|s| {
            for lane in 0..4 {
                let session = &session;
                s.spawn(move || (from..to).filter(|i| i % 4 == lane).for_each(session));
            }
        });
    };
    // The daemon's heaps settle at a level that wanders by several MiB from one batch of
    // clients to the next (which threads freed what, where). The baseline is the highest level
    // over a warm-up of three batches, so that a leak shows as growth beyond that wander.
    let mut rss_before = 0;
    let mut fds_before = 0;
    for (from, to) in [(0, 20), (20, 40), (40, 60)] {
        run(from, to);
        fds_before = settled(&daemon, 0);
        rss_before = rss_before.max(stats(&socket).rss_bytes);
    }
    run(60, 260);
    let fds_after = settled(&daemon, 0);
    let s = stats(&socket);
    assert_eq!(fds_after, fds_before, "descriptors after 60 and after 260 sessions");
    assert!(s.sessions >= 260, "{} sessions", s.sessions);
    assert_eq!(s.gpu_bytes, 0, "memory still accounted to departed clients");
    // Each session opened an instance and a device of its own, mapped a segment, and shared
    // its window's images with the compositor: keeping any of these would cost far more than
    // the 80 KiB a session that this allows.
    let grown = s.rss_bytes.saturating_sub(rss_before);
    assert!(
        grown < 200 * (80 << 10),
        "resident memory grew {} KiB over 200 sessions ({rss_before} → {})",
        grown >> 10,
        s.rss_bytes
    );
}

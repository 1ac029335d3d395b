//! A hostile head unit takes nothing from the instrument cluster (docs/security.md), with real
//! processes under other users: an ID the configuration reserves for the cluster's user is
//! refused to anyone else, whenever they ask; a user bound to its entries by credentials keeps
//! their quota, class and placement whatever it calls itself; a user that opens sessions until
//! refused leaves the cluster a device of its own and its memory reserve.
//!
//! Starting processes as other users needs root; those tests say so and skip without it.

mod support;

use std::io::{BufRead, BufReader};
use std::os::unix::fs::PermissionsExt;
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, ChildStdout, Command, Stdio};

use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::control::Priority;
use support::scene::list;
use support::users::{root, IC_USER, NOBODY};
use support::windows::{Client, EGL_BAD_MATCH};
use support::{stats, Daemon, TempDir};

const GL_TEXTURE_2D: u32 = 0x0DE1;
const GL_RGBA: u32 = 0x1908;
const GL_UNSIGNED_BYTE: u32 = 0x1401;

#[test]
fn client_process() {
    support::windows::serve();
}

/// A daemon whose client socket other users' processes reach (group `nogroup`), configured
/// by `config`, with `args` besides.
fn vm_daemon(tag: &str, config: &str, args: &[&str]) -> (TempDir, Daemon, std::path::PathBuf) {
    let dir = TempDir::new(tag);
    std::fs::set_permissions(&dir.0, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    let shim = support::shim_dir(&dir);
    let path = dir.0.join("strata.toml");
    std::fs::write(&path, config).expect("config");
    let path = path.to_str().expect("utf-8").to_string();
    let mut all = vec!["--output", "t=64x48", "--lighting", "off", "--client-group", "nogroup", "--config", &path];
    all.extend_from_slice(args);
    let daemon = Daemon::start(tag, &all);
    (dir, daemon, shim)
}

#[test]
fn an_id_reserved_for_the_clusters_user_is_refused_to_others_and_then_given_to_the_cluster() {
    if !root() {
        return;
    }
    let config = "[[layout]]\nclient = \"instrument-cluster\"\nuser = \"daemon\"\nx = 0\ny = 0\nz = 0.5\nwidth = \
                  16\nheight = 16\npriority = \"high\"\nid = 1000\n\n[[surface]]\nid = 1000\nx = 40\ny = 8\n\n\
                  [[surface]]\nid = 2000\nuser = \"daemon\"\n";
    let (_dir, daemon, shim) = vm_daemon("hostile-ids", config, &[]);
    let socket = daemon.socket.clone();
    // The head unit starts first, asking for the cluster's ID three times, then for the ID a
    // [[surface]] entry reserves.
    let hu = Client::start_as(&socket, &shim, "instrument-cluster", 3, Some(1000), NOBODY);
    assert_eq!(hu.got, vec![Err(EGL_BAD_MATCH); 3], "the layout's reserved ID");
    let other = Client::start_as(&socket, &shim, "hu", 1, Some(2000), NOBODY);
    assert_eq!(other.got, vec![Err(EGL_BAD_MATCH)], "the [[surface]] entry's reserved ID");
    let log = daemon.log_text();
    let lines = |needle: &str| log.lines().filter(|l| l.contains(needle)).count();
    assert_eq!(
        lines("surface id 1000 is reserved by the [[layout]] \"instrument-cluster\" entry for clients with uid 1"),
        1,
        "logged once:\n{log}"
    );
    assert_eq!(lines("surface id 2000 is reserved by the [[surface]] 2000 entry for clients with uid 1"), 1, "{log}");
    // The cluster then gets its ID, its preset's placement and its class.
    let ic = Client::start_painting_as(
        &socket,
        &shim,
        "instrument-cluster",
        None,
        "8,8,0.5,16x16",
        [[1.0, 0.0, 0.0]; 2],
        Some(IC_USER),
    );
    assert_eq!(ic.got, vec![Ok(1000)]);
    let (rows, _) = list(&socket);
    let row = rows.iter().find(|r| r.id == 1000).expect("the cluster's surface");
    assert_eq!((row.peer.uid, row.rect, row.priority), (IC_USER.0, [40, 8, 16, 16], Priority::High));
    // An ID no entry reserves stays free to all.
    let free = Client::start_as(&socket, &shim, "hu", 1, Some(3000), NOBODY);
    assert_eq!(free.got, vec![Ok(3000)]);
    for c in [hu, other, ic, free] {
        c.stop();
    }
    daemon.stop();
}

#[test]
fn a_head_unit_renamed_to_escape_its_entries_still_gets_their_quota_class_and_place() {
    if !root() {
        return;
    }
    // The head unit's user is bound to its entries by credentials alone; a generous entry
    // names "x", which it calls itself.
    let config = "[[layout]]\nuser = \"nobody\"\nx = 32\ny = 16\nz = 0.5\nwidth = 16\nheight = 16\npriority = \
                  \"low\"\n\n[[quota]]\nuser = \"nobody\"\ngpu-bytes = \"4M\"\n\n[[quota]]\nclient = \"x\"\ngpu-bytes = \
                  \"1G\"\n\n[[layout]]\nclient = \"x\"\nx = 0\ny = 0\nz = 0.5\npriority = \"high\"\n";
    let (_dir, daemon, shim) = vm_daemon("hostile-rename", config, &[]);
    let socket = daemon.socket.clone();
    let hu = Client::start_painting_as(&socket, &shim, "x", None, "0,0,0.5,8x8", [[0.0, 1.0, 0.0]; 2], Some(NOBODY));
    let (rows, _) = list(&socket);
    let row = rows.iter().find(|r| r.peer.uid == NOBODY.0).expect("the head unit's surface");
    assert_eq!((row.rect, row.priority), ([32, 16, 16, 16], Priority::Low), "its entry's place and class");
    let s = stats(&socket);
    let c = s.clients.iter().find(|c| c.peer.uid == NOBODY.0).expect("the head unit");
    assert_eq!((c.name.as_str(), c.gpu_bytes_limit, c.priority), ("x", 4 << 20, Priority::Low), "its entry's quota");
    // A client of another user that calls itself "x" gets what names "x".
    let mut root_x = support::gl::connect(&socket, "x");
    let _cur = egl_context(&mut root_x, 0, 0, SurfaceKind::Pbuffer { width: 4, height: 4 }).expect("context");
    let s = stats(&socket);
    let c = s.clients.iter().find(|c| c.peer.uid == 0 && c.name == "x").expect("root's x");
    assert_eq!((c.gpu_bytes_limit, c.priority), (1 << 30, Priority::High));
    hu.stop();
    daemon.stop();
}

/// The head unit's process that opens sessions until the daemon refuses one, filling each
/// with textures until its memory is refused; it reports what it got and keeps its sessions
/// until its stdin closes.
#[test]
fn flood_process() {
    let Ok(socket) = std::env::var("STRATA_FLOOD_SOCKET") else { return };
    let mut sessions = Vec::new();
    let mut bytes = 0u64;
    let refusal = loop {
        let opts = ConnectOptions {
            socket: socket.clone().into(),
            name: format!("hu-{}", sessions.len()),
            ..Default::default()
        };
        let mut gl = match Connection::connect(&opts) {
            Ok(gl) => gl,
            Err(e) => break e.to_string(),
        };
        let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 4, height: 4 }).expect("context");
        bytes += fill(&mut gl, 512);
        sessions.push((gl, cur));
        assert!(sessions.len() < 1000, "never refused");
    };
    println!("flood sessions {} bytes {bytes} refused: {refusal}", sessions.len());
    let _ = std::io::stdin().lines().count();
}

/// Gives textures of `side`² RGBA8 images until one is refused (or 64 are made); the bytes
/// granted.
fn fill(gl: &mut Connection, side: i32) -> u64 {
    let mut granted = 0;
    for name in 1..=64 {
        gl.glBindTexture(GL_TEXTURE_2D, name).expect("io");
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, side, side, 0, GL_RGBA, GL_UNSIGNED_BYTE, None).expect("io");
        if gl.glGetError().expect("io") != 0 {
            break;
        }
        granted += (side * side * 4) as u64;
    }
    granted
}

/// The instrument cluster's process: one session, two 1024² textures, then it
/// reports the GL errors it got and keeps its session until its stdin closes.
#[test]
fn cluster_process() {
    let Ok(socket) = std::env::var("STRATA_CLUSTER_SOCKET") else { return };
    let opts = ConnectOptions { socket: socket.into(), name: "instrument-cluster".into(), ..Default::default() };
    let mut gl = Connection::connect(&opts).expect("the cluster connects");
    let _cur = egl_context(&mut gl, 0, 0, SurfaceKind::Pbuffer { width: 4, height: 4 }).expect("context");
    let mut errors = 0;
    for name in 1..=2 {
        gl.glBindTexture(GL_TEXTURE_2D, name).expect("io");
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA as i32, 1024, 1024, 0, GL_RGBA, GL_UNSIGNED_BYTE, None).expect("io");
        errors += u32::from(gl.glGetError().expect("io") != 0);
    }
    println!("cluster errors {errors}");
    let _ = std::io::stdin().lines().count();
}

/// One of this test binary's processes, running as another user.
struct Process {
    child: Child,
    out: BufReader<ChildStdout>,
}

impl Process {
    /// Closes its stdin, reads the rest of what it says, and checks it ends well.
    fn stop(mut self) {
        drop(self.child.stdin.take());
        let _ = std::io::copy(&mut self.out, &mut std::io::sink());
        assert!(self.child.wait().expect("wait").success());
    }
}

/// Starts this test binary's `which` process as `user` with `env` pointing at `socket`, and
/// reads its report line (the one starting with `starts`).
fn start(which: &str, env: &str, socket: &Path, user: (u32, u32), starts: &str) -> (Process, String) {
    let mut child = Command::new(std::env::current_exe().expect("test binary"))
        .args(["--exact", which, "--nocapture", "--test-threads", "1"])
        .env(env, socket)
        .uid(user.0)
        .gid(user.1)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("process");
    let mut out = BufReader::new(child.stdout.take().expect("stdout"));
    let mut line = String::new();
    while !line.contains(starts) {
        line.clear();
        assert!(out.read_line(&mut line).expect("output") > 0, "{which} said nothing");
    }
    let line = line[line.find(starts).unwrap_or(0)..].trim_end().to_string();
    (Process { child, out }, line)
}

#[test]
fn a_head_unit_opening_sessions_until_refused_leaves_the_cluster_its_device_and_its_reserve() {
    if !root() {
        return;
    }
    let config = "[[layout]]\nclient = \"instrument-cluster\"\nuser = \"daemon\"\nx = 0\ny = 0\nz = 0.5\npriority = \
                  \"high\"\n";
    let args = [
        "--max-sessions-per-uid",
        "6",
        "--max-client-devices",
        "7",
        "--reserve-devices",
        "1",
        "--quota-total-gpu-bytes",
        "40M",
        "--reserve-gpu-bytes",
        "16M",
    ];
    let (_dir, daemon, _shim) = vm_daemon("hostile-flood", config, &args);
    let socket = daemon.socket.clone();
    let (hu, report) = start("flood_process", "STRATA_FLOOD_SOCKET", &socket, NOBODY, "flood sessions");
    let words: Vec<&str> = report.split_whitespace().collect();
    let (sessions, bytes): (u64, u64) = (words[2].parse().expect("n"), words[4].parse().expect("bytes"));
    assert_eq!(sessions, 6, "{report}");
    assert!(report.contains("uid 65534 holds 6 sessions (--max-sessions-per-uid)"), "{report}");
    assert!(bytes <= 24 << 20, "the head unit holds {bytes} bytes, beyond the 24 MiB not reserved: {report}");
    // The cluster connects after the flood: on a device of its own, with its textures granted
    // from the reserve.
    let (ic, said) = start("cluster_process", "STRATA_CLUSTER_SOCKET", &socket, IC_USER, "cluster errors");
    assert_eq!(said, "cluster errors 0", "the cluster's memory was refused");
    let s = stats(&socket);
    let c = s.clients.iter().find(|c| c.peer.uid == IC_USER.0).expect("the cluster");
    assert!(c.device.as_ref().is_some_and(|d| d.own), "the cluster shares a device: {:?}", c.device);
    assert!(c.priority == Priority::High && c.gpu_bytes >= 8 << 20, "{c:?}");
    let hus: Vec<_> = s.clients.iter().filter(|c| c.peer.uid == NOBODY.0).collect();
    assert_eq!(hus.len(), 6);
    assert!(s.refused.get("sessions-per-uid").is_some_and(|&n| n >= 1), "{:?}", s.refused);
    daemon.wait_log("(--max-sessions-per-uid)");
    hu.stop();
    ic.stop();
    daemon.stop();
}

#[test]
fn half_open_connections_of_one_user_leave_the_door_open_to_the_cluster() {
    if !root() {
        return;
    }
    let config = "[[layout]]\nclient = \"instrument-cluster\"\nuser = \"daemon\"\nx = 0\ny = 0\nz = 0.5\npriority = \
                  \"high\"\n";
    let (_dir, daemon, _shim) = vm_daemon("hostile-half-open", config, &["--max-handshakes-per-uid", "8"]);
    let socket = daemon.socket.clone();
    // A hundred connections that never say a word: eight in their handshake, the rest waiting
    // their turn.
    let silent: Vec<std::os::unix::net::UnixStream> =
        (0..100).map(|_| std::os::unix::net::UnixStream::connect(&socket).expect("connect")).collect();
    // The cluster connects and renders meanwhile.
    let (ic, said) = start("cluster_process", "STRATA_CLUSTER_SOCKET", &socket, IC_USER, "cluster errors");
    assert_eq!(said, "cluster errors 0");
    // Each silent one is closed in time: those in their handshake when it times out, those whose
    // turn never came refused, saying why.
    let started = std::time::Instant::now();
    let mut refused = 0;
    for s in &silent {
        s.set_read_timeout(Some(std::time::Duration::from_secs(20))).expect("timeout");
        let reply: Result<strata_protocol::handshake::ServerMessage, _> =
            strata_protocol::handshake::read_message(&mut &*s, "refusal");
        match reply {
            Ok(r) => {
                let why = format!("{r:?}");
                assert!(why.contains("uid 0 has 8 handshakes in progress (--max-handshakes-per-uid)"), "{why}");
                refused += 1;
            }
            Err(e) => assert!(e.to_string().contains("fill whole buffer"), "not closed: {e}"),
        }
    }
    assert!(started.elapsed() < std::time::Duration::from_secs(15), "{:?}", started.elapsed());
    assert!(refused >= 80, "{refused} refused");
    let s = stats(&socket);
    let counted = s.refused.get("handshakes-per-uid").copied().unwrap_or(0);
    assert!(counted >= refused && counted <= 92, "{refused} seen refused, {counted} counted: {:?}", s.refused);
    let log = daemon.log_text();
    let lines = log.lines().filter(|l| l.contains("--max-handshakes-per-uid")).count();
    assert!((1..=4).contains(&lines), "{lines} lines about {refused} refusals:\n{log}");
    ic.stop();
    drop(silent);
    daemon.stop();
}

#[test]
fn a_layout_argument_that_would_shadow_an_entry_with_credentials_stops_the_daemon() {
    let dir = TempDir::new("hostile-shadow");
    let config = dir.0.join("strata.toml");
    std::fs::write(&config, "[[layout]]\nclient = \"ic\"\nuser = \"daemon\"\nx = 0\ny = 0\nz = 0.5\n").expect("config");
    let out = Command::new(support::stratad())
        .args(["serve", "--output", "t=8x8", "--layout", "ic=10,10,0.5", "--socket"])
        .arg(dir.0.join("s.sock"))
        .arg("--config")
        .arg(&config)
        .output()
        .expect("serve");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "it served");
    assert!(
        err.contains(
            "--layout \"ic\" would shadow the configuration's [[layout]] entry for \"ic\", which requires uid 1"
        ),
        "{err}"
    );
}

//! Who may do what (docs/security.md), with real processes running as other users: a client
//! of another uid renders through the client socket but cannot control the daemon; a client
//! that claims the instrument cluster's name under the wrong uid gets neither its class nor its
//! placement; no process of another uid opens a segment while clients come and go; and bad
//! input at the doors (a control request on the client socket, a render client on the control
//! socket, descriptors sent to the daemon, unknown users and groups) is refused clearly; and a
//! connection passed on by a process that has exited is served under that process's
//! credentials.
//!
//! Starting processes as other users needs root; those tests say so and skip without it.

mod support;

use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use strata_protocol::control::{Priority, SurfaceRow};
use support::scene::{ctl, list, png};
use support::users::{root, IC_USER, NOBODY};
use support::windows::{self, Client};
use support::{Daemon, TempDir};

/// A uid that no client runs as: the prober's.
const PROBER: (u32, u32) = (65533, 65533);

const RED: [f32; 3] = [1.0, 0.0, 0.0];
const GREEN: [f32; 3] = [0.0, 1.0, 0.0];

#[test]
fn client_process() {
    windows::serve();
}

/// The prober a test starts as another uid: it tries to open every segment it can name.
#[test]
fn probe_process() {
    let Ok(seconds) = std::env::var("STRATA_PROBE_SECONDS") else { return };
    let end = Instant::now() + Duration::from_secs_f64(seconds.parse().expect("seconds"));
    let (mut tried, mut opened) = (0u64, Vec::new());
    while Instant::now() < end {
        probe_round(&mut tried, &mut opened);
    }
    println!("probe: tried {tried} opened {}", opened.len());
    for o in opened.iter().take(5) {
        println!("probe: opened {o}");
    }
}

/// One pass over every name a segment could be opened by: each file in `/dev/shm`, and each
/// process's `/proc/PID/fd/N` and `/proc/PID/map_files/*`. An open counts if what it opened is
/// a Strata segment.
fn probe_round(tried: &mut u64, opened: &mut Vec<String>) {
    let mut attempt = |path: &Path| {
        *tried += 1;
        let Ok(f) = std::fs::File::open(path) else { return };
        use std::os::fd::AsRawFd;
        let what = std::fs::read_link(format!("/proc/self/fd/{}", f.as_raw_fd())).unwrap_or_default();
        let what = what.to_string_lossy();
        if what.starts_with("/memfd:strata") || what.starts_with("/dev/shm/strata") {
            opened.push(format!("{} ({what})", path.display()));
        }
    };
    for e in std::fs::read_dir("/dev/shm").into_iter().flatten().flatten() {
        attempt(&e.path());
    }
    let pids: Vec<u32> = std::fs::read_dir("/proc")
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().to_str()?.parse().ok())
        .filter(|&p| p != std::process::id())
        .collect();
    for pid in pids {
        for fd in 0..48 {
            attempt(Path::new(&format!("/proc/{pid}/fd/{fd}")));
        }
        for e in std::fs::read_dir(format!("/proc/{pid}/map_files")).into_iter().flatten().flatten() {
            attempt(&e.path());
        }
    }
}

/// A directory other users can reach, holding the drop-in libraries and a daemon whose client
/// socket is open to `nogroup` and whose configuration gives the name `instrument-cluster` to
/// user `daemon` alone: high class, a deadline, a fixed place.
fn vm_daemon(tag: &str) -> (TempDir, Daemon, std::path::PathBuf) {
    let dir = TempDir::new(tag);
    std::fs::set_permissions(&dir.0, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    let shim = support::shim_dir(&dir);
    let config = dir.0.join("strata.toml");
    std::fs::write(
        &config,
        "[[layout]]\nclient = \"instrument-cluster\"\nuser = \"daemon\"\nx = 0\ny = 0\nz = 0.5\nwidth = 16\nheight = \
         16\npriority = \"high\"\ndeadline = true\n\n[[quota]]\nclient = \"instrument-cluster\"\nuser = \
         \"daemon\"\ntextures = 64\n",
    )
    .expect("config");
    let config = config.to_str().expect("utf-8");
    let args = ["--output", "t=64x48", "--lighting", "off", "--client-group", "nogroup", "--config", config];
    let daemon = Daemon::start("identity", &args);
    (dir, daemon, shim)
}

/// `stratad ctl ARGS --socket SOCKET` run as `user`: its exit status and stderr.
fn ctl_as(user: (u32, u32), socket: &Path, args: &[&str]) -> (bool, String) {
    let out = Command::new(support::stratad())
        .arg("ctl")
        .args(args)
        .arg("--socket")
        .arg(socket)
        .uid(user.0)
        .gid(user.1)
        .output()
        .expect("ctl");
    (out.status.success(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// The surface row of the client running as `uid`.
fn row_of(rows: &[SurfaceRow], uid: u32) -> &SurfaceRow {
    rows.iter().find(|r| r.peer.uid == uid).unwrap_or_else(|| panic!("no surface of uid {uid}: {rows:?}"))
}

/// The colour of output pixel (x, y).
fn pixel(socket: &Path, shot: &Path, x: u32, y: u32) -> [u8; 3] {
    ctl(socket, &["screenshot", "t", shot.to_str().expect("utf-8")]);
    let (w, _, rgba) = png(shot);
    let i = ((y * w + x) * 4) as usize;
    [rgba[i], rgba[i + 1], rgba[i + 2]]
}

#[test]
fn a_client_of_another_uid_renders_but_cannot_control_the_daemon() {
    if !root() {
        return;
    }
    let (dir, daemon, shim) = vm_daemon("identity-uid");
    let socket = daemon.socket.clone();
    let control = strata_protocol::handshake::control_socket_for(&socket);
    // The client socket is open to the group, the control socket to the operator alone.
    let (c, k) = (std::fs::metadata(&socket).expect("socket"), std::fs::metadata(&control).expect("control"));
    assert_eq!((c.mode() & 0o777, c.gid()), (0o660, NOBODY.1), "client socket");
    assert_eq!((k.mode() & 0o777, k.uid()), (0o600, 0), "control socket");

    let hu = Client::start_painting_as(&socket, &shim, "hu", None, "32,16,0.5,16x16", [RED, GREEN], Some(NOBODY));
    // Its frame shows: green on top, red below (GL's bottom half), where it asked.
    let shot = dir.0.join("shot.png");
    assert_eq!(pixel(&socket, &shot, 40, 19), [0, 255, 0], "the top half of nobody's frame");
    assert_eq!(pixel(&socket, &shot, 40, 28), [255, 0, 0], "the bottom half of nobody's frame");
    let (rows, _) = list(&socket);
    let r = row_of(&rows, NOBODY.0);
    assert_eq!((r.client.as_str(), r.peer.gid, r.peer.unverified), ("hu", NOBODY.1, false));
    assert_eq!(r.peer.pid, hu.pid(), "the pid the kernel gave");
    let id = r.id.to_string();
    let text = ctl(&socket, &["list"]);
    assert!(text.contains(&format!("uid {} pid {}", NOBODY.0, hu.pid())), "ctl list shows uid and pid:\n{text}");

    // The same user cannot move it or take a screenshot: the control socket is not theirs.
    let theirs = dir.0.join("theirs.png");
    for args in [&["move", &id, "0", "0", "0.5"][..], &["screenshot", "t", theirs.to_str().expect("utf-8")]] {
        let (ok, err) = ctl_as(NOBODY, &socket, args);
        assert!(!ok && err.contains("Permission denied"), "nobody's ctl {args:?}: {err}");
    }
    assert!(!theirs.exists());
    // The operator can.
    ctl(&socket, &["move", &id, "0", "0", "0.5"]);
    assert_eq!(list(&socket).0.iter().find(|r| r.id.to_string() == id).map(|r| r.rect), Some([0, 0, 16, 16]));
    assert_eq!(pixel(&socket, &shot, 8, 3), [0, 255, 0], "moved by the operator");

    // Control requests on the client socket are refused, whoever sends them.
    match strata_client::ControlConnection::connect(&socket) {
        Err(strata_client::control::ControlError::Refused(why)) => {
            assert!(why.contains("control socket") && why.contains(&*control.to_string_lossy()), "{why}")
        }
        Ok(_) => panic!("a control connection on the client socket was served"),
        Err(e) => panic!("not a clear refusal: {e}"),
    }
    // And a render client on the control socket.
    let opts = strata_client::ConnectOptions { socket: control.clone(), ..Default::default() };
    let err = strata_client::Connection::connect(&opts).err().expect("a render client on the control socket");
    assert!(err.to_string().contains("client socket"), "{err}");
    hu.stop();
    daemon.stop();
}

#[test]
fn a_client_claiming_the_clusters_name_under_the_wrong_uid_gets_neither_its_class_nor_its_place() {
    if !root() {
        return;
    }
    let (_dir, daemon, shim) = vm_daemon("identity-name");
    let socket = daemon.socket.clone();
    let name = "instrument-cluster";
    // Both state a placement of their own; the entry's is fixed for the genuine one.
    let ic = Client::start_painting_as(&socket, &shim, name, None, "40,30,0.5,16x16", [RED, GREEN], Some(IC_USER));
    let fake = Client::start_painting_as(&socket, &shim, name, None, "24,30,0.5,16x16", [RED, GREEN], Some(NOBODY));
    let (rows, _) = list(&socket);
    let genuine = row_of(&rows, IC_USER.0);
    assert_eq!((genuine.priority, genuine.deadline, genuine.rect), (Priority::High, true, [0, 0, 16, 16]));
    assert!(!genuine.peer.unverified);
    let impostor = row_of(&rows, NOBODY.0);
    assert_eq!((impostor.priority, impostor.deadline, impostor.rect), (Priority::Normal, false, [24, 30, 16, 16]));
    assert!(impostor.peer.unverified, "{impostor:?}");
    daemon.wait_log("treated as unnamed");
    ic.stop();
    fake.stop();
    daemon.stop();
}

#[test]
fn no_process_of_another_uid_opens_a_segment_while_clients_come_and_go() {
    if !root() {
        return;
    }
    let (_dir, daemon, _) = vm_daemon("identity-segments");
    let socket = daemon.socket.clone();
    let probe = |user: (u32, u32), seconds: &str| {
        Command::new(std::env::current_exe().expect("test binary"))
            .args(["--exact", "probe_process", "--nocapture", "--test-threads", "1"])
            .env("STRATA_PROBE_SECONDS", seconds)
            .uid(user.0)
            .gid(user.1)
            .stdout(Stdio::piped())
            .spawn()
            .expect("prober")
    };
    let prober = probe(PROBER, "6");
    // Clients of two users come and go meanwhile, each streaming verified commands.
    let started = Instant::now();
    let mut rounds = 0;
    while started.elapsed() < Duration::from_secs(5) {
        let mine = support::sample_client(&socket, "seg-root", 3000, 1000, rounds);
        let theirs = Command::new(support::stratad())
            .args(["client", "--name", "seg-nobody", "--commands", "3000", "--verify-every", "1000", "--socket"])
            .arg(&socket)
            .uid(NOBODY.0)
            .gid(NOBODY.1)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("client as nobody");
        support::expect_verified(theirs, 3000);
        support::expect_verified(mine, 3000);
        rounds += 1;
    }
    let out = prober.wait_with_output().expect("prober");
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text.lines().find(|l| l.contains("probe: tried")).unwrap_or_else(|| panic!("prober said {text}"));
    let nums: Vec<u64> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
    assert!(rounds >= 2 && nums[0] > 1000, "{rounds} rounds of clients, the prober tried {}", nums[0]);
    assert_eq!(nums[1], 0, "a process of another uid opened segments:\n{text}");
    daemon.stop();
}

#[test]
fn bad_input_at_the_doors_is_refused_and_other_clients_carry_on() {
    use std::io::Read;
    use std::os::fd::AsFd;
    let daemon = Daemon::start("identity-bad", &["--output", "t=32x32"]);
    let socket = daemon.socket.clone();
    let bystander = support::sample_client(&socket, "bystander", 200_000, 10_000, 3);

    // Descriptors sent with the preamble: refused, saying why, and closed.
    let stream = std::os::unix::net::UnixStream::connect(&socket).expect("connect");
    stream.set_read_timeout(Some(Duration::from_secs(10))).expect("timeout");
    let passed = std::fs::File::open("/dev/null").expect("a descriptor to send");
    let pre = strata_protocol::handshake::preamble(strata_protocol::handshake::PROTOCOL_VERSION);
    strata_protocol::fd_passing::send_with_fd(stream.as_fd(), &pre, passed.as_fd()).expect("send");
    let reply: strata_protocol::handshake::ServerMessage =
        strata_protocol::handshake::read_message(&mut &stream, "refusal").expect("a refusal");
    let why = format!("{reply:?}");
    assert!(why.contains("file descriptors"), "{why}");
    let mut rest = Vec::new();
    let _ = (&stream).read_to_end(&mut rest);

    // Unknown users and groups stop the daemon before it starts, naming them.
    let bad = daemon.dir.0.join("bad.toml");
    std::fs::write(&bad, "[[layout]]\nclient = \"ic\"\nuser = \"no-such-user-x\"\nx = 0\ny = 0\nz = 0.5\n")
        .expect("config");
    let quota = daemon.dir.0.join("quota.toml");
    std::fs::write(&quota, "[[quota]]\nclient = \"ic\"\ngroup = \"no-such-group-x\"\ntextures = 1\n").expect("config");
    let other = daemon.dir.0.join("other.sock");
    for (args, says) in [
        (vec!["--config", bad.to_str().expect("utf-8")], "no user named \"no-such-user-x\""),
        (vec!["--config", quota.to_str().expect("utf-8")], "no group named \"no-such-group-x\""),
        (vec!["--client-group", "no-such-group-y"], "no group named \"no-such-group-y\""),
    ] {
        let out = Command::new(support::stratad())
            .args(["serve", "--output", "t=8x8", "--socket"])
            .arg(&other)
            .args(&args)
            .output()
            .expect("serve");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(says), "{args:?}: {err}");
    }
    support::expect_verified(bystander, 200_000);
    daemon.stop();
}

/// The process a test starts to connect and hand its connection on: it connects, starts
/// `handoff_child` with the connection as descriptor 3, says its pid, and exits at once.
#[test]
fn handoff_process() {
    use std::os::fd::AsRawFd;
    let Ok(socket) = std::env::var("STRATA_HANDOFF_SOCKET") else { return };
    let stream = std::os::unix::net::UnixStream::connect(&socket).expect("connect");
    let fd = stream.as_raw_fd();
    let mut cmd = Command::new(std::env::current_exe().expect("test binary"));
    cmd.args(["--exact", "handoff_child", "--nocapture", "--test-threads", "1"])
        .env_remove("STRATA_HANDOFF_SOCKET")
        .env("STRATA_HANDOFF_PARENT", std::process::id().to_string());
    support::pass_fds(&mut cmd, vec![fd]);
    // This process exits at once without waiting: that is the point, and init reaps the child.
    #[allow(clippy::zombie_processes)]
    cmd.spawn().expect("the child that takes the connection over");
    println!("handoff: pid {}", std::process::id());
}

/// The child that takes over a connection whose connecting process has exited: once it has,
/// it performs the handshake over descriptor 3, streams verified commands, says so, and keeps
/// the connection until its stdin closes.
#[test]
fn handoff_child() {
    use std::io::BufRead;
    use std::os::fd::FromRawFd;
    let Ok(parent) = std::env::var("STRATA_HANDOFF_PARENT") else { return };
    let gone = Instant::now() + Duration::from_secs(10);
    while Path::new(&format!("/proc/{parent}")).exists() {
        assert!(Instant::now() < gone, "the connecting process never exited");
        std::thread::sleep(Duration::from_millis(10));
    }
    // SAFETY: the parent placed the connected socket at descriptor 3, owned by nothing else here.
    let stream = unsafe { std::os::unix::net::UnixStream::from_raw_fd(3) };
    let opts = strata_client::ConnectOptions { name: "handed-on".into(), tally: true, ..Default::default() };
    let mut conn = strata_client::Connection::connect_over(stream, &opts).expect("handshake over the passed socket");
    let mut load = strata_client::workload::Workload::new(5, 4096);
    for _ in 0..20_000 {
        strata_client::Calls::send(&mut conn, &load.next_command()).expect("send");
    }
    let tally = conn.verify().expect("verify");
    assert!(tally.matches, "{tally:?}");
    println!("handoff: verified {}", tally.commands);
    let _ = std::io::stdin().lock().lines().count();
}

#[test]
fn a_client_whose_connecting_process_has_exited_is_served_under_its_credentials() {
    use std::io::BufRead;
    let daemon = Daemon::start("identity-exited", &["--output", "t=32x32"]);
    let mut handoff = Command::new(std::env::current_exe().expect("test binary"))
        .args(["--exact", "handoff_process", "--nocapture", "--test-threads", "1"])
        .env("STRATA_HANDOFF_SOCKET", &daemon.socket)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("handoff");
    let stdin = handoff.stdin.take();
    let mut lines = std::io::BufReader::new(handoff.stdout.take().expect("stdout")).lines();
    assert!(handoff.wait().expect("handoff").success());
    let mut said = |what: &str| loop {
        let line = lines.next().unwrap_or_else(|| panic!("no {what:?} line")).expect("read");
        if let Some((_, rest)) = line.split_once(what) {
            return rest.trim().to_string();
        }
    };
    let pid: u32 = said("handoff: pid").parse().expect("pid");
    assert_eq!(said("handoff: verified"), "20000");
    // The daemon serves it under the credentials of the process that connected, gone by now.
    assert!(!Path::new(&format!("/proc/{pid}")).exists());
    let stats = support::stats(&daemon.socket);
    let c = stats.clients.iter().find(|c| c.name == "handed-on").expect("the client is listed");
    // SAFETY: getuid cannot fail.
    assert_eq!((c.peer.pid, c.peer.uid), (pid, unsafe { libc::getuid() }));
    drop(stdin);
    let after = support::sample_client(&daemon.socket, "after", 20_000, 0, 9);
    support::expect_verified(after, 20_000);
    daemon.stop();
}

//! stratad under systemd, with this test playing the service manager's part: it binds the
//! client and control sockets and passes them as descriptors 3 and 4 (`LISTEN_FDS=2`,
//! `LISTEN_FDNAMES=stratad.socket:control`, `LISTEN_PID` the daemon's), as the units in
//! packaging/systemd do, and listens on `NOTIFY_SOCKET`. The daemon serves clients and `ctl` on
//! those sockets (its `--socket` points nowhere usable), says `READY=1` once it can, pings `WATCHDOG=1` at half of
//! `WATCHDOG_USEC`, says `STOPPING=1` on SIGTERM, and leaves the socket in place for the next
//! start. A descriptor that is not a listening Unix socket is refused with a clear error.

mod support;

use std::os::fd::AsRawFd;
use std::os::unix::net::{UnixDatagram, UnixListener};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::TempDir;

/// `stratad serve` started as systemd starts it: `fds` as descriptors 3, 4, … named `names`
/// (`LISTEN_FDNAMES`), and `LISTEN_PID` its own PID (`sh` sets it, then `exec`s the daemon in
/// its place).
fn activated(
    fds: &[i32],
    names: &str,
    notify: &std::path::Path,
    log: &std::path::Path,
    extra_env: &[(&str, &str)],
) -> Command {
    let mut cmd = Command::new("sh");
    let script = format!(
        "LISTEN_PID=$$ LISTEN_FDS={} exec \"$0\" serve --output t=64x64 --socket /nonexistent/strata.sock \
         --allow-fault-injection",
        fds.len()
    );
    cmd.args(["-c", &script])
        .arg(support::stratad())
        .env("NOTIFY_SOCKET", notify)
        .env("LISTEN_FDNAMES", names)
        .env_remove("LISTEN_PID")
        .env_remove("LISTEN_FDS")
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(log).expect("log file"));
    for (k, v) in extra_env {
        cmd.env(k, v);
    }
    support::pass_fds(&mut cmd, fds.to_vec());
    cmd
}

/// The notifications received within `wait`, until one contains `until`.
fn notifications(sock: &UnixDatagram, wait: Duration, until: &str) -> Vec<String> {
    let end = Instant::now() + wait;
    let mut got = Vec::new();
    let mut buf = [0u8; 4096];
    while let Some(left) = end.checked_duration_since(Instant::now()) {
        sock.set_read_timeout(Some(left.max(Duration::from_millis(1)))).expect("timeout");
        let Ok(n) = sock.recv(&mut buf) else { break };
        let msg = String::from_utf8_lossy(&buf[..n]).into_owned();
        let done = !until.is_empty() && msg.contains(until);
        got.push(msg);
        if done {
            break;
        }
    }
    got
}

#[test]
fn socket_activation_readiness_watchdog_and_stopping() {
    let dir = TempDir::new("systemd");
    let path = dir.0.join("strata.sock");
    let listener = UnixListener::bind(&path).expect("bind");
    // Where `ctl --socket PATH` looks: beside the client socket.
    let control = UnixListener::bind(dir.0.join("strata-control.sock")).expect("bind the control socket");
    let notify_path = dir.0.join("notify");
    let notify = UnixDatagram::bind(&notify_path).expect("notify socket");

    let log = dir.0.join("stratad.log");
    let fds = [listener.as_raw_fd(), control.as_raw_fd()];
    let names = "stratad.socket:control";
    let daemon = activated(&fds, names, &notify_path, &log, &[("WATCHDOG_USEC", "400000")]).spawn().expect("stratad");
    let mut daemon = Killed(daemon);
    let pid = daemon.0.id();
    let ready = notifications(&notify, Duration::from_secs(90), "READY=1");
    let status = ready.iter().find(|m| m.contains("READY=1"));
    let status = status.unwrap_or_else(|| panic!("no READY=1 within 90 s, {} other messages", ready.len()));
    assert!(status.contains(&format!("STATUS=serving on {}", path.display())), "{status}");

    // Clients reach it through the socket the service manager holds.
    let client = support::sample_client(&path, "activated", 2000, 500, 7);
    support::expect_verified(client, 2000);

    // The compositor thread pings at half of WATCHDOG_USEC (200 ms), idle or not.
    let pings = notifications(&notify, Duration::from_secs(2), "");
    let count = pings.iter().filter(|m| m.contains("WATCHDOG=1")).count();
    assert!(count >= 3, "{count} watchdog pings in 2 s: {pings:?}");

    // A wedged compositor stops the pings, so systemd (WatchdogSec=) would restart the
    // daemon; its control socket still answers meanwhile.
    let out = Command::new(support::stratad())
        .args(["ctl", "wedge-compositor", "--socket"])
        .arg(&path)
        .output()
        .expect("ctl");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let _in_flight = notifications(&notify, Duration::from_millis(300), "");
    let after = notifications(&notify, Duration::from_millis(1500), "");
    let late = after.iter().filter(|m| m.contains("WATCHDOG=1")).count();
    assert_eq!(late, 0, "watchdog pings from a wedged compositor: {after:?}");
    let out = Command::new(support::stratad()).args(["ctl", "list", "--socket"]).arg(&path).output().expect("ctl");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));

    // SIGTERM: STOPPING=1, a clean exit, and the socket stays for the next start.
    // SAFETY: plain kill(2) on our own child.
    unsafe { libc::kill(pid as i32, libc::SIGTERM) };
    let stopping = notifications(&notify, Duration::from_secs(30), "STOPPING=1");
    assert!(stopping.iter().any(|m| m.contains("STOPPING=1")), "{stopping:?}");
    let status = daemon.0.wait_deadline();
    let text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(status.success(), "stratad: {status}\n{text}");
    assert!(path.exists(), "the activated socket was removed");
    assert!(dir.0.join("strata-control.sock").exists(), "the activated control socket was removed");
    drop(listener);
    drop(control);

    // Descriptor 3 that is not a listening Unix socket: a clear error, no start.
    let file = std::fs::File::create(dir.0.join("not-a-socket")).expect("file");
    let bad_log = dir.0.join("bad.log");
    let status =
        activated(&[file.as_raw_fd()], "stratad.socket", &notify_path, &bad_log, &[]).status().expect("stratad");
    let err = std::fs::read_to_string(&bad_log).unwrap_or_default();
    assert!(!status.success(), "stratad served on a regular file");
    assert!(err.contains("not a listening Unix stream socket"), "{err}");

    // Two client sockets (no control socket named): a clear error, no start.
    let a = UnixListener::bind(dir.0.join("a.sock")).expect("bind");
    let b = UnixListener::bind(dir.0.join("b.sock")).expect("bind");
    let two_log = dir.0.join("two.log");
    let fds = [a.as_raw_fd(), b.as_raw_fd()];
    let status = activated(&fds, "stratad.socket:other.socket", &notify_path, &two_log, &[]).status().expect("stratad");
    let err = std::fs::read_to_string(&two_log).unwrap_or_default();
    assert!(!status.success(), "stratad served on two client sockets");
    assert!(err.contains("one client socket and one control socket"), "{err}");
}

/// A daemon killed if the test ends before it stops.
struct Killed(std::process::Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Waiting for a child with a deadline.
trait WaitDeadline {
    fn wait_deadline(&mut self) -> std::process::ExitStatus;
}

impl WaitDeadline for std::process::Child {
    fn wait_deadline(&mut self) -> std::process::ExitStatus {
        let end = Instant::now() + Duration::from_secs(60);
        loop {
            if let Some(status) = self.try_wait().expect("wait") {
                return status;
            }
            if Instant::now() > end {
                let _ = self.kill();
                panic!("stratad did not stop within 60 s of SIGTERM");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

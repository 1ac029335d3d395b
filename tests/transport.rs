//! Multi-process transport tests: a real `stratad`, real client processes, and hostile clients.

mod support;

use std::io::Write;
use std::time::Duration;

use strata_client::workload::Workload;
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use strata_protocol::handshake::HandshakeError;
use strata_protocol::ring::{KIND_CHUNK_FIRST, KIND_WHOLE};
use strata_protocol::wire::Blob;
use support::*;

#[test]
fn two_clients_stream_a_million_commands_each() {
    let daemon = Daemon::start("million", &[]);
    let a = sample_client(&daemon.socket, "ic-load", 1_000_000, 250_000, 11);
    let b = sample_client(&daemon.socket, "hu-load", 1_000_000, 250_000, 12);
    expect_verified(a, 1_000_000);
    expect_verified(b, 1_000_000);
    assert!(daemon.stop().success());
}

#[test]
fn version_mismatch_is_refused_naming_both_versions() {
    let daemon = Daemon::start("version", &[]);
    let opts = ConnectOptions { socket: daemon.socket.clone(), version: 99, ..ConnectOptions::default() };
    match Connection::connect(&opts) {
        Err(ClientError::Handshake(HandshakeError::Refused(reason))) => {
            let ours = format!("version {}", strata_protocol::handshake::PROTOCOL_VERSION);
            assert!(reason.contains("version 99") && reason.contains(&ours), "{reason}");
        }
        Err(e) => panic!("expected a refusal, got {e}"),
        Ok(_) => panic!("a client with the wrong version was accepted"),
    }
    daemon.wait_log("protocol version mismatch");
}

fn header(len: u32, kind: u32) -> Vec<u8> {
    [len.to_le_bytes(), kind.to_le_bytes()].concat()
}

fn framed(payload: &[u8]) -> (Vec<u8>, u32) {
    let mut f = header(payload.len() as u32, KIND_WHOLE);
    f.extend_from_slice(payload);
    let size = ((f.len() + 7) & !7) as u32;
    f.resize(size as usize, 0);
    (f, size)
}

/// Each kind of bad input is disconnected with a logged reason while a well-behaved client
/// keeps streaming; the daemon survives all of them.
#[test]
fn bad_clients_are_disconnected_and_others_unaffected() {
    let mut daemon = Daemon::start("bad", &[]);
    let good = sample_client(&daemon.socket, "bystander", 400_000, 20_000, 5);
    // A second bystander in this process, connected for the whole test, streams and verifies
    // between every bad client.
    let opts = ConnectOptions { socket: daemon.socket.clone(), tally: true, ..ConnectOptions::default() };
    let mut watcher = Connection::connect(&opts).expect("watcher");
    let mut load = Workload::new(3, 2048);
    let mut stream_and_verify = |what: &str| {
        for _ in 0..20_000 {
            watcher.send(&load.next_command()).expect("watcher send");
        }
        let t = watcher.verify().expect("watcher verify");
        assert!(t.matches, "bystander stream damaged after {what}: {t:?}");
    };

    let garbage: Vec<u8> = (0..256u32).map(|i| (i.wrapping_mul(2654435761) >> 13) as u8).collect();
    let (garbage_frame, garbage_size) = framed(&garbage[..37]);
    let (unknown_frame, unknown_size) = framed(&[251, 0x60, 0xEA]);
    let mut truncated = header(100, KIND_WHOLE);
    truncated.extend_from_slice(&[7; 20]);
    let mut chunk = header(24, KIND_CHUNK_FIRST);
    chunk.extend_from_slice(&(1u64 << 20).to_le_bytes());
    chunk.extend_from_slice(&[1; 16]);

    // Each case lists the reasons any one of which the log must give.
    type Case = (&'static str, Vec<u8>, u32, &'static [&'static str]);
    let cases: Vec<Case> = vec![
        ("garbage-bytes", garbage.clone(), 256, &["does not fit", "truncated frame", "unknown frame kind"]),
        ("garbage-frame", garbage_frame, garbage_size, &["malformed", "trailing bytes", "unknown command opcode"]),
        ("truncated-frame", truncated, 28, &["truncated frame: it needs 112 bytes but only 28"]),
        ("absurd-length", header(0x7fff_fff0, KIND_WHOLE), 64, &["frame length 2147483632 does not fit"]),
        ("unknown-command", unknown_frame, unknown_size, &["unknown command opcode 60000"]),
    ];
    for (name, bytes, advance, reasons) in cases {
        let mut raw = RawClient::connect(&daemon.socket, name);
        raw.writer.inject(&bytes, advance);
        assert!(raw.wait_disconnected(), "{name}: daemon did not disconnect");
        daemon.wait_log(&format!("name={name} role=raw}}: strata_server::listener: disconnected: protocol violation"));
        let log = daemon.log_text();
        let line = log
            .lines()
            .find(|l| l.contains(&format!("name={name} role=raw")) && l.contains("disconnected"))
            .unwrap_or("");
        assert!(reasons.iter().any(|r| line.contains(r)), "{name}: none of {reasons:?} logged:\n{log}");
        daemon.assert_running();
        stream_and_verify(name);
    }

    // Closing the socket in the middle of a (chunked) command.
    let mut raw = RawClient::connect(&daemon.socket, "mid-command");
    raw.writer.inject(&chunk, 32);
    std::thread::sleep(Duration::from_millis(50));
    drop(raw);
    daemon.wait_log(
        "name=mid-command role=raw}: strata_server::listener: client disconnected in the middle of a command",
    );
    stream_and_verify("mid-command");

    // Garbage instead of a handshake, and garbage on the socket after it.
    let mut s = std::os::unix::net::UnixStream::connect(&daemon.socket).expect("connect");
    s.write_all(b"GET / HTTP/1.1\r\n\r\n").expect("write");
    daemon.wait_log("not a Strata client");
    let mut raw = RawClient::connect(&daemon.socket, "socket-garbage");
    raw.stream.write_all(&garbage).expect("write");
    assert!(raw.wait_disconnected(), "socket garbage: daemon did not disconnect");
    daemon.wait_log("unexpected bytes on the client socket");
    stream_and_verify("socket garbage");

    expect_verified(good, 400_000);
    daemon.assert_running();
    let mut conn = Connection::connect(&ConnectOptions { socket: daemon.socket.clone(), ..ConnectOptions::default() })
        .expect("a new client after the bad ones");
    assert_eq!(conn.strataPing(42).expect("ping"), 42);
    let log = daemon.log_text();
    assert!(!log.contains("panicked"), "daemon panicked:\n{log}");
    assert!(daemon.stop().success());
}

/// A client whose second thread scribbles over its command ring while the daemon reads it:
/// the daemon ends that session at worst (with a reason), never panics, and a bystander's
/// stream stays intact.
#[test]
fn a_racing_writer_ends_only_its_own_session() {
    use rand::{Rng, SeedableRng};
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, Mutex};

    let mut daemon = Daemon::start("racing", &[]);
    let opts = ConnectOptions { socket: daemon.socket.clone(), tally: true, ..ConnectOptions::default() };
    let mut watcher = Connection::connect(&opts).expect("bystander");
    let mut load = Workload::new(9, 2048);
    for round in 0..4u64 {
        let name = format!("racer-{round}");
        let mut raw = RawClient::connect(&daemon.socket, &name);
        let region = raw.segment.command_ring().expect("ring");
        // The racer and the framing writer take turns (the writer's slices are not atomic);
        // the daemon reads throughout.
        let turn = Arc::new(Mutex::new(()));
        let stop = Arc::new(AtomicBool::new(false));
        let racer = {
            let (turn, stop) = (turn.clone(), stop.clone());
            std::thread::spawn(move || {
                let mut rng = rand::rngs::StdRng::seed_from_u64(round);
                while !stop.load(Ordering::Relaxed) {
                    let _turn = turn.lock().expect("turn");
                    for _ in 0..64 {
                        // Payload bytes mostly; a header byte in one round of two.
                        let off = rng.random_range(0..region.capacity() as usize);
                        if round % 2 == 1 || off % 8 >= 4 {
                            region.scribble(off, rng.random());
                        }
                    }
                }
            })
        };
        let started = std::time::Instant::now();
        let gone = std::cell::Cell::new(false);
        while started.elapsed() < Duration::from_millis(700) && !gone.get() {
            let _turn = turn.lock().expect("turn");
            for i in 0..32 {
                let text = format!("attribute_{i}_{}", "x".repeat(i as usize * 7));
                let cmd = strata_protocol::Command::BindAttribLocation {
                    program: i,
                    index: 0,
                    name: strata_protocol::Text::borrowed(&text),
                };
                let bytes = strata_protocol::codec::encode_to_vec(&cmd).expect("encode");
                let wrote = raw.writer.write::<strata_protocol::ring::RingError>(bytes.len(), &|| false, |b| {
                    b.copy_from_slice(&bytes);
                    Ok(())
                });
                if wrote.is_err() {
                    gone.set(true);
                    break;
                }
            }
            raw.writer.publish();
        }
        stop.store(true, Ordering::Relaxed);
        racer.join().expect("racer");
        drop(raw);
        daemon.wait_log(&format!("name={name} role=raw}}: strata_server::listener::client: session ended"));
        daemon.assert_running();
        for _ in 0..20_000 {
            watcher.send(&load.next_command()).expect("bystander send");
        }
        let t = watcher.verify().expect("bystander verify");
        assert!(t.matches, "bystander stream damaged by {name}: {t:?}");
    }
    let log = daemon.log_text();
    assert!(!log.contains("panicked"), "daemon panicked:\n{log}");
    // The racer did strike: a scribbled header or payload ended at least one of its sessions.
    let ended = (0..4)
        .filter(|r| {
            log.contains(&format!(
                "name=racer-{r} role=raw}}: strata_server::listener: disconnected: protocol violation"
            ))
        })
        .count();
    eprintln!("racing sessions ended for a protocol violation: {ended} of 4");
    assert!(ended > 0, "no racing session was ended for what it wrote:\n{log}");
    assert!(daemon.stop().success());
}

/// Payloads several times larger than the command ring arrive whole (chunked transfer).
#[test]
fn payload_larger_than_the_ring() {
    let daemon = Daemon::start("large", &["--cmd-ring", "65536"]);
    let opts = ConnectOptions { socket: daemon.socket.clone(), tally: true, ..ConnectOptions::default() };
    let mut conn = Connection::connect(&opts).expect("connect");
    let big: Vec<u8> = (0..3 * 1024 * 1024 + 13).map(|i: u32| (i % 251) as u8).collect();
    conn.glBufferData(0x8892, big.len() as i64, Some(Blob::borrowed(&big)), 0x88E4).expect("buffer data");
    conn.glTexImage2D(0x0DE1, 0, 0x1908, 1024, 256, 0, 0x1908, 0x1401, Some(Blob::borrowed(&big[..1 << 20])))
        .expect("tex");
    conn.glClear(0x4000).expect("clear");
    let tally = conn.verify().expect("verify");
    assert!(tally.matches, "{tally:?}");
    assert_eq!(tally.commands, 3);
}

#[test]
fn live_socket_is_refused_stale_socket_replaced_and_removed_on_exit() {
    let dir = TempDir::new("claim");
    let socket = dir.0.join("s.sock");
    drop(std::os::unix::net::UnixListener::bind(&socket).expect("stale socket"));
    assert!(socket.exists());
    let log = dir.0.join("a.log");
    let first = std::process::Command::new(stratad())
        .args(["serve", "--socket"])
        .arg(&socket)
        .stderr(std::fs::File::create(&log).expect("log"))
        .spawn()
        .expect("spawn");
    let mut daemon = Daemon { child: first, socket: socket.clone(), log, dir: TempDir::new("claim-log") };
    daemon.wait_log("replacing stale socket");
    daemon.wait_log("stratad serving");
    let second =
        std::process::Command::new(stratad()).args(["serve", "--socket"]).arg(&socket).output().expect("second daemon");
    assert!(!second.status.success());
    assert!(String::from_utf8_lossy(&second.stderr).contains("already serving"), "{second:?}");
    daemon.assert_running();
    assert!(daemon.stop().success());
    assert!(!socket.exists(), "socket left behind after SIGTERM");
}

/// A client name that carries a line break and a log line of its own, and runs to 300
/// characters, shows in the daemon's log escaped and cut: it forges no line.
#[test]
fn a_name_forges_no_log_line() {
    let daemon = Daemon::start("names", &[]);
    let forged = "2026-01-01T00:00:00.000000Z  WARN strata_server::listener: forged";
    let name = format!("hu\n{forged}{}", "y".repeat(300));
    let raw = RawClient::connect(&daemon.socket, &name);
    drop(raw);
    daemon.wait_log("name=hu\\n2026-01-01T00:00:00.000000Z  WARN");
    let log = daemon.log_text();
    assert!(!log.lines().any(|l| l.starts_with(forged)), "a forged line in the log:\n{log}");
    assert!(log.contains("…(368 characters)"), "the name is not cut:\n{log}");
    assert!(!log.contains(&"y".repeat(100)), "the name is not cut:\n{log}");
}

/// The daemon out of descriptors (`ulimit -n 64`) while 200 connections wait: it pauses
/// accepting after each failure instead of spinning, logs about it at most once a second,
/// uses almost no CPU meanwhile, and serves again once the connections go.
#[test]
fn out_of_descriptors_the_daemon_pauses_and_logs_once_a_second() {
    use std::os::unix::process::CommandExt;
    let dir = TempDir::new("emfile");
    let socket = dir.0.join("s.sock");
    let log = dir.0.join("d.log");
    let mut cmd = std::process::Command::new(stratad());
    cmd.args(["serve", "--socket"]).arg(&socket).stderr(std::fs::File::create(&log).expect("log"));
    // SAFETY: only setrlimit (async-signal-safe) between fork and exec.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit { rlim_cur: 64, rlim_max: 64 };
            if libc::setrlimit(libc::RLIMIT_NOFILE, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    let child = cmd.spawn().expect("spawn");
    let pid = child.id();
    let mut daemon = Daemon { child, socket: socket.clone(), log, dir: TempDir::new("emfile-log") };
    daemon.wait_log("stratad serving");
    let flood: Vec<_> =
        (0..200).map(|_| std::os::unix::net::UnixStream::connect(&socket).expect("the kernel queues it")).collect();
    daemon.wait_log("accept failed: Too many open files");
    let cpu = || {
        let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).expect("stat");
        let fields: Vec<u64> =
            stat.rsplit(')').next().expect("fields").split_whitespace().filter_map(|f| f.parse().ok()).collect();
        // utime and stime, fields 14 and 15 of the whole line (clock ticks of 10 ms).
        (fields[10] + fields[11]) as f64 / 100.0
    };
    let (before, started) = (cpu(), std::time::Instant::now());
    std::thread::sleep(Duration::from_secs(4));
    let share = (cpu() - before) / started.elapsed().as_secs_f64();
    let text = daemon.log_text();
    let lines = text.lines().filter(|l| l.contains("accept failed")).count();
    let seconds = 5 + started.elapsed().as_secs() as usize;
    let head: Vec<&str> = text.lines().take(20).collect();
    assert!(
        lines <= seconds,
        "{lines} lines about refusals in about {seconds} s; the log begins:\n{}",
        head.join("\n")
    );
    assert!(share < 0.05, "the refusing daemon used {:.1} % of a core", share * 100.0);
    drop(flood);
    let mut conn = Connection::connect(&ConnectOptions { socket: socket.clone(), ..ConnectOptions::default() })
        .expect("a client once the flood is gone");
    assert_eq!(conn.strataPing(7).expect("ping"), 7);
    daemon.assert_running();
    assert!(daemon.stop().success());
}

/// A fence's mark reaches the client through its segment's fence word with nothing sent after
/// the fence: polling costs no round trip. The client only reads shared memory while it waits;
/// the daemon's own watch of the device publishes the mark once the draw before it completes.
#[test]
fn a_fence_mark_is_published_without_a_request() {
    let daemon = Daemon::start("fence-word", &[]);
    let opts =
        ConnectOptions { socket: daemon.socket.clone(), name: "fence-word".into(), tally: true, ..Default::default() };
    let mut c = Connection::connect(&opts).expect("connect");
    let pbuffer = strata_client::setup::SurfaceKind::Pbuffer { width: 64, height: 64 };
    strata_client::setup::egl_context(&mut c, 24, 8, pbuffer).expect("context");
    for round in 0..3 {
        c.glClearColor(0.2, 0.4, 0.6, 1.0).expect("clear colour");
        c.glClear(0x4000).expect("clear");
        let mark = c.strataFence().expect("fence");
        assert!(mark > 0, "round {round}: the daemon gave no mark");
        let sent = c.sent();
        assert!(sent.is_some(), "the connection counts what it sends");
        let start = std::time::Instant::now();
        while c.fences_reached() < mark {
            assert!(start.elapsed() < Duration::from_secs(5), "round {round}: mark {mark} never published");
            std::thread::sleep(Duration::from_micros(200));
        }
        assert_eq!(c.sent(), sent, "round {round}: waiting sent commands");
        eprintln!("round {round}: mark {mark} published {:.2} ms after the fence", start.elapsed().as_secs_f64() * 1e3);
    }
}

//! What the daemon holds in its own memory for its clients is charged to them before it is
//! allocated (docs/security.md): a client that leaves a 255 MiB command unfinished is charged
//! for it in `ctl stats`, fifty such clients grow the daemon's memory by no more than what is
//! charged, the daemon's total for them caps the lot, and a command begun and never finished
//! ends its client's session in time, giving everything back.

mod support;

use std::time::{Duration, Instant};

use support::{expect_verified, sample_client, stats, Daemon, RawClient};

/// The daemon's default rings: its segment and the private copy of a frame are charged as
/// twice the command ring and the reply ring.
const SEGMENT: u64 = 2 * (8 << 20) + (1 << 20);

/// The daemon's anonymous memory once it has stopped moving (two reads 300 ms apart within
/// 1 MiB), with the stats of the last read.
fn settled(socket: &std::path::Path) -> strata_protocol::control::DaemonStats {
    let start = Instant::now();
    let mut last = stats(socket);
    loop {
        std::thread::sleep(Duration::from_millis(300));
        let s = stats(socket);
        if s.rss_anon_bytes.abs_diff(last.rss_anon_bytes) < 1 << 20 && s.daemon_bytes == last.daemon_bytes {
            return s;
        }
        assert!(start.elapsed() < Duration::from_secs(120), "the daemon's memory never settled");
        last = s;
    }
}

#[test]
fn unfinished_commands_are_charged_and_the_daemons_memory_grows_by_no_more_than_is_charged() {
    const CLIENTS: usize = 50;
    const LEN: usize = 255 << 20;
    // Slack for what the daemon allocates besides (per-session bookkeeping, allocator
    // rounding): far below one unfinished command.
    const BOUND: u64 = 64 << 20;
    let args = ["--devices", "shared", "--quota-total-daemon-bytes", "2G", "--quota-command-seconds", "600"];
    let daemon = Daemon::start("held-unfinished", &args);
    let socket = daemon.socket.clone();
    let bystander = sample_client(&socket, "bystander", 100_000, 10_000, 4);
    let mut clients: Vec<RawClient> =
        (0..CLIENTS).map(|i| RawClient::connect(&socket, &format!("holder-{i}"))).collect();
    let before = settled(&socket);
    let held: Vec<u64> =
        before.clients.iter().filter(|c| c.name.starts_with("holder-")).map(|c| c.daemon_bytes).collect();
    assert_eq!(held, vec![SEGMENT; CLIENTS], "each session's segment is charged from the start");
    // Each sends all of a 255 MiB command but its last chunk.
    let msg = vec![0u8; LEN];
    for c in &mut clients {
        c.writer.write_unfinished(&msg, &|| true).expect("write");
    }
    let after = settled(&socket);
    let holders: Vec<_> = after.clients.iter().filter(|c| c.name.starts_with("holder-")).collect();
    assert_eq!(holders.len(), CLIENTS, "every session lives");
    let charged: Vec<u64> = holders.iter().map(|c| c.daemon_bytes).collect();
    let full = charged.iter().filter(|&&b| b >= SEGMENT + LEN as u64).count();
    // 2 GiB holds fifty segments and four unfinished commands: the rest are
    // refused the memory and skipped unkept.
    assert!(full >= 1, "no unfinished command is charged: {charged:?}");
    assert!(charged.iter().all(|&b| b == SEGMENT || b >= SEGMENT + LEN as u64), "{charged:?}");
    assert!(after.daemon_bytes <= after.daemon_bytes_limit, "{} > {}", after.daemon_bytes, after.daemon_bytes_limit);
    let grown = after.rss_anon_bytes.saturating_sub(before.rss_anon_bytes);
    let newly_charged = after.daemon_bytes - before.daemon_bytes;
    println!(
        "{full} of {CLIENTS} unfinished commands held; anonymous memory grew {} MiB, charges {} MiB",
        grown >> 20,
        newly_charged >> 20
    );
    assert!(grown <= newly_charged + BOUND, "the daemon's memory grew {grown} bytes, {newly_charged} charged");
    expect_verified(bystander, 100_000);
    drop(clients);
    daemon.stop();
}

#[test]
fn a_command_begun_and_never_finished_ends_its_session_in_time() {
    let args = ["--devices", "shared", "--quota-command-seconds", "1"];
    let daemon = Daemon::start("held-stale", &args);
    let socket = daemon.socket.clone();
    let bystander = sample_client(&socket, "bystander", 200_000, 10_000, 5);
    let mut c = RawClient::connect(&socket, "stalls");
    c.writer.write_unfinished(&vec![7u8; 20 << 20], &|| true).expect("write");
    let start = Instant::now();
    assert!(c.wait_disconnected(), "the session did not end");
    let took = start.elapsed();
    assert!(took < Duration::from_secs(10), "it took {took:?}");
    daemon.wait_log("not finished");
    let log = daemon.log_text();
    assert!(log.contains("a chunked message of 20971520 bytes was begun"), "{log}");
    let s = stats(&socket);
    assert!(s.clients.iter().all(|c| c.name != "stalls"), "the session is gone");
    assert_eq!(s.daemon_bytes, s.clients.iter().map(|c| c.daemon_bytes).sum::<u64>(), "its memory was given back");
    expect_verified(bystander, 200_000);
    daemon.stop();
}

//! A daemon left running while applications come and go returns what each one held: fifty
//! short sessions of an unmodified GLES2 program (glmark2-es2 through the drop-in libraries),
//! every fifth killed with SIGKILL in the middle of its frames, leave the daemon's resident
//! memory within 5 % of what it was after the first five (medians of five sessions each), no client memory or objects
//! accounted, and no more objects on the device than the compositor had then.

mod support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use strata_protocol::control::DaemonStats;
use support::{Daemon, TempDir, Xvfb};

const SESSIONS: usize = 50;
const WARM_UP: usize = 5;

/// Waits until no client is connected, then returns the daemon's statistics.
fn settled(socket: &Path) -> DaemonStats {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        let s = support::stats(socket);
        if s.clients.is_empty() {
            return s;
        }
        assert!(Instant::now() < deadline, "clients never left: {:?}", s.clients);
        std::thread::sleep(Duration::from_millis(20));
    }
}

#[test]
fn fifty_sessions_come_and_go_and_the_daemon_keeps_nothing_of_them() {
    let missing: Vec<&str> = ["glmark2-es2", "Xvfb"].into_iter().filter(|p| support::which(p).is_none()).collect();
    if !support::nothing_missing(&missing) {
        return;
    }
    let x = Xvfb::start(640, 480).expect("Xvfb");
    // glibc's own thresholds: the daemon otherwise keeps what its heaps free, up to
    // `gpu::TRIM_THRESHOLD` at the top of each (`gpu::keep_freed_memory`), and which of glibc's
    // heaps a session's threads land on moves its resident memory by megabytes with no leak
    // behind it. This test looks for what the daemon's own code keeps of a session; the cap on
    // what the allocator keeps is `tests/device_churn.rs`'s, with the daemon as it runs.
    let mut daemon = Daemon::start_with_env("sessions", &[], &[("GLIBC_TUNABLES", "glibc.malloc.perturb=0")]);
    let tmp = TempDir::new("sessions-shim");
    let shim = support::shim_dir(&tmp);
    let mut base: Option<DaemonStats> = None;
    let mut rss = Vec::new();
    for i in 1..=SESSIONS {
        let killed = i % 5 == 0;
        // Textures, buffers, shaders, a window surface and paced swaps, in a few hundred ms.
        let duration = if killed { "5" } else { "0.3" };
        let mut child = Command::new("glmark2-es2")
            .args(["-s", "320x240", "-b", &format!("texture:duration={duration}")])
            .args(["-b", &format!("shading:shading=phong:duration={duration}")])
            .env("DISPLAY", &x.display)
            .env("LD_LIBRARY_PATH", &shim)
            .env("STRATA_SOCKET", &daemon.socket)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("spawn glmark2-es2");
        if killed {
            // Mid-frame: well after its first swap, long before it would finish.
            std::thread::sleep(Duration::from_millis(1200));
            let _ = child.kill();
        }
        let status = child.wait().expect("wait glmark2-es2");
        assert!(killed || status.success(), "session {i}: glmark2-es2 {status}");
        let s = settled(&daemon.socket);
        rss.push((s.rss_bytes, s.rss_anon_bytes));
        if i == WARM_UP {
            base = Some(s);
        }
    }
    daemon.assert_running();
    let base = base.expect("warm-up stats");
    let last = settled(&daemon.socket);
    let mib = |b: u64| b as f64 / f64::from(1 << 20);
    // RSS moves by a few MiB from one session to the next with where the allocator's arenas
    // stand, so each end is the median of five sessions: the five after the first five, and
    // the last five.
    let median = |w: &[(u64, u64)]| {
        let mut v: Vec<u64> = w.iter().map(|r| r.0).collect();
        v.sort_unstable();
        v[v.len() / 2] as f64
    };
    let (before, after) = (median(&rss[WARM_UP..WARM_UP + 5]), median(&rss[SESSIONS - 5..]));
    let growth = (after - before) / before;
    let curve: Vec<String> = rss.iter().map(|&(b, a)| format!("{:.0}/{:.0}", mib(b), mib(a))).collect();
    eprintln!(
        "rss (median of 5) after {WARM_UP} sessions {:.1} MiB, after {SESSIONS} {:.1} MiB ({:+.2} %); MiB per session: {}",
        before / f64::from(1 << 20),
        after / f64::from(1 << 20),
        growth * 100.0,
        curve.join(" ")
    );
    assert!(growth < 0.05, "resident memory grew {:.1} % after the first {WARM_UP} sessions", growth * 100.0);
    // A session killed before its handshake (a slow start on a loaded machine) is not counted.
    let clean = (SESSIONS - SESSIONS / 5) as u64;
    assert!((clean..=SESSIONS as u64).contains(&last.sessions), "{} sessions counted", last.sessions);
    assert_eq!(last.gpu_bytes, 0, "client memory still accounted after every client left");
    assert!(last.objects.values().all(|&n| n == 0), "client objects still counted: {:?}", last.objects);
    for (kind, &n) in &last.device_objects {
        let before = base.device_objects.get(kind).copied().unwrap_or(0);
        assert!(n <= before + 2, "{kind} on the device: {before} after {WARM_UP} sessions, {n} after {SESSIONS}");
    }
}

//! Priority with a device per client, with two real client processes: a low-priority head
//! unit saturates its device with one huge draw per frame while a high-priority instrument
//! cluster swaps at interval 1. The IC's frames must reach the screen (the composite that took
//! them completed on the compositor's device) within `BOUND` of their swap at the 99th
//! percentile. The same run on one device shared by everyone (`--devices shared`) must exceed
//! it, which shows that the bound is the devices' doing: there, an IC frame waits behind whole
//! head-unit frames on the one queue.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The IC's p99 swap-to-shown latency a device per client must keep it under.
const BOUND: Duration = Duration::from_millis(100);

/// Fragment-loop iterations of the head unit's one draw: on lavapipe one frame of it takes
/// several hundred milliseconds, far beyond `BOUND`.
const HU_ITERATIONS: &str = "400";

const CONFIG: &str = r#"
[[layout]]
client = "ic"
x = 0
y = 0
z = 0.5
priority = "high"
deadline = true

[[layout]]
client = "hu"
x = 320
y = 0
z = 0.6
priority = "low"
"#;

struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn stratad(bench: &Path) -> PathBuf {
    let stratad = bench.with_file_name("stratad");
    assert!(stratad.is_file(), "{} is not built: run `cargo build -p strata-server` first", stratad.display());
    stratad
}

/// `stratad ctl list --json`, or `None` while the daemon does not answer.
fn list(stratad: &Path, socket: &Path) -> Option<serde_json::Value> {
    let out = Command::new(stratad).args(["ctl", "--json", "--socket"]).arg(socket).arg("list").output().ok()?;
    out.status.success().then(|| serde_json::from_slice(&out.stdout).ok()).flatten()
}

/// Runs the head unit and then the IC beside it; returns the IC surface's row.
fn ic_beside_busy_hu(tag: &str, extra: &[&str]) -> serde_json::Value {
    let bench = Path::new(env!("CARGO_BIN_EXE_strata-bench"));
    let stratad = stratad(bench);
    let dir = std::env::temp_dir().join(format!("strata-interference-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (socket, config) = (dir.join("s.sock"), dir.join("config.toml"));
    std::fs::write(&config, CONFIG).expect("config");
    let log = std::fs::File::create(dir.join("stratad.log")).expect("log");
    let _daemon = Killed(
        Command::new(&stratad)
            .args(["serve", "--output", "main=960x360", "--socket"])
            .arg(&socket)
            .arg("--config")
            .arg(&config)
            .args(extra)
            .stdout(Stdio::null())
            .stderr(log)
            .spawn()
            .expect("start stratad"),
    );
    let start = Instant::now();
    while list(&stratad, &socket).is_none() {
        assert!(start.elapsed() < Duration::from_secs(30), "stratad did not start");
        std::thread::sleep(Duration::from_millis(100));
    }
    let client = |role: &str, seconds: &str, window: &str| {
        let mut c = Command::new(bench);
        c.args(["interference-client", "--role", role, "--seconds", seconds, "--window", window])
            .args(["--iterations", HU_ITERATIONS, "--out"])
            .arg(dir.join(format!("{role}.json")))
            .arg("--socket")
            .arg(&socket)
            .stdout(Stdio::null())
            .stderr(Stdio::null());
        c
    };
    let _hu = Killed(client("huge-draw", "600", "320,0,640x360").spawn().expect("start the head unit"));
    // Let the head unit's frames fill the queue (and its cost be measured) first.
    std::thread::sleep(Duration::from_secs(3));
    // The IC runs with `--hold`: after its measured seconds it says `end` and keeps drawing
    // until its stdin closes, so its row can be read while it is live.
    let mut ic = client("ic", "4", "0,0,320x320");
    let mut ic = Killed(ic.arg("--hold").stdin(Stdio::piped()).stdout(Stdio::piped()).spawn().expect("start the IC"));
    let out = ic.0.stdout.take().expect("IC stdout");
    let ended = std::io::BufRead::lines(std::io::BufReader::new(out)).map_while(Result::ok).any(|l| l.trim() == "end");
    assert!(ended, "the IC stopped before its measured seconds ended");
    let rows = list(&stratad, &socket).expect("ctl list");
    drop(ic.0.stdin.take());
    let _ = std::fs::remove_dir_all(&dir);
    let surfaces = rows["surfaces"].as_array().cloned().unwrap_or_default();
    let hu = surfaces.iter().find(|s| s["client"] == "hu").expect("the head unit's surface is listed");
    assert!(hu["frames"].as_u64().is_some_and(|f| f >= 2), "the head unit drew too little: {hu}");
    surfaces.iter().find(|s| s["client"] == "ic").cloned().expect("the IC's surface is listed")
}

#[test]
fn a_high_priority_frame_is_shown_promptly_beside_a_saturating_low_priority_client() {
    let with = ic_beside_busy_hu("with", &[]);
    let without = ic_beside_busy_hu("without", &["--devices", "shared"]);
    let p99 = |row: &serde_json::Value| row["shown_latency_us"][1].as_u64().map(Duration::from_micros);
    eprintln!("IC swap-to-shown p99: {:?} with a device per client, {:?} on one", p99(&with), p99(&without));
    let (Some(with), Some(without)) = (p99(&with), p99(&without)) else {
        panic!("the IC's surface row is missing: {with} / {without}");
    };
    assert!(with <= BOUND, "with a device per client the IC's frames took {with:?} (p99) to be shown, over {BOUND:?}");
    assert!(without > BOUND, "on one shared device the IC's frames took only {without:?}: the load is too light");
}

//! A short `strata-bench soak`: clients of every behaviour are started and killed with SIGKILL
//! (mid-command, mid-upload, mid-swap, blocked in a paced swap, stalled), leave cleanly or run
//! into their quota, while a bystander's every frame is checked against the same frame
//! composited alone. The daemon must survive all of it and stop cleanly, and no bystander
//! frame may be wrong. (The long run, with its memory plot, is `strata-bench soak`.)

use std::path::Path;
use std::process::Command;

#[test]
fn the_daemon_survives_client_churn_and_the_bystander_never_shows_a_wrong_frame() {
    let bench = Path::new(env!("CARGO_BIN_EXE_strata-bench"));
    let stratad = bench.with_file_name("stratad");
    // `cargo test --workspace` builds it for the daemon's own tests.
    assert!(stratad.is_file(), "{} is not built: run `cargo build -p strata-server` first", stratad.display());
    let out = std::env::temp_dir().join(format!("strata-soak-test-{}", std::process::id()));
    let run = Command::new(bench)
        .args(["soak", "--minutes", "0.5", "--clients", "28", "--concurrent", "2", "--json", "--out"])
        .arg(&out)
        .arg("--stratad")
        .arg(&stratad)
        .output()
        .expect("run strata-bench soak");
    let text = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "soak failed: {}{}", text, String::from_utf8_lossy(&run.stderr));
    let r: serde_json::Value = serde_json::from_str(&text).expect("soak JSON");
    eprintln!("soak: {} clients, {} killed, bystander {}", r["clients_started"], r["killed"], r["bystander"]);
    assert_eq!(r["daemon_faults"].as_array().map(Vec::len), Some(0), "daemon faults: {}", r["daemon_faults"]);
    assert_eq!(r["clients_started"], 28);
    assert_eq!(r["ended_with_error"], 0, "a client that should end by itself failed");
    assert!(r["killed"].as_u64().is_some_and(|k| k >= 10), "too few kills: {}", r["killed"]);
    assert!(r["bystander"]["frames_checked"].as_u64().is_some_and(|n| n >= 100), "{}", r["bystander"]);
    assert_eq!(r["bystander"]["wrong"], 0, "wrong bystander frames: {}", r["bystander"]);
    let _ = std::fs::remove_dir_all(&out);
}

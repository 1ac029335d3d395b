//! `stratad run`: an unmodified application (Debian's glmark2-es2 under Xvfb) started on the
//! drop-in libraries without `LD_LIBRARY_PATH`, validating through the daemon; its `--name`,
//! `--window`, `--priority` and `--surface-id` reach the daemon (`ctl list`); bad options,
//! a missing program and missing libraries fail before anything starts, each saying why.

mod support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::{Daemon, TempDir, Xvfb};

fn oracles_present() -> bool {
    let missing: Vec<&str> = ["glmark2-es2", "Xvfb"].into_iter().filter(|p| support::which(p).is_none()).collect();
    support::nothing_missing(&missing)
}

/// `stratad run ARGS` with the drop-in libraries in `gl`, the daemon at `socket` and X at
/// `display`.
fn run(gl: &Path, socket: &Path, display: &str, args: &[&str]) -> Command {
    let mut cmd = Command::new(support::stratad());
    cmd.arg("run")
        .args(args)
        .env("STRATA_GL_DIR", gl)
        .env("STRATA_SOCKET", socket)
        .env("DISPLAY", display)
        .env_remove("LD_LIBRARY_PATH")
        .env_remove("STRATA_WINDOW")
        .env_remove("STRATA_NAME");
    cmd
}

fn surfaces(socket: &Path) -> Vec<serde_json::Value> {
    let out =
        Command::new(support::stratad()).args(["ctl", "list", "--json", "--socket"]).arg(socket).output().expect("ctl");
    assert!(out.status.success(), "ctl list: {}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    v["surfaces"].as_array().cloned().unwrap_or_default()
}

#[test]
fn run_starts_an_unmodified_application_on_the_drop_in_libraries() {
    if !oracles_present() {
        return;
    }
    let tmp = TempDir::new("launcher");
    let gl = support::shim_dir(&tmp);
    let x = Xvfb::start(1024, 768).expect("Xvfb");
    let daemon = Daemon::start("launcher", &["--output", "t=800x600"]);

    // The command the README shows: glmark2 validates through the daemon.
    let (out, timed_out) = support::wait_with_deadline(
        run(&gl, &daemon.socket, &x.display, &["--", "glmark2-es2", "--validate", "-b", "build"])
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("stratad run"),
        Duration::from_secs(180),
    );
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!timed_out && out.status.success(), "stratad run: {}\n{text}", out.status);
    let line = text.lines().find(|l| l.contains("Validation:")).unwrap_or("(no validation line)");
    assert!(line.ends_with("Validation: Success"), "{line}\n{text}\nstratad log:\n{}", daemon.log_text());

    // Name, placement, class and surface ID reach the daemon.
    let args = [
        "--name",
        "hu-media",
        "--window",
        "10,20,0.5",
        "--priority",
        "low",
        "--surface-id",
        "1234",
        "--",
        "glmark2-es2",
        "-b",
        "build:duration=30",
    ];
    let mut child = run(&gl, &daemon.socket, &x.display, &args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("stratad run");
    let end = Instant::now() + Duration::from_secs(60);
    let row = loop {
        if let Some(r) = surfaces(&daemon.socket).into_iter().find(|s| s["client"] == "hu-media") {
            break r;
        }
        assert!(Instant::now() < end, "no surface of hu-media within 60 s: {:?}", surfaces(&daemon.socket));
        std::thread::sleep(Duration::from_millis(100));
    };
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(row["id"], 1234, "{row}");
    assert_eq!(
        (row["rect"][0].as_i64(), row["rect"][1].as_i64(), row["z"].as_f64()),
        (Some(10), Some(20), Some(0.5)),
        "{row}"
    );
    assert_eq!(row["priority"], "low", "{row}");

    // Bad input: each refused before the application starts, saying why.
    let empty = tmp.0.join("empty");
    std::fs::create_dir_all(&empty).expect("dir");
    let cases: [(&Path, &[&str], &str); 5] = [
        (&gl, &["--window", "1,2", "--", "true"], "expected \"x,y,z\" or \"x,y,z,WxH\""),
        (&gl, &["--surface-id", "0", "--", "true"], "surface id 0 is outside 1..="),
        (&gl, &["--priority", "urgent", "--", "true"], "unknown priority \"urgent\""),
        (&gl, &["--", "/nonexistent/app"], "starting /nonexistent/app"),
        (&empty, &["--", "true"], "holds no libEGL.so.1 and libGLESv2.so.2"),
    ];
    for (dir, args, says) in cases {
        let out = run(dir, &daemon.socket, &x.display, args).output().expect("stratad run");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(says), "{args:?}: {}\n{err}", out.status);
    }
    let out = run(&gl, &daemon.socket, &x.display, &[]).output().expect("stratad run");
    assert!(!out.status.success(), "stratad run without an application succeeded");
}

#[test]
fn run_asks_qt_for_the_core_input_events_the_library_sends() {
    let tmp = TempDir::new("launcher-qt");
    let gl = support::shim_dir(&tmp);
    let env = |preset: Option<&str>| {
        let mut cmd = Command::new(support::stratad());
        cmd.args(["run", "--", "/bin/sh", "-c", "printf %s \"$QT_XCB_NO_XI2\""]).env("STRATA_GL_DIR", &gl);
        match preset {
            Some(v) => cmd.env("QT_XCB_NO_XI2", v),
            None => cmd.env_remove("QT_XCB_NO_XI2"),
        };
        let out = cmd.output().expect("stratad run");
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    assert_eq!(env(None), "1");
    assert_eq!(env(Some("0")), "0", "a value the user set is kept");
}

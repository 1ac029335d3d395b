//! Scheduling classes at the boundary: `EGL_CONTEXT_PRIORITY_LEVEL_IMG` at `eglCreateContext`,
//! reported back by `eglQueryContext`; the configuration's `priority` winning over it; both
//! shown by `ctl list` and `ctl stats`; and bad values refused with clear errors.

mod support;

use std::path::Path;
use std::process::Command;

use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::control::Priority;
use strata_protocol::Slice;
use support::{Daemon, TempDir};

const EGL_CONTEXT_CLIENT_VERSION: i32 = 0x3098;
const EGL_CONTEXT_PRIORITY_LEVEL_IMG: i32 = 0x3100;
const EGL_CONTEXT_PRIORITY_HIGH_IMG: i32 = 0x3101;
const EGL_CONTEXT_PRIORITY_MEDIUM_IMG: i32 = 0x3102;
const EGL_CONTEXT_PRIORITY_LOW_IMG: i32 = 0x3103;
const EGL_CONTEXT_CLIENT_TYPE: i32 = 0x3097;
const EGL_NONE: i32 = 0x3038;
const EGL_BAD_ATTRIBUTE: i32 = 0x3004;
const EGL_BAD_CONTEXT: i32 = 0x3006;

/// Connects as `name` and creates a context with `attribs` (before `EGL_NONE`); returns the
/// connection, display and the context or the EGL error.
fn context(socket: &Path, name: &str, attribs: &[i32]) -> (Connection, u32, Result<u32, i32>) {
    let mut gl =
        Connection::connect(&ConnectOptions { socket: socket.into(), name: name.into(), ..Default::default() })
            .expect("connect");
    let d = gl.eglGetDisplay(0).expect("io");
    gl.eglInitialize(d).expect("io").expect("eglInitialize");
    let configs = gl.eglChooseConfig(d, Slice::new(&[EGL_NONE]), 1).expect("io").expect("eglChooseConfig");
    let mut list = vec![EGL_CONTEXT_CLIENT_VERSION, 2];
    list.extend_from_slice(attribs);
    list.push(EGL_NONE);
    let ctx = gl.eglCreateContext(d, configs[0], 0, Slice::new(&list)).expect("io");
    (gl, d, ctx)
}

fn level(gl: &mut Connection, d: u32, ctx: u32) -> i32 {
    gl.eglQueryContext(d, ctx, EGL_CONTEXT_PRIORITY_LEVEL_IMG).expect("io").expect("eglQueryContext")
}

fn class_of(socket: &Path, name: &str) -> Priority {
    let s = support::stats(socket);
    s.clients.iter().find(|c| c.name == name).map(|c| c.priority).expect("the client is listed")
}

#[test]
fn egl_context_priority_is_honoured_unless_the_configuration_says_otherwise() {
    let dir = TempDir::new("priority-config");
    let config = dir.0.join("config.toml");
    std::fs::write(&config, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\npriority = \"high\"\ndeadline = true\n\n[[layout]]\nclient = \"hu\"\nx = 0\ny = 0\nz = 1\npriority = \"low\"\n").expect("config");
    let daemon = Daemon::start("priority", &["--config", config.to_str().expect("utf-8 path")]);
    let socket = &daemon.socket;

    // Not in the configuration: the context's request applies, and is reported back.
    let (mut app, d, ctx) = context(socket, "app", &[EGL_CONTEXT_PRIORITY_LEVEL_IMG, EGL_CONTEXT_PRIORITY_HIGH_IMG]);
    let ctx = ctx.expect("eglCreateContext");
    assert_eq!(level(&mut app, d, ctx), EGL_CONTEXT_PRIORITY_HIGH_IMG);
    assert_eq!(class_of(socket, "app"), Priority::High);
    // Without the attribute a client is normal (medium).
    let (mut plain, d2, ctx2) = context(socket, "plain", &[]);
    assert_eq!(level(&mut plain, d2, ctx2.expect("eglCreateContext")), EGL_CONTEXT_PRIORITY_MEDIUM_IMG);
    assert_eq!(class_of(socket, "plain"), Priority::Normal);

    // In the configuration: it wins over the request, and eglQueryContext says so.
    let (mut hu, d3, ctx3) = context(socket, "hu", &[EGL_CONTEXT_PRIORITY_LEVEL_IMG, EGL_CONTEXT_PRIORITY_HIGH_IMG]);
    assert_eq!(level(&mut hu, d3, ctx3.expect("eglCreateContext")), EGL_CONTEXT_PRIORITY_LOW_IMG);
    assert_eq!(class_of(socket, "hu"), Priority::Low);
    let (mut ic, d4, ctx4) = context(socket, "ic", &[EGL_CONTEXT_PRIORITY_LEVEL_IMG, EGL_CONTEXT_PRIORITY_LOW_IMG]);
    assert_eq!(level(&mut ic, d4, ctx4.expect("eglCreateContext")), EGL_CONTEXT_PRIORITY_HIGH_IMG);
    assert_eq!(class_of(socket, "ic"), Priority::High);

    // Bad values: an unknown level, an attribute eglQueryContext does not answer here, and a
    // context that does not exist.
    let (_bad, _, refused) = context(socket, "bad", &[EGL_CONTEXT_PRIORITY_LEVEL_IMG, 0x3104]);
    assert_eq!(refused, Err(EGL_BAD_ATTRIBUTE));
    assert_eq!(app.eglQueryContext(d, ctx, EGL_CONTEXT_CLIENT_TYPE).expect("io"), Err(EGL_BAD_ATTRIBUTE));
    assert_eq!(app.eglQueryContext(d, 999, EGL_CONTEXT_PRIORITY_LEVEL_IMG).expect("io"), Err(EGL_BAD_CONTEXT));

    // `ctl list --json` shows the class and the deadline with each surface's row.
    let mut ic_gl = ic;
    let cur = strata_client::setup::egl_context(
        &mut ic_gl,
        0,
        0,
        strata_client::setup::SurfaceKind::Window { rect: [0, 0, 16, 16], z: 0.5 },
    )
    .expect("window");
    ic_gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("eglSwapBuffers");
    let out = Command::new(support::stratad())
        .args(["ctl", "--json", "--socket"])
        .arg(socket)
        .arg("list")
        .output()
        .expect("ctl list");
    let list: serde_json::Value = serde_json::from_slice(&out.stdout).expect("ctl list JSON");
    let row = list["surfaces"].as_array().and_then(|s| s.iter().find(|r| r["client"] == "ic")).cloned();
    let row = row.expect("the IC's surface is listed");
    assert_eq!((row["priority"].as_str(), row["deadline"].as_bool()), (Some("high"), Some(true)), "{row}");
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")));
}

#[test]
fn an_unknown_class_in_the_configuration_stops_the_daemon_naming_the_classes() {
    let dir = TempDir::new("priority-bad");
    let config = dir.0.join("config.toml");
    std::fs::write(&config, "[[layout]]\nclient = \"ic\"\nx = 0\ny = 0\nz = 0.5\npriority = \"urgent\"\n")
        .expect("config");
    let out = Command::new(support::stratad())
        .args(["serve", "--output", "headless:main=64x64", "--socket"])
        .arg(dir.0.join("s.sock"))
        .arg("--config")
        .arg(&config)
        .output()
        .expect("run stratad");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "stratad started with an unknown class");
    assert!(err.contains("urgent") && ["high", "normal", "low"].iter().all(|c| err.contains(c)), "{err}");
    let out = Command::new(support::stratad())
        .args(["serve", "--default-priority", "urgent", "--socket"])
        .arg(dir.0.join("s2.sock"))
        .output()
        .expect("run stratad");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("high, normal and low"), "{err}");
}

//! Real input devices (`stratad serve --input libinput`). Bad device options stop the daemon
//! before it serves, with an error that names the device, the output or the layout, and leave
//! no socket behind. Where the machine lets a test make a virtual device (`/dev/uinput`), a
//! virtual mouse and keyboard drive a client's surface through libinput: motion and a click
//! reach it at the pointer's output position, and keys reach it as the text they type.

mod support;

use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

use strata_client::setup::{egl_context, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection};
use strata_protocol::input::{Device, InputEvent, Phase};
use support::{Daemon, TempDir};

/// `stratad serve` with `extra`: it must exit with an error containing `want`.
fn refused(extra: &[&str], want: &str) {
    let dir = TempDir::new("input-devices-bad");
    let socket = dir.0.join("strata.sock");
    let child = Command::new(support::stratad())
        .arg("serve")
        .arg("--socket")
        .arg(&socket)
        .args(["--output", "headless:main=64x64", "--input", "libinput"])
        .args(extra)
        .env("RUST_BACKTRACE", "0")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawn stratad");
    let (out, killed) = support::wait_with_deadline(child, Duration::from_secs(60));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!killed, "stratad {extra:?} kept running: {stderr}");
    assert!(!out.status.success(), "stratad {extra:?} started");
    assert!(stderr.contains(want), "stratad {extra:?} did not say {want:?}: {stderr}");
    assert!(!socket.exists(), "stratad {extra:?} left its socket behind");
    assert!(!dir.0.join("strata-control.sock").exists(), "stratad {extra:?} left its control socket behind");
}

#[test]
fn bad_device_options_stop_the_daemon_with_a_clear_error() {
    refused(&["--input-device", "/nonexistent/event0"], "input device /nonexistent/event0: No such file or directory");
    refused(&["--input-device", "/dev/null"], "input device /dev/null: libinput does not take it as an input device");
    refused(&["--input-output", "side"], "--input-output: no output named \"side\"; outputs: main");
    refused(&["--input-layout", "no-such-layout"], "keyboard layout \"no-such-layout\"");
}

#[test]
fn the_seat_without_devices_is_read_and_reported() {
    // A machine without input devices (a container, CI): the daemon serves and says so.
    let daemon = Daemon::start("input-devices-seat", &["--output", "headless:main=64x64", "--input", "libinput"]);
    let deadline = Instant::now() + Duration::from_secs(10);
    let log = loop {
        let log = daemon.log_text();
        let seen = ["libinput found no input device", "input device added"].iter().any(|l| log.contains(l));
        if seen || Instant::now() > deadline {
            break log;
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(log.contains("reading the seat's input devices through libinput"), "{log}");
    let devices = Path::new("/dev/input").read_dir().map(|d| d.count()).unwrap_or(0);
    if devices == 0 {
        assert!(log.contains("libinput found no input device"), "{log}");
    }
    assert!(support::stats(&daemon.socket).clients.is_empty());
}

/// Linux input event codes the virtual devices use.
mod code {
    pub const EV_SYN: u16 = 0;
    pub const EV_KEY: u16 = 1;
    pub const EV_REL: u16 = 2;
    pub const REL_X: u16 = 0;
    pub const REL_Y: u16 = 1;
    pub const BTN_LEFT: u16 = 0x110;
    pub const KEY_H: u16 = 35;
    pub const KEY_I: u16 = 23;
    pub const KEY_LEFTSHIFT: u16 = 42;
}

#[test]
fn a_virtual_mouse_and_keyboard_reach_the_surface_under_the_pointer() {
    use evdev::uinput::VirtualDevice;
    use evdev::{AttributeSet, InputEvent as Ev, KeyCode, RelativeAxisCode};
    let mut keys = AttributeSet::<KeyCode>::new();
    for k in [code::BTN_LEFT, code::KEY_H, code::KEY_I, code::KEY_LEFTSHIFT] {
        keys.insert(KeyCode(k));
    }
    let mut axes = AttributeSet::<RelativeAxisCode>::new();
    axes.insert(RelativeAxisCode::REL_X);
    axes.insert(RelativeAxisCode::REL_Y);
    // Not an oracle that CI installs: only a machine with the uinput module has the device.
    let built = VirtualDevice::builder()
        .and_then(|b| b.name("strata test mouse and keyboard").with_keys(&keys))
        .and_then(|b| b.with_relative_axes(&axes))
        .and_then(|b| b.build());
    let mut dev = match built {
        Ok(d) => d,
        Err(e) => {
            eprintln!("skipping: no virtual input device on this machine (/dev/uinput: {e})");
            return;
        }
    };
    let node = dev.enumerate_dev_nodes_blocking().expect("device nodes").find_map(Result::ok).expect("an event node");
    let node = node.to_str().expect("path").to_string();
    let daemon = Daemon::start(
        "input-devices-uinput",
        &["--output", "headless:main=200x100", "--lighting", "off", "--input", "libinput", "--input-device", &node],
    );
    let opts = ConnectOptions { socket: daemon.socket.clone(), name: "touched".into(), ..Default::default() };
    let mut gl = Connection::connect(&opts).expect("connect");
    let cur = egl_context(&mut gl, 0, 0, SurfaceKind::Window { rect: [20, 10, 160, 80], z: 0.5 }).expect("context");
    gl.glClearColor(0.2, 0.4, 0.6, 1.0).expect("io");
    gl.glClear(0x4000).expect("io");
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("eglSwapBuffers");
    gl.glFinish().expect("io");
    std::thread::sleep(Duration::from_millis(500));
    let emit = |dev: &mut VirtualDevice, events: &[(u16, u16, i32)]| {
        let mut v: Vec<Ev> = events.iter().map(|&(t, c, value)| Ev::new(t, c, value)).collect();
        v.push(Ev::new(code::EV_SYN, 0, 0));
        dev.emit(&v).expect("emit");
    };
    // The pointer starts at the output's corner: 60, 40 on, it is over the surface at 40, 30.
    emit(&mut dev, &[(code::EV_REL, code::REL_X, 60), (code::EV_REL, code::REL_Y, 40)]);
    emit(&mut dev, &[(code::EV_KEY, code::BTN_LEFT, 1)]);
    emit(&mut dev, &[(code::EV_KEY, code::BTN_LEFT, 0)]);
    for (k, v) in [(code::KEY_LEFTSHIFT, 1), (code::KEY_H, 1), (code::KEY_H, 0), (code::KEY_LEFTSHIFT, 0)] {
        emit(&mut dev, &[(code::EV_KEY, k, v)]);
    }
    emit(&mut dev, &[(code::EV_KEY, code::KEY_I, 1)]);
    emit(&mut dev, &[(code::EV_KEY, code::KEY_I, 0)]);
    let mut got = Vec::new();
    let deadline = Instant::now() + Duration::from_secs(10);
    while Instant::now() < deadline && got.iter().filter(|e| matches!(e, InputEvent::Text { .. })).count() < 2 {
        if let Some(e) = gl.next_input(Duration::from_millis(100)).expect("input") {
            got.push(e);
        }
    }
    let points: Vec<(Phase, f32, f32)> = got
        .iter()
        .filter_map(|e| match e {
            InputEvent::Point { device: Device::Pointer, id: 1, phase, x, y, .. } => Some((*phase, *x, *y)),
            _ => None,
        })
        .collect();
    // libinput may accelerate relative motion: the press lands where the pointer went.
    assert!(matches!(points.first(), Some((Phase::Down, x, y)) if *x > 0.0 && *y > 0.0), "{got:?}");
    assert!(points.iter().any(|p| p.0 == Phase::Up), "{got:?}");
    let text: Vec<&str> = got
        .iter()
        .filter_map(|e| match e {
            InputEvent::Text { text, .. } => Some(text.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(text, ["H", "i"], "{got:?}");
}

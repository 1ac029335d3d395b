//! An unmodified Qt Quick application (Debian's `qmlscene`, Qt 5 built for OpenGL ES) started
//! with `stratad run` reacts to `ctl input`: a tap on its MouseArea turns the rectangle from
//! red to green, and text goes into its TextInput. Both reactions are read from the output's
//! screenshot (written to `target/strata-tests/qt_quick.png`) and from what the application
//! prints, which includes the click's coordinates in its own window.

mod support;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::mpsc::Receiver;
use std::time::{Duration, Instant};

use strata_client::ControlConnection;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{Action, InputRequest};
use support::{Daemon, TempDir, Xvfb};

/// Where the application's window surface is placed (`--window X,Y,Z`).
const AT: (i32, i32) = (10, 20);
/// The output's size.
const OUT: (u32, u32) = (320, 240);

/// The output's image, RGBA rows from the top.
fn screenshot(c: &mut ControlConnection) -> Vec<u8> {
    match c.request(&ControlRequest::Screenshot { output: "main".into() }).expect("screenshot") {
        ControlReply::Image { rgba, .. } => rgba.0,
        other => panic!("{other:?}"),
    }
}

/// The colour at output pixel (x, y).
fn pixel(img: &[u8], x: u32, y: u32) -> [u8; 3] {
    let i = ((y * OUT.0 + x) * 4) as usize;
    [img[i], img[i + 1], img[i + 2]]
}

/// Dark pixels (typed text) in the TextInput's part of the window.
fn ink(img: &[u8]) -> usize {
    let (x0, y0) = (AT.0 as u32, AT.1 as u32 + 96);
    (y0..y0 + 64).flat_map(|y| (x0..x0 + 200).map(move |x| (x, y))).filter(|&(x, y)| pixel(img, x, y)[0] < 80).count()
}

/// Screenshots until `ok` holds (panics after 10 s, with `what`).
fn until(c: &mut ControlConnection, what: &str, ok: impl Fn(&[u8]) -> bool) -> Vec<u8> {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let img = screenshot(c);
        if ok(&img) {
            return img;
        }
        assert!(Instant::now() < deadline, "the output never showed {what}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// The application's output (Qt writes `console.log` to stderr), line by line.
fn lines(child: &mut std::process::Child) -> Receiver<String> {
    let err = BufReader::new(child.stderr.take().expect("stderr"));
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for l in err.lines().map_while(Result::ok) {
            if tx.send(l).is_err() {
                return;
            }
        }
    });
    rx
}

/// Lines until one equal to `want` (panics after 10 s).
fn expect(rx: &Receiver<String>, want: &str) {
    let mut seen = Vec::new();
    loop {
        match rx.recv_timeout(Duration::from_secs(10)) {
            Ok(l) if l == want => return,
            Ok(l) => seen.push(l),
            Err(_) => panic!("qmlscene did not print {want:?}; it printed {seen:?}"),
        }
    }
}

#[test]
fn an_unmodified_qt_quick_application_reacts_to_taps_and_text() {
    let Some(qmlscene) = support::which("qmlscene") else {
        assert!(
            !support::oracles_required(),
            "STRATA_REQUIRE_ORACLES is set: qmlscene is missing (tools/install-deps)"
        );
        eprintln!("skipping: qmlscene is missing (tools/install-deps installs it)");
        return;
    };
    let Some(x) = Xvfb::start_or_skip(400, 300) else { return };
    let (w, h) = OUT;
    let output = format!("headless:main={w}x{h}");
    let daemon = Daemon::start("qt-quick", &["--lighting", "off", "--output", &output]);
    let tmp = TempDir::new("qt-quick");
    let qml = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/qml/tap_and_type.qml");
    let mut app = Command::new(support::stratad())
        .args(["run", "--window", &format!("{},{},0.5", AT.0, AT.1), "--"])
        .arg(&qmlscene)
        .arg(&qml)
        .env("DISPLAY", &x.display)
        .env("STRATA_SOCKET", &daemon.socket)
        .env("STRATA_GL_DIR", support::shim_dir(&tmp))
        .env("XDG_RUNTIME_DIR", &tmp.0)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("stratad run qmlscene");
    let printed = lines(&mut app);
    let mut c = ControlConnection::connect_beside(&daemon.socket).expect("control");
    // The button's centre, in the output: its window's (50, 40).
    let (bx, by) = ((AT.0 + 50) as u32, (AT.1 + 40) as u32);
    let before = until(&mut c, "the red rectangle", |img| pixel(img, bx, by) == [255, 0, 0]);
    assert_eq!(ink(&before), 0, "text before any was typed");
    let mut input =
        |action: Action| match c.request(&ControlRequest::Input(InputRequest { output: "main".into(), action })) {
            Ok(ControlReply::Input(o)) => assert!(o.surface.is_some(), "{o:?}"),
            other => panic!("{other:?}"),
        };
    input(Action::Tap { x: bx as f32 + 0.5, y: by as f32 + 0.5 });
    expect(&printed, "qml: clicked 50 40");
    // The tap focused the window, so the text goes to its TextInput.
    input(Action::Text { text: "Hi".into() });
    expect(&printed, "qml: text Hi");
    let after =
        until(&mut c, "the green rectangle and the text", |img| pixel(img, bx, by) == [0, 255, 0] && ink(img) > 200);
    let dir =
        PathBuf::from(support::stratad()).parent().and_then(Path::parent).expect("target dir").join("strata-tests");
    std::fs::create_dir_all(&dir).expect("create target/strata-tests");
    image::save_buffer(dir.join("qt_quick.png"), &after, w, h, image::ColorType::Rgba8).expect("write the screenshot");
    let _ = app.kill();
    let _ = app.wait();
}

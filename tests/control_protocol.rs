//! The control protocol against a running daemon with real client processes: its JSON lines as
//! docs/control.md gives them (and what it refuses), `ctl watch` (events with names and pids,
//! frame statistics, several watchers, one that never reads dropped while the daemon carries
//! on), `ctl analyze` (every reason a surface does not show) and `ctl export` read back by
//! `--config`.

mod support;

use std::io::{BufRead, BufReader, Write};
use std::os::unix::net::UnixStream;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};
use strata_protocol::handshake::control_socket_for;

use support::scene::{ctl, list, try_ctl, Scene};
use support::windows::{self, Client};
use support::Daemon;

#[test]
fn client_process() {
    windows::serve();
}

/// A raw JSON-lines conversation: writes `line`, returns the daemon's answer line (the daemon
/// may close the connection before a line too long for it is written whole).
fn exchange(reader: &mut BufReader<UnixStream>, writer: &mut UnixStream, line: &str) -> serde_json::Value {
    let _ = writer.write_all(line.as_bytes()).and_then(|()| writer.write_all(b"\n"));
    let mut answer = String::new();
    reader.read_line(&mut answer).expect("read");
    serde_json::from_str(&answer).unwrap_or_else(|e| panic!("{answer:?}: {e}"))
}

#[test]
fn the_json_lines_are_as_documented_and_bad_ones_get_clear_errors() {
    let daemon = Daemon::start("control-json", &["--output", "t=32x32"]);
    let connect = || {
        let w = UnixStream::connect(control_socket_for(&daemon.socket)).expect("connect");
        (BufReader::new(w.try_clone().expect("clone")), w)
    };
    let (mut r, mut w) = connect();
    let v = exchange(&mut r, &mut w, r#"{"hello":{"version":999,"name":"old-hmi"}}"#);
    assert_eq!(v["refused"]["reason"], "control protocol version 999; this daemon speaks 1");
    let (mut r, mut w) = connect();
    let v = exchange(&mut r, &mut w, r#"{"hello":{"version":1,"name":"hmi"}}"#);
    assert_eq!(v, serde_json::json!({"ready": {"version": 1}}));
    let v = exchange(&mut r, &mut w, r#""list""#);
    assert_eq!(v["list"]["outputs"][0]["name"], "t", "{v}");
    assert_eq!(v["list"]["surfaces"], serde_json::json!([]));
    // A malformed request is answered with an error; the connection goes on.
    let v = exchange(&mut r, &mut w, r#"{"mvoe":{"surface":1}}"#);
    assert!(v["error"].as_str().is_some_and(|e| e.contains("malformed control request")), "{v}");
    let v = exchange(&mut r, &mut w, r#"{"apply":{"changes":[{"opacity":{"surface":5,"opacity":0.5}}]}}"#);
    assert_eq!(v["error"], "no surface 5; `stratad ctl list` shows them");
    // JSON has no infinity, but a number beyond f32 reads as one: refused by the daemon.
    let v = exchange(&mut r, &mut w, r#"{"move":{"surface":5,"x":0,"y":0,"z":1e300}}"#);
    assert_eq!(v["error"], "z inf is not a finite number");
    let v = exchange(&mut r, &mut w, r#"{"apply":{"changes":[{"opacity":{"surface":5,"opacity":1e300}}]}}"#);
    assert_eq!(v["error"], "opacity inf is outside [0, 1]");
    let v = exchange(&mut r, &mut w, r#"{"screenshot":{"output":"t"}}"#);
    assert_eq!((v["image"]["width"].as_u64(), v["image"]["rgba"].as_str().map(str::len)), (Some(32), Some(5464)));
    // A line beyond the limit ends the connection with an error; the daemon carries on.
    let long = format!(r#"{{"analyze":{{"surface":1{}}}}}"#, " ".repeat(1 << 20));
    let v = exchange(&mut r, &mut w, &long);
    assert!(v["error"].as_str().is_some_and(|e| e.contains("longer than 1048576 bytes")), "{v}");
    ctl(&daemon.socket, &["list"]);
}

/// `ctl watch --json` as a process, its lines arriving on a channel.
fn watcher(socket: &std::path::Path) -> (std::process::Child, mpsc::Receiver<serde_json::Value>) {
    let mut child = Command::new(support::stratad())
        .args(["ctl", "watch", "--json", "--socket"])
        .arg(socket)
        .stdout(Stdio::piped())
        .spawn()
        .expect("ctl watch");
    let out = BufReader::new(child.stdout.take().expect("stdout"));
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in out.lines().map_while(Result::ok) {
            if tx.send(serde_json::from_str(&line).expect("a JSON event")).is_err() {
                return;
            }
        }
    });
    (child, rx)
}

/// The first event `pred` accepts within 10 s.
fn expect(
    rx: &mpsc::Receiver<serde_json::Value>,
    what: &str,
    pred: impl Fn(&serde_json::Value) -> bool,
) -> serde_json::Value {
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        match rx.recv_timeout(left) {
            Ok(e) if pred(&e) => return e,
            Ok(_) => {}
            Err(_) => panic!("no {what} event"),
        }
    }
}

#[test]
fn watchers_see_clients_surfaces_changes_and_frames() {
    let daemon = Daemon::start("control-watch", &["--output", "t=64x48"]);
    let socket = daemon.socket.clone();
    let (mut w1, rx1) = watcher(&socket);
    let (mut w2, rx2) = watcher(&socket);
    // Both are subscribed once a change reaches them.
    let probe = |rx: &mpsc::Receiver<serde_json::Value>| {
        let _ = try_ctl(&socket, &["layer", "create", "probe"]);
        let _ = try_ctl(&socket, &["layer", "destroy", "probe"]);
        expect(rx, "probe", |e| e["changed"]["layer-destroy"]["layer"] == "probe");
    };
    probe(&rx1);
    probe(&rx2);
    let dir = support::TempDir::new("control-watch");
    let shim = support::shim_dir(&dir);
    let c =
        Client::start_painting(&socket, &shim, "cluster", "100", "0,0,0.5,16x16", [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let pid = u64::from(c.pid());
    for rx in [&rx1, &rx2] {
        let e = expect(rx, "client-connected", |e| e.get("client-connected").is_some());
        assert_eq!(
            (&e["client-connected"]["name"], e["client-connected"]["pid"].as_u64()),
            (&"cluster".into(), Some(pid))
        );
        let e = expect(rx, "surface-created", |e| e.get("surface-created").is_some());
        assert_eq!(
            (e["surface-created"]["surface"].as_u64(), e["surface-created"]["pid"].as_u64()),
            (Some(100), Some(pid))
        );
    }
    ctl(&socket, &["surface", "100", "opacity", "0.5"]);
    let e = expect(&rx1, "changed", |e| e.get("changed").is_some());
    assert_eq!(e["changed"], serde_json::json!({"opacity": {"surface": 100, "opacity": 0.5}}));
    // Once a second: the frame it swapped, shown.
    let e = expect(&rx1, "frames", |e| e["frames"]["surface"] == 100 && e["frames"]["frames"] == 1);
    assert_eq!(e["frames"]["shown"], 1, "{e}");
    c.stop();
    for rx in [&rx1, &rx2] {
        let e = expect(rx, "surface-destroyed", |e| e.get("surface-destroyed").is_some());
        assert_eq!(
            (e["surface-destroyed"]["surface"].as_u64(), e["surface-destroyed"]["pid"].as_u64()),
            (Some(100), Some(pid))
        );
        let e = expect(rx, "client-gone", |e| e.get("client-gone").is_some());
        assert_eq!(e["client-gone"]["pid"].as_u64(), Some(pid));
        assert!(e["client-gone"]["reason"].as_str().is_some_and(|r| !r.is_empty()), "{e}");
    }
    let _ = w1.kill();
    let _ = w2.kill();
}

#[test]
fn a_watcher_that_never_reads_is_dropped_and_the_daemon_carries_on() {
    let scene = Scene::start();
    let socket = scene.socket();
    let (mut reading, rx) = watcher(&socket);
    let mut stuck = UnixStream::connect(control_socket_for(&socket)).expect("connect");
    stuck.write_all(b"{\"hello\":{\"version\":1,\"name\":\"stuck\"}}\n\"watch\"\n").expect("write");
    // Batches of 500 changes, toggling a surface: far more than a socket buffer holds.
    let changes: Vec<String> =
        (0..500).map(|i| format!(r#"{{"visibility":{{"surface":100,"visible":{}}}}}"#, i % 2 == 1)).collect();
    let batch = scene.file("many.json", &format!(r#"{{"changes":[{}]}}"#, changes.join(",")));
    let mut slowest = Duration::ZERO;
    let deadline = Instant::now() + Duration::from_secs(60);
    while !scene.daemon.log_text().contains("dropped a watcher") {
        assert!(Instant::now() < deadline, "the stuck watcher was never dropped:\n{}", scene.daemon.log_text());
        ctl(&socket, &["apply", &batch]);
        let t = Instant::now();
        list(&socket);
        slowest = slowest.max(t.elapsed());
    }
    eprintln!("slowest ctl list while a watcher was stuck: {slowest:?}");
    // The reading watcher still gets what follows.
    ctl(&socket, &["surface", "200", "opacity", "0.75"]);
    expect(&rx, "the change after the drop", |e| e["changed"]["opacity"]["surface"] == 200);
    scene.check("after the stuck watcher");
    let _ = reading.kill();
    drop(stuck);
    for c in scene.clients {
        c.stop();
    }
}

#[test]
fn analyze_gives_every_reason_a_surface_does_not_show() {
    let scene = Scene::start();
    let socket = scene.socket();
    let reasons = |id: &str| -> serde_json::Value {
        let v: serde_json::Value = serde_json::from_str(&ctl(&socket, &["analyze", id, "--json"])).expect("json");
        v["reasons"].clone()
    };
    assert_eq!(reasons("200"), serde_json::json!([]));
    assert_eq!(ctl(&socket, &["analyze", "200"]).trim(), "surface 200 shows");
    ctl(&socket, &["surface", "200", "visibility", "off"]);
    assert_eq!(reasons("200"), serde_json::json!(["hidden"]));
    let text = ctl(&socket, &["analyze", "200"]);
    assert!(text.contains("does not show") && text.contains("its visibility is off"), "{text}");
    ctl(&socket, &["surface", "200", "visibility", "on"]);
    ctl(&socket, &["layer", "create", "hu"]);
    ctl(&socket, &["layer", "hu", "add", "200"]);
    ctl(&socket, &["layer", "hu", "visibility", "off"]);
    ctl(&socket, &["surface", "200", "opacity", "0"]);
    assert_eq!(reasons("200"), serde_json::json!([{"layer-hidden": {"layer": "hu"}}, "transparent"]));
    ctl(&socket, &["layer", "destroy", "hu"]);
    ctl(&socket, &["surface", "200", "opacity", "1"]);
    ctl(&socket, &["surface", "200", "source-region", "0", "0", "0", "5"]);
    assert_eq!(reasons("200"), serde_json::json!(["zero-size"]));
    ctl(&socket, &["surface", "200", "source-region", "0", "0", "16", "16"]);
    ctl(&socket, &["move", "200", "500", "500", "0.5"]);
    assert_eq!(reasons("200"), serde_json::json!(["off-outputs"]));
    ctl(&socket, &["move", "200", "12", "10", "0.5"]);
    // 300, nearer and stretched over the whole output, covers 100 and 200.
    ctl(&socket, &["surface", "300", "destination-region", "0", "0", "64", "48"]);
    let (rows, _) = list(&socket);
    assert_eq!(rows.len(), 3);
    // The clients' configs have no alpha, so their surfaces are opaque.
    assert_eq!(reasons("100"), serde_json::json!([{"covered": {"by": [300]}}]));
    assert_eq!(reasons("200"), serde_json::json!([{"covered": {"by": [300]}}]));
    // Half of it uncovered: it shows.
    ctl(&socket, &["surface", "300", "destination-region", "0", "0", "10", "48"]);
    assert_eq!(reasons("100"), serde_json::json!([]));
    let e = try_ctl(&socket, &["analyze", "777"]).expect_err("unknown surface");
    assert!(e.contains("no surface 777"), "{e}");
    // A surface that never swapped.
    let idle = Client::start(&socket, &scene.shim, "idle", 1, Some("400"), None, false);
    assert_eq!(reasons("400"), serde_json::json!(["no-frame"]));
    idle.stop();
    for c in scene.clients {
        c.stop();
    }
}

#[test]
fn an_export_is_a_configuration_that_restores_the_scene() {
    let scene = Scene::start();
    let socket = scene.socket();
    ctl(&socket, &["surface", "100", "opacity", "0.5"]);
    ctl(&socket, &["surface", "200", "destination-region", "30", "2", "32", "24"]);
    ctl(&socket, &["surface", "300", "source-region", "0", "4", "16", "8"]);
    ctl(&socket, &["surface", "300", "visibility", "off"]);
    ctl(&socket, &["move", "100", "6", "7", "0.75"]);
    ctl(&socket, &["layer", "create", "ic"]);
    ctl(&socket, &["layer", "ic", "add", "100"]);
    ctl(&socket, &["layer", "ic", "opacity", "0.5"]);
    ctl(&socket, &["light", "set", "--ambient", "0.25"]);
    let file = scene.dir.0.join("scene.json");
    ctl(&socket, &["export", file.to_str().expect("utf-8")]);
    let exported: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).expect("read")).expect("json");
    assert_eq!(exported["output"], serde_json::json!(["headless:t=64x48+0+0"]));
    assert_eq!(
        exported["layer"],
        serde_json::json!([{"name": "ic", "visible": true, "opacity": 0.5, "surfaces": [100]}])
    );
    assert_eq!(exported["surface"].as_array().map(Vec::len), Some(3), "{exported}");
    let (rows_before, layers_before) = list(&socket);
    let expected_before = scene.expected();
    let light_before = ctl(&socket, &["light", "show", "--json"]);
    for c in scene.clients {
        c.stop();
    }

    // A new daemon from the export alone, and the same clients: the same scene.
    let daemon = Daemon::start("control-export", &["--config", file.to_str().expect("utf-8")]);
    let socket = daemon.socket.clone();
    let shim = scene.shim.clone();
    // Placed elsewhere by the clients themselves: the export's surface entries win.
    let clients: Vec<Client> = support::scene::PAINT
        .iter()
        .map(|(name, id, _, colors)| Client::start_painting(&socket, &shim, name, id, "0,0,0.9,16x16", *colors))
        .collect();
    let (rows, layers) = list(&socket);
    let key = |r: &strata_protocol::control::SurfaceRow| (r.id, r.rect, r.z, r.props, r.shown_visible, r.shown_opacity);
    assert_eq!(rows.iter().map(key).collect::<Vec<_>>(), rows_before.iter().map(key).collect::<Vec<_>>());
    assert_eq!(layers, layers_before);
    assert_eq!(ctl(&socket, &["light", "show", "--json"]), light_before);
    ctl(&socket, &["light", "off"]);
    let shot = scene.dir.0.join("restored.png");
    ctl(&socket, &["screenshot", "t", shot.to_str().expect("utf-8")]);
    let got = image::open(&shot).expect("png").to_rgba8().into_raw();
    assert_eq!(support::scene::differing(&got, &expected_before), 0, "the restored output");
    for c in clients {
        c.stop();
    }

    // A configuration with a bad value stops the daemon before it starts, naming it.
    let bad = scene.dir.0.join("bad.json");
    std::fs::write(&bad, r#"{"surface": [{"id": 100, "opacity": 2}]}"#).expect("write");
    let out = Command::new(support::stratad())
        .args(["serve", "--output", "t=8x8", "--config"])
        .arg(&bad)
        .arg("--socket")
        .arg(scene.dir.0.join("bad.sock"))
        .output()
        .expect("stratad");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("surface 100") && err.contains("opacity 2 is outside [0, 1]"),
        "{err}"
    );
}

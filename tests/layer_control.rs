//! The layer-manager controls against a running daemon with real client processes:
//! `ctl surface ID visibility|opacity|source-region|destination-region`, `ctl layer …` and
//! `ctl apply FILE.json`. Every state the output reaches is compared with the f64 reference
//! compositor, fed with each surface's own frame (`ctl screenshot --surface`) and the
//! properties `ctl list --json` reports. A batch applied while screenshots are taken shows
//! either wholly or not at all, and every bad input is refused with nothing applied.

mod support;

use std::path::Path;
use std::process::Command;

use strata_protocol::control::SurfaceRow;
use strata_protocol::properties::LayerRow;
use strata_server::compositor::reference::{self, RefLayer};
use strata_server::compositor::{Lighting, Props, Source};
use support::windows::{self, Client};
use support::{Daemon, TempDir};

#[test]
fn client_process() {
    windows::serve();
}

const W: u32 = 64;
const H: u32 = 48;

/// `stratad ctl ARGS --socket SOCKET`: its stdout, or its stderr as the error.
fn try_ctl(socket: &Path, args: &[&str]) -> Result<String, String> {
    let out = Command::new(support::stratad()).arg("ctl").args(args).arg("--socket").arg(socket).output().expect("ctl");
    if out.status.success() {
        Ok(String::from_utf8(out.stdout).expect("utf-8"))
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

fn ctl(socket: &Path, args: &[&str]) -> String {
    try_ctl(socket, args).unwrap_or_else(|e| panic!("ctl {args:?}: {e}"))
}

/// Surfaces and layers as `ctl list --json` gives them.
fn list(socket: &Path) -> (Vec<SurfaceRow>, Vec<LayerRow>) {
    let v: serde_json::Value = serde_json::from_str(&ctl(socket, &["list", "--json"])).expect("json");
    (
        serde_json::from_value(v["surfaces"].clone()).expect("surface rows"),
        serde_json::from_value(v["layers"].clone()).expect("layer rows"),
    )
}

/// A PNG written by `ctl screenshot`, as RGBA rows top first.
fn png(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path).expect("png").to_rgba8();
    (img.width(), img.height(), img.into_raw())
}

/// The daemon, its clients and each surface's frame (RGBA, bottom row first, as the reference
/// takes it), by surface ID.
struct Scene {
    _dir: TempDir,
    daemon: Daemon,
    clients: Vec<Client>,
    frames: Vec<(u64, Vec<u8>)>,
    shot: std::path::PathBuf,
}

impl Scene {
    /// Three 16×16 clients: 100 and 200 overlapping in one z-group, 300 nearer and overlapping
    /// both, each of two colours.
    fn start() -> Scene {
        let dir = TempDir::new("layer-control");
        let output = format!("t={W}x{H}");
        let daemon = Daemon::start("layer-control", &["--output", &output]);
        let socket = daemon.socket.clone();
        let shim = support::shim_dir(&dir);
        let paint = [
            ("a", "100", "4,4,0.5,16x16", [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]),
            ("b", "200", "12,10,0.5,16x16", [[0.0, 0.0, 1.0], [0.0, 1.0, 1.0]]),
            ("c", "300", "16,14,0.25,16x16", [[1.0, 0.0, 1.0], [1.0, 1.0, 1.0]]),
        ];
        let clients: Vec<Client> = paint
            .iter()
            .map(|(name, id, window, colors)| Client::start_painting(&socket, &shim, name, id, window, *colors))
            .collect();
        ctl(&socket, &["light", "off"]);
        let shot = dir.0.join("shot.png");
        let frames = [100u64, 200, 300]
            .into_iter()
            .map(|id| {
                ctl(&socket, &["screenshot", "--surface", &id.to_string(), shot.to_str().expect("utf-8")]);
                let (w, _, rgba) = png(&shot);
                // Bottom row first.
                let rows: Vec<u8> = rgba.chunks((w * 4) as usize).rev().flatten().copied().collect();
                (id, rows)
            })
            .collect();
        Scene { _dir: dir, daemon, clients, frames, shot }
    }

    /// A file in the test's directory holding `text`.
    fn file(&self, name: &str, text: &str) -> String {
        let path = self._dir.0.join(name);
        std::fs::write(&path, text).expect("write");
        path.to_str().expect("utf-8").to_string()
    }

    fn socket(&self) -> std::path::PathBuf {
        self.daemon.socket.clone()
    }

    /// What the f64 reference composites from the rows `ctl list` reports now.
    fn expected(&self) -> Vec<u8> {
        let (rows, _) = list(&self.socket());
        let layers: Vec<RefLayer> = rows
            .iter()
            .filter(|r| r.shown_visible)
            .map(|r| {
                let color = self.frames.iter().find(|f| f.0 == r.id).expect("a frame").1.clone();
                let whole = [0, 0, r.image[0], r.image[1]];
                let source = (r.props.source.is_some() || r.props.destination.is_some())
                    .then(|| Source { image: r.image, region: clip(r.props.source.unwrap_or(whole), whole) });
                RefLayer {
                    rect: r.rect,
                    z: r.z,
                    color,
                    depth: None,
                    normal: r.normal,
                    projection: None,
                    props: Props { source, opacity: r.shown_opacity },
                }
            })
            .collect();
        let light = Lighting { enabled: false, ..Lighting::default() };
        reference::composite(&layers, W, H, [0.0, 0.0, 0.0, 1.0], &light)
    }

    /// The output's image now.
    fn output(&self) -> Vec<u8> {
        ctl(&self.socket(), &["screenshot", "t", self.shot.to_str().expect("utf-8")]);
        let (w, h, rgba) = png(&self.shot);
        assert_eq!((w, h), (W, H));
        rgba
    }

    /// Asserts that the output matches the reference, naming the step.
    fn check(&self, step: &str) {
        let (got, want) = (self.output(), self.expected());
        let bad = differing(&got, &want);
        assert!(bad == 0, "{step}: {bad} pixels differ from the f64 reference by more than 1");
    }
}

/// `r` clipped to `to`, an empty rectangle where they miss.
fn clip(r: [i32; 4], to: [i32; 4]) -> [i32; 4] {
    let x0 = r[0].max(to[0]);
    let y0 = r[1].max(to[1]);
    let x1 = (r[0] + r[2]).min(to[0] + to[2]);
    let y1 = (r[1] + r[3]).min(to[1] + to[3]);
    [x0, y0, (x1 - x0).max(0), (y1 - y0).max(0)]
}

/// Pixels of `a` and `b` that differ by more than 1 in some channel.
fn differing(a: &[u8], b: &[u8]) -> usize {
    a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 1)).count()
}

#[test]
fn surface_and_layer_properties_show_as_the_reference_composites_them() {
    let scene = Scene::start();
    let socket = scene.socket();
    let s = |args: &[&str]| ctl(&socket, args);
    // By hand: at (14, 12) 100 and 200 overlap at one depth, and 200, later, is on top: the
    // top half of its frame, cyan; under it, the bottom half of 100's, red.
    let at = |img: &[u8]| img[((12 * W + 14) * 4) as usize..][..3].to_vec();
    assert_eq!(at(&scene.output()), [0, 255, 255], "200 on top");
    scene.check("as placed");

    // Hidden: it takes no part in the depth select, so what it covered shows.
    s(&["surface", "200", "visibility", "off"]);
    scene.check("200 hidden");
    assert_eq!(at(&scene.output()), [255, 0, 0], "100 where 200 was");
    s(&["surface", "200", "visibility", "on"]);
    s(&["surface", "300", "opacity", "0.5"]);
    scene.check("300 at half opacity");
    s(&["surface", "200", "opacity", "0"]);
    scene.check("200 transparent");
    s(&["surface", "200", "opacity", "1"]);

    // Regions: a crop at scale 1, a stretch, and both.
    s(&["surface", "100", "source-region", "4", "2", "8", "12"]);
    scene.check("100 cropped");
    s(&["surface", "200", "destination-region", "30", "2", "32", "24"]);
    scene.check("200 stretched");
    s(&["surface", "300", "source-region", "0", "4", "16", "8"]);
    s(&["surface", "300", "destination-region", "2", "30", "40", "10"]);
    scene.check("300 cropped and stretched");
    let (rows, _) = list(&socket);
    let r300 = rows.iter().find(|r| r.id == 300).expect("300");
    assert_eq!((r300.rect, r300.image, r300.props.source), ([2, 30, 40, 10], [16, 16], Some([0, 4, 16, 8])));

    // A layer of the instrument cluster's surfaces: its visibility and opacity combine with
    // each member's own.
    s(&["layer", "create", "ic"]);
    s(&["layer", "ic", "add", "100"]);
    s(&["layer", "ic", "add", "300"]);
    s(&["layer", "ic", "opacity", "0.5"]);
    scene.check("layer ic at half opacity (300 at a quarter)");
    let (rows, layers) = list(&socket);
    assert_eq!(layers, vec![LayerRow { name: "ic".into(), visible: true, opacity: 0.5, surfaces: vec![100, 300] }]);
    assert_eq!(rows.iter().find(|r| r.id == 300).map(|r| r.shown_opacity), Some(0.25));
    s(&["layer", "ic", "visibility", "off"]);
    scene.check("layer ic hidden");
    s(&["layer", "ic", "remove", "300"]);
    scene.check("300 out of the hidden layer");
    s(&["layer", "destroy", "ic"]);
    scene.check("layer ic destroyed");
    assert!(list(&socket).1.is_empty());

    for c in scene.clients {
        c.stop();
    }
}

#[test]
fn bad_input_is_refused_and_nothing_of_a_failed_batch_applies() {
    let scene = Scene::start();
    let socket = scene.socket();
    let refused = |args: &[&str], says: &str| {
        let e = try_ctl(&socket, args).expect_err(&format!("{args:?} must fail"));
        assert!(e.contains(says), "{args:?}: {e}");
    };
    let before = list(&socket);
    refused(&["surface", "999", "opacity", "0.5"], "no surface 999");
    refused(&["surface", "100", "opacity", "1.5"], "opacity 1.5 is outside [0, 1]");
    refused(&["surface", "100", "opacity", "-0.5"], "opacity -0.5 is outside [0, 1]");
    refused(&["surface", "100", "source-region", "0", "0", "-1", "4"], "negative size");
    refused(&["surface", "100", "destination-region", "0", "0", "4", "-4"], "negative size");
    refused(&["surface", "100", "visibility", "maybe"], "invalid value 'maybe'");
    refused(&["layer", "nope", "add", "100"], "no layer \"nope\"");
    refused(&["layer", "bad name", "add", "100"], "layer name");
    refused(&["layer", "create", "bad/name"], "layer name");
    refused(&["layer", "ic", "fly"], "not a layer command");
    ctl(&socket, &["layer", "create", "ic"]);
    refused(&["layer", "create", "ic"], "layer \"ic\" exists already");
    refused(&["layer", "ic", "add", "999"], "no surface 999");
    refused(&["layer", "ic", "remove", "100"], "surface 100 is not in layer \"ic\"");
    refused(&["layer", "ic", "opacity", "2"], "opacity 2 is outside [0, 1]");
    ctl(&socket, &["layer", "destroy", "ic"]);
    refused(&["layer", "destroy", "ic"], "no layer \"ic\"");
    // A malformed batch, and one whose third change fails: nothing of either applies.
    let bad = scene.file("bad.json", r#"{"changes": [{"opacity": {"surface": 100, "opacity": 0.3}}"#);
    refused(&["apply", &bad], "is not a batch of changes");
    let unknown = scene
        .file("unknown.json", r#"{"changes": [{"opacity": {"surface": 100, "opacity": 0.3}}, {"frobnicate": {}}]}"#);
    refused(&["apply", &unknown], "unknown variant `frobnicate`");
    let partial = scene.file(
        "partial.json",
        r#"{"changes": [
            {"opacity": {"surface": 100, "opacity": 0.3}},
            {"layer-create": {"layer": "hu"}},
            {"visibility": {"surface": 999, "visible": false}}
        ]}"#,
    );
    refused(&["apply", &partial], "change 2 of the batch: no surface 999");
    refused(&["apply", &partial], "nothing of the batch applied");
    let range = scene.file(
        "range.json",
        r#"{"changes": [{"opacity": {"surface": 100, "opacity": 0.3}}, {"opacity": {"surface": 200, "opacity": 7}}]}"#,
    );
    refused(&["apply", &range], "change 1 of the batch: opacity 7 is outside [0, 1]");
    refused(&["apply", "/nonexistent/batch.json"], "reading /nonexistent/batch.json");
    assert_eq!(list(&socket), before, "nothing applied");
    scene.check("after the refusals");
    for c in scene.clients {
        c.stop();
    }
}

/// Screenshots taken while batches of three changes to three surfaces are applied back and
/// forth show either batch's whole result, never part of one.
#[test]
fn a_batch_shows_wholly_or_not_at_all() {
    let scene = Scene::start();
    let socket = scene.socket();
    let one = scene.file(
        "one.json",
        r#"{"changes": [
            {"opacity": {"surface": 100, "opacity": 0.25}},
            {"visibility": {"surface": 300, "visible": false}},
            {"destination-region": {"surface": 200, "region": [30, 20, 32, 24]}}
        ]}"#,
    );
    let two = scene.file(
        "two.json",
        r#"{"changes": [
            {"opacity": {"surface": 100, "opacity": 1}},
            {"visibility": {"surface": 300, "visible": true}},
            {"destination-region": {"surface": 200, "region": [12, 10, 16, 16]}}
        ]}"#,
    );
    assert_eq!(ctl(&socket, &["apply", &one]).trim(), "applied 3 changes");
    let want_one = scene.expected();
    ctl(&socket, &["apply", &two]);
    let want_two = scene.expected();
    assert!(differing(&want_one, &want_two) > 100, "the two states differ widely");
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let flipper = {
        let (stop, socket, one, two) = (stop.clone(), socket.clone(), one.clone(), two.clone());
        std::thread::spawn(move || {
            let mut n = 0;
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                ctl(&socket, &["apply", if n % 2 == 0 { &one } else { &two }]);
                n += 1;
            }
            n
        })
    };
    let (mut ones, mut twos) = (0, 0);
    for i in 0..30 {
        let got = scene.output();
        match (differing(&got, &want_one), differing(&got, &want_two)) {
            (0, _) => ones += 1,
            (_, 0) => twos += 1,
            (a, b) => {
                panic!("screenshot {i} shows part of a batch: {a} pixels off the first state, {b} off the second")
            }
        }
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    let flips = flipper.join().expect("flipper");
    eprintln!("{flips} batches applied; screenshots: {ones} of the first state, {twos} of the second");
    assert!(flips >= 2, "the batches ran while the screenshots were taken");
    for c in scene.clients {
        c.stop();
    }
}

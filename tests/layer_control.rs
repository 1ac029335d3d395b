//! The layer-manager controls against a running daemon with real client processes:
//! `ctl surface ID visibility|opacity|source-region|destination-region`, `ctl layer …` and
//! `ctl apply FILE.json`. Every state the output reaches is compared with the f64 reference
//! compositor, fed with each surface's own frame (`ctl screenshot --surface`) and the
//! properties `ctl list --json` reports. A batch applied while screenshots are taken shows
//! either wholly or not at all, and every bad input is refused with nothing applied.

mod support;

use strata_protocol::properties::LayerRow;
use support::scene::{ctl, differing, list, try_ctl, Scene, W};
use support::windows;

#[test]
fn client_process() {
    windows::serve();
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

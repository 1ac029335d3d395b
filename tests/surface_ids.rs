//! Stable surface IDs with real client processes: the layout's `id` (one, or a list in the
//! order a client creates its window surfaces) wins, then `STRATA_SURFACE_ID` in the client's
//! environment, then the application's own `EGL_SURFACE_ID_STRATA`; a surface without one
//! gets a runtime ID that none of those can be. `eglQuerySurface` and `ctl list` report the
//! ID, `ctl move` addresses it, a second live surface claiming an ID fails with
//! `EGL_BAD_MATCH` and a log line naming the holder, a malformed `STRATA_SURFACE_ID` fails with
//! `EGL_BAD_ATTRIBUTE`, and a client that restarts gets its ID back.
//!
//! Each client is this test binary run again as `client_process`, which loads the drop-in
//! libEGL, creates window surfaces, prints what it got and keeps them until its stdin closes.

mod support;

use std::process::Command;

use strata_protocol::control::SurfaceRow;
use support::windows::{self, Client, EGL_BAD_ATTRIBUTE, EGL_BAD_MATCH};
use support::{Daemon, TempDir};

#[test]
fn client_process() {
    windows::serve();
}

fn ctl(socket: &std::path::Path, args: &[&str]) -> String {
    let out = Command::new(support::stratad()).arg("ctl").args(args).arg("--socket").arg(socket).output().expect("ctl");
    assert!(out.status.success(), "ctl {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("utf-8")
}

fn rows(socket: &std::path::Path) -> Vec<SurfaceRow> {
    let v: serde_json::Value = serde_json::from_str(&ctl(socket, &["list", "--json"])).expect("json");
    serde_json::from_value(v["surfaces"].clone()).expect("surface rows")
}

#[test]
fn surfaces_keep_the_ids_the_layout_the_environment_or_the_application_give() {
    let dir = TempDir::new("surface-ids");
    let config = dir.0.join("config.toml");
    let entry =
        |client: &str, id: &str| format!("[[layout]]\nclient = \"{client}\"\nx = 0\ny = 0\nz = 0.5\nid = {id}\n\n");
    std::fs::write(&config, entry("ic", "1000") + &entry("hu", "[2000, 2001]")).expect("config");
    let daemon = Daemon::start("surface-ids", &["--output", "t=64x64", "--config", config.to_str().expect("utf-8")]);
    let socket = daemon.socket.clone();
    let shim = support::shim_dir(&dir);

    // The layout wins over the environment; a list is taken in creation order, and a surface
    // beyond it gets a runtime ID, which is never one the layout gives.
    let ic = Client::start(&socket, &shim, "ic", 1, Some("5"), None, false);
    assert_eq!(ic.got, vec![Ok(1000)]);
    let hu = Client::start(&socket, &shim, "hu", 3, None, None, false);
    assert_eq!(hu.got[..2], [Ok(2000), Ok(2001)]);
    let runtime = hu.got[2].expect("a runtime id");
    assert!(![1000, 2000, 2001].contains(&runtime), "runtime id {runtime}");

    // The environment, then the application's own attribute; a second live claim is refused.
    let app = Client::start(&socket, &shim, "app", 1, Some("3000"), Some(3500), false);
    assert_eq!(app.got, vec![Ok(3000)], "STRATA_SURFACE_ID wins over the application's attribute");
    let own = Client::start(&socket, &shim, "own", 1, None, Some(4000), false);
    assert_eq!(own.got, vec![Ok(4000)]);
    // A refused claim does not use the ID up: the same window asks for it again.
    let twin = Client::start(&socket, &shim, "twin", 2, Some("3000,4001"), None, false);
    assert_eq!(twin.got, vec![Err(EGL_BAD_MATCH), Err(EGL_BAD_MATCH)], "3000 is app's");
    daemon.wait_log("surface id 3000 is already held by a surface of client \"app\"");
    let bad = Client::start(&socket, &shim, "bad", 1, Some("cluster"), None, false);
    assert_eq!(bad.got, vec![Err(EGL_BAD_ATTRIBUTE)]);
    let zero = Client::start(&socket, &shim, "zero", 1, None, Some(0), false);
    assert_eq!(zero.got, vec![Err(EGL_BAD_ATTRIBUTE)]);
    daemon.wait_log("surface id 0 is outside 1..=");

    // ctl list reports the IDs, in creation order; ctl move addresses a stable one.
    let ids: Vec<(u64, String)> = rows(&socket).into_iter().map(|r| (r.id, r.client)).collect();
    let want: Vec<(u64, String)> =
        [(1000, "ic"), (2000, "hu"), (2001, "hu"), (runtime as u64, "hu"), (3000, "app"), (4000, "own")]
            .into_iter()
            .map(|(id, c)| (id, c.to_string()))
            .collect();
    assert_eq!(ids, want);
    ctl(&socket, &["move", "1000", "8", "4", "0.25"]);
    let moved = rows(&socket).into_iter().find(|r| r.id == 1000).expect("ic's surface");
    assert_eq!((moved.rect[0], moved.rect[1], moved.z), (8, 4, 0.25));

    // A surface's newest frame, as its client drew it (top row first in the PNG); a surface
    // that never swapped, and an unknown one, are clear errors.
    let painter = Client::start(&socket, &shim, "painter", 1, Some("5000"), None, true);
    assert_eq!(painter.got, vec![Ok(5000)]);
    let png = dir.0.join("surface.png");
    ctl(&socket, &["screenshot", "--surface", "5000", png.to_str().expect("utf-8")]);
    let img = image::open(&png).expect("png").to_rgba8();
    assert_eq!(img.dimensions(), (16, 16));
    assert_eq!((img.get_pixel(8, 2).0, img.get_pixel(8, 13).0), ([0, 255, 0, 255], [255, 0, 0, 255]), "green on top");
    for (id, says) in [("1000", "surface 1000 has not swapped a frame yet"), ("777", "no surface 777")] {
        let out = Command::new(support::stratad())
            .args(["ctl", "screenshot", "--surface", id, png.to_str().expect("utf-8"), "--socket"])
            .arg(&socket)
            .output()
            .expect("ctl");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success() && err.contains(says), "{id}: {err}");
    }
    painter.stop();

    // The instrument cluster restarts: its surface gets its ID back; the claim that failed
    // succeeds once the holder is gone.
    ic.stop();
    app.stop();
    let ic = Client::start(&socket, &shim, "ic", 1, None, None, false);
    assert_eq!(ic.got, vec![Ok(1000)]);
    let twin2 = Client::start(&socket, &shim, "twin2", 1, Some("3000"), None, false);
    assert_eq!(twin2.got, vec![Ok(3000)]);
    for c in [ic, hu, own, twin, bad, zero, twin2] {
        c.stop();
    }
}

//! A daemon with three painting clients whose output the tests compare with the f64 reference
//! compositor, and `stratad ctl` run as a process.

use std::path::Path;
use std::process::Command;

use strata_compositor::reference::{self, RefLayer};
use strata_compositor::{Lighting, Props, Source};
use strata_protocol::control::SurfaceRow;
use strata_protocol::properties::LayerRow;

use super::windows::Client;
use super::{Daemon, TempDir};

/// The output's width.
pub const W: u32 = 64;
/// The output's height.
pub const H: u32 = 48;

/// `stratad ctl ARGS --socket SOCKET`: its stdout, or its stderr as the error.
pub fn try_ctl(socket: &Path, args: &[&str]) -> Result<String, String> {
    let out = Command::new(super::stratad()).arg("ctl").args(args).arg("--socket").arg(socket).output().expect("ctl");
    if out.status.success() {
        Ok(String::from_utf8(out.stdout).expect("utf-8"))
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

pub fn ctl(socket: &Path, args: &[&str]) -> String {
    try_ctl(socket, args).unwrap_or_else(|e| panic!("ctl {args:?}: {e}"))
}

/// Surfaces and layers as `ctl list --json` gives them.
pub fn list(socket: &Path) -> (Vec<SurfaceRow>, Vec<LayerRow>) {
    let v: serde_json::Value = serde_json::from_str(&ctl(socket, &["list", "--json"])).expect("json");
    (
        serde_json::from_value(v["surfaces"].clone()).expect("surface rows"),
        serde_json::from_value(v["layers"].clone()).expect("layer rows"),
    )
}

/// A PNG written by `ctl screenshot`, as RGBA rows top first.
pub fn png(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path).expect("png").to_rgba8();
    (img.width(), img.height(), img.into_raw())
}

/// The scene's clients: name, surface ID, `STRATA_WINDOW`, and the colours of its frame's
/// bottom and top halves.
pub const PAINT: [(&str, &str, &str, [[f32; 3]; 2]); 3] = [
    ("a", "100", "4,4,0.5,16x16", [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]),
    ("b", "200", "12,10,0.5,16x16", [[0.0, 0.0, 1.0], [0.0, 1.0, 1.0]]),
    ("c", "300", "16,14,0.25,16x16", [[1.0, 0.0, 1.0], [1.0, 1.0, 1.0]]),
];

/// The daemon, its clients and each surface's frame (RGBA, bottom row first, as the reference
/// takes it), by surface ID.
pub struct Scene {
    pub dir: TempDir,
    pub daemon: Daemon,
    pub clients: Vec<Client>,
    pub frames: Vec<(u64, Vec<u8>)>,
    pub shot: std::path::PathBuf,
    /// The drop-in libraries' directory.
    pub shim: std::path::PathBuf,
}

impl Scene {
    /// Three 16×16 clients: 100 and 200 overlapping in one z-group, 300 nearer and overlapping
    /// both, each of two colours.
    pub fn start() -> Scene {
        let dir = TempDir::new("layer-control");
        let output = format!("t={W}x{H}");
        let daemon = Daemon::start("layer-control", &["--output", &output]);
        let socket = daemon.socket.clone();
        let shim = super::shim_dir(&dir);
        let clients: Vec<Client> = PAINT
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
        Scene { dir, daemon, clients, frames, shot, shim }
    }

    /// A file in the test's directory holding `text`.
    pub fn file(&self, name: &str, text: &str) -> String {
        let path = self.dir.0.join(name);
        std::fs::write(&path, text).expect("write");
        path.to_str().expect("utf-8").to_string()
    }

    pub fn socket(&self) -> std::path::PathBuf {
        self.daemon.socket.clone()
    }

    /// What the f64 reference composites from the rows `ctl list` reports now.
    pub fn expected(&self) -> Vec<u8> {
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
    pub fn output(&self) -> Vec<u8> {
        ctl(&self.socket(), &["screenshot", "t", self.shot.to_str().expect("utf-8")]);
        let (w, h, rgba) = png(&self.shot);
        assert_eq!((w, h), (W, H));
        rgba
    }

    /// Asserts that the output matches the reference, naming the step.
    pub fn check(&self, step: &str) {
        let (got, want) = (self.output(), self.expected());
        let bad = differing(&got, &want);
        assert!(bad == 0, "{step}: {bad} pixels differ from the f64 reference by more than 1");
    }
}

/// `r` clipped to `to`, an empty rectangle where they miss.
pub fn clip(r: [i32; 4], to: [i32; 4]) -> [i32; 4] {
    let x0 = r[0].max(to[0]);
    let y0 = r[1].max(to[1]);
    let x1 = (r[0] + r[2]).min(to[0] + to[2]);
    let y1 = (r[1] + r[3]).min(to[1] + to[3]);
    [x0, y0, (x1 - x0).max(0), (y1 - y0).max(0)]
}

/// Pixels of `a` and `b` that differ by more than 1 in some channel.
pub fn differing(a: &[u8], b: &[u8]) -> usize {
    a.chunks(4).zip(b.chunks(4)).filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 1)).count()
}

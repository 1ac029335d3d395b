//! Composites drawn band by band: a change of a low-priority surface that would hold up the
//! next refresh is drawn in bands between refreshes, into a staging image copied in whole.
//! Forced here for every change (`--band-above-ms 0 --band-ms 0`: bands of 8 rows), the
//! bands happen while only `ctl list` is asked (no screenshot finishes them), the
//! high-priority client keeps its refreshes, and the output the bands leave shows the frame
//! as GL's clear and scissor define it, row for row.

mod support;

use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use strata_client::setup::Current;
use strata_client::{Calls, Connection, ControlConnection};
use strata_protocol::control::OutputRow;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use support::gl::{clear, connect, window, GL_SCISSOR_TEST};
use support::{Daemon, TempDir};

/// The low-priority surface: x, y, width, height.
const HU: [i32; 4] = [80, 8, 160, 112];
/// The high-priority surface, beside it.
const IC: [i32; 4] = [0, 0, 64, 64];

/// Frame `f`'s colours: rows below `split(f)` (GL's bottom-up rows) one colour, above another.
fn frame(f: u32) -> ([u8; 3], [u8; 3], i32) {
    let v = (f % 200) as u8;
    ([200, v, 40], [30, 90, 250 - v], 13 + (f % 7) as i32 * 11)
}

fn draw(gl: &mut Connection, cur: Current, f: u32) {
    let (below, above, split) = frame(f);
    gl.glDisable(GL_SCISSOR_TEST).expect("io");
    clear(gl, above);
    gl.glEnable(GL_SCISSOR_TEST).expect("io");
    gl.glScissor(0, 0, HU[2], split).expect("io");
    clear(gl, below);
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
}

fn output(socket: &Path) -> OutputRow {
    match ControlConnection::connect_beside(socket).expect("control").request(&ControlRequest::List).expect("list") {
        ControlReply::List { mut outputs, .. } => outputs.remove(0),
        other => panic!("list: {other:?}"),
    }
}

#[test]
fn a_low_priority_change_is_drawn_in_bands_between_refreshes() {
    let dir = TempDir::new("bands-config");
    let config = dir.0.join("stratad.toml");
    let entry = |name: &str, r: [i32; 4], class: &str| {
        format!("[[layout]]\nclient = \"{name}\"\nx = {}\ny = {}\nz = 0.5\npriority = \"{class}\"\n\n", r[0], r[1])
    };
    std::fs::write(&config, entry("ic", IC, "high") + &entry("hu", HU, "low")).expect("config");
    let daemon = Daemon::start(
        "bands",
        &[
            "--lighting",
            "off",
            "--output",
            "headless:b=256x128",
            "--band-above-ms",
            "0",
            "--band-ms",
            "0",
            "--config",
            config.to_str().expect("utf-8 path"),
        ],
    );
    let socket = daemon.socket.clone();

    // The IC swaps at interval 1 throughout, paced by the refreshes.
    let stop = Arc::new(AtomicBool::new(false));
    let ic_frames = Arc::new(AtomicU64::new(0));
    let ic = {
        let (socket, stop, frames) = (socket.clone(), stop.clone(), ic_frames.clone());
        std::thread::spawn(move || {
            let mut gl = connect(&socket, "ic");
            let cur = window(&mut gl, IC, 1);
            while !stop.load(Ordering::Acquire) {
                clear(&mut gl, [0, 200, 0]);
                gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("swap");
                frames.fetch_add(1, Ordering::Relaxed);
            }
            // Connected still: its surface stays on the output.
            gl
        })
    };

    // The HU draws until several of its frames were composited in bands, with nothing but
    // `ctl list` asked of the compositor.
    let mut gl = connect(&socket, "hu");
    let cur = window(&mut gl, HU, 0);
    let (start, ic_start) = (Instant::now(), ic_frames.load(Ordering::Relaxed));
    let mut f = 0;
    while output(&socket).banded < 5 {
        assert!(start.elapsed() < Duration::from_secs(30), "no composite was banded: {:?}", output(&socket));
        draw(&mut gl, cur, f);
        f += 1;
        std::thread::sleep(Duration::from_millis(5));
    }
    let secs = start.elapsed().as_secs_f64();
    let ic_rate = (ic_frames.load(Ordering::Relaxed) - ic_start) as f64 / secs;
    stop.store(true, Ordering::Release);
    let ic = ic.join().expect("the IC thread");
    assert!(secs < 1.0 || ic_rate > 20.0, "the IC swapped {ic_rate:.1} times a second beside the bands");

    // The last frame: banded by the compositor thread, which a screenshot then only reads.
    let before = output(&socket).banded;
    draw(&mut gl, cur, f);
    let start = Instant::now();
    while output(&socket).banded == before {
        assert!(start.elapsed() < Duration::from_secs(20), "the last frame was never banded");
        std::thread::sleep(Duration::from_millis(10));
    }
    std::thread::sleep(Duration::from_millis(300));
    let composites = output(&socket).composites;
    let img = match ControlConnection::connect_beside(&socket)
        .expect("control")
        .request(&ControlRequest::Screenshot { output: "b".into() })
        .expect("screenshot")
    {
        ControlReply::Image { width, height, rgba } => image::RgbaImage::from_raw(width, height, rgba.0).expect("size"),
        other => panic!("screenshot: {other:?}"),
    };
    assert_eq!(output(&socket).composites, composites, "the screenshot composited again");
    let (below, above, split) = frame(f);
    let mut wrong = 0;
    for row in 0..HU[3] {
        // Output rows run top-down; GL's rows bottom-up.
        let want = if HU[3] - 1 - row < split { below } else { above };
        for x in 0..HU[2] {
            let p = img.get_pixel((HU[0] + x) as u32, (HU[1] + row) as u32).0;
            if [p[0], p[1], p[2]] != want {
                wrong += 1;
            }
        }
    }
    assert_eq!(wrong, 0, "{wrong} pixels of the banded frame differ");
    let p = img.get_pixel(10, 10).0;
    assert_eq!([p[0], p[1], p[2]], [0, 200, 0], "the IC");
    drop((gl, ic));
    daemon.stop();
}

//! Input routing against a running daemon: taps go to the surface whose fragment is shown at
//! that point, which the f64 reference compositor decides from the clients' geometry (tilted
//! planes at one z whose depths cross along a known line, and a nearer group that is
//! transparent over half of it). Keys go only to the focused surface; a surface with input
//! off never receives an event; bad input is dropped or refused without reaching another
//! surface, and the daemon and its other clients carry on.

mod support;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver};
use std::sync::Arc;
use std::time::Duration;

use strata_client::setup::{egl_context, link_program, SurfaceKind};
use strata_client::{Calls, ConnectOptions, Connection, ControlConnection};
use strata_compositor::reference::{self, RefLayer};
use strata_compositor::Props;
use strata_protocol::events::Event;
use strata_protocol::handshake::{ControlReply, ControlRequest};
use strata_protocol::input::{Action, Device, InputEvent, InputOutcome, InputRequest, Phase};
use strata_protocol::{Blob, Slice, Text};
use support::Daemon;

/// The output: 256×128 pixels, named `main`.
const OUT: (i32, i32) = (256, 128);

/// One client's window: where it is, and what it draws. Its quad spans NDC x from `span.0`
/// to `span.1` (all of y) at NDC depth `plane[0]·x + plane[1]·y + plane[2]`, opaque; the rest
/// is cleared to transparent black at depth 1.
#[derive(Clone, Copy)]
struct Spec {
    name: &'static str,
    rect: [i32; 4],
    z: f32,
    plane: [f64; 3],
    span: (f64, f64),
    color: [f32; 3],
}

const IC: Spec = Spec {
    name: "ic",
    rect: [20, 10, 160, 100],
    z: 0.5,
    plane: [0.8, 0.0, 0.0],
    span: (-1.0, 1.0),
    color: [1.0, 0.5, 0.0],
};
const HU: Spec = Spec {
    name: "hu",
    rect: [70, 20, 160, 100],
    z: 0.5,
    plane: [-0.8, 0.1, 0.0],
    span: (-1.0, 1.0),
    color: [0.0, 0.3, 1.0],
};
/// A nearer group's surface, opaque over its left half only.
const FRONT: Spec = Spec {
    name: "front",
    rect: [110, 30, 60, 60],
    z: 0.2,
    plane: [0.0, 0.0, 0.9],
    span: (-1.0, 0.0),
    color: [0.0, 1.0, 0.0],
};

impl Spec {
    /// NDC depth at NDC (x, y).
    fn ndc_depth(&self, x: f64, y: f64) -> f64 {
        self.plane[0] * x + self.plane[1] * y + self.plane[2]
    }

    /// The reference's view of it: colour and window depth of every pixel, bottom row first,
    /// from the geometry alone.
    fn reference(&self) -> RefLayer {
        let [_, _, w, h] = self.rect;
        let (mut color, mut depth) = (Vec::new(), Vec::new());
        for sy in 0..h {
            for sx in 0..w {
                let x = (f64::from(sx) + 0.5) / f64::from(w) * 2.0 - 1.0;
                let y = (f64::from(sy) + 0.5) / f64::from(h) * 2.0 - 1.0;
                if x >= self.span.0 && x < self.span.1 {
                    color.extend(self.color.map(|c| (c * 255.0).round() as u8));
                    color.push(255);
                    depth.push(((self.ndc_depth(x, y) + 1.0) / 2.0) as f32);
                } else {
                    color.extend([0, 0, 0, 0]);
                    depth.push(1.0);
                }
            }
        }
        RefLayer {
            rect: self.rect,
            z: self.z,
            color,
            depth: Some(depth),
            normal: [0.0, 0.0, 1.0],
            projection: None,
            props: Props::default(),
        }
    }
}

const VS: &str = "attribute vec4 pos; void main() { gl_Position = pos; }";
const FS: &str = "precision mediump float; uniform vec3 col; void main() { gl_FragColor = vec4(col, 1.0); }";

/// A client on its own thread: it draws its spec once, then passes on every input event it
/// receives (when `reads`; else it reads none) until stopped.
struct Client {
    events: Receiver<InputEvent>,
    stop: Arc<AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Client {
    fn start(socket: &Path, spec: Spec, reads: bool) -> Client {
        let (tx, events) = channel();
        let (ready_tx, ready) = channel();
        let stop = Arc::new(AtomicBool::new(false));
        let stopped = stop.clone();
        let socket = socket.to_path_buf();
        let thread = std::thread::spawn(move || {
            let opts = ConnectOptions { socket, name: spec.name.into(), ..Default::default() };
            let mut gl = Connection::connect(&opts).expect("connect");
            draw(&mut gl, spec);
            ready_tx.send(()).expect("ready");
            while !stopped.load(Ordering::Relaxed) {
                if !reads {
                    std::thread::sleep(Duration::from_millis(10));
                    continue;
                }
                match gl.next_input(Duration::from_millis(20)) {
                    Ok(Some(e)) => {
                        let _ = tx.send(e);
                    }
                    Ok(None) => {}
                    Err(_) => return,
                }
            }
        });
        ready.recv_timeout(Duration::from_secs(60)).expect("the client drew its frame");
        Client { events, stop, thread: Some(thread) }
    }

    /// Every event received within `wait`.
    fn drain(&self, wait: Duration) -> Vec<InputEvent> {
        let mut v = Vec::new();
        while let Ok(e) = self.events.recv_timeout(wait) {
            v.push(e);
        }
        v
    }

    /// The next event, waiting up to 5 s.
    fn next(&self) -> InputEvent {
        self.events.recv_timeout(Duration::from_secs(5)).expect("an input event")
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Draws `spec` into a new window surface and swaps.
fn draw(gl: &mut Connection, spec: Spec) {
    let cur = egl_context(gl, 24, 0, SurfaceKind::Window { rect: spec.rect, z: spec.z }).expect("context");
    let p = link_program(gl, (1, 2, 3), VS, FS, &["pos"]).expect("program");
    let col = gl.glGetUniformLocation(p, Text::borrowed("col")).expect("io");
    gl.glUniform3f(col, spec.color[0], spec.color[1], spec.color[2]).expect("io");
    gl.glEnable(0x0B71).expect("io"); // GL_DEPTH_TEST
    let (x0, x1) = (spec.span.0, spec.span.1);
    // A little past the top and bottom edges, so that the quad covers every row.
    let corner = |x: f64, y: f64| [x as f32, y as f32, spec.ndc_depth(x, y) as f32, 1.0];
    let c = [corner(x0, -1.1), corner(x1, -1.1), corner(x1, 1.1), corner(x0, 1.1)];
    let verts: Vec<f32> = [0, 1, 2, 0, 2, 3].iter().flat_map(|&i| c[i]).collect();
    let bytes: &[u8] = bytemuck::cast_slice(&verts);
    gl.glGenBuffers(Slice::new(&[10])).expect("io");
    gl.glBindBuffer(0x8892, 10).expect("io");
    gl.glBufferData(0x8892, bytes.len() as i64, Some(Blob::borrowed(bytes)), 0x88E4).expect("io");
    gl.glVertexAttribPointer(0, 4, 0x1406, false, 16, 0).expect("io");
    gl.glEnableVertexAttribArray(0).expect("io");
    gl.glClearColor(0.0, 0.0, 0.0, 0.0).expect("io");
    gl.glClear(0x4000 | 0x0100).expect("io");
    gl.glDrawArrays(0x0004, 0, 6).expect("io");
    gl.eglSwapBuffers(cur.display, cur.surface).expect("io").expect("eglSwapBuffers");
    gl.glFinish().expect("io");
}

/// The daemon and the control connection the test drives it with.
struct Bench {
    daemon: Daemon,
    control: ControlConnection,
}

impl Bench {
    fn start(tag: &str) -> Bench {
        Bench::start_with(tag, &[])
    }

    /// A daemon given `extra` options besides the output.
    fn start_with(tag: &str, extra: &[&str]) -> Bench {
        let size = format!("headless:main={}x{}", OUT.0, OUT.1);
        let mut args = vec!["--lighting", "off", "--output", &size];
        args.extend_from_slice(extra);
        let daemon = Daemon::start(tag, &args);
        let control = ControlConnection::connect_beside(&daemon.socket).expect("control");
        Bench { daemon, control }
    }

    fn socket(&self) -> PathBuf {
        self.daemon.socket.clone()
    }

    fn request(&mut self, req: ControlRequest) -> ControlReply {
        self.control.request(&req).expect("control request")
    }

    /// `ctl input` on `main`: where its events went, or the daemon's refusal.
    fn input(&mut self, action: Action) -> Result<InputOutcome, String> {
        match self.request(ControlRequest::Input(InputRequest { output: "main".into(), action })) {
            ControlReply::Input(o) => Ok(o),
            ControlReply::Error(e) => Err(e),
            other => panic!("unexpected reply {other:?}"),
        }
    }

    fn tap(&mut self, x: f32, y: f32) -> Option<u64> {
        self.input(Action::Tap { x, y }).expect("tap").surface
    }

    /// Each client's surface ID, by client name.
    fn ids(&mut self) -> std::collections::HashMap<String, u64> {
        match self.request(ControlRequest::List) {
            ControlReply::List { surfaces, .. } => surfaces.into_iter().map(|s| (s.client, s.id)).collect(),
            other => panic!("unexpected reply {other:?}"),
        }
    }

    fn change(&mut self, c: strata_protocol::properties::Change) {
        match self.request(ControlRequest::Apply { changes: vec![c] }) {
            ControlReply::List { .. } => {}
            other => panic!("unexpected reply {other:?}"),
        }
    }
}

/// The reference's pick at the centre of output pixel (x, y), as a spec index.
fn expected(specs: &[Spec], x: i32, y: i32) -> Option<usize> {
    let layers: Vec<RefLayer> = specs.iter().map(Spec::reference).collect();
    reference::pick(&layers, x, y)
}

/// Whether the reference picks the same everywhere within `r` pixels of (x, y) (a tap there
/// lies a few pixels away from any line where the answer changes).
fn settled(layers: &[RefLayer], x: i32, y: i32, r: i32) -> bool {
    let at = reference::pick(layers, x, y);
    (-r..=r).all(|dy| (-r..=r).all(|dx| reference::pick(layers, x + dx, y + dy) == at))
}

/// Taps either side of the line where the two tilted planes (`specs` 0 and 1) cross, a few
/// pixels away, on several rows: the nearer plane's client (`id`) must get each.
fn taps_either_side_of_the_crossing(b: &mut Bench, layers: &[RefLayer], id: impl Fn(usize) -> u64) {
    let mut crossings = 0;
    for y in [25, 40, 60, 95, 105] {
        let row: Vec<Option<usize>> = (0..OUT.0).map(|x| reference::pick(layers, x, y)).collect();
        let Some(x) = (1..OUT.0 as usize).find(|&x| row[x - 1] == Some(0) && row[x] == Some(1)) else { continue };
        let x = x as i32;
        crossings += 1;
        assert_eq!(b.tap((x - 3) as f32 + 0.5, y as f32 + 0.5), Some(id(0)), "3 px left of the line at row {y} ({x})");
        assert_eq!(b.tap((x + 2) as f32 + 0.5, y as f32 + 0.5), Some(id(1)), "3 px right of the line at row {y} ({x})");
    }
    assert!(crossings >= 3, "the planes cross on only {crossings} of the rows tried");
}

#[test]
fn taps_reach_the_surface_whose_fragment_is_shown_there() {
    let mut b = Bench::start("input-pick");
    let socket = b.socket();
    let specs = [IC, HU, FRONT];
    let clients: Vec<Client> = specs.iter().map(|s| Client::start(&socket, *s, true)).collect();
    let ids = b.ids();
    let id = |i: usize| ids[specs[i].name];
    let layers: Vec<RefLayer> = specs.iter().map(Spec::reference).collect();
    taps_either_side_of_the_crossing(&mut b, &layers, id);

    // A grid over the whole output, each tap where the reference's answer is settled.
    let mut checked = [0usize; 4];
    for y in (2..OUT.1).step_by(6) {
        for x in (2..OUT.0).step_by(6) {
            if !settled(&layers, x, y, 2) {
                continue;
            }
            let want = reference::pick(&layers, x, y);
            assert_eq!(b.tap(x as f32 + 0.5, y as f32 + 0.5), want.map(id), "tap at ({x}, {y})");
            checked[want.map_or(3, |i| i)] += 1;
        }
    }
    assert!(checked.iter().all(|&n| n >= 5), "taps per outcome (ic, hu, front, none): {checked:?}");
    // Input routing read those texels on its own device, never waiting for the compositor's.
    let [own, compositor] = support::stats(&socket).pick_reads;
    assert!(own > 0 && compositor == 0, "texels read on input's device {own}, on the compositor's {compositor}");

    // The nearer group's transparent half lets taps through to the group behind.
    let (fx, fy) = (FRONT.rect[0] + 45, FRONT.rect[1] + 30);
    assert_eq!(expected(&specs, fx, fy).map(|i| specs[i].name), Some("hu"));
    assert_eq!(b.tap(fx as f32 + 0.5, fy as f32 + 0.5), Some(id(1)), "through the transparent half");
    assert_eq!(b.tap((FRONT.rect[0] + 15) as f32, fy as f32), Some(id(2)), "on the opaque half");

    // Each tap reached its client as a touch down and up at the point, in its own pixels.
    for c in &clients {
        c.drain(Duration::from_millis(300));
    }
    let (tx, ty) = (30.5f32, 50.5f32);
    assert_eq!(b.tap(tx, ty), Some(id(0)));
    let mut got: Vec<InputEvent> = Vec::new();
    while got.len() < 2 {
        match clients[0].next() {
            e @ InputEvent::Point { .. } => got.push(e),
            InputEvent::Focus { .. } => {}
            other => panic!("unexpected {other:?}"),
        }
    }
    let local = (tx - IC.rect[0] as f32, ty - IC.rect[1] as f32);
    for (e, phase) in got.iter().zip([Phase::Down, Phase::Up]) {
        assert_eq!(
            *e,
            InputEvent::Point { surface: id(0), device: Device::Touch, id: 0, phase, x: local.0, y: local.1 }
        );
    }

    // Shown at half size through a destination region, a surface gets points in its image's
    // own pixels: the region's offset and scale undone.
    let region = [0, 0, IC.rect[2] / 2, IC.rect[3] / 2];
    b.change(strata_protocol::properties::Change::DestinationRegion { surface: id(0), region });
    assert_eq!(b.tap(10.5, 20.5), Some(id(0)));
    let down = loop {
        match clients[0].next() {
            e @ InputEvent::Point { phase: Phase::Down, .. } => break e,
            _ => continue,
        }
    };
    assert!(matches!(down, InputEvent::Point { x: 21.0, y: 41.0, .. }), "{down:?}");
}

#[test]
fn picks_on_the_compositors_device_reach_the_same_surfaces() {
    let mut b = Bench::start_with("input-pick-compositor", &["--input-pick", "compositor"]);
    let socket = b.socket();
    let specs = [IC, HU];
    let _clients: Vec<Client> = specs.iter().map(|s| Client::start(&socket, *s, true)).collect();
    let ids = b.ids();
    let layers: Vec<RefLayer> = specs.iter().map(Spec::reference).collect();
    taps_either_side_of_the_crossing(&mut b, &layers, |i| ids[specs[i].name]);
    let [own, compositor] = support::stats(&socket).pick_reads;
    assert!(own == 0 && compositor > 0, "texels read on input's device {own}, on the compositor's {compositor}");
}

#[test]
fn a_surface_with_input_off_never_gets_an_event_and_input_passes_over_it() {
    use strata_protocol::properties::Change;
    let mut b = Bench::start("input-accept");
    let socket = b.socket();
    let specs = [IC, HU, FRONT];
    let clients: Vec<Client> = specs.iter().map(|s| Client::start(&socket, *s, true)).collect();
    let ids = b.ids();
    let (front, ic) = (ids["front"], ids["ic"]);
    b.change(Change::InputAcceptance { surface: front, accepts: false });
    b.change(Change::InputAcceptance { surface: ic, accepts: false });
    // Without the surfaces that take no input, the reference picks among the rest.
    let rest = [HU];
    let layers: Vec<RefLayer> = rest.iter().map(Spec::reference).collect();
    let mut to_hu = 0;
    for y in (2..OUT.1).step_by(9) {
        for x in (2..OUT.0).step_by(9) {
            let got = b.tap(x as f32 + 0.5, y as f32 + 0.5);
            assert_ne!(got, Some(front));
            assert_ne!(got, Some(ic));
            if settled(&layers, x, y, 1) {
                assert_eq!(got, reference::pick(&layers, x, y).map(|_| ids["hu"]), "({x}, {y})");
                to_hu += usize::from(got.is_some());
            }
        }
    }
    assert!(to_hu >= 20, "{to_hu} taps reached hu");
    assert!(b.input(Action::Focus { surface: front }).is_err(), "a surface without input takes no focus");
    assert!(clients[0].drain(Duration::from_millis(300)).is_empty(), "ic got events with input off");
    assert!(clients[2].drain(Duration::from_millis(10)).is_empty(), "front got events with input off");
    assert!(!clients[1].drain(Duration::from_millis(10)).is_empty());
}

#[test]
fn keys_and_text_go_to_the_focused_surface_only() {
    let mut b = Bench::start("input-focus");
    let socket = b.socket();
    let clients: Vec<Client> = [IC, HU].iter().map(|s| Client::start(&socket, *s, true)).collect();
    let ids = b.ids();
    let (ic, hu) = (ids["ic"], ids["hu"]);
    // `ctl watch` reports focus changes.
    let watcher = ControlConnection::connect_beside(&socket).expect("control");
    let (focus_tx, focus_changes) = channel();
    std::thread::spawn(move || {
        for e in watcher.watch().expect("watch").map_while(Result::ok) {
            let seen = match e {
                Event::Focus { output, surface } => (output, surface),
                Event::Changed(_) => ("changed".to_string(), None),
                _ => continue,
            };
            if focus_tx.send(seen).is_err() {
                return;
            }
        }
    });
    // Once the watcher sees a change, it is watching.
    let marker = strata_protocol::properties::Change::InputAcceptance { surface: ic, accepts: true };
    while {
        b.change(marker.clone());
        focus_changes.recv_timeout(Duration::from_millis(200)).is_err()
    } {}
    while focus_changes.recv_timeout(Duration::from_millis(100)).is_ok() {}
    assert!(b.input(Action::Key { name: "Return".into() }).expect("key").dropped.is_some(), "no focus yet");
    // A tap on ic focuses it.
    assert_eq!(b.tap(30.0, 50.0), Some(ic));
    assert_eq!(b.input(Action::Key { name: "Return".into() }).expect("key").surface, Some(ic));
    let ic_events = clients[0].drain(Duration::from_millis(300));
    assert!(ic_events.contains(&InputEvent::Focus { surface: ic, focused: true }));
    assert!(ic_events.contains(&InputEvent::Key { surface: ic, keysym: 0xff0d, pressed: true }));
    assert!(ic_events.contains(&InputEvent::Key { surface: ic, keysym: 0xff0d, pressed: false }));
    assert!(clients[1].drain(Duration::from_millis(10)).is_empty(), "hu got ic's keys");
    // Focus moved by the controller: ic is told it lost it, and text goes to hu.
    assert_eq!(b.input(Action::Focus { surface: hu }).expect("focus").surface, Some(hu));
    assert_eq!(b.input(Action::Text { text: "héllo".into() }).expect("text").surface, Some(hu));
    assert_eq!(clients[0].next(), InputEvent::Focus { surface: ic, focused: false });
    let hu_events = clients[1].drain(Duration::from_millis(300));
    assert_eq!(
        hu_events,
        vec![InputEvent::Focus { surface: hu, focused: true }, InputEvent::Text { surface: hu, text: "héllo".into() }]
    );
    assert!(clients[0].drain(Duration::from_millis(10)).is_empty());
    match b.request(ControlRequest::List) {
        ControlReply::List { outputs, .. } => assert_eq!(outputs[0].focus, Some(hu)),
        other => panic!("{other:?}"),
    }
    let watched: Vec<(String, Option<u64>)> =
        (0..2).map(|_| focus_changes.recv_timeout(Duration::from_secs(5)).expect("a focus event")).collect();
    assert_eq!(watched, vec![("main".to_string(), Some(ic)), ("main".to_string(), Some(hu))]);
}

#[test]
fn bad_input_is_dropped_or_refused_and_reaches_no_other_surface() {
    let mut b = Bench::start("input-bad");
    let socket = b.socket();
    let ic = Client::start(&socket, IC, true);
    let ids = b.ids();
    let ic_id = ids["ic"];
    // Outside every surface, outside the output, an unknown output or key: dropped or refused.
    let dropped = |o: InputOutcome| o.surface.is_none() && o.dropped.is_some();
    assert!(dropped(b.input(Action::Tap { x: 250.0, y: 120.0 }).expect("tap")), "no surface there");
    let off = b.input(Action::Tap { x: 300.0, y: 5.0 }).expect("tap");
    assert!(off.dropped.as_deref().is_some_and(|d| d.contains("outside output")), "{off:?}");
    assert!(dropped(b.input(Action::Tap { x: -1.0, y: 5.0 }).expect("tap")));
    let e = b
        .request(ControlRequest::Input(InputRequest { output: "nope".into(), action: Action::Tap { x: 1.0, y: 1.0 } }));
    assert!(matches!(&e, ControlReply::Error(m) if m.contains("no output named \"nope\"")), "{e:?}");
    let e = b.input(Action::Key { name: "Enter".into() }).expect_err("unknown key");
    assert!(e.contains("unknown key name \"Enter\""), "{e}");
    assert!(dropped(b.input(Action::Move { device: Device::Pointer, id: 1, x: 5.0, y: 5.0 }).expect("move")));
    assert!(dropped(b.input(Action::Release { device: Device::Touch, id: 3 }).expect("release")));
    assert!(ic.drain(Duration::from_millis(300)).is_empty(), "ic got events it must not");
    // Each dropped action is counted (the refused ones are not: they were never carried out).
    assert_eq!(support::stats(&socket).input_dropped, 5, "dropped actions counted");

    // 10,000 motion events of one grab: merged where the client is behind, the press and
    // release never lost, the last position delivered.
    let hu = Client::start(&socket, HU, true);
    let hu_id = b.ids()["hu"];
    let press = Action::Press { device: Device::Touch, id: 4, x: 200.0, y: 60.0 };
    assert_eq!(b.input(press.clone()).expect("press").surface, Some(hu_id));
    for i in 0..10_000 {
        let x = 100.0 + (i % 100) as f32;
        assert_eq!(
            b.input(Action::Move { device: Device::Touch, id: 4, x, y: 60.0 }).expect("move").surface,
            Some(hu_id)
        );
    }
    assert_eq!(b.input(Action::Release { device: Device::Touch, id: 4 }).expect("release").surface, Some(hu_id));
    let got: Vec<InputEvent> =
        hu.drain(Duration::from_millis(500)).into_iter().filter(|e| matches!(e, InputEvent::Point { .. })).collect();
    let phase = |e: &InputEvent| match e {
        InputEvent::Point { phase, .. } => *phase,
        _ => unreachable!(),
    };
    assert_eq!(got.first().map(phase), Some(Phase::Down));
    assert_eq!(got.last().map(phase), Some(Phase::Up));
    assert!(got[1..got.len() - 1].iter().all(|e| phase(e) == Phase::Motion));
    let last_x = 100.0 + 99.0 - HU.rect[0] as f32;
    assert!(matches!(got[got.len() - 2], InputEvent::Point { x, .. } if x == last_x), "{:?}", got[got.len() - 2]);

    // A surface destroyed during a grab: the grab ends cleanly.
    assert_eq!(b.input(press.clone()).expect("press").surface, Some(hu_id));
    drop(hu);
    // Its session ends a moment after the client hangs up (longer on a busy machine).
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    while b.ids().contains_key("hu") {
        assert!(std::time::Instant::now() < deadline, "hu's surface outlived its client by 10 s");
        std::thread::sleep(Duration::from_millis(20));
    }
    let gone = b.input(Action::Move { device: Device::Touch, id: 4, x: 150.0, y: 60.0 }).expect("move");
    assert!(gone.dropped.as_deref().is_some_and(|d| d.contains("is gone; the grab ended")), "{gone:?}");
    assert!(dropped(b.input(Action::Release { device: Device::Touch, id: 4 }).expect("release")));

    // A client that reads none of its events is disconnected once they pile up; the daemon
    // and the other client carry on.
    let deaf = Client::start(&socket, HU, false);
    let deaf_id = b.ids()["hu"];
    b.input(Action::Focus { surface: deaf_id }).expect("focus");
    let mut sent = 0;
    while sent < 20_000 && b.ids().contains_key("hu") {
        for _ in 0..500 {
            b.input(Action::Key { name: "a".into() }).expect("key");
        }
        sent += 500;
    }
    assert!(!b.ids().contains_key("hu"), "a client that read none of {sent} key presses is still connected");
    b.daemon.wait_log("it read none of its last 1024 input events");
    drop(deaf);
    assert_eq!(b.tap(30.0, 50.0), Some(ic_id), "ic still gets taps");
    assert!(ic
        .drain(Duration::from_millis(300))
        .iter()
        .any(|e| matches!(e, InputEvent::Point { phase: Phase::Up, .. })));
}

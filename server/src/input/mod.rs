//! Input routing: which client gets each touch, click and key. A press or touch-down goes to
//! the surface shown at that point (`Root::pick`: the compositor's depth select for one
//! pixel, input acceptance honoured), which then grabs that point until it is released, as in
//! Wayland; each touch point grabs on its own. Keys and text go to the surface that has the
//! output's keyboard focus: the last one pressed on, or the one `ctl input focus` names.
//! Events are queued per client (`queue`) and written to its socket by its connection; what
//! cannot be delivered is dropped and counted, never sent to another surface.

pub mod libinput;
pub mod queue;

use std::collections::HashMap;
use std::sync::Mutex;

use strata_protocol::events::Event;
use strata_protocol::input::{self, Action, Device, InputEvent, InputOutcome, InputRequest, Phase};
use tracing::debug;

pub use queue::{EventQueue, Overflow, MAX_QUEUED};

use strata_compositor::root::Root;
use strata_scene::Scene;

/// A point held down: the surface it went down on, and where it last was (output space).
#[derive(Debug, Clone, Copy)]
struct Grab {
    surface: u64,
    at: [f32; 2],
}

#[derive(Debug, Default)]
struct State {
    /// Points held down, by output, device and button or touch point.
    grabs: HashMap<(String, Device, u32), Grab>,
    /// Each output's keyboard focus.
    focus: HashMap<String, u64>,
    /// Actions whose events went nowhere.
    dropped: u64,
}

/// The daemon's input routing state.
#[derive(Debug, Default)]
pub struct Router {
    state: Mutex<State>,
}

/// Where events go: `deliver(client, event)` queues one for a client (false: no such client).
pub type Deliver<'a> = &'a dyn Fn(u64, InputEvent) -> bool;

/// What routing one action needs from the daemon.
pub struct Context<'a> {
    /// The outputs and the depth select.
    pub root: &'a Root,
    /// The surfaces.
    pub scene: &'a Scene,
    /// The clients' queues.
    pub deliver: Deliver<'a>,
}

fn dropped(why: String) -> InputOutcome {
    InputOutcome { surface: None, dropped: Some(why), queued_us: None, device_us: None }
}

fn to(surface: u64) -> InputOutcome {
    InputOutcome { surface: Some(surface), dropped: None, queued_us: None, device_us: None }
}

impl Router {
    /// Each output's keyboard focus (output name, surface ID).
    pub fn focus(&self) -> HashMap<String, u64> {
        self.state.lock().map(|s| s.focus.clone()).unwrap_or_default()
    }

    /// Actions whose events were dropped (no surface there, none focused, the surface gone).
    pub fn dropped(&self) -> u64 {
        self.state.lock().map_or(0, |s| s.dropped)
    }

    /// Routes one `ctl input` request: an error for a request that cannot be carried out (an
    /// unknown output or key, a surface that does not take input); else where its events went,
    /// or why they were dropped.
    pub fn handle(&self, cx: &Context<'_>, req: &InputRequest) -> Result<InputOutcome, String> {
        req.action.validate()?;
        let (output, rect) = cx.root.output(&req.output)?;
        let global = |x: f32, y: f32| -> Result<[f32; 2], String> {
            if x < 0.0 || y < 0.0 || x >= rect[2] as f32 || y >= rect[3] as f32 {
                return Err(format!("({x}, {y}) lies outside output {output:?} ({}x{})", rect[2], rect[3]));
            }
            Ok([rect[0] as f32 + x, rect[1] as f32 + y])
        };
        let outcome = match &req.action {
            Action::Tap { x, y } => match global(*x, *y) {
                Err(why) => dropped(why),
                Ok(p) => {
                    let down = self.press(cx, &output, Device::Touch, 0, p)?;
                    if down.surface.is_some() {
                        self.release(cx, &output, Device::Touch, 0);
                    }
                    down
                }
            },
            Action::Press { device, id, x, y } => match global(*x, *y) {
                Err(why) => dropped(why),
                Ok(p) => self.press(cx, &output, *device, *id, p)?,
            },
            Action::Move { device, id, x, y } => match global(*x, *y) {
                // A held point may leave the output; its grab follows it to the edge.
                Err(_) => self.motion(
                    cx,
                    &output,
                    *device,
                    *id,
                    [rect[0] as f32 + x.clamp(0.0, rect[2] as f32), rect[1] as f32 + y.clamp(0.0, rect[3] as f32)],
                ),
                Ok(p) => self.motion(cx, &output, *device, *id, p),
            },
            Action::Release { device, id } => self.release(cx, &output, *device, *id),
            Action::Key { name } => {
                let keysym = input::keysym(name).map_err(|e| e.to_string())?;
                self.to_focus(cx, &output, |surface| {
                    vec![
                        InputEvent::Key { surface, keysym, pressed: true },
                        InputEvent::Key { surface, keysym, pressed: false },
                    ]
                })
            }
            Action::Text { text } => {
                self.to_focus(cx, &output, |surface| vec![InputEvent::Text { surface, text: text.clone() }])
            }
            Action::Focus { surface } => {
                if cx.scene.input_client(*surface).is_none() {
                    return Err(format!(
                        "no surface {surface} that accepts input; `stratad ctl list` shows surfaces and their input"
                    ));
                }
                self.set_focus(cx, &output, *surface);
                to(*surface)
            }
        };
        if let Some(why) = &outcome.dropped {
            debug!(output, "input dropped: {why}");
            if let Ok(mut s) = self.state.lock() {
                s.dropped += 1;
            }
        }
        Ok(outcome)
    }

    /// A point goes down at `p` (output space): the surface shown there grabs it and takes the
    /// output's focus.
    fn press(
        &self,
        cx: &Context<'_>,
        output: &str,
        device: Device,
        id: u32,
        p: [f32; 2],
    ) -> Result<InputOutcome, String> {
        // A point pressed again without a release: the old grab ends first.
        let held = self.state.lock().ok().and_then(|s| s.grabs.get(&(output.to_string(), device, id)).copied());
        if held.is_some() {
            self.release(cx, output, device, id);
        }
        let Some(t) = cx.root.pick(p)? else {
            return Ok(dropped(format!("no surface that accepts input is shown at ({}, {})", p[0], p[1])));
        };
        // The surface pressed on takes the focus first, so that the press finds it focused.
        let lost = self.take_focus(cx, output, t.surface, Some(t.client));
        let [x, y] = t.local;
        let down =
            (cx.deliver)(t.client, InputEvent::Point { surface: t.surface, device, id, phase: Phase::Down, x, y });
        if let Some(lost) = lost {
            self.tell_lost(cx, lost);
        }
        if !down {
            return Ok(dropped(format!("surface {}'s client is gone", t.surface)));
        }
        if let Ok(mut s) = self.state.lock() {
            s.grabs.insert((output.to_string(), device, id), Grab { surface: t.surface, at: p });
        }
        Ok(InputOutcome { device_us: t.device_us, ..to(t.surface) })
    }

    /// A held point moves to `p`: its grab's surface gets it.
    fn motion(&self, cx: &Context<'_>, output: &str, device: Device, id: u32, p: [f32; 2]) -> InputOutcome {
        let key = (output.to_string(), device, id);
        let Some(grab) = self.state.lock().ok().and_then(|mut s| {
            let g = s.grabs.get_mut(&key)?;
            g.at = p;
            Some(*g)
        }) else {
            return dropped(format!("{device:?} {id} is not pressed on output {output:?}"));
        };
        self.to_grab(cx, key, grab, Phase::Motion)
    }

    /// A held point is released where it last was: its grab's surface gets it, and the grab
    /// ends.
    fn release(&self, cx: &Context<'_>, output: &str, device: Device, id: u32) -> InputOutcome {
        let key = (output.to_string(), device, id);
        let Some(grab) = self.state.lock().ok().and_then(|mut s| s.grabs.remove(&key)) else {
            return dropped(format!("{device:?} {id} is not pressed on output {output:?}"));
        };
        self.to_grab(cx, key, grab, Phase::Up)
    }

    /// Sends `phase` of a grabbed point to its surface; a surface gone (or no longer taking
    /// input) ends the grab.
    fn to_grab(&self, cx: &Context<'_>, key: (String, Device, u32), grab: Grab, phase: Phase) -> InputOutcome {
        let (device, id) = (key.1, key.2);
        let target =
            cx.scene.surface_point(grab.surface, grab.at).filter(|_| cx.scene.input_client(grab.surface).is_some());
        let delivered = target.is_some_and(|(client, [x, y])| {
            (cx.deliver)(client, InputEvent::Point { surface: grab.surface, device, id, phase, x, y })
        });
        if delivered {
            return to(grab.surface);
        }
        if let Ok(mut s) = self.state.lock() {
            s.grabs.remove(&key);
        }
        dropped(format!("surface {} that grabbed {device:?} {id} is gone; the grab ended", grab.surface))
    }

    /// Sends the events `make` gives for the output's focused surface.
    fn to_focus(&self, cx: &Context<'_>, output: &str, make: impl Fn(u64) -> Vec<InputEvent>) -> InputOutcome {
        let Some(surface) = self.state.lock().ok().and_then(|s| s.focus.get(output).copied()) else {
            return dropped(format!("no surface has output {output:?}'s keyboard focus"));
        };
        let Some(client) = cx.scene.input_client(surface) else {
            if let Ok(mut s) = self.state.lock() {
                s.focus.remove(output);
            }
            cx.scene.emit(Event::Focus { output: output.to_string(), surface: None });
            return dropped(format!(
                "surface {surface}, which had output {output:?}'s focus, is gone or takes no input"
            ));
        };
        if make(surface).into_iter().all(|e| (cx.deliver)(client, e)) {
            to(surface)
        } else {
            dropped(format!("surface {surface}'s client is gone"))
        }
    }

    /// Gives the output's focus to `surface`, telling the surface that loses it and the one
    /// that gets it.
    fn set_focus(&self, cx: &Context<'_>, output: &str, surface: u64) {
        if let Some(lost) = self.take_focus(cx, output, surface, cx.scene.input_client(surface)) {
            self.tell_lost(cx, lost);
        }
    }

    /// Gives the output's focus to `surface`, and tells it (through `client`, its client);
    /// the surface that lost the focus, which [`Router::tell_lost`] tells. A press tells the
    /// surface pressed on first, without looking anything up in the scene, so that its focus
    /// and its press are queued before another client's news.
    fn take_focus(&self, cx: &Context<'_>, output: &str, surface: u64, client: Option<u64>) -> Option<u64> {
        let old = self.state.lock().ok().map(|mut s| s.focus.insert(output.to_string(), surface))?;
        if old == Some(surface) {
            return None;
        }
        if let Some(client) = client {
            (cx.deliver)(client, InputEvent::Focus { surface, focused: true });
        }
        cx.scene.emit(Event::Focus { output: output.to_string(), surface: Some(surface) });
        old
    }

    /// Tells surface `lost` it lost its output's focus, if it is still there.
    fn tell_lost(&self, cx: &Context<'_>, lost: u64) {
        if let Some((client, _)) = cx.scene.surface_point(lost, [0.0, 0.0]) {
            (cx.deliver)(client, InputEvent::Focus { surface: lost, focused: false });
        }
    }
}

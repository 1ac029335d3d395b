//! Input: what `stratad ctl input` (and an output's own window) hands the daemon, in output
//! pixels, and the events the daemon delivers to the client whose surface is shown at that
//! point, in that surface's own pixels (y down, as a window system counts them).

use serde::{Deserialize, Serialize};

/// The kind of device a point comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Device {
    /// A mouse or touchpad; its ID is the button (1 left, 2 middle, 3 right).
    Pointer,
    /// A touchscreen; its ID is the touch point's, each grabbing on its own.
    Touch,
}

/// What a point does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Phase {
    /// A button pressed or a finger down: the surface shown there grabs the point.
    Down,
    /// Moved while down: goes to the surface that grabbed it.
    Motion,
    /// Released: goes to the surface that grabbed it, and ends the grab.
    Up,
}

/// One action of `stratad ctl input` on an output (coordinates in that output's pixels).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum Action {
    /// A touch down and up at one point (touch point 0).
    Tap {
        /// x from the output's left edge.
        x: f32,
        /// y from the output's top edge.
        y: f32,
    },
    /// A button press or touch down.
    Press {
        /// Pointer or touch.
        device: Device,
        /// The button or touch point.
        id: u32,
        /// x from the output's left edge.
        x: f32,
        /// y from the output's top edge.
        y: f32,
    },
    /// A move of a pressed button or a touch point.
    Move {
        /// Pointer or touch.
        device: Device,
        /// The button or touch point.
        id: u32,
        /// x from the output's left edge.
        x: f32,
        /// y from the output's top edge.
        y: f32,
    },
    /// A button release or touch up (where it last was).
    Release {
        /// Pointer or touch.
        device: Device,
        /// The button or touch point.
        id: u32,
    },
    /// A key pressed and released, by its X keysym name (`Return`, `a`, `F1`, …).
    Key {
        /// The name.
        name: String,
    },
    /// Text typed, one character after another.
    Text {
        /// The text.
        text: String,
    },
    /// Gives the output's keyboard focus to a surface.
    Focus {
        /// Surface ID.
        surface: u64,
    },
}

/// A `ctl input` request: an action on a named output.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputRequest {
    /// The output's name (empty: the first).
    pub output: String,
    /// What happens.
    pub action: Action,
}

/// What the daemon did with a `ctl input` request.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputOutcome {
    /// The surface the events went to (`None`: dropped).
    pub surface: Option<u64>,
    /// Why they were dropped, when they were.
    pub dropped: Option<String>,
    /// Microseconds from the request's arrival on the control connection to its first event
    /// in the client's queue (when one was queued).
    #[serde(default)]
    pub queued_us: Option<u64>,
    /// Of those, the microseconds a press waited on the device it read the texels under the
    /// point on (when it read any: readings are kept until the scene changes).
    #[serde(default)]
    pub device_us: Option<u64>,
}

/// One event the daemon delivers to a client, on its client socket.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum InputEvent {
    /// A point (button or touch) went down, moved or went up over one of the client's surfaces.
    Point {
        /// Surface ID.
        surface: u64,
        /// Pointer or touch.
        device: Device,
        /// The button or touch point.
        id: u32,
        /// Down, motion or up.
        phase: Phase,
        /// x in the surface's image pixels, from its left edge.
        x: f32,
        /// y in the surface's image pixels, from its top edge.
        y: f32,
    },
    /// A key went down or up on the surface that has its output's focus.
    Key {
        /// Surface ID.
        surface: u64,
        /// The X keysym.
        keysym: u32,
        /// Down (else up).
        pressed: bool,
    },
    /// Text typed into the focused surface (also sent as keys where each character has a
    /// keysym).
    Text {
        /// Surface ID.
        surface: u64,
        /// The text.
        text: String,
    },
    /// The surface got or lost its output's keyboard focus.
    Focus {
        /// Surface ID.
        surface: u64,
        /// Got it (else lost it).
        focused: bool,
    },
}

impl InputEvent {
    /// The surface it is for.
    pub fn surface(&self) -> u64 {
        match self {
            InputEvent::Point { surface, .. }
            | InputEvent::Key { surface, .. }
            | InputEvent::Text { surface, .. }
            | InputEvent::Focus { surface, .. } => *surface,
        }
    }

    /// Whether `next` may replace it in a queue: both are motion of the same point over the
    /// same surface.
    pub fn merges_with(&self, next: &InputEvent) -> bool {
        matches!(
            (self, next),
            (
                InputEvent::Point { surface: a, device: da, id: ia, phase: Phase::Motion, .. },
                InputEvent::Point { surface: b, device: db, id: ib, phase: Phase::Motion, .. },
            ) if a == b && da == db && ia == ib
        )
    }
}

/// Keysyms of the named keys `ctl input key` knows besides single characters (X11's
/// `keysymdef.h` names and values).
const NAMED_KEYS: &[(&str, u32)] = &[
    ("BackSpace", 0xff08),
    ("Tab", 0xff09),
    ("Return", 0xff0d),
    ("Escape", 0xff1b),
    ("Delete", 0xffff),
    ("Home", 0xff50),
    ("Left", 0xff51),
    ("Up", 0xff52),
    ("Right", 0xff53),
    ("Down", 0xff54),
    ("Page_Up", 0xff55),
    ("Page_Down", 0xff56),
    ("End", 0xff57),
    ("Insert", 0xff63),
    ("Menu", 0xff67),
    ("KP_Enter", 0xff8d),
    ("Shift_L", 0xffe1),
    ("Shift_R", 0xffe2),
    ("Control_L", 0xffe3),
    ("Control_R", 0xffe4),
    ("Alt_L", 0xffe9),
    ("Alt_R", 0xffea),
    ("Super_L", 0xffeb),
    ("space", 0x20),
];

/// A key name `ctl input key` does not know.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown key name {0:?}: a single character, F1 to F12, or one of {names}", names = known_names())]
pub struct UnknownKey(pub String);

fn known_names() -> String {
    NAMED_KEYS.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
}

/// The keysym of a character: Latin-1 characters are their own code; others are
/// `0x0100_0000` plus their code point (X11's rule for Unicode keysyms). Control characters
/// have none.
pub fn char_keysym(c: char) -> Option<u32> {
    let code = u32::from(c);
    match code {
        0x20..=0x7e | 0xa0..=0xff => Some(code),
        0x100.. => Some(0x0100_0000 + code),
        _ => None,
    }
}

/// The keysym named `name`: a named key, `F1`…`F12`, or a single character.
pub fn keysym(name: &str) -> Result<u32, UnknownKey> {
    if let Some((_, k)) = NAMED_KEYS.iter().find(|(n, _)| *n == name) {
        return Ok(*k);
    }
    if let Some(n) = name.strip_prefix('F').and_then(|n| n.parse::<u32>().ok()).filter(|n| (1..=12).contains(n)) {
        return Ok(0xffbe + n - 1);
    }
    let mut chars = name.chars();
    match (chars.next(), chars.next()) {
        (Some(c), None) => char_keysym(c).ok_or_else(|| UnknownKey(name.to_string())),
        _ => Err(UnknownKey(name.to_string())),
    }
}

/// Most characters one `ctl input text` may carry.
pub const MAX_TEXT: usize = 4096;

impl Action {
    /// Checks what the action carries without the daemon: key names, finite coordinates,
    /// text length.
    pub fn validate(&self) -> Result<(), String> {
        let finite = |x: f32, y: f32| {
            if x.is_finite() && y.is_finite() {
                Ok(())
            } else {
                Err(format!("coordinates ({x}, {y}) are not finite"))
            }
        };
        match self {
            Action::Tap { x, y } | Action::Press { x, y, .. } | Action::Move { x, y, .. } => finite(*x, *y),
            Action::Key { name } => keysym(name).map(|_| ()).map_err(|e| e.to_string()),
            Action::Text { text } if text.chars().count() > MAX_TEXT => {
                Err(format!("text of {} characters; at most {MAX_TEXT} at once", text.chars().count()))
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn key_names_resolve_to_x_keysyms() {
        assert_eq!(keysym("Return"), Ok(0xff0d));
        assert_eq!(keysym("a"), Ok(0x61));
        assert_eq!(keysym("F1"), Ok(0xffbe));
        assert_eq!(keysym("F12"), Ok(0xffc9));
        assert_eq!(keysym("é"), Ok(0xe9));
        assert_eq!(keysym("€"), Ok(0x0100_20ac));
        for bad in ["F13", "F0", "Enter", "", "ab", "\n"] {
            assert!(keysym(bad).is_err(), "{bad:?}");
        }
        assert!(keysym("Enter").unwrap_err().to_string().contains("Return"));
    }

    #[test]
    fn only_motion_of_one_point_over_one_surface_merges() {
        let p = |surface, id, phase| InputEvent::Point { surface, device: Device::Touch, id, phase, x: 1.0, y: 2.0 };
        assert!(p(1, 0, Phase::Motion).merges_with(&p(1, 0, Phase::Motion)));
        assert!(!p(1, 0, Phase::Motion).merges_with(&p(1, 1, Phase::Motion)));
        assert!(!p(1, 0, Phase::Motion).merges_with(&p(2, 0, Phase::Motion)));
        assert!(!p(1, 0, Phase::Down).merges_with(&p(1, 0, Phase::Motion)));
        assert!(!p(1, 0, Phase::Motion).merges_with(&p(1, 0, Phase::Up)));
    }
}

//! What a watched daemon reports (`stratad ctl watch`), and its answers to `ctl analyze`.

use serde::{Deserialize, Serialize};

/// One event of `stratad ctl watch`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Event {
    /// A client connected.
    ClientConnected {
        /// Its number.
        client: u64,
        /// Its name.
        name: String,
        /// Its process ID, as the kernel reports the peer of its socket (0 where unknown).
        pid: u32,
    },
    /// A client's session ended.
    ClientGone {
        /// Its number.
        client: u64,
        /// Its name.
        name: String,
        /// Its process ID (0 where unknown).
        pid: u32,
        /// Why: it disconnected, violated the protocol, exceeded a quota, …
        reason: String,
    },
    /// A window surface was created.
    SurfaceCreated {
        /// Its ID.
        surface: u64,
        /// Its client's number.
        client: u64,
        /// Its client's name.
        name: String,
        /// Its client's process ID (0 where unknown).
        pid: u32,
    },
    /// A window surface was destroyed (also when its client left).
    SurfaceDestroyed {
        /// Its ID.
        surface: u64,
        /// Its client's number.
        client: u64,
        /// Its client's name.
        name: String,
        /// Its client's process ID (0 where unknown).
        pid: u32,
    },
    /// A property change was applied (`ctl surface`, `ctl layer`, `ctl apply`).
    Changed(crate::properties::Change),
    /// A surface's frames over the last second, sent once a second per surface.
    Frames {
        /// Surface ID.
        surface: u64,
        /// Frames swapped in the interval.
        frames: u64,
        /// Of those, frames a composite took.
        shown: u64,
        /// Deadline misses in the interval (deadline surfaces only).
        deadline_misses: u64,
        /// Frames swapped per second.
        fps: f64,
    },
    /// An output's keyboard focus moved (a press on a surface, or `ctl input focus`).
    Focus {
        /// The output.
        output: String,
        /// The surface that has it now (`None`: none, its surface having gone).
        surface: Option<u64>,
    },
    /// The watcher fell behind by this many events and is dropped (the last line it gets).
    Dropped {
        /// Events it did not read in time.
        missed: u64,
    },
}

/// Why a surface does not show (`stratad ctl analyze`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reason {
    /// Its client has not swapped a frame yet.
    NoFrame,
    /// Its own visibility is off.
    Hidden,
    /// A layer holding it is hidden.
    LayerHidden {
        /// The layer.
        layer: String,
    },
    /// Its opacity, its layers' taken in, is 0.
    Transparent,
    /// Its rectangle or its source region has no area.
    ZeroSize,
    /// Its rectangle lies outside every output.
    OffOutputs,
    /// Nearer groups' opaque surfaces cover every pixel of it that lies on an output.
    Covered {
        /// The surfaces that cover it, nearest group first.
        by: Vec<u64>,
    },
}

/// The answer to `stratad ctl analyze SURFACE`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Analysis {
    /// Surface ID.
    pub surface: u64,
    /// Whether some pixel of it can show.
    pub visible: bool,
    /// Every reason it cannot (empty when it can).
    pub reasons: Vec<Reason>,
}

impl std::fmt::Display for Reason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reason::NoFrame => write!(f, "its client has not swapped a frame yet"),
            Reason::Hidden => write!(f, "its visibility is off"),
            Reason::LayerHidden { layer } => write!(f, "layer {layer:?}, which holds it, is hidden"),
            Reason::Transparent => write!(f, "its opacity (its layers' taken in) is 0"),
            Reason::ZeroSize => write!(f, "its rectangle or source region has no area"),
            Reason::OffOutputs => write!(f, "it lies outside every output"),
            Reason::Covered { by } => {
                let ids: Vec<String> = by.iter().map(u64::to_string).collect();
                write!(f, "opaque surfaces of nearer groups cover it: {}", ids.join(", "))
            }
        }
    }
}

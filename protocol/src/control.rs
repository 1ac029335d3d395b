//! `stratad ctl`: the requests an administrator sends over a control connection and the
//! daemon's answers, plus the lighting settings they read and change.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// A client's priority class: what CPU and GPU priority its session and device get.
///
/// Each client renders on a device of its own. `high` (an instrument cluster) gets the
/// highest priority the platform grants (nice −5 where the daemon may raise it, the queue's
/// `HIGH` global priority where the GPU offers it), `low` the lowest (its threads idle-class,
/// at nice 19; `LOW` global priority), and `normal` the default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Priority {
    /// The instrument cluster's class: the highest priority the platform grants.
    High,
    /// The default.
    #[default]
    Normal,
    /// Runs on what the others leave.
    Low,
}

impl std::str::FromStr for Priority {
    type Err = String;

    /// Parses `high`, `normal` or `low`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "high" => Ok(Priority::High),
            "normal" => Ok(Priority::Normal),
            "low" => Ok(Priority::Low),
            _ => Err(format!("unknown priority {s:?}: the classes are high, normal and low")),
        }
    }
}

/// `EGL_CONTEXT_PRIORITY_LEVEL_IMG` (`EGL_IMG_context_priority`): the context attribute with
/// which a client asks for a class.
pub const EGL_CONTEXT_PRIORITY_LEVEL_IMG: i32 = 0x3100;
/// The environment variable with which `stratad run --priority` asks for a class for every
/// context of an application that asks for none itself.
pub const PRIORITY_ENV: &str = "STRATA_PRIORITY";

impl Priority {
    /// The `EGL_CONTEXT_PRIORITY_LEVEL_IMG` value of the class (`EGL_CONTEXT_PRIORITY_HIGH_IMG`,
    /// `_MEDIUM_IMG` or `_LOW_IMG`).
    pub fn egl_level(self) -> i32 {
        match self {
            Priority::High => 0x3101,
            Priority::Normal => 0x3102,
            Priority::Low => 0x3103,
        }
    }

    /// The class an `EGL_CONTEXT_PRIORITY_LEVEL_IMG` value asks for.
    pub fn from_egl_level(level: i32) -> Option<Priority> {
        [Priority::High, Priority::Normal, Priority::Low].into_iter().find(|p| p.egl_level() == level)
    }

    /// The class's name as the configuration and `ctl` spell it.
    pub fn name(self) -> &'static str {
        match self {
            Priority::High => "high",
            Priority::Normal => "normal",
            Priority::Low => "low",
        }
    }
}

/// Where a client's frames waited, summed over its session, in microseconds.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Waits {
    /// In `eglSwapBuffers`, for the swap interval, frames in flight, or a free buffer.
    pub swap_us: u64,
    /// For its own device to finish its work (readbacks, `glFinish`, the previous frame at a
    /// swap).
    pub gpu_us: u64,
}

/// Where lighting takes a fragment's normal from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum NormalSource {
    /// One normal per surface (the thesis' method, and the default).
    PerSurface,
    /// Reconstructed from the selected surface's depth by central differences.
    FromDepth,
}

/// Uniform Phong lighting (§4.6): `(ambient + diffuse + specular) · light colour · colour`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lighting {
    /// Whether lighting is applied at all.
    pub enabled: bool,
    /// Ambient factor (thesis: 0.1).
    pub ambient: f32,
    /// Specular exponent (thesis: 32).
    pub shininess: f32,
    /// Light position in output space: x, y in [-1, 1] (y up), the output plane at z = 0.
    pub position: [f32; 3],
    /// Viewer position in the same space.
    pub view: [f32; 3],
    /// Light colour (thesis: white).
    pub color: [f32; 3],
    /// Normal source.
    pub normals: NormalSource,
    /// For `FromDepth`: depth units per pixel that count as a 45° slope's inverse.
    pub depth_normal_scale: f32,
}

impl Default for Lighting {
    fn default() -> Self {
        Lighting {
            enabled: true,
            ambient: 0.1,
            shininess: 32.0,
            position: [1.0, 1.0, 2.0],
            view: [0.0, 0.0, 2.0],
            color: [1.0; 3],
            normals: NormalSource::PerSurface,
            depth_normal_scale: 64.0,
        }
    }
}

/// A change to the lighting: every `Some` field replaces the current value.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct LightChange {
    /// Turn lighting on or off.
    pub enabled: Option<bool>,
    /// Ambient factor.
    pub ambient: Option<f32>,
    /// Specular exponent.
    pub shininess: Option<f32>,
    /// Light position.
    pub position: Option<[f32; 3]>,
    /// Viewer position.
    pub view: Option<[f32; 3]>,
    /// Light colour.
    pub color: Option<[f32; 3]>,
    /// Normal source.
    pub normals: Option<NormalSource>,
}

/// The change that sets every parameter to `l`'s.
impl From<Lighting> for LightChange {
    fn from(l: Lighting) -> Self {
        LightChange {
            enabled: Some(l.enabled),
            ambient: Some(l.ambient),
            shininess: Some(l.shininess),
            position: Some(l.position),
            view: Some(l.view),
            color: Some(l.color),
            normals: Some(l.normals),
        }
    }
}

impl LightChange {
    /// Checks that every given value is finite and in range (ambient and colour in [0, 1],
    /// shininess positive).
    pub fn validate(&self) -> Result<(), String> {
        let finite = |name: &str, v: &[f32]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(format!("{name} must be finite"))
            }
        };
        for (name, v) in [("position", self.position), ("view", self.view), ("color", self.color)] {
            if let Some(v) = v {
                finite(name, &v)?;
            }
        }
        if let Some(c) = self.color {
            if c.iter().any(|x| !(0.0..=1.0).contains(x)) {
                return Err("color components must lie in [0, 1]".into());
            }
        }
        if let Some(a) = self.ambient {
            if !(0.0..=1.0).contains(&a) {
                return Err(format!("ambient {a} must lie in [0, 1]"));
            }
        }
        if let Some(s) = self.shininess {
            if !(s.is_finite() && s > 0.0) {
                return Err(format!("shininess {s} must be a positive number"));
            }
        }
        Ok(())
    }

    /// `light` with this change applied.
    pub fn apply(&self, mut light: Lighting) -> Lighting {
        light.enabled = self.enabled.unwrap_or(light.enabled);
        light.ambient = self.ambient.unwrap_or(light.ambient);
        light.shininess = self.shininess.unwrap_or(light.shininess);
        light.position = self.position.unwrap_or(light.position);
        light.view = self.view.unwrap_or(light.view);
        light.color = self.color.unwrap_or(light.color);
        light.normals = self.normals.unwrap_or(light.normals);
        light
    }
}

/// What a control client (`stratad ctl`, or a controller through `strata_client::control`)
/// asks; in JSON, as docs/control.md shows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ControlRequest {
    /// Every output and window surface.
    List,
    /// The output's last composited image (composited first if anything changed).
    Screenshot {
        /// Output name; empty for the first output.
        output: String,
    },
    /// Moves a window surface.
    Move {
        /// Surface id, as `List` shows it.
        surface: u64,
        /// New left edge.
        x: i32,
        /// New top edge.
        y: i32,
        /// New depth layer.
        z: f32,
    },
    /// Changes the lighting (an empty change just reports it).
    Light(LightChange),
    /// Sets a window surface's normal (per-surface lighting, the thesis' method).
    Normal {
        /// Surface id, as `List` shows it.
        surface: u64,
        /// The normal in output space (x right, y up, z towards the viewer); need not be unit.
        normal: [f32; 3],
    },
    /// The daemon's memory, and every client's resources against its quota.
    Stats,
    /// Destroys client `client`'s GPU device, as a fault or a driver reset would lose it
    /// (only when the daemon was started with `--allow-fault-injection`; for tests).
    LoseDevice {
        /// The client's number, as `Stats` shows it.
        client: u64,
    },
    /// A window surface's newest complete frame, as its client drew it (answered with
    /// `ControlReply::Image`, top row first).
    SurfaceScreenshot {
        /// Surface ID, as `List` shows it.
        surface: u64,
    },
    /// Applies property changes in one step: all of them show in the same composite, or, if
    /// any fails, none applies (answered with `List`).
    Apply {
        /// The changes, in order.
        changes: Vec<crate::properties::Change>,
    },
    /// Why a surface does not show, or that it does (answered with `Analysis`).
    Analyze {
        /// Surface ID.
        surface: u64,
    },
    /// The whole scene in the form `--config` reads (answered with `Scene`).
    Export,
    /// Turns the connection into a stream of `ControlReply::Event`s until it closes.
    Watch,
    /// Stops the compositor thread as a composite that never returns would, so that the
    /// service manager's watchdog hears nothing more (only when the daemon was started with
    /// `--allow-fault-injection`; for tests; answered with `List`).
    WedgeCompositor,
    /// Input on an output: a tap, a press, move or release, a key, text, or a focus change
    /// (answered with `Input`).
    Input(crate::input::InputRequest),
}

/// One thread of a device's driver.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct DeviceThread {
    /// Its thread id.
    pub tid: i32,
    /// Its name (`/proc/self/task/TID/comm`).
    pub name: String,
    /// Its nice value.
    pub nice: i32,
}

/// A device as `stratad ctl stats` shows it.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DeviceStats {
    /// Whether it is the client's own device (else the compositor's, shared).
    pub own: bool,
    /// The threads its driver started (lavapipe's queue and rasterizer threads).
    pub threads: Vec<DeviceThread>,
    /// The queue global priority the driver granted (`None`: not offered).
    pub global_priority: Option<String>,
    /// Time the device has been busy, microseconds: on a CPU rasterizer the CPU time of its
    /// threads; on a GPU, the time from each frame's last submission to its completion.
    pub busy_us: u64,
    /// Whether the device was lost.
    pub lost: bool,
}

/// One client's resources, as `stratad ctl stats` shows them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClientStats {
    /// The client's number.
    pub id: u64,
    /// Its name.
    pub name: String,
    /// Its role.
    pub role: String,
    /// GPU memory it holds (buffers, texture and renderbuffer images, surfaces), bytes.
    pub gpu_bytes: u64,
    /// Its limit on that.
    pub gpu_bytes_limit: u64,
    /// Bytes the daemon holds in its own memory for it (its segment, a command being
    /// assembled from chunks).
    #[serde(default)]
    pub daemon_bytes: u64,
    /// Its limit on that.
    #[serde(default)]
    pub daemon_bytes_limit: u64,
    /// Objects it holds, by kind (`buffers`, `textures`, …, `contexts`, `surfaces`).
    pub objects: BTreeMap<String, u64>,
    /// Allocations refused because they exceeded its quota.
    pub refusals: u64,
    /// Bytes of command stream it has sent.
    pub stream_bytes: u64,
    /// Its scheduling class.
    pub priority: Priority,
    /// Where its frames waited.
    pub waits: Waits,
    /// Deadline misses of its surfaces (see `SurfaceRow::deadline_misses`).
    pub deadline_misses: u64,
    /// Its credentials.
    #[serde(default)]
    pub peer: Peer,
    /// The device it renders on, once its session has opened it.
    pub device: Option<DeviceStats>,
}

/// The daemon's resources, as `stratad ctl stats` shows them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DaemonStats {
    /// Resident memory of the daemon process, bytes.
    pub rss_bytes: u64,
    /// The most resident memory it has had, bytes.
    pub peak_rss_bytes: u64,
    /// Of the resident memory, what is anonymous (heaps, stacks, driver allocations) rather
    /// than pages of mapped files such as the program's and libraries' code, bytes.
    pub rss_anon_bytes: u64,
    /// Client sessions started since the daemon started.
    pub sessions: u64,
    /// Connected clients.
    pub clients: Vec<ClientStats>,
    /// GPU memory all clients hold, bytes.
    pub gpu_bytes: u64,
    /// The limit on that for all clients together.
    pub gpu_bytes_limit: u64,
    /// Of that limit, what only the reserved class holds (`--reserve-gpu-bytes`).
    #[serde(default)]
    pub reserve_bytes: u64,
    /// The daemon's own memory its sessions hold for their clients, bytes.
    #[serde(default)]
    pub daemon_bytes: u64,
    /// The limit on that for all clients together.
    #[serde(default)]
    pub daemon_bytes_limit: u64,
    /// Connections refused at the doors, by cap (`sessions-per-uid`, `handshakes`, `accept`
    /// for accepts the system refused, …).
    #[serde(default)]
    pub refused: BTreeMap<String, u64>,
    /// Objects all clients hold, by kind.
    pub objects: BTreeMap<String, u64>,
    /// Objects alive on the device, by type, as the GPU layer counts them (clients' and the
    /// compositor's).
    pub device_objects: BTreeMap<String, u64>,
    /// The compositor's device.
    pub compositor_device: Option<DeviceStats>,
    /// `ctl input` actions (and output windows' input) whose events went nowhere: no surface
    /// there, outside the output, nothing focused, a point not pressed, a grab's surface gone.
    #[serde(default)]
    pub input_dropped: u64,
    /// Texels input routing has read to pick surfaces: on its own device, and on the
    /// compositor's.
    #[serde(default)]
    pub pick_reads: [u64; 2],
}

/// One row of `stratad ctl list`: a window surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceRow {
    /// Surface ID: stable where the layout, `STRATA_SURFACE_ID` or the application fixed one
    /// (see [`crate::surface_id`]), else a runtime ID; no two live surfaces share one. `ctl
    /// list` gives rows in stacking order (creation order; later on top when depths tie).
    pub id: u64,
    /// Owning client's number.
    pub client_id: u64,
    /// Owning client's name.
    pub client: String,
    /// x, y, width, height.
    pub rect: [i32; 4],
    /// Depth layer.
    pub z: f32,
    /// Frames swapped.
    pub frames: u64,
    /// The newest frame the compositor has shown.
    pub shown: u64,
    /// Swap interval (0: unthrottled).
    pub interval: i32,
    /// The surface's normal for per-surface lighting.
    pub normal: [f32; 3],
    /// Bytes of command stream its client has sent so far (all its surfaces together).
    pub stream_bytes: u64,
    /// Its client's scheduling class.
    pub priority: Priority,
    /// Whether the compositor watches its frame deadline (`deadline = true` in the layout).
    pub deadline: bool,
    /// Refreshes at which its newest frame was older than its swap interval allows (counted
    /// for deadline surfaces only).
    pub deadline_misses: u64,
    /// Swap-to-shown latency of its recent frames (up to the last 1024 shown): the time from
    /// `eglSwapBuffers` publishing a frame to the device completing the composite that took
    /// it, p50, p99 and max, in microseconds.
    pub shown_latency_us: [u64; 3],
    /// The projection in effect for its depth (the layout's, else its EGL surface
    /// attributes'); `None`: undeclared, compared by raw depth.
    #[serde(default)]
    pub projection: Option<crate::projection::Projection>,
    /// Whether its ID is stable (the layout's, `STRATA_SURFACE_ID` or the application's).
    pub stable: bool,
    /// Its image's width and height (`rect` differs where a destination region scales it).
    pub image: [i32; 2],
    /// Its visibility, opacity and regions (its layers' are in `ControlReply::List::layers`).
    pub props: crate::properties::SurfaceProps,
    /// Whether it shows, its layers' visibility taken in.
    pub shown_visible: bool,
    /// Its opacity times its layers'.
    pub shown_opacity: f32,
    /// Its client's credentials.
    #[serde(default)]
    pub peer: Peer,
}

/// Who a client is, as the kernel told the daemon when it connected (`SO_PEERCRED`): never
/// what the client says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Peer {
    /// Process ID of the process that connected (it may have exited since).
    pub pid: u32,
    /// Its user ID.
    pub uid: u32,
    /// Its primary group ID.
    pub gid: u32,
    /// Whether it claims the name of a configuration entry whose credentials it lacks; such a
    /// client is treated as unnamed (no entry's placement, class, deadline, projection or quota).
    pub unverified: bool,
}

/// The credentials an entry requires (resolved `uid` and `gid`; `None`: any).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Requirement {
    /// The user ID it requires.
    pub uid: Option<u32>,
    /// The primary group ID it requires.
    pub gid: Option<u32>,
}

impl Requirement {
    /// Whether it requires anything.
    pub fn any(self) -> bool {
        self.uid.is_some() || self.gid.is_some()
    }

    /// Whether `peer`'s credentials meet it.
    pub fn admits(self, peer: &Peer) -> bool {
        self.uid.is_none_or(|u| u == peer.uid) && self.gid.is_none_or(|g| g == peer.gid)
    }
}

impl std::fmt::Display for Requirement {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.uid, self.gid) {
            (Some(u), Some(g)) => write!(f, "uid {u} and gid {g}"),
            (Some(u), None) => write!(f, "uid {u}"),
            (None, Some(g)) => write!(f, "gid {g}"),
            (None, None) => f.write_str("nothing"),
        }
    }
}

/// One output of `stratad ctl list`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OutputRow {
    /// Output name.
    pub name: String,
    /// `headless` or `window`.
    pub kind: String,
    /// The part of the global output space it shows: x, y, width, height.
    pub rect: [i32; 4],
    /// Frames composited into it so far (only when something changed).
    pub composites: u64,
    /// Of those, the ones drawn band by band over several refreshes (`--band-above-ms`).
    pub banded: u64,
    /// Passes the last composite drew.
    pub passes: u64,
    /// The part of the output the last composite redrew: x, y, width, height.
    pub region: [i32; 4],
    /// The composites' own device time so far (between timestamps at the start of a
    /// composite's first pass and the end of its last; where the device has no timestamps,
    /// from submission to completion), microseconds: divided by `composites`, what a
    /// composite costs the device.
    pub composite_us: u64,
    /// Time the composites waited on the compositor's queue before and around their own
    /// work (submission to completion, less their device time), microseconds.
    pub queue_us: u64,
    /// CPU time the compositor thread spent planning, encoding and submitting composites,
    /// microseconds.
    pub encode_us: u64,
    /// The scene's damage count (`ControlReply::List::damage`) that the newest completed
    /// composite shows: every change counted up to it is on the output.
    pub shown_damage: u64,
    /// The surface that has its keyboard focus.
    #[serde(default)]
    pub focus: Option<u64>,
}

/// The daemon's answer to a `ControlRequest`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ControlReply {
    /// Every output, and every window surface in stacking order.
    List {
        /// Outputs.
        outputs: Vec<OutputRow>,
        /// Window surfaces.
        surfaces: Vec<SurfaceRow>,
        /// Layers, by name.
        layers: Vec<crate::properties::LayerRow>,
        /// The scene's damage count now: it moves with every change that needs a composite
        /// (an output shows the change once its `shown_damage` reaches it).
        damage: u64,
    },
    /// A composited image: RGBA8, top row first.
    Image {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
        /// Pixels.
        rgba: crate::Bytes,
    },
    /// The moved surface, as it is now.
    Moved(SurfaceRow),
    /// The lighting now in force.
    Light(Lighting),
    /// The daemon's and its clients' resources.
    Stats(DaemonStats),
    /// Why a surface does or does not show.
    Analysis(crate::events::Analysis),
    /// The whole scene, in the form the daemon's `--config` reads (docs/control.md): outputs,
    /// layout, surfaces with their properties, layers, lighting and quotas.
    Scene(serde_json::Value),
    /// One event of a watched daemon.
    Event(crate::events::Event),
    /// Where an input request's events went.
    Input(crate::input::InputOutcome),
    /// The request failed.
    Error(String),
}

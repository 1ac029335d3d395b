//! `stratad serve`'s settings, the executor and device choices, and why serving can fail.

use std::path::PathBuf;

use strata_protocol::control::Priority;
use strata_protocol::handshake;

/// Daemon settings.
#[derive(Debug, Clone)]
pub struct ServeOptions {
    /// The client socket: where render clients connect.
    pub socket: PathBuf,
    /// The control socket (`None`: beside the client socket, `NAME-control.sock`).
    pub control_socket: Option<PathBuf>,
    /// The group the client socket is opened to (mode 0660; `None`: 0600, the daemon's user).
    pub client_group: Option<u32>,
    /// The group the control socket is opened to (mode 0660; `None`: 0600).
    pub control_group: Option<u32>,
    /// Command ring capacity per client, bytes (power of two).
    pub cmd_ring: u32,
    /// Reply ring capacity per client, bytes (power of two).
    pub reply_ring: u32,
    /// What runs each client's commands.
    pub executor: ExecutorKind,
    /// Sampled textures per compositor pass (`None`: the device's limit).
    pub max_textures: Option<u32>,
    /// How the compositor combines surfaces (3D, or the 2D baseline).
    pub compositor: strata_compositor::Mode,
    /// The colour format of chained compositor passes' intermediates.
    pub intermediate: strata_compositor::Intermediate,
    /// How surfaces' depth is stored: format and reversed-Z (`--depth-format`, `--reversed-z`).
    pub depth: strata_gles::DepthOptions,
    /// How render clients send `GL_FLOAT` client-side vertex arrays (told in the welcome).
    pub vertex_wire: strata_protocol::handshake::VertexWire,
    /// Whether the compositor leaves out surfaces under opaque nearer groups (the image is the
    /// same either way).
    pub cull: bool,
    /// Uniform lighting of composited output (initially; `stratad ctl light` changes it).
    pub lighting: strata_compositor::Lighting,
    /// The outputs the compositor draws.
    pub outputs: Vec<strata_compositor::root::OutputSpec>,
    /// Most composites per second.
    pub refresh_hz: f64,
    /// Frames a window surface may have swapped but not yet shown before its swap blocks.
    pub frames_in_flight: u32,
    /// Where clients' window surfaces go unless they say (first match by client name wins).
    pub layout: Vec<crate::layout::LayoutEntry>,
    /// Placement and properties of surfaces by stable ID (the configuration's `[[surface]]`).
    pub surfaces: Vec<crate::layout::SurfaceEntry>,
    /// Layers created at start (the configuration's `[[layer]]`).
    pub layers: Vec<crate::layout::LayerEntry>,
    /// Each client's limits, unless a quota entry names it.
    pub limits: strata_device::account::Limits,
    /// Per-client limits by client name (first match wins).
    pub quotas: Vec<crate::quota::QuotaEntry>,
    /// GPU memory all clients together may hold.
    pub total_gpu_bytes: u64,
    /// The daemon's own memory all clients' sessions together may hold.
    pub total_daemon_bytes: u64,
    /// Longest a chunked command may take from its first chunk to its last.
    pub command_time: std::time::Duration,
    /// The class of clients the configuration does not name and whose contexts do not ask.
    pub default_class: Priority,
    /// Whether each client renders on a device of its own or all share the compositor's.
    pub devices: DeviceMode,
    /// How window surfaces' frames reach the compositor's device.
    pub frame_transfer: strata_gles::TransferMode,
    /// Which clients get OpenGL ES 3.0 contexts (`--es3`, `--es3-for-es2`).
    pub es3: strata_gles::Es3Contexts,
    /// Whether devices ask for a queue global priority by class where the adapter offers it.
    pub global_priority: bool,
    /// Whether `ctl` may destroy a client's device (`ControlRequest::LoseDevice`; tests).
    pub fault_injection: bool,
    /// Rasterizer threads of each client's device on a CPU rasterizer (`None`: the driver's
    /// default).
    pub client_rasterizer_threads: Option<u32>,
    /// Most clients' devices open at once (`None`: as many as the driver opens); clients
    /// beyond it share the compositor's device.
    pub max_client_devices: Option<usize>,
    /// Caps on sessions, devices and handshakes, and the reserved class's reserves.
    pub caps: crate::caps::CapArgs,
    /// When the compositor draws a lower-priority change band by band between refreshes.
    pub bands: strata_compositor::root::BandOptions,
    /// Real input devices (`--input libinput`).
    pub input: crate::input::libinput::InputArgs,
}

/// Which device each client renders on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum DeviceMode {
    /// A device (and instance) of its own, created on its session thread at its class's
    /// priority; its window surfaces' frames reach the compositor's device through shared
    /// memory.
    #[default]
    PerClient,
    /// The compositor's device, one queue for everyone: no parallelism between clients and no
    /// isolation from each other's faults; a client's class only sets its session thread's
    /// CPU priority (to compare, or for a driver that cannot open a device per client).
    Shared,
}

/// The executor each client session gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ExecutorKind {
    /// The GLES 2.0 executor on the GPU (Vulkan; lavapipe without a GPU).
    #[default]
    Gles,
    /// Transport only: decode, stage bulk data, execute nothing (for transport benchmarks).
    Drain,
}

impl Default for ServeOptions {
    fn default() -> Self {
        ServeOptions {
            socket: handshake::default_socket_path(),
            control_socket: None,
            client_group: None,
            control_group: None,
            cmd_ring: 8 << 20,
            reply_ring: 1 << 20,
            executor: ExecutorKind::Gles,
            max_textures: None,
            compositor: strata_compositor::Mode::ThreeD,
            intermediate: strata_compositor::Intermediate::Rgba8,
            depth: strata_gles::DepthOptions::default(),
            vertex_wire: strata_protocol::handshake::VertexWire::Float,
            cull: true,
            lighting: strata_compositor::Lighting::default(),
            outputs: vec![strata_compositor::root::OutputSpec::default()],
            refresh_hz: 60.0,
            frames_in_flight: 2,
            layout: Vec::new(),
            surfaces: Vec::new(),
            layers: Vec::new(),
            limits: strata_device::account::Limits::default(),
            quotas: Vec::new(),
            total_gpu_bytes: strata_device::account::default_total(),
            command_time: std::time::Duration::from_secs(30),
            total_daemon_bytes: strata_device::account::default_total() / 2,
            default_class: Priority::Normal,
            devices: DeviceMode::PerClient,
            frame_transfer: strata_gles::TransferMode::Auto,
            es3: strata_gles::Es3Contexts::Off,
            global_priority: true,
            fault_injection: false,
            client_rasterizer_threads: Some(1),
            bands: strata_compositor::root::BandOptions::default(),
            max_client_devices: None,
            caps: crate::caps::CapArgs::default(),
            input: crate::input::libinput::InputArgs::default(),
        }
    }
}

/// Why the daemon could not serve.
#[derive(Debug, thiserror::Error)]
pub enum ServerError {
    /// Another daemon answers on the socket.
    #[error("another stratad is already serving on {0}")]
    AlreadyServing(PathBuf),
    /// Something other than a socket sits at the path.
    #[error("{0} exists and is not a socket; refusing to replace it")]
    NotASocket(PathBuf),
    /// No GPU device could be opened.
    #[error(transparent)]
    Gpu(#[from] strata_device::GpuError),
    /// The socket the service manager passed cannot be served on.
    #[error(transparent)]
    Activation(#[from] crate::systemd::ActivationError),
    /// The compositor or an output cannot run as configured.
    #[error(transparent)]
    Root(#[from] strata_compositor::root::RootError),
    /// No outputs, or two with one name.
    #[error("{0}")]
    Outputs(String),
    /// Caps and reserves that cannot hold together.
    #[error(transparent)]
    Caps(#[from] crate::caps::CapError),
    /// Ring sizes are unusable.
    #[error("ring capacity {0} must be a power of two between 4 KiB and 1 GiB")]
    BadRing(u32),
    /// Input devices cannot be read as configured.
    #[error(transparent)]
    Input(#[from] crate::input::libinput::LibinputError),
    /// Socket I/O failed.
    #[error("{context}: {source}")]
    Io {
        /// What was being done.
        context: String,
        /// The OS error.
        source: std::io::Error,
    },
}

pub(crate) fn io_err(context: impl Into<String>) -> impl FnOnce(std::io::Error) -> ServerError {
    let context = context.into();
    move |source| ServerError::Io { context, source }
}

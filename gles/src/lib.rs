//! The GLES 2.0 executor: runs one client's EGL/GLES command stream on wgpu.
//!
//! GL misuse never reaches wgpu: every call is validated against the client's GL state first,
//! and an invalid one records the GL error and changes nothing, as a driver would. What does
//! reach wgpu runs inside error scopes, so a wgpu validation error is logged against this client
//! and never panics the daemon.
//!
//! One module per GL concept, validation beside execution. `dispatch` routes each command (the
//! match is generated from the protocol's command table) to the handler named like the GL
//! call, `glBufferData` in `buffers`, `glDrawArrays` in `draw`, and so on; handlers validate
//! against [`context::Context`], record a [`error::GlError`] or act, and leave GPU work to
//! `render`. `conv` holds the typed enums and every GL → wgpu mapping.

mod account;
mod active_uniforms;
mod attachment_info;
mod blit;
mod buffer_copies;
mod buffers;
mod channels;
mod clear_buffers;
mod compressed;
mod context;
mod context_attribs;
mod conv;
mod copyimage;
mod debug;
mod dispatch;
mod divisors;
mod draw;
mod draw_plan;
mod draw_state;
pub mod egl;
mod egl_config;
mod egl_image;
pub mod enums;
mod enums_es3;
mod error;
mod flushed;
mod formats;
mod framebuffers;
pub mod glsl;
mod image_calls;
mod indices;
mod int_attribs;
mod integer;
mod invalidate;
pub mod limits;
mod linking;
mod names;
mod objects;
mod packed_float;
mod pipelines;
mod pixels;
mod programs;
mod queries;
mod query_objects;
mod render;
mod renderbuffers;
mod resolve;
mod samplers;
mod sampling;
mod shaders;
mod state;
mod surface;
mod teximage;
mod texstorage;
mod textures;
mod transform_feedback;
mod typed;
mod uniform_blocks;
mod uniforms;
mod unpack;
mod version;
mod vertex;

use std::collections::HashMap;
use std::sync::Arc;

pub mod execute;
pub use objects::surface::{DepthFormat, DepthOptions, Surface};
pub use strata_scene::transfer::TransferMode;

use context::Context;
use render::Renderer;
use strata_device::Gpu;

/// Where the daemon's configuration puts a client's window surfaces, whatever they ask for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Left edge in the output space.
    pub x: i32,
    /// Top edge in the output space.
    pub y: i32,
    /// Depth layer (larger is farther).
    pub z: f32,
    /// Width and height, where the configuration fixes them (else the window's own).
    pub size: Option<(u32, u32)>,
}

/// Runs one client's commands on the shared GPU.
pub struct GlesExecutor {
    gpu: Arc<Gpu>,
    r: Renderer,
    initialized: bool,
    surfaces: HashMap<u32, Surface>,
    contexts: HashMap<u32, Context>,
    /// Which context keeps each share group's shared tables, by group (see
    /// [`Objects::take_shared`](context::Objects::take_shared)).
    holders: HashMap<u32, u32>,
    /// The client's EGLImages, by handle (handles share `next_handle` with contexts and
    /// surfaces).
    images: HashMap<u32, objects::egl_image::EglImage>,
    next_handle: u32,
    /// The current (context, surface).
    current: Option<(u32, u32)>,
    /// Invalid `EGL_STRATA_surface_projection` declarations this client made (only the first
    /// is logged at warn).
    bad_projections: u32,
    /// The stable IDs the daemon's configuration gives this client's window surfaces, in the
    /// order it creates them.
    surface_ids: Vec<u64>,
    /// Window surfaces this client has created: which of `surface_ids` the next one takes.
    windows_made: usize,
    /// Stable IDs this client has been refused: each is logged once.
    refused_ids: std::collections::BTreeSet<u64>,
    uid: u64,
    /// Where window surfaces are shown: the scene, this client's id and name.
    scene: Option<(Arc<strata_scene::Scene>, u64, String)>,
    /// Where the daemon's configuration puts this client's windows, whatever they ask.
    placement: Option<Placement>,
    /// What this client may hold and holds (GPU memory, object counts).
    account: Arc<strata_device::account::Account>,
    /// Whether the daemon's configuration fixes the client's class (EGL's request is then
    /// ignored), and whether its surfaces have deadlines.
    policy_fixed: bool,
    deadline: bool,
    /// The projection the daemon's configuration gives this client's window surfaces: wins
    /// over what their EGL attributes declare.
    projection: Option<strata_protocol::projection::Projection>,
    /// How surfaces' depth is stored (`--depth-format`, `--reversed-z`).
    depth: DepthOptions,
    /// How window surfaces' frames reach the compositor (`--frame-transfer`).
    frame_transfer: TransferMode,
    /// Publishes each swapped frame once its work has completed on this client's device.
    waiter: strata_scene::FrameWaiter,
    /// Which requests get an OpenGL ES 3.0 context (`--es3`, `--es3-for-es2`).
    es3: Es3Contexts,
}

/// Which context requests get OpenGL ES 3.0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Es3Contexts {
    /// None: a request for version 3 is `EGL_BAD_MATCH` (ES 3.0 is being built).
    #[default]
    Off,
    /// Those that ask for version 3; a request for 2.0 gets 2.0.
    Asked,
    /// Those that ask for version 3 or 2, as Mesa answers a 2.0 request with the highest
    /// version it has (`--es3-for-es2`).
    ForEs2,
}

impl Drop for GlesExecutor {
    fn drop(&mut self) {
        // A client that leaves, even mid-frame, disappears from the next composite.
        if let Some((scene, client, _)) = &self.scene {
            scene.remove(*client, None);
        }
    }
}

impl GlesExecutor {
    /// An executor drawing on `gpu`; it logs within its session's span.
    pub fn new(gpu: Arc<Gpu>) -> Self {
        GlesExecutor {
            r: Renderer::new(gpu.clone()),
            waiter: strata_scene::FrameWaiter::new(gpu.clone(), "frames".into()),
            frame_transfer: TransferMode::Auto,
            gpu,
            initialized: false,
            surfaces: HashMap::new(),
            contexts: HashMap::new(),
            holders: HashMap::new(),
            images: HashMap::new(),
            next_handle: 1,
            current: None,
            uid: 1,
            scene: None,
            placement: None,
            account: strata_device::account::Account::unlimited(),
            policy_fixed: false,
            deadline: false,
            projection: None,
            depth: DepthOptions::default(),
            bad_projections: 0,
            surface_ids: Vec::new(),
            windows_made: 0,
            refused_ids: Default::default(),
            es3: Es3Contexts::Off,
        }
    }

    /// Schedules this client in `class`; with `fixed`, what its EGL contexts ask for is
    /// ignored. With `deadline`, the compositor counts its surfaces' missed deadlines.
    pub fn with_priority(mut self, class: strata_protocol::control::Priority, fixed: bool, deadline: bool) -> Self {
        self.r.lane.set_class(class);
        self.policy_fixed = fixed;
        self.deadline = deadline;
        self
    }

    /// Submits this client's work through `lane`, whose class the daemon set.
    pub fn with_lane(mut self, lane: Arc<strata_device::Lane>) -> Self {
        self.r.lane = lane;
        self
    }

    /// This client's way onto the queue.
    pub fn lane(&self) -> Arc<strata_device::Lane> {
        self.r.lane.clone()
    }

    /// Places this client's window surfaces at `placement` instead of where it asks.
    pub fn with_placement(mut self, placement: Option<Placement>) -> Self {
        self.placement = placement;
        self
    }

    /// Declares `projection` for this client's window surfaces, whatever their EGL attributes
    /// declare (`None`: theirs apply).
    pub fn with_projection(mut self, projection: Option<strata_protocol::projection::Projection>) -> Self {
        self.projection = projection;
        self
    }

    /// Gives this client's window surfaces, in the order it creates them, the stable `ids`
    /// (those beyond the list get the ID they ask for, or a runtime one).
    pub fn with_surface_ids(mut self, ids: Vec<u64>) -> Self {
        self.surface_ids = ids;
        self
    }

    /// Stores this client's surfaces' depth as `depth` says.
    pub fn with_depth(mut self, depth: DepthOptions) -> Self {
        self.depth = depth;
        self
    }

    /// Hands window surfaces' frames to the compositor as `mode` says.
    pub fn with_frame_transfer(mut self, mode: TransferMode) -> Self {
        self.frame_transfer = mode;
        self
    }

    /// Gives OpenGL ES 3.0 contexts to the requests `es3` says.
    pub fn with_es3(mut self, es3: Es3Contexts) -> Self {
        self.es3 = es3;
        self
    }

    /// Holds this client to `account`'s quota.
    pub fn with_account(mut self, account: Arc<strata_device::account::Account>) -> Self {
        self.account = account;
        self
    }

    /// Shows this client's window surfaces in `scene` as client `id` named `name`.
    pub fn with_scene(mut self, scene: Arc<strata_scene::Scene>, id: u64, name: &str) -> Self {
        self.scene = Some((scene, id, name.to_string()));
        self.waiter = strata_scene::FrameWaiter::new(self.gpu.clone(), format!("frames-{id}"));
        self
    }

    /// Whether this client renders on a device of its own (not the compositor's).
    fn own_device(&self) -> bool {
        let comp = self.scene.as_ref().and_then(|(scene, _, _)| scene.compositor());
        comp.is_none_or(|c| !Arc::ptr_eq(&c, &self.gpu))
    }

    /// Moves this client's threads to `class`'s CPU priority (on its session thread): its
    /// session thread's nice value and slice and, with a device of its own, the device's driver
    /// threads' (in the idle class when low, as `Gpu::open_with` puts them). Raising needs
    /// `CAP_SYS_NICE`; without it, only lowering takes effect.
    pub(crate) fn apply_class_priority(&self, class: strata_protocol::control::Priority) {
        let nice = strata_device::nice_for(class);
        strata_device::set_thread_class(class);
        if self.own_device() {
            let idle = class == strata_protocol::control::Priority::Low;
            for &t in &self.gpu.threads {
                strata_device::set_thread_idle(t, idle);
            }
            self.gpu.renice(nice);
            for &t in &self.gpu.threads {
                strata_device::set_thread_slice(t, strata_device::slice_for(class));
            }
        }
    }

    /// Pipelines created because none in the cache matched.
    pub fn pipeline_cache_misses(&self) -> u64 {
        self.r.pipeline_misses
    }

    /// The surface with handle `id`, for the compositor and tests.
    pub fn surface(&self, id: u32) -> Option<&Surface> {
        self.surfaces.get(&id)
    }
}

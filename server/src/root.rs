//! The root surface (§4.5): the compositor thread and the outputs it draws. Surfaces live in
//! one global output space; each output shows one rectangle of it. The thread sleeps until
//! the scene's damage count moves (a swap, a surface added, moved or gone, a lighting change)
//! or a swap waits for a refresh, composites at most once per refresh period, and counts the
//! refresh so paced swaps can proceed.

use std::str::FromStr;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::control::OutputRow;
use strata_protocol::projection::Projection;
use tracing::{info, warn};

use crate::compositor::{Compositor, CompositorError, Intermediate, Layer, Mode};
use crate::gpu::Gpu;
use crate::scene::{Part, Region, Scene, Work};

/// Default output: the width and height of a typical automotive centre display.
pub const DEFAULT_OUTPUT: (u32, u32) = (1920, 720);

/// Where an output's image goes besides the daemon's memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// Off-screen only (screenshots).
    Headless,
    /// Also shown in a desktop window; failing to open one is an error.
    Window,
    /// A window when a display exists and one opens, else headless.
    Auto,
}

/// One output: a name and the rectangle of the global output space it shows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputSpec {
    /// Name used by `stratad ctl screenshot`.
    pub name: String,
    /// Headless, window, or whichever the environment allows.
    pub kind: OutputKind,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Left edge in the output space.
    pub x: i32,
    /// Top edge in the output space.
    pub y: i32,
}

impl Default for OutputSpec {
    fn default() -> Self {
        OutputSpec {
            name: "main".into(),
            kind: OutputKind::Auto,
            width: DEFAULT_OUTPUT.0,
            height: DEFAULT_OUTPUT.1,
            x: 0,
            y: 0,
        }
    }
}

/// An output specification that does not parse.
#[derive(Debug, thiserror::Error)]
#[error("output {0:?} is not [window:|headless:]NAME=WxH[+X+Y] with sizes 1..=8192 (e.g. main=1920x720+0+0)")]
pub struct BadOutputSpec(String);

impl FromStr for OutputSpec {
    type Err = BadOutputSpec;

    /// Parses `[window:|headless:]NAME=WxH[+X+Y]` (or `WxH`, named `main`); headless unless
    /// `window:` is given.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || BadOutputSpec(s.to_string());
        let (kind, rest) = if let Some(r) = s.strip_prefix("window:") {
            (OutputKind::Window, r)
        } else {
            (OutputKind::Headless, s.strip_prefix("headless:").unwrap_or(s))
        };
        let (name, geom) = match rest.split_once('=') {
            Some((n, g)) if !n.is_empty() => (n.to_string(), g),
            Some(_) => return Err(bad()),
            None => ("main".to_string(), rest),
        };
        let mut parts = geom.split('+');
        let size = parts.next().ok_or_else(bad)?;
        let (w, h) = size.split_once('x').ok_or_else(bad)?;
        let width: u32 = w.parse().map_err(|_| bad())?;
        let height: u32 = h.parse().map_err(|_| bad())?;
        let x: i32 = parts.next().map(str::parse).transpose().map_err(|_| bad())?.unwrap_or(0);
        let y: i32 = parts.next().map(str::parse).transpose().map_err(|_| bad())?.unwrap_or(0);
        if parts.next().is_some() || !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
            return Err(bad());
        }
        Ok(OutputSpec { name, kind, width, height, x, y })
    }
}

struct Output {
    spec: OutputSpec,
    texture: wgpu::Texture,
    window: Option<crate::window::WindowOutput>,
    composites: u64,
    passes: u64,
    /// The part the last composite redrew (output pixels).
    region: [i32; 4],
    /// Whether the last composite reached the window (if any).
    presented: bool,
    /// The composites' own device time so far.
    device: Duration,
    /// Time they waited on the queue.
    queue: Duration,
    /// Time spent planning, encoding and submitting them.
    encode: Duration,
}

struct Inner {
    compositor: Compositor,
    outputs: Vec<Output>,
    /// The damage count the outputs reflect (`None`: never composited).
    composited: Option<u64>,
}

/// The compositor thread's state, shared with control requests (screenshots, listings).
pub struct Root {
    gpu: Arc<Gpu>,
    scene: Arc<Scene>,
    inner: Mutex<Inner>,
}

/// Why the root surface could not start.
#[derive(Debug, thiserror::Error)]
pub enum RootError {
    /// The compositor cannot run as configured.
    #[error(transparent)]
    Compositor(#[from] CompositorError),
    /// A window output could not open.
    #[error(transparent)]
    Window(#[from] crate::window::WindowError),
}

/// The longest the compositor waits for one composite (a wedged device must not wedge it).
const COMPOSITE_WAIT_LIMIT: Duration = Duration::from_secs(5);

/// Background of every output: opaque black.
const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

impl Root {
    /// Creates the outputs, composited in `mode` (chained passes through `intermediate`, surfaces
    /// under opaque nearer groups culled when `cull`); fails if the texture limit cannot chain or
    /// exceeds the device's, or a window output cannot open.
    pub fn new(
        gpu: Arc<Gpu>,
        scene: Arc<Scene>,
        outputs: &[OutputSpec],
        max_textures: Option<u32>,
        mode: Mode,
        intermediate: Intermediate,
        cull: bool,
    ) -> Result<Root, RootError> {
        let compositor = Compositor::new(gpu.clone(), max_textures)?
            .with_mode(mode)
            .with_intermediate(intermediate)
            .with_culling(cull);
        let mut made = Vec::new();
        for spec in outputs {
            let window = match spec.kind {
                OutputKind::Headless => None,
                OutputKind::Window => {
                    Some(crate::window::WindowOutput::open(&gpu, &spec.name, spec.width, spec.height)?)
                }
                OutputKind::Auto if crate::window::display_available() => {
                    match crate::window::WindowOutput::open(&gpu, &spec.name, spec.width, spec.height) {
                        Ok(w) => Some(w),
                        Err(e) => {
                            warn!(output = %spec.name, "{e}; the output is headless");
                            None
                        }
                    }
                }
                OutputKind::Auto => None,
            };
            made.push(Output {
                window,
                texture: gpu.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("output"),
                    size: wgpu::Extent3d { width: spec.width, height: spec.height, depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: wgpu::TextureFormat::Rgba8Unorm,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                        | wgpu::TextureUsages::COPY_SRC
                        | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                }),
                spec: spec.clone(),
                composites: 0,
                passes: 0,
                region: [0; 4],
                presented: true,
                device: Duration::ZERO,
                queue: Duration::ZERO,
                encode: Duration::ZERO,
            });
        }
        Ok(Root { gpu, scene, inner: Mutex::new(Inner { compositor, outputs: made, composited: None }) })
    }

    /// Composites every output if the scene changed since the last composite; returns the
    /// damage count the outputs now reflect.
    pub fn composite_if_damaged(&self) -> Option<u64> {
        self.composite_part(Part::All)
    }

    /// Composites `part` of what changed on every output: with `Part::All`, everything, if
    /// anything changed since the last composite (returning the damage count the outputs now
    /// reflect); with `Part::High`, only high-priority surfaces' new frames (returning `None`
    /// when the compositor is unavailable).
    pub fn composite_part(&self, part: Part) -> Option<u64> {
        let mut inner = self.inner.lock().ok()?;
        let damage = self.scene.damage();
        if inner.composited == Some(damage) {
            return Some(damage);
        }
        let Inner { compositor, outputs, .. } = &mut *inner;
        let started = Instant::now();
        let mut composited = Vec::new();
        // Every surface's newest complete frame, marked as read until this composite has
        // completed (`Scene::shown`), so no client draws into it meanwhile.
        let (_, seen, shown) = self.scene.compose(part, |surfaces, light, changed| {
            for (index, out) in outputs.iter_mut().enumerate() {
                let (ox, oy) = (out.spec.x, out.spec.y);
                // The changed region in this output's pixels; nothing to do if it misses it.
                let local = match changed {
                    Region::Full => None,
                    Region::None => continue,
                    Region::Rect(r) => {
                        let (ox, oy) = (i64::from(ox), i64::from(oy));
                        let x0 = (r[0] - ox).max(0);
                        let y0 = (r[1] - oy).max(0);
                        let x1 = (r[0] + r[2] - ox).min(i64::from(out.spec.width));
                        let y1 = (r[1] + r[3] - oy).min(i64::from(out.spec.height));
                        if x1 <= x0 || y1 <= y0 {
                            continue;
                        }
                        // Within the output, so each fits in a u32.
                        Some([x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32])
                    }
                };
                let layers: Vec<Layer<'_>> = surfaces
                    .iter()
                    .filter_map(|s| {
                        Some(Layer {
                            // Placements far outside the i32 range of this output's pixels
                            // cover none of them; saturating keeps them outside.
                            rect: [s.rect[0].saturating_sub(ox), s.rect[1].saturating_sub(oy), s.rect[2], s.rect[3]],
                            z: s.z,
                            color: s.color.as_ref()?,
                            depth: s.depth.as_ref(),
                            normal: s.normal,
                            projection: Projection::shader_params(s.projection.as_ref()),
                            opaque: s.opaque,
                        })
                    })
                    .collect();
                compositor.composite(&layers, light, &out.texture, BACKGROUND, local);
                out.composites += 1;
                composited.push(index);
                out.passes = compositor.last_passes as u64;
                out.region =
                    local.map_or([0, 0, out.spec.width as i32, out.spec.height as i32], |r| r.map(|v| v as i32));
                out.presented = false;
            }
        })?;
        if part == Part::All {
            inner.composited = Some(seen);
        }
        let submitted = Instant::now();
        for out in inner.outputs.iter_mut().filter(|o| !o.presented) {
            out.presented = true;
            if let Some(w) = &mut out.window {
                w.present(&self.gpu, &out.texture);
            }
        }
        // Wait for this composite: nothing else runs on the compositor's device.
        let waited = match inner.compositor.last_submission.take() {
            Some(index) => {
                let wait = wgpu::PollType::Wait { submission_index: Some(index), timeout: Some(COMPOSITE_WAIT_LIMIT) };
                if let Err(e) = self.gpu.device.poll(wait) {
                    warn!("waiting for a composite: {e}");
                }
                submitted.elapsed()
            }
            None => Duration::ZERO,
        };
        let device = inner.compositor.take_device_time().unwrap_or(waited).min(waited);
        self.scene.shown(shown);
        // Each output composited shares the round's time (one output: its composite's cost).
        let n = composited.len().max(1) as u32;
        let encode = submitted.duration_since(started);
        for &i in &composited {
            if let Some(out) = inner.outputs.get_mut(i) {
                out.device += device / n;
                out.queue += (waited - device) / n;
                out.encode += encode / n;
            }
        }
        Some(seen)
    }

    /// The outputs as `stratad ctl list` shows them.
    pub fn rows(&self) -> Vec<OutputRow> {
        let Ok(inner) = self.inner.lock() else { return Vec::new() };
        inner
            .outputs
            .iter()
            .map(|o| OutputRow {
                name: o.spec.name.clone(),
                kind: if o.window.is_some() { "window" } else { "headless" }.into(),
                rect: [o.spec.x, o.spec.y, o.spec.width as i32, o.spec.height as i32],
                composites: o.composites,
                passes: o.passes,
                region: o.region,
                composite_us: o.device.as_micros() as u64,
                queue_us: o.queue.as_micros() as u64,
                encode_us: o.encode.as_micros() as u64,
            })
            .collect()
    }

    /// The named output's current image (RGBA8, top row first), composited first if the
    /// scene changed. An empty name means the first output.
    pub fn screenshot(&self, name: &str) -> Result<(u32, u32, Vec<u8>), String> {
        self.composite_if_damaged().ok_or("the compositor is unavailable")?;
        let inner = self.inner.lock().map_err(|_| "the compositor is unavailable")?;
        let out =
            if name.is_empty() { inner.outputs.first() } else { inner.outputs.iter().find(|o| o.spec.name == name) };
        let Some(out) = out else {
            let names: Vec<&str> = inner.outputs.iter().map(|o| o.spec.name.as_str()).collect();
            return Err(format!("no output named {name:?}; outputs: {}", names.join(", ")));
        };
        let (w, h) = (out.spec.width, out.spec.height);
        let rgba = self.gpu.read_rgba8(&out.texture, [0, 0, w, h]).ok_or("reading the output back failed")?;
        Ok((w, h, rgba))
    }

    /// Runs the compositor loop on a new thread until [`Root::stop`]: composite when damaged,
    /// at most `refresh_hz` times a second.
    pub fn spawn(self: &Arc<Self>, refresh_hz: f64) -> std::io::Result<std::thread::JoinHandle<()>> {
        let root = self.clone();
        let period = Duration::from_secs_f64(1.0 / refresh_hz.clamp(1.0, 1000.0));
        self.scene.set_root(true);
        std::thread::Builder::new().name("compositor".into()).spawn(move || {
            // The compositor is on every frame's path to the output: it runs at the high
            // class's CPU priority where the daemon may raise it.
            let nice = crate::gpu::set_thread_nice(crate::gpu::nice_for(strata_protocol::control::Priority::High));
            info!(refresh_hz, nice, "compositor running");
            let mut next = Instant::now();
            let mut seen = None;
            loop {
                if root.scene.wait_for_work(seen.unwrap_or(u64::MAX)) == Work::Stop {
                    break;
                }
                let now = Instant::now();
                if next > now {
                    std::thread::sleep(next - now);
                }
                next = (next + period).max(now);
                // High-priority surfaces' new frames first, and the refresh counted once they
                // are shown; then whatever else changed, which may take longer.
                let high = root.composite_part(Part::High);
                root.scene.refreshed();
                match high.and_then(|_| root.composite_part(Part::All)) {
                    Some(d) => seen = Some(d),
                    None => {
                        warn!("the compositor's state is poisoned; stopping it");
                        root.scene.set_root(false);
                        break;
                    }
                }
            }
            info!("compositor stopped");
        })
    }

    /// Stops the compositor loop and releases every waiting swap.
    pub fn stop(&self) {
        self.scene.set_root(false);
    }
}

//! The root surface (§4.5): the compositor thread and the outputs it draws. Surfaces live in
//! one global output space; each output shows one rectangle of it. The thread sleeps until
//! the scene's damage count moves (a swap, a surface added, moved or gone, a lighting change)
//! or a swap waits for a refresh, composites at most once per refresh period, and counts the
//! refresh so paced swaps can proceed.

use std::str::FromStr;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::control::OutputRow;
use tracing::{info, warn};

use crate::compositor::{Compositor, CompositorError, Layer};
use crate::gpu::Gpu;
use crate::scene::{Scene, Work};

/// Default output: the width and height of a typical automotive centre display.
pub const DEFAULT_OUTPUT: (u32, u32) = (1920, 720);

/// One output: a name and the rectangle of the global output space it shows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputSpec {
    /// Name used by `stratad ctl screenshot`.
    pub name: String,
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
        OutputSpec { name: "headless-0".into(), width: DEFAULT_OUTPUT.0, height: DEFAULT_OUTPUT.1, x: 0, y: 0 }
    }
}

/// An output specification that does not parse.
#[derive(Debug, thiserror::Error)]
#[error("output {0:?} is not NAME=WxH[+X+Y] with sizes 1..=8192 (e.g. headless-0=1920x720+0+0)")]
pub struct BadOutputSpec(String);

impl FromStr for OutputSpec {
    type Err = BadOutputSpec;

    /// Parses `NAME=WxH[+X+Y]` (or `WxH`, named `headless-0`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || BadOutputSpec(s.to_string());
        let (name, geom) = match s.split_once('=') {
            Some((n, g)) if !n.is_empty() => (n.to_string(), g),
            Some(_) => return Err(bad()),
            None => ("headless-0".to_string(), s),
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
        Ok(OutputSpec { name, width, height, x, y })
    }
}

struct Output {
    spec: OutputSpec,
    texture: wgpu::Texture,
    composites: u64,
    passes: u64,
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

/// Background of every output: opaque black.
const BACKGROUND: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

impl Root {
    /// Creates the outputs; fails if the texture limit cannot chain or exceeds the device's.
    pub fn new(
        gpu: Arc<Gpu>,
        scene: Arc<Scene>,
        outputs: &[OutputSpec],
        max_textures: Option<u32>,
    ) -> Result<Root, CompositorError> {
        let compositor = Compositor::new(gpu.clone(), max_textures)?;
        let outputs = outputs
            .iter()
            .map(|spec| Output {
                texture: gpu.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some("output"),
                    size: wgpu::Extent3d { width: spec.width, height: spec.height, depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: wgpu::TextureFormat::Rgba8Unorm,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                }),
                spec: spec.clone(),
                composites: 0,
                passes: 0,
            })
            .collect();
        Ok(Root { gpu, scene, inner: Mutex::new(Inner { compositor, outputs, composited: None }) })
    }

    /// Composites every output if the scene changed since the last composite; returns the
    /// damage count the outputs now reflect.
    pub fn composite_if_damaged(&self) -> Option<u64> {
        let mut inner = self.inner.lock().ok()?;
        let damage = self.scene.damage();
        if inner.composited == Some(damage) {
            return Some(damage);
        }
        let Inner { compositor, outputs, .. } = &mut *inner;
        // Encode and submit under the scene lock: no swap can interleave, so every front
        // image sampled here is a completed frame.
        let (_, seen) = self.scene.compose(|surfaces, light| {
            for out in outputs.iter_mut() {
                let (ox, oy) = (out.spec.x, out.spec.y);
                let layers: Vec<Layer<'_>> = surfaces
                    .iter()
                    .filter_map(|s| {
                        Some(Layer {
                            rect: [s.rect[0] - ox, s.rect[1] - oy, s.rect[2], s.rect[3]],
                            z: s.z,
                            color: s.color.as_ref()?,
                            depth: s.depth.as_ref(),
                            normal: [0.0, 0.0, 1.0],
                        })
                    })
                    .collect();
                compositor.composite(&layers, light, &out.texture, BACKGROUND);
                out.composites += 1;
                out.passes = compositor.last_passes as u64;
            }
        })?;
        inner.composited = Some(seen);
        let _ = self.gpu.device.poll(wgpu::PollType::wait_indefinitely());
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
                kind: "headless".into(),
                rect: [o.spec.x, o.spec.y, o.spec.width as i32, o.spec.height as i32],
                composites: o.composites,
                passes: o.passes,
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
            info!(refresh_hz, "compositor running");
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
                match root.composite_if_damaged() {
                    Some(d) => seen = Some(d),
                    None => {
                        warn!("the compositor's state is poisoned; stopping it");
                        root.scene.set_root(false);
                        break;
                    }
                }
                root.scene.refreshed();
            }
            info!("compositor stopped");
        })
    }

    /// Stops the compositor loop and releases every waiting swap.
    pub fn stop(&self) {
        self.scene.set_root(false);
    }
}

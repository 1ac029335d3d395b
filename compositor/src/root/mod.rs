//! The root surface (§4.5): the compositor thread and the outputs it draws. Surfaces live in
//! one global output space; each output shows one rectangle of it. The thread sleeps until
//! the scene's damage count moves (a swap, a surface added, moved or gone, a lighting change)
//! or a swap waits for a refresh, composites at most once per refresh period, and counts the
//! refresh so paced swaps can proceed.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use strata_protocol::control::{OutputRow, Priority};
use strata_protocol::projection::Projection;
use tracing::{info, warn};

use crate::{Compositor, Intermediate, Layer, Mode, Props};
use bands::{Banded, Cost, Job, KeptLayer};
use strata_device::Gpu;
use strata_scene::{Part, Region, Scene, Shown, Work};

mod bands;
mod draw_bands;
mod outputs;
mod pick;
mod picking;
mod state;

pub use bands::BandOptions;
pub use outputs::{BadOutputSpec, OutputKind, OutputSpec, DEFAULT_OUTPUT};
pub use pick::Target;
pub use state::{Root, RootError, Watchdog};

use outputs::{output_texture, Output};
use state::{Inner, BACKGROUND, COMPOSITE_WAIT_LIMIT};

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
        // The output windows' own input, routed as `ctl input` is.
        let input = std::sync::mpsc::channel();
        for spec in outputs {
            let window = match spec.kind {
                OutputKind::Headless => None,
                OutputKind::Window => Some(crate::window::WindowOutput::open(
                    &gpu,
                    &spec.name,
                    spec.width,
                    spec.height,
                    Some(input.0.clone()),
                )?),
                OutputKind::Auto if crate::window::display_available() => {
                    match crate::window::WindowOutput::open(
                        &gpu,
                        &spec.name,
                        spec.width,
                        spec.height,
                        Some(input.0.clone()),
                    ) {
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
                texture: output_texture(&gpu, "output", spec.width, spec.height),
                spec: spec.clone(),
                composites: 0,
                banded: 0,
                passes: 0,
                region: [0; 4],
                presented: true,
                device: Duration::ZERO,
                queue: Duration::ZERO,
                encode: Duration::ZERO,
                staging: None,
            });
        }
        let inner = Inner { compositor, outputs: made, composited: None, bands: None, cost: Cost::default() };
        let places = outputs.iter().map(|o| (o.name.clone(), [o.x, o.y, o.width as i32, o.height as i32])).collect();
        Ok(Root {
            gpu,
            scene,
            places,
            inner: Mutex::new(inner),
            bands: BandOptions::default(),
            wedged: Default::default(),
            picker: Mutex::new(None),
            window_input: Mutex::new(Some(input.1)),
        })
    }

    /// Draws changes band by band as `bands` says.
    pub fn with_bands(mut self, bands: BandOptions) -> Self {
        self.bands = bands;
        self
    }

    /// Whether a composite is being drawn band by band (the compositor thread must go on
    /// without waiting for new damage).
    pub fn banding(&self) -> bool {
        self.inner.lock().is_ok_and(|i| i.bands.is_some())
    }

    /// Composites `part` of what changed on every output: with `Part::All`, everything, if
    /// anything changed since the last composite (finishing a banded composite first), and
    /// returns the damage count the outputs now reflect; with `Part::High`, only high-priority
    /// surfaces' new frames (`None` when the compositor is unavailable). With a `deadline` (the
    /// next refresh), a `Part::All` change predicted to take longer than
    /// [`BandOptions::above`], while high-priority surfaces are shown but none overlaps it, is
    /// drawn band by band, as much of it now as fits before the deadline.
    fn composite(&self, part: Part, deadline: Option<Instant>) -> Option<u64> {
        let mut inner = self.inner.lock().ok()?;
        if part == Part::All && inner.bands.is_some() {
            self.run_bands(&mut inner, deadline);
            if inner.bands.is_some() {
                return Some(self.scene.damage());
            }
        }
        let damage = self.scene.damage();
        if inner.composited == Some(damage) {
            return Some(damage);
        }
        let Inner { compositor, outputs, cost, .. } = &mut *inner;
        let started = Instant::now();
        let mut composited = Vec::new();
        let mut jobs = Vec::new();
        let mut light_taken = None;
        let mut pixels = 0u64;
        // Every surface's newest complete frame, marked as read until this composite has
        // completed (`Scene::shown`), so no client draws into it meanwhile.
        let (_, seen, shown) = self.scene.compose(part, |surfaces, light, changed| {
            light_taken = Some(*light);
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
                        let props = Props::of(s, s.props.opacity)?;
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
                            props,
                        })
                    })
                    .collect();
                let r = local.unwrap_or([0, 0, out.spec.width, out.spec.height]);
                let area = u64::from(r[2]) * u64::from(r[3]);
                let in_output = |s: [i32; 4]| [s[0] - ox, s[1] - oy, s[2], s[3]].map(i64::from);
                // Banded only where there is a high-priority surface to protect, and not under it.
                let high = surfaces.iter().filter(|s| s.priority == Priority::High);
                let band = part == Part::All
                    && deadline.is_some()
                    && high.clone().next().is_some()
                    && cost.predict(area).is_some_and(|t| t > self.bands.above)
                    && !high.clone().any(|s| bands::overlaps(in_output(s.rect), r.map(i64::from)));
                if band {
                    let layers = layers.iter().map(KeptLayer::keep).collect();
                    jobs.push(Job { output: index, region: r, rows_done: 0, layers });
                    continue;
                }
                if let Err(e) = compositor.composite(&layers, light, &out.texture, BACKGROUND, local) {
                    // The output keeps its last image.
                    tracing::error!(output = %out.spec.name, "{e}");
                    continue;
                }
                pixels += area;
                out.composites += 1;
                composited.push(index);
                out.passes = compositor.last_passes as u64;
                out.region = r.map(|v| v as i32);
                out.presented = false;
            }
        })?;
        let banded = !jobs.is_empty();
        let shown = match light_taken {
            Some(light) if banded => {
                // The frames the bands read stay read until the last band is copied in.
                self.scene.hold();
                inner.bands = Some(Banded { jobs, light, shown, seen });
                Shown::default()
            }
            _ => {
                if part == Part::All {
                    inner.composited = Some(seen);
                }
                shown
            }
        };
        let submitted = Instant::now();
        for out in inner.outputs.iter_mut().filter(|o| !o.presented) {
            out.presented = true;
            if let Some(w) = &mut out.window {
                w.present(&self.gpu, &out.texture);
            }
        }
        let (device, waited) = self.wait_composite(&mut inner);
        self.scene.shown(shown);
        if part == Part::All {
            inner.cost.record(pixels, started.elapsed());
        }
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
        if banded {
            self.run_bands(&mut inner, deadline);
        }
        Some(seen)
    }

    /// Waits for the compositor's last submission; its own device time, and the whole wait.
    fn wait_composite(&self, inner: &mut Inner) -> (Duration, Duration) {
        let submitted = Instant::now();
        // Nothing else runs on the compositor's device.
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
        (inner.compositor.take_device_time().unwrap_or(waited).min(waited), waited)
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
                banded: o.banded,
                passes: o.passes,
                region: o.region,
                composite_us: o.device.as_micros() as u64,
                queue_us: o.queue.as_micros() as u64,
                encode_us: o.encode.as_micros() as u64,
                shown_damage: inner.composited.unwrap_or(0),
                // Filled in by the listener, which routes input.
                focus: None,
            })
            .collect()
    }

    /// The named output's current image (RGBA8, top row first), composited first if the
    /// scene changed. An empty name means the first output.
    pub fn screenshot(&self, name: &str) -> Result<(u32, u32, Vec<u8>), String> {
        self.composite(Part::All, None).ok_or("the compositor is unavailable")?;
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

    /// Window surface `id`'s newest complete frame as RGBA8 rows, top row first (the order of a
    /// PNG), as its client drew it: width, height and pixels.
    pub fn surface_screenshot(&self, id: u64) -> Result<(u32, u32, Vec<u8>), String> {
        // No composite runs while the frame is read: both mark it read the same way.
        let _composites = self.inner.lock().map_err(|_| "the compositor is unavailable")?;
        let read = self.scene.read_frame(id, |view| {
            let t = view.texture();
            let (w, h) = (t.width(), t.height());
            self.gpu.read_rgba8(t, [0, 0, w, h]).map(|rows| (w, h, rows))
        });
        let (w, h, rows) = match read {
            Some(Some(image)) => image,
            Some(None) => return Err(format!("reading surface {id}'s frame back failed")),
            None if self.scene.rows().iter().any(|r| r.id == id) => {
                return Err(format!("surface {id} has not swapped a frame yet"))
            }
            None => return Err(format!("no surface {id}; `stratad ctl list` shows them")),
        };
        // Surface images are in GL row order: bottom row first.
        let row = w as usize * 4;
        let flipped: Vec<u8> = rows.chunks_exact(row).rev().flatten().copied().collect();
        Ok((w, h, flipped))
    }

    /// Runs the compositor loop on a new thread until [`Root::stop`]: composite when damaged,
    /// at most `refresh_hz` times a second; with `watchdog`, it also calls its `ping` (the
    /// service manager's watchdog) every `period`.
    pub fn spawn(
        self: &Arc<Self>,
        refresh_hz: f64,
        watchdog: Option<Watchdog>,
    ) -> std::io::Result<std::thread::JoinHandle<()>> {
        let (watchdog, ping) = match watchdog {
            Some(w) => (Some(w.period), w.ping),
            None => (None, (|| ()) as fn()),
        };
        let root = self.clone();
        let period = Duration::from_secs_f64(1.0 / refresh_hz.clamp(1.0, 1000.0));
        self.scene.set_root(true);
        std::thread::Builder::new().name("compositor".into()).spawn(move || {
            // The compositor is on every frame's path to the output: it runs at the high
            // class's CPU priority where the daemon may raise it.
            let nice = strata_device::set_thread_class(strata_protocol::control::Priority::High);
            info!(refresh_hz, nice, "compositor running");
            let mut next = Instant::now();
            let mut seen = None;
            let mut pinged = Instant::now();
            if watchdog.is_some() {
                ping();
            }
            loop {
                while root.wedged.load(std::sync::atomic::Ordering::Relaxed) && root.scene.root_running() {
                    std::thread::sleep(Duration::from_millis(20));
                }
                // The service manager's watchdog hears from this loop only: a compositor
                // stuck in a composite stops the pings.
                if watchdog.is_some_and(|w| pinged.elapsed() >= w) {
                    ping();
                    pinged = Instant::now();
                }
                let quiet = watchdog.map(|w| w.saturating_sub(pinged.elapsed()));
                match root.scene.wait_for_work(seen.unwrap_or(u64::MAX), quiet) {
                    Work::Stop => break,
                    Work::Quiet => continue,
                    Work::Refresh => {}
                }
                let now = Instant::now();
                if next > now {
                    std::thread::sleep(next - now);
                }
                next = (next + period).max(now);
                // High-priority surfaces' new frames first, and the refresh counted once they
                // are shown; then whatever else changed, which may take longer.
                let high = root.composite(Part::High, None);
                root.scene.refreshed();
                // Whatever else changed, banded where it would hold up the next refresh.
                match high.and_then(|_| root.composite(Part::All, Some(next))) {
                    // A banded composite goes on at the next refresh, new damage or not.
                    Some(_) if root.banding() => seen = None,
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

    /// The output windows' pointer, touch and key input as actions on their outputs (once).
    pub fn take_window_input(&self) -> Option<std::sync::mpsc::Receiver<strata_protocol::input::InputRequest>> {
        self.window_input.lock().ok()?.take()
    }

    /// Stops the compositor loop and releases every waiting swap.
    pub fn stop(&self) {
        self.scene.set_root(false);
    }

    /// Fault injection (`ctl wedge-compositor`, for tests): the compositor thread stops
    /// compositing and pinging the watchdog, as if a composite never returned, until the daemon
    /// stops.
    pub fn wedge(&self) {
        warn!("the compositor is wedged (fault injection)");
        self.wedged.store(true, std::sync::atomic::Ordering::Relaxed);
    }
}

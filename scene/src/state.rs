//! What the compositor sees: every client's window surfaces with their placement and their
//! buffers (`mailbox`), and the lighting. A frame is published when its work has completed on
//! its client's device, and every composite takes each surface's newest complete frame, so a
//! frame is either wholly visible or not at all; the buffer a composite reads is not drawn
//! into again until that composite has completed.
//!
//! The scene also carries the pacing between the two sides. Every change that needs a new
//! composite bumps a damage counter; the compositor thread ("root") sleeps until it moves.
//! A swap blocks while its surface has K frames in flight (swapped but not yet composited),
//! and with a swap interval n ≥ 1 also until n output refreshes have passed since the
//! surface's previous swap. Interval 0 never blocks.

use std::collections::{BTreeMap, HashMap};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use strata_device::Gpu;
use strata_protocol::control::{LightChange, Lighting, Priority, Requirement, SurfaceRow};

use crate::ids::{IdRefused, Ids};
use crate::layers::Layers;
use crate::mailbox::{Buffers, Images};
use crate::presets::SurfaceEntry;
use crate::region::Region;

/// Events kept for watchers that have not read them yet.
const EVENT_BACKLOG: usize = 1024;

/// Swap-to-shown latencies kept per surface for `ctl list`.
pub(crate) const LATENCIES: usize = 1024;

/// Longest a swap waits for the compositor before giving up on pacing (a wedged compositor
/// must not wedge its clients).
pub(crate) const MAX_SWAP_WAIT: Duration = Duration::from_secs(2);

/// A window surface's front images and placement.
#[derive(Clone)]
pub struct SceneSurface {
    /// Surface ID: stable where the layout or the client fixed one, else a runtime ID; no
    /// two live surfaces share one.
    pub id: u64,
    /// Stacking position: creation order (later on top when depths tie).
    pub order: u64,
    /// Owning client's number.
    pub client_id: u64,
    /// Owning client's name.
    pub client: String,
    /// x, y (from the output space's top), width, height in pixels: where it shows (its
    /// destination region where one is set, else its placement at its image's size).
    pub rect: [i32; 4],
    /// Its image's width and height (the newest frame's).
    pub image: [i32; 2],
    /// Its visibility, opacity and regions.
    pub props: strata_protocol::properties::SurfaceProps,
    /// Depth layer: larger is farther.
    pub z: f32,
    /// The newest complete frame's colour (RGBA8, GL row order), as the compositor's device
    /// sees it.
    pub color: Option<wgpu::TextureView>,
    /// Its depth (depth aspect only), if the surface has depth.
    pub depth: Option<wgpu::TextureView>,
    /// The same frame on input routing's pick device, where it imported the buffer.
    pub pick: Option<Images>,
    /// The surface's buffers and what each is used for.
    pub buffers: Buffers,
    /// Its config has no alpha: its colour's alpha reads as 1 everywhere.
    pub opaque: bool,
    /// Frames swapped so far.
    pub frames: u64,
    /// The newest frame a composite has taken.
    pub shown: u64,
    /// Swap interval (EGL default 1).
    pub interval: i32,
    /// The normal per-surface lighting uses (default: facing the viewer).
    pub normal: [f32; 3],
    /// The refresh count at the surface's previous swap.
    pub(crate) last_swap_refresh: u64,
    /// A new size (width, height) that takes effect with the next frame presented.
    pub(crate) resized: Option<(i32, i32)>,
    /// Whether the compositor counts this surface's deadline misses.
    pub deadline: bool,
    /// Refreshes at which its newest frame was older than its interval allows.
    pub deadline_misses: u64,
    /// When its newest frame was published, and the refresh count then.
    pub(crate) presented: Option<(Instant, u64)>,
    /// Recent swap-to-shown latencies, microseconds, oldest first.
    pub(crate) latencies: std::collections::VecDeque<u32>,
    /// Its client's scheduling class.
    pub priority: Priority,
    /// Its declared projection (the layout's, else its EGL surface attributes'), by which the
    /// compositor compares its depth with other surfaces'; `None`: raw depth.
    pub projection: Option<strata_protocol::projection::Projection>,
    /// Its ID is a stable one (the layout's, the environment's or the application's).
    pub stable: bool,
}

impl SceneSurface {
    /// The row `stratad ctl list` shows (`layers`: the scene's).
    pub fn row(&self, layers: &Layers) -> SurfaceRow {
        let (shown_visible, shown_opacity) = self.shown_in(layers);
        SurfaceRow {
            stable: self.stable,
            image: self.image,
            props: self.props,
            shown_visible,
            shown_opacity,
            id: self.id,
            client_id: self.client_id,
            client: self.client.clone(),
            rect: self.rect,
            z: self.z,
            frames: self.frames,
            shown: self.shown,
            interval: self.interval,
            normal: self.normal,
            stream_bytes: 0,
            priority: self.priority,
            deadline: self.deadline,
            deadline_misses: self.deadline_misses,
            shown_latency_us: self.latency_summary(),
            projection: self.projection,
            // Filled in by `Scene::list`, which knows the clients.
            peer: Default::default(),
        }
    }

    /// p50, p99 and max of the recent swap-to-shown latencies, microseconds.
    pub(crate) fn latency_summary(&self) -> [u64; 3] {
        let mut v: Vec<u32> = self.latencies.iter().copied().collect();
        if v.is_empty() {
            return [0; 3];
        }
        v.sort_unstable();
        let at = |q: f64| u64::from(v[((v.len() - 1) as f64 * q).round() as usize]);
        [at(0.5), at(0.99), at(1.0)]
    }
}

/// The frames a composite took that were new, with when each was swapped.
#[derive(Debug, Default)]
pub struct Shown(pub(crate) Vec<((u64, u32), Instant)>);

pub(crate) struct State {
    pub(crate) surfaces: BTreeMap<(u64, u32), SceneSurface>,
    pub(crate) ids: Ids,
    pub(crate) damage: u64,
    /// What changed since the last composite, but for high-priority surfaces' new frames.
    pub(crate) region: Region,
    /// Where high-priority surfaces' new frames changed the output since the last composite.
    pub(crate) region_high: Region,
    pub(crate) refreshes: u64,
    /// A compositor thread consumes frames; without one, swaps never wait.
    pub(crate) root: bool,
    /// Swaps waiting for a refresh to pass.
    pub(crate) pacing_waiters: usize,
    pub(crate) lighting: Lighting,
    /// Named groups of surfaces.
    pub(crate) layers: Layers,
    /// Each connected client's class and whether its surfaces have deadlines.
    pub(crate) policies: HashMap<u64, (Priority, bool)>,
    /// Each connected client's process ID (0: unknown).
    pub(crate) peers: HashMap<u64, strata_protocol::control::Peer>,
    /// The configuration's surface entries, by stable ID.
    pub(crate) presets: HashMap<u64, SurfaceEntry>,
}

/// Every window surface of every client, and the lighting.
pub struct Scene {
    pub(crate) state: Mutex<State>,
    pub(crate) changed: Condvar,
    pub(crate) frames_in_flight: u64,
    /// Each connected client's count of command-stream bytes, by client id.
    pub(crate) streams: Mutex<HashMap<u64, Arc<AtomicU64>>>,
    /// The compositor's device, which reads the surfaces' buffers.
    pub(crate) compositor: std::sync::OnceLock<Arc<Gpu>>,
    /// Input routing's pick device, which imports the surfaces' buffers too (`scene::input`).
    pub(crate) pick_device: std::sync::OnceLock<Arc<Gpu>>,
    /// Events for `ctl watch`.
    pub(crate) events: tokio::sync::broadcast::Sender<strata_protocol::events::Event>,
}

impl Default for Scene {
    fn default() -> Self {
        Scene::new(2, Lighting::default())
    }
}

/// Which damage a composite redraws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// Only where high-priority surfaces' new frames changed the output: drawn first at each
    /// refresh, so that a large change elsewhere never delays them.
    High,
    /// Everything that changed.
    All,
}

/// What [`Scene::acquire`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Acquired {
    /// This buffer is now the back buffer.
    Buffer(usize),
    /// None is free, and the surface may have another.
    Grow,
    /// None became free in time.
    TimedOut,
    /// The surface is gone.
    Gone,
}

impl Scene {
    /// An empty scene allowing `frames_in_flight` (at least 1) unshown frames per surface.
    pub fn new(frames_in_flight: u32, lighting: Lighting) -> Scene {
        Scene {
            state: Mutex::new(State {
                surfaces: BTreeMap::new(),
                ids: Ids::default(),
                damage: 0,
                region: Region::Full,
                region_high: Region::None,
                refreshes: 0,
                root: false,
                pacing_waiters: 0,
                lighting,
                layers: Layers::new(),
                policies: HashMap::new(),
                peers: HashMap::new(),
                presets: HashMap::new(),
            }),
            changed: Condvar::new(),
            frames_in_flight: u64::from(frames_in_flight.max(1)),
            streams: Mutex::new(HashMap::new()),
            compositor: std::sync::OnceLock::new(),
            pick_device: std::sync::OnceLock::new(),
            events: tokio::sync::broadcast::channel(EVENT_BACKLOG).0,
        }
    }

    /// Names the compositor's device (once): clients' buffers are made readable on it.
    pub fn set_compositor(&self, gpu: Arc<Gpu>) {
        let _ = self.compositor.set(gpu);
    }

    /// The compositor's device, if one was named.
    pub fn compositor(&self) -> Option<Arc<Gpu>> {
        self.compositor.get().cloned()
    }

    /// The counter client `client`'s session adds its command-stream bytes to; `ctl list`
    /// reports it with the client's surfaces.
    pub fn stream_counter(&self, client: u64) -> Arc<AtomicU64> {
        let counter = Arc::new(AtomicU64::new(0));
        if let Ok(mut m) = self.streams.lock() {
            m.insert(client, counter.clone());
        }
        counter
    }

    /// Bytes of command stream client `client` has sent.
    pub fn stream_bytes(&self, client: u64) -> u64 {
        self.streams.lock().ok().and_then(|m| m.get(&client).map(|c| c.load(Ordering::Relaxed))).unwrap_or(0)
    }

    /// Drops a departed client's counter.
    pub fn forget_stream(&self, client: u64) {
        if let Ok(mut m) = self.streams.lock() {
            m.remove(&client);
        }
    }

    pub(crate) fn lock(&self) -> Option<MutexGuard<'_, State>> {
        self.state.lock().ok()
    }

    pub(crate) fn damaged(&self, g: MutexGuard<'_, State>, r: Region) {
        self.damaged_as(g, r, false);
    }

    /// Records damage `r`; `high`: a high-priority surface's new frame, which the compositor
    /// draws first (`Part::High`).
    pub(crate) fn damaged_as(&self, mut g: MutexGuard<'_, State>, r: Region, high: bool) {
        g.damage += 1;
        if high {
            g.region_high = g.region_high.union(r);
        } else {
            g.region = g.region.union(r);
        }
        drop(g);
        self.changed.notify_all();
    }

    /// Keeps the stable IDs the configuration names out of the runtime IDs; an ID with a
    /// claim (the entry's name and the credentials it requires) goes only to clients whose
    /// credentials the claim admits.
    pub fn reserve_ids(&self, ids: impl IntoIterator<Item = (u64, Option<(String, Requirement)>)>) {
        if let Some(mut g) = self.lock() {
            for (id, claim) in ids {
                g.ids.reserve(id, claim);
            }
        }
    }

    /// Registers a new window surface (visible once it has swapped) with the stable ID `asked`
    /// or a runtime one; returns its ID, or why the one asked for is refused.
    pub fn add(
        &self,
        client: u64,
        surface: u32,
        name: &str,
        rect: [i32; 4],
        z: f32,
        asked: Option<u64>,
    ) -> Result<u64, IdRefused> {
        let Some(mut guard) = self.lock() else { return Ok(0) };
        let g = &mut *guard;
        let surfaces = &g.surfaces;
        let holder = |id| surfaces.values().find(|s| s.id == id).map(|s| s.client.clone());
        let (id, order) = g.ids.assign(asked, g.peers.get(&client), holder)?;
        let (priority, deadline) = g.policies.get(&client).copied().unwrap_or_default();
        let pid = g.peers.get(&client).map_or(0, |p| p.pid);
        g.surfaces.insert(
            (client, surface),
            SceneSurface {
                id,
                order,
                client_id: client,
                client: name.to_string(),
                rect,
                image: [rect[2], rect[3]],
                props: Default::default(),
                z,
                color: None,
                depth: None,
                pick: None,
                buffers: Buffers::default(),
                opaque: false,
                frames: 0,
                shown: 0,
                interval: 1,
                normal: [0.0, 0.0, 1.0],
                last_swap_refresh: 0,
                resized: None,
                deadline,
                deadline_misses: 0,
                presented: None,
                latencies: std::collections::VecDeque::new(),
                priority,
                projection: None,
                stable: asked == Some(id),
            },
        );
        g.apply_preset(id);
        drop(guard);
        self.emit(strata_protocol::events::Event::SurfaceCreated { surface: id, client, name: name.to_string(), pid });
        Ok(id)
    }

    /// Sets client `client`'s scheduling class and whether its surfaces have deadlines, for
    /// its surfaces now and later.
    pub fn set_policy(&self, client: u64, priority: Priority, deadline: bool) {
        let Some(mut g) = self.lock() else { return };
        g.policies.insert(client, (priority, deadline));
        for s in g.surfaces.values_mut().filter(|s| s.client_id == client) {
            s.priority = priority;
            s.deadline = deadline;
        }
    }

    /// Sets a surface's declared projection (`None`: compared by raw depth).
    pub fn set_projection(
        &self,
        client: u64,
        surface: u32,
        projection: Option<strata_protocol::projection::Projection>,
    ) {
        let Some(mut g) = self.lock() else { return };
        if let Some(s) = g.surfaces.get_mut(&(client, surface)) {
            s.projection = projection;
            let r = Region::None.with(s.rect);
            self.damaged(g, r);
        }
    }

    /// Gives a surface a new size, which its rectangle takes with the next frame presented (its
    /// last frame stays on screen as it is until then); id, position, depth layer, normal,
    /// interval and pacing are kept.
    pub fn resize(&self, client: u64, surface: u32, width: i32, height: i32) {
        if let Some(mut g) = self.lock() {
            if let Some(s) = g.surfaces.get_mut(&(client, surface)) {
                s.resized = Some((width, height));
            }
        }
    }

    /// Sets a surface's swap interval (clamped to 0..=10).
    pub fn set_interval(&self, client: u64, surface: u32, interval: i32) {
        if let Some(mut g) = self.lock() {
            if let Some(s) = g.surfaces.get_mut(&(client, surface)) {
                s.interval = interval.clamp(0, 10);
            }
        }
    }

    /// Removes one surface, or with `surface == None` all of a client's.
    pub fn remove(&self, client: u64, surface: Option<u32>) {
        let Some(mut g) = self.lock() else { return };
        if surface.is_none() {
            g.policies.remove(&client);
        }
        let mut gone = Region::None;
        let mut destroyed = Vec::new();
        g.surfaces.retain(|k, s| {
            let keep = k.0 != client || surface.is_some_and(|id| id != k.1);
            if !keep {
                destroyed.push((s.id, s.client.clone()));
                if s.color.is_some() {
                    gone = gone.with(s.rect);
                }
            }
            keep
        });
        let pid = g.peers.get(&client).map_or(0, |p| p.pid);
        if gone != Region::None {
            self.damaged(g, gone);
        } else {
            drop(g);
        }
        for (id, name) in destroyed {
            self.emit(strata_protocol::events::Event::SurfaceDestroyed { surface: id, client, name, pid });
        }
    }

    /// The lighting in force.
    pub fn lighting(&self) -> Lighting {
        self.lock().map(|g| g.lighting).unwrap_or_default()
    }

    /// Applies a lighting change; returns the lighting now in force.
    pub fn change_lighting(&self, change: &LightChange) -> Lighting {
        let Some(mut g) = self.lock() else { return Lighting::default() };
        let new = change.apply(g.lighting);
        if new != g.lighting {
            g.lighting = new;
            self.damaged(g, Region::Full);
        }
        new
    }

    /// Every surface's row, in stacking order.
    pub fn rows(&self) -> Vec<SurfaceRow> {
        let mut surfaces: Vec<&SceneSurface> = Vec::new();
        let g = self.lock();
        if let Some(g) = &g {
            surfaces.extend(g.surfaces.values());
        }
        surfaces.sort_by_key(|s| s.order);
        let layers = g.as_ref().map(|g| g.layers.clone()).unwrap_or_default();
        let mut rows: Vec<SurfaceRow> = surfaces.into_iter().map(|s| s.row(&layers)).collect();
        if let Some(g) = &g {
            for r in &mut rows {
                r.peer = g.peers.get(&r.client_id).copied().unwrap_or_default();
            }
        }
        drop(g);
        if let Ok(m) = self.streams.lock() {
            for r in &mut rows {
                r.stream_bytes = m.get(&r.client_id).map_or(0, |c| c.load(Ordering::Relaxed));
            }
        }
        rows
    }

    /// The damage count: it moves whenever a new composite would differ.
    pub fn damage(&self) -> u64 {
        self.lock().map(|g| g.damage).unwrap_or(0)
    }

    /// Records that `r` must be composited again, as if it had changed.
    pub fn redraw(&self, r: Region) {
        if let Some(g) = self.lock() {
            self.damaged(g, r);
        }
    }

    /// The rectangles (x, y, width, height in the output space) of high-priority surfaces.
    pub fn high_rects(&self) -> Vec<[i32; 4]> {
        self.lock()
            .map(|g| g.surfaces.values().filter(|s| s.priority == Priority::High).map(|s| s.rect).collect())
            .unwrap_or_default()
    }
}

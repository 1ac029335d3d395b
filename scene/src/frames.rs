//! The life of a window surface's frames, from both sides, in one place (as Android's
//! BufferQueue owns a buffer from dequeue to release):
//! - the client's side, a [`Producer`] its executor holds for each window surface: buffers
//!   added ([`Producer::add_buffer`]), a swapped frame queued ([`Producer::queue`]: pending until
//!   its work completes on the client's device, then delivered and published as the newest
//!   frame), the next back buffer dequeued ([`Producer::dequeue`]);
//! - the compositor's side: each composite takes every surface's newest frame
//!   ([`Scene::compose`]) and releases it once complete ([`Scene::shown`], or over several
//!   refreshes [`Scene::hold`] and [`Scene::release`]); a screenshot reads one
//!   ([`Scene::read_frame`]).
//!
//! What each buffer is used for at any time is kept in `mailbox`; how its images reach the
//! compositor's device in `transfer`; the thread that waits for a frame's work in `waiter`.

use std::sync::Arc;
use std::time::Instant;

use strata_device::{Gpu, Lane};
use strata_protocol::control::{Lighting, Priority};

use crate::mailbox::{Buffers, Use, Views};
use crate::region::{damage_in_output, Region};
use crate::state::{Acquired, Part, Scene, SceneSurface, Shown, LATENCIES, MAX_SWAP_WAIT};
use crate::transfer::CopyPath;
use crate::waiter::FrameWaiter;

/// One window surface's frames as its client's executor drives them.
#[derive(Clone)]
pub struct Producer {
    scene: Arc<Scene>,
    client: u64,
    surface: u32,
}

/// A frame swapped into one buffer, for [`Producer::queue`].
pub struct Swapped<'a> {
    /// The buffer swapped (the back buffer until now).
    pub buffer: usize,
    /// Its colour has no alpha.
    pub opaque: bool,
    /// What changed since the previous frame (image GL coordinates; `None`: all of it).
    pub damage: Option<Vec<[i32; 4]>>,
    /// Where frames are copied through host memory: the buffer's copy path and its colour
    /// image on the client's device.
    pub copy: Option<(Arc<CopyPath>, &'a wgpu::Texture)>,
}

impl Scene {
    /// The client's side of the frames of its window surface `surface` (registered with
    /// [`Scene::add`]).
    pub fn producer(self: &Arc<Self>, client: u64, surface: u32) -> Producer {
        Producer { scene: self.clone(), client, surface }
    }
}

impl Producer {
    /// Adds a buffer the compositor sees as `views` (as the back buffer if `back`); its index,
    /// or `None` if the surface is gone.
    pub fn add_buffer(&self, views: Views, back: bool) -> Option<usize> {
        self.scene.add_buffer(self.client, self.surface, views, back)
    }

    /// The client swapped `frame.buffer`: it is pending until the work submitted so far on
    /// `gpu` (through `lane`) completes, then (copied to the compositor's device where frames
    /// are copied) published as the surface's newest frame. `waiter` waits meanwhile, so the
    /// caller never does.
    pub fn queue(&self, gpu: &Gpu, lane: &Lane, waiter: &mut FrameWaiter, frame: Swapped<'_>) {
        let Swapped { buffer, opaque, damage, copy } = frame;
        self.scene.submit(self.client, self.surface, buffer);
        let copy = copy.map(|(path, color)| {
            path.record(gpu, lane, color);
            path
        });
        // Marks the end of everything this frame submitted.
        let index = gpu.submit(lane, Vec::new());
        let comp = self.scene.compositor();
        let (scene, client, surface) = (self.scene.clone(), self.client, self.surface);
        waiter.after(
            index,
            Box::new(move || {
                if let (Some(c), Some(comp)) = (&copy, &comp) {
                    if !c.deliver(comp) {
                        tracing::warn!(surface, "a frame could not be read back, so it is not shown");
                        return;
                    }
                }
                scene.complete(client, surface, buffer, opaque, damage.as_deref());
            }),
        );
    }

    /// The buffer to draw the next frame into (see [`Acquired`]); the surface may have at most
    /// `most` buffers.
    pub fn dequeue(&self, most: usize) -> Acquired {
        self.scene.acquire(self.client, self.surface, most)
    }

    /// A buffer to draw into when none became free in time.
    pub fn take_any(&self) -> Option<usize> {
        self.scene.take_any(self.client, self.surface)
    }

    /// New buffers after a resize (the first is the back buffer), of `width`×`height`.
    pub fn replace_buffers(&self, width: i32, height: i32, views: Vec<Views>) {
        self.scene.resize(self.client, self.surface, width, height);
        self.scene.replace_buffers(self.client, self.surface, views);
    }

    /// The surface's swap interval.
    pub fn interval(&self) -> i32 {
        self.scene.interval(self.client, self.surface)
    }

    /// Blocks while the surface has too many frames in flight or its interval has not passed
    /// (`Scene::throttle`).
    pub fn throttle(&self) {
        self.scene.throttle(self.client, self.surface);
    }
}

impl Scene {
    /// Adds a buffer to a surface (as its back buffer if `back`); its index, or `None` if
    /// there is no such surface.
    fn add_buffer(&self, client: u64, surface: u32, views: Views, back: bool) -> Option<usize> {
        let mut g = self.lock()?;
        let s = g.surfaces.get_mut(&(client, surface))?;
        Some(s.buffers.add(views, back))
    }

    /// The client swapped back buffer `buffer`: it waits for its work to complete.
    fn submit(&self, client: u64, surface: u32, buffer: usize) {
        if let Some(mut g) = self.lock() {
            if let Some(s) = g.surfaces.get_mut(&(client, surface)) {
                s.buffers.submit(buffer);
            }
        }
    }

    /// Publishes buffer `buffer`, whose work has completed on the client's device, as the
    /// surface's newest frame; `opaque`: the colour buffer has no alpha; `damage`: the
    /// rectangles the client says changed since its previous frame (image GL coordinates;
    /// `None`: all of it).
    fn complete(&self, client: u64, surface: u32, buffer: usize, opaque: bool, damage: Option<&[[i32; 4]]>) {
        let Some(mut g) = self.lock() else { return };
        let refreshes = g.refreshes;
        let Some(s) = g.surfaces.get_mut(&(client, surface)) else { return };
        let Some(views) = s.buffers.complete(buffer) else { return };
        s.color = Some(views.shown.color);
        s.depth = views.shown.depth;
        s.pick = views.pick;
        s.opaque = opaque;
        s.frames += 1;
        s.presented = Some((Instant::now(), refreshes));
        let old = s.rect;
        let resized = s.resized.is_some();
        if let Some((w, h)) = s.resized.take() {
            s.image = [w, h];
            // A destination region keeps its size: the new image is scaled to it.
            if s.props.destination.is_none() {
                s.rect[2] = w;
                s.rect[3] = h;
            }
        }
        let r = match damage {
            // Stated damage of a frame of the same size: only that part changed.
            Some(d) if !resized => damage_in_output(s.rect, s.image, s.props.source, d),
            _ => Region::None.with(old).with(s.rect),
        };
        let high = s.priority == Priority::High;
        self.damaged_as(g, r, high);
    }

    /// Waits (at most two seconds) until no frame of client `client` waits to be published.
    pub fn wait_published(&self, client: u64) {
        let Some(mut g) = self.lock() else { return };
        let start = Instant::now();
        loop {
            let pending =
                g.surfaces.values().any(|s| s.client_id == client && s.buffers.uses().contains(&Use::Pending));
            let left = MAX_SWAP_WAIT.saturating_sub(start.elapsed());
            if !pending || left.is_zero() {
                return;
            }
            g = match self.changed.wait_timeout(g, left) {
                Ok((g, _)) => g,
                Err(_) => return,
            };
        }
    }

    /// A buffer of the surface to draw the next frame into: a free one that no composite
    /// reads, marked as the back buffer. When there is none, `Grow` if the surface has fewer
    /// than `most` buffers (the caller adds one), else waits for one (a frame completing, or
    /// the composite that reads one completing) for at most two seconds.
    fn acquire(&self, client: u64, surface: u32, most: usize) -> Acquired {
        let Some(mut g) = self.lock() else { return Acquired::Gone };
        let start = Instant::now();
        loop {
            let Some(s) = g.surfaces.get_mut(&(client, surface)) else { return Acquired::Gone };
            if let Some(i) = s.buffers.take_free() {
                return Acquired::Buffer(i);
            }
            if s.buffers.len() < most {
                return Acquired::Grow;
            }
            let left = MAX_SWAP_WAIT.saturating_sub(start.elapsed());
            if left.is_zero() {
                return Acquired::TimedOut;
            }
            g = match self.changed.wait_timeout(g, left) {
                Ok((g, _)) => g,
                Err(_) => return Acquired::Gone,
            };
        }
    }

    /// A surface's swap interval (1 if there is no such surface).
    fn interval(&self, client: u64, surface: u32) -> i32 {
        self.lock().and_then(|g| g.surfaces.get(&(client, surface)).map(|s| s.interval)).unwrap_or(1)
    }

    /// A buffer to draw into when none became free in time: the first that is not pending,
    /// even if a composite reads it or it is the newest frame.
    fn take_any(&self, client: u64, surface: u32) -> Option<usize> {
        let mut g = self.lock()?;
        g.surfaces.get_mut(&(client, surface))?.buffers.take_any()
    }

    /// Gives a surface new buffers (a resize; the first is the back buffer). Its newest frame
    /// stays shown until one of the new buffers completes.
    fn replace_buffers(&self, client: u64, surface: u32, views: Vec<Views>) {
        let Some(mut g) = self.lock() else { return };
        if let Some(s) = g.surfaces.get_mut(&(client, surface)) {
            s.buffers = Buffers::default();
            for (i, v) in views.into_iter().enumerate() {
                s.buffers.add(v, i == 0);
            }
        }
        drop(g);
        self.changed.notify_all();
    }

    /// The composite just taken (by [`Scene::compose`]) goes on over several refreshes: the
    /// frames it reads stay read until [`Scene::release`], whatever composites run meanwhile.
    pub fn hold(&self) {
        if let Some(mut g) = self.lock() {
            for s in g.surfaces.values_mut() {
                s.buffers.hold();
            }
        }
    }

    /// The composite held over several refreshes has completed: its frames may be drawn into
    /// again, and how long each waited from its swap is recorded.
    pub fn release(&self, frames: Shown) {
        self.done(frames, Buffers::release);
    }

    /// Runs `f` on window surface `id`'s newest complete frame (its colour view), which stays
    /// read meanwhile so that its client does not draw into it; `None` if there is no such
    /// surface or it has not swapped yet. The caller makes sure no composite is in flight
    /// (the compositor holds the same reading mark until its composite completes).
    pub fn read_frame<R>(&self, id: u64, f: impl FnOnce(&wgpu::TextureView) -> R) -> Option<R> {
        let (key, view) = {
            let mut g = self.lock()?;
            let (key, s) = g.surfaces.iter_mut().find(|(_, s)| s.id == id)?;
            let view = s.color.clone()?;
            s.buffers.read_latest();
            (*key, view)
        };
        let r = f(&view);
        if let Some(mut g) = self.lock() {
            if let Some(s) = g.surfaces.get_mut(&key) {
                s.buffers.done_reading();
            }
        }
        // The buffer may be drawn into again.
        self.changed.notify_all();
        Some(r)
    }

    /// Runs `f` on the surfaces shown (in stacking order; their layers' opacity multiplied
    /// into `props.opacity`), the lighting and the region changed since the last composite
    /// (`part` of it). The newest frame of each surface is marked as read
    /// until [`Scene::shown`], so no client draws into it meanwhile; `f` runs without the
    /// lock. Returns `f`'s result, the damage count it reflects, and the new frames it took
    /// (for [`Scene::shown`]).
    pub fn compose<R>(
        &self,
        part: Part,
        f: impl FnOnce(&[SceneSurface], &Lighting, Region) -> R,
    ) -> Option<(R, u64, Shown)> {
        let mut g = self.lock()?;
        let high = std::mem::replace(&mut g.region_high, Region::None);
        let region = match part {
            Part::High => high,
            Part::All => std::mem::replace(&mut g.region, Region::None).union(high),
        };
        let mut taken = Vec::new();
        for (key, s) in g.surfaces.iter_mut() {
            if part == Part::High && s.priority != Priority::High {
                s.buffers.read_latest();
                continue;
            }
            if let (true, Some((at, _))) = (s.frames > s.shown, s.presented) {
                taken.push((*key, at));
            }
            s.shown = s.frames;
            s.buffers.read_latest();
        }
        let mut v: Vec<SceneSurface> = g
            .surfaces
            .values()
            .filter_map(|s| {
                let (visible, opacity) = s.shown_in(&g.layers);
                let mut s = s.clone();
                s.props.opacity = opacity;
                visible.then_some(s)
            })
            .collect();
        v.sort_by_key(|s| s.order);
        let (damage, lighting) = (g.damage, g.lighting);
        drop(g);
        self.changed.notify_all();
        let r = f(&v, &lighting, region);
        Some((r, damage, Shown(taken)))
    }

    /// Records, once a composite has completed on the device, how long each frame it took
    /// waited from its swap.
    pub fn shown(&self, frames: Shown) {
        self.done(frames, Buffers::done_reading);
    }

    /// Ends a composite's reads (`end` on every surface's buffers) and records how long each
    /// frame it took waited from its swap.
    fn done(&self, frames: Shown, end: fn(&mut Buffers)) {
        let now = Instant::now();
        let Some(mut g) = self.lock() else { return };
        for s in g.surfaces.values_mut() {
            end(&mut s.buffers);
        }
        for (key, at) in frames.0 {
            if let Some(s) = g.surfaces.get_mut(&key) {
                if s.latencies.len() == LATENCIES {
                    s.latencies.pop_front();
                }
                s.latencies.push_back(now.duration_since(at).as_micros().min(u128::from(u32::MAX)) as u32);
            }
        }
        drop(g);
        // Buffers no composite reads any more may be drawn into again.
        self.changed.notify_all();
    }
}

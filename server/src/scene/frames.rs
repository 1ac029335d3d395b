//! The scene's side of each window surface's frames: its buffers as the compositor's device
//! sees them, the swap that submits one, the frame waiter's publication of it, and the search
//! for the next back buffer (see `mailbox` for what each buffer is used for).

use std::time::Instant;

use strata_protocol::control::Priority;

use super::{Acquired, Buffers, Region, Scene, Shown, Use, Views, MAX_SWAP_WAIT};

impl Scene {
    /// Adds a buffer to a surface (as its back buffer if `back`); its index, or `None` if
    /// there is no such surface.
    pub fn add_buffer(&self, client: u64, surface: u32, views: Views, back: bool) -> Option<usize> {
        let mut g = self.lock()?;
        let s = g.surfaces.get_mut(&(client, surface))?;
        Some(s.buffers.add(views, back))
    }

    /// The client swapped back buffer `buffer`: it waits for its work to complete.
    pub fn submit(&self, client: u64, surface: u32, buffer: usize) {
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
    pub fn complete(&self, client: u64, surface: u32, buffer: usize, opaque: bool, damage: Option<&[[i32; 4]]>) {
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
            Some(d) if !resized => super::region::damage_in_output(s.rect, s.image, s.props.source, d),
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
    pub fn acquire(&self, client: u64, surface: u32, most: usize) -> Acquired {
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
    pub fn interval(&self, client: u64, surface: u32) -> i32 {
        self.lock().and_then(|g| g.surfaces.get(&(client, surface)).map(|s| s.interval)).unwrap_or(1)
    }

    /// A buffer to draw into when none became free in time: the first that is not pending,
    /// even if a composite reads it or it is the newest frame.
    pub fn take_any(&self, client: u64, surface: u32) -> Option<usize> {
        let mut g = self.lock()?;
        g.surfaces.get_mut(&(client, surface))?.buffers.take_any()
    }

    /// Gives a surface new buffers (a resize; the first is the back buffer). Its newest frame
    /// stays shown until one of the new buffers completes.
    pub fn replace_buffers(&self, client: u64, surface: u32, views: Vec<Views>) {
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
}

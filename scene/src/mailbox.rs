//! A window surface's buffers as a mailbox between its client's device and the compositor's.
//!
//! Each buffer is an image pair (colour and depth) the client draws into on its own device and
//! the compositor reads on its own, through the same memory. A buffer is, at any time:
//! - `Back`: the client draws into it (framebuffer 0);
//! - `Pending`: swapped, its work not yet complete on the client's device;
//! - `Latest`: the newest complete frame, which every composite takes;
//! - `Free`: none of these.
//!
//! Besides, the buffer the composite in flight reads is marked as read until that composite
//! completes on the compositor's device, and so is the buffer an input pick reads texels of
//! (a mark of its own, so that a pick never waits for a composite). A client takes a new back
//! buffer only among the free buffers that nothing reads; a frame that completes replaces the latest at once, so a
//! frame the compositor never took is dropped, never queued (mailbox).

/// What a buffer is used for now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Use {
    /// Neither drawn into, nor waiting, nor the newest frame.
    Free,
    /// The client draws into it.
    Back,
    /// Swapped; its work is not yet complete on the client's device.
    Pending,
    /// The newest complete frame.
    Latest,
}

/// One buffer's images as one device reads them: colour, and depth (depth aspect only) if it
/// has one.
#[derive(Clone)]
pub struct Images {
    /// The colour (RGBA8, GL row order).
    pub color: wgpu::TextureView,
    /// The depth, if the buffer has one.
    pub depth: Option<wgpu::TextureView>,
}

/// One buffer as the daemon reads it: the compositor's views, and input routing's where its
/// pick device imported the same memory (`root::pick`).
#[derive(Clone)]
pub struct Views {
    /// The compositor's device's views.
    pub shown: Images,
    /// The pick device's views (`None`: picks read the buffer on the compositor's device).
    pub pick: Option<Images>,
}

impl Views {
    /// Views on the compositor's device only.
    pub fn shown(color: wgpu::TextureView, depth: Option<wgpu::TextureView>) -> Views {
        Views { shown: Images { color, depth }, pick: None }
    }
}

/// A window surface's buffers.
#[derive(Clone, Default)]
pub struct Buffers {
    views: Vec<Views>,
    uses: Vec<Use>,
    /// The buffer the composite in flight reads.
    reading: Option<usize>,
    /// The buffer a composite drawn band by band over several refreshes reads.
    held: Option<usize>,
    /// The buffer an input pick reads texels of.
    picking: Option<usize>,
}

impl Buffers {
    /// How many buffers the surface has.
    pub fn len(&self) -> usize {
        self.views.len()
    }

    /// Whether it has none yet.
    pub fn is_empty(&self) -> bool {
        self.views.is_empty()
    }

    /// Adds a buffer, in use as the back buffer if `back`; its index.
    pub fn add(&mut self, views: Views, back: bool) -> usize {
        self.views.push(views);
        self.uses.push(if back { Use::Back } else { Use::Free });
        self.views.len() - 1
    }

    /// Each buffer's use.
    pub fn uses(&self) -> &[Use] {
        &self.uses
    }

    /// The newest complete frame's buffer.
    pub fn latest(&self) -> Option<usize> {
        self.uses.iter().position(|u| *u == Use::Latest)
    }

    /// A free buffer no composite reads, now the back buffer.
    pub fn take_free(&mut self) -> Option<usize> {
        let i = (0..self.uses.len())
            .find(|&i| self.uses[i] == Use::Free && ![self.reading, self.held, self.picking].contains(&Some(i)))?;
        self.uses[i] = Use::Back;
        Some(i)
    }

    /// Any buffer that is not pending, now the back buffer (when none became free in time).
    pub fn take_any(&mut self) -> Option<usize> {
        let i = (0..self.uses.len()).find(|&i| matches!(self.uses[i], Use::Free | Use::Latest))?;
        self.uses[i] = Use::Back;
        Some(i)
    }

    /// The back buffer `i` was swapped: it waits for its work.
    pub fn submit(&mut self, i: usize) {
        if let Some(u) = self.uses.get_mut(i) {
            *u = Use::Pending;
        }
    }

    /// Buffer `i`'s work completed: it is the newest frame, and the previous newest is free
    /// (or, while a composite reads it, free once that completes). Its views, if it exists.
    pub fn complete(&mut self, i: usize) -> Option<Views> {
        if self.uses.get(i) != Some(&Use::Pending) {
            return None;
        }
        for u in self.uses.iter_mut().filter(|u| **u == Use::Latest) {
            *u = Use::Free;
        }
        self.uses[i] = Use::Latest;
        Some(self.views[i].clone())
    }

    /// A composite reads the newest frame until [`Buffers::done_reading`].
    pub fn read_latest(&mut self) {
        self.reading = self.latest();
    }

    /// The composite that read has completed.
    pub fn done_reading(&mut self) {
        self.reading = None;
    }

    /// An input pick reads texels of the newest frame until [`Buffers::done_picking`].
    pub fn pick_latest(&mut self) {
        self.picking = self.latest();
    }

    /// The pick's read has completed.
    pub fn done_picking(&mut self) {
        self.picking = None;
    }

    /// The buffer the composite in flight reads.
    pub fn reading(&self) -> Option<usize> {
        self.reading
    }

    /// The composite in flight goes on over several refreshes: what it reads stays read until
    /// [`Buffers::release`], whatever composites run meanwhile.
    pub fn hold(&mut self) {
        self.held = self.reading;
    }

    /// The composite drawn over several refreshes has completed.
    pub fn release(&mut self) {
        self.held = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn views() -> Vec<Views> {
        let Ok(gpu) = strata_device::Gpu::open() else { return Vec::new() };
        let tex = gpu.texture_2d("test", wgpu::TextureFormat::Rgba8Unorm, (1, 1), wgpu::TextureUsages::TEXTURE_BINDING);
        (0..4).map(|_| Views::shown(tex.create_view(&Default::default()), None)).collect()
    }

    /// `n` buffers (at most 4), the first the back buffer, each at its index; `None` without
    /// a device.
    fn buffers(n: usize) -> Option<Buffers> {
        let v = views();
        if v.is_empty() {
            return None;
        }
        let mut b = Buffers::default();
        for (i, views) in v.into_iter().take(n).enumerate() {
            assert_eq!(b.add(views, i == 0), i);
        }
        Some(b)
    }

    #[test]
    fn a_buffer_read_or_newest_is_never_handed_out() {
        let Some(mut b) = buffers(3) else { return };
        // Frame 1 in buffer 0 completes; the compositor reads it.
        b.submit(0);
        assert_eq!(b.take_free(), Some(1));
        assert!(b.complete(0).is_some());
        b.read_latest();
        assert_eq!(b.reading(), Some(0));
        // Frame 2 (buffer 1) completes while the composite still reads buffer 0: buffer 0 is
        // free but read, so the only buffer to hand out is 2.
        b.submit(1);
        assert_eq!(b.take_free(), Some(2));
        assert!(b.complete(1).is_some());
        assert_eq!(b.latest(), Some(1));
        b.submit(2);
        assert_eq!(b.take_free(), None, "buffer 0 is read, 1 newest, 2 pending");
        b.done_reading();
        assert_eq!(b.take_free(), Some(0));
        // A frame never composited is dropped when a newer one completes (mailbox).
        assert!(b.complete(2).is_some());
        assert_eq!(b.uses(), [Use::Back, Use::Free, Use::Latest]);
        // Completing a buffer that is not pending changes nothing.
        assert!(b.complete(1).is_none());
    }

    #[test]
    fn a_buffer_an_input_pick_reads_is_never_handed_out_whatever_composites_do() {
        let Some(mut b) = buffers(2) else { return };
        b.submit(0);
        assert!(b.complete(0).is_some());
        // A pick and a composite read buffer 0 at once; the composite completes first.
        b.pick_latest();
        b.read_latest();
        b.done_reading();
        assert_eq!(b.take_free(), Some(1));
        b.submit(1);
        assert!(b.complete(1).is_some());
        assert_eq!(b.take_free(), None, "buffer 0 is picked, 1 newest");
        b.done_picking();
        assert_eq!(b.take_free(), Some(0));
    }

    #[test]
    fn a_buffer_held_over_refreshes_stays_read_through_other_composites() {
        let Some(mut b) = buffers(3) else { return };
        b.submit(0);
        assert!(b.complete(0).is_some());
        // A composite drawn over several refreshes reads buffer 0.
        b.read_latest();
        b.hold();
        b.done_reading();
        // Frame 2 completes; a composite of another part reads it and completes.
        assert_eq!(b.take_free(), Some(1));
        b.submit(1);
        assert!(b.complete(1).is_some());
        b.read_latest();
        b.done_reading();
        // Buffer 0 is free but still held: only buffer 2 can be handed out.
        assert_eq!(b.take_free(), Some(2));
        b.submit(2);
        assert_eq!(b.take_free(), None, "buffer 0 held, 1 newest, 2 pending");
        b.release();
        assert_eq!(b.take_free(), Some(0));
    }
}

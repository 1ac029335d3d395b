//! A window surface's buffers on the executor's side: the render target each one is, how its
//! frames are copied where they are, its memory, and its age (`EGL_EXT_buffer_age`). What each
//! buffer is used for, and its frames' life, belong to the scene (`strata_scene::Producer`).

use std::sync::Arc;

use strata_device::account::Reservation;
use strata_scene::transfer::{CopyPath, Transfer};

use crate::render::Target;

/// One buffer of a window surface.
pub(crate) struct Buffer {
    /// What the client draws into.
    pub(crate) target: Target,
    /// How frames drawn into it are copied, for `Transfer::Copy`.
    pub(crate) copy: Option<Arc<CopyPath>>,
    /// Its memory, held against the client's quota.
    pub(crate) _reserved: Reservation,
    /// The surface's swap count when this buffer was last swapped (`EGL_EXT_buffer_age`);
    /// `None` before its first frame.
    pub(crate) swapped_at: Option<u64>,
}

/// A window surface's buffers; `target` of the surface is the back one's.
pub(crate) struct Window {
    /// The buffers, by the index the scene knows them by.
    pub(crate) buffers: Vec<Buffer>,
    /// The back buffer.
    pub(crate) back: usize,
    /// How its frames reach the compositor.
    pub(crate) transfer: Transfer,
    /// Frames swapped so far.
    pub(crate) swaps: u64,
}

impl Window {
    /// Records that buffer `i` was swapped.
    pub(crate) fn swapped(&mut self, i: usize) {
        if let Some(b) = self.buffers.get_mut(i) {
            b.swapped_at = Some(self.swaps);
        }
        self.swaps += 1;
    }

    /// `EGL_BUFFER_AGE_EXT` of the back buffer: how many frames ago its contents were the
    /// newest (1: the previous frame's), 0 for a buffer that holds no frame yet.
    pub(crate) fn age(&self) -> u64 {
        self.buffers.get(self.back).and_then(|b| b.swapped_at).map_or(0, |at| self.swaps - at)
    }
}

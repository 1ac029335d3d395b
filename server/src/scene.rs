//! What the compositor sees: every client's window surfaces with their placement and the
//! front images of their last completed frame. Executors publish on swap; the compositor
//! reads under the same lock, so a frame is either wholly visible or not at all.

use std::collections::BTreeMap;
use std::sync::Mutex;

/// A window surface's front images and placement.
#[derive(Clone)]
pub struct SceneSurface {
    /// Owning client's name.
    pub client: String,
    /// x, y (from the output's top), width, height in output pixels.
    pub rect: [i32; 4],
    /// Depth layer: larger is farther.
    pub z: f32,
    /// Front colour (RGBA8, GL row order).
    pub color: Option<wgpu::TextureView>,
    /// Front depth (depth aspect only), if the surface has depth.
    pub depth: Option<wgpu::TextureView>,
    /// Stacking order: creation order, later on top when depths tie.
    pub stack: u64,
    /// Frames swapped so far.
    pub frames: u64,
}

/// The surfaces by (client, surface handle), and the last stacking number handed out.
type Surfaces = (BTreeMap<(u64, u32), SceneSurface>, u64);

/// Every window surface of every client.
#[derive(Default)]
pub struct Scene {
    inner: Mutex<Surfaces>,
}

impl Scene {
    /// Registers a new window surface (visible once it has swapped).
    pub fn add(&self, client: u64, surface: u32, name: &str, rect: [i32; 4], z: f32) {
        if let Ok(mut g) = self.inner.lock() {
            g.1 += 1;
            let stack = g.1;
            g.0.insert(
                (client, surface),
                SceneSurface { client: name.to_string(), rect, z, color: None, depth: None, stack, frames: 0 },
            );
        }
    }

    /// Publishes a completed frame's front images.
    pub fn present(&self, client: u64, surface: u32, color: wgpu::TextureView, depth: Option<wgpu::TextureView>) {
        if let Ok(mut g) = self.inner.lock() {
            if let Some(s) = g.0.get_mut(&(client, surface)) {
                s.color = Some(color);
                s.depth = depth;
                s.frames += 1;
            }
        }
    }

    /// Removes one surface, or with `surface == None` all of a client's.
    pub fn remove(&self, client: u64, surface: Option<u32>) {
        if let Ok(mut g) = self.inner.lock() {
            g.0.retain(|k, _| k.0 != client || surface.is_some_and(|s| s != k.1));
        }
    }

    /// Runs `f` on the surfaces in stacking order while holding the lock, so no swap can
    /// interleave with what `f` submits.
    pub fn with<R>(&self, f: impl FnOnce(&[SceneSurface]) -> R) -> Option<R> {
        let g = self.inner.lock().ok()?;
        let mut v: Vec<SceneSurface> = g.0.values().cloned().collect();
        v.sort_by_key(|s| s.stack);
        Some(f(&v))
    }
}

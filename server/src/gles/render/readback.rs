//! Readback, depth uploads, and waiting for the GPU. Reads and waits first submit the open
//! pass; a depth upload runs in a `[Flush]` command, after it.

use super::super::dispatch::Flushed;
use super::{Renderer, Target};

impl Renderer {
    /// Reads `[x, y, w, h]` of the target's colour image as tightly packed RGBA8 rows, bottom
    /// row first (GL order, which is also memory order here).
    pub fn read_rgba(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.flush();
        let (tex, _) = target.color.as_ref()?;
        self.gpu.read_rgba8(tex, rect)
    }

    /// Waits until the GPU has finished everything this client submitted.
    pub fn finish(&mut self) {
        self.flush();
        self.lane.wait_idle(&self.gpu);
    }

    /// Writes depth values (normalised, rows bottom-up) and optionally stencil values into the
    /// rectangle `[x, y, w, h]` of a `size` depth or depth-stencil texture.
    pub fn upload_depth(
        &mut self,
        _: &Flushed,
        tex: &wgpu::Texture,
        size: (u32, u32),
        rect: [u32; 4],
        depths: &[f32],
        stencil: Option<&[u8]>,
    ) {
        self.gpu.write_depth_region(tex, size, rect, depths, stencil);
    }
}

//! Reading a texture's texels, or a buffer's bytes, back to host memory, waiting for the device.

use crate::gpu::Gpu;
use crate::lane::Lane;

impl Gpu {
    /// Reads `[x, y, w, h]` of an RGBA8 texture as tightly packed rows in memory order.
    pub fn read_rgba8(&self, tex: &wgpu::Texture, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.read_texels(&self.lane, tex, (0, 0), rect, wgpu::TextureAspect::All, 4)
    }

    /// Reads `[x, y, w, h]` of `aspect` of array layer `layer`, mip level `level`, of a texture
    /// whose texels there take `bpp` bytes (the stencil aspect: 1), as tightly packed rows in
    /// memory order; the copy is `lane`'s work.
    pub fn read_texels(
        &self,
        lane: &Lane,
        tex: &wgpu::Texture,
        (layer, level): (u32, u32),
        rect: [u32; 4],
        aspect: wgpu::TextureAspect,
        bpp: u32,
    ) -> Option<Vec<u8>> {
        let [x, y, w, h] = rect;
        if w == 0 || h == 0 {
            return Some(Vec::new());
        }
        let row = (w * bpp).div_ceil(256) * 256;
        let buf = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(row * h),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: tex,
                mip_level: level,
                origin: wgpu::Origin3d { x, y, z: layer },
                aspect,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buf,
                layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row), rows_per_image: None },
            },
            wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
        );
        self.submit(lane, vec![enc.finish()]);
        let slice = buf.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        let _ = self.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
        rx.recv().ok()?.ok()?;
        let data = slice.get_mapped_range().ok()?;
        let mut out = Vec::with_capacity((w * h * bpp) as usize);
        for r in 0..h {
            let start = (r * row) as usize;
            out.extend_from_slice(&data[start..start + (w * bpp) as usize]);
        }
        drop(data);
        buf.unmap();
        Some(out)
    }

    /// Reads `len` bytes of `buffer` from `offset` (both multiples of 4), after `lane`'s work
    /// so far: what the device wrote there.
    pub fn read_buffer(&self, lane: &Lane, buffer: &wgpu::Buffer, offset: u64, len: u64) -> Option<Vec<u8>> {
        if len == 0 {
            return Some(Vec::new());
        }
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("buffer readback"),
            size: len,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(buffer, offset, &staging, 0, len);
        self.submit(lane, vec![enc.finish()]);
        let slice = staging.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        let _ = self.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
        rx.recv().ok()?.ok()?;
        let data = slice.get_mapped_range().ok()?.to_vec();
        staging.unmap();
        Some(data)
    }
}

//! How a window surface's buffers reach the compositor's device: images shared between the two
//! devices, or a copy of each frame through host memory (`mailbox` keeps what each buffer is
//! used for, `frames` its life).
//!
//! How a buffer reaches the compositor ([`Transfer`]):
//! - `Same`: the client draws on the compositor's device (`stratad serve --devices shared`, or
//!   no compositor), which samples the client's own images;
//! - `Export`: the images live in memory the client's device exports and the compositor's
//!   imports, so both read and write the same bytes and nothing is copied;
//! - `Copy`: where the driver cannot share images between devices, each frame is copied: its
//!   colour, and its depth read as 32-bit floats, into a buffer the client's device maps, then
//!   into the compositor's own images.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use tracing::{info, warn};

use strata_device::{Gpu, Lane, ShareError};

use crate::depth::Depth;
use crate::mailbox::{Images, Views};

/// The colour format of every window surface's images (RGBA8, GL row order).
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// How window surfaces' frames reach the compositor (`stratad serve --frame-transfer`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum TransferMode {
    /// Share the images' memory where both devices can (`VK_KHR_external_memory_fd`), else
    /// copy each frame through host memory.
    #[default]
    Auto,
    /// Always copy each frame through host memory (to measure it, or to avoid a driver's
    /// sharing).
    Copy,
}

/// How one surface's frames reach the compositor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Transfer {
    /// One device for both: the compositor samples the client's images.
    Same,
    /// The same memory, exported by the client's device and imported by the compositor's.
    Export,
    /// Copied through host memory at every swap.
    Copy,
}

/// Whether "frames go through host memory" was logged (once per daemon).
static COPY_LOGGED: AtomicBool = AtomicBool::new(false);

/// How frames of `depth` surfaces travel from `client` to `compositor`.
pub fn transfer(
    client: &Arc<Gpu>,
    compositor: Option<&Arc<Gpu>>,
    depth: Option<wgpu::TextureFormat>,
    mode: TransferMode,
) -> Transfer {
    let Some(comp) = compositor.filter(|c| !Arc::ptr_eq(c, client)) else { return Transfer::Same };
    let why = match mode {
        TransferMode::Copy => "--frame-transfer copy".to_string(),
        TransferMode::Auto => {
            let shared = client.exportable(comp, COLOR_FORMAT).and_then(|()| match depth {
                Some(f) => client.exportable(comp, f),
                None => Ok(()),
            });
            match shared {
                Ok(()) => return Transfer::Export,
                Err(e) => e.to_string(),
            }
        }
    };
    if !COPY_LOGGED.swap(true, Ordering::Relaxed) {
        info!(driver = %client.info.driver, "window surfaces' frames are copied through host memory: {why}");
    }
    Transfer::Copy
}

/// A buffer's copy through host memory: a readback buffer on the client's device (colour
/// rows, then depth rows, each padded to 256 bytes), the float image its depth is read into,
/// and the compositor's own images.
pub struct CopyPath {
    readback: wgpu::Buffer,
    depth_float: Option<(wgpu::Texture, wgpu::TextureView, wgpu::BindGroup)>,
    color: wgpu::Texture,
    depth: Option<wgpu::Texture>,
    size: (u32, u32),
    mapped: Arc<AtomicBool>,
}

/// Bytes of one row of `width` 4-byte texels, padded as buffer copies require.
fn padded_row(width: u32) -> u32 {
    (width * 4).div_ceil(256) * 256
}

/// A depth-aspect view, as the compositor samples depth.
pub fn depth_view(t: &wgpu::Texture) -> wgpu::TextureView {
    t.create_view(&wgpu::TextureViewDescriptor { aspect: wgpu::TextureAspect::DepthOnly, ..Default::default() })
}

impl CopyPath {
    /// The copy path of a buffer of `size` whose depth the client's `depth` view shows; the
    /// compositor's images and their views.
    pub fn new(client: &Gpu, comp: &Gpu, size: (u32, u32), depth: Option<&wgpu::TextureView>) -> (CopyPath, Views) {
        let row = u64::from(padded_row(size.0));
        let rows = u64::from(size.1) * if depth.is_some() { 2 } else { 1 };
        let readback = client.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame readback"),
            size: row * rows,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let depth_float = depth.map(|view| {
            let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
            let t = client.texture_2d("frame depth as float", wgpu::TextureFormat::R32Float, size, usage);
            let v = t.create_view(&Default::default());
            let (bgl, _) = Depth::of(client).reader();
            let group = client.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("frame depth read"),
                layout: &bgl,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(view) }],
            });
            (t, v, group)
        });
        let color = comp.texture_2d(
            "frame colour copy",
            COLOR_FORMAT,
            size,
            wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        );
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let depth_tex =
            depth.map(|_| comp.texture_2d("frame depth copy", wgpu::TextureFormat::Depth32Float, size, usage));
        let views = Views::shown(color.create_view(&Default::default()), depth_tex.as_ref().map(depth_view));
        let path = CopyPath { readback, depth_float, color, depth: depth_tex, size, mapped: Arc::default() };
        (path, views)
    }

    /// Bytes of host memory and images it adds: readback, float depth, the compositor's copies.
    pub fn bytes(size: (u32, u32), depth: bool) -> u64 {
        let px = u64::from(size.0) * u64::from(size.1);
        px * if depth { 4 * 5 } else { 4 * 2 }
    }

    /// Records the copies of the buffer's `color` image (and its depth) into the readback
    /// buffer and submits them on the client's device through `lane`, then asks for the buffer
    /// to be mapped once they complete.
    pub(crate) fn record(&self, gpu: &Gpu, lane: &Lane, color: &wgpu::Texture) {
        let (w, h) = self.size;
        let row = padded_row(w);
        let extent = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
        let mut enc = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame copy") });
        let copy = |enc: &mut wgpu::CommandEncoder, texture: &wgpu::Texture, offset: u64| {
            enc.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &self.readback,
                    layout: wgpu::TexelCopyBufferLayout { offset, bytes_per_row: Some(row), rows_per_image: None },
                },
                extent,
            );
        };
        copy(&mut enc, color, 0);
        if let Some((t, v, group)) = &self.depth_float {
            let (_, pipeline) = Depth::of(gpu).reader();
            strata_device::fullscreen_pass(&mut enc, "frame depth read", v, &pipeline, group);
            copy(&mut enc, t, u64::from(row) * u64::from(h));
        }
        gpu.submit(lane, vec![enc.finish()]);
        let mapped = self.mapped.clone();
        mapped.store(false, Ordering::Release);
        self.readback.slice(..).map_async(wgpu::MapMode::Read, move |r| mapped.store(r.is_ok(), Ordering::Release));
    }

    /// Once the copies have completed (and the client's device was polled): writes the frame
    /// into the compositor's images. Returns whether it could.
    pub(crate) fn deliver(&self, comp: &Gpu) -> bool {
        if !self.mapped.load(Ordering::Acquire) {
            return false;
        }
        let (w, h) = self.size;
        let row = padded_row(w) as usize;
        {
            let Ok(data) = self.readback.slice(..).get_mapped_range() else { return false };
            comp.write_texture(
                self.color.as_image_copy(),
                &data[..row * h as usize],
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(row as u32), rows_per_image: None },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
            if let Some(depth) = &self.depth {
                let mut values = Vec::with_capacity((w * h) as usize);
                for r in 0..h as usize {
                    let start = row * (h as usize + r);
                    values.extend_from_slice(bytemuck::cast_slice::<u8, f32>(&data[start..start + 4 * w as usize]));
                }
                Depth::of(comp).write(depth, w, h, &values);
            }
        }
        self.readback.unmap();
        self.mapped.store(false, Ordering::Release);
        true
    }
}

/// The buffer's images on the client's device, made exportable when frames are shared: the
/// colour and depth textures, and the compositor's views of the same memory. Where `pick`
/// (input routing's device) imports it too, its views of it; a pick device that cannot only
/// leaves picks to the compositor's device.
pub fn shared_images(
    client: &Gpu,
    comp: &Gpu,
    pick: Option<&Gpu>,
    size: (u32, u32),
    depth: Option<wgpu::TextureFormat>,
) -> Result<((wgpu::Texture, Option<wgpu::Texture>), Views), ShareError> {
    let (color, memory) = client.create_exported("surface colour", COLOR_FORMAT, size)?;
    let mut for_pick = pick.and_then(|p| Some((p, vec![(COLOR_FORMAT, memory.try_clone().ok()?)])));
    let color_in = comp.import("surface colour (imported)", COLOR_FORMAT, size, memory)?;
    let (depth, depth_in) = match depth {
        Some(f) => {
            let (d, memory) = client.create_exported("surface depth", f, size)?;
            match (memory.try_clone(), for_pick.as_mut()) {
                (Ok(m), Some((_, v))) => v.push((f, m)),
                _ => for_pick = None,
            }
            (Some(d), Some(comp.import("surface depth (imported)", f, size, memory)?))
        }
        None => (None, None),
    };
    let pick = for_pick.and_then(|(gpu, memories)| {
        let mut textures = Vec::new();
        for (f, m) in memories {
            match gpu.import("surface (imported for input)", f, size, m) {
                Ok(t) => textures.push(t),
                Err(e) => {
                    warn!("input routing's device could not import a window surface's images ({e}); its picks wait for the compositor's device");
                    return None;
                }
            }
        }
        let mut t = textures.iter();
        let color = t.next()?.create_view(&Default::default());
        Some(Images { color, depth: t.next().map(depth_view) })
    });
    let shown = Images { color: color_in.create_view(&Default::default()), depth: depth_in.as_ref().map(depth_view) };
    Ok(((color, depth), Views { shown, pick }))
}

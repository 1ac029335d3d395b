//! A GPU device: the compositor's, and one per client (each on an instance of its own). A
//! client's window surfaces live in memory its device exports and the compositor's imports
//! (`share`); `open` opens a device at a class's priority.

mod open;
mod share;

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

pub use open::{
    keep_freed_memory, nice_for, set_thread_class, set_thread_idle, set_thread_nice, set_thread_realtime,
    set_thread_slice, settle_environment, slice_for, DeviceOptions, HIGH_SLICE, MMAP_THRESHOLD, RASTERIZER_THREADS,
    TRIM_THRESHOLD,
};
pub use share::{shared_usage, DeviceIdentity, Exported, ShareError};

/// Why no GPU device could be opened.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter matched.
    #[error("no Vulkan adapter found ({0}); on Debian install mesa-vulkan-drivers and libvulkan1")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("opening the device failed: {0}")]
    Device(#[from] wgpu::RequestDeviceError),
    /// The device could not be opened with a queue global priority.
    #[error("opening the device with a queue global priority failed")]
    Priority,
}

/// Optional device features the executor uses where the adapter has them: linear filtering
/// of RGBA32F (`OES_texture_float_linear`), and BC, ETC2 and ASTC block formats (compressed textures
/// sampled natively instead of decoded on upload), and Depth32FloatStencil8 (`--depth-format
/// 32float` for configs with stencil), timestamps (the composite's own device time), and
/// depth clip control (`EXT_depth_clamp`), and border clamping (`EXT_texture_border_clamp`).
pub(crate) const OPTIONAL_FEATURES: wgpu::Features = wgpu::Features::FLOAT32_FILTERABLE
    .union(wgpu::Features::TIMESTAMP_QUERY)
    .union(wgpu::Features::DEPTH32FLOAT_STENCIL8)
    .union(wgpu::Features::TEXTURE_COMPRESSION_BC)
    .union(wgpu::Features::TEXTURE_COMPRESSION_ETC2)
    .union(wgpu::Features::TEXTURE_COMPRESSION_ASTC)
    .union(wgpu::Features::DEPTH_CLIP_CONTROL)
    .union(wgpu::Features::DUAL_SOURCE_BLENDING)
    .union(wgpu::Features::ADDRESS_MODE_CLAMP_TO_BORDER);

/// The pipelines of `write_depth`, one per depth format.
type DepthWriters = HashMap<wgpu::TextureFormat, (wgpu::BindGroupLayout, wgpu::RenderPipeline)>;

/// A device and its queue: the compositor's, or one client's.
pub struct Gpu {
    /// Lazily built pipelines for `write_depth`.
    depth_writers: Mutex<DepthWriters>,
    /// The optional features the device was opened with.
    pub features: wgpu::Features,
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// Adapter name, driver and backend, for logs and `GL_RENDERER`.
    pub info: wgpu::AdapterInfo,
    /// The device's limits.
    pub limits: wgpu::Limits,
    /// The instance, for window surfaces.
    pub instance: wgpu::Instance,
    /// The adapter, for window surfaces' capabilities.
    pub adapter: wgpu::Adapter,
    /// What every client's GLES renderer shares, built by the first one.
    pub gles: std::sync::OnceLock<Arc<crate::gles::RendererFixed>>,
    /// The queue's global priority the driver granted (`None`: not offered or not asked).
    pub global_priority: Option<&'static str>,
    /// Set when the device is lost (a fault, a reset, or destroyed): nothing more runs on it.
    pub lost: Arc<std::sync::atomic::AtomicBool>,
    /// The pipeline that reads a depth image as floats (`depth_read.wgsl`), built on first use.
    depth_reader: std::sync::OnceLock<(wgpu::BindGroupLayout, wgpu::RenderPipeline)>,
    /// Frame completion time the frame waiter measured (for devices that are not CPU
    /// rasterizers), microseconds.
    pub(crate) waited_us: std::sync::atomic::AtomicU64,
    /// The threads the driver started for this device (lavapipe's queue and rasterizer
    /// threads), which inherited the nice value of the thread that opened it.
    pub threads: Vec<i32>,
}

impl std::fmt::Debug for Gpu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Gpu").field("adapter", &self.info.name).field("threads", &self.threads).finish()
    }
}

impl Gpu {
    /// Whether the device blends with a fragment's second colour (`GL_EXT_blend_func_extended`).
    pub fn dual_source(&self) -> bool {
        self.features.contains(wgpu::Features::DUAL_SOURCE_BLENDING)
    }

    /// Whether the device was lost.
    pub fn is_lost(&self) -> bool {
        self.lost.load(std::sync::atomic::Ordering::Acquire)
    }

    /// The pipeline drawing a full-screen triangle that writes the depth image bound at 0
    /// into an R32Float target, and its bind group layout.
    pub fn depth_reader(&self) -> (wgpu::BindGroupLayout, wgpu::RenderPipeline) {
        self.depth_reader
            .get_or_init(|| {
                self.pipeline(
                    "depth read",
                    wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/depth_read.wgsl").into()),
                    &[texture_entry(0, wgpu::TextureSampleType::Depth)],
                    &[Some(wgpu::ColorTargetState {
                        format: wgpu::TextureFormat::R32Float,
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                    None,
                    VertexInput::None,
                )
            })
            .clone()
    }

    /// How long the device has been busy: on a CPU rasterizer (lavapipe) the CPU time of its
    /// driver threads, which is exactly its work; on a GPU, the time from each frame's last
    /// submission to its completion, as the frame waiter saw it.
    pub fn busy(&self) -> std::time::Duration {
        if self.info.device_type == wgpu::DeviceType::Cpu {
            self.threads_cpu_time()
        } else {
            std::time::Duration::from_micros(self.waited_us.load(std::sync::atomic::Ordering::Relaxed))
        }
    }

    /// Sets the nice value of the driver's threads of this device (a client moved to another
    /// class); raising needs `CAP_SYS_NICE`, without which they stay where they are.
    pub fn renice(&self, nice: i32) {
        for &tid in &self.threads {
            #[cfg(target_os = "linux")]
            // SAFETY: setpriority on one of this process's threads only sets its nice value.
            unsafe {
                libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, nice);
            }
        }
    }

    /// CPU time the driver's threads of this device have used (on a CPU rasterizer such as
    /// lavapipe, the time the device was busy), read from `/proc/self/task/*/stat`.
    pub fn threads_cpu_time(&self) -> std::time::Duration {
        // SAFETY: sysconf only reads a constant.
        let ticks = unsafe { libc::sysconf(libc::_SC_CLK_TCK) }.max(1) as f64;
        let total: u64 = self
            .threads
            .iter()
            .filter_map(|t| {
                let stat = std::fs::read_to_string(format!("/proc/self/task/{t}/stat")).ok()?;
                // Fields after the command name (which may hold spaces) start at its ')'.
                let rest = stat.rsplit_once(')')?.1;
                let f: Vec<&str> = rest.split_whitespace().collect();
                Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
            })
            .sum();
        std::time::Duration::from_secs_f64(total as f64 / ticks)
    }
}

/// A fragment-stage binding of a 2D texture read with `textureLoad` (`sample_type`: a
/// non-filterable float or a depth texture).
pub fn texture_entry(binding: u32, sample_type: wgpu::TextureSampleType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}

/// A fragment-stage binding of a uniform buffer.
pub fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Records one full-screen triangle drawn with `pipeline` and `group` into `target`, which keeps
/// what it held elsewhere (loaded and stored).
pub fn fullscreen_pass(
    enc: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
) {
    fullscreen_pass_at(enc, label, (target, None), pipeline, group);
}

/// [`fullscreen_pass`] into slice `slice` of a 3D `target` view, drawn as instance `slice`
/// (the shader's way of knowing it); `None`: a 2D view, instance 0.
pub fn fullscreen_pass_at(
    enc: &mut wgpu::CommandEncoder,
    label: &str,
    (target, slice): (&wgpu::TextureView, Option<u32>),
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
) {
    let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: slice,
            resolve_target: None,
            ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    rp.set_pipeline(pipeline);
    rp.set_bind_group(0, group, &[]);
    let instance = slice.unwrap_or(0);
    rp.draw(0..3, instance..instance + 1);
}

/// Non-filterable float textures, for [`texture_entry`].
pub const UNFILTERED: wgpu::TextureSampleType = wgpu::TextureSampleType::Float { filterable: false };

/// The vertex input of a [`Gpu::pipeline`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VertexInput {
    /// None: the vertex shader makes its positions from the vertex index.
    None,
    /// One `vec4<f32>` per instance at location 0 (a rectangle), drawn as a four-vertex strip.
    InstanceRect,
}

/// The view formats of surface colour images: an sRGB view, which `EGL_KHR_gl_colorspace`
/// surfaces draw through.
pub const SRGB_VIEW: [wgpu::TextureFormat; 1] = [wgpu::TextureFormat::Rgba8UnormSrgb];

/// The descriptor of a single-level, single-sample 2D texture of `format` and `(width, height)`
/// for `usage` (what [`Gpu::texture_2d`] creates, and what shared images are described as).
pub fn descriptor_2d(
    label: &str,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    usage: wgpu::TextureUsages,
) -> wgpu::TextureDescriptor<'_> {
    wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats: &[],
    }
}

impl Gpu {
    /// A single-level, single-sample 2D texture of `format` and `(width, height)` for `usage`.
    pub fn texture_2d(
        &self,
        label: &str,
        format: wgpu::TextureFormat,
        (width, height): (u32, u32),
        usage: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.device.create_texture(&descriptor_2d(label, format, (width, height), usage))
    }

    /// A pipeline with the `vs` and `fs` entry points of `source`, one bind group of `entries`,
    /// `vertex` input (none: one full-screen triangle from the vertex index), into `targets`
    /// (and a depth attachment if `depth`): the one pipeline builder behind full-screen passes
    /// and the compositor's cells.
    pub fn pipeline(
        &self,
        label: &str,
        source: wgpu::ShaderSource<'_>,
        entries: &[wgpu::BindGroupLayoutEntry],
        targets: &[Option<wgpu::ColorTargetState>],
        depth: Option<wgpu::DepthStencilState>,
        vertex: VertexInput,
    ) -> (wgpu::BindGroupLayout, wgpu::RenderPipeline) {
        let d = &self.device;
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor { label: Some(label), source });
        let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries });
        let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        // One vec4 per instance (a rectangle), drawn as a four-vertex strip.
        let rect = [wgpu::VertexAttribute { format: wgpu::VertexFormat::Float32x4, offset: 0, shader_location: 0 }];
        let (buffers, primitive) = match vertex {
            VertexInput::None => (vec![], Default::default()),
            VertexInput::InstanceRect => (
                vec![Some(wgpu::VertexBufferLayout {
                    array_stride: 16,
                    step_mode: wgpu::VertexStepMode::Instance,
                    attributes: &rect,
                })],
                wgpu::PrimitiveState { topology: wgpu::PrimitiveTopology::TriangleStrip, ..Default::default() },
            ),
        };
        let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(label),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &buffers,
            },
            primitive,
            depth_stencil: depth,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        });
        (bgl, pipeline)
    }

    /// Writes depth values (in [0, 1], rows in memory order) into a whole `width`×`height`
    /// depth texture.
    pub fn write_depth(&self, tex: &wgpu::Texture, width: u32, height: u32, values: &[f32]) {
        self.write_depth_region(tex, 0, (width, height), [0, 0, width, height], values, None);
    }

    /// Writes depth values (in [0, 1], rows in memory order) into the rectangle `[x, y, w, h]`
    /// of array layer `layer` (a cube face) of a `width`×`height` depth or depth-stencil
    /// texture, and stencil values (one byte per texel) if given. wgpu cannot copy into depth aspects, so the depths pass through a float
    /// texture and a scissored pass that sets `frag_depth`; stencil is copied directly.
    pub fn write_depth_region(
        &self,
        tex: &wgpu::Texture,
        layer: u32,
        size: (u32, u32),
        rect: [u32; 4],
        depths: &[f32],
        stencil: Option<&[u8]>,
    ) {
        let [x, y, w, h] = rect;
        if w == 0 || h == 0 {
            return;
        }
        let d = &self.device;
        let format = tex.format();
        let (bgl, pipeline) = {
            let mut writers = self.depth_writers.lock().unwrap_or_else(|e| e.into_inner());
            writers
                .entry(format)
                .or_insert_with(|| {
                    self.pipeline(
                        "depth upload",
                        wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/depth_upload.wgsl").into()),
                        &[texture_entry(0, UNFILTERED)],
                        &[],
                        Some(wgpu::DepthStencilState {
                            format,
                            depth_write_enabled: Some(true),
                            depth_compare: Some(wgpu::CompareFunction::Always),
                            stencil: Default::default(),
                            bias: Default::default(),
                        }),
                        VertexInput::None,
                    )
                })
                .clone()
        };
        let src = d.create_texture(&wgpu::TextureDescriptor {
            label: Some("depth upload source"),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let extent = wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 };
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &src,
                mip_level: 0,
                origin: wgpu::Origin3d { x, y, z: 0 },
                aspect: wgpu::TextureAspect::All,
            },
            bytemuck::cast_slice(depths),
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w * 4), rows_per_image: None },
            extent,
        );
        let src_view = src.create_view(&Default::default());
        let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &bgl,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src_view) }],
        });
        let dst = tex.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2),
            base_array_layer: layer,
            array_layer_count: Some(1),
            ..Default::default()
        });
        let keep_depth = wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store };
        let keep_stencil = wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store };
        let mut enc = d.create_command_encoder(&Default::default());
        {
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("depth upload"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &dst,
                    depth_ops: Some(keep_depth),
                    stencil_ops: format.has_stencil_aspect().then_some(keep_stencil),
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            rp.set_pipeline(&pipeline);
            rp.set_bind_group(0, &group, &[]);
            rp.set_scissor_rect(x, y, w, h);
            rp.draw(0..3, 0..1);
        }
        self.queue.submit([enc.finish()]);
        if let Some(s) = stencil.filter(|_| format.has_stencil_aspect()) {
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: tex,
                    mip_level: 0,
                    origin: wgpu::Origin3d { x, y, z: layer },
                    aspect: wgpu::TextureAspect::StencilOnly,
                },
                s,
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w), rows_per_image: None },
                extent,
            );
        }
    }

    /// Reads `[x, y, w, h]` of an RGBA8 texture as tightly packed rows in memory order.
    pub fn read_rgba8(&self, tex: &wgpu::Texture, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.read_texels(tex, (0, 0), rect, wgpu::TextureAspect::All, 4)
    }

    /// Reads `[x, y, w, h]` of `aspect` of array layer `layer`, mip level `level`, of a texture
    /// whose texels there take `bpp` bytes (the stencil aspect: 1), as tightly packed rows in
    /// memory order.
    pub fn read_texels(
        &self,
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
        self.queue.submit([enc.finish()]);
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
}

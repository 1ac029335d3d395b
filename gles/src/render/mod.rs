//! Turning validated GL draws into wgpu work, for one client: render targets, the pipeline
//! cache, one render pass per target for as long as the target stays the same, a per-pass ring
//! for uniforms and generated vertex data, clears, mipmap generation and readback.
//!
//! | module | concept |
//! |---|---|
//! | `targets` | what framebuffer 0 or a framebuffer object resolves to |
//! | `pipelines` | bind group layouts, samplers and the render pipeline cache |
//! | `passes` | recording draws into the open pass, and submitting it |
//! | `clears` | clears as load operations or as masked, scissored quads |
//! | `mipmaps` | `glGenerateMipmap` as a chain of box-filter passes |
//! | `readback` | reads, depth uploads and waiting for the GPU |

mod blit;
mod clears;
mod draw_spec;
mod keys;
mod mipmaps;
pub mod occlusion;
mod pass;
mod passes;
mod pipelines;
mod readback;
mod targets;

use std::collections::HashMap;
use std::sync::Arc;

pub use blit::Blit;
pub use draw_spec::{DrawSpec, RasterState, Source, VertexInput};
pub use targets::Target;

use crate::formats::COLOR_FORMAT;
use crate::objects::program::LinkedProgram;
use crate::objects::texture::SamplerState;
use keys::{ClearKey, PipelineKey};
use occlusion::Occlusion;
use pass::Pass;
use strata_device::Gpu;

/// The renderer of one client: its caches and the open pass.
pub struct Renderer {
    gpu: Arc<Gpu>,
    pipelines: HashMap<PipelineKey, wgpu::RenderPipeline>,
    clear_pipelines: HashMap<ClearKey, wgpu::RenderPipeline>,
    samplers: HashMap<(SamplerState, bool), wgpu::Sampler>,
    /// Pipelines created because none matched.
    pub pipeline_misses: u64,
    /// Render passes submitted.
    pub passes: u64,
    /// Draws recorded.
    pub draws: u64,
    /// GPU validation errors caught since the executor last charged them to its client.
    pub errors: Vec<String>,
    pass: Option<Pass>,
    staging: Vec<u8>,
    ring: Option<(wgpu::Buffer, u64)>,
    align: u64,
    fixed: Arc<Fixed>,
    layouts: HashMap<(u64, u32), (wgpu::BindGroupLayout, wgpu::PipelineLayout)>,
    /// The client's way onto the queue.
    pub lane: Arc<strata_device::Lane>,
    /// The occlusion query the current context has active: draws recorded count for it.
    pub occlusion: Option<Arc<Occlusion>>,
}

/// A 1×1 opaque black image (`layers` of them): what an incomplete texture samples as.
fn black(gpu: &Gpu, layers: u32, dim: wgpu::TextureViewDimension) -> wgpu::TextureView {
    let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("incomplete texture"),
        size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: layers },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: COLOR_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for layer in 0..layers {
        gpu.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &tex,
                mip_level: 0,
                origin: wgpu::Origin3d { x: 0, y: 0, z: layer },
                aspect: wgpu::TextureAspect::All,
            },
            &[0, 0, 0, 255],
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4), rows_per_image: None },
            wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
        );
    }
    tex.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), ..Default::default() })
}

/// A 1×1×1 opaque black 3D image, which incomplete 3D textures sample.
fn black_volume(gpu: &Gpu) -> wgpu::TextureView {
    let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("incomplete 3d texture"),
        size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D3,
        format: COLOR_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    gpu.write_texture(
        tex.as_image_copy(),
        &[0, 0, 0, 255],
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4), rows_per_image: None },
        wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
    );
    tex.create_view(&Default::default())
}

/// A 1×1 (×1) integer image holding (0, 0, 0, 1), signed or not, of `dim` (2D, 3D or a 2D
/// array): what incomplete textures read through integer samplers.
fn black_int(gpu: &Gpu, signed: bool, dim: wgpu::TextureViewDimension) -> wgpu::TextureView {
    let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("incomplete integer texture"),
        size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: if dim == wgpu::TextureViewDimension::D3 {
            wgpu::TextureDimension::D3
        } else {
            wgpu::TextureDimension::D2
        },
        format: if signed { wgpu::TextureFormat::Rgba8Sint } else { wgpu::TextureFormat::Rgba8Uint },
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    gpu.write_texture(
        tex.as_image_copy(),
        &[0, 0, 0, 1],
        wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4), rows_per_image: None },
        wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
    );
    tex.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), ..Default::default() })
}

/// The bind group layout of the mipmap shaders: the level above, of `dim`, and a sampler.
fn mip_layout(gpu: &Gpu, dim: wgpu::TextureViewDimension) -> wgpu::BindGroupLayout {
    gpu.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("mipmap"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: dim,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    })
}

/// The objects every client's renderer uses unchanged: the clear and mipmap shaders and
/// layouts, and the black images incomplete textures sample. They are built once per device
/// (not per client: creating them for every session would cost each session its own uploads).
pub struct Fixed {
    black_2d: wgpu::TextureView,
    black_cube: wgpu::TextureView,
    black_3d: wgpu::TextureView,
    /// What incomplete 2D arrays sample: one opaque black layer.
    black_array: wgpu::TextureView,
    /// What incomplete textures read through integer samplers, unsigned then signed: 2D, 3D,
    /// and 2D arrays (integer cube maps too, which are fetched as arrays).
    black_int: [[wgpu::TextureView; 3]; 2],
    /// What a uniform block without a large enough buffer reads: zeros, as many as a block
    /// may hold.
    zero_block: wgpu::Buffer,
    /// What a transform feedback program's capture buffers are when it does not capture: one
    /// small buffer per binding, which nothing writes.
    unused_capture: Vec<wgpu::Buffer>,
    clear_module: wgpu::ShaderModule,
    clear_bgl: wgpu::BindGroupLayout,
    clear_layout: wgpu::PipelineLayout,
    mip_module: wgpu::ShaderModule,
    mip_bgl: wgpu::BindGroupLayout,
    mip3_module: wgpu::ShaderModule,
    mip3_bgl: wgpu::BindGroupLayout,
    /// Clear pipelines by target and masks, compiled once for all clients.
    clear_pipelines: std::sync::Mutex<HashMap<ClearKey, wgpu::RenderPipeline>>,
    /// Mipmap pipelines by format and whether they filter 3D images, compiled once for all
    /// clients.
    mip_pipelines: std::sync::Mutex<HashMap<(wgpu::TextureFormat, bool), wgpu::RenderPipeline>>,
    /// The blit shaders and their layouts (`glBlitFramebuffer`) for each kind of source
    /// (`blit::Source`), each made on its first blit.
    blit: [std::sync::OnceLock<(wgpu::ShaderModule, wgpu::BindGroupLayout)>; 5],
    /// Blit pipelines by destination format, written channels and kind of source, compiled
    /// once for all clients.
    blit_pipelines: std::sync::Mutex<HashMap<(wgpu::TextureFormat, u32, usize), wgpu::RenderPipeline>>,
}

impl Fixed {
    fn new(gpu: &Gpu) -> Self {
        let d = &gpu.device;
        let clear_module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("clear"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/clear.wgsl").into()),
        });
        let clear_bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("clear"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let clear_layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("clear"),
            bind_group_layouts: &[Some(&clear_bgl)],
            immediate_size: 0,
        });
        let mip_module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("mipmap"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/mipmap.wgsl").into()),
        });
        let mip_bgl = mip_layout(gpu, wgpu::TextureViewDimension::D2);
        let mip3_module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("mipmap 3d"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/mipmap3d.wgsl").into()),
        });
        let mip3_bgl = mip_layout(gpu, wgpu::TextureViewDimension::D3);
        Fixed {
            black_2d: black(gpu, 1, wgpu::TextureViewDimension::D2),
            black_cube: black(gpu, 6, wgpu::TextureViewDimension::Cube),
            black_array: black(gpu, 1, wgpu::TextureViewDimension::D2Array),
            black_3d: black_volume(gpu),
            black_int: [false, true].map(|signed| {
                [wgpu::TextureViewDimension::D2, wgpu::TextureViewDimension::D3, wgpu::TextureViewDimension::D2Array]
                    .map(|dim| black_int(gpu, signed, dim))
            }),
            unused_capture: (0..crate::glsl::capture::MAX_SEPARATE_ATTRIBS)
                .map(|_| {
                    d.create_buffer(&wgpu::BufferDescriptor {
                        label: Some("unused capture buffer"),
                        size: 16,
                        usage: wgpu::BufferUsages::STORAGE,
                        mapped_at_creation: false,
                    })
                })
                .collect(),
            zero_block: d.create_buffer(&wgpu::BufferDescriptor {
                label: Some("zero uniform block"),
                size: u64::from(crate::glsl::blocks::MAX_UNIFORM_BLOCK_SIZE),
                usage: wgpu::BufferUsages::UNIFORM,
                mapped_at_creation: false,
            }),
            clear_module,
            clear_bgl,
            clear_layout,
            mip_module,
            mip_bgl,
            mip3_module,
            mip3_bgl,
            clear_pipelines: Default::default(),
            mip_pipelines: Default::default(),
            blit: Default::default(),
            blit_pipelines: Default::default(),
        }
    }
}

impl Renderer {
    /// A renderer drawing with `gpu`.
    pub fn new(gpu: Arc<Gpu>) -> Self {
        let fixed = gpu.shared(Fixed::new);
        let align = u64::from(gpu.limits.min_uniform_buffer_offset_alignment).max(16);
        let lane = strata_device::Lane::new(strata_protocol::control::Priority::Normal);
        Renderer {
            lane,
            gpu,
            pipelines: HashMap::new(),
            clear_pipelines: HashMap::new(),
            samplers: HashMap::new(),
            pipeline_misses: 0,
            passes: 0,
            draws: 0,
            errors: Vec::new(),
            pass: None,
            staging: Vec::new(),
            ring: None,
            align,
            fixed,
            layouts: HashMap::new(),
            occlusion: None,
        }
    }
}

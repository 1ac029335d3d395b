//! Turning validated GL draws into wgpu work: render targets, the pipeline cache, one render
//! pass per target for as long as the target stays the same, a per-pass ring for uniforms and
//! generated vertex data, clears, mipmap generation and readback.

use std::collections::HashMap;
use std::sync::Arc;

use super::enums::*;
use super::objects::{LinkedProgram, SamplerState};
use crate::gpu::Gpu;

/// An error with all its sources, for logs (wgpu's top-level text is only "Validation Error").
pub fn error_chain(e: &wgpu::Error) -> String {
    let mut s = match e {
        wgpu::Error::Validation { description, .. } => description.clone(),
        other => other.to_string(),
    };
    let mut src = std::error::Error::source(e);
    while let Some(x) = src {
        s.push_str(": ");
        s.push_str(&x.to_string());
        src = x.source();
    }
    s
}

/// Colour format of every colour target and texture.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// A render target: what framebuffer 0 or a framebuffer object resolves to.
#[derive(Clone)]
pub struct Target {
    /// Identity for pass batching (surface or attachment ids).
    pub key: (u64, u64),
    /// Colour image: texture and single-level view.
    pub color: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// Depth/stencil view and its format.
    pub depth: Option<(wgpu::TextureView, wgpu::TextureFormat)>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Target {
    /// Whether the depth/stencil format has a stencil aspect.
    pub fn has_stencil(&self) -> bool {
        matches!(self.depth, Some((_, f)) if f.has_stencil_aspect())
    }
}

/// Where a draw's vertex or index bytes come from.
#[derive(Clone)]
pub enum Source {
    /// A client buffer object's GPU copy, at a byte offset.
    Buffer(wgpu::Buffer, u64),
    /// Bytes generated for this draw (converted attributes, constants, widened indices).
    Bytes(Vec<u8>),
}

/// One vertex input of a draw.
#[derive(Clone)]
pub struct VertexInput {
    /// Shader location.
    pub location: u32,
    /// Element format.
    pub format: wgpu::VertexFormat,
    /// Byte stride (0 for a constant).
    pub stride: u64,
    /// The bytes.
    pub source: Source,
}

/// Fixed-function state that selects a pipeline.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct RasterState {
    /// Primitive topology.
    pub topology: wgpu::PrimitiveTopology,
    /// Index format of an indexed strip (wgpu requires it; restart can never trigger, see draw).
    pub strip_index: Option<wgpu::IndexFormat>,
    /// GL front face is CCW.
    pub front_ccw: bool,
    /// Face culled, if culling is on.
    pub cull: Option<wgpu::Face>,
    /// Depth test function (`None`: test off), and depth writes.
    pub depth: Option<(wgpu::CompareFunction, bool)>,
    /// Stencil state if the test is on.
    pub stencil: Option<wgpu::StencilState>,
    /// Polygon offset (factor bits, units).
    pub bias: Option<(u32, i32)>,
    /// Blend state if blending is on.
    pub blend: Option<wgpu::BlendState>,
    /// Colour write mask.
    pub write_mask: wgpu::ColorWrites,
}

/// Everything a validated draw needs.
pub struct DrawSpec<'a> {
    /// The program.
    pub program: Arc<LinkedProgram>,
    /// Uniform block bytes.
    pub uniforms: &'a [u8],
    /// Per sampler: texture view, its uid, sampling state, and whether it is a depth texture
    /// (`None`: incomplete, sample black).
    pub textures: Vec<Option<(wgpu::TextureView, u64, SamplerState, bool)>>,
    /// Vertex inputs.
    pub inputs: Vec<VertexInput>,
    /// Indices, if indexed.
    pub index: Option<(Source, wgpu::IndexFormat)>,
    /// Vertices or indices to draw.
    pub count: u32,
    /// First vertex (non-indexed).
    pub first: u32,
    /// Fixed-function state.
    pub raster: RasterState,
    /// Viewport x, y, w, h, near, far.
    pub viewport: [f32; 6],
    /// Scissor rectangle, already clipped to the target.
    pub scissor: [u32; 4],
    /// Stencil reference.
    pub stencil_ref: u32,
    /// Blend constant.
    pub blend_color: [f64; 4],
}

#[derive(Clone, PartialEq, Eq, Hash)]
struct PipelineKey {
    program: u64,
    depth_mask: u32,
    inputs: Vec<(u32, wgpu::VertexFormat, u64)>,
    raster: RasterState,
    color: bool,
    depth_format: Option<wgpu::TextureFormat>,
}

#[derive(Clone, PartialEq, Eq, Hash)]
struct ClearKey {
    color: Option<wgpu::ColorWrites>,
    depth: Option<(wgpu::TextureFormat, bool, Option<u32>)>,
    target_color: bool,
}

enum Bind {
    Program {
        program: Arc<LinkedProgram>,
        layout: wgpu::BindGroupLayout,
        uniform: Option<u32>,
        textures: Vec<(wgpu::TextureView, u64, wgpu::Sampler, SamplerState)>,
    },
    Clear(u32),
}

struct Recorded {
    pipeline: wgpu::RenderPipeline,
    bind: Bind,
    vertex: Vec<(Source, u64)>,
    index: Option<(Source, u64, wgpu::IndexFormat)>,
    count: u32,
    first: u32,
    viewport: [f32; 6],
    scissor: [u32; 4],
    stencil_ref: u32,
    blend_color: [f64; 4],
}

struct Pass {
    target: Target,
    clear_color: Option<wgpu::Color>,
    clear_depth: Option<f32>,
    clear_stencil: Option<u32>,
    draws: Vec<Recorded>,
}

/// The renderer of one client: its caches and the open pass.
pub struct Renderer {
    gpu: Arc<Gpu>,
    pipelines: HashMap<PipelineKey, wgpu::RenderPipeline>,
    clear_pipelines: HashMap<ClearKey, wgpu::RenderPipeline>,
    samplers: HashMap<SamplerState, wgpu::Sampler>,
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
    black_2d: wgpu::TextureView,
    black_cube: wgpu::TextureView,
    clear_module: wgpu::ShaderModule,
    clear_bgl: wgpu::BindGroupLayout,
    clear_layout: wgpu::PipelineLayout,
    mip_module: wgpu::ShaderModule,
    mip_bgl: wgpu::BindGroupLayout,
    mip_pipeline: Option<wgpu::RenderPipeline>,
    layouts: HashMap<(u64, u32), (wgpu::BindGroupLayout, wgpu::PipelineLayout)>,
}

/// A program's bind group layout entries: the uniform block at 0, then a texture and a sampler
/// per sampler uniform. Samplers in `depth_mask` take depth textures, which bind as
/// unfilterable float with a non-filtering sampler.
pub fn layout_entries(info: &super::glsl::Linked, depth_mask: u32) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = Vec::new();
    if info.block_size > 0 {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(u64::from(info.block_size)),
            },
            count: None,
        });
    }
    for (i, (ty, b)) in info.samplers.iter().enumerate() {
        let depth = depth_mask & (1 << i) != 0;
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: *b,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: !depth },
                view_dimension: if *ty == super::glsl::Ty::SamplerCube {
                    wgpu::TextureViewDimension::Cube
                } else {
                    wgpu::TextureViewDimension::D2
                },
                multisampled: false,
            },
            count: None,
        });
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: b + 1,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Sampler(if depth {
                wgpu::SamplerBindingType::NonFiltering
            } else {
                wgpu::SamplerBindingType::Filtering
            }),
            count: None,
        });
    }
    entries
}

fn black(gpu: &Gpu, layers: u32) -> wgpu::TextureView {
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
        gpu.queue.write_texture(
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
    let dim = if layers == 6 { wgpu::TextureViewDimension::Cube } else { wgpu::TextureViewDimension::D2 };
    tex.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), ..Default::default() })
}

fn offset_of(staging: &mut Vec<u8>, bytes: &[u8], align: u64) -> u64 {
    let off = (staging.len() as u64).div_ceil(align) * align;
    staging.resize(off as usize, 0);
    staging.extend_from_slice(bytes);
    off
}

impl Renderer {
    /// A renderer drawing with `gpu`.
    pub fn new(gpu: Arc<Gpu>) -> Self {
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
        let mip_bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("mipmap"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
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
        });
        let align = u64::from(gpu.limits.min_uniform_buffer_offset_alignment).max(16);
        Renderer {
            black_2d: black(&gpu, 1),
            black_cube: black(&gpu, 6),
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
            clear_module,
            clear_bgl,
            clear_layout,
            mip_module,
            mip_bgl,
            mip_pipeline: None,
            layouts: HashMap::new(),
        }
    }

    /// Whether draws are recorded but not yet submitted.
    pub fn pending(&self) -> bool {
        self.pass.as_ref().is_some_and(|p| {
            !p.draws.is_empty() || p.clear_color.is_some() || p.clear_depth.is_some() || p.clear_stencil.is_some()
        })
    }

    fn pass_for(&mut self, target: &Target) -> &mut Pass {
        if self.pass.as_ref().is_some_and(|p| p.target.key != target.key) {
            self.flush();
        }
        self.pass.get_or_insert_with(|| Pass {
            target: target.clone(),
            clear_color: None,
            clear_depth: None,
            clear_stencil: None,
            draws: Vec::new(),
        })
    }

    /// `glClear` of the whole target with full masks, folded into the pass's load operations
    /// when nothing has been drawn yet.
    #[allow(clippy::too_many_arguments)]
    pub fn clear(
        &mut self,
        target: &Target,
        color: Option<([f32; 4], wgpu::ColorWrites)>,
        depth: Option<(f32, bool)>,
        stencil: Option<(u32, u32)>,
        scissor: Option<[u32; 4]>,
    ) {
        let full_color = color.is_none_or(|(_, m)| m == wgpu::ColorWrites::ALL);
        let full_depth = depth.is_none_or(|(_, w)| w);
        let full_stencil = stencil.is_none_or(|(_, m)| m & 0xff == 0xff);
        let whole = scissor.is_none_or(|s| s == [0, 0, target.width, target.height]);
        let pass = self.pass_for(target);
        if pass.draws.is_empty() && full_color && full_depth && full_stencil && whole {
            if let Some((c, _)) = color {
                pass.clear_color = Some(wgpu::Color { r: c[0].into(), g: c[1].into(), b: c[2].into(), a: c[3].into() });
            }
            if let Some((d, _)) = depth {
                pass.clear_depth = Some(d.clamp(0.0, 1.0));
            }
            if let Some((s, _)) = stencil {
                pass.clear_stencil = Some(s & 0xff);
            }
            return;
        }
        // A quad that honours masks and the scissor.
        let has_depth = target.depth.is_some();
        let key = ClearKey {
            color: color.map(|(_, m)| m),
            depth: target.depth.as_ref().map(|(_, f)| {
                (*f, depth.is_some_and(|(_, w)| w), stencil.filter(|_| target.has_stencil()).map(|(_, m)| m))
            }),
            target_color: target.color.is_some(),
        };
        let pipeline = self.clear_pipeline(&key);
        let mut params = [0u8; 32];
        let c = color.map(|(c, _)| c).unwrap_or([0.0; 4]);
        for (i, v) in c.iter().enumerate() {
            params[i * 4..i * 4 + 4].copy_from_slice(&v.to_ne_bytes());
        }
        params[16..20].copy_from_slice(&depth.map(|(d, _)| d.clamp(0.0, 1.0)).unwrap_or(0.0).to_ne_bytes());
        let off = offset_of(&mut self.staging, &params, self.align) as u32;
        let scissor = scissor.unwrap_or([0, 0, target.width, target.height]);
        let pass = self.pass_for(target);
        let _ = has_depth;
        pass.draws.push(Recorded {
            pipeline,
            bind: Bind::Clear(off),
            vertex: Vec::new(),
            index: None,
            count: 3,
            first: 0,
            viewport: [0.0, 0.0, target.width as f32, target.height as f32, 0.0, 1.0],
            scissor,
            stencil_ref: stencil.map(|(s, _)| s).unwrap_or(0),
            blend_color: [0.0; 4],
        });
    }

    fn clear_pipeline(&mut self, key: &ClearKey) -> wgpu::RenderPipeline {
        if let Some(p) = self.clear_pipelines.get(key) {
            return p.clone();
        }
        let targets = [Some(wgpu::ColorTargetState {
            format: COLOR_FORMAT,
            blend: None,
            write_mask: key.color.unwrap_or(wgpu::ColorWrites::empty()),
        })];
        let depth_stencil = key.depth.map(|(format, write, stencil)| {
            let face = wgpu::StencilFaceState {
                compare: wgpu::CompareFunction::Always,
                fail_op: wgpu::StencilOperation::Keep,
                depth_fail_op: wgpu::StencilOperation::Keep,
                pass_op: wgpu::StencilOperation::Replace,
            };
            wgpu::DepthStencilState {
                format,
                depth_write_enabled: Some(write),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: match stencil {
                    Some(mask) => wgpu::StencilState { front: face, back: face, read_mask: 0xff, write_mask: mask },
                    None => Default::default(),
                },
                bias: Default::default(),
            }
        });
        let p = self.gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("clear"),
            layout: Some(&self.clear_layout),
            vertex: wgpu::VertexState {
                module: &self.clear_module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &self.clear_module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: if key.target_color { &targets } else { &[] },
            }),
            multiview_mask: None,
            cache: None,
        });
        self.clear_pipelines.insert(key.clone(), p.clone());
        p
    }

    fn sampler(&mut self, s: SamplerState) -> wgpu::Sampler {
        if let Some(x) = self.samplers.get(&s) {
            return x.clone();
        }
        let filter = |f: u32| {
            if matches!(f, LINEAR | LINEAR_MIPMAP_NEAREST | LINEAR_MIPMAP_LINEAR) {
                wgpu::FilterMode::Linear
            } else {
                wgpu::FilterMode::Nearest
            }
        };
        let wrap = |w: u32| match w {
            CLAMP_TO_EDGE => wgpu::AddressMode::ClampToEdge,
            MIRRORED_REPEAT => wgpu::AddressMode::MirrorRepeat,
            _ => wgpu::AddressMode::Repeat,
        };
        let mip = if matches!(s.min, NEAREST_MIPMAP_LINEAR | LINEAR_MIPMAP_LINEAR) {
            wgpu::MipmapFilterMode::Linear
        } else {
            wgpu::MipmapFilterMode::Nearest
        };
        let x = self.gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: None,
            address_mode_u: wrap(s.wrap_s),
            address_mode_v: wrap(s.wrap_t),
            address_mode_w: wrap(s.wrap_t),
            mag_filter: filter(s.mag),
            min_filter: filter(s.min),
            mipmap_filter: mip,
            lod_min_clamp: 0.0,
            lod_max_clamp: if s.uses_mipmaps() { 32.0 } else { 0.0 },
            compare: None,
            anisotropy_clamp: 1,
            border_color: None,
        });
        self.samplers.insert(s, x.clone());
        x
    }

    /// The bind group and pipeline layouts of `program` with the samplers in `mask` taking depth
    /// textures.
    fn layouts(&mut self, program: &LinkedProgram, mask: u32) -> (wgpu::BindGroupLayout, wgpu::PipelineLayout) {
        if mask == 0 {
            return (program.bgl.clone(), program.layout.clone());
        }
        let d = &self.gpu.device;
        self.layouts
            .entry((program.id, mask))
            .or_insert_with(|| {
                let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("gles depth-sampling"),
                    entries: &layout_entries(&program.info, mask),
                });
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: None,
                    bind_group_layouts: &[Some(&bgl)],
                    immediate_size: 0,
                });
                (bgl, layout)
            })
            .clone()
    }

    fn pipeline(&mut self, spec: &DrawSpec<'_>, target: &Target, depth_mask: u32) -> wgpu::RenderPipeline {
        let key = PipelineKey {
            program: spec.program.id,
            depth_mask,
            inputs: spec.inputs.iter().map(|i| (i.location, i.format, i.stride)).collect(),
            raster: spec.raster.clone(),
            color: target.color.is_some(),
            depth_format: target.depth.as_ref().map(|d| d.1),
        };
        if let Some(p) = self.pipelines.get(&key) {
            return p.clone();
        }
        self.pipeline_misses += 1;
        let (_, pipeline_layout) = self.layouts(&spec.program, depth_mask);
        let attrs: Vec<[wgpu::VertexAttribute; 1]> = spec
            .inputs
            .iter()
            .map(|i| [wgpu::VertexAttribute { format: i.format, offset: 0, shader_location: i.location }])
            .collect();
        let layouts: Vec<Option<wgpu::VertexBufferLayout<'_>>> = spec
            .inputs
            .iter()
            .zip(&attrs)
            .map(|(i, a)| {
                Some(wgpu::VertexBufferLayout {
                    array_stride: i.stride,
                    step_mode: if i.stride == 0 {
                        wgpu::VertexStepMode::Instance
                    } else {
                        wgpu::VertexStepMode::Vertex
                    },
                    attributes: a,
                })
            })
            .collect();
        let r = &spec.raster;
        let depth_stencil = key.depth_format.map(|format| wgpu::DepthStencilState {
            format,
            depth_write_enabled: Some(r.depth.is_some_and(|d| d.1)),
            depth_compare: Some(r.depth.map(|d| d.0).unwrap_or(wgpu::CompareFunction::Always)),
            stencil: if format.has_stencil_aspect() {
                r.stencil.clone().unwrap_or_default()
            } else {
                Default::default()
            },
            bias: match r.bias {
                Some((factor, units)) => {
                    wgpu::DepthBiasState { constant: units, slope_scale: f32::from_bits(factor), clamp: 0.0 }
                }
                None => Default::default(),
            },
        });
        let targets = [Some(wgpu::ColorTargetState { format: COLOR_FORMAT, blend: r.blend, write_mask: r.write_mask })];
        // The y flip mirrors the image, so GL's front winding is the opposite one in wgpu.
        let front_face = if r.front_ccw { wgpu::FrontFace::Cw } else { wgpu::FrontFace::Ccw };
        let p = self.gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("gles"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &spec.program.vs,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                buffers: &layouts,
            },
            primitive: wgpu::PrimitiveState {
                topology: r.topology,
                strip_index_format: r.strip_index,
                front_face,
                cull_mode: r.cull,
                unclipped_depth: false,
                polygon_mode: wgpu::PolygonMode::Fill,
                conservative: false,
            },
            depth_stencil,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &spec.program.fs,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                targets: if key.color { &targets } else { &[] },
            }),
            multiview_mask: None,
            cache: None,
        });
        self.pipelines.insert(key, p.clone());
        p
    }

    /// Records a validated draw into the target's pass.
    pub fn draw(&mut self, target: &Target, spec: DrawSpec<'_>) {
        let depth_mask = spec
            .textures
            .iter()
            .enumerate()
            .filter(|(_, t)| t.as_ref().is_some_and(|t| t.3))
            .fold(0u32, |m, (i, _)| m | (1 << i));
        let pipeline = self.pipeline(&spec, target, depth_mask);
        let (layout, _) = self.layouts(&spec.program, depth_mask);
        // Open the target's pass first: switching targets flushes the previous pass, which
        // uploads and empties the staging area, so this draw's data must go in after that.
        self.pass_for(target);
        let uniform =
            (!spec.uniforms.is_empty()).then(|| offset_of(&mut self.staging, spec.uniforms, self.align) as u32);
        let mut textures = Vec::with_capacity(spec.textures.len());
        for (i, t) in spec.textures.iter().enumerate() {
            let cube = spec.program.info.samplers.get(i).is_some_and(|s| s.0 == super::glsl::Ty::SamplerCube);
            match t {
                Some((view, uid, state, depth)) => {
                    // Depth textures are read with a non-filtering sampler: nearest filters.
                    let state = if *depth { SamplerState { min: NEAREST, mag: NEAREST, ..*state } } else { *state };
                    textures.push((view.clone(), *uid, self.sampler(state), state))
                }
                None => {
                    let view = if cube { self.black_cube.clone() } else { self.black_2d.clone() };
                    let s = SamplerState::default();
                    textures.push((view, u64::MAX - u64::from(cube), self.sampler(s), s));
                }
            }
        }
        let align = 4;
        let mut vertex = Vec::with_capacity(spec.inputs.len());
        for i in spec.inputs {
            match i.source {
                Source::Buffer(b, off) => vertex.push((Source::Buffer(b, off), 0)),
                Source::Bytes(bytes) => {
                    let off = offset_of(&mut self.staging, &bytes, align);
                    vertex.push((Source::Bytes(Vec::new()), off));
                }
            }
        }
        let index = spec.index.map(|(src, fmt)| match src {
            Source::Buffer(b, off) => (Source::Buffer(b, off), 0, fmt),
            Source::Bytes(bytes) => {
                let off = offset_of(&mut self.staging, &bytes, align);
                (Source::Bytes(Vec::new()), off, fmt)
            }
        });
        self.draws += 1;
        let rec = Recorded {
            pipeline,
            bind: Bind::Program { program: spec.program, layout, uniform, textures },
            vertex,
            index,
            count: spec.count,
            first: spec.first,
            viewport: spec.viewport,
            scissor: spec.scissor,
            stencil_ref: spec.stencil_ref,
            blend_color: spec.blend_color,
        };
        self.pass_for(target).draws.push(rec);
    }

    /// Encodes and submits the open pass. A GPU validation error is queued in `errors`.
    pub fn flush(&mut self) {
        let Some(pass) = self.pass.take() else { return };
        self.passes += 1;
        let guard = self.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let d = &self.gpu.device;
        // Upload this pass's uniforms and generated vertex data in one write.
        if !self.staging.is_empty() {
            let need = (self.staging.len() as u64).div_ceil(256) * 256;
            if self.ring.as_ref().is_none_or(|(_, cap)| *cap < need) {
                let cap = need.next_power_of_two().max(64 << 10);
                let buf = d.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("per-pass ring"),
                    size: cap,
                    usage: wgpu::BufferUsages::UNIFORM
                        | wgpu::BufferUsages::VERTEX
                        | wgpu::BufferUsages::INDEX
                        | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.ring = Some((buf, cap));
            }
            self.staging.resize(need as usize, 0);
            if let Some((ring, _)) = &self.ring {
                self.gpu.queue.write_buffer(ring, 0, &self.staging);
            }
            self.staging.clear();
        }
        let ring = self.ring.as_ref().map(|(b, _)| b.clone());
        let mut groups: Vec<Option<wgpu::BindGroup>> = Vec::with_capacity(pass.draws.len());
        let mut cache: HashMap<(u64, Vec<(u64, SamplerState)>), wgpu::BindGroup> = HashMap::new();
        let mut clear_group: Option<wgpu::BindGroup> = None;
        for r in &pass.draws {
            let g = match &r.bind {
                Bind::Clear(_) => {
                    if clear_group.is_none() {
                        if let Some(ring) = &ring {
                            clear_group = Some(d.create_bind_group(&wgpu::BindGroupDescriptor {
                                label: Some("clear"),
                                layout: &self.clear_bgl,
                                entries: &[wgpu::BindGroupEntry {
                                    binding: 0,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer: ring,
                                        offset: 0,
                                        size: wgpu::BufferSize::new(32),
                                    }),
                                }],
                            }));
                        }
                    }
                    clear_group.clone()
                }
                Bind::Program { program, layout, uniform, textures } => {
                    if uniform.is_none() && textures.is_empty() {
                        None
                    } else {
                        let key = (program.id, textures.iter().map(|t| (t.1, t.3)).collect::<Vec<_>>());
                        if let Some(g) = cache.get(&key) {
                            Some(g.clone())
                        } else {
                            let mut entries = Vec::new();
                            if let (Some(_), Some(ring)) = (uniform, &ring) {
                                entries.push(wgpu::BindGroupEntry {
                                    binding: 0,
                                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                                        buffer: ring,
                                        offset: 0,
                                        size: wgpu::BufferSize::new(u64::from(program.info.block_size)),
                                    }),
                                });
                            }
                            for (i, t) in textures.iter().enumerate() {
                                let b = program.info.samplers[i].1;
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b,
                                    resource: wgpu::BindingResource::TextureView(&t.0),
                                });
                                entries.push(wgpu::BindGroupEntry {
                                    binding: b + 1,
                                    resource: wgpu::BindingResource::Sampler(&t.2),
                                });
                            }
                            let g = d.create_bind_group(&wgpu::BindGroupDescriptor {
                                label: None,
                                layout,
                                entries: &entries,
                            });
                            cache.insert(key, g.clone());
                            Some(g)
                        }
                    }
                }
            };
            groups.push(g);
        }
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("gles pass") });
        {
            let t = &pass.target;
            let color = t.color.as_ref().map(|(_, view)| wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: pass.clear_color.map(wgpu::LoadOp::Clear).unwrap_or(wgpu::LoadOp::Load),
                    store: wgpu::StoreOp::Store,
                },
            });
            let depth = t.depth.as_ref().map(|(view, f)| wgpu::RenderPassDepthStencilAttachment {
                view,
                depth_ops: Some(wgpu::Operations {
                    load: pass.clear_depth.map(wgpu::LoadOp::Clear).unwrap_or(wgpu::LoadOp::Load),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: f.has_stencil_aspect().then(|| wgpu::Operations {
                    load: pass.clear_stencil.map(wgpu::LoadOp::Clear).unwrap_or(wgpu::LoadOp::Load),
                    store: wgpu::StoreOp::Store,
                }),
            });
            let colors = [color];
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("gles"),
                color_attachments: if t.color.is_some() { &colors } else { &[] },
                depth_stencil_attachment: depth,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            for (r, g) in pass.draws.iter().zip(&groups) {
                rp.set_pipeline(&r.pipeline);
                match (&r.bind, g) {
                    (Bind::Clear(off), Some(g)) => rp.set_bind_group(0, g, &[*off]),
                    (Bind::Program { uniform: Some(off), .. }, Some(g)) => rp.set_bind_group(0, g, &[*off]),
                    (Bind::Program { uniform: None, .. }, Some(g)) => rp.set_bind_group(0, g, &[]),
                    _ => {}
                }
                for (slot, (src, off)) in r.vertex.iter().enumerate() {
                    match src {
                        Source::Buffer(b, o) => rp.set_vertex_buffer(slot as u32, b.slice(*o..)),
                        Source::Bytes(_) => {
                            if let Some(ring) = &ring {
                                rp.set_vertex_buffer(slot as u32, ring.slice(*off..));
                            }
                        }
                    }
                }
                let [x, y, w, h, n, f] = r.viewport;
                rp.set_viewport(x, y, w, h, n, f);
                let [sx, sy, sw, sh] = r.scissor;
                rp.set_scissor_rect(sx, sy, sw, sh);
                rp.set_stencil_reference(r.stencil_ref);
                let [br, bg, bb, ba] = r.blend_color;
                rp.set_blend_constant(wgpu::Color { r: br, g: bg, b: bb, a: ba });
                match &r.index {
                    Some((src, off, fmt)) => {
                        match src {
                            Source::Buffer(b, o) => rp.set_index_buffer(b.slice(*o..), *fmt),
                            Source::Bytes(_) => {
                                if let Some(ring) = &ring {
                                    rp.set_index_buffer(ring.slice(*off..), *fmt);
                                }
                            }
                        }
                        rp.draw_indexed(0..r.count, 0, 0..1);
                    }
                    None => rp.draw(r.first..r.first + r.count, 0..1),
                }
            }
        }
        self.gpu.queue.submit([enc.finish()]);
        if let Some(e) = pollster::block_on(guard.pop()) {
            self.errors.push(error_chain(&e));
        }
    }

    /// Reads `[x, y, w, h]` of the target's colour image as tightly packed RGBA8 rows, bottom
    /// row first (GL order, which is also memory order here).
    pub fn read_rgba(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.flush();
        let (tex, _) = target.color.as_ref()?;
        self.gpu.read_rgba8(tex, rect)
    }

    /// Waits until the GPU has finished everything submitted.
    pub fn finish(&mut self) {
        self.flush();
        let _ = self.gpu.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None });
    }

    /// Writes depth values (normalised, rows bottom-up) into a Depth32Float texture.
    pub fn upload_depth(&mut self, tex: &wgpu::Texture, width: u32, height: u32, values: &[f32]) {
        self.flush();
        self.gpu.write_depth(tex, width, height, values);
    }

    /// Fills levels 1.. of every face from level 0 with a 2×2 box filter.
    pub fn generate_mipmaps(&mut self, tex: &wgpu::Texture, mips: u32, layers: u32) {
        self.flush();
        let d = &self.gpu.device;
        let pipeline = self
            .mip_pipeline
            .get_or_insert_with(|| {
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("mipmap"),
                    bind_group_layouts: &[Some(&self.mip_bgl)],
                    immediate_size: 0,
                });
                d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("mipmap"),
                    layout: Some(&layout),
                    vertex: wgpu::VertexState {
                        module: &self.mip_module,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &self.mip_module,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &[Some(COLOR_FORMAT.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            })
            .clone();
        let linear =
            self.sampler(SamplerState { min: LINEAR, mag: LINEAR, wrap_s: CLAMP_TO_EDGE, wrap_t: CLAMP_TO_EDGE });
        let d = &self.gpu.device;
        let mut enc = d.create_command_encoder(&Default::default());
        for layer in 0..layers {
            for level in 1..mips {
                let view = |l: u32| {
                    tex.create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(wgpu::TextureViewDimension::D2),
                        base_mip_level: l,
                        mip_level_count: Some(1),
                        base_array_layer: layer,
                        array_layer_count: Some(1),
                        ..Default::default()
                    })
                };
                let src = view(level - 1);
                let dst = view(level);
                let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: None,
                    layout: &self.mip_bgl,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src) },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&linear) },
                    ],
                });
                let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("mipmap"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &dst,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                rp.set_pipeline(&pipeline);
                rp.set_bind_group(0, &group, &[]);
                rp.draw(0..3, 0..1);
            }
        }
        self.gpu.queue.submit([enc.finish()]);
    }
}

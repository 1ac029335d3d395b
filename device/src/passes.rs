//! Building blocks of the full-screen passes every layer draws: bind group entries, the one
//! pipeline builder ([`Gpu::pipeline`]), full-screen triangles, 2D texture descriptors.

use crate::gpu::Gpu;

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
}

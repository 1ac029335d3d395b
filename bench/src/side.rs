//! What the execute benchmark compares: sides that draw frames and read the last one back.

use anyhow::Result;
use indicatif::ProgressBar;

/// What a side is set up with.
pub(crate) struct Setup {
    /// Square framebuffer size.
    pub(crate) size: u32,
    /// Rasterizer threads of the client's device (0: the driver's).
    pub(crate) client_rasterizer_threads: u32,
}

/// The two sides of a comparison (through `stratad`, then the baseline) and what they draw.
pub(crate) type Sides = (Box<dyn Side>, Box<dyn Side>, String);

/// One side of the comparison.
pub(crate) trait Side {
    /// Submits frame `f`.
    fn frame(&mut self, f: u32) -> Result<()>;
    /// Waits for the frames submitted.
    fn wait(&mut self) -> Result<()>;
    /// The target's colour as the last frame left it (RGBA8, bottom row first).
    fn read(&mut self) -> Result<Vec<u8>>;
    /// The executor's counters, for the side through `stratad`.
    fn stats(&mut self) -> Result<Option<strata_protocol::ExecStats>> {
        Ok(None)
    }
    /// Draws frames `range` and waits for them: the seconds it took.
    fn frames(&mut self, range: std::ops::Range<u32>, pb: Option<&ProgressBar>) -> Result<f64> {
        let start = std::time::Instant::now();
        for f in range {
            self.frame(f)?;
            if let Some(pb) = pb {
                pb.inc(1);
            }
        }
        self.wait()?;
        Ok(start.elapsed().as_secs_f64())
    }
    /// Frame `f` again, read back.
    fn image(&mut self, f: u32) -> Result<Vec<u8>> {
        self.frame(f)?;
        self.read()
    }
}

/// A native side's device and target: an RGBA8 colour image (read back at the end) and a depth
/// image, square, and the buffers and pipeline of the mesh drawn into them.
pub(crate) struct NativeTarget {
    pub(crate) gpu: std::sync::Arc<strata_device::Gpu>,
    color_tex: wgpu::Texture,
    color: wgpu::TextureView,
    depth: wgpu::TextureView,
    size: u32,
}

impl NativeTarget {
    /// A device of its own and a target of `size`².
    pub(crate) fn new(size: u32) -> Result<NativeTarget> {
        let gpu = strata_device::Gpu::open()?;
        let square = (size, size);
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let color_tex = gpu.texture_2d("execute colour", wgpu::TextureFormat::Rgba8Unorm, square, usage);
        let color = color_tex.create_view(&Default::default());
        let depth_format = wgpu::TextureFormat::Depth24PlusStencil8;
        let depth = gpu
            .texture_2d("execute depth", depth_format, square, wgpu::TextureUsages::RENDER_ATTACHMENT)
            .create_view(&Default::default());
        Ok(NativeTarget { gpu, color_tex, color, depth, size })
    }

    /// A buffer of `usage` holding `bytes`.
    pub(crate) fn buffer(&self, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        let b = self.gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: bytes.len() as u64,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.gpu.write_buffer(&b, 0, bytes);
        b
    }

    /// The pipeline drawing a mesh of positions and normals (`Float32x3` each, 24 bytes a
    /// vertex) with `vertex` and `fragment` (Strata's translation: clockwise front faces, as its
    /// y flip makes them) into the target, depth-tested.
    pub(crate) fn pipeline(
        &self,
        layout: &wgpu::PipelineLayout,
        vertex: naga::Module,
        fragment: naga::Module,
    ) -> wgpu::RenderPipeline {
        let d = &self.gpu.device;
        let module = |m: naga::Module| {
            d.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: None,
                source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(m)),
            })
        };
        let (vmod, fmod) = (module(vertex), module(fragment));
        let attrs = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
        d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: None,
            layout: Some(layout),
            vertex: wgpu::VertexState {
                module: &vmod,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 24,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &attrs,
                })],
            },
            primitive: wgpu::PrimitiveState { front_face: wgpu::FrontFace::Cw, ..Default::default() },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth24PlusStencil8,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &fmod,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::TextureFormat::Rgba8Unorm.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
    }

    /// One frame: the target cleared, `count` indices of `mesh` (vertex and index buffers)
    /// drawn `instances` times with `pipeline` and `group`, submitted.
    pub(crate) fn frame(
        &self,
        pipeline: &wgpu::RenderPipeline,
        group: &wgpu::BindGroup,
        mesh: (&wgpu::Buffer, &wgpu::Buffer),
        count: u32,
        instances: u32,
    ) {
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: None,
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.color,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth,
                    depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Store }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            rp.set_pipeline(pipeline);
            rp.set_bind_group(0, group, &[]);
            rp.set_vertex_buffer(0, mesh.0.slice(..));
            rp.set_index_buffer(mesh.1.slice(..), wgpu::IndexFormat::Uint32);
            rp.draw_indexed(0..count, 0, 0..instances);
        }
        self.gpu.submit(&self.gpu.lane, vec![enc.finish()]);
    }

    /// Waits for the frames submitted.
    pub(crate) fn wait(&self) -> Result<()> {
        self.gpu.device.poll(wgpu::PollType::Wait { submission_index: None, timeout: None })?;
        Ok(())
    }

    /// The target's colour, read back (RGBA8, bottom row first).
    pub(crate) fn image(&self) -> Result<Vec<u8>> {
        self.gpu
            .read_rgba8(&self.color_tex, [0, 0, self.size, self.size])
            .ok_or_else(|| anyhow::anyhow!("reading the frame back failed"))
    }
}

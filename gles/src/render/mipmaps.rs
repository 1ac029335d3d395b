//! Mipmap generation: each level drawn from the one above with a 2×2 box filter (2×2×2 for the
//! slices of a 3D image, `GL_OES_texture_3D`).

use crate::enums::*;
use crate::flushed::Flushed;
use crate::render::{Renderer, SamplerState};

impl Renderer {
    /// The mipmap pipeline for `format`, of 3D images with `three_d`, compiled once for all
    /// clients (each compile costs the driver memory it keeps).
    fn mip_pipeline(&self, format: wgpu::TextureFormat, three_d: bool) -> wgpu::RenderPipeline {
        let d = &self.gpu.device;
        let (module, bgl) = if three_d {
            (&self.fixed.mip3_module, &self.fixed.mip3_bgl)
        } else {
            (&self.fixed.mip_module, &self.fixed.mip_bgl)
        };
        let mut shared = self.fixed.mip_pipelines.lock().unwrap_or_else(|e| e.into_inner());
        shared
            .entry((format, three_d))
            .or_insert_with(|| {
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("mipmap"),
                    bind_group_layouts: &[Some(bgl)],
                    immediate_size: 0,
                });
                d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("mipmap"),
                    layout: Some(&layout),
                    vertex: wgpu::VertexState {
                        module,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &[Some(format.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            })
            .clone()
    }

    /// The bilinear sampler that takes the box filter, clamped to the edge.
    fn mip_sampler(&mut self) -> wgpu::Sampler {
        let linear = SamplerState {
            min: LINEAR,
            mag: LINEAR,
            wrap_s: CLAMP_TO_EDGE,
            wrap_t: CLAMP_TO_EDGE,
            wrap_r: CLAMP_TO_EDGE,
            ..SamplerState::default()
        };
        self.sampler(linear, false)
    }

    /// Fills levels 1.. of every face of a (filterable, renderable) `format` texture from level
    /// 0 with a 2×2 box filter, after the pending pass (`[Flush]`).
    pub fn generate_mipmaps(
        &mut self,
        _: &Flushed,
        tex: &wgpu::Texture,
        mips: u32,
        layers: u32,
        format: wgpu::TextureFormat,
    ) {
        let pipeline = self.mip_pipeline(format, false);
        let linear = self.mip_sampler();
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
                let group = self.mip_group(&self.fixed.mip_bgl, &src, &linear);
                strata_device::fullscreen_pass(&mut enc, "mipmap", &dst, &pipeline, &group);
            }
        }
        self.gpu.submit(&self.lane, vec![enc.finish()]);
    }

    /// Fills levels 1.. of a (filterable, renderable) `format` 3D texture from level 0, each
    /// slice with a 2×2×2 box filter, after the pending pass (`[Flush]`).
    pub fn generate_volume_mipmaps(
        &mut self,
        _: &Flushed,
        tex: &wgpu::Texture,
        mips: u32,
        format: wgpu::TextureFormat,
    ) {
        let pipeline = self.mip_pipeline(format, true);
        let linear = self.mip_sampler();
        let d = &self.gpu.device;
        let mut enc = d.create_command_encoder(&Default::default());
        for level in 1..mips {
            let view = |l: u32| {
                tex.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D3),
                    base_mip_level: l,
                    mip_level_count: Some(1),
                    ..Default::default()
                })
            };
            let (src, dst) = (view(level - 1), view(level));
            let group = self.mip_group(&self.fixed.mip3_bgl, &src, &linear);
            for slice in 0..(tex.depth_or_array_layers() >> level).max(1) {
                strata_device::fullscreen_pass_at(&mut enc, "mipmap 3d", (&dst, Some(slice)), &pipeline, &group);
            }
        }
        self.gpu.submit(&self.lane, vec![enc.finish()]);
    }

    /// The bind group of a mipmap draw reading `src` through `smp`.
    fn mip_group(
        &self,
        layout: &wgpu::BindGroupLayout,
        src: &wgpu::TextureView,
        smp: &wgpu::Sampler,
    ) -> wgpu::BindGroup {
        self.gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(src) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(smp) },
            ],
        })
    }
}

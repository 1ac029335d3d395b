//! Mipmap generation: each level drawn from the one above with a 2×2 box filter.

use super::super::dispatch::Flushed;
use super::super::enums::*;
use super::{Renderer, SamplerState};

impl Renderer {
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
        let d = &self.gpu.device;
        // Compiled once for all clients (each compile costs the driver memory it keeps).
        let mut shared = self.fixed.mip_pipelines.lock().unwrap_or_else(|e| e.into_inner());
        let pipeline = shared
            .entry(format)
            .or_insert_with(|| {
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("mipmap"),
                    bind_group_layouts: &[Some(&self.fixed.mip_bgl)],
                    immediate_size: 0,
                });
                d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("mipmap"),
                    layout: Some(&layout),
                    vertex: wgpu::VertexState {
                        module: &self.fixed.mip_module,
                        entry_point: Some("vs"),
                        compilation_options: Default::default(),
                        buffers: &[],
                    },
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &self.fixed.mip_module,
                        entry_point: Some("fs"),
                        compilation_options: Default::default(),
                        targets: &[Some(format.into())],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            })
            .clone();
        drop(shared);
        let linear = self.sampler(
            SamplerState {
                min: LINEAR,
                mag: LINEAR,
                wrap_s: CLAMP_TO_EDGE,
                wrap_t: CLAMP_TO_EDGE,
                ..SamplerState::default()
            },
            false,
        );
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
                    layout: &self.fixed.mip_bgl,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src) },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&linear) },
                    ],
                });
                crate::gpu::fullscreen_pass(&mut enc, "mipmap", &dst, &pipeline, &group);
            }
        }
        self.lane.submit(&self.gpu, vec![enc.finish()]);
    }
}

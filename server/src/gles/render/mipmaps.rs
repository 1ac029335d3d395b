//! Mipmap generation: each level drawn from the one above with a 2×2 box filter.

use super::super::enums::*;
use super::{Renderer, SamplerState};

/// Most destination pixels in one band of a level when a sliced client's mipmaps are
/// generated (each band is a slice of its own).
const MIP_BAND_PIXELS: u32 = 1 << 16;

impl Renderer {
    /// Fills levels 1.. of every face of a (filterable, renderable) `format` texture from level
    /// 0 with a 2×2 box filter.
    pub fn generate_mipmaps(&mut self, tex: &wgpu::Texture, mips: u32, layers: u32, format: wgpu::TextureFormat) {
        self.flush();
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
        let linear =
            self.sampler(SamplerState { min: LINEAR, mag: LINEAR, wrap_s: CLAMP_TO_EDGE, wrap_t: CLAMP_TO_EDGE });
        let d = &self.gpu.device;
        // A sliced client's levels go one band of rows at a time, each submitted in its turn.
        let sliced = self.lane.sliced();
        // A policy that forces pieces (a test of the image) cuts even small levels.
        let band_pixels = if self.lane.forced_pieces().is_some() { 16 } else { MIP_BAND_PIXELS };
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
                let (w, h) = ((tex.width() >> level).max(1), (tex.height() >> level).max(1));
                let bands = if sliced { (w * h).div_ceil(band_pixels).clamp(1, h) } else { 1 };
                let rows = h.div_ceil(bands);
                for y in (0..h).step_by(rows as usize) {
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
                    rp.set_scissor_rect(0, y, w, rows.min(h - y));
                    rp.draw(0..3, 0..1);
                    drop(rp);
                    if sliced {
                        let done = std::mem::replace(&mut enc, d.create_command_encoder(&Default::default()));
                        self.lane.submit(&self.gpu, vec![done.finish()], "a band of mipmap generation");
                    }
                }
            }
        }
        if !sliced {
            self.lane.submit(&self.gpu, vec![enc.finish()], "mipmap generation");
        }
    }
}

//! Depth images written from and read into plain floats: wgpu cannot copy into a depth aspect,
//! nor copy most depth formats out, so both go through a full-screen pass
//! (`shaders/depth_upload.wgsl`, `shaders/depth_read.wgsl`). A frame copied through host
//! memory, a depth texture's upload and a depth read all use them; the pipelines are built once
//! per device.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use strata_device::{texture_entry, Gpu, Lane, VertexInput, UNFILTERED};

/// One device's depth pipelines (`Depth::of`).
#[derive(Default)]
pub struct Depth {
    /// The pipeline that reads a depth image as floats, built on first use.
    reader: OnceLock<(wgpu::BindGroupLayout, wgpu::RenderPipeline)>,
    /// The pipelines that write depth values, one per depth format, built on first use.
    writers: Mutex<HashMap<wgpu::TextureFormat, (wgpu::BindGroupLayout, wgpu::RenderPipeline)>>,
}

impl Depth {
    /// `gpu`'s depth pipelines.
    pub fn of(gpu: &Gpu) -> DepthOn<'_> {
        Depth::for_lane(gpu, &gpu.lane)
    }

    /// `gpu`'s depth pipelines, their writes submitted as `lane`'s work.
    pub fn for_lane<'a>(gpu: &'a Gpu, lane: &'a Lane) -> DepthOn<'a> {
        DepthOn { gpu, lane, depth: gpu.shared(|_| Depth::default()) }
    }
}

/// [`Depth`] together with its device, for one use.
pub struct DepthOn<'a> {
    gpu: &'a Gpu,
    lane: &'a Lane,
    depth: Arc<Depth>,
}

impl DepthOn<'_> {
    /// The pipeline drawing a full-screen triangle that writes the depth image bound at 0
    /// into an R32Float target, and its bind group layout.
    pub fn reader(&self) -> (wgpu::BindGroupLayout, wgpu::RenderPipeline) {
        self.depth
            .reader
            .get_or_init(|| {
                self.gpu.pipeline(
                    "depth read",
                    wgpu::ShaderSource::Wgsl(include_str!("../../shaders/depth_read.wgsl").into()),
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

    /// Writes depth values (in [0, 1], rows in memory order) into a whole `width`×`height`
    /// depth texture.
    pub fn write(&self, tex: &wgpu::Texture, width: u32, height: u32, values: &[f32]) {
        self.write_region(tex, (0, 0), (width, height), [0, 0, width, height], values, None);
    }

    /// Writes depth values (in [0, 1], rows in memory order) into the rectangle `[x, y, w, h]`
    /// of array layer `layer` (a cube face) of mip level `level`, `width`×`height`, of a depth
    /// or depth-stencil texture, and stencil values (one byte per texel) if given. wgpu cannot copy into depth aspects, so the depths pass through a float
    /// texture and a scissored pass that sets `frag_depth`; stencil is copied directly.
    pub fn write_region(
        &self,
        tex: &wgpu::Texture,
        (layer, level): (u32, u32),
        size: (u32, u32),
        rect: [u32; 4],
        depths: &[f32],
        stencil: Option<&[u8]>,
    ) {
        let [x, y, w, h] = rect;
        if w == 0 || h == 0 {
            return;
        }
        let gpu = self.gpu;
        let d = &gpu.device;
        let format = tex.format();
        let (bgl, pipeline) = {
            let mut writers = self.depth.writers.lock().unwrap_or_else(|e| e.into_inner());
            writers
                .entry(format)
                .or_insert_with(|| {
                    gpu.pipeline(
                        "depth upload",
                        wgpu::ShaderSource::Wgsl(include_str!("../../shaders/depth_upload.wgsl").into()),
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
        gpu.write_texture(
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
            base_mip_level: level,
            mip_level_count: Some(1),
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
        gpu.submit(self.lane, vec![enc.finish()]);
        if let Some(s) = stencil.filter(|_| format.has_stencil_aspect()) {
            gpu.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: tex,
                    mip_level: level,
                    origin: wgpu::Origin3d { x, y, z: layer },
                    aspect: wgpu::TextureAspect::StencilOnly,
                },
                s,
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(w), rows_per_image: None },
                extent,
            );
        }
    }
}

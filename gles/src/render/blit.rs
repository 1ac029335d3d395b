//! `glBlitFramebuffer`'s colour copy as a draw: the source level copied aside (so that a blit
//! within one image reads what was there before), then each destination buffer drawn over the
//! clipped destination rectangle by a fragment shader that samples the source at the point
//! each pixel's centre maps to, nearest or linear (`shaders/framebuffer_blit.wgsl`).

use crate::enums::*;
use crate::flushed::Flushed;
use crate::objects::image::Subresource;
use crate::render::{Renderer, SamplerState};

/// One colour blit: where it reads, where it writes, and how the rectangles map.
pub struct Blit<'a> {
    /// The source image, the level and layer read, and that level's size.
    pub src: (&'a wgpu::Texture, Subresource, (u32, u32)),
    /// Each destination buffer: its view, format, the channels it writes and the 3D slice it
    /// shows.
    pub dst: Vec<(&'a wgpu::TextureView, wgpu::TextureFormat, wgpu::ColorWrites, Option<u32>)>,
    /// The source rectangle's corners as given (x0, y0, x1, y1).
    pub src_rect: [i32; 4],
    /// The destination rectangle's corners as given.
    pub dst_rect: [i32; 4],
    /// The destination pixels written: x, y, width, height (clipped, and scissored).
    pub clip: [u32; 4],
    /// `GL_LINEAR` filtering (else nearest).
    pub linear: bool,
}

/// What a blit's source holds, which decides its shader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Source {
    /// Filterable floats (normalized, half-float, packed float, and 32-bit float where the
    /// device filters it): sampled.
    Float,
    /// Unsigned integers: fetched.
    Uint,
    /// Signed integers: fetched.
    Sint,
    /// 32-bit floats the device cannot filter, nearest: fetched.
    UnfilterableNearest,
    /// 32-bit floats the device cannot filter, linear: four texels fetched and weighed as a
    /// linear filter weighs them.
    UnfilterableLinear,
}

impl Source {
    /// The kind of a source of `format` on a device with `features`, read with a linear
    /// filter or not.
    fn of(format: wgpu::TextureFormat, features: wgpu::Features, linear: bool) -> Source {
        match format.sample_type(None, Some(features)) {
            Some(wgpu::TextureSampleType::Sint) => Source::Sint,
            Some(wgpu::TextureSampleType::Uint) => Source::Uint,
            Some(wgpu::TextureSampleType::Float { filterable: false }) if linear => Source::UnfilterableLinear,
            Some(wgpu::TextureSampleType::Float { filterable: false }) => Source::UnfilterableNearest,
            _ => Source::Float,
        }
    }

    /// Its slot among the shaders and in the pipelines' key.
    fn slot(self) -> usize {
        self as usize
    }
}

impl Renderer {
    /// The blit shader and layout for a source of `kind`, made once.
    fn blit_shader(&self, kind: Source) -> &(wgpu::ShaderModule, wgpu::BindGroupLayout) {
        let slot = &self.fixed.blit[kind.slot()];
        slot.get_or_init(|| {
            let d = &self.gpu.device;
            let source = include_str!("../../../shaders/framebuffer_blit.wgsl");
            let source = match kind {
                Source::Float => source.to_string(),
                Source::Uint => int_blit_source(source, "u32"),
                Source::Sint => int_blit_source(source, "i32"),
                Source::UnfilterableNearest => int_blit_source(source, "f32"),
                Source::UnfilterableLinear => unfilterable_linear_source(source),
            };
            let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("blit"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty,
                count: None,
            };
            let texture = wgpu::BindingType::Texture {
                sample_type: match kind {
                    Source::Float => wgpu::TextureSampleType::Float { filterable: true },
                    Source::Sint => wgpu::TextureSampleType::Sint,
                    Source::Uint => wgpu::TextureSampleType::Uint,
                    Source::UnfilterableNearest | Source::UnfilterableLinear => {
                        wgpu::TextureSampleType::Float { filterable: false }
                    }
                },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            };
            let uniform = wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            };
            let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("blit"),
                entries: &[
                    entry(0, texture),
                    entry(
                        1,
                        wgpu::BindingType::Sampler(match kind {
                            Source::Float => wgpu::SamplerBindingType::Filtering,
                            _ => wgpu::SamplerBindingType::NonFiltering,
                        }),
                    ),
                    entry(2, uniform),
                ],
            });
            (module, bgl)
        })
    }

    /// The blit pipeline from a source of `kind` writing the `writes` channels of `format`,
    /// compiled once for all clients.
    fn blit_pipeline(
        &self,
        kind: Source,
        format: wgpu::TextureFormat,
        writes: wgpu::ColorWrites,
    ) -> wgpu::RenderPipeline {
        let (module, bgl) = self.blit_shader(kind);
        let mut shared = self.fixed.blit_pipelines.lock().unwrap_or_else(|e| e.into_inner());
        shared
            .entry((format, writes.bits(), kind.slot()))
            .or_insert_with(|| {
                let d = &self.gpu.device;
                let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                    label: Some("blit"),
                    bind_group_layouts: &[Some(bgl)],
                    immediate_size: 0,
                });
                d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("blit"),
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
                        targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: writes })],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
            })
            .clone()
    }

    /// The multisample image `src` resolved (each pixel's samples averaged) into a new
    /// single-sample image of its size and format, after the pending pass (`[Flush]`).
    pub fn resolve(&mut self, _: &Flushed, src: &wgpu::Texture) -> wgpu::Texture {
        let d = &self.gpu.device;
        let size = src.size();
        let resolved = d.create_texture(&wgpu::TextureDescriptor {
            label: Some("resolved"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: src.format(),
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = src.create_view(&Default::default());
        let target = resolved.create_view(&Default::default());
        let mut enc = d.create_command_encoder(&Default::default());
        enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("resolve"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: Some(&target),
                ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.gpu.submit(&self.lane, vec![enc.finish()]);
        resolved
    }

    /// Draws blit `b` into each of its destination buffers, after the pending pass (`[Flush]`).
    pub fn blit(&mut self, _: &Flushed, b: &Blit<'_>) {
        let [x, y, w, h] = b.clip;
        if w == 0 || h == 0 || b.dst.is_empty() {
            return;
        }
        let (tex, at, (sw, sh)) = b.src;
        let d = &self.gpu.device;
        // The source level, copied aside.
        let copy = d.create_texture(&wgpu::TextureDescriptor {
            label: Some("blit source"),
            size: wgpu::Extent3d { width: sw, height: sh, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: tex.format(),
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let mut enc = d.create_command_encoder(&Default::default());
        enc.copy_texture_to_texture(
            wgpu::TexelCopyTextureInfo {
                texture: tex,
                mip_level: at.level,
                origin: wgpu::Origin3d { x: 0, y: 0, z: at.layer },
                aspect: wgpu::TextureAspect::All,
            },
            copy.as_image_copy(),
            wgpu::Extent3d { width: sw, height: sh, depth_or_array_layers: 1 },
        );
        let [sx0, sy0, sx1, sy1] = b.src_rect.map(|v| v as f32);
        let [dx0, dy0, dx1, dy1] = b.dst_rect.map(|v| v as f32);
        let params: [f32; 8] = [
            dx0,
            dy0,
            (sx1 - sx0) / (dx1 - dx0),
            (sy1 - sy0) / (dy1 - dy0),
            sx0,
            sy0,
            1.0 / sw as f32,
            1.0 / sh as f32,
        ];
        let buffer = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("blit parameters"),
            size: 32,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.gpu.write_buffer(&buffer, 0, bytemuck::cast_slice(&params));
        let kind = Source::of(tex.format(), self.gpu.features, b.linear);
        // An unfilterable source is fetched (its linear filter computed in the shader).
        let filter = if b.linear && kind == Source::Float { LINEAR } else { NEAREST };
        let state = SamplerState {
            min: filter,
            mag: filter,
            wrap_s: CLAMP_TO_EDGE,
            wrap_t: CLAMP_TO_EDGE,
            wrap_r: CLAMP_TO_EDGE,
            ..SamplerState::default()
        };
        let sampler = self.sampler(state, false);
        let view = copy.create_view(&Default::default());
        let (_, bgl) = self.blit_shader(kind);
        let group = self.gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("blit"),
            layout: bgl,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&view) },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&sampler) },
                wgpu::BindGroupEntry { binding: 2, resource: buffer.as_entire_binding() },
            ],
        });
        for &(target, format, writes, slice) in &b.dst {
            let pipeline = self.blit_pipeline(kind, format, writes);
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("blit"),
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
            rp.set_pipeline(&pipeline);
            rp.set_bind_group(0, &group, &[]);
            rp.set_scissor_rect(x, y, w, h);
            rp.draw(0..3, 0..1);
        }
        self.gpu.submit(&self.lane, vec![enc.finish()]);
    }
}

/// The blit shader for texels of `scalar` (`i32` or `u32`, or `f32` for floats the device
/// cannot filter): the nearest texel fetched, as integer images are never filtered.
fn int_blit_source(source: &str, scalar: &str) -> String {
    let body_at = source.find("@fragment").unwrap_or(source.len());
    let head = source[..body_at].replace("texture_2d<f32>", &format!("texture_2d<{scalar}>"));
    format!(
        "{head}@fragment
fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<{scalar}> {{
    let s = p.src0 + (pos.xy - p.dst0) * p.scale;
    let size = vec2<i32>(textureDimensions(src));
    return textureLoad(src, clamp(vec2<i32>(floor(s)), vec2<i32>(0), size - 1), 0);
}}
"
    )
}

/// The blit shader for 32-bit floats the device cannot filter, with a linear filter: the four
/// texels around the point fetched (clamped to the edge) and weighed bilinearly.
fn unfilterable_linear_source(source: &str) -> String {
    let body_at = source.find("@fragment").unwrap_or(source.len());
    format!(
        "{}@fragment
fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {{
    let s = p.src0 + (pos.xy - p.dst0) * p.scale - vec2<f32>(0.5);
    let size = vec2<i32>(textureDimensions(src));
    let i = vec2<i32>(floor(s));
    let f = s - floor(s);
    let lo = vec2<i32>(0);
    let hi = size - 1;
    let a = textureLoad(src, clamp(i, lo, hi), 0);
    let b = textureLoad(src, clamp(i + vec2<i32>(1, 0), lo, hi), 0);
    let c = textureLoad(src, clamp(i + vec2<i32>(0, 1), lo, hi), 0);
    let d = textureLoad(src, clamp(i + vec2<i32>(1, 1), lo, hi), 0);
    return mix(mix(a, b, f.x), mix(c, d, f.x), f.y);
}}
",
        &source[..body_at]
    )
}

//! Pipelines and their inputs: bind group layouts (with variants for depth textures), the
//! sampler cache, and the render pipeline cache keyed by program, vertex layout, fixed-function
//! state and target formats.

use crate::conv::{front_face, sampler_descriptor};
use crate::objects::program::layout_entries;
use crate::render::keys::PipelineKey;
use crate::render::{DrawSpec, LinkedProgram, Renderer, SamplerState, Target};

impl Renderer {
    /// The sampler for `s`, cached.
    pub(super) fn sampler(&mut self, s: SamplerState, white: bool) -> wgpu::Sampler {
        if let Some(x) = self.samplers.get(&(s, white)) {
            return x.clone();
        }
        let x = self.gpu.device.create_sampler(&sampler_descriptor(s, white));
        self.samplers.insert((s, white), x.clone());
        x
    }

    /// The bind group and pipeline layouts of `program` with the samplers in `mask` taking
    /// unfilterable images.
    pub(super) fn layouts(
        &mut self,
        program: &LinkedProgram,
        mask: u32,
    ) -> (wgpu::BindGroupLayout, wgpu::PipelineLayout) {
        if mask == 0 {
            return (program.bgl.clone(), program.layout.clone());
        }
        let d = &self.gpu.device;
        self.layouts
            .entry((program.id, mask))
            .or_insert_with(|| {
                let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("gles unfilterable-sampling"),
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

    /// The render pipeline for a draw of `spec` into `target`, cached.
    pub(super) fn pipeline(&mut self, spec: &DrawSpec<'_>, target: &Target, depth_mask: u32) -> wgpu::RenderPipeline {
        let key = PipelineKey {
            program: spec.program.id,
            depth_mask,
            inputs: spec.inputs.iter().map(|i| (i.location, i.format, i.stride, i.per_instance)).collect(),
            raster: spec.raster.clone(),
            colors: target.slots().iter().map(|s| s.map(|s| (s.1, s.2))).collect(),
            depth_format: target.depth.as_ref().map(|d| d.1),
            samples: target.samples,
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
                    step_mode: if i.stride == 0 || i.per_instance || spec.raster.points {
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
                Some((factor, units, clamp)) => wgpu::DepthBiasState {
                    constant: units,
                    slope_scale: f32::from_bits(factor),
                    clamp: f32::from_bits(clamp),
                },
                None => Default::default(),
            },
        });
        // Every slot blends alike (ES 2.0 has one blend state); channels an image lacks are
        // never written.
        let targets: Vec<Option<wgpu::ColorTargetState>> = key
            .colors
            .iter()
            .map(|s| {
                s.map(|(absent, format)| wgpu::ColorTargetState {
                    format,
                    // Integer colour buffers are never blended (ES 3.0 §4.1.7), nor 32-bit
                    // float ones where the device cannot blend them (GL_EXT_float_blend is then
                    // not offered).
                    blend: r.blend.filter(|_| {
                        matches!(format.sample_type(None, None), Some(wgpu::TextureSampleType::Float { .. }))
                            && format
                                .guaranteed_format_features(self.gpu.features)
                                .flags
                                .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE)
                    }),
                    write_mask: r.write_mask - absent,
                })
            })
            .collect();
        let p = self.gpu.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("gles"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &spec.vs,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                buffers: &layouts,
            },
            primitive: wgpu::PrimitiveState {
                topology: r.topology,
                strip_index_format: r.strip_index,
                front_face: front_face(r.front_ccw != r.clip.upper_left),
                cull_mode: r.cull,
                unclipped_depth: r.unclipped_depth,
                polygon_mode: wgpu::PolygonMode::Fill,
                conservative: false,
            },
            depth_stencil,
            multisample: wgpu::MultisampleState {
                count: key.samples,
                mask: r.coverage_mask,
                alpha_to_coverage_enabled: r.alpha_to_coverage,
            },
            fragment: Some(wgpu::FragmentState {
                module: spec.fs.as_ref().unwrap_or(&spec.program.fs),
                entry_point: Some("main"),
                compilation_options: Default::default(),
                targets: if key.colors.iter().any(Option::is_some) { &targets } else { &[] },
            }),
            multiview_mask: None,
            cache: None,
        });
        self.pipelines.insert(key, p.clone());
        p
    }
}

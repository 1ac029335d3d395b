//! The 3D compositor (the thesis' "root surface", §4.5–4.6): every surface's colour and depth
//! are combined into one output image. Surfaces are grouped by z and the groups drawn far
//! (larger z) to near. Within a group each output fragment takes the surface with the nearest
//! depth; on equal depth the surface later in stacking order wins. Outside its rectangle a
//! surface has no fragment. The selected colour (straight alpha) is lit, premultiplied, and
//! blended over what lies beneath.
//!
//! A pass can sample at most `m` textures; a surface needs two (colour and depth), so one pass
//! takes `p = ⌊m/2⌋` surfaces. Larger groups are chained: each further pass takes the previous
//! pass's intermediate (the selected colour, RGBA8, and its depth and normal, f32) plus `p − 1`
//! new surfaces. Because an intermediate holds exactly what a single pass would have selected,
//! and lighting runs only in the last pass, a chain is bit-identical to one pass.

pub mod reference;

use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::Arc;

use crate::gpu::Gpu;

pub use strata_protocol::control::{Lighting, NormalSource};

/// One surface to composite.
pub struct Layer<'a> {
    /// x, y (from the output's top), width, height in output pixels.
    pub rect: [i32; 4],
    /// Depth layer: larger is farther; equal values form one group.
    pub z: f32,
    /// Colour (RGBA8, rows in GL order: bottom first).
    pub color: &'a wgpu::TextureView,
    /// Depth (a depth format, same size), or `None`: depth 1 everywhere.
    pub depth: Option<&'a wgpu::TextureView>,
    /// The surface's normal for `NormalSource::PerSurface`.
    pub normal: [f32; 3],
}

/// A compositor configuration the device cannot honour.
#[derive(Debug, thiserror::Error)]
pub enum CompositorError {
    /// Fewer than 4 textures per pass cannot chain (intermediate + one new surface).
    #[error("--max-textures {0} is too small: chaining needs at least 4 (the intermediate's colour and depth plus one surface's)")]
    TooFewTextures(u32),
    /// More textures than the device samples per stage.
    #[error("--max-textures {requested} exceeds the device's limit of {device} sampled textures per shader stage")]
    ExceedsDevice {
        /// Requested.
        requested: u32,
        /// The device's limit.
        device: u32,
    },
}

#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct PassKind {
    surfaces: usize,
    intermediate: bool,
    last: bool,
    lit: bool,
    from_depth: bool,
}

const GEOM_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// Intermediate depth meaning "no fragment here".
const EMPTY: f64 = 4.0;

/// The GPU compositor.
pub struct Compositor {
    gpu: Arc<Gpu>,
    per_pass: usize,
    max_textures: u32,
    pipelines: HashMap<PassKind, (wgpu::BindGroupLayout, wgpu::RenderPipeline)>,
    dummy_depth: wgpu::TextureView,
    /// Passes drawn by the last `composite`.
    pub last_passes: usize,
}

/// WGSL for one pass shape.
fn shader(k: &PassKind) -> String {
    let n = k.surfaces;
    let mut s = String::new();
    let _ = writeln!(s, "struct Surf {{ rect: vec4<f32>, normal: vec4<f32>, }};");
    let _ = writeln!(
        s,
        "struct Params {{ light_pos: vec4<f32>, light_color: vec4<f32>, view_pos: vec4<f32>, misc: vec4<f32>, surf: array<Surf, {n}>, }};"
    );
    let _ = writeln!(s, "@group(0) @binding(0) var<uniform> P: Params;");
    for i in 0..n {
        let _ = writeln!(s, "@group(0) @binding({}) var color{i}: texture_2d<f32>;", 1 + 2 * i);
        let _ = writeln!(s, "@group(0) @binding({}) var depth{i}: texture_depth_2d;", 2 + 2 * i);
    }
    if k.intermediate {
        let _ = writeln!(s, "@group(0) @binding({}) var icolor: texture_2d<f32>;", 1 + 2 * n);
        let _ = writeln!(s, "@group(0) @binding({}) var igeom: texture_2d<f32>;", 2 + 2 * n);
    }
    s.push_str(
        "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {\n    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));\n    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);\n}\n",
    );
    if k.from_depth {
        for i in 0..n {
            let _ = write!(
                s,
                "fn dn{i}(p: vec2<i32>, size: vec2<i32>) -> vec3<f32> {{
    let x0 = max(p.x - 1, 0); let x1 = min(p.x + 1, size.x - 1);
    let y0 = max(p.y - 1, 0); let y1 = min(p.y + 1, size.y - 1);
    var dzdx = 0.0; var dzdy = 0.0;
    if (x1 > x0) {{ dzdx = (textureLoad(depth{i}, vec2<i32>(x1, p.y), 0) - textureLoad(depth{i}, vec2<i32>(x0, p.y), 0)) / f32(x1 - x0); }}
    if (y1 > y0) {{ dzdy = (textureLoad(depth{i}, vec2<i32>(p.x, y1), 0) - textureLoad(depth{i}, vec2<i32>(p.x, y0), 0)) / f32(y1 - y0); }}
    return normalize(vec3<f32>(-dzdx * P.light_color.w, -dzdy * P.light_color.w, 1.0));
}}
"
            );
        }
    }
    if k.last && k.lit {
        s.push_str(
            "fn light(c: vec3<f32>, n_raw: vec3<f32>, frag_px: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(0.0);
    if (length(n_raw) > 0.0) { n = normalize(n_raw); }
    let frag = vec3<f32>(frag_px.x / P.misc.z * 2.0 - 1.0, 1.0 - frag_px.y / P.misc.w * 2.0, 0.0);
    let ld = normalize(P.light_pos.xyz - frag);
    let vd = normalize(P.view_pos.xyz - frag);
    let diffuse = max(dot(n, ld), 0.0);
    let r = reflect(-ld, n);
    let base = max(dot(vd, r), 0.0);
    var specular = 1.0;
    if (P.misc.y != 0.0) { specular = pow(base, P.misc.y); }
    let f = P.misc.x + diffuse + specular;
    return clamp(c * f * P.light_color.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
}
",
        );
    }
    if k.last {
        s.push_str("@fragment fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {\n");
    } else {
        s.push_str("struct Out { @location(0) color: vec4<f32>, @location(1) geom: vec4<f32>, };\n");
        s.push_str("@fragment fn fs(@builtin(position) pos: vec4<f32>) -> Out {\n");
    }
    let _ = writeln!(s, "    let px = vec2<i32>(floor(pos.xy));\n    var best_d: f32 = {EMPTY:.1};\n    var best_c = vec4<f32>(0.0);\n    var best_n = vec3<f32>(0.0, 0.0, 1.0);\n    var found = false;");
    if k.intermediate {
        s.push_str("    let g = textureLoad(igeom, px, 0);\n    if (g.x < 2.0) { best_d = g.x; best_c = textureLoad(icolor, px, 0); best_n = g.yzw; found = true; }\n");
    }
    for i in 0..n {
        let normal = if k.from_depth {
            format!("if (has_depth) {{ best_n = dn{i}(sp, size); }} else {{ best_n = vec3<f32>(0.0, 0.0, 1.0); }}")
        } else {
            format!("best_n = P.surf[{i}].normal.xyz;")
        };
        let _ = write!(
            s,
            "    {{
        let r = P.surf[{i}].rect;
        let l = vec2<i32>(px.x - i32(r.x), px.y - i32(r.y));
        let size = vec2<i32>(i32(r.z), i32(r.w));
        if (l.x >= 0 && l.y >= 0 && l.x < size.x && l.y < size.y) {{
            let sp = vec2<i32>(l.x, size.y - 1 - l.y);
            let has_depth = P.surf[{i}].normal.w > 0.5;
            var d: f32 = 1.0;
            if (has_depth) {{ d = textureLoad(depth{i}, sp, 0); }}
            if (d <= best_d) {{
                best_d = d;
                best_c = textureLoad(color{i}, sp, 0);
                {normal}
                found = true;
            }}
        }}
    }}
"
        );
    }
    s.push_str("    if (!found) { discard; }\n");
    if k.last {
        if k.lit {
            s.push_str("    let rgb = light(best_c.rgb, best_n, pos.xy);\n");
        } else {
            s.push_str("    let rgb = best_c.rgb;\n");
        }
        s.push_str("    return vec4<f32>(rgb * best_c.a, best_c.a);\n}\n");
    } else {
        s.push_str(
            "    var o: Out;\n    o.color = best_c;\n    o.geom = vec4<f32>(best_d, best_n);\n    return o;\n}\n",
        );
    }
    s
}

impl Compositor {
    /// A compositor sampling at most `max_textures` textures per pass (default: the device's
    /// limit). At least 4 are needed to chain.
    pub fn new(gpu: Arc<Gpu>, max_textures: Option<u32>) -> Result<Compositor, CompositorError> {
        let device = gpu.limits.max_sampled_textures_per_shader_stage;
        let m = max_textures.unwrap_or(device);
        if m < 4 {
            return Err(CompositorError::TooFewTextures(m));
        }
        if m > device {
            return Err(CompositorError::ExceedsDevice { requested: m, device });
        }
        let d = &gpu.device;
        let tex = |format, label| {
            d.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
                view_formats: &[],
            })
            .create_view(&Default::default())
        };
        Ok(Compositor {
            dummy_depth: tex(wgpu::TextureFormat::Depth32Float, "no depth"),
            gpu,
            per_pass: (m / 2) as usize,
            max_textures: m,
            pipelines: HashMap::new(),
            last_passes: 0,
        })
    }

    /// The texture limit in force.
    pub fn max_textures(&self) -> u32 {
        self.max_textures
    }

    /// Passes a group of `k` surfaces takes: `1 + ⌈(k − p)/(p − 1)⌉` beyond `p`.
    pub fn passes(&self, k: usize) -> usize {
        let p = self.per_pass;
        if k <= p {
            1
        } else {
            1 + (k - p).div_ceil(p - 1)
        }
    }

    fn pipeline(&mut self, k: PassKind) -> (wgpu::BindGroupLayout, wgpu::RenderPipeline) {
        if let Some(p) = self.pipelines.get(&k) {
            return p.clone();
        }
        let d = &self.gpu.device;
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("compositor"),
            source: wgpu::ShaderSource::Wgsl(shader(&k).into()),
        });
        let vis = wgpu::ShaderStages::FRAGMENT;
        let float = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: vis,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let mut entries = vec![wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: vis,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }];
        for i in 0..k.surfaces as u32 {
            entries.push(float(1 + 2 * i));
            entries.push(wgpu::BindGroupLayoutEntry {
                binding: 2 + 2 * i,
                visibility: vis,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Depth,
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            });
        }
        if k.intermediate {
            let n = k.surfaces as u32;
            entries.push(float(1 + 2 * n));
            entries.push(float(2 + 2 * n));
        }
        let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("compositor"),
            entries: &entries,
        });
        let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        let over = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        };
        let last = [Some(wgpu::ColorTargetState {
            format: COLOR_FORMAT,
            blend: Some(wgpu::BlendState { color: over, alpha: over }),
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let mid = [Some(COLOR_FORMAT.into()), Some(GEOM_FORMAT.into())];
        let pipeline = d.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("compositor"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs"),
                compilation_options: Default::default(),
                targets: if k.last { &last } else { &mid },
            }),
            multiview_mask: None,
            cache: None,
        });
        self.pipelines.insert(k, (bgl.clone(), pipeline.clone()));
        (bgl, pipeline)
    }

    fn intermediate(&self, w: u32, h: u32) -> [(wgpu::Texture, wgpu::TextureView); 2] {
        [COLOR_FORMAT, GEOM_FORMAT].map(|format| {
            let t = self.gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("compositor intermediate"),
                size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            });
            let v = t.create_view(&Default::default());
            (t, v)
        })
    }

    /// Composites `layers` (in stacking order) into `output` (RGBA8, render-attachment usage),
    /// over `background` (straight alpha).
    pub fn composite(&mut self, layers: &[Layer<'_>], light: &Lighting, output: &wgpu::Texture, background: [f32; 4]) {
        let (w, h) = (output.width(), output.height());
        let out_view = output.create_view(&Default::default());
        let d = self.gpu.device.clone();
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("composite") });
        let a = f64::from(background[3]);
        enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("background"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &out_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: f64::from(background[0]) * a,
                        g: f64::from(background[1]) * a,
                        b: f64::from(background[2]) * a,
                        a,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let mut zs: Vec<f32> = layers.iter().map(|l| l.z).filter(|z| z.is_finite()).collect();
        zs.sort_by(|a, b| b.total_cmp(a));
        zs.dedup();
        let mut passes = 0;
        let mut spare: Option<[(wgpu::Texture, wgpu::TextureView); 2]> = None;
        for z in zs {
            let group: Vec<&Layer<'_>> = layers.iter().filter(|l| l.z == z).collect();
            let p = self.per_pass;
            let mut chunks: Vec<&[&Layer<'_>]> = vec![&group[..group.len().min(p)]];
            let mut rest = &group[group.len().min(p)..];
            while !rest.is_empty() {
                let take = rest.len().min(p - 1);
                chunks.push(&rest[..take]);
                rest = &rest[take..];
            }
            let mut prev: Option<[(wgpu::Texture, wgpu::TextureView); 2]> = None;
            for (ci, chunk) in chunks.iter().enumerate() {
                let last = ci + 1 == chunks.len();
                let kind = PassKind {
                    surfaces: chunk.len(),
                    intermediate: prev.is_some(),
                    last,
                    lit: light.enabled,
                    from_depth: light.normals == NormalSource::FromDepth,
                };
                let (bgl, pipeline) = self.pipeline(kind);
                // Parameters.
                let mut params: Vec<f32> = Vec::with_capacity(16 + 8 * chunk.len());
                params.extend_from_slice(&[light.position[0], light.position[1], light.position[2], 0.0]);
                params.extend_from_slice(&[light.color[0], light.color[1], light.color[2], light.depth_normal_scale]);
                params.extend_from_slice(&[light.view[0], light.view[1], light.view[2], 0.0]);
                params.extend_from_slice(&[light.ambient, light.shininess, w as f32, h as f32]);
                for l in chunk.iter() {
                    params.extend_from_slice(&[l.rect[0] as f32, l.rect[1] as f32, l.rect[2] as f32, l.rect[3] as f32]);
                    params.extend_from_slice(&[
                        l.normal[0],
                        l.normal[1],
                        l.normal[2],
                        if l.depth.is_some() { 1.0 } else { 0.0 },
                    ]);
                }
                let ubuf = d.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("compositor params"),
                    size: (params.len() * 4) as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.gpu.queue.write_buffer(&ubuf, 0, bytemuck::cast_slice(&params));
                let mut entries = vec![wgpu::BindGroupEntry { binding: 0, resource: ubuf.as_entire_binding() }];
                for (i, l) in chunk.iter().enumerate() {
                    let i = i as u32;
                    entries.push(wgpu::BindGroupEntry {
                        binding: 1 + 2 * i,
                        resource: wgpu::BindingResource::TextureView(l.color),
                    });
                    entries.push(wgpu::BindGroupEntry {
                        binding: 2 + 2 * i,
                        resource: wgpu::BindingResource::TextureView(l.depth.unwrap_or(&self.dummy_depth)),
                    });
                }
                if let Some(pv) = &prev {
                    let n = chunk.len() as u32;
                    entries.push(wgpu::BindGroupEntry {
                        binding: 1 + 2 * n,
                        resource: wgpu::BindingResource::TextureView(&pv[0].1),
                    });
                    entries.push(wgpu::BindGroupEntry {
                        binding: 2 + 2 * n,
                        resource: wgpu::BindingResource::TextureView(&pv[1].1),
                    });
                }
                let group_bind =
                    d.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout: &bgl, entries: &entries });
                let target = if last {
                    None
                } else {
                    Some(
                        spare
                            .take()
                            .filter(|s| s[0].0.width() == w && s[0].0.height() == h)
                            .unwrap_or_else(|| self.intermediate(w, h)),
                    )
                };
                {
                    let attachments: Vec<Option<wgpu::RenderPassColorAttachment<'_>>> = match &target {
                        None => vec![Some(wgpu::RenderPassColorAttachment {
                            view: &out_view,
                            depth_slice: None,
                            resolve_target: None,
                            ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                        })],
                        Some(t) => vec![
                            Some(wgpu::RenderPassColorAttachment {
                                view: &t[0].1,
                                depth_slice: None,
                                resolve_target: None,
                                ops: wgpu::Operations {
                                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                                    store: wgpu::StoreOp::Store,
                                },
                            }),
                            Some(wgpu::RenderPassColorAttachment {
                                view: &t[1].1,
                                depth_slice: None,
                                resolve_target: None,
                                ops: wgpu::Operations {
                                    load: wgpu::LoadOp::Clear(wgpu::Color { r: EMPTY, g: 0.0, b: 0.0, a: 0.0 }),
                                    store: wgpu::StoreOp::Store,
                                },
                            }),
                        ],
                    };
                    let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                        label: Some("composite pass"),
                        color_attachments: &attachments,
                        depth_stencil_attachment: None,
                        timestamp_writes: None,
                        occlusion_query_set: None,
                        multiview_mask: None,
                    });
                    rp.set_pipeline(&pipeline);
                    rp.set_bind_group(0, &group_bind, &[]);
                    rp.draw(0..3, 0..1);
                }
                passes += 1;
                // The pass just written becomes the next one's input; the old input is reused.
                if let Some(old) = prev.take() {
                    spare = Some(old);
                }
                prev = target;
            }
        }
        self.gpu.queue.submit([enc.finish()]);
        self.last_passes = passes;
    }
}

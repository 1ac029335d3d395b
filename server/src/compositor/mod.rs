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
    /// The background fill of partial composites, built on first use.
    fill: Option<(wgpu::BindGroupLayout, wgpu::RenderPipeline)>,
    /// Passes drawn by the last `composite`.
    pub last_passes: usize,
}

/// The pass shader's template (`shaders/composite.wgsl`).
const TEMPLATE: &str = include_str!("../../../shaders/composite.wgsl");

impl PassKind {
    /// Whether the pass has the template property `name`.
    fn has(&self, name: &str) -> bool {
        match name {
            "intermediate" => self.intermediate,
            "last" => self.last,
            "lit" => self.lit,
            "from_depth" => self.from_depth,
            other => unreachable!("shaders/composite.wgsl names an unknown property {other:?}"),
        }
    }
}

/// Renders template lines from `*pos` up to the matching `//#end` (or the end) into `out`,
/// keeping them when `keep`; `surface` is the surface of an enclosing `//#each surface`.
fn render(lines: &[&str], pos: &mut usize, keep: bool, surface: Option<usize>, k: &PassKind, out: &mut String) {
    while let Some(line) = lines.get(*pos) {
        *pos += 1;
        let directive = line.trim();
        if directive == "//#end" {
            return;
        }
        if let Some(cond) = directive.strip_prefix("//#if ") {
            let on = match cond.strip_prefix('!') {
                Some(name) => !k.has(name),
                None => k.has(cond),
            };
            render(lines, pos, keep && on, surface, k, out);
        } else if directive == "//#each surface" {
            let body = *pos;
            render(lines, pos, false, surface, k, out);
            if keep {
                for i in 0..k.surfaces {
                    let mut p = body;
                    render(lines, &mut p, true, Some(i), k, out);
                }
            }
        } else if keep && !directive.starts_with("//") {
            // Comment lines document the template; the specialised shader leaves them out.
            let mut l = line.replace("{{N}}", &k.surfaces.to_string()).replace("{{EMPTY}}", &format!("{EMPTY:.1}"));
            l = l
                .replace("{{icolor_binding}}", &(1 + 2 * k.surfaces).to_string())
                .replace("{{igeom_binding}}", &(2 + 2 * k.surfaces).to_string());
            if let Some(i) = surface {
                l = l
                    .replace("{{i}}", &i.to_string())
                    .replace("{{color_binding}}", &(1 + 2 * i).to_string())
                    .replace("{{depth_binding}}", &(2 + 2 * i).to_string());
            }
            out.push_str(&l);
            out.push('\n');
        }
    }
}

/// WGSL for one pass shape: the template specialised.
fn shader(k: &PassKind) -> String {
    let lines: Vec<&str> = TEMPLATE.lines().collect();
    let mut out = String::with_capacity(TEMPLATE.len() * 2);
    render(&lines, &mut 0, true, None, k, &mut out);
    out
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
            fill: None,
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
        use crate::gpu::{texture_entry, uniform_entry, UNFILTERED};
        let mut entries = vec![uniform_entry(0)];
        for i in 0..k.surfaces as u32 {
            entries.push(texture_entry(1 + 2 * i, UNFILTERED));
            entries.push(texture_entry(2 + 2 * i, wgpu::TextureSampleType::Depth));
        }
        if k.intermediate {
            let n = k.surfaces as u32;
            entries.push(texture_entry(1 + 2 * n, UNFILTERED));
            entries.push(texture_entry(2 + 2 * n, UNFILTERED));
        }
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
        let (bgl, pipeline) =
            self.gpu.fullscreen_pipeline("compositor", &shader(&k), &entries, if k.last { &last } else { &mid }, None);
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
    /// over `background` (straight alpha). With `region` (x, y, width, height in output
    /// pixels) only that part is redrawn and the rest of `output` is kept; the result is the
    /// same as a whole composite wherever the layers outside the region are unchanged.
    pub fn composite(
        &mut self,
        layers: &[Layer<'_>],
        light: &Lighting,
        output: &wgpu::Texture,
        background: [f32; 4],
        region: Option<[u32; 4]>,
    ) {
        let (w, h) = (output.width(), output.height());
        let whole = [0, 0, w, h];
        let region = match region {
            Some(r) => {
                let (x0, y0) = (r[0].min(w), r[1].min(h));
                [x0, y0, r[2].min(w - x0), r[3].min(h - y0)]
            }
            None => whole,
        };
        if region[2] == 0 || region[3] == 0 {
            self.last_passes = 0;
            return;
        }
        let partial = region != whole;
        // Layers with no fragment in the region change nothing there.
        let (rx0, ry0, rx1, ry1) = (
            i64::from(region[0]),
            i64::from(region[1]),
            i64::from(region[0] + region[2]),
            i64::from(region[1] + region[3]),
        );
        let layers: Vec<&Layer<'_>> = layers
            .iter()
            .filter(|l| {
                let (x0, y0) = (i64::from(l.rect[0]), i64::from(l.rect[1]));
                let (x1, y1) = (x0 + i64::from(l.rect[2]), y0 + i64::from(l.rect[3]));
                x0 < rx1 && x1 > rx0 && y0 < ry1 && y1 > ry0
            })
            .collect();
        let out_view = output.create_view(&Default::default());
        let d = self.gpu.device.clone();
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("composite") });
        let a = background[3];
        let premultiplied = [background[0] * a, background[1] * a, background[2] * a, a];
        let fill = partial.then(|| {
            let (bgl, pipeline) = self
                .fill
                .get_or_insert_with(|| {
                    self.gpu.fullscreen_pipeline(
                        "background fill",
                        include_str!("../../../shaders/fill.wgsl"),
                        &[crate::gpu::uniform_entry(0)],
                        &[Some(COLOR_FORMAT.into())],
                        None,
                    )
                })
                .clone();
            let ubuf = d.create_buffer(&wgpu::BufferDescriptor {
                label: Some("background"),
                size: 16,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            self.gpu.queue.write_buffer(&ubuf, 0, bytemuck::cast_slice(&premultiplied));
            let group = d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("background"),
                layout: &bgl,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: ubuf.as_entire_binding() }],
            });
            (pipeline, group)
        });
        {
            let load = if partial {
                wgpu::LoadOp::Load
            } else {
                let c = premultiplied.map(f64::from);
                wgpu::LoadOp::Clear(wgpu::Color { r: c[0], g: c[1], b: c[2], a: c[3] })
            };
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("background"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &out_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if let Some((pipeline, group)) = &fill {
                rp.set_pipeline(pipeline);
                rp.set_bind_group(0, group, &[]);
                rp.set_scissor_rect(region[0], region[1], region[2], region[3]);
                rp.draw(0..3, 0..1);
            }
        }
        let mut zs: Vec<f32> = layers.iter().map(|l| l.z).filter(|z| z.is_finite()).collect();
        zs.sort_by(|a, b| b.total_cmp(a));
        zs.dedup();
        let mut passes = 0;
        let mut spare: Option<[(wgpu::Texture, wgpu::TextureView); 2]> = None;
        for z in zs {
            let group: Vec<&Layer<'_>> = layers.iter().copied().filter(|l| l.z == z).collect();
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
                    rp.set_scissor_rect(region[0], region[1], region[2], region[3]);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pass_shape_specialises_to_valid_wgsl() {
        for surfaces in 1..=4 {
            for bits in 0..16u32 {
                let k = PassKind {
                    surfaces,
                    intermediate: bits & 1 != 0,
                    last: bits & 2 != 0,
                    lit: bits & 4 != 0,
                    from_depth: bits & 8 != 0,
                };
                let src = shader(&k);
                assert!(!src.contains("{{") && !src.contains("//#"), "unfilled template:\n{src}");
                let module =
                    naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| panic!("{}\n{src}", e.emit_to_string(&src)));
                naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
                    .validate(&module)
                    .unwrap_or_else(|e| panic!("{e:?}\n{src}"));
                assert_eq!(src.matches("var color").count(), surfaces);
                assert_eq!(src.contains("var igeom"), k.intermediate);
                assert_eq!(src.contains("fn light("), k.last && k.lit);
                assert_eq!(src.matches("fn dn").count(), if k.from_depth { surfaces } else { 0 });
            }
        }
    }
}

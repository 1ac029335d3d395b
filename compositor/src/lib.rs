//! The 3D compositor (the thesis' "root surface", §4.5–4.6): every surface's colour and depth
//! are combined into one output image. Surfaces are grouped by z and the groups drawn far
//! (larger z) to near. Within a group each output fragment takes the surface with the nearest
//! depth; on equal depth the surface later in stacking order wins. Depth is compared in eye
//! space: each surface's window depth is linearised by its declared projection
//! (`Layer::projection`); an undeclared surface's eye depth is its raw depth, and a surface
//! without a depth image lies at its far plane. Outside its rectangle a surface has no
//! fragment. The selected colour (straight alpha) is lit, premultiplied, and blended over what
//! lies beneath.
//!
//! A composite costs what its region needs (`plan`): the region is cut into cells by coverage;
//! a cell no surface covers is filled with the background, a cell one surface of a group covers
//! costs one fetch of it, and only where several surfaces of a group overlap does the depth
//! select run, over those surfaces only. The farthest group at a cell is laid on the
//! background in its shader; nearer ones are blended over it.
//!
//! A pass can sample at most `m` textures; a surface needs two (colour and depth), so one pass
//! takes `p = ⌊m/2⌋` surfaces. Where more overlap, passes are chained: each further pass takes
//! the previous pass's intermediate (the selected colour, RGBA8, and its eye depth and normal,
//! f32) plus `p − 1` new surfaces. Because an intermediate holds exactly what a single pass would
//! have selected, and lighting runs only in the last pass, a chain is bit-identical to one pass.
//! `with_intermediate` can make the intermediate's colour RGBA16F instead (twice the bytes; an
//! RGBA8 texel then passes through a 16-bit float, which holds k/255 to within 2⁻¹¹ relative).
//!
//! Culling (`with_culling`, on by default): in a cell where some group's members are all opaque
//! (`Layer::opaque`: the surface's config has no alpha, so its colour has alpha 1 everywhere),
//! every farther group is left out of the cell and that group is laid on the background. Nothing
//! left out could show, and every group still drawn selects the same surface at every pixel
//! (normals from depth come from the selected surface's own depth), so the image is the same,
//! bit for bit, as without culling.
//!
//! Regions and opacity (`Layer::props`): a surface shows a source region of its image over its
//! rectangle. Where the two have the same size each pixel fetches its own texel exactly; where
//! they differ the colour is filtered bilinearly (texel centres at half-integers, clamped to the
//! region) and the depth select uses the nearest texel, both located in integer arithmetic so
//! that the f64 reference finds the same texels. Opacity multiplies the selected colour's
//! alpha; a surface with opacity below 1 is never treated as opaque by culling.
//!
//! `Mode::TwoD` is the 2D baseline: painter's order by z only, no depth, no lighting, each
//! visible part of a surface copied as it is (opacity does not apply).

#![warn(missing_docs)]

mod encode;
pub mod figures;
mod inputs;
mod plan;
pub mod pointer;
pub mod reference;
mod resources;
pub mod root;
mod shader;
mod timing;
pub mod window;

use std::sync::Arc;

use encode::Builder;
use resources::Resources;
use strata_device::Gpu;

pub use strata_protocol::control::{Lighting, NormalSource};

/// Most distinct per-surface normals that get a light map (the rest are lit in the shader).
const MAX_LIGHT_MAPS: usize = 4;

/// Largest output (pixels) with light maps: 4 bytes a pixel per map.
const LIGHT_MAP_MAX_PIXELS: u64 = 8 << 20;

/// The part of a surface's image that is shown, stretched over its rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Source {
    /// The image's width and height.
    pub image: [i32; 2],
    /// The part shown: x, y (from the image's top), width, height, within the image.
    pub region: [i32; 4],
}

/// How a surface is shown beyond its placement: which part of its image, and how opaquely.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Props {
    /// The part of the image shown over the rectangle (scaled, and filtered bilinearly, where
    /// its size differs from the rectangle's; fetched exactly where it is the same); `None`: the
    /// whole image, whose size is the rectangle's.
    pub source: Option<Source>,
    /// Multiplies the selected premultiplied colour (its alpha): 0 shows nothing of it, 1 shows
    /// it as drawn. The surface still takes part in its group's depth select.
    pub opacity: f32,
}

impl Default for Props {
    fn default() -> Self {
        Props { source: None, opacity: 1.0 }
    }
}

impl Props {
    /// How the compositor shows scene surface `s` with opacity `opacity`: `None` where nothing
    /// of it can show (an empty rectangle or source region).
    pub fn of(s: &strata_scene::SceneSurface, opacity: f32) -> Option<Props> {
        if !s.can_show() {
            return None;
        }
        let region = s.source_region()?;
        let source = (!s.exact()).then_some(Source { image: s.image, region });
        Some(Props { source, opacity })
    }

    /// Whether the source is scaled to rectangle `rect` (sizes differ).
    pub fn scaled(&self, rect: [i32; 4]) -> bool {
        self.source.is_some_and(|s| s.region[2] != rect[2] || s.region[3] != rect[3])
    }

    /// The source in effect for rectangle `rect`: the image's size and the region shown.
    pub fn source_for(&self, rect: [i32; 4]) -> Source {
        self.source.unwrap_or(Source { image: [rect[2], rect[3]], region: [0, 0, rect[2], rect[3]] })
    }
}

/// One surface to composite.
pub struct Layer<'a> {
    /// x, y (from the output's top), width, height in output pixels: where the surface shows
    /// (its image's size unless `props.source` scales it).
    pub rect: [i32; 4],
    /// Depth layer: larger is farther; equal values form one group.
    pub z: f32,
    /// Colour (RGBA8, rows in GL order: bottom first).
    pub color: &'a wgpu::TextureView,
    /// Depth (a depth format, same size), or `None`: at its far plane everywhere (depth 1 when
    /// undeclared).
    pub depth: Option<&'a wgpu::TextureView>,
    /// The surface's normal for `NormalSource::PerSurface`.
    pub normal: [f32; 3],
    /// Its declared projection as the shader takes it (`Projection::shader_params`): kind (0
    /// orthographic, 1 perspective), near, far, reversed (0 or 1); `Projection::RAW` when
    /// undeclared, which compares its raw depth.
    pub projection: [f32; 4],
    /// Its colour has alpha 1 everywhere (a surface whose config has no alpha, whose alpha
    /// reads as 1): nothing beneath it can show, so culling may leave out what it covers
    /// (only where `props.opacity` is 1 too).
    pub opaque: bool,
    /// Which part of its image shows, and its opacity.
    pub props: Props,
}

/// How surfaces are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Mode {
    /// Per-fragment depth compositing within z-groups, with lighting (the thesis' design).
    #[default]
    #[value(name = "3d")]
    ThreeD,
    /// A 2D blitting compositor: painter's order by z (then stacking order), no depth, no
    /// lighting, every surface opaque, only the visible part of each copied.
    #[value(name = "2d")]
    TwoD,
}

/// The colour format of chained passes' intermediates (the last pass writes the output as
/// before).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Intermediate {
    /// RGBA8 unorm: holds a selected surface texel exactly (the default).
    #[default]
    #[value(name = "rgba8")]
    Rgba8,
    /// RGBA16 float: twice the bytes per pixel.
    #[value(name = "rgba16f")]
    Rgba16f,
}

impl Intermediate {
    /// Its texture format.
    pub fn format(self) -> wgpu::TextureFormat {
        match self {
            Intermediate::Rgba8 => wgpu::TextureFormat::Rgba8Unorm,
            Intermediate::Rgba16f => wgpu::TextureFormat::Rgba16Float,
        }
    }
}

/// A compositor configuration the device cannot honour, or a pass it cannot build.
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
    /// A pass shape's shader could not be composed from `shaders/composite.wgsl`.
    #[error("the compositor's shader for {kind} does not compose: {message}")]
    Shader {
        /// The pass shape (or the module) it failed for.
        kind: String,
        /// naga_oil's report, and the generated source.
        message: String,
    },
    /// A draw's images are not the ones its pass binds.
    #[error("a compositor draw of {kind} has {views} images where its pass binds {images}")]
    Views {
        /// The pass shape.
        kind: String,
        /// Images the draw has.
        views: usize,
        /// Images its pass binds.
        images: usize,
    },
}

/// What the last composite did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Cells the region was cut into.
    pub cells: usize,
    /// Cells (per z-group) where the depth select ran.
    pub selects: usize,
    /// Of those, cells that needed chained passes.
    pub chained: usize,
    /// Draw calls.
    pub draws: usize,
    /// Render passes.
    pub render_passes: usize,
    /// Surfaces not sampled in a cell (counted once per cell) because a nearer group of opaque
    /// surfaces covers it.
    pub culled: usize,
}

/// The GPU compositor.
pub struct Compositor {
    gpu: Arc<Gpu>,
    per_pass: usize,
    max_textures: u32,
    mode: Mode,
    intermediate: Intermediate,
    cull: bool,
    res: Resources,
    /// Passes the last composite's z-groups take by the thesis' count (`passes(k)` per group
    /// of `k` surfaces in the region); cells where fewer surfaces overlap chain less.
    pub last_passes: usize,
    /// What the last composite did.
    pub last_stats: Stats,
    /// The queue submission of the last composite that drew anything.
    pub last_submission: Option<wgpu::SubmissionIndex>,
    /// Timestamps around each composite, where the device has them.
    timing: Option<timing::Timing>,
}

impl Compositor {
    /// A 3D compositor sampling at most `max_textures` textures per pass (default: the
    /// device's limit). At least 4 are needed to chain.
    pub fn new(gpu: Arc<Gpu>, max_textures: Option<u32>) -> Result<Compositor, CompositorError> {
        let device = gpu.limits.max_sampled_textures_per_shader_stage;
        let m = max_textures.unwrap_or(device);
        if m < 4 {
            return Err(CompositorError::TooFewTextures(m));
        }
        if m > device {
            return Err(CompositorError::ExceedsDevice { requested: m, device });
        }
        Ok(Compositor {
            timing: timing::Timing::new(&gpu),
            res: Resources::new(gpu.clone())?,
            gpu,
            per_pass: (m / 2) as usize,
            max_textures: m,
            mode: Mode::ThreeD,
            intermediate: Intermediate::default(),
            cull: true,
            last_passes: 0,
            last_stats: Stats::default(),
            last_submission: None,
        })
    }

    /// The same compositor in `mode`.
    pub fn with_mode(mut self, mode: Mode) -> Compositor {
        self.mode = mode;
        self
    }

    /// The same compositor with chained passes' intermediate colour in `format`.
    pub fn with_intermediate(mut self, format: Intermediate) -> Compositor {
        self.intermediate = format;
        self.res.set_intermediate_format(format.format());
        self
    }

    /// The same compositor with culling of surfaces under opaque nearer groups on or off (on
    /// by default; off only for measurement: the image is the same).
    pub fn with_culling(mut self, on: bool) -> Compositor {
        self.cull = on;
        self
    }

    /// Whether surfaces under opaque nearer groups are culled.
    pub fn culling(&self) -> bool {
        self.cull
    }

    /// The colour format of chained passes' intermediates.
    pub fn intermediate(&self) -> Intermediate {
        self.intermediate
    }

    /// How it combines surfaces.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The texture limit in force.
    pub fn max_textures(&self) -> u32 {
        self.max_textures
    }

    /// The device time of the last composite (from timestamps at the start of its first pass
    /// and the end of its last), once it has completed; `None` where the device has no
    /// timestamps or the composite drew nothing.
    pub fn take_device_time(&mut self) -> Option<std::time::Duration> {
        self.timing.as_mut()?.device_time(&self.gpu)
    }

    /// Passes a group of `k` surfaces takes: `1 + ⌈(k − p)/(p − 1)⌉` beyond `p`.
    pub fn passes(&self, k: usize) -> usize {
        plan::chunks(k, self.per_pass).len()
    }

    /// Composites `layers` (in stacking order) into `output` (RGBA8, render-attachment usage),
    /// over `background` (straight alpha). With `region` (x, y, width, height in output
    /// pixels) only that part is redrawn and the rest of `output` is kept; the result is the
    /// same as a whole composite wherever the layers outside the region are unchanged. A
    /// region that misses the output, or has no area, draws nothing. An error (nothing
    /// submitted) where a pass's shader cannot be composed.
    pub fn composite(
        &mut self,
        layers: &[Layer<'_>],
        light: &Lighting,
        output: &wgpu::Texture,
        background: [f32; 4],
        region: Option<[u32; 4]>,
    ) -> Result<(), CompositorError> {
        self.last_passes = 0;
        self.last_stats = Stats::default();
        let (w, h) = (output.width(), output.height());
        let r = region.unwrap_or([0, 0, w, h]);
        let (x0, y0) = (r[0].min(w), r[1].min(h));
        let (x1, y1) = (x0.saturating_add(r[2]).min(w), y0.saturating_add(r[3]).min(h));
        if x1 <= x0 || y1 <= y0 || w > i32::MAX as u32 || h > i32::MAX as u32 {
            return Ok(());
        }
        let region = [x0 as i32, y0 as i32, x1 as i32, y1 as i32];
        let rects: Vec<Option<plan::Rect>> =
            layers.iter().map(|l| if l.z.is_finite() { plan::clip(l.rect, region) } else { None }).collect();
        let cells = plan::cells(&rects, region);
        let z: Vec<f32> = layers.iter().map(|l| l.z).collect();
        let align = self.res.align;
        let mut culled = 0;
        let mut b = Builder::new(layers, (w, h), self.per_pass, light, background, align);
        match self.mode {
            Mode::ThreeD => {
                self.light_maps(&mut b, layers, light, (w, h));
                let opaque: Vec<bool> = layers.iter().map(|l| l.opaque && l.props.opacity >= 1.0).collect();
                let plan = plan::plan_3d(&cells, &z, self.cull.then_some(&opaque[..]));
                culled = plan.culled;
                b.fill(&plan.fill);
                for g in &plan.groups {
                    b.group(&mut self.res, g);
                }
                for lz in plan::depth_layers(z.iter().copied()) {
                    let k = rects.iter().zip(&z).filter(|(r, &z)| r.is_some() && z == lz).count();
                    if k > 0 {
                        self.last_passes += self.passes(k);
                    }
                }
            }
            Mode::TwoD => {
                let (fill, copies) = plan::plan_2d(&cells, &z);
                b.fill(&fill);
                for (layer, rects) in &copies {
                    b.copy(&self.res, *layer, rects);
                }
                self.last_passes = 1;
            }
        }
        self.res.upload(&b.uniforms, &b.instances);
        self.last_stats = Stats {
            cells: cells.len(),
            selects: b.selects,
            chained: b.chained,
            draws: b.passes.iter().map(|p| p.draws.len()).sum(),
            render_passes: b.passes.len(),
            culled,
        };
        let encoded = self.encode(b.passes, output, region);
        self.res.finish();
        encoded
    }

    /// With lighting from per-surface normals, the light maps of the first `MAX_LIGHT_MAPS`
    /// distinct normals (in stacking order), drawn first where the lighting changed. Which
    /// normals get one depends only on the scene, so a partial composite lights each pixel the
    /// way a whole one does.
    fn light_maps(&mut self, b: &mut Builder<'_>, layers: &[Layer<'_>], light: &Lighting, size: (u32, u32)) {
        let mut keep: Vec<[u32; 3]> = Vec::new();
        let small = u64::from(size.0) * u64::from(size.1) <= LIGHT_MAP_MAX_PIXELS;
        if light.enabled && light.normals == NormalSource::PerSurface && small {
            let stamp: [u32; 16] =
                bytemuck::cast_slice::<u8, u32>(&b.uniforms[..64]).try_into().unwrap_or([u32::MAX; 16]);
            for l in layers.iter().filter(|l| l.z.is_finite()) {
                let n = encode::unit_normal(l.normal);
                let bits = n.map(f32::to_bits);
                if keep.len() == MAX_LIGHT_MAPS || keep.contains(&bits) {
                    continue;
                }
                keep.push(bits);
                let (view, stale) = self.res.light_map(n, size, stamp);
                if stale {
                    b.light_map(n, view.clone());
                }
                b.maps.push((bits, view));
            }
        }
        self.res.keep_light_maps(&keep);
    }

    /// Records and submits the passes (nothing where one cannot be built).
    fn encode(
        &mut self,
        passes: Vec<encode::PassOp>,
        output: &wgpu::Texture,
        region: plan::Rect,
    ) -> Result<(), CompositorError> {
        let out_view = output.create_view(&Default::default());
        let d = self.gpu.device.clone();
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("composite") });
        let n = passes.len();
        for (i, pass) in passes.into_iter().enumerate() {
            let attach = |view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                })
            };
            let attachments: Vec<_> = match &pass.target {
                None => vec![attach(&out_view)],
                Some(views) => views.iter().map(attach).collect(),
            };
            let mut rp = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("composite pass"),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: self.timing.as_ref().and_then(|t| t.writes(i, n)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            if pass.target.is_none() {
                // Cells never leave the region; the scissor makes sure of it.
                let [x0, y0, x1, y1] = region.map(|v| v as u32);
                rp.set_scissor_rect(x0, y0, x1 - x0, y1 - y0);
            }
            rp.set_vertex_buffer(0, self.res.instances.buffer.slice(..));
            let mut current: Option<Option<shader::PassKind>> = None;
            for draw in pass.draws {
                if current != Some(draw.kind) {
                    let (_, pipeline) = self.res.pipeline(draw.kind)?;
                    rp.set_pipeline(&pipeline);
                    current = Some(draw.kind);
                }
                let group = self.res.bind_group(draw.kind, draw.views)?;
                if draw.kind.is_some() {
                    rp.set_bind_group(0, &group, &[draw.block]);
                } else {
                    rp.set_bind_group(0, &group, &[]);
                }
                rp.draw(0..4, draw.instances);
            }
        }
        if let (Some(t), true) = (&mut self.timing, n > 0) {
            t.resolve(&mut enc);
        }
        self.last_submission = Some(self.gpu.submit(&self.gpu.lane, vec![enc.finish()]));
        Ok(())
    }
}

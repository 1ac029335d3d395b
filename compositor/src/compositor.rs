//! The GPU compositor: plans a region's cells, encodes their passes and submits them.

use std::sync::Arc;

use strata_device::Gpu;

use crate::encode::Builder;
use crate::layer::{CompositorError, Intermediate, Layer, Mode, Stats};
use crate::resources::Resources;
use crate::{encode, plan, timing};
use strata_protocol::control::{Lighting, NormalSource};

/// Most distinct per-surface normals that get a light map (the rest are lit in the shader).
const MAX_LIGHT_MAPS: usize = 4;

/// Largest output (pixels) with light maps: 4 bytes a pixel per map.
const LIGHT_MAP_MAX_PIXELS: u64 = 8 << 20;

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
            let mut current: Option<Option<crate::kind::PassKind>> = None;
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

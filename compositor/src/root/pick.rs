//! Which surface is shown at a point of an output: the compositor's own depth select, run for
//! one pixel. For each candidate surface (shown, accepting input, its rectangle holding the
//! point) the compositor's device reads one texel of its newest frame, depth and alpha
//! (`shaders/pick.wgsl`); never the whole image. Readings are kept until the scene changes, so
//! a point is read at most once per change. Groups are taken near (smaller z) to far: within a
//! group the nearest eye depth wins, the later surface on a tie; a group whose winner is
//! transparent there (alpha times opacity 0) lets the point through to the group behind.

use std::collections::HashMap;

use strata_protocol::projection::Projection;

use strata_device::Gpu;
use strata_scene::{Candidate, Images};

const SHADER: &str = include_str!("../../../shaders/pick.wgsl");

/// The surface a point goes to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Target {
    /// Surface ID.
    pub surface: u64,
    /// Its client's number.
    pub client: u64,
    /// The point in its image's pixels, from the top-left corner.
    pub local: [f32; 2],
    /// Microseconds the pick waited on the device for texels (`None`: all were kept).
    pub device_us: Option<u64>,
}

/// The pick pipeline of one device.
struct DevicePicker {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    /// Bound where a surface has no depth image.
    no_depth: wgpu::TextureView,
}

/// The pick pipelines and the readings of the current scene.
pub struct Picker {
    /// On the compositor's device, for frames only it reads (copied frames, `--devices
    /// shared`, or a pick device that could not import them).
    compositor: Option<DevicePicker>,
    /// On the pick device, which imports every shared frame.
    own: Option<DevicePicker>,
    /// The damage count the readings belong to.
    damage: u64,
    /// Window depth and alpha by surface and texel.
    readings: HashMap<(u64, [u32; 2]), [f32; 2]>,
    /// Texels read so far: on the pick device, and on the compositor's.
    pub reads: [u64; 2],
}

impl DevicePicker {
    fn new(gpu: &Gpu) -> DevicePicker {
        let d = &gpu.device;
        let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let texture = |sample_type| wgpu::BindingType::Texture {
            sample_type,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        };
        let buffer = |ty| wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None };
        let layout = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("pick"),
            entries: &[
                entry(0, texture(wgpu::TextureSampleType::Float { filterable: false })),
                entry(1, texture(wgpu::TextureSampleType::Depth)),
                entry(2, buffer(wgpu::BufferBindingType::Uniform)),
                entry(3, buffer(wgpu::BufferBindingType::Storage { read_only: false })),
            ],
        });
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("pick"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline_layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("pick"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("pick"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let no_depth = gpu
            .texture_2d(
                "pick no depth",
                wgpu::TextureFormat::Depth32Float,
                (1, 1),
                wgpu::TextureUsages::TEXTURE_BINDING,
            )
            .create_view(&Default::default());
        DevicePicker { pipeline, layout, no_depth }
    }

    /// Window depth and alpha of each texel (`texel`, whether the image has depth, its
    /// images on this device), read in one submission, with the microseconds from submitting
    /// the read to its results mapped; `None` where the read fails.
    fn read(&self, gpu: &Gpu, texels: &[([u32; 2], &Images)]) -> Option<(Vec<[f32; 2]>, u64)> {
        let d = &gpu.device;
        // Each texel's result at its own storage-aligned offset.
        let stride = u64::from(gpu.limits.min_storage_buffer_offset_alignment.max(8));
        let size = stride * texels.len() as u64;
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC;
        let results =
            d.create_buffer(&wgpu::BufferDescriptor { label: Some("pick"), size, usage, mapped_at_creation: false });
        let readback = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("pick readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = d.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("pick") });
        let mut groups = Vec::new();
        for (i, (texel, images)) in texels.iter().enumerate() {
            let params: [u32; 4] = [texel[0], texel[1], u32::from(images.depth.is_some()), 0];
            let uniform = d.create_buffer(&wgpu::BufferDescriptor {
                label: Some("pick params"),
                size: 16,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            gpu.write_buffer(&uniform, 0, bytemuck::cast_slice(&params));
            let out =
                wgpu::BufferBinding { buffer: &results, offset: stride * i as u64, size: wgpu::BufferSize::new(8) };
            let depth = images.depth.as_ref().unwrap_or(&self.no_depth);
            groups.push(d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("pick"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&images.color) },
                    wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(depth) },
                    wgpu::BindGroupEntry { binding: 2, resource: uniform.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::Buffer(out) },
                ],
            }));
        }
        {
            let mut pass =
                enc.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("pick"), timestamp_writes: None });
            pass.set_pipeline(&self.pipeline);
            for g in &groups {
                pass.set_bind_group(0, g, &[]);
                pass.dispatch_workgroups(1, 1, 1);
            }
        }
        enc.copy_buffer_to_buffer(&results, 0, &readback, 0, size);
        let submitted = std::time::Instant::now();
        let index = gpu.submit(&gpu.lane, vec![enc.finish()]);
        let slice = readback.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        let wait =
            wgpu::PollType::Wait { submission_index: Some(index), timeout: Some(std::time::Duration::from_secs(5)) };
        let _ = d.poll(wait);
        rx.recv_timeout(std::time::Duration::from_secs(5)).ok()?.ok()?;
        let waited = submitted.elapsed().as_micros() as u64;
        let data = slice.get_mapped_range().ok()?;
        let values: &[f32] = bytemuck::cast_slice(&data);
        let at = |i: usize| (stride as usize / 4) * i;
        Some(((0..texels.len()).map(|i| [values[at(i)], values[at(i) + 1]]).collect(), waited))
    }
}

impl Picker {
    pub(crate) fn new() -> Picker {
        Picker { compositor: None, own: None, damage: u64::MAX, readings: HashMap::new(), reads: [0; 2] }
    }

    /// Window depth and alpha of each candidate's texel, read where this scene (`damage`)
    /// has not read them yet: on the pick device (`own`) for the frames it imported, else on
    /// the compositor's device (`comp`). With the microseconds the reads waited for their
    /// devices (`None`: nothing was read); `None` where a read fails.
    pub(crate) fn read<'a>(
        &mut self,
        comp: &Gpu,
        own: Option<&Gpu>,
        damage: u64,
        cands: &'a [Candidate],
    ) -> Option<(Vec<[f32; 2]>, Option<u64>)> {
        if damage != self.damage {
            self.readings.clear();
            self.damage = damage;
        }
        let missing: Vec<&'a Candidate> =
            cands.iter().filter(|c| !self.readings.contains_key(&(c.id, c.texel))).collect();
        let mut waited = None;
        // The pick device's images where it has them, else the compositor's.
        let images = |c: &'a Candidate| match (own, &c.pick) {
            (Some(_), Some(images)) => (true, images),
            _ => (false, &c.shown),
        };
        for (on_own, gpu) in [(true, own), (false, Some(comp))] {
            let Some(gpu) = gpu else { continue };
            let texels: Vec<(&Candidate, &Images)> = missing
                .iter()
                .filter_map(|c| {
                    let (o, i) = images(c);
                    (o == on_own).then_some((*c, i))
                })
                .collect();
            if texels.is_empty() {
                continue;
            }
            let picker = if on_own { &mut self.own } else { &mut self.compositor };
            let at: Vec<([u32; 2], &Images)> = texels.iter().map(|(c, i)| (c.texel, *i)).collect();
            let (values, us) = picker.get_or_insert_with(|| DevicePicker::new(gpu)).read(gpu, &at)?;
            waited = Some(waited.unwrap_or(0) + us);
            for ((c, _), v) in texels.iter().zip(values) {
                self.readings.insert((c.id, c.texel), v);
            }
            self.reads[usize::from(!on_own)] += at.len() as u64;
        }
        let readings = cands.iter().map(|c| self.readings.get(&(c.id, c.texel)).copied()).collect::<Option<_>>()?;
        Some((readings, waited))
    }
}

/// Eye depth of a reading, as the compositor's select compares it (`compositor::reference`):
/// NaN as the far plane's window depth, clamped to [0, 1], linearised by the projection; a
/// surface without depth lies at its far plane.
fn eye_depth(window: f32, has_depth: bool, projection: Option<&Projection>) -> f64 {
    if !has_depth {
        return projection.map_or(1.0, |p| f64::from(p.far));
    }
    let far = if projection.is_some_and(|p| p.reversed) { 0.0 } else { 1.0 };
    let d = if window.is_nan() { far } else { f64::from(window).clamp(0.0, 1.0) };
    projection.map_or(d, |p| p.eye_depth(d))
}

/// The index of the candidate shown (`readings`: each one's window depth and alpha), or
/// `None` where every group is transparent there.
pub fn winner(cands: &[Candidate], readings: &[[f32; 2]]) -> Option<usize> {
    let mut zs: Vec<f32> = cands.iter().map(|c| c.z).collect();
    zs.sort_by(f32::total_cmp);
    zs.dedup();
    for z in zs {
        let mut best: Option<(f64, usize)> = None;
        // Candidates come in stacking order: a later one wins a tie.
        for (i, c) in cands.iter().enumerate().filter(|(_, c)| c.z == z) {
            let d = eye_depth(readings[i][0], c.shown.depth.is_some(), c.projection.as_ref());
            if best.is_none_or(|b| d <= b.0) {
                best = Some((d, i));
            }
        }
        let Some((_, i)) = best else { continue };
        let alpha = if cands[i].opaque { 1.0 } else { f64::from(readings[i][1]) };
        if alpha * f64::from(cands[i].opacity.clamp(0.0, 1.0)) > 0.0 {
            return Some(i);
        }
    }
    None
}

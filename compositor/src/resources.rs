//! What the compositor keeps between composites, so that a composite allocates nothing in the
//! steady state: pipelines per pass shape, one uniform buffer (the lighting, then one block
//! per draw, bound with dynamic offsets), one instance buffer (the cells' rectangles), bind
//! groups by the images they bind, and the chain's intermediates.

use std::collections::HashMap;
use std::sync::Arc;

use crate::inputs::{PassInputs, Uniform};
use crate::kind::{Geom, PassKind};
use crate::shader::{Composer, FILL};
use crate::CompositorError;
use strata_device::Gpu;

/// The output's format.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Bytes of the lighting parameters at the start of the uniform buffer (`Params`).
pub const PARAMS_SIZE: u64 = 80;

/// Bytes of one surface's entry in a draw's block (`Surf`: rect, src, normal, proj, img; five
/// 16-byte vectors, so the uniform array's stride is a multiple of 16 as std140 requires).
pub const SURF_SIZE: u64 = 80;

/// Bind groups unused for this many composites are dropped (a surface alternates between two
/// front images, so each of its bind groups is typically used every other composite).
const KEEP_COMPOSITES: u64 = 4;

/// A pipeline and its bind group layout.
pub type Pipeline = (wgpu::BindGroupLayout, wgpu::RenderPipeline);

/// The two ping-pong intermediates of chained passes: the selected colour and its geometry,
/// covering the bounding box of the cells that chain.
pub struct Intermediates {
    /// Width and height.
    pub size: (u32, u32),
    /// What the geometry images hold.
    pub geom: Geom,
    /// Colour images (the intermediate format: RGBA8 unless chosen otherwise) and views.
    pub color: [(wgpu::Texture, wgpu::TextureView); 2],
    /// Geometry images and views.
    pub geometry: [(wgpu::Texture, wgpu::TextureView); 2],
}

/// A light map: the lighting factor of every output pixel for one normal.
struct LightMap {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    /// The lighting parameters it was drawn with (bit patterns).
    stamp: [u32; 16],
}

/// A buffer that grows (and is then replaced) when a composite needs more.
pub struct Growing {
    /// The buffer.
    pub buffer: wgpu::Buffer,
    usage: wgpu::BufferUsages,
    label: &'static str,
}

impl Growing {
    fn new(d: &wgpu::Device, label: &'static str, usage: wgpu::BufferUsages, size: u64) -> Growing {
        let buffer =
            d.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: false });
        Growing { buffer, usage, label }
    }

    /// Makes room for `size` bytes; returns whether the buffer was replaced.
    fn reserve(&mut self, d: &wgpu::Device, size: u64) -> bool {
        if size <= self.buffer.size() {
            return false;
        }
        *self = Growing::new(d, self.label, self.usage, size.next_power_of_two());
        true
    }
}

/// The compositor's persistent GPU resources.
pub struct Resources {
    gpu: Arc<Gpu>,
    /// Composes each pass shape's shader on a pipeline miss.
    composer: Composer,
    pipelines: HashMap<PassKind, Pipeline>,
    fill: Option<Pipeline>,
    groups: HashMap<(Option<PassKind>, Vec<wgpu::TextureView>), (wgpu::BindGroup, u64)>,
    /// The uniform buffer: `Params`, then one block per draw.
    pub uniforms: Growing,
    /// The cells' clip-space rectangles, one instance each.
    pub instances: Growing,
    /// Light maps by the bits of their unit normal.
    maps: HashMap<[u32; 3], LightMap>,
    /// The chain's intermediates, once a chain was needed.
    pub intermediates: Option<Intermediates>,
    /// Bound in place of the depth image of a surface without one.
    pub dummy_depth: wgpu::TextureView,
    /// Composites so far (ages bind groups).
    generation: u64,
    /// The device's alignment of dynamic uniform offsets.
    pub align: u64,
    /// The colour format of chained passes' intermediates.
    intermediate_format: wgpu::TextureFormat,
}

/// Bytes of a draw block with `n` surfaces.
pub fn block_size(n: usize) -> u64 {
    16 + SURF_SIZE * n as u64
}

impl Resources {
    /// Empty caches and small buffers (an error where `shaders/composite.wgsl` is no module).
    pub fn new(gpu: Arc<Gpu>) -> Result<Resources, CompositorError> {
        let d = &gpu.device;
        let dummy_depth = gpu
            .texture_2d(
                "no depth",
                wgpu::TextureFormat::Depth32Float,
                (1, 1),
                wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::RENDER_ATTACHMENT,
            )
            .create_view(&Default::default());
        let uniforms =
            Growing::new(d, "compositor uniforms", wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST, 4096);
        let instances =
            Growing::new(d, "compositor cells", wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST, 4096);
        let align = u64::from(gpu.limits.min_uniform_buffer_offset_alignment.max(16));
        Ok(Resources {
            composer: Composer::new()?,
            pipelines: HashMap::new(),
            fill: None,
            groups: HashMap::new(),
            uniforms,
            instances,
            intermediates: None,
            maps: HashMap::new(),
            dummy_depth,
            generation: 0,
            align,
            intermediate_format: COLOR_FORMAT,
            gpu,
        })
    }

    /// A pipeline drawing the compositor's cells (one instanced rectangle each), bound as
    /// `inputs` describes.
    fn build(
        &self,
        label: &str,
        source: wgpu::ShaderSource<'_>,
        inputs: &PassInputs,
        targets: &[Option<wgpu::ColorTargetState>],
    ) -> Pipeline {
        self.gpu.pipeline(label, source, &inputs.layout(), targets, None, strata_device::VertexInput::InstanceRect)
    }

    /// The pipeline of pass shape `k` (`None`: the background fill), built on first use; an
    /// error where its shader cannot be composed.
    pub fn pipeline(&mut self, k: Option<PassKind>) -> Result<Pipeline, CompositorError> {
        let Some(k) = k else {
            if let Some(p) = &self.fill {
                return Ok(p.clone());
            }
            let target = [Some(COLOR_FORMAT.into())];
            let p =
                self.build("compositor fill", wgpu::ShaderSource::Wgsl(FILL.into()), &PassInputs::of(None), &target);
            self.fill = Some(p.clone());
            return Ok(p);
        };
        if let Some(p) = self.pipelines.get(&k) {
            return Ok(p.clone());
        }
        let source = wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(self.composer.compose(&k)?));
        let inputs = PassInputs::of(Some(&k));
        if k.factor {
            let target = [Some(wgpu::TextureFormat::R32Float.into())];
            let p = self.build("compositor light map", source, &inputs, &target);
            self.pipelines.insert(k, p.clone());
            return Ok(p);
        }
        let over = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
            operation: wgpu::BlendOperation::Add,
        };
        let targets: Vec<Option<wgpu::ColorTargetState>> = if !k.last {
            vec![Some(self.intermediate_format.into()), Some(k.geom().format().into())]
        } else {
            let blend = (!k.base && !k.copy).then_some(wgpu::BlendState { color: over, alpha: over });
            vec![Some(wgpu::ColorTargetState { format: COLOR_FORMAT, blend, write_mask: wgpu::ColorWrites::ALL })]
        };
        let p = self.build("compositor", source, &inputs, &targets);
        self.pipelines.insert(k, p.clone());
        Ok(p)
    }

    /// The bind group of a draw of shape `k` (`None`: the fill) over `views` (its images in the
    /// order of `PassInputs::textures`), cached while it keeps being used.
    pub fn bind_group(
        &mut self,
        k: Option<PassKind>,
        views: Vec<wgpu::TextureView>,
    ) -> Result<wgpu::BindGroup, CompositorError> {
        let generation = self.generation;
        let key = (k, views);
        if let Some((g, used)) = self.groups.get_mut(&key) {
            *used = generation;
            return Ok(g.clone());
        }
        let (bgl, _) = self.pipeline(k)?;
        let inputs = PassInputs::of(k.as_ref());
        let buffer = &self.uniforms.buffer;
        let block = block_size(k.map_or(0, |k| k.surfaces));
        let uniform = |u: Uniform| {
            let size = if u == Uniform::Params { PARAMS_SIZE } else { block };
            wgpu::BindingResource::Buffer(wgpu::BufferBinding { buffer, offset: 0, size: wgpu::BufferSize::new(size) })
        };
        let entries = inputs.entries(uniform, &key.1).ok_or_else(|| CompositorError::Views {
            kind: format!("{k:?}"),
            views: key.1.len(),
            images: inputs.textures().count(),
        })?;
        let g = self.gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("compositor"),
            layout: &bgl,
            entries: &entries,
        });
        self.groups.insert(key, (g.clone(), generation));
        Ok(g)
    }

    /// Writes this composite's uniforms and cells, growing the buffers (and dropping the bind
    /// groups that named the old uniform buffer) where needed.
    pub fn upload(&mut self, uniforms: &[u8], instances: &[f32]) {
        let d = self.gpu.device.clone();
        if self.uniforms.reserve(&d, uniforms.len() as u64) {
            self.groups.clear();
        }
        self.instances.reserve(&d, (instances.len() * 4) as u64);
        self.gpu.write_buffer(&self.uniforms.buffer, 0, uniforms);
        if !instances.is_empty() {
            self.gpu.write_buffer(&self.instances.buffer, 0, bytemuck::cast_slice(instances));
        }
    }

    /// Sets the colour format of the intermediates, dropping the pipelines, bind groups and
    /// intermediates made for another.
    pub fn set_intermediate_format(&mut self, format: wgpu::TextureFormat) {
        if format != self.intermediate_format {
            self.intermediate_format = format;
            self.pipelines.clear();
            self.groups.clear();
            self.intermediates = None;
        }
    }

    /// Intermediates of at least `size` holding `geom`, reallocated (dropping the bind groups
    /// that named the old ones) when the current ones are too small or hold other geometry.
    pub fn intermediates(&mut self, size: (u32, u32), geom: Geom) -> &Intermediates {
        let fits =
            self.intermediates.as_ref().is_some_and(|i| i.geom == geom && i.size.0 >= size.0 && i.size.1 >= size.1);
        if !fits {
            let old = self.intermediates.as_ref().map_or((0, 0), |i| i.size);
            let size = (size.0.max(old.0), size.1.max(old.1));
            let gpu = &self.gpu;
            let make = |format, label| {
                let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
                let t = gpu.texture_2d(label, format, size, usage);
                let v = t.create_view(&Default::default());
                (t, v)
            };
            self.groups.clear();
            self.intermediates = Some(Intermediates {
                size,
                geom,
                color: [
                    make(self.intermediate_format, "compositor intermediate"),
                    make(self.intermediate_format, "compositor intermediate"),
                ],
                geometry: [
                    make(geom.format(), "compositor intermediate"),
                    make(geom.format(), "compositor intermediate"),
                ],
            });
        }
        self.intermediates.as_ref().unwrap_or_else(|| unreachable!("set above"))
    }

    /// The light map of unit normal `n` for an output of `size` and lighting `stamp`, and
    /// whether it must be drawn (new, or drawn for other lighting). Maps of normals not in
    /// `keep` are dropped.
    pub fn light_map(&mut self, n: [f32; 3], size: (u32, u32), stamp: [u32; 16]) -> (wgpu::TextureView, bool) {
        let key = n.map(f32::to_bits);
        let fits = self.maps.get(&key).is_some_and(|m| m.texture.width() == size.0 && m.texture.height() == size.1);
        if !fits {
            let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
            let texture = self.gpu.texture_2d("compositor light map", wgpu::TextureFormat::R32Float, size, usage);
            let view = texture.create_view(&Default::default());
            // Bind groups naming a replaced map are never looked up again and age out.
            self.maps.insert(key, LightMap { texture, view, stamp: [u32::MAX; 16] });
        }
        let map = self.maps.get_mut(&key).unwrap_or_else(|| unreachable!("inserted above"));
        let stale = map.stamp != stamp;
        map.stamp = stamp;
        (map.view.clone(), stale)
    }

    /// Drops the light maps of normals other than `keep` (bit patterns).
    pub fn keep_light_maps(&mut self, keep: &[[u32; 3]]) {
        self.maps.retain(|k, _| keep.contains(k));
    }

    /// Ends a composite: bind groups unused for a while are dropped.
    pub fn finish(&mut self) {
        let g = self.generation;
        self.groups.retain(|_, (_, used)| g.saturating_sub(*used) < KEEP_COMPOSITES);
        self.generation += 1;
    }
}

//! Shader and program objects: a shader's source and compiled interface, a program's attached
//! shaders and its last link, the GPU modules and layouts a link makes, and what a link was
//! made from (the recipe its program binary holds).

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use serde::{Deserialize, Serialize};
use strata_device::Gpu;

use crate::error::error_chain;
use crate::glsl;
use crate::glsl::types::Stage;
use crate::typed::ClipControl;

/// A shader object.
pub struct ShaderObj {
    /// Vertex or fragment.
    pub stage: Stage,
    /// The source as last set.
    pub source: String,
    /// The compiled interface, after a successful compile.
    pub compiled: Option<glsl::Shader>,
    /// Whether the last compile succeeded.
    pub compiled_ok: bool,
    /// The info log of the last compile.
    pub log: String,
    /// Deleted while attached: freed when detached.
    pub delete_pending: bool,
}

/// A linked program's GPU-side state.
pub struct LinkedProgram {
    /// Reflection from the linker.
    pub info: glsl::Linked,
    /// Vertex module.
    pub vs: wgpu::ShaderModule,
    /// Fragment module.
    pub fs: wgpu::ShaderModule,
    /// Bind group layout: uniform block, then texture/sampler pairs.
    pub bgl: wgpu::BindGroupLayout,
    /// Pipeline layout.
    pub layout: wgpu::PipelineLayout,
    /// Location → (uniform index, array element).
    pub locations: Vec<(usize, u32)>,
    /// What it was linked from, which its program binary holds.
    pub recipe: Recipe,
    /// Unique id for caches.
    pub id: u64,
    /// The compiled stages it was linked from, for program pipelines.
    pub stages: LinkedStages,
    /// The points vertex stage, created on the first `GL_POINTS` draw (or why it failed).
    pub(crate) points_vs: OnceLock<Result<wgpu::ShaderModule, String>>,
    /// Vertex stages for `GL_EXT_clip_control` states other than the default, by (points,
    /// state), created on first use (or why they failed).
    pub(crate) clip_vs: Mutex<HashMap<(bool, ClipControl), Result<wgpu::ShaderModule, String>>>,
    /// Capturing vertex stages (transform feedback), by (points, clip control, rasterizer
    /// discard), created on first use (or why they failed).
    pub(crate) capture_vs: Mutex<VariantCache<(bool, ClipControl, bool, bool)>>,
}

/// Vertex stage variants by what selects them, each created on first use (or why it failed).
pub(crate) type VariantCache<K> = HashMap<K, Result<wgpu::ShaderModule, String>>;

/// The stages a link used: program pipelines link a vertex stage of one separable program
/// with the fragment stage of another (`GL_EXT_separate_shader_objects`), so a separable
/// program keeps its compiled stages.
#[derive(Default)]
pub struct LinkedStages {
    /// Whether it was linked separable: only such programs serve pipeline stages.
    pub separable: bool,
    /// The stages it has code for, as `GL_*_SHADER_BIT_EXT` bits.
    pub bits: u32,
    /// The vertex stage, if it has one and is separable.
    pub vertex: Option<glsl::Shader>,
    /// The fragment stage, if it has one and is separable.
    pub fragment: Option<glsl::Shader>,
}

impl LinkedStages {
    /// What a link of `vertex` and `fragment` keeps: the stages only if `separable`.
    pub fn new(separable: bool, vertex: Option<glsl::Shader>, fragment: Option<glsl::Shader>) -> LinkedStages {
        let bits = u32::from(vertex.is_some()) | (u32::from(fragment.is_some()) << 1);
        if separable {
            LinkedStages { separable, bits, vertex, fragment }
        } else {
            LinkedStages { separable, bits, vertex: None, fragment: None }
        }
    }
}

/// A shader module from a translated stage; the error if the GPU refuses it.
pub fn shader_module(gpu: &Gpu, label: &str, module: naga::Module) -> Result<wgpu::ShaderModule, String> {
    let guard = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let m = gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
    });
    match pollster::block_on(guard.pop()) {
        Some(e) => Err(error_chain(&e)),
        None => Ok(m),
    }
}

impl LinkedProgram {
    /// The vertex module of `GL_POINTS` draws (see `glsl::Linked::points_source`), created
    /// on first use; the error says why the GPU or the translator refused it.
    pub fn points_vs(&self, gpu: &Gpu) -> Result<wgpu::ShaderModule, String> {
        self.points_vs.get_or_init(|| shader_module(gpu, "vs points", glsl::points_vertex(&self.info)?)).clone()
    }

    /// The vertex module (`points`: the points variant) for the clip control state `clip`,
    /// created on first use.
    pub fn clip_vs(&self, gpu: &Gpu, points: bool, clip: ClipControl) -> Result<wgpu::ShaderModule, String> {
        let mut cache = self.clip_vs.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        cache
            .entry((points, clip))
            .or_insert_with(|| {
                let z = if clip.zero_to_one { glsl::ClipZ::Direct } else { glsl::ClipZ::Forward };
                shader_module(gpu, "vs clip control", self.info.vertex_variant(points, clip.upper_left, z)?)
            })
            .clone()
    }

    /// The vertex module (`points`: the points variant) that captures the transform feedback
    /// varyings, for clip control state `clip`, rasterizer discard `discard` and draws whose
    /// vertices are `unrolled` (see `glsl::Linked::capturing_variant`).
    pub fn capture_vs(
        &self,
        gpu: &Gpu,
        points: bool,
        clip: ClipControl,
        (discard, unrolled): (bool, bool),
    ) -> Result<wgpu::ShaderModule, String> {
        let mut cache = self.capture_vs.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        cache
            .entry((points, clip, discard, unrolled))
            .or_insert_with(|| {
                let z = if clip.zero_to_one { glsl::ClipZ::Direct } else { glsl::ClipZ::Forward };
                let m = self.info.capturing_variant(points, clip.upper_left, z, Some((discard, unrolled)))?;
                shader_module(gpu, "vs capture", m)
            })
            .clone()
    }
}

/// A program object.
#[derive(Default)]
pub struct Program {
    /// Attached shader names.
    pub attached: Vec<u32>,
    /// `glBindAttribLocation` requests for the next link.
    pub bindings: HashMap<String, u32>,
    /// The result of the last successful link.
    pub linked: Option<Arc<LinkedProgram>>,
    /// Whether the last link succeeded.
    pub link_ok: bool,
    /// The info log.
    pub log: String,
    /// Uniform block contents (std140).
    pub data: Vec<u8>,
    /// Texture unit of each sampler uniform.
    pub units: Vec<u32>,
    /// The uniform buffer binding of each uniform block (`glUniformBlockBinding`; 0 after a
    /// link).
    pub block_bindings: Vec<u32>,
    /// Deleted while current: freed when no longer in use.
    pub delete_pending: bool,
    /// `glValidateProgram` result.
    pub validated: bool,
    /// `GL_PROGRAM_SEPARABLE_EXT`: whether the next link makes a program pipelines can use.
    pub separable: bool,
    /// `glTransformFeedbackVaryings`: the varyings the next link captures, and whether each
    /// goes to a buffer of its own (`GL_TRANSFORM_FEEDBACK_BUFFER_MODE` `GL_SEPARATE_ATTRIBS`;
    /// the default is `GL_INTERLEAVED_ATTRIBS`).
    pub xfb: (Vec<String>, bool),
}

impl Program {
    /// Makes a link's result the program's: its executable with uniforms at their initial
    /// values, or the failure's log (the previous executable stays in use, as GL specifies).
    pub fn install(&mut self, result: Result<LinkedProgram, String>) {
        match result {
            Ok(linked) => {
                self.data = vec![0; linked.info.block_size as usize];
                self.units = vec![0; linked.info.samplers.len()];
                self.block_bindings = vec![0; linked.info.blocks.len()];
                self.linked = Some(Arc::new(linked));
                self.link_ok = true;
                self.log.clear();
            }
            Err(log) => {
                self.link_ok = false;
                self.log = log;
            }
        }
    }
}

/// What a link produced, and the stages it used.
pub type LinkResult = (glsl::Linked, Recipe, LinkedStages);

/// Creates a linked program's shader modules and layouts; the info log if the GPU rejects them.
pub fn create_gpu_program(gpu: &Gpu, (info, recipe, stages): LinkResult, id: u64) -> Result<LinkedProgram, String> {
    let d = &gpu.device;
    let guard = d.push_error_scope(wgpu::ErrorFilter::Validation);
    let vs = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("vs"),
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(info.vertex.clone())),
    });
    let fs = d.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("fs"),
        source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(info.fragment.clone())),
    });
    let entries = layout_entries(&info, 0);
    let bgl = d.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: None, entries: &entries });
    let layout = d.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&bgl)],
        immediate_size: 0,
    });
    if let Some(e) = pollster::block_on(guard.pop()) {
        return Err(format!("error: the GPU rejected the program: {}", error_chain(&e)));
    }
    let mut locations = Vec::new();
    for (i, u) in info.uniforms.iter().enumerate() {
        for e in 0..u.len {
            locations.push((i, e));
        }
    }
    Ok(LinkedProgram {
        info,
        vs,
        fs,
        bgl,
        layout,
        locations,
        recipe,
        id,
        stages,
        points_vs: OnceLock::new(),
        clip_vs: Mutex::default(),
        capture_vs: Mutex::default(),
    })
}

/// What a program was linked from: enough to link it again.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Recipe {
    /// The vertex shader's source.
    pub vertex: String,
    /// The fragment shader's source.
    pub fragment: String,
    /// `glBindAttribLocation` requests in force at the link, by name.
    pub bindings: Vec<(String, u32)>,
    /// The transform feedback varyings the link captured, and whether separately.
    pub xfb: (Vec<String>, bool),
}

impl Recipe {
    /// The recipe of a link of `s` alone (the other stage's source empty) with `bindings`.
    pub fn new(s: &glsl::Shader, bindings: &HashMap<String, u32>) -> Recipe {
        let mut listed: Vec<(String, u32)> = bindings.iter().map(|(k, v)| (k.clone(), *v)).collect();
        listed.sort();
        let (vertex, fragment) = match s.stage {
            Stage::Vertex => (s.source.clone(), String::new()),
            Stage::Fragment => (String::new(), s.source.clone()),
        };
        Recipe { vertex, fragment, bindings: listed, xfb: (Vec::new(), false) }
    }
}

/// A program's bind group layout entries: the uniform block at 0, then a texture and a sampler
/// per sampler uniform. Samplers in `depth_mask` take images that cannot be filtered (depth,
/// and float ones without `FLOAT32_FILTERABLE`), which bind as unfilterable float with a
/// non-filtering sampler.
pub fn layout_entries(info: &glsl::Linked, depth_mask: u32) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = Vec::new();
    if info.block_size > 0 {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(u64::from(info.block_size)),
            },
            count: None,
        });
    }
    for b in &info.blocks {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: b.binding,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(u64::from(b.block.size)),
            },
            count: None,
        });
    }
    for (i, (ty, b)) in info.samplers.iter().enumerate() {
        // Integer samplers fetch unfiltered texels; their cube maps as a 2D array of faces.
        let int = ty.int_sampler();
        let depth = depth_mask & (1 << i) != 0 || int.is_some();
        let sample_type = match int {
            Some(true) => wgpu::TextureSampleType::Sint,
            Some(false) => wgpu::TextureSampleType::Uint,
            None => wgpu::TextureSampleType::Float { filterable: !depth },
        };
        let ty = match ty.sampler_base() {
            glsl::Ty::SamplerCube if int.is_some() => glsl::Ty::Sampler2DArray,
            t => t,
        };
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: *b,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type,
                view_dimension: match ty {
                    glsl::Ty::SamplerCube | glsl::Ty::SamplerCubeShadow => wgpu::TextureViewDimension::Cube,
                    glsl::Ty::Sampler3D => wgpu::TextureViewDimension::D3,
                    glsl::Ty::Sampler2DArray | glsl::Ty::Sampler2DArrayShadow => wgpu::TextureViewDimension::D2Array,
                    _ => wgpu::TextureViewDimension::D2,
                },
                multisampled: false,
            },
            count: None,
        });
        // The sampler, and the border sampler.
        for binding in [b + 1, b + 2] {
            entries.push(wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Sampler(if depth {
                    wgpu::SamplerBindingType::NonFiltering
                } else {
                    wgpu::SamplerBindingType::Filtering
                }),
                count: None,
            });
        }
    }
    if let Some(c) = &info.capture {
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: glsl::capture::PARAMS_BINDING,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(glsl::capture::PARAMS_SIZE),
            },
            count: None,
        });
        for b in 0..c.strides.len() as u32 {
            entries.push(wgpu::BindGroupLayoutEntry {
                binding: glsl::capture::FIRST_BUFFER_BINDING + b,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            });
        }
    }
    entries
}

/// A draw's vertex stage and, when not the program's own, its fragment stage.
pub type Stages = (wgpu::ShaderModule, Option<wgpu::ShaderModule>);

//! Program objects: creation, attachment, attribute bindings, linking (through `glsl`, then
//! wgpu shader modules and layouts), use, deletion and queries.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use strata_protocol::{ActiveVariable, Text};

use super::context::{ClipControl, Context, Objects, MAX_ATTRIBS};
use super::enums::*;
use super::error::{GlError, GlResult};
use super::glsl::{self, Stage};
use super::program_binary::Recipe;
use super::render::{error_chain, layout_entries};
use super::GlesExecutor;
use strata_device::Gpu;

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
    points_vs: OnceLock<Result<wgpu::ShaderModule, String>>,
    /// Vertex stages for `GL_EXT_clip_control` states other than the default, by (points,
    /// state), created on first use (or why they failed).
    clip_vs: Mutex<HashMap<(bool, ClipControl), Result<wgpu::ShaderModule, String>>>,
}

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
pub(super) fn shader_module(gpu: &Gpu, label: &str, module: naga::Module) -> Result<wgpu::ShaderModule, String> {
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
    /// Deleted while current: freed when no longer in use.
    pub delete_pending: bool,
    /// `glValidateProgram` result.
    pub validated: bool,
    /// `GL_PROGRAM_SEPARABLE_EXT`: whether the next link makes a program pipelines can use.
    pub separable: bool,
}

impl Program {
    /// Makes a link's result the program's: its executable with uniforms at their initial
    /// values, or the failure's log (the previous executable stays in use, as GL specifies).
    pub(super) fn install(&mut self, result: Result<LinkedProgram, String>) {
        match result {
            Ok(linked) => {
                self.data = vec![0; linked.info.block_size as usize];
                self.units = vec![0; linked.info.samplers.len()];
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

/// `f` of program `name`, or `default` after recording the error GL gives for a bad name.
fn with_program<T>(ctx: &mut Context, name: u32, default: T, f: impl FnOnce(&Program) -> T) -> T {
    match ctx.objects.programs.get(&name) {
        Some(p) => f(p),
        None => {
            let e = ctx.objects.shader_or_program_error(name);
            ctx.record(e);
            default
        }
    }
}

/// Frees the shaders among `shaders` that were deleted while attached and are now attached
/// to no program.
fn release_shaders(objects: &mut Objects, shaders: &[u32]) {
    for s in shaders {
        let still = objects.programs.values().any(|p| p.attached.contains(s));
        if !still && objects.shaders.get(s).is_some_and(|x| x.delete_pending) {
            objects.shaders.remove(s);
            objects.forget_label(SHADER_KHR, *s);
        }
    }
}

/// Removes `program` (deleted, and no longer in use) with its label, freeing the shaders
/// that were deleted while attached to it.
pub(super) fn remove_program(objects: &mut Objects, program: u32) {
    if let Some(p) = objects.programs.remove(&program) {
        objects.forget_label(PROGRAM_KHR, program);
        release_shaders(objects, &p.attached);
    }
}

/// The last successful link of `program`, for the active-variable queries: an unlinked
/// program is `GL_INVALID_VALUE`, a name that is no program the usual error.
pub fn linked_for_query(objects: &Objects, program: u32) -> GlResult<&LinkedProgram> {
    match objects.programs.get(&program) {
        Some(p) => p.linked.as_deref().ok_or(GlError::InvalidValue),
        None => Err(objects.shader_or_program_error(program)),
    }
}

/// What a link produced, and the stages it used.
pub(super) type LinkResult = (glsl::Linked, Recipe, LinkedStages);

/// Links the program's attached shaders: the program info log on failure. A separable
/// program may have one stage; it is linked against a stand-in for the other.
fn link_stages(objects: &Objects, p: &Program) -> Result<LinkResult, String> {
    let find = |stage: Stage| p.attached.iter().filter_map(|s| objects.shaders.get(s)).find(|s| s.stage == stage);
    let compiled = |s: &super::shaders::ShaderObj| match &s.compiled {
        Some(c) if s.compiled_ok => Ok(c.clone()),
        _ => Err("error: an attached shader did not compile".to_string()),
    };
    let vertex = find(Stage::Vertex).map(compiled).transpose()?;
    let fragment = find(Stage::Fragment).map(compiled).transpose()?;
    let (info, recipe) = link_either(vertex.as_ref(), fragment.as_ref(), &p.bindings, p.separable)?;
    Ok((info, recipe, LinkedStages::new(p.separable, vertex, fragment)))
}

/// Links both stages, or one alone where `separable` allows.
pub(super) fn link_either(
    vertex: Option<&glsl::Shader>,
    fragment: Option<&glsl::Shader>,
    bindings: &HashMap<String, u32>,
    separable: bool,
) -> Result<(glsl::Linked, Recipe), String> {
    match (vertex, fragment) {
        (Some(v), Some(f)) => link_shaders(v, f, bindings),
        (Some(one), None) | (None, Some(one)) if separable => link_one(one, bindings),
        _ => Err("error: a program needs one vertex and one fragment shader".to_string()),
    }
}

/// Links one compiled stage alone, as a separable program.
pub(super) fn link_one(s: &glsl::Shader, bindings: &HashMap<String, u32>) -> Result<(glsl::Linked, Recipe), String> {
    let info = glsl::link_alone(s, bindings, MAX_ATTRIBS as u32)?;
    Ok((info, Recipe::new(s, bindings)))
}

/// Links two compiled shaders with attribute `bindings`, with what they were linked from.
pub(super) fn link_shaders(
    v: &glsl::Shader,
    f: &glsl::Shader,
    bindings: &HashMap<String, u32>,
) -> Result<(glsl::Linked, Recipe), String> {
    let info = glsl::link(v, f, bindings, MAX_ATTRIBS as u32)?;
    let mut recipe = Recipe::new(v, bindings);
    recipe.fragment = f.source.clone();
    Ok((info, recipe))
}

/// Creates a linked program's shader modules and layouts; the info log if the GPU rejects them.
pub(super) fn create_gpu_program(
    gpu: &Gpu,
    (info, recipe, stages): LinkResult,
    id: u64,
) -> Result<LinkedProgram, String> {
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
    })
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glCreateProgram(&mut self, ctx: &mut Context, name: u32) -> GlResult {
        let objects = &mut ctx.objects;
        if name == 0 || objects.shaders.contains_key(&name) || objects.programs.contains_key(&name) {
            return Err(GlError::InvalidValue);
        }
        self.admit(ctx, strata_device::account::Kind::Program, 1)?;
        ctx.objects.programs.insert(name, Program::default());
        Ok(())
    }

    pub(super) fn glDeleteProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        if program == 0 {
            return Ok(());
        }
        let objects = &mut ctx.objects;
        if !objects.programs.contains_key(&program) {
            return Err(objects.shader_or_program_error(program));
        }
        if let Some(p) = objects.programs.get_mut(&program) {
            p.delete_pending = true;
        }
        super::pipelines::release_if_unused(ctx, program);
        Ok(())
    }

    pub(super) fn glAttachShader(&mut self, ctx: &mut Context, program: u32, shader: u32) -> GlResult {
        let objects = &mut ctx.objects;
        let Some(p) = objects.programs.get(&program) else { return Err(objects.shader_or_program_error(program)) };
        let Some(stage) = objects.shaders.get(&shader).map(|s| s.stage) else {
            return Err(objects.shader_or_program_error(shader));
        };
        let same_stage = p.attached.iter().any(|s| objects.shaders.get(s).is_some_and(|x| x.stage == stage));
        if p.attached.contains(&shader) || same_stage {
            return Err(GlError::InvalidOperation);
        }
        if let Some(p) = objects.programs.get_mut(&program) {
            p.attached.push(shader);
        }
        Ok(())
    }

    pub(super) fn glDetachShader(&mut self, ctx: &mut Context, program: u32, shader: u32) -> GlResult {
        let objects = &mut ctx.objects;
        if !objects.programs.contains_key(&program) {
            return Err(objects.shader_or_program_error(program));
        }
        if !objects.shaders.contains_key(&shader) {
            return Err(objects.shader_or_program_error(shader));
        }
        let Some(p) = objects.programs.get_mut(&program) else { return Ok(()) };
        let i = p.attached.iter().position(|&s| s == shader).ok_or(GlError::InvalidOperation)?;
        p.attached.remove(i);
        release_shaders(objects, &[shader]);
        Ok(())
    }

    pub(super) fn glBindAttribLocation(
        &mut self,
        ctx: &mut Context,
        program: u32,
        index: u32,
        name: Text<'_>,
    ) -> GlResult {
        if index as usize >= MAX_ATTRIBS {
            return Err(GlError::InvalidValue);
        }
        if name.as_str().starts_with("gl_") {
            return Err(GlError::InvalidOperation);
        }
        let objects = &mut ctx.objects;
        match objects.programs.get_mut(&program) {
            Some(p) => {
                p.bindings.insert(name.as_str().to_string(), index);
                Ok(())
            }
            None => Err(objects.shader_or_program_error(program)),
        }
    }

    pub(super) fn glLinkProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        let id = self.next_uid();
        let gpu = &self.gpu;
        let objects = &mut ctx.objects;
        let Some(p) = objects.programs.get(&program) else { return Err(objects.shader_or_program_error(program)) };
        let result = link_stages(objects, p).and_then(|linked| create_gpu_program(gpu, linked, id));
        if let Some(p) = objects.programs.get_mut(&program) {
            p.install(result);
        }
        Ok(())
    }

    pub(super) fn glUseProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        let objects = &mut ctx.objects;
        if program != 0 && !objects.programs.get(&program).is_some_and(|p| p.link_ok) {
            return Err(objects.shader_or_program_error(program));
        }
        let old = std::mem::replace(&mut ctx.bindings.program, program);
        super::pipelines::release_if_unused(ctx, old);
        Ok(())
    }

    pub(super) fn glValidateProgram(&mut self, ctx: &mut Context, program: u32) -> GlResult {
        let objects = &mut ctx.objects;
        match objects.programs.get_mut(&program) {
            Some(p) => {
                p.validated = p.link_ok;
                Ok(())
            }
            None => Err(objects.shader_or_program_error(program)),
        }
    }

    pub(super) fn glIsProgram(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.programs.contains_key(&name)
    }

    pub(super) fn glGetProgramiv(&mut self, ctx: &mut Context, program: u32, pname: u32) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => {
                let linked = p.linked.as_ref();
                match pname {
                    LINK_STATUS => Ok(i32::from(p.link_ok)),
                    // Linking completes within glLinkProgram.
                    COMPLETION_STATUS_KHR => Ok(1),
                    DELETE_STATUS => Ok(i32::from(p.delete_pending)),
                    PROGRAM_SEPARABLE_EXT => Ok(i32::from(p.separable)),
                    VALIDATE_STATUS => Ok(i32::from(p.validated)),
                    INFO_LOG_LENGTH => Ok(if p.log.is_empty() { 0 } else { p.log.len() as i32 + 1 }),
                    ATTACHED_SHADERS => Ok(p.attached.len() as i32),
                    PROGRAM_BINARY_LENGTH_OES => Ok(super::program_binary::length(p)),
                    ACTIVE_ATTRIBUTES => Ok(linked.map_or(0, |l| l.info.attributes.len() as i32)),
                    ACTIVE_UNIFORMS => Ok(linked.map_or(0, |l| l.info.uniforms.len() as i32)),
                    ACTIVE_ATTRIBUTE_MAX_LENGTH => Ok(linked
                        .map_or(0, |l| l.info.attributes.iter().map(|a| a.0.name.len() as i32 + 1).max().unwrap_or(0))),
                    ACTIVE_UNIFORM_MAX_LENGTH => Ok(linked.map_or(0, |l| {
                        l.info
                            .uniforms
                            .iter()
                            .map(|u| u.name.len() as i32 + if u.is_array { 4 } else { 1 })
                            .max()
                            .unwrap_or(0)
                    })),
                    _ => Err(GlError::InvalidEnum),
                }
            }
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            0
        })
    }

    pub(super) fn glGetProgramInfoLog(&mut self, ctx: &mut Context, program: u32) -> String {
        with_program(ctx, program, String::new(), |p| p.log.clone())
    }

    pub(super) fn glGetAttachedShaders(&mut self, ctx: &mut Context, program: u32) -> Vec<u32> {
        with_program(ctx, program, vec![], |p| p.attached.clone())
    }

    pub(super) fn glGetAttribLocation(&mut self, ctx: &mut Context, program: u32, name: Text<'_>) -> i32 {
        let v = match ctx.objects.programs.get(&program) {
            Some(p) => match &p.linked {
                Some(l) => Ok(l.info.attributes.iter().find(|a| a.0.name == name.as_str()).map_or(-1, |a| a.1 as i32)),
                None => Err(GlError::InvalidOperation),
            },
            None => Err(ctx.objects.shader_or_program_error(program)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            -1
        })
    }

    pub(super) fn glGetActiveAttrib(&mut self, ctx: &mut Context, program: u32, index: u32) -> Option<ActiveVariable> {
        let v = linked_for_query(&ctx.objects, program).and_then(|l| {
            let (a, _) = l.info.attributes.get(index as usize).ok_or(GlError::InvalidValue)?;
            Ok(ActiveVariable { size: 1, ty: a.ty.gl_enum(), name: a.name.clone() })
        });
        v.map_err(|e| ctx.record(e)).ok()
    }
}

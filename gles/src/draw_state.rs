//! What a draw uses, decided in one place from the context's state (as ANGLE's `StateCache`
//! answers it for a draw): the target it draws into (`resolve`), the executable it runs (the
//! program in use, or the bound pipeline's stages linked together), the stages its framebuffer
//! and state select (a reversed-Z surface's depth, `GL_EXT_clip_control`, points), the
//! fixed-function state (raster, depth, stencil, blending; each value mapped by `conv`), and
//! the textures its samplers read. Draws ask here; nothing else decides any of it.

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use crate::context::{Context, StencilFace};
use crate::conv::{blend_component, color_writes, compare, stencil_op};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::glsl::types::{Stage, Ty};
use crate::glsl::{self, ClipZ};
use crate::limits::MAX_REVERSED_STAGES;
use crate::linking::link_shaders;
use crate::objects::pipeline::{Combined, Ready};
use crate::objects::program::{create_gpu_program, shader_module, LinkedProgram, LinkedStages, Stages};
use crate::objects::surface::ReversedZ;
use crate::objects::texture::{SamplerState, Texture};
use crate::pipelines::{linked, validate};
use crate::render::{RasterState, Target};
use crate::typed::{ClipControl, TextureTarget};
use crate::GlesExecutor;

/// What a draw uses, once decided: where it draws, and the stages it runs where they are not
/// its program's own.
pub(crate) struct DrawState {
    /// The draw framebuffer's images.
    pub target: Target,
    /// The reversed-Z constants of a reversed-Z surface's framebuffer 0.
    pub reversed: Option<ReversedZ>,
    /// The vertex (and fragment) stage its state selects, where not the program's own.
    pub stages: Option<Stages>,
}

/// The executable a draw runs, with its uniforms' values and samplers' units.
pub struct Executable<'c> {
    /// The linked program.
    pub program: Arc<LinkedProgram>,
    /// Its uniform block.
    pub data: Cow<'c, [u8]>,
    /// The texture unit of each of its samplers.
    pub units: Cow<'c, [u32]>,
    /// The uniform buffer binding each of its uniform blocks reads (`glUniformBlockBinding`).
    pub block_bindings: Cow<'c, [u32]>,
}

/// Links the vertex stage of `vp` with the fragment stage of `fp` (`id`: the executable's).
pub(crate) fn combine(
    gpu: &strata_device::Gpu,
    vp: &LinkedProgram,
    fp: &LinkedProgram,
    id: u64,
) -> Result<Combined, String> {
    let (Some(vs), Some(fs)) = (&vp.stages.vertex, &fp.stages.fragment) else {
        return Err("a stage has no code".into());
    };
    let taken: HashSet<String> = vs.uniforms.iter().map(|u| u.name.clone()).collect();
    let fs = glsl::rename_uniforms(fs, &taken);
    // The vertex program's attribute locations, so that its queries answer for the pipeline.
    let bindings: HashMap<String, u32> = vp.info.attributes.iter().map(|(a, loc)| (a.name.clone(), *loc)).collect();
    let (info, recipe) = link_shaders(vs, &fs, &bindings)?;
    let program = create_gpu_program(gpu, (info, recipe, LinkedStages::default()), id)?;
    let index = |l: &LinkedProgram, name: &str| l.info.uniforms.iter().position(|u| u.name == name);
    let mut sources = Vec::new();
    for u in &program.info.uniforms {
        let source = match index(vp, &u.name) {
            Some(i) if taken.contains(&u.name) => (Stage::Vertex, i),
            _ => fp
                .info
                .uniforms
                .iter()
                .position(|f| glsl::fragment_uniform_name(&f.name, &taken) == u.name)
                .map(|i| (Stage::Fragment, i))
                .ok_or_else(|| format!("uniform `{}' has no source", u.name))?,
        };
        sources.push(source);
    }
    Ok(Combined { key: (vp.id, fp.id), program: Arc::new(program), sources })
}

impl Context {
    /// The executable draws run: the program in use, else the bound pipeline's as its last
    /// [`GlesExecutor::prepare_pipeline`] left it; `None` if there is none.
    pub fn executable(&self) -> Option<Executable<'_>> {
        let objects = &self.objects;
        let own = |name: u32| {
            let p = objects.programs.get(&name)?;
            Some(Executable {
                program: p.linked.clone()?,
                data: Cow::Borrowed(&p.data),
                units: Cow::Borrowed(&p.units),
                block_bindings: Cow::Borrowed(&p.block_bindings),
            })
        };
        if self.bindings.program != 0 {
            return own(self.bindings.program);
        }
        let pl = objects.pipelines.get(&self.bindings.pipeline)?;
        match pl.ready.as_ref()? {
            Ready::Own(name) => own(*name),
            Ready::Combined(c) => {
                let (data, units) = c.feed(objects.programs.get(&pl.vertex)?, objects.programs.get(&pl.fragment)?)?;
                // Program pipelines are ES 3.1's and `GL_EXT_separate_shader_objects`'s: their
                // blocks read binding 0.
                Some(Executable {
                    program: c.program.clone(),
                    data: Cow::Owned(data),
                    units: Cow::Owned(units),
                    block_bindings: Cow::Owned(Vec::new()),
                })
            }
        }
    }

    /// The linked program draws run, without its uniforms' values (see [`Context::executable`]).
    pub fn draw_program(&self) -> Option<Arc<LinkedProgram>> {
        let objects = &self.objects;
        let own = |name: u32| objects.programs.get(&name).and_then(|p| p.linked.clone());
        if self.bindings.program != 0 {
            return own(self.bindings.program);
        }
        match objects.pipelines.get(&self.bindings.pipeline)?.ready.as_ref()? {
            Ready::Own(name) => own(*name),
            Ready::Combined(c) => Some(c.program.clone()),
        }
    }

    /// The program `glUniform*` writes: the one in use, else the bound pipeline's active
    /// program (0 for none).
    pub fn uniform_program(&self) -> u32 {
        match self.bindings.program {
            0 => self.objects.pipelines.get(&self.bindings.pipeline).map_or(0, |pl| pl.active),
            p => p,
        }
    }
}

impl GlesExecutor {
    /// What a draw (`points`: of `GL_POINTS`) uses now: its target (an incomplete framebuffer
    /// is `GL_INVALID_FRAMEBUFFER_OPERATION`), its executable readied (a pipeline that cannot
    /// draw is `GL_INVALID_OPERATION`) and its stages. `None`: the draw is dropped, GL having no
    /// error for a variant of its stages that failed (the reason is logged).
    pub(crate) fn draw_state(&mut self, ctx: &mut Context, points: bool) -> GlResult<Option<DrawState>> {
        let target = self.draw_target(ctx).map_err(|_| GlError::InvalidFramebufferOperation)?;
        self.prepare_pipeline(ctx)?;
        let reversed = self.reversed_target(ctx);
        match self.draw_stages(ctx, reversed, points) {
            Ok(stages) => Ok(Some(DrawState { target, reversed, stages })),
            Err(e) => {
                tracing::warn!("draw dropped: a variant of the program's stages failed: {e}");
                Ok(None)
            }
        }
    }

    /// The reversed-Z constants of the draw framebuffer when it is a reversed-Z surface's
    /// framebuffer 0.
    pub(super) fn reversed_target(&self, ctx: &Context) -> Option<ReversedZ> {
        self.reversed_framebuffer(ctx.bindings.framebuffer)
    }

    /// The reversed-Z constants of framebuffer `bound` (a draw or read binding) when it is a
    /// reversed-Z surface's framebuffer 0.
    pub(super) fn reversed_framebuffer(&self, bound: u32) -> Option<ReversedZ> {
        let (_, sid) = self.current?;
        if bound != 0 {
            return None;
        }
        self.surfaces.get(&sid)?.reversed
    }

    /// The stages of a draw of the current program (`points`: of `GL_POINTS`) into a
    /// framebuffer with `reversed` depth, when they are not the program's own; `None` without
    /// a linked program or where its own serve. The error says why a variant failed.
    pub(super) fn draw_stages(
        &mut self,
        ctx: &Context,
        reversed: Option<ReversedZ>,
        points: bool,
    ) -> Result<Option<Stages>, String> {
        let Some(program) = ctx.draw_program() else {
            return Ok(None);
        };
        let clip = ctx.raster.clip;
        if let Some(r) = reversed {
            return self.reversed_stages(&program, r, points, clip.upper_left).map(Some);
        }
        if clip != ClipControl::default() {
            return program.clip_vs(&self.gpu, points, clip).map(|vs| Some((vs, None)));
        }
        if points {
            return program.points_vs(&self.gpu).map(|vs| Some((vs, None)));
        }
        Ok(None)
    }

    /// `program`'s reversed-Z stages for the current surface `r`: the vertex stage
    /// (`points`: its points variant; `upper_left`: with that window origin) and, if it reads
    /// `gl_FragCoord`, the fragment stage; created on first use and kept by the surface.
    fn reversed_stages(
        &mut self,
        program: &LinkedProgram,
        r: ReversedZ,
        points: bool,
        upper_left: bool,
    ) -> Result<Stages, String> {
        let (_, sid) = self.current.ok_or("no current surface")?;
        let surface = self.surfaces.get_mut(&sid).ok_or("no current surface")?;
        let key = (program.id, points, upper_left);
        if let Some(stages) = surface.reversed_stages.get(&key) {
            return Ok(stages.clone());
        }
        let gpu = &self.gpu;
        let z = ClipZ::Reversed { near: r.near, far: r.far };
        let vs = shader_module(gpu, "vs reversed-z", program.info.vertex_variant(points, upper_left, z)?)?;
        let fs = match program.info.reversed_fragment() {
            Some(fs) => Some(shader_module(gpu, "fs reversed-z", fs?)?),
            None => None,
        };
        // Programs relinked frame after frame would otherwise grow the cache without end.
        if surface.reversed_stages.len() >= MAX_REVERSED_STAGES {
            surface.reversed_stages.clear();
        }
        surface.reversed_stages.insert(key, (vs.clone(), fs.clone()));
        Ok((vs, fs))
    }

    /// Before a draw with no program in use: validates the bound pipeline (`GL_INVALID_OPERATION`
    /// if it cannot draw) and links its two programs' stages together where it needs that.
    pub(super) fn prepare_pipeline(&mut self, ctx: &mut Context) -> GlResult {
        if ctx.bindings.program != 0 || ctx.bindings.pipeline == 0 {
            return Ok(());
        }
        let objects = &ctx.objects;
        let Some(pl) = objects.pipelines.get(&ctx.bindings.pipeline) else { return Ok(()) };
        validate(objects, pl).map_err(|_| GlError::InvalidOperation)?;
        let ready = match (linked(objects, pl.vertex), linked(objects, pl.fragment)) {
            // As on Mesa, a pipeline with no stages cannot draw.
            (None, None) => return Err(GlError::InvalidOperation),
            (Some(_), None) => Some(Ready::Own(pl.vertex)),
            (None, Some(_)) => Some(Ready::Own(pl.fragment)),
            (Some(_), Some(_)) if pl.vertex == pl.fragment => Some(Ready::Own(pl.vertex)),
            (Some(v), Some(f)) => match &pl.ready {
                Some(Ready::Combined(c)) if c.key == (v.id, f.id) => return Ok(()),
                _ => {
                    let (v, f) = (v.clone(), f.clone());
                    let id = self.next_uid();
                    match combine(&self.gpu, &v, &f, id) {
                        Ok(c) => Some(Ready::Combined(c)),
                        Err(e) => {
                            tracing::warn!("a program pipeline's stages failed to link together: {e}");
                            return Err(GlError::InvalidOperation);
                        }
                    }
                }
            },
        };
        if let Some(pl) = ctx.objects.pipelines.get_mut(&ctx.bindings.pipeline) {
            pl.ready = ready;
        }
        Ok(())
    }
}

/// The fixed-function state of a draw with `topology` into `target` by a program that writes
/// a second colour (`dual`) or not.
pub(crate) fn raster_state(
    ctx: &Context,
    topology: wgpu::PrimitiveTopology,
    target: &Target,
    dual: bool,
) -> RasterState {
    let (raster, ds, blend) = (&ctx.raster, &ctx.depth_stencil, &ctx.blend);
    let triangles = matches!(topology, wgpu::PrimitiveTopology::TriangleList | wgpu::PrimitiveTopology::TriangleStrip);
    let cull = (raster.cull && triangles).then_some(match raster.cull_face {
        FRONT => Some(wgpu::Face::Front),
        BACK => Some(wgpu::Face::Back),
        _ => None,
    });
    // Culling both faces draws nothing; emulate with a never-passing depth test.
    let cull_all = cull == Some(None);
    let depth = if target.has_depth() && (ds.depth_test || cull_all) {
        let func = if cull_all { NEVER } else { ds.depth_func };
        Some((compare(func), ds.depth_mask && !cull_all))
    } else {
        None
    };
    let stencil = (ds.stencil_test && target.has_stencil()).then(|| {
        let face = |f: &StencilFace| wgpu::StencilFaceState {
            compare: compare(f.func),
            fail_op: stencil_op(f.fail),
            depth_fail_op: stencil_op(f.zfail),
            pass_op: stencil_op(f.zpass),
        };
        wgpu::StencilState {
            front: face(&ds.stencil[0]),
            back: face(&ds.stencil[1]),
            read_mask: ds.stencil[0].mask & 0xff,
            write_mask: ds.stencil[0].write & 0xff,
        }
    });
    let blend_state = blend.enabled.then(|| wgpu::BlendState {
        color: blend_component(blend.func[0], blend.func[1], blend.eq[0], dual),
        alpha: blend_component(blend.func[2], blend.func[3], blend.eq[1], dual),
    });
    let bias = (raster.polygon_offset_fill && triangles && target.has_depth()).then(|| {
        // GL's units are in minimum resolvable depth steps, as Vulkan's constant factor is.
        let [factor, units, clamp] = raster.polygon_offset;
        (factor.to_bits(), units as i32, clamp.to_bits())
    });
    RasterState {
        topology,
        strip_index: None,
        front_ccw: raster.front_face == CCW,
        cull: cull.flatten(),
        depth,
        stencil,
        bias,
        blend: blend_state,
        // Channels each colour buffer lacks keep their fixed values (the pipeline masks them).
        write_mask: color_writes(blend.color_mask),
        points: false,
        reversed_z: None,
        unclipped_depth: raster.depth_clamp,
        clip: raster.clip,
        coverage_mask: coverage_mask(raster, target.samples),
        // wgpu takes the coverage from output 0's alpha, so that output has a float image.
        alpha_to_coverage: raster.alpha_to_coverage
            && target.samples > 1
            && target.color.as_ref().is_some_and(|(t, _)| {
                matches!(t.format().sample_type(None, None), Some(wgpu::TextureSampleType::Float { .. }))
            }),
    }
}

/// The samples of a target of `samples` samples that draws may cover: with
/// `GL_SAMPLE_COVERAGE` on, the first `value × samples` (truncated, as Mesa takes them), or the
/// others if inverted; else all of them.
fn coverage_mask(raster: &crate::context::Raster, samples: u32) -> u64 {
    if !raster.sample_coverage || samples <= 1 {
        return !0;
    }
    let (value, invert) = raster.coverage;
    let n = (value * samples as f32) as u32;
    let mask = (1u64 << n.min(samples)) - 1;
    if invert {
        !mask & ((1u64 << samples) - 1)
    } else {
        mask
    }
}

/// A texture a sampler reads, with the state it is read with.
pub(crate) struct Bound<'c> {
    /// The texture.
    pub texture: &'c Texture,
    /// Its sampling state, or the sampler object's bound to the unit over it (ES 3.0).
    pub state: SamplerState,
    /// The border colour (`GL_EXT_texture_border_clamp`), the sampler object's where one is
    /// bound.
    pub border: [f32; 4],
}

/// The texture each of `program`'s samplers reads through its unit in `units`: the one bound
/// there for the sampler's target where it is complete (read with the unit's sampler object,
/// if one is bound) and has an image; `None` where the sampler reads black.
pub(crate) fn bound_textures<'c>(ctx: &'c Context, program: &LinkedProgram, units: &[u32]) -> Vec<Option<Bound<'c>>> {
    program
        .info
        .samplers
        .iter()
        .zip(units.iter())
        .map(|((ty, _), unit)| {
            let target = match ty.sampler_base() {
                Ty::SamplerCube | Ty::SamplerCubeShadow => TextureTarget::CubeMap,
                Ty::SamplerExternal => TextureTarget::External,
                Ty::Sampler3D => TextureTarget::ThreeD,
                Ty::Sampler2DArray | Ty::Sampler2DArrayShadow => TextureTarget::TwoDArray,
                _ => TextureTarget::TwoD,
            };
            let name = ctx.bindings.units.get(*unit as usize)?[target.slot()];
            let t = ctx.objects.texture(target, name)?;
            let object = ctx.bindings.samplers.get(*unit as usize).and_then(|s| ctx.objects.samplers.get(s));
            let (state, border) = match object {
                Some(s) => (s.state.over(&t.sampler), s.border),
                None => (t.sampler, t.border),
            };
            (t.target == target.as_gl() && t.complete_with(&state) && t.gpu.is_some()).then_some(Bound {
                texture: t,
                state,
                border,
            })
        })
        .collect()
}

//! `GL_EXT_separate_shader_objects`: program pipeline objects, whose stages come from
//! separable programs, validated as Mesa validates them; and the executable draws run. While
//! no program is in use, a bound pipeline draws: where one program serves both stages (or only
//! one stage is filled), its own executable; otherwise the vertex stage of one program and the
//! fragment stage of another, linked again into one executable that is kept until either
//! program is relinked. Each program keeps its own uniform values; the executable's block is
//! filled from both at each draw, the fragment stage's uniforms renamed where the names clash.

use std::collections::HashMap;
use std::sync::Arc;

use strata_protocol::{Slice, Text};

use crate::context::{Context, Objects};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::glsl;
use crate::glsl::types::Stage;
use crate::limits::MAX_PIPELINES;
use crate::linking::release_if_unused;
use crate::objects::pipeline::Pipeline;
use crate::objects::program::{create_gpu_program, LinkedProgram, LinkedStages};
use crate::GlesExecutor;

/// `GL_VERTEX_SHADER_BIT_EXT`.
const VERTEX_SHADER_BIT: u32 = 0x1;
/// `GL_FRAGMENT_SHADER_BIT_EXT`.
const FRAGMENT_SHADER_BIT: u32 = 0x2;
/// `GL_ALL_SHADER_BITS_EXT`.
const ALL_SHADER_BITS: u32 = u32::MAX;
/// `GL_ACTIVE_PROGRAM_EXT`.
const ACTIVE_PROGRAM: u32 = 0x8259;

/// The linked program `name`, if it has an executable.
pub(crate) fn linked(objects: &Objects, name: u32) -> Option<&Arc<LinkedProgram>> {
    objects.programs.get(&name).and_then(|p| p.linked.as_ref())
}

/// Checks that `pl`'s stages can draw together; the error is the info log (empty where
/// Mesa's is: interfaces that differ).
pub(crate) fn validate(objects: &Objects, pl: &Pipeline) -> Result<(), String> {
    for (name, bits) in [(pl.vertex, VERTEX_SHADER_BIT), (pl.fragment, FRAGMENT_SHADER_BIT)] {
        let Some(l) = linked(objects, name) else { continue };
        let serves = bits | if pl.vertex == pl.fragment { VERTEX_SHADER_BIT | FRAGMENT_SHADER_BIT } else { 0 };
        if l.stages.bits & !serves != 0 {
            return Err(format!("Program {name} is active for some, but not all, of the stages it was linked with\n"));
        }
    }
    if pl.vertex != pl.fragment {
        let stage = |name, f: fn(&LinkedStages) -> &Option<glsl::Shader>| {
            linked(objects, name).and_then(|l| f(&l.stages).as_ref())
        };
        if let (Some(vs), Some(fs)) = (stage(pl.vertex, |s| &s.vertex), stage(pl.fragment, |s| &s.fragment)) {
            if !glsl::interfaces_match(vs, fs) {
                return Err(String::new());
            }
        }
    }
    Ok(())
}

/// The pipeline `name` for a command that needs one: never generated is `GL_INVALID_OPERATION`.
fn pipeline(ctx: &mut Context, name: u32) -> GlResult<&mut Pipeline> {
    ctx.objects.pipelines.get_mut(&name).ok_or(GlError::InvalidOperation)
}

/// A linked program for a pipeline command: 0 is none; a bad name is GL's usual error; an
/// unlinked program is `GL_INVALID_OPERATION`.
fn pipeline_program(objects: &Objects, program: u32) -> GlResult<Option<&Arc<LinkedProgram>>> {
    if program == 0 {
        return Ok(None);
    }
    let p = objects.programs.get(&program).ok_or_else(|| objects.shader_or_program_error(program))?;
    match &p.linked {
        Some(l) if p.link_ok => Ok(Some(l)),
        _ => Err(GlError::InvalidOperation),
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenProgramPipelinesEXT(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        let pipelines = &mut ctx.objects.pipelines;
        if pipelines.len() as u64 + pipelines.fresh(names.iter()) > MAX_PIPELINES {
            return Err(GlError::OutOfMemory);
        }
        pipelines.generate(names.iter());
        Ok(())
    }

    /// Deleting the bound pipeline unbinds it; unknown names and 0 are ignored.
    pub(super) fn glDeleteProgramPipelinesEXT(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in names.iter() {
            if n != 0 && ctx.bindings.pipeline == n {
                ctx.bindings.pipeline = 0;
            }
            if let Some(pl) = ctx.objects.pipelines.remove(&n) {
                for program in [pl.vertex, pl.fragment, pl.active] {
                    release_if_unused(ctx, program);
                }
            }
        }
        Ok(())
    }

    pub(super) fn glBindProgramPipelineEXT(&mut self, ctx: &mut Context, name: u32) -> GlResult {
        if name != 0 {
            pipeline(ctx, name)?.ever_bound = true;
        }
        ctx.bindings.pipeline = name;
        Ok(())
    }

    pub(super) fn glIsProgramPipelineEXT(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.pipelines.get(&name).is_some_and(|pl| pl.ever_bound)
    }

    pub(super) fn glUseProgramStagesEXT(
        &mut self,
        ctx: &mut Context,
        name: u32,
        stages: u32,
        program: u32,
    ) -> GlResult {
        pipeline(ctx, name)?;
        if stages != ALL_SHADER_BITS && stages & !(VERTEX_SHADER_BIT | FRAGMENT_SHADER_BIT) != 0 {
            return Err(GlError::InvalidValue);
        }
        let has = match pipeline_program(&ctx.objects, program)? {
            Some(l) if !l.stages.separable => return Err(GlError::InvalidOperation),
            Some(l) => l.stages.bits,
            None => 0,
        };
        let pl = pipeline(ctx, name)?;
        pl.ever_bound = true;
        // As on Mesa, new stages are not validated yet.
        pl.validated = false;
        pl.log.clear();
        let mut replaced = Vec::new();
        for (bit, slot) in [(VERTEX_SHADER_BIT, &mut pl.vertex), (FRAGMENT_SHADER_BIT, &mut pl.fragment)] {
            if stages & bit != 0 {
                replaced.push(std::mem::replace(slot, if has & bit != 0 { program } else { 0 }));
            }
        }
        for old in replaced {
            release_if_unused(ctx, old);
        }
        Ok(())
    }

    pub(super) fn glActiveShaderProgramEXT(&mut self, ctx: &mut Context, name: u32, program: u32) -> GlResult {
        pipeline(ctx, name)?;
        pipeline_program(&ctx.objects, program)?;
        let pl = pipeline(ctx, name)?;
        pl.ever_bound = true;
        let old = std::mem::replace(&mut pl.active, program);
        release_if_unused(ctx, old);
        Ok(())
    }

    pub(super) fn glValidateProgramPipelineEXT(&mut self, ctx: &mut Context, name: u32) -> GlResult {
        pipeline(ctx, name)?;
        let result = ctx.objects.pipelines.get(&name).map(|pl| validate(&ctx.objects, pl));
        let pl = pipeline(ctx, name)?;
        pl.ever_bound = true;
        match result {
            Some(Err(log)) => {
                pl.validated = false;
                pl.log = log;
            }
            _ => {
                pl.validated = true;
                pl.log.clear();
            }
        }
        Ok(())
    }

    pub(super) fn glGetProgramPipelineivEXT(&mut self, ctx: &mut Context, name: u32, pname: u32) -> Vec<i32> {
        let v = match ctx.objects.pipelines.get(&name) {
            None => Err(GlError::InvalidOperation),
            Some(pl) => match pname {
                ACTIVE_PROGRAM => Ok(pl.active as i32),
                VERTEX_SHADER => Ok(pl.vertex as i32),
                FRAGMENT_SHADER => Ok(pl.fragment as i32),
                VALIDATE_STATUS => Ok(i32::from(pl.validated)),
                INFO_LOG_LENGTH => Ok(if pl.log.is_empty() { 0 } else { pl.log.len() as i32 + 1 }),
                _ => Err(GlError::InvalidEnum),
            },
        };
        v.map(|v| vec![v]).unwrap_or_else(|e| {
            ctx.record(e);
            vec![]
        })
    }

    pub(super) fn glGetProgramPipelineInfoLogEXT(&mut self, ctx: &mut Context, name: u32) -> String {
        match ctx.objects.pipelines.get(&name) {
            Some(pl) => pl.log.clone(),
            None => {
                // As on Mesa: unlike the other pipeline calls, `GL_INVALID_VALUE`.
                ctx.record(GlError::InvalidValue);
                String::new()
            }
        }
    }

    pub(super) fn glProgramParameteriEXT(
        &mut self,
        ctx: &mut Context,
        program: u32,
        pname: u32,
        value: i32,
    ) -> GlResult {
        let objects = &mut ctx.objects;
        let error = objects.shader_or_program_error(program);
        let p = objects.programs.get_mut(&program).ok_or(error)?;
        if pname != PROGRAM_SEPARABLE_EXT {
            return Err(GlError::InvalidEnum);
        }
        if !matches!(value, 0 | 1) {
            return Err(GlError::InvalidValue);
        }
        p.separable = value == 1;
        Ok(())
    }

    /// A program of one stage made from `source`: separable, linked if the source compiles,
    /// else unlinked with the compile's log.
    pub(super) fn glCreateShaderProgramvEXT(
        &mut self,
        ctx: &mut Context,
        shader_type: u32,
        name: u32,
        source: Text<'_>,
    ) -> GlResult {
        let stage = match shader_type {
            VERTEX_SHADER => Stage::Vertex,
            FRAGMENT_SHADER => Stage::Fragment,
            _ => return Err(GlError::InvalidEnum),
        };
        self.glCreateProgram(ctx, name)?;
        let id = self.next_uid();
        let compiled = glsl::compile(stage, source.as_str());
        let compiled_ok = compiled.is_ok();
        let result = compiled.and_then(|s| {
            let (info, recipe) = crate::linking::link_one(&s, &HashMap::new())?;
            let stages = match stage {
                Stage::Vertex => LinkedStages::new(true, Some(s), None),
                Stage::Fragment => LinkedStages::new(true, None, Some(s)),
            };
            create_gpu_program(&self.gpu, (info, recipe, stages), id)
        });
        if let Some(p) = ctx.objects.programs.get_mut(&name) {
            // As on Mesa, only a program whose source compiled is made separable.
            p.separable = compiled_ok;
            p.install(result);
        }
        Ok(())
    }
}

//! Program objects: creation, attachment, attribute bindings, linking (through `glsl`, then
//! wgpu shader modules and layouts), use, deletion and queries.

use strata_protocol::{ActiveVariable, Text};

use crate::context::Context;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_ATTRIBS;
use crate::linking::{link_stages, linked_for_query, release_shaders};
use crate::objects::program::{create_gpu_program, Program};
use crate::GlesExecutor;

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
        crate::linking::release_if_unused(ctx, program);
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
        crate::linking::release_if_unused(ctx, old);
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
                    PROGRAM_BINARY_LENGTH_OES => Ok(crate::program_binary::length(p)),
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

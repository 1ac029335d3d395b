//! Shader objects: creation, source, compilation (through `glsl`), deletion and queries.

use strata_protocol::{Blob, Slice, Text};

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::glsl;
use crate::glsl::types::Stage;
use crate::objects::program::ShaderObj;
use crate::GlesExecutor;

/// `f` of shader `name`, or `default` after recording the error GL gives for a bad name.
fn with_shader<T>(ctx: &mut Context, name: u32, default: T, f: impl FnOnce(&ShaderObj) -> T) -> T {
    match ctx.objects.shaders.get(&name) {
        Some(s) => f(s),
        None => {
            let e = ctx.objects.shader_or_program_error(name);
            ctx.record(e);
            default
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glCreateShader(&mut self, ctx: &mut Context, shader_type: u32, name: u32) -> GlResult {
        let stage = match shader_type {
            VERTEX_SHADER => Stage::Vertex,
            FRAGMENT_SHADER => Stage::Fragment,
            _ => return Err(GlError::InvalidEnum),
        };
        let objects = &mut ctx.objects;
        if name == 0 || objects.shaders.contains_key(&name) || objects.programs.contains_key(&name) {
            return Err(GlError::InvalidValue);
        }
        self.admit(ctx, strata_device::account::Kind::Shader, 1)?;
        let objects = &mut ctx.objects;
        objects.shaders.insert(
            name,
            ShaderObj {
                stage,
                source: String::new(),
                compiled: None,
                compiled_ok: false,
                log: String::new(),
                delete_pending: false,
            },
        );
        Ok(())
    }

    pub(super) fn glShaderSource(&mut self, ctx: &mut Context, shader: u32, source: Text<'_>) -> GlResult {
        let objects = &mut ctx.objects;
        match objects.shaders.get_mut(&shader) {
            Some(s) => s.source = source.as_str().to_string(),
            None => return Err(objects.shader_or_program_error(shader)),
        }
        Ok(())
    }

    pub(super) fn glCompileShader(&mut self, ctx: &mut Context, shader: u32) -> GlResult {
        let objects = &mut ctx.objects;
        let Some(s) = objects.shaders.get_mut(&shader) else { return Err(objects.shader_or_program_error(shader)) };
        match glsl::compile(s.stage, &s.source) {
            Ok(c) => {
                s.log = c.log.clone();
                s.compiled = Some(c);
                s.compiled_ok = true;
            }
            Err(log) => {
                s.compiled_ok = false;
                s.log = log;
            }
        }
        Ok(())
    }

    /// No binary format is offered (`GL_NUM_SHADER_BINARY_FORMATS` is 0).
    pub(super) fn glShaderBinary(
        &mut self,
        _ctx: &mut Context,
        _shaders: Slice<'_, u32>,
        _binary_format: u32,
        _binary: Blob<'_>,
    ) -> GlResult {
        Err(GlError::InvalidEnum)
    }

    /// A hint that needs no action: the compiler holds no resources between compiles.
    pub(super) fn glReleaseShaderCompiler(&mut self, _ctx: &mut Context) -> GlResult {
        Ok(())
    }

    pub(super) fn glDeleteShader(&mut self, ctx: &mut Context, shader: u32) -> GlResult {
        if shader == 0 {
            return Ok(());
        }
        let objects = &mut ctx.objects;
        if !objects.shaders.contains_key(&shader) {
            return Err(objects.shader_or_program_error(shader));
        }
        if objects.programs.values().any(|p| p.attached.contains(&shader)) {
            if let Some(s) = objects.shaders.get_mut(&shader) {
                s.delete_pending = true;
            }
        } else {
            objects.shaders.remove(&shader);
            objects.forget_label(SHADER_KHR, shader);
        }
        Ok(())
    }

    pub(super) fn glIsShader(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.shaders.contains_key(&name)
    }

    pub(super) fn glGetShaderiv(&mut self, ctx: &mut Context, shader: u32, pname: u32) -> i32 {
        let v = match ctx.objects.shaders.get(&shader) {
            Some(s) => match pname {
                SHADER_TYPE => Ok(if s.stage == Stage::Vertex { VERTEX_SHADER as i32 } else { FRAGMENT_SHADER as i32 }),
                COMPILE_STATUS => Ok(i32::from(s.compiled_ok)),
                // Compiling completes within glCompileShader.
                COMPLETION_STATUS_KHR => Ok(1),
                DELETE_STATUS => Ok(i32::from(s.delete_pending)),
                INFO_LOG_LENGTH => Ok(if s.log.is_empty() { 0 } else { s.log.len() as i32 + 1 }),
                SHADER_SOURCE_LENGTH => Ok(if s.source.is_empty() { 0 } else { s.source.len() as i32 + 1 }),
                _ => Err(GlError::InvalidEnum),
            },
            None => Err(ctx.objects.shader_or_program_error(shader)),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            0
        })
    }

    pub(super) fn glGetShaderInfoLog(&mut self, ctx: &mut Context, shader: u32) -> String {
        with_shader(ctx, shader, String::new(), |s| s.log.clone())
    }

    pub(super) fn glGetShaderSource(&mut self, ctx: &mut Context, shader: u32) -> String {
        with_shader(ctx, shader, String::new(), |s| s.source.clone())
    }

    pub(super) fn glGetShaderPrecisionFormat(
        &mut self,
        ctx: &mut Context,
        shader_type: u32,
        precision_type: u32,
    ) -> ([i32; 2], i32) {
        if !matches!(shader_type, VERTEX_SHADER | FRAGMENT_SHADER) || !(LOW_FLOAT..=HIGH_INT).contains(&precision_type)
        {
            ctx.record(GlError::InvalidEnum);
            return ([0, 0], 0);
        }
        if precision_type <= LOW_FLOAT + 2 {
            ([127, 127], 23)
        } else {
            ([31, 30], 0)
        }
    }
}

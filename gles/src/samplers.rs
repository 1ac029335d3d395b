//! Sampler objects (ES 3.0): names, their binding to texture units (where they override the
//! sampling state of the textures read through the unit; `draw_state::bound_textures`), and
//! their parameters, set and read through `sampling` as a texture's are. Checked in the order
//! of Mesa's `samplerobj.c`: an unknown sampler first, then the name, then the value.

use strata_protocol::Slice;

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_UNITS;
use crate::objects::sampler::Sampler;
use crate::sampling::{self, Allowed, Owner};
use crate::GlesExecutor;

/// Sampler object `name`: `GL_INVALID_OPERATION` where it is none.
fn sampler(ctx: &mut Context, name: u32) -> GlResult<&mut Sampler> {
    ctx.objects.samplers.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)
}

impl GlesExecutor {
    /// Sets one parameter of sampler object `name` from `v`.
    fn sampler_parameter(&mut self, ctx: &mut Context, name: u32, pname: u32, v: f32) -> GlResult {
        let allowed = Allowed { es3: true, border: self.has_border_clamp() };
        sampler(ctx, name)?;
        let setting = sampling::setting(Owner::Sampler, allowed, pname, v)?;
        setting.apply(&mut sampler(ctx, name)?.state);
        Ok(())
    }

    /// One parameter of sampler object `name` (nothing, with the error recorded, for an
    /// unknown sampler or name).
    fn get_sampler_parameter(&mut self, ctx: &mut Context, name: u32, pname: u32) -> Vec<f32> {
        let answer = match sampler(ctx, name) {
            Ok(s) if pname == TEXTURE_BORDER_COLOR_EXT => Ok(s.border.to_vec()),
            Ok(s) => {
                sampling::value(Owner::Sampler, true, &s.state, pname).map(|v| vec![v]).ok_or(GlError::InvalidEnum)
            }
            Err(e) => Err(e),
        };
        answer.unwrap_or_else(|e| {
            ctx.record(e);
            vec![]
        })
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenSamplers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        self.admit(ctx, strata_device::account::Kind::Texture, ctx.objects.samplers.fresh(names.iter()))?;
        ctx.objects.samplers.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteSamplers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.objects.samplers.delete(names.iter()) {
            ctx.objects.forget_label(SAMPLER, n);
            for s in ctx.bindings.samplers.iter_mut().filter(|s| **s == n) {
                *s = 0;
            }
        }
        Ok(())
    }

    pub(super) fn glIsSampler(&mut self, ctx: &mut Context, sampler: u32) -> bool {
        ctx.objects.samplers.is(sampler)
    }

    pub(super) fn glBindSampler(&mut self, ctx: &mut Context, unit: u32, sampler: u32) -> GlResult {
        if unit as usize >= MAX_UNITS {
            return Err(GlError::InvalidValue);
        }
        if sampler != 0 && !ctx.objects.samplers.is(sampler) {
            return Err(GlError::InvalidOperation);
        }
        ctx.bindings.samplers[unit as usize] = sampler;
        Ok(())
    }

    pub(super) fn glSamplerParameteri(&mut self, ctx: &mut Context, sampler: u32, pname: u32, param: i32) -> GlResult {
        self.sampler_parameter(ctx, sampler, pname, param as f32)
    }

    pub(super) fn glSamplerParameterf(&mut self, ctx: &mut Context, sampler: u32, pname: u32, param: f32) -> GlResult {
        self.sampler_parameter(ctx, sampler, pname, param)
    }

    pub(super) fn glSamplerParameteriv(
        &mut self,
        ctx: &mut Context,
        name: u32,
        pname: u32,
        params: Slice<'_, i32>,
    ) -> GlResult {
        if pname == TEXTURE_BORDER_COLOR_EXT {
            let v: Vec<f32> = params.iter().map(sampling::normalized).collect();
            return self.sampler_border(ctx, name, &v);
        }
        let v = params.get(0).ok_or(GlError::InvalidValue)?;
        self.sampler_parameter(ctx, name, pname, v as f32)
    }

    pub(super) fn glSamplerParameterfv(
        &mut self,
        ctx: &mut Context,
        name: u32,
        pname: u32,
        params: Slice<'_, f32>,
    ) -> GlResult {
        if pname == TEXTURE_BORDER_COLOR_EXT {
            return self.sampler_border(ctx, name, &params.to_vec());
        }
        let v = params.get(0).ok_or(GlError::InvalidValue)?;
        self.sampler_parameter(ctx, name, pname, v)
    }

    /// Sets sampler object `name`'s border colour (four values; `GL_EXT_texture_border_clamp`).
    fn sampler_border(&mut self, ctx: &mut Context, name: u32, v: &[f32]) -> GlResult {
        let s = sampler(ctx, name)?;
        let [r, g, b, a] = *v else { return Err(GlError::InvalidValue) };
        s.border = [r, g, b, a];
        Ok(())
    }

    pub(super) fn glGetSamplerParameteriv(&mut self, ctx: &mut Context, sampler: u32, pname: u32) -> Vec<i32> {
        sampling::as_ints(pname, self.get_sampler_parameter(ctx, sampler, pname))
    }

    pub(super) fn glGetSamplerParameterfv(&mut self, ctx: &mut Context, sampler: u32, pname: u32) -> Vec<f32> {
        self.get_sampler_parameter(ctx, sampler, pname)
    }
}

//! Texture objects: names, units and bindings, sampling parameters, their GPU images and
//! mipmap generation. Image specification (uploads and copies) is in `teximage`.

use strata_protocol::Slice;

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::Compressed;
use crate::sampling::{self, Allowed, Owner};
use crate::typed::TextureTarget;
use crate::GlesExecutor;

/// `GL_REQUIRED_TEXTURE_IMAGE_UNITS_OES`: the units an external texture takes (always 1).
const REQUIRED_TEXTURE_IMAGE_UNITS_OES: u32 = 0x8D68;

/// Sets `GL_TEXTURE_BORDER_COLOR_EXT` of the texture bound to `target` (four values).
fn set_border(ctx: &mut Context, target: u32, v: &[f32]) -> GlResult {
    let target = TextureTarget::from_gl_in(target, ctx.es3())?;
    let [r, g, b, a] = *v else { return Err(GlError::InvalidValue) };
    let name = ctx.bindings.texture(target);
    let t = ctx.objects.texture_mut(target, name).ok_or(GlError::InvalidOperation)?;
    t.border = [r, g, b, a];
    Ok(())
}

/// Sets one sampling parameter of the texture bound to `target`.
fn tex_parameter(ctx: &mut Context, border: bool, target: u32, pname: u32, v: f32) -> GlResult {
    let target = TextureTarget::from_gl_in(target, ctx.es3())?;
    // GL_OES_EGL_image_external: external textures have no mipmaps and only clamp.
    if target == TextureTarget::External {
        let ok = match pname {
            TEXTURE_MIN_FILTER => matches!(v as u32, NEAREST | LINEAR),
            TEXTURE_WRAP_S | TEXTURE_WRAP_T => v as u32 == CLAMP_TO_EDGE,
            _ => true,
        };
        if !ok {
            return Err(GlError::InvalidEnum);
        }
    }
    let name = ctx.bindings.texture(target);
    if let Some(channel) = swizzle_channel(ctx, pname) {
        // ES 3.0's swizzles: a source channel, zero or one (a float rounded, as on Mesa).
        let source = v.round();
        if !(0.0..=f32::from(u16::MAX)).contains(&source)
            || !matches!(source as u32, RED_EXT | GREEN | BLUE | ALPHA | ZERO | ONE)
        {
            return Err(GlError::InvalidEnum);
        }
        let t = ctx.objects.texture_mut(target, name).ok_or(GlError::InvalidOperation)?;
        t.swizzle.0[channel] = source as u32;
        return Ok(());
    }
    let allowed = Allowed { es3: ctx.es3(), border };
    let setting = sampling::setting(Owner::Texture, allowed, pname, v)?;
    let t = ctx.objects.texture_mut(target, name).ok_or(GlError::InvalidOperation)?;
    setting.apply(&mut t.sampler);
    Ok(())
}

/// The channel `GL_TEXTURE_SWIZZLE_R`…`_A` name in an ES 3.0 context.
fn swizzle_channel(ctx: &Context, pname: u32) -> Option<usize> {
    let channel = pname.wrapping_sub(TEXTURE_SWIZZLE_R) as usize;
    (ctx.es3() && channel < 4).then_some(channel)
}

/// One sampling parameter of the texture bound to `target`, recording `GL_INVALID_ENUM` (and
/// answering nothing) for a bad target or name, or when nothing is bound.
fn get_tex_parameter(ctx: &mut Context, target: u32, pname: u32) -> Vec<f32> {
    let target = TextureTarget::from_gl_in(target, ctx.es3()).ok();
    let bound = target.map(|t| (t, ctx.bindings.texture(t)));
    // Texture 0 is the context's default texture of the target.
    let texture = |(t, n): (TextureTarget, u32)| ctx.objects.texture(t, n);
    if pname == TEXTURE_BORDER_COLOR_EXT {
        if let Some(t) = bound.and_then(texture) {
            return t.border.to_vec();
        }
    }
    // Mesa answers the format's query in ES 2.0 contexts too (where it is always false), the
    // levels' only in ES 3.0 ones.
    if pname == TEXTURE_IMMUTABLE_FORMAT || (ctx.es3() && pname == TEXTURE_IMMUTABLE_LEVELS) {
        if let Some(t) = bound.and_then(texture) {
            let levels = t.immutable_levels as f32;
            return vec![if pname == TEXTURE_IMMUTABLE_LEVELS { levels } else { f32::from(u8::from(levels > 0.0)) }];
        }
    }
    if let Some(channel) = swizzle_channel(ctx, pname) {
        if let Some(t) = bound.and_then(texture) {
            return vec![t.swizzle.0[channel] as f32];
        }
    }
    let es3 = ctx.es3();
    let v = bound.and_then(texture).map(|t| t.sampler).and_then(|s| match pname {
        // Every texture takes one unit (Mesa answers for every target).
        REQUIRED_TEXTURE_IMAGE_UNITS_OES => Some(1.0),
        _ => sampling::value(Owner::Texture, es3, &s, pname),
    });
    match v {
        Some(v) => vec![v],
        None => {
            ctx.record(GlError::InvalidEnum);
            vec![]
        }
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenTextures(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        self.admit(ctx, strata_device::account::Kind::Texture, ctx.objects.textures.fresh(names.iter()))?;
        ctx.objects.textures.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteTextures(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.objects.textures.delete(names.iter()) {
            ctx.objects.forget_label(TEXTURE, n);
            for s in ctx.bindings.units.iter_mut().flatten() {
                if *s == n {
                    *s = 0;
                }
            }
        }
        Ok(())
    }

    pub(super) fn glActiveTexture(&mut self, ctx: &mut Context, texture: u32) -> GlResult {
        let unit = texture.wrapping_sub(TEXTURE0) as usize;
        let bindings = &mut ctx.bindings;
        if unit >= bindings.units.len() {
            return Err(GlError::InvalidEnum);
        }
        bindings.active_unit = unit;
        Ok(())
    }

    pub(super) fn glBindTexture(&mut self, ctx: &mut Context, target: u32, texture: u32) -> GlResult {
        let target = TextureTarget::from_gl_in(target, ctx.es3())?;
        self.admit(ctx, strata_device::account::Kind::Texture, ctx.objects.textures.fresh([texture]))?;
        if let Some(t) = ctx.objects.textures.bind(texture) {
            // A texture takes the target it is first bound to, and keeps it.
            if t.target == 0 {
                t.target = target.as_gl();
                if target == TextureTarget::External {
                    // GL_OES_EGL_image_external's initial state.
                    (t.sampler.min, t.sampler.wrap_s, t.sampler.wrap_t) = (LINEAR, CLAMP_TO_EDGE, CLAMP_TO_EDGE);
                }
            } else if t.target != target.as_gl() {
                return Err(GlError::InvalidOperation);
            }
        }
        ctx.bindings.units[ctx.bindings.active_unit][target.slot()] = texture;
        Ok(())
    }

    pub(super) fn glIsTexture(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.textures.get(&name).is_some_and(|t| t.target != 0)
    }

    pub(super) fn glTexParameteri(&mut self, ctx: &mut Context, target: u32, pname: u32, param: i32) -> GlResult {
        tex_parameter(ctx, self.has_border_clamp(), target, pname, param as f32)
    }

    pub(super) fn glTexParameterf(&mut self, ctx: &mut Context, target: u32, pname: u32, param: f32) -> GlResult {
        tex_parameter(ctx, self.has_border_clamp(), target, pname, param)
    }

    pub(super) fn glTexParameteriv(
        &mut self,
        ctx: &mut Context,
        target: u32,
        pname: u32,
        params: Slice<'_, i32>,
    ) -> GlResult {
        if pname == TEXTURE_BORDER_COLOR_EXT {
            // Normalised as GL converts a signed integer colour (Mesa's arithmetic, in f32).
            let v: Vec<f32> = params.iter().map(sampling::normalized).collect();
            return set_border(ctx, target, &v);
        }
        let v = params.get(0).ok_or(GlError::InvalidValue)?;
        tex_parameter(ctx, self.has_border_clamp(), target, pname, v as f32)
    }

    pub(super) fn glTexParameterfv(
        &mut self,
        ctx: &mut Context,
        target: u32,
        pname: u32,
        params: Slice<'_, f32>,
    ) -> GlResult {
        if pname == TEXTURE_BORDER_COLOR_EXT {
            return set_border(ctx, target, &params.to_vec());
        }
        let v = params.get(0).ok_or(GlError::InvalidValue)?;
        tex_parameter(ctx, self.has_border_clamp(), target, pname, v)
    }

    pub(super) fn glGetTexParameteriv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> Vec<i32> {
        sampling::as_ints(pname, get_tex_parameter(ctx, target, pname))
    }

    pub(super) fn glGetTexParameterfv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> Vec<f32> {
        get_tex_parameter(ctx, target, pname)
    }

    pub(super) fn glGenerateMipmap(&mut self, ctx: &mut Context, flushed: &Flushed, target: u32) -> GlResult {
        let target = TextureTarget::from_gl_in(target, ctx.es3())?;
        if target == TextureTarget::External {
            return Err(GlError::InvalidEnum);
        }
        let name = ctx.bindings.texture(target);
        let t = ctx.objects.texture_mut(target, name).ok_or(GlError::InvalidOperation)?;
        let layers = if t.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
        let img = t.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
        // A 2D array's layers are generated one by one; its levels are defined for all at once.
        let image_layers = if img.array { img.depth } else { layers as u32 };
        // Depth and compressed images have no mipmaps to generate; nor do images that cannot
        // be filtered (ES 3.0 §3.8.10 spells out the rule ES 2.0 leaves implicit).
        if img.storage.is_depth() || Compressed::from_gl(t.format).is_some() || !img.filterable {
            return Err(GlError::InvalidOperation);
        }
        if t.defined[..layers].iter().any(|d| d & 1 == 0) {
            return Err(GlError::InvalidOperation);
        }
        let (tex, mips, format) = (img.texture.clone(), img.mips, img.storage.wgpu());
        for d in &mut t.defined[..layers] {
            *d = (1 << mips) - 1;
        }
        if t.target == TEXTURE_3D_OES {
            self.r.generate_volume_mipmaps(flushed, &tex, mips, format);
        } else {
            self.r.generate_mipmaps(flushed, &tex, mips, image_layers, format);
        }
        Ok(())
    }
}

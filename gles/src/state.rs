//! Fixed-function state: capabilities, viewport and scissor, clear values, write masks, depth,
//! culling, blending, stencil, polygon offset, line width, hints and pixel store.

use crate::context::{Context, StencilFace};

use crate::typed::ClipControl;

use crate::conv::{blend_factor, blend_op, reads_src1, valid_func, valid_stencil_op};
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::limits::MAX_TEXTURE;
use crate::typed::Capability;
use crate::GlesExecutor;

/// A `clampf` parameter as GL stores it: clamped to [0, 1] (NaN becomes 0).
fn clampf(x: f32) -> f32 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(0.0, 1.0)
    }
}

/// Sets the blend factors (RGB source, RGB destination, alpha source, alpha destination).
/// With `extended` (`GL_EXT_blend_func_extended`), the second colour's factors are factors, and
/// `GL_SRC_ALPHA_SATURATE` is a destination factor too.
fn set_blend_func(ctx: &mut Context, f: [u32; 4], extended: bool) -> GlResult {
    let known = |x: u32| blend_factor(x).is_some() && (extended || !reads_src1(x));
    let saturate_dst = f[1] == SRC_ALPHA_SATURATE || f[3] == SRC_ALPHA_SATURATE;
    if f.iter().all(|&x| known(x)) && (extended || !saturate_dst) {
        ctx.blend.func = f;
        Ok(())
    } else {
        Err(GlError::InvalidEnum)
    }
}

/// Applies `f` to the stencil state of `face` once `valid` (the other arguments) holds.
fn set_stencil(ctx: &mut Context, face: u32, f: impl Fn(&mut StencilFace), valid: bool) -> GlResult {
    if !valid {
        return Err(GlError::InvalidEnum);
    }
    let faces = &mut ctx.depth_stencil.stencil;
    match face {
        FRONT => f(&mut faces[0]),
        BACK => f(&mut faces[1]),
        FRONT_AND_BACK => {
            f(&mut faces[0]);
            f(&mut faces[1]);
        }
        _ => return Err(GlError::InvalidEnum),
    }
    Ok(())
}

/// Sets the stencil function of `face`.
fn stencil_func(ctx: &mut Context, face: u32, func: u32, reference: i32, mask: u32) -> GlResult {
    let set = |f: &mut StencilFace| {
        f.func = func;
        f.reference = reference;
        f.mask = mask;
    };
    set_stencil(ctx, face, set, valid_func(func))
}

/// Sets the stencil operations of `face`.
fn stencil_op(ctx: &mut Context, face: u32, fail: u32, zfail: u32, zpass: u32) -> GlResult {
    let set = |f: &mut StencilFace| {
        f.fail = fail;
        f.zfail = zfail;
        f.zpass = zpass;
    };
    set_stencil(ctx, face, set, [fail, zfail, zpass].iter().all(|&o| valid_stencil_op(o)))
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glEnable(&mut self, ctx: &mut Context, cap: u32) -> GlResult {
        *ctx.enabled_mut(Capability::on(cap, self.gpu.features, ctx.es3())?) = true;
        Ok(())
    }

    pub(super) fn glDisable(&mut self, ctx: &mut Context, cap: u32) -> GlResult {
        *ctx.enabled_mut(Capability::on(cap, self.gpu.features, ctx.es3())?) = false;
        Ok(())
    }

    pub(super) fn glIsEnabled(&mut self, ctx: &mut Context, cap: u32) -> bool {
        match Capability::on(cap, self.gpu.features, ctx.es3()) {
            Ok(c) => ctx.enabled(c),
            Err(e) => {
                ctx.record(e);
                false
            }
        }
    }

    pub(super) fn glViewport(&mut self, ctx: &mut Context, x: i32, y: i32, width: i32, height: i32) -> GlResult {
        if width < 0 || height < 0 {
            return Err(GlError::InvalidValue);
        }
        ctx.raster.viewport = [x, y, width.min(MAX_TEXTURE as i32), height.min(MAX_TEXTURE as i32)];
        Ok(())
    }

    pub(super) fn glScissor(&mut self, ctx: &mut Context, x: i32, y: i32, width: i32, height: i32) -> GlResult {
        if width < 0 || height < 0 {
            return Err(GlError::InvalidValue);
        }
        ctx.raster.scissor = [x, y, width, height];
        Ok(())
    }

    pub(super) fn glClearColor(&mut self, ctx: &mut Context, red: f32, green: f32, blue: f32, alpha: f32) -> GlResult {
        // `clampf` parameters are clamped to [0, 1] when specified (ES 2.0 §2.3); ES 3.0 keeps
        // the colour as given and clamps it for fixed-point buffers only, when clearing.
        let c = [red, green, blue, alpha];
        ctx.blend.clear_color = if ctx.es3() { c.map(|x| if x.is_nan() { 0.0 } else { x }) } else { c.map(clampf) };
        Ok(())
    }

    pub(super) fn glClearDepthf(&mut self, ctx: &mut Context, depth: f32) -> GlResult {
        ctx.depth_stencil.clear_depth = clampf(depth);
        Ok(())
    }

    pub(super) fn glClearStencil(&mut self, ctx: &mut Context, s: i32) -> GlResult {
        ctx.depth_stencil.clear_stencil = s;
        Ok(())
    }

    pub(super) fn glColorMask(
        &mut self,
        ctx: &mut Context,
        red: bool,
        green: bool,
        blue: bool,
        alpha: bool,
    ) -> GlResult {
        ctx.blend.color_mask = [red, green, blue, alpha];
        Ok(())
    }

    pub(super) fn glDepthMask(&mut self, ctx: &mut Context, flag: bool) -> GlResult {
        ctx.depth_stencil.depth_mask = flag;
        Ok(())
    }

    pub(super) fn glDepthFunc(&mut self, ctx: &mut Context, func: u32) -> GlResult {
        if !valid_func(func) {
            return Err(GlError::InvalidEnum);
        }
        ctx.depth_stencil.depth_func = func;
        Ok(())
    }

    pub(super) fn glDepthRangef(&mut self, ctx: &mut Context, near: f32, far: f32) -> GlResult {
        ctx.depth_stencil.depth_range = [clampf(near), clampf(far)];
        Ok(())
    }

    pub(super) fn glCullFace(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        if !matches!(mode, FRONT | BACK | FRONT_AND_BACK) {
            return Err(GlError::InvalidEnum);
        }
        ctx.raster.cull_face = mode;
        Ok(())
    }

    pub(super) fn glFrontFace(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        if !matches!(mode, CW | CCW) {
            return Err(GlError::InvalidEnum);
        }
        ctx.raster.front_face = mode;
        Ok(())
    }

    /// `GL_EXT_clip_control`: the window origin and the clip depth range of later draws.
    pub(super) fn glClipControlEXT(&mut self, ctx: &mut Context, origin: u32, depth: u32) -> GlResult {
        if !matches!(origin, LOWER_LEFT_EXT | UPPER_LEFT_EXT)
            || !matches!(depth, NEGATIVE_ONE_TO_ONE_EXT | ZERO_TO_ONE_EXT)
        {
            return Err(GlError::InvalidEnum);
        }
        ctx.raster.clip = ClipControl { upper_left: origin == UPPER_LEFT_EXT, zero_to_one: depth == ZERO_TO_ONE_EXT };
        Ok(())
    }

    pub(super) fn glBlendFunc(&mut self, ctx: &mut Context, sfactor: u32, dfactor: u32) -> GlResult {
        set_blend_func(ctx, [sfactor, dfactor, sfactor, dfactor], self.gpu.dual_source())
    }

    pub(super) fn glBlendFuncSeparate(
        &mut self,
        ctx: &mut Context,
        src_rgb: u32,
        dst_rgb: u32,
        src_alpha: u32,
        dst_alpha: u32,
    ) -> GlResult {
        set_blend_func(ctx, [src_rgb, dst_rgb, src_alpha, dst_alpha], self.gpu.dual_source())
    }

    pub(super) fn glBlendEquation(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        blend_op(mode).ok_or(GlError::InvalidEnum)?;
        ctx.blend.eq = [mode, mode];
        Ok(())
    }

    pub(super) fn glBlendEquationSeparate(&mut self, ctx: &mut Context, mode_rgb: u32, mode_alpha: u32) -> GlResult {
        if blend_op(mode_rgb).is_none() || blend_op(mode_alpha).is_none() {
            return Err(GlError::InvalidEnum);
        }
        ctx.blend.eq = [mode_rgb, mode_alpha];
        Ok(())
    }

    pub(super) fn glBlendColor(&mut self, ctx: &mut Context, red: f32, green: f32, blue: f32, alpha: f32) -> GlResult {
        ctx.blend.color = [red, green, blue, alpha].map(clampf);
        Ok(())
    }

    pub(super) fn glStencilFunc(&mut self, ctx: &mut Context, func: u32, reference: i32, mask: u32) -> GlResult {
        stencil_func(ctx, FRONT_AND_BACK, func, reference, mask)
    }

    pub(super) fn glStencilFuncSeparate(
        &mut self,
        ctx: &mut Context,
        face: u32,
        func: u32,
        reference: i32,
        mask: u32,
    ) -> GlResult {
        stencil_func(ctx, face, func, reference, mask)
    }

    pub(super) fn glStencilMask(&mut self, ctx: &mut Context, mask: u32) -> GlResult {
        set_stencil(ctx, FRONT_AND_BACK, |f| f.write = mask, true)
    }

    pub(super) fn glStencilMaskSeparate(&mut self, ctx: &mut Context, face: u32, mask: u32) -> GlResult {
        set_stencil(ctx, face, |f| f.write = mask, true)
    }

    pub(super) fn glStencilOp(&mut self, ctx: &mut Context, fail: u32, zfail: u32, zpass: u32) -> GlResult {
        stencil_op(ctx, FRONT_AND_BACK, fail, zfail, zpass)
    }

    pub(super) fn glStencilOpSeparate(
        &mut self,
        ctx: &mut Context,
        face: u32,
        fail: u32,
        zfail: u32,
        zpass: u32,
    ) -> GlResult {
        stencil_op(ctx, face, fail, zfail, zpass)
    }

    pub(super) fn glPolygonOffset(&mut self, ctx: &mut Context, factor: f32, units: f32) -> GlResult {
        ctx.raster.polygon_offset = [factor, units, 0.0];
        Ok(())
    }

    pub(super) fn glMaxShaderCompilerThreadsKHR(&mut self, ctx: &mut Context, count: u32) -> GlResult {
        // A hint: compiles and links complete within their calls whatever the count.
        ctx.compiler_threads = count;
        Ok(())
    }

    pub(super) fn glPolygonOffsetClampEXT(
        &mut self,
        ctx: &mut Context,
        factor: f32,
        units: f32,
        clamp: f32,
    ) -> GlResult {
        ctx.raster.polygon_offset = [factor, units, clamp];
        Ok(())
    }

    pub(super) fn glLineWidth(&mut self, ctx: &mut Context, width: f32) -> GlResult {
        if width <= 0.0 || width.is_nan() {
            return Err(GlError::InvalidValue);
        }
        ctx.raster.line_width = width;
        Ok(())
    }

    pub(super) fn glHint(&mut self, ctx: &mut Context, target: u32, mode: u32) -> GlResult {
        if !matches!(mode, FASTEST | NICEST | DONT_CARE) {
            return Err(GlError::InvalidEnum);
        }
        match target {
            GENERATE_MIPMAP_HINT => ctx.mipmap_hint = mode,
            FRAGMENT_SHADER_DERIVATIVE_HINT_OES => ctx.derivative_hint = mode,
            _ => return Err(GlError::InvalidEnum),
        }
        Ok(())
    }

    /// The coverage parameters, which draws into multisample targets mask their samples with.
    pub(super) fn glSampleCoverage(&mut self, ctx: &mut Context, value: f32, invert: bool) -> GlResult {
        ctx.raster.coverage = (clampf(value), invert);
        Ok(())
    }

    pub(super) fn glPixelStorei(&mut self, ctx: &mut Context, pname: u32, param: i32) -> GlResult {
        let es3 = ctx.es3();
        let store = &mut ctx.pixel_store;
        match pname {
            UNPACK_ALIGNMENT | PACK_ALIGNMENT if matches!(param, 1 | 2 | 4 | 8) => {
                if pname == UNPACK_ALIGNMENT {
                    store.unpack_alignment = param;
                } else {
                    store.pack_alignment = param;
                }
            }
            UNPACK_ALIGNMENT | PACK_ALIGNMENT => return Err(GlError::InvalidValue),
            // EXT_unpack_subimage.
            UNPACK_ROW_LENGTH | UNPACK_SKIP_ROWS | UNPACK_SKIP_PIXELS if param < 0 => {
                return Err(GlError::InvalidValue)
            }
            UNPACK_ROW_LENGTH => store.unpack_row_length = param,
            UNPACK_SKIP_ROWS => store.unpack_skip_rows = param,
            UNPACK_SKIP_PIXELS => store.unpack_skip_pixels = param,
            // NV_pack_subimage and ANGLE_pack_reverse_row_order.
            PACK_ROW_LENGTH | PACK_SKIP_ROWS | PACK_SKIP_PIXELS if param < 0 => return Err(GlError::InvalidValue),
            PACK_ROW_LENGTH | PACK_SKIP_ROWS | PACK_SKIP_PIXELS => {
                store.pack_rows[(pname - PACK_ROW_LENGTH) as usize] = param;
            }
            PACK_REVERSE_ROW_ORDER_ANGLE => store.pack_reverse = param as u8,
            UNPACK_IMAGE_HEIGHT | UNPACK_SKIP_IMAGES if es3 && param < 0 => return Err(GlError::InvalidValue),
            UNPACK_IMAGE_HEIGHT if es3 => store.unpack_images[0] = param,
            UNPACK_SKIP_IMAGES if es3 => store.unpack_images[1] = param,
            _ => return Err(GlError::InvalidEnum),
        }
        Ok(())
    }
}

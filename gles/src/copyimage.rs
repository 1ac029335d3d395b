//! Texture images copied from the framebuffer: `glCopyTexImage2D` and `glCopyTexSubImage2D`
//! (into 8-bit colour images only: float, depth and compressed images are not copy targets).

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{sized_color_base, Compressed, Storage};
use crate::render::Target;
use crate::teximage::{image_texture, validate_box, validate_size};
use crate::typed::ImageTarget;
use crate::GlesExecutor;

#[allow(non_snake_case)]
impl GlesExecutor {
    /// Copies a rectangle of the framebuffer's colour into a texture level (at slice `zo` of a
    /// 3D image, `glCopyTexSubImage3DOES`); with `internal` (`glCopyTexImage2D`) level 0 is
    /// (re)specified first. `image` is the target parsed, or its error.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn copy_tex(
        &mut self,
        ctx: &mut Context,
        _flushed: &Flushed,
        image: GlResult<ImageTarget>,
        level: i32,
        internal: Option<u32>,
        [xo, yo, zo]: [i32; 3],
        x: i32,
        y: i32,
        w: i32,
        h: i32,
        border: i32,
    ) -> GlResult {
        let src = self.read_target(ctx).map_err(|_| GlError::InvalidFramebufferOperation)?;
        // ES 3.0 §3.8.5: a multisample read framebuffer is never copied from.
        if src.samples > 1 {
            return Err(GlError::InvalidOperation);
        }
        crate::framebuffers::read_selected(ctx)?;
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let image = image?;
        let last = crate::teximage::max_level(gpu, image);
        if level < 0 || w < 0 || h < 0 || border != 0 || level > last {
            return Err(GlError::InvalidValue);
        }
        // A half-float read buffer (GL_EXT_color_buffer_half_float) copies into no 8-bit image.
        if src.half_float() {
            return Err(GlError::InvalidOperation);
        }
        // As on Mesa: a new image copied from an sRGB surface (EGL_KHR_gl_colorspace) would
        // need an sRGB internal format, which ES 2.0 has none of.
        if internal.is_some() && src.srgb {
            return Err(GlError::InvalidValue);
        }
        // A sized colour format (GL_OES_required_internalformat) copies as its unsized one where
        // its components are as wide as the framebuffer's (always 8 bits here); depth formats,
        // narrower ones and the sized formats of extensions not offered are
        // GL_INVALID_OPERATION, as Mesa answers.
        if let Some(f) = internal {
            let narrow = matches!(f, LUMINANCE4_ALPHA4_OES | RGB565 | RGB5_A1 | RGBA4 | RGB10_A2_EXT);
            let depth = matches!(
                f,
                DEPTH_COMPONENT
                    | DEPTH_STENCIL_OES
                    | DEPTH_COMPONENT16
                    | DEPTH_COMPONENT24_OES
                    | DEPTH_COMPONENT32_OES
                    | DEPTH24_STENCIL8_OES
            );
            if narrow || depth {
                return Err(GlError::InvalidOperation);
            }
        }
        let internal = internal.map(|f| sized_color_base(f).unwrap_or(f));
        if let Some(f) = internal {
            if !matches!(f, RGBA | RGB | LUMINANCE | LUMINANCE_ALPHA | ALPHA) {
                return Err(GlError::InvalidEnum);
            }
            validate_size(gpu, image, level, [w, h, 1], border)?;
        }
        let name = image_texture(ctx, image);
        let t = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
        let level = level as u32;
        if internal.is_some() {
            crate::texstorage::mutable(t)?;
        }
        if let Some(f) = internal {
            if level == 0 {
                t.ensure_image(gpu, &account, uid, w as u32, h as u32, Storage::Rgba8)?;
                t.format = f;
            }
        }
        let img = t.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
        if img.storage != Storage::Rgba8 || Compressed::from_gl(t.format).is_some() {
            if internal.is_some() {
                // A colour level of a float, depth or compressed texture: the texture is
                // incomplete until its levels agree again.
                t.defined[image.face as usize] &= !(1 << level);
                return Ok(());
            }
            return Err(GlError::InvalidOperation);
        }
        let (lw, lh) = img.level_size(level);
        if internal.is_some() && (lw, lh) != (w as u32, h as u32) {
            return Err(GlError::InvalidValue);
        }
        validate_box([lw, lh, img.level_depth(level)], [xo, yo, zo], [w, h, 1])?;
        t.defined[image.face as usize] |= 1 << level;
        let rgb = t.format == RGB;
        let Some((src_tex, _)) = &src.color else { return Ok(()) };
        // Clip the source rectangle to the framebuffer.
        let (sx0, sy0) = (x.max(0), y.max(0));
        let (sx1, sy1) = (x.saturating_add(w).min(src.width as i32), y.saturating_add(h).min(src.height as i32));
        if sx1 <= sx0 || sy1 <= sy0 {
            return Ok(());
        }
        let dst = [(xo + sx0 - x) as u32, (yo + sy0 - y) as u32, (sx1 - sx0) as u32, (sy1 - sy0) as u32];
        let dst_tex = img.texture.clone();
        let (from, to) = (src.color_at, img.at(image.face + zo as u32, level));
        let (view, slice) = img.attach_view(image.face + zo as u32, level);
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        enc.copy_texture_to_texture(
            wgpu::TexelCopyTextureInfo {
                texture: src_tex,
                mip_level: from.level,
                origin: wgpu::Origin3d { x: sx0 as u32, y: sy0 as u32, z: from.layer },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyTextureInfo {
                texture: &img.texture,
                mip_level: to.level,
                origin: wgpu::Origin3d { x: dst[0], y: dst[1], z: to.layer },
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::Extent3d { width: (sx1 - sx0) as u32, height: (sy1 - sy0) as u32, depth_or_array_layers: 1 },
        );
        // The pending pass, whose draws the copy may read, went before this command (`Flushed`).
        self.gpu.submit(&self.r.lane, vec![enc.finish()]);
        if rgb {
            // The copy brought the framebuffer's alpha along; an RGB image reads alpha as 1.
            let color = (dst_tex, view);
            let absent = wgpu::ColorWrites::ALPHA;
            let mut level_target = Target::color_only((uid, 3), color, (lw, lh), absent);
            level_target.slices = vec![slice];
            let alpha_one = Some(([0.0, 0.0, 0.0, 1.0], wgpu::ColorWrites::ALPHA, None));
            self.r.clear(&level_target, alpha_one, None, None, Some(dst));
        }
        Ok(())
    }
}

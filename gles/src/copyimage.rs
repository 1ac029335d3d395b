//! Texture images copied from the framebuffer: `glCopyTexImage2D` and `glCopyTexSubImage2D`
//! (in ES 2.0 into 8-bit colour images only; in ES 3.0 into float and 10-bit ones too, a new
//! image of such a format from a buffer of its kind: `GL_EXT_color_buffer_float`; depth and
//! compressed images are not copy targets).

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{immutable_storage, sized_color_base, Compressed, Storage};
use crate::render::{Blit, Target};
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
        flushed: &Flushed,
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
        let es3 = ctx.es3();
        // A half-float read buffer (GL_EXT_color_buffer_half_float) copies into no 8-bit image.
        if !es3 && src.half_float() {
            return Err(GlError::InvalidOperation);
        }
        // ES 3.0: a new image of a float or 10-bit format copies from a buffer of the same
        // kind that has every channel it has; any other from an 8-bit one (as Mesa answers).
        let float_image = internal.filter(|_| es3).and_then(float_copy_format);
        if let Some(f) = internal.filter(|_| es3) {
            let fits = match float_image {
                Some(kind) => {
                    let has = crate::channels::color_bits(f).map(|b| b != 0);
                    let lacks = src.absent;
                    let channels = [
                        wgpu::ColorWrites::RED,
                        wgpu::ColorWrites::GREEN,
                        wgpu::ColorWrites::BLUE,
                        wgpu::ColorWrites::ALPHA,
                    ];
                    copy_kind(src.color_format()) == Some(kind)
                        && has.iter().zip(channels).all(|(h, c)| !h || !lacks.contains(c))
                }
                None => copy_kind(src.color_format()).is_none(),
            };
            if !fits {
                return Err(GlError::InvalidOperation);
            }
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
        if let Some(f) = internal.filter(|_| float_image.is_none()) {
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
        // The image a copy specifies: its unsized format, storage, sized format (0 for none)
        // and whether it counts as half-float.
        let new = match (internal, float_image) {
            (Some(f), Some(_)) => {
                immutable_storage(f, gpu.features).map(|(base, storage, half)| (base, storage, f, half))
            }
            (Some(f), None) => {
                let base = sized_color_base(f).unwrap_or(f);
                if !matches!(base, RGBA | RGB | LUMINANCE | LUMINANCE_ALPHA | ALPHA) {
                    return Err(GlError::InvalidEnum);
                }
                Some((base, Storage::Rgba8, 0, false))
            }
            (None, _) => None,
        };
        if new.is_some() {
            validate_size(gpu, image, level, [w, h, 1], border)?;
        }
        let name = image_texture(ctx, image);
        let t = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
        let level = level as u32;
        if internal.is_some() {
            crate::texstorage::mutable(t)?;
        }
        if let Some((base, storage, sized, half)) = new {
            if level == 0 {
                t.ensure_image(gpu, &account, uid, w as u32, h as u32, storage)?;
                t.format = base;
                t.sized = sized;
                t.half_float = half;
            }
        }
        let img = t.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
        // ES 2.0 copies into 8-bit images only; ES 3.0 into float and 10-bit ones too,
        // converting (as Mesa does, whatever the read buffer holds).
        let copyable = match img.storage {
            Storage::Rgba8 => true,
            Storage::Half | Storage::Float | Storage::Rgb10a2 | Storage::Rg11b10 => es3,
            _ => false,
        };
        let compressed = Compressed::from_gl(t.format).is_some();
        if let Some((_, storage, _, _)) = new {
            if img.storage != storage || compressed {
                // A colour level of a float, depth or compressed texture: the texture is
                // incomplete until its levels agree again.
                t.defined[image.face as usize] &= !(1 << level);
                return Ok(());
            }
        } else if !copyable || compressed {
            return Err(GlError::InvalidOperation);
        }
        let (lw, lh) = img.level_size(level);
        if new.is_some() && (lw, lh) != (w as u32, h as u32) {
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
        let eight_bit =
            matches!(src_tex.format(), wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb);
        if img.storage != Storage::Rgba8 || !eight_bit {
            // Between formats (ES 3.0): drawn, texel for texel, converting as a blit does; the
            // channels the image's format lacks keep their values.
            let format = img.storage.wgpu();
            let writes = wgpu::ColorWrites::ALL - crate::channels::absent_channels(t.format);
            let (sw, sh) = (sx1 - sx0, sy1 - sy0);
            let [dx, dy, _, _] = dst.map(|v| v as i32);
            let blit = Blit {
                src: (src_tex, from, (src.width, src.height)),
                dst: vec![(&view, format, writes, slice)],
                src_rect: [sx0, sy0, sx0 + sw, sy0 + sh],
                dst_rect: [dx, dy, dx + sw, dy + sh],
                clip: dst,
                linear: false,
            };
            self.r.blit(flushed, &blit);
            return Ok(());
        }
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

/// The kinds of colour a copy tells apart (ES 3.0): half floats, 32-bit floats, packed floats
/// and 10-bit normalized values; `None` is 8-bit normalized colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum CopyKind {
    Half,
    Float,
    Packed,
    Ten,
}

/// The kind of a read buffer of `format`.
fn copy_kind(format: Option<wgpu::TextureFormat>) -> Option<CopyKind> {
    use wgpu::TextureFormat as F;
    match format? {
        F::Rgba16Float => Some(CopyKind::Half),
        F::Rgba32Float => Some(CopyKind::Float),
        F::Rg11b10Ufloat => Some(CopyKind::Packed),
        F::Rgb10a2Unorm => Some(CopyKind::Ten),
        _ => None,
    }
}

/// The kind of ES 3.0's sized format `f` where it is a renderable float or 10-bit one, which a
/// new image copies only from a buffer of that kind.
fn float_copy_format(f: u32) -> Option<CopyKind> {
    match f {
        R16F_EXT | RG16F_EXT | RGB16F_EXT | RGBA16F_EXT => Some(CopyKind::Half),
        R32F | RG32F | RGBA32F => Some(CopyKind::Float),
        crate::packed_float::R11F_G11F_B10F => Some(CopyKind::Packed),
        RGB10_A2_EXT => Some(CopyKind::Ten),
        _ => None,
    }
}

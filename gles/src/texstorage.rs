//! Immutable texture storage (ES 3.0's `glTexStorage2D` and `glTexStorage3D`, for 2D, cube, 3D
//! and 2D array textures): every level of the bound texture allocated at once in a sized internal format, after which the texture's
//! images cannot be respecified (`glTexImage*`, `glCopyTexImage2D` and
//! `glCompressedTexImage*` on it are `GL_INVALID_OPERATION`), only written. Checked in the
//! order of Mesa's `texstorage.c`; the memory of every level and layer is reserved against the
//! client's quota before anything is allocated.

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::formats::{immutable_storage, is_unsized, Compressed, Storage};
use crate::limits::{max_3d_level, max_3d_size, max_array_layers, MAX_LEVEL, MAX_TEXTURE};
use crate::objects::image::TextureImage;
use crate::objects::texture::Texture;
use crate::typed::TextureTarget;
use crate::GlesExecutor;

/// The levels a full mip chain of a `width`×`height`×`depth` image has.
fn chain_levels(width: i32, height: i32, depth: i32) -> i32 {
    32 - (width.max(height).max(depth).max(1) as u32).leading_zeros() as i32
}

/// `GL_INVALID_OPERATION` where `t`'s images were made by `glTexStorage*` and cannot be
/// respecified; the last check of every image specification call, as on Mesa.
pub(crate) fn mutable(t: &Texture) -> GlResult {
    if t.immutable_levels == 0 {
        Ok(())
    } else {
        Err(GlError::InvalidOperation)
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glTexStorage2D(
        &mut self,
        ctx: &mut Context,
        target: u32,
        levels: i32,
        internalformat: u32,
        width: i32,
        height: i32,
    ) -> GlResult {
        let target = match target {
            TEXTURE_2D => TextureTarget::TwoD,
            TEXTURE_CUBE_MAP => TextureTarget::CubeMap,
            _ => return Err(GlError::InvalidEnum),
        };
        self.tex_storage(ctx, target, levels, internalformat, [width, height, 1])
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glTexStorage3D(
        &mut self,
        ctx: &mut Context,
        target: u32,
        levels: i32,
        internalformat: u32,
        width: i32,
        height: i32,
        depth: i32,
    ) -> GlResult {
        let target = match target {
            TEXTURE_3D_OES => TextureTarget::ThreeD,
            TEXTURE_2D_ARRAY => TextureTarget::TwoDArray,
            _ => return Err(GlError::InvalidEnum),
        };
        self.tex_storage(ctx, target, levels, internalformat, [width, height, depth])
    }

    /// Gives the texture bound to `target` `levels` immutable levels of `internal`, level 0
    /// `size` (width, height, slices), in Mesa's order of checks.
    fn tex_storage(
        &mut self,
        ctx: &mut Context,
        target: TextureTarget,
        levels: i32,
        internal: u32,
        [width, height, depth]: [i32; 3],
    ) -> GlResult {
        // A compressed image keeps its format as its own ("format"), decoded on upload where the
        // device lacks it (its blocks' storage is chosen below).
        let compressed = Compressed::offered_gl(internal, self.gpu.features, ctx.es3());
        let sized = immutable_storage(internal, self.gpu.features)
            .or(compressed.map(|c| (internal, c.decoded_storage(), false)));
        let Some((format, mut storage, half_float)) = sized else {
            if !is_unsized(internal) {
                tracing::warn!(internal, "glTexStorage: this sized internal format is not supported yet");
            }
            return Err(GlError::InvalidEnum);
        };
        if width < 1 || height < 1 || depth < 1 || levels < 1 {
            return Err(GlError::InvalidValue);
        }
        let (three_d, cube) = (target == TextureTarget::ThreeD, target == TextureTarget::CubeMap);
        let last = if three_d { max_3d_level(&self.gpu) } else { MAX_LEVEL };
        if levels > last + 1 || levels > chain_levels(width, height, if three_d { depth } else { 1 }) {
            return Err(GlError::InvalidOperation);
        }
        let name = ctx.bindings.texture(target);
        let t = ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
        mutable(t)?;
        // Of the compressed formats only ASTC's has 3D images (its sliced 3D extension).
        let flat = compressed.is_some_and(|c| !matches!(c, Compressed::Astc(_) | Compressed::AstcSrgb(_)));
        if (storage.is_depth() || flat) && three_d {
            return Err(GlError::InvalidOperation);
        }
        let most = if three_d { max_3d_size(&self.gpu) } else { MAX_TEXTURE } as i32;
        let most_layers = if three_d { most } else { max_array_layers(&self.gpu) as i32 };
        if width > most || height > most || depth > most_layers || (cube && width != height) {
            return Err(GlError::InvalidValue);
        }
        let size = (width as u32, height as u32, depth as u32);
        let levels = levels as u32;
        if let Some(c) = compressed {
            // Blocks go up as they are only into a 2D image of whole blocks, as
            // glCompressedTexImage2D keeps them.
            let (bw, bh) = c.block_size();
            let whole_blocks = target == TextureTarget::TwoD && size.0.is_multiple_of(bw) && size.1.is_multiple_of(bh);
            if whole_blocks && c.native_on(self.gpu.features).is_some() {
                storage = Storage::Native(c);
            }
        }
        // The old image's memory is given back before the new one is reserved.
        t.gpu = None;
        t.defined = [0; 6];
        let img = TextureImage::with_levels(&self.gpu, &self.account, t.target, size, storage, Some(levels))?;
        let faces = if cube { 6 } else { 1 };
        for d in &mut t.defined[..faces] {
            *d = (1 << levels) - 1;
        }
        t.gpu = Some(img);
        t.uid = self.next_uid();
        t.format = format;
        t.half_float = half_float;
        t.sized = internal;
        t.immutable_levels = levels;
        Ok(())
    }
}

/// Whether data of `format` and `ty` may be written to a texture that `glTexStorage*` made in
/// `sized`, by ES 3.0's table of format, type and internal format combinations (and
/// `GL_EXT_texture_storage`'s for the luminance and alpha formats).
pub(crate) fn sized_accepts(sized: u32, format: u32, ty: u32) -> bool {
    let half_or_float = matches!(ty, HALF_FLOAT | FLOAT);
    match sized {
        RGBA8_OES | SRGB8_ALPHA8 => format == RGBA && ty == UNSIGNED_BYTE,
        SRGB8 => format == RGB && ty == UNSIGNED_BYTE,
        BGRA8_EXT => format == BGRA_EXT && ty == UNSIGNED_BYTE,
        RGB8_OES => format == RGB && ty == UNSIGNED_BYTE,
        RGB565 => format == RGB && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_5_6_5),
        RGBA4 => format == RGBA && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_4_4_4_4),
        RGB5_A1 => format == RGBA && matches!(ty, UNSIGNED_BYTE | UNSIGNED_SHORT_5_5_5_1),
        R8_EXT => format == RED_EXT && ty == UNSIGNED_BYTE,
        RG8_EXT => format == RG_EXT && ty == UNSIGNED_BYTE,
        ALPHA8_OES => format == ALPHA && ty == UNSIGNED_BYTE,
        LUMINANCE8_OES => format == LUMINANCE && ty == UNSIGNED_BYTE,
        LUMINANCE8_ALPHA8_OES => format == LUMINANCE_ALPHA && ty == UNSIGNED_BYTE,
        R8_SNORM => format == RED_EXT && ty == BYTE,
        RG8_SNORM => format == RG_EXT && ty == BYTE,
        RGB8_SNORM => format == RGB && ty == BYTE,
        RGBA8_SNORM => format == RGBA && ty == BYTE,
        RGBA16F_EXT => format == RGBA && half_or_float,
        RGB16F_EXT => format == RGB && half_or_float,
        RG16F_EXT => format == RG_EXT && half_or_float,
        R16F_EXT => format == RED_EXT && half_or_float,
        RGBA32F => format == RGBA && ty == FLOAT,
        RGB32F => format == RGB && ty == FLOAT,
        RG32F => format == RG_EXT && ty == FLOAT,
        R32F => format == RED_EXT && ty == FLOAT,
        RGB10_A2_EXT => format == RGBA && ty == UNSIGNED_INT_2_10_10_10_REV_EXT,
        DEPTH_COMPONENT16 => format == DEPTH_COMPONENT && matches!(ty, UNSIGNED_SHORT | UNSIGNED_INT),
        DEPTH_COMPONENT24_OES => format == DEPTH_COMPONENT && ty == UNSIGNED_INT,
        DEPTH24_STENCIL8_OES => format == DEPTH_STENCIL_OES && ty == UNSIGNED_INT_24_8_OES,
        DEPTH_COMPONENT32F => format == DEPTH_COMPONENT && ty == FLOAT,
        DEPTH32F_STENCIL8 => format == DEPTH_STENCIL_OES && ty == FLOAT_32_UNSIGNED_INT_24_8_REV,
        // The float luminance and alpha formats take their unsized format's data.
        ALPHA16F_EXT | ALPHA32F_EXT => format == ALPHA && half_or_float,
        LUMINANCE16F_EXT | LUMINANCE32F_EXT => format == LUMINANCE && half_or_float,
        LUMINANCE_ALPHA16F_EXT | LUMINANCE_ALPHA32F_EXT => format == LUMINANCE_ALPHA && half_or_float,
        _ => crate::packed_float::accepts(sized, format, ty)
            .unwrap_or_else(|| crate::integer::IntFormat::from_gl(sized).is_some_and(|f| f.upload() == (format, ty))),
    }
}

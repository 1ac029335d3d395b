//! 3D textures (`GL_OES_texture_3D`): `glTexImage3DOES` and `glTexSubImage3DOES`, their
//! compressed forms (ASTC slices, `GL_KHR_texture_compression_astc_sliced_3d`, decoded on
//! upload), `glCopyTexSubImage3DOES` and slices as framebuffer attachments. A 3D image is a
//! wgpu 3D texture; its slices are written one by one, slice `z` where a 2D image's
//! [`Region`] names a face. Uploads read the slices one after another, as ES 2.0 has no
//! image height to unpack by.

use strata_protocol::Blob;

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{internal_accepts, known_internal, same_layout, sized_fits, upload_storage, Compressed};
use crate::objects::framebuffer::Attachment;
use crate::objects::image::Region;
use crate::objects::texture::Texture;
use crate::teximage::{blank, block_aligned};
use crate::typed::{ImageTarget, TextureTarget};
use crate::unpack::{to_storage, Unpack};
use crate::GlesExecutor;
use strata_device::Gpu;

/// Checks a new 3D level's number and size as Mesa does: `GL_INVALID_VALUE` for a level past
/// the last, a negative size, one beyond the largest that level may have, or a border.
fn validate_volume(gpu: &Gpu, level: i32, size: [i32; 3], border: i32) -> GlResult {
    if !(0..=crate::limits::max_3d_level(gpu)).contains(&level) || border != 0 {
        return Err(GlError::InvalidValue);
    }
    let most = (crate::limits::max_3d_size(gpu) >> level) as i32;
    if size.iter().any(|&n| !(0..=most).contains(&n)) {
        return Err(GlError::InvalidValue);
    }
    Ok(())
}

/// Checks a box `[x, y, z, w, h, d]` against a level of `size`: `GL_INVALID_VALUE` if it does
/// not fit.
fn validate_box(size: [u32; 3], b: [i32; 6]) -> GlResult {
    let fits = (0..3).all(|i| {
        let (o, n) = (i64::from(b[i]), i64::from(b[i + 3]));
        o >= 0 && n >= 0 && o + n <= i64::from(size[i])
    });
    if fits {
        Ok(())
    } else {
        Err(GlError::InvalidValue)
    }
}

/// The 3D texture bound to the active unit, for an upload that needs one (name 0 is refused,
/// as for 2D images).
fn bound(ctx: &mut Context) -> GlResult<&mut Texture> {
    let name = ctx.bindings.texture(TextureTarget::ThreeD);
    ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)
}

/// The checks sub-image updates share, in Mesa's order: the level's number (`GL_INVALID_VALUE`),
/// a texture whose level is defined (`GL_INVALID_OPERATION`), then `fits`, then the box.
fn sub_volume<'a>(
    gpu: &Gpu,
    ctx: &'a mut Context,
    level: i32,
    b: [i32; 6],
    fits: impl FnOnce(&Texture) -> GlResult,
) -> GlResult<(&'a mut Texture, [u32; 3])> {
    if !(0..=crate::limits::max_3d_level(gpu)).contains(&level) {
        return Err(GlError::InvalidValue);
    }
    let t = bound(ctx)?;
    let level = level as u32;
    let img = t.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
    if t.defined[0] & (1 << level) == 0 {
        return Err(GlError::InvalidOperation);
    }
    let (w, h) = img.level_size(level);
    let size = [w, h, img.level_depth(level)];
    fits(t)?;
    validate_box(size, b)?;
    Ok((t, size))
}

/// Writes `slices` (tightly packed, one after another) of `w`×`h` texels of `bytes` each into
/// `level` of `t`'s image from slice `z` on.
fn write_slices(
    t: &Texture,
    gpu: &Gpu,
    flushed: &Flushed,
    level: u32,
    [x, y, z]: [u32; 3],
    [w, h]: [u32; 2],
    data: &[u8],
) {
    let Some(img) = &t.gpu else { return };
    let bytes = (w * h * img.storage.texel_bytes()) as usize;
    if bytes == 0 {
        return;
    }
    for (k, slice) in data.chunks_exact(bytes).enumerate() {
        let region = Region { face: z + k as u32, level, x, y, width: w, height: h };
        img.write(gpu, flushed, region, slice);
    }
}

/// Marks `level` of `t`'s image defined where it is consistent with level 0: `same` format or
/// storage, the size level 0 gives it, a level the image has; else undefined (the texture is
/// then incomplete). Whether it is defined.
fn define_level(t: &mut Texture, level: u32, [w, h, d]: [u32; 3], same: bool) -> bool {
    let consistent = t.gpu.as_ref().is_some_and(|img| {
        same && img.level_size(level) == (w.max(1), h.max(1)) && img.level_depth(level) == d.max(1) && level < img.mips
    });
    if consistent {
        t.defined[0] |= 1 << level;
    } else {
        t.defined[0] &= !(1 << level);
    }
    consistent
}

/// Compressed `data` of `w`×`h` slices one after another, decoded slice by slice.
fn decode_slices(c: Compressed, data: &Blob<'_>, w: u32, h: u32) -> Vec<u8> {
    let slice = c.image_size(w, h).max(1);
    data.as_bytes().chunks_exact(slice).flat_map(|s| c.decode_for(s, w, h)).collect()
}

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glTexImage3DOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        internalformat: u32,
        width: i32,
        height: i32,
        depth: i32,
        border: i32,
        format: u32,
        pixel_type: u32,
        pixels: Option<Blob<'_>>,
    ) -> GlResult {
        if target != TEXTURE_3D_OES {
            return Err(GlError::InvalidEnum);
        }
        let storage = upload_storage(format, pixel_type);
        if !matches!(storage, Err(GlError::InvalidEnum)) && !known_internal(internalformat) {
            return Err(GlError::InvalidValue);
        }
        let storage = storage?;
        let internal = match sized_fits(internalformat, format, pixel_type) {
            Some(true) => format,
            Some(false) => return Err(GlError::InvalidOperation),
            None => internalformat,
        };
        // No 3D depth images (OES_depth_texture names 2D and cube maps only).
        if storage.is_depth() || !internal_accepts(internal, format, self.gpu.features) {
            return Err(GlError::InvalidOperation);
        }
        validate_volume(&self.gpu, level, [width, height, depth], border)?;
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let unpack = Unpack::of(&ctx.pixel_store);
        let (w, h, d, level) = (width as u32, height as u32, depth as u32, level as u32);
        let texels = match &pixels {
            Some(p) => Some(
                to_storage(p.as_bytes(), w as usize, (h * d) as usize, format, pixel_type, unpack, storage)
                    .ok_or(GlError::InvalidOperation)?,
            ),
            None => None,
        };
        let t = bound(ctx)?;
        if level == 0 {
            t.ensure_volume(gpu, &account, uid, (w, h, d), storage)?;
            t.format = internal;
            t.half_float = pixel_type == HALF_FLOAT_OES;
        }
        let same = t.gpu.as_ref().is_some_and(|img| img.storage == storage);
        if !define_level(t, level, [w, h, d], same) {
            return Ok(());
        }
        let data = texels.unwrap_or_else(|| blank(w as usize * h as usize * d as usize, format, storage));
        write_slices(t, gpu, flushed, level, [0, 0, 0], [w, h], &data);
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glTexSubImage3DOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        xoffset: i32,
        yoffset: i32,
        zoffset: i32,
        width: i32,
        height: i32,
        depth: i32,
        format: u32,
        pixel_type: u32,
        pixels: Blob<'_>,
    ) -> GlResult {
        if target != TEXTURE_3D_OES {
            return Err(GlError::InvalidEnum);
        }
        let storage = upload_storage(format, pixel_type)?;
        let unpack = Unpack::of(&ctx.pixel_store);
        let fits = |t: &Texture| match (Compressed::from_gl(t.format), &t.gpu) {
            // ASTC images take no uncompressed data (GL_INVALID_VALUE, as for 2D).
            (Some(_), _) => Err(GlError::InvalidValue),
            (None, Some(img)) if same_layout(t.format, format) && storage == img.storage => Ok(()),
            _ => Err(GlError::InvalidOperation),
        };
        let b = [xoffset, yoffset, zoffset, width, height, depth];
        let (t, _) = sub_volume(&self.gpu, ctx, level, b, fits)?;
        let (w, h, d) = (width as u32, height as u32, depth as u32);
        if pixels.is_empty() || w == 0 || h == 0 || d == 0 {
            return Ok(());
        }
        let data = to_storage(pixels.as_bytes(), w as usize, (h * d) as usize, format, pixel_type, unpack, storage)
            .ok_or(GlError::InvalidOperation)?;
        let origin = [xoffset as u32, yoffset as u32, zoffset as u32];
        write_slices(t, &self.gpu, flushed, level as u32, origin, [w, h], &data);
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glCompressedTexImage3DOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        internalformat: u32,
        width: i32,
        height: i32,
        depth: i32,
        border: i32,
        data: Blob<'_>,
    ) -> GlResult {
        if target != TEXTURE_3D_OES {
            return Err(GlError::InvalidEnum);
        }
        // Only ASTC has 3D images (GL_KHR_texture_compression_astc_sliced_3d).
        let c = Compressed::offered_gl(internalformat, self.gpu.features)
            .filter(|c| matches!(c, Compressed::Astc(_) | Compressed::AstcSrgb(_)))
            .ok_or(GlError::InvalidEnum)?;
        validate_volume(&self.gpu, level, [width, height, depth], border)?;
        let (w, h, d, level) = (width as u32, height as u32, depth as u32, level as u32);
        let slice = c.image_size(w, h);
        if slice.checked_mul(d as usize) != Some(data.len()) {
            return Err(GlError::InvalidValue);
        }
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let t = bound(ctx)?;
        if level == 0 {
            t.ensure_volume(gpu, &account, uid, (w, h, d), c.decoded_storage())?;
            t.format = internalformat;
        }
        let same = t.format == internalformat;
        if !define_level(t, level, [w, h, d], same) {
            return Ok(());
        }
        write_slices(t, gpu, flushed, level, [0, 0, 0], [w, h], &decode_slices(c, &data, w, h));
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glCompressedTexSubImage3DOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        xoffset: i32,
        yoffset: i32,
        zoffset: i32,
        width: i32,
        height: i32,
        depth: i32,
        format: u32,
        data: Blob<'_>,
    ) -> GlResult {
        if target != TEXTURE_3D_OES {
            return Err(GlError::InvalidEnum);
        }
        let c = Compressed::offered_gl(format, self.gpu.features).ok_or(GlError::InvalidOperation)?;
        let (w, h, d) = (width.max(0) as u32, height.max(0) as u32, depth.max(0) as u32);
        let slice = c.image_size(w, h);
        if slice.checked_mul(d as usize) != Some(data.len()) {
            return Err(GlError::InvalidValue);
        }
        let fits = |t: &Texture| if t.format == format { Ok(()) } else { Err(GlError::InvalidOperation) };
        let b = [xoffset, yoffset, zoffset, width, height, depth];
        let (t, size) = sub_volume(&self.gpu, ctx, level, b, fits)?;
        if !block_aligned(c.block_size(), (size[0], size[1]), xoffset, yoffset, width, height) {
            return Err(GlError::InvalidOperation);
        }
        let origin = [xoffset as u32, yoffset as u32, zoffset as u32];
        write_slices(t, &self.gpu, flushed, level as u32, origin, [w, h], &decode_slices(c, &data, w, h));
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glCopyTexSubImage3DOES(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        xoffset: i32,
        yoffset: i32,
        zoffset: i32,
        x: i32,
        y: i32,
        width: i32,
        height: i32,
    ) -> GlResult {
        if target != TEXTURE_3D_OES {
            return Err(GlError::InvalidEnum);
        }
        let image = ImageTarget { face: 0, cube: false, three_d: true };
        self.copy_tex(ctx, flushed, Ok(image), level, None, [xoffset, yoffset, zoffset], x, y, width, height, 0)
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glFramebufferTexture3DOES(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        textarget: u32,
        texture: u32,
        level: i32,
        zoffset: i32,
    ) -> GlResult {
        if target != FRAMEBUFFER {
            return Err(GlError::InvalidEnum);
        }
        if texture == 0 {
            return crate::framebuffers::set_attachment(ctx, attachment, Attachment::None);
        }
        let t = ctx.objects.textures.get(&texture).ok_or(GlError::InvalidOperation)?;
        // As Mesa: the target named must be 3D, and the texture's.
        if textarget != TEXTURE_3D_OES || t.target != TEXTURE_3D_OES {
            return Err(GlError::InvalidOperation);
        }
        if !(0..crate::limits::max_3d_size(&self.gpu) as i32).contains(&zoffset)
            || !(0..=crate::limits::max_3d_level(&self.gpu)).contains(&level)
        {
            return Err(GlError::InvalidValue);
        }
        let a = Attachment::Texture { name: texture, level: level as u32, face: zoffset as u32 };
        crate::framebuffers::set_attachment(ctx, attachment, a)
    }
}

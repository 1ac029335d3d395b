//! Texture image specification from client data: `glTexImage2D` and `glTexSubImage2D` for
//! colour (8-bit, packed, BGRA, float and half-float), depth (`OES_depth_texture`) and
//! depth-stencil (`OES_packed_depth_stencil`) images. Compressed uploads are in `compressed`,
//! copies from the framebuffer in `copyimage`.

use strata_protocol::Blob;

use crate::context::Context;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{internal_accepts, known_internal, same_layout, sized_fits, upload_storage, Compressed, Storage};
use crate::limits::MAX_LEVEL;
use crate::limits::MAX_TEXTURE;
use crate::objects::image::{Region, TextureImage};
use crate::objects::texture::Texture;
use crate::typed::ImageTarget;
use crate::unpack::{depth_stencil_values, to_storage, Unpack};
use crate::GlesExecutor;

/// The texture name an image of `target` goes to: the one bound to its binding point.
pub fn image_texture(ctx: &Context, target: ImageTarget) -> u32 {
    ctx.bindings.texture(target.binding())
}

/// Checks a new image's level and size: `GL_INVALID_VALUE` for a level outside 0..=13, a
/// negative or too large size, a border, or a non-square cube face.
pub fn validate_size(image: ImageTarget, level: i32, width: i32, height: i32, border: i32) -> GlResult {
    if !(0..=MAX_LEVEL).contains(&level)
        || width < 0
        || height < 0
        || border != 0
        || width as u32 > MAX_TEXTURE
        || height as u32 > MAX_TEXTURE
        || (image.cube && width != height)
    {
        return Err(GlError::InvalidValue);
    }
    Ok(())
}

/// Checks a sub-image rectangle against its level: `GL_INVALID_VALUE` if it does not fit.
pub fn validate_rect(level_size: (u32, u32), x: i32, y: i32, width: i32, height: i32) -> GlResult {
    let (lw, lh) = (i64::from(level_size.0), i64::from(level_size.1));
    let (x, y, w, h) = (i64::from(x), i64::from(y), i64::from(width), i64::from(height));
    if x < 0 || y < 0 || w < 0 || h < 0 || x + w > lw || y + h > lh {
        return Err(GlError::InvalidValue);
    }
    Ok(())
}

/// The part of a texture image that a sub-image upload writes, once checked.
pub struct SubImage<'a> {
    /// The texture bound for the image's target.
    pub texture: &'a mut Texture,
    /// Where the data goes.
    pub region: Region,
    /// The size of the level written.
    pub size: (u32, u32),
}

/// The checks `glTexSubImage2D` and `glCompressedTexSubImage2D` share, in GL's order: a level
/// outside 0..=13 is `GL_INVALID_VALUE`; no texture bound or an undefined image is
/// `GL_INVALID_OPERATION`; then data that `format_fits` refuses for the texture is the error it
/// gives; a rectangle outside the
/// level is `GL_INVALID_VALUE`; and on a compressed image, a rectangle that is not whole blocks
/// (`EXT_texture_compression_s3tc`) is `GL_INVALID_OPERATION`.
pub fn sub_image<'a>(
    ctx: &'a mut Context,
    image: ImageTarget,
    level: i32,
    [x, y, width, height]: [i32; 4],
    format_fits: impl FnOnce(&Texture, &TextureImage) -> GlResult,
) -> GlResult<SubImage<'a>> {
    if !(0..=MAX_LEVEL).contains(&level) {
        return Err(GlError::InvalidValue);
    }
    let name = image_texture(ctx, image);
    let texture = ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
    let (face, level) = (image.face, level as u32);
    let img = texture.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
    if texture.defined[face as usize] & (1 << level) == 0 {
        return Err(GlError::InvalidOperation);
    }
    format_fits(texture, img)?;
    let size = img.level_size(level);
    validate_rect(size, x, y, width, height)?;
    if Compressed::from_gl(texture.format).is_some_and(|c| !block_aligned(c.block_size(), size, x, y, width, height)) {
        return Err(GlError::InvalidOperation);
    }
    let region = Region { face, level, x: x as u32, y: y as u32, width: width as u32, height: height as u32 };
    Ok(SubImage { texture, region, size })
}

/// `EXT_texture_compression_s3tc`'s rule for updating part of a compressed image (ASTC's is
/// the same for its footprints): the rectangle starts on a block boundary and covers whole
/// blocks, except where it reaches the level's right or top edge.
pub(super) fn block_aligned(
    block: (u32, u32),
    level_size: (u32, u32),
    x: i32,
    y: i32,
    width: i32,
    height: i32,
) -> bool {
    let (bw, bh) = (block.0 as i32, block.1 as i32);
    let edge = |o: i32, n: i32, b: i32, size: u32| n % b == 0 || i64::from(o) + i64::from(n) == i64::from(size);
    x % bw == 0 && y % bh == 0 && edge(x, width, bw, level_size.0) && edge(y, height, bh, level_size.1)
}

/// `texels` texels of an image specified without data: zero, but with alpha 1 where the format
/// has no alpha (RGB and luminance images read alpha as 1 whatever their colour).
pub(super) fn blank(texels: usize, format: u32, storage: Storage) -> Vec<u8> {
    let alpha: f32 = if matches!(format, RGB | LUMINANCE | RED_EXT | RG_EXT) { 1.0 } else { 0.0 };
    let rgba = [0.0, 0.0, 0.0, alpha];
    let texel: Vec<u8> = match storage {
        Storage::Half => rgba.iter().flat_map(|v| half::f16::from_f32(*v).to_bits().to_ne_bytes()).collect(),
        Storage::Float => rgba.iter().flat_map(|v| v.to_ne_bytes()).collect(),
        _ => vec![0, 0, 0, (alpha * 255.0) as u8],
    };
    texel.repeat(texels)
}

#[allow(non_snake_case)]
impl GlesExecutor {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn glTexImage2D(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        internalformat: i32,
        width: i32,
        height: i32,
        border: i32,
        format: u32,
        pixel_type: u32,
        pixels: Option<Blob<'_>>,
    ) -> GlResult {
        let image = ImageTarget::from_gl(target)?;
        let storage = upload_storage(format, pixel_type);
        // Unknown enums first, then an internal format that is none, then the pairing.
        if !matches!(storage, Err(GlError::InvalidEnum)) && !known_internal(internalformat as u32) {
            return Err(GlError::InvalidValue);
        }
        let storage = storage?;
        // A sized internal format (GL_OES_required_internalformat) stores as its unsized one.
        let internal = match sized_fits(internalformat as u32, format, pixel_type) {
            Some(true) => format,
            Some(false) => return Err(GlError::InvalidOperation),
            None => internalformat as u32,
        };
        if storage.is_depth() {
            // Depth formats have no mipmaps (OES_depth_texture); cube faces take them too
            // (OES_depth_texture_cube_map).
            if internal != format || level != 0 {
                return Err(GlError::InvalidOperation);
            }
            validate_size(image, level, width, height, border)?;
            let pixels = pixels.as_ref().map(|p| p.as_bytes());
            return self.depth_tex_image(
                ctx,
                flushed,
                image,
                width as u32,
                height as u32,
                format,
                pixel_type,
                storage,
                pixels,
            );
        }
        if !internal_accepts(internal, format, self.gpu.features) {
            return Err(GlError::InvalidOperation);
        }
        validate_size(image, level, width, height, border)?;
        let (uid, uid2) = (self.next_uid(), self.next_uid());
        let account = self.account.clone();
        let gpu = &self.gpu;
        let name = image_texture(ctx, image);
        let unpack = Unpack::of(&ctx.pixel_store);
        let t = ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
        let (w, h, level) = (width as u32, height as u32, level as u32);
        let texels = match &pixels {
            Some(p) => Some(
                to_storage(p.as_bytes(), w as usize, h as usize, format, pixel_type, unpack, storage)
                    .ok_or(GlError::InvalidOperation)?,
            ),
            None => None,
        };
        if level == 0 {
            t.ensure_image(gpu, &account, uid, w, h, storage)?;
            t.format = internal;
            t.half_float = pixel_type == HALF_FLOAT_OES;
        } else if Compressed::from_gl(internal).is_some() && storage == Storage::Rgba8 {
            // Uncompressed data for a level of a natively compressed image.
            t.decompress(gpu, flushed, &account, uid2)?;
        }
        let face = image.face;
        let Some(img) = &t.gpu else { return Ok(()) };
        if img.storage != storage || img.level_size(level) != (w.max(1), h.max(1)) || level >= img.mips {
            // A level inconsistent with level 0 leaves the texture incomplete.
            t.defined[face as usize] &= !(1 << level);
            return Ok(());
        }
        t.defined[face as usize] |= 1 << level;
        let region = Region { face, level, x: 0, y: 0, width: w, height: h };
        match texels {
            Some(data) => img.write(gpu, flushed, region, &data),
            None => img.write(gpu, flushed, region, &blank(w as usize * h as usize, format, storage)),
        }
        Ok(())
    }

    /// `glTexImage2D` of a validated `DEPTH_COMPONENT` or `DEPTH_STENCIL_OES` image (level 0 of
    /// a 2D texture or a cube face).
    #[allow(clippy::too_many_arguments)]
    fn depth_tex_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        w: u32,
        h: u32,
        format: u32,
        ty: u32,
        storage: Storage,
        pixels: Option<&[u8]>,
    ) -> GlResult {
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let unpack = Unpack::of(&ctx.pixel_store);
        let values = match pixels {
            Some(b) => {
                Some(depth_stencil_values(b, w as usize, h as usize, ty, unpack).ok_or(GlError::InvalidOperation)?)
            }
            None => None,
        };
        let name = image_texture(ctx, image);
        let t = ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
        t.ensure_image(gpu, &account, uid, w, h, storage)?;
        if image.cube {
            t.defined[image.face as usize] = 1;
        } else {
            t.defined = [1, 0, 0, 0, 0, 0];
        }
        t.format = format;
        let Some(img) = &t.gpu else { return Ok(()) };
        let texture = img.texture.clone();
        if let Some((depths, stencil)) = values.filter(|_| w > 0 && h > 0) {
            let stencil = (!stencil.is_empty()).then_some(stencil.as_slice());
            self.r.upload_depth(flushed, &texture, image.face, (w, h), [0, 0, w, h], &depths, stencil);
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glTexSubImage2D(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        target: u32,
        level: i32,
        xoffset: i32,
        yoffset: i32,
        width: i32,
        height: i32,
        format: u32,
        pixel_type: u32,
        pixels: Blob<'_>,
    ) -> GlResult {
        let image = ImageTarget::from_gl(target)?;
        let storage = upload_storage(format, pixel_type)?;
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let unpack = Unpack::of(&ctx.pixel_store);
        let fits = |t: &Texture, img: &TextureImage| {
            let fits = match Compressed::from_gl(t.format) {
                Some(Compressed::S3tc(_)) => internal_accepts(t.format, format, gpu.features),
                // ASTC images take no uncompressed data: Mesa finds no format to convert it
                // to, which is GL_INVALID_VALUE.
                Some(Compressed::Astc(_) | Compressed::AstcSrgb(_)) => return Err(GlError::InvalidValue),
                // ETC1 images cannot be updated in part (OES_compressed_ETC1_RGB8_texture), nor
                // sRGB S3TC images by uncompressed data.
                Some(Compressed::Etc1 | Compressed::S3tcSrgb(_)) => false,
                // ES 2.0: the format must be the image's (RGBA and BGRA count as one,
                // MESA_bgra); the type must give the same storage.
                None => same_layout(t.format, format) && storage == img.storage,
            };
            if fits {
                Ok(())
            } else {
                Err(GlError::InvalidOperation)
            }
        };
        let SubImage { texture: t, region, size } =
            sub_image(ctx, image, level, [xoffset, yoffset, width, height], fits)?;
        let (w, h) = (region.width, region.height);
        if pixels.is_empty() || w == 0 || h == 0 {
            // No data (a null pointer): nothing to write.
            return Ok(());
        }
        let Some(img) = &t.gpu else { return Ok(()) };
        if storage.is_depth() {
            let (depths, stencil) = depth_stencil_values(pixels.as_bytes(), w as usize, h as usize, pixel_type, unpack)
                .ok_or(GlError::InvalidOperation)?;
            let texture = img.texture.clone();
            let stencil = (!stencil.is_empty()).then_some(stencil.as_slice());
            let rect = [region.x, region.y, w, h];
            self.r.upload_depth(flushed, &texture, image.face, size, rect, &depths, stencil);
            return Ok(());
        }
        let target_storage = if matches!(img.storage, Storage::Native(_)) { Storage::Rgba8 } else { img.storage };
        let data = to_storage(pixels.as_bytes(), w as usize, h as usize, format, pixel_type, unpack, target_storage)
            .ok_or(GlError::InvalidOperation)?;
        t.decompress(gpu, flushed, &account, uid)?;
        if let Some(img) = &t.gpu {
            img.write(gpu, flushed, region, &data);
        }
        Ok(())
    }
}

//! Texture images specified from client data, for every shape of image, as Mesa's
//! `teximage.c` serves every dimension: `glTexImage2D`/`glTexImage3DOES` and
//! `glTexSubImage2D`/`glTexSubImage3DOES`, for colour (8-bit, packed, BGRA, float and
//! half-float), depth (`OES_depth_texture`) and depth-stencil (`OES_packed_depth_stencil`)
//! images. The entry points name the shape (an [`ImageTarget`]: a 2D image, a cube face or a 3D
//! image; next, a 2D array's layers) and a size with a depth (1 for a 2D image), and share one
//! path: the checks, the image's (re)specification and its layers written one by one (a 3D
//! image's slice `z` is the layer a cube map's face is). Compressed uploads are in
//! `compressed`, copies from the framebuffer in `copyimage`, attachments in `framebuffers`.

use strata_device::Gpu;
use strata_protocol::Blob;

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{
    immutable_storage, internal_accepts, known_internal, same_layout, sized_fits, upload_storage, Compressed, Storage,
};
use crate::limits::{max_3d_level, max_3d_size, max_array_layers, MAX_LEVEL, MAX_TEXTURE};
use crate::objects::image::{Region, TextureImage};
use crate::objects::texture::Texture;
use crate::texstorage::{mutable, sized_accepts};
use crate::typed::ImageTarget;
use crate::unpack::{depth_stencil_values, to_storage_rounded, Unpack};
use crate::GlesExecutor;

/// The texture name an image of `target` goes to: the one bound to its binding point.
pub fn image_texture(ctx: &Context, target: ImageTarget) -> u32 {
    ctx.bindings.texture(target.binding())
}

/// The last level an image of `image`'s shape may have: log2 of the largest image (for a 3D
/// image, of the largest 3D image the device allows).
pub fn max_level(gpu: &Gpu, image: ImageTarget) -> i32 {
    if image.three_d {
        max_3d_level(gpu)
    } else {
        MAX_LEVEL
    }
}

/// Checks a new image's level and size as Mesa does: `GL_INVALID_VALUE` for a level past the
/// shape's last, a negative size, one beyond the largest (for a 3D image, the largest that
/// level may have), a border, or a non-square cube face.
pub fn validate_size(gpu: &Gpu, image: ImageTarget, level: i32, size: [i32; 3], border: i32) -> GlResult {
    if !(0..=max_level(gpu, image)).contains(&level) || border != 0 {
        return Err(GlError::InvalidValue);
    }
    let most = if image.three_d { (max_3d_size(gpu) >> level) as i32 } else { MAX_TEXTURE as i32 };
    let layers = if image.array { max_array_layers(gpu) as i32 } else { most };
    let [w, h, d] = size;
    if ![w, h].iter().all(|n| (0..=most).contains(n)) || !(0..=layers).contains(&d) || (image.cube && w != h) {
        return Err(GlError::InvalidValue);
    }
    Ok(())
}

/// Checks a sub-image box at `origin` of `extent` against a level of `size` (width, height and
/// slices): `GL_INVALID_VALUE` if it does not fit.
pub fn validate_box(size: [u32; 3], origin: [i32; 3], extent: [i32; 3]) -> GlResult {
    let fits = (0..3).all(|i| {
        let (o, n) = (i64::from(origin[i]), i64::from(extent[i]));
        o >= 0 && n >= 0 && o + n <= i64::from(size[i])
    });
    if fits {
        Ok(())
    } else {
        Err(GlError::InvalidValue)
    }
}

/// The part of a texture image that a sub-image upload writes, once checked.
pub struct SubImage<'a> {
    /// The texture bound for the image's target.
    pub texture: &'a mut Texture,
    /// Where the data's first layer goes.
    pub region: Region,
    /// How many layers (a 3D image's slices) it writes, from `region`'s on.
    pub layers: u32,
    /// The size of the level written.
    pub size: (u32, u32),
}

/// The checks `glTexSubImage*` and `glCompressedTexSubImage*` share, in Mesa's order: a level
/// past the shape's last is `GL_INVALID_VALUE`; no texture bound or an undefined image is
/// `GL_INVALID_OPERATION`; then data that `format_fits` refuses for the texture is the error it
/// gives; a box outside the level is `GL_INVALID_VALUE`; and on a compressed image, a rectangle
/// that is not whole blocks (`EXT_texture_compression_s3tc`) is `GL_INVALID_OPERATION`.
pub fn sub_image<'a>(
    gpu: &Gpu,
    ctx: &'a mut Context,
    image: ImageTarget,
    level: i32,
    origin: [i32; 3],
    extent: [i32; 3],
    format_fits: impl FnOnce(&Texture, &TextureImage) -> GlResult,
) -> GlResult<SubImage<'a>> {
    if !(0..=max_level(gpu, image)).contains(&level) {
        return Err(GlError::InvalidValue);
    }
    let name = image_texture(ctx, image);
    let texture = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
    let (face, level) = (image.face, level as u32);
    let img = texture.gpu.as_ref().ok_or(GlError::InvalidOperation)?;
    if texture.defined[face as usize] & (1 << level) == 0 {
        return Err(GlError::InvalidOperation);
    }
    format_fits(texture, img)?;
    let size = img.level_size(level);
    validate_box([size.0, size.1, img.level_depth(level)], origin, extent)?;
    let [x, y, z] = origin;
    let [width, height, layers] = extent;
    if Compressed::from_gl(texture.format).is_some_and(|c| !block_aligned(c.block_size(), size, x, y, width, height)) {
        return Err(GlError::InvalidOperation);
    }
    let (width, height) = (width as u32, height as u32);
    let region = Region { face: face + z as u32, level, x: x as u32, y: y as u32, width, height };
    Ok(SubImage { texture, region, layers: layers as u32, size })
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

/// Whether `level` of texture `t`'s image, just (re)specified as `size` (width, height, slices)
/// in `same` format or storage as level 0, is consistent with level 0: if so it is marked
/// defined at `layer`, else undefined there (the texture is then incomplete).
pub(super) fn define_level(t: &mut Texture, layer: u32, level: u32, [w, h, d]: [u32; 3], same: bool) -> bool {
    let consistent = t.gpu.as_ref().is_some_and(|img| {
        same && img.level_size(level) == (w.max(1), h.max(1)) && img.level_depth(level) == d.max(1) && level < img.mips
    });
    if consistent {
        t.defined[layer as usize] |= 1 << level;
    } else {
        t.defined[layer as usize] &= !(1 << level);
    }
    consistent
}

/// Writes `layers` layers of `data` (tightly packed, one after another) into `img` from
/// `region`'s layer on, each the size of `region`.
pub(super) fn write_layers(img: &TextureImage, gpu: &Gpu, flushed: &Flushed, region: Region, layers: u32, data: &[u8]) {
    let bytes = (region.width * region.height * img.storage.texel_bytes()) as usize;
    if bytes == 0 {
        return;
    }
    for (k, layer) in data.chunks_exact(bytes).take(layers as usize).enumerate() {
        img.write(gpu, flushed, Region { face: region.face + k as u32, ..region }, layer);
    }
}

/// `texels` texels of an image specified without data: zero, but with alpha 1 where the format
/// has no alpha (RGB and luminance images read alpha as 1 whatever their colour).
pub(super) fn blank(texels: usize, format: u32, storage: Storage) -> Vec<u8> {
    let alpha: f32 = if matches!(format, RGB | LUMINANCE | RED_EXT | RG_EXT) { 1.0 } else { 0.0 };
    let rgba = [0.0, 0.0, 0.0, alpha];
    let texel: Vec<u8> = match storage {
        Storage::Int { bits, .. } => crate::integer::blank_texel(bits),
        Storage::Half => rgba.iter().flat_map(|v| half::f16::from_f32(*v).to_bits().to_ne_bytes()).collect(),
        Storage::Float => rgba.iter().flat_map(|v| v.to_ne_bytes()).collect(),
        // Packed: zero, with the format's alpha (RGB10_A2 has its own; R11F_G11F_B10F none).
        Storage::Rgb10a2 | Storage::Rg11b10 => 0u32.to_ne_bytes().to_vec(),
        _ => vec![0, 0, 0, (alpha * 255.0) as u8],
    };
    texel.repeat(texels)
}

/// A 3D image's target: `GL_TEXTURE_3D_OES` (anything else is `GL_INVALID_ENUM`).
pub(super) fn volume_target(target: u32) -> GlResult<ImageTarget> {
    if target == TEXTURE_3D_OES {
        Ok(ImageTarget { face: 0, cube: false, three_d: true, array: false })
    } else {
        Err(GlError::InvalidEnum)
    }
}

/// The target of an image with layers: a 3D image's, or in an ES 3.0 context (`es3`) a 2D
/// array's, `GL_TEXTURE_2D_ARRAY` (anything else is `GL_INVALID_ENUM`).
pub(super) fn layered_target(target: u32, es3: bool) -> GlResult<ImageTarget> {
    if es3 && target == TEXTURE_2D_ARRAY {
        Ok(ImageTarget { face: 0, cube: false, three_d: false, array: true })
    } else {
        volume_target(target)
    }
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// (Re)specifies level `level` of `image` as `size` (width, height, layers) from `pixels`
    /// (none: blank), in the order of Mesa's checks.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn tex_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        level: i32,
        internalformat: u32,
        [width, height, depth]: [i32; 3],
        border: i32,
        format: u32,
        pixel_type: u32,
        pixels: Option<Blob<'_>>,
    ) -> GlResult {
        // ES 3.0's float depth formats: a level of a 2D image, a cube face or a 2D array, as
        // the other depth images are.
        // Mesa takes float depths for the unsized depth format too.
        let unsized_float = (internalformat, format, pixel_type) == (DEPTH_COMPONENT, DEPTH_COMPONENT, FLOAT);
        if ctx.es3() && (matches!(internalformat, DEPTH_COMPONENT32F | DEPTH32F_STENCIL8) || unsized_float) {
            if !unsized_float && !sized_accepts(internalformat, format, pixel_type) {
                // An unknown pairing of format and type first, as Mesa answers.
                return match upload_storage(format, pixel_type) {
                    Err(GlError::InvalidEnum) if pixel_type != FLOAT_32_UNSIGNED_INT_24_8_REV => {
                        Err(GlError::InvalidEnum)
                    }
                    _ => Err(GlError::InvalidOperation),
                };
            }
            if image.three_d {
                return Err(GlError::InvalidOperation);
            }
            validate_size(&self.gpu, image, level, [width, height, depth], border)?;
            let storage = if format == DEPTH_COMPONENT { Storage::Depth } else { Storage::DepthStencil };
            let pixels = pixels.as_ref().map(|p| p.as_bytes());
            let size = [width as u32, height as u32, depth as u32, level as u32];
            // The unsized format with float depths keeps them as DEPTH_COMPONENT32F does.
            let sized = if unsized_float { DEPTH_COMPONENT32F } else { internalformat };
            return self.depth_tex_image(ctx, flushed, image, size, (format, sized), pixel_type, storage, pixels);
        }
        // ES 3.0's sized formats that ES 2.0's extensions do not name (the float ones): the
        // data ES 3.0's table gives the format, kept as the format keeps it.
        // ES 3.0's RGB10_A2 too, which is renderable there (ES 2.0's extensions keep it as
        // half floats, as its unsized RGBA form still is).
        let es3_format = sized_fits(internalformat, 0, 0).is_none() || internalformat == RGB10_A2_EXT;
        let es3_sized = match ctx.es3() && es3_format {
            true => immutable_storage(internalformat, self.gpu.features).filter(|(_, s, _)| !s.is_depth()),
            false => None,
        };
        let (data_type, storage, internal, half_float, sized) = if let Some((base, kept, half)) = es3_sized {
            let ty = if pixel_type == HALF_FLOAT { HALF_FLOAT_OES } else { pixel_type };
            if !sized_accepts(internalformat, format, pixel_type) {
                // An unknown enum first (ES 3.0's signed types are known: their pairing is
                // wrong).
                match upload_storage(format, ty) {
                    Err(GlError::InvalidEnum)
                        if !matches!(ty, BYTE | SHORT | INT) && !crate::packed_float::is_packed_float_type(ty) =>
                    {
                        return Err(GlError::InvalidEnum)
                    }
                    _ => return Err(GlError::InvalidOperation),
                }
            }
            (ty, kept, base, half, internalformat)
        } else {
            let storage = match upload_storage(format, pixel_type) {
                // ES 3.0's packed float data pairs only with its sized formats.
                Err(GlError::InvalidEnum) if ctx.es3() && crate::packed_float::is_packed_float_type(pixel_type) => {
                    Err(GlError::InvalidOperation)
                }
                s => s,
            };
            // Unknown enums first, then an internal format that is none, then the pairing.
            if !matches!(storage, Err(GlError::InvalidEnum)) && !known_internal(internalformat) {
                return Err(GlError::InvalidValue);
            }
            let storage = storage?;
            // A sized internal format (GL_OES_required_internalformat) stores as its unsized one.
            let internal = match sized_fits(internalformat, format, pixel_type) {
                Some(true) => format,
                Some(false) => return Err(GlError::InvalidOperation),
                None => internalformat,
            };
            if storage.is_depth() {
                // Depth formats have no mipmaps in ES 2.0 (OES_depth_texture; ES 3.0 has them),
                // and no 3D images: it names 2D images and cube faces
                // (OES_depth_texture_cube_map), and ES 3.0 2D arrays.
                if image.three_d || internal != format || (level != 0 && !ctx.es3()) {
                    return Err(GlError::InvalidOperation);
                }
                validate_size(&self.gpu, image, level, [width, height, depth], border)?;
                let pixels = pixels.as_ref().map(|p| p.as_bytes());
                let size = [width as u32, height as u32, depth as u32, level as u32];
                return self.depth_tex_image(ctx, flushed, image, size, (format, 0), pixel_type, storage, pixels);
            }
            if !internal_accepts(internal, format, self.gpu.features) {
                return Err(GlError::InvalidOperation);
            }
            (pixel_type, storage, internal, pixel_type == HALF_FLOAT_OES, 0)
        };
        validate_size(&self.gpu, image, level, [width, height, depth], border)?;
        let (uid, uid2) = (self.next_uid(), self.next_uid());
        let account = self.account.clone();
        let gpu = &self.gpu;
        let name = image_texture(ctx, image);
        let unpack = Unpack::of(&ctx.pixel_store);
        let t = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
        mutable(t)?;
        let (w, h, d, level) = (width as u32, height as u32, depth as u32, level as u32);
        // Layers are read one after another: ES 2.0 has no image height to unpack them by.
        let round = crate::packed_float::rounding(sized);
        let texels = match &pixels {
            Some(p) => Some(
                to_storage_rounded(
                    p.as_bytes(),
                    w as usize,
                    (h * d) as usize,
                    (format, data_type),
                    unpack,
                    storage,
                    round,
                )
                .ok_or(GlError::InvalidOperation)?,
            ),
            None => None,
        };
        if level == 0 {
            t.ensure_volume(gpu, &account, uid, (w, h, d), storage)?;
            t.format = internal;
            t.half_float = half_float;
            t.sized = sized;
        } else if Compressed::from_gl(internal).is_some() && storage == Storage::Rgba8 {
            // Uncompressed data for a level of a natively compressed image.
            t.decompress(gpu, flushed, &account, uid2)?;
        }
        let same = t.gpu.as_ref().is_some_and(|img| img.storage == storage);
        if !define_level(t, image.face, level, [w, h, d], same) {
            return Ok(());
        }
        let Some(img) = &t.gpu else { return Ok(()) };
        let region = Region { face: image.face, level, x: 0, y: 0, width: w, height: h };
        let data = texels.unwrap_or_else(|| blank(w as usize * h as usize * d as usize, format, storage));
        write_layers(img, gpu, flushed, region, d, &data);
        Ok(())
    }

    /// `glTexImage2D` (`3D`) of a validated `DEPTH_COMPONENT` or `DEPTH_STENCIL_OES` image
    /// (level `level` of a 2D texture, a cube face or a 2D array of `d` layers; `sized`: its
    /// float sized format, or 0).
    #[allow(clippy::too_many_arguments)]
    fn depth_tex_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        [w, h, d, level]: [u32; 4],
        (format, sized): (u32, u32),
        ty: u32,
        storage: Storage,
        pixels: Option<&[u8]>,
    ) -> GlResult {
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let unpack = Unpack::of(&ctx.pixel_store);
        let layers = if image.array { d } else { 1 };
        let values = match pixels {
            Some(b) => Some(
                depth_stencil_values(b, w as usize, (h * layers) as usize, ty, unpack)
                    .ok_or(GlError::InvalidOperation)?,
            ),
            None => None,
        };
        let name = image_texture(ctx, image);
        let t = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
        mutable(t)?;
        if level == 0 {
            t.ensure_volume(gpu, &account, uid, (w, h, layers), storage)?;
            t.format = format;
            t.sized = sized;
        }
        let same = t.gpu.as_ref().is_some_and(|img| img.storage == storage);
        if !define_level(t, image.face, level, [w, h, layers], same) {
            return Ok(());
        }
        let Some(img) = &t.gpu else { return Ok(()) };
        let texture = img.texture.clone();
        if let Some((depths, stencil)) = values.filter(|_| w > 0 && h > 0) {
            let at = (image.face, level);
            self.upload_depth_layers(flushed, &texture, at, (w, h), [0, 0, w, h], layers, (&depths, &stencil));
        }
        Ok(())
    }

    /// Writes `layers` layers of depth (and stencil, where given) values, one after another,
    /// into the rectangle `rect` of the layers from `first` on of level `level` (`size`) of a
    /// depth texture.
    #[allow(clippy::too_many_arguments)]
    fn upload_depth_layers(
        &mut self,
        flushed: &Flushed,
        texture: &wgpu::Texture,
        (first, level): (u32, u32),
        size: (u32, u32),
        rect: [u32; 4],
        layers: u32,
        (depths, stencil): (&[f32], &[u8]),
    ) {
        let per = (rect[2] * rect[3]) as usize;
        for k in 0..layers as usize {
            let (Some(d), s) = (depths.get(k * per..(k + 1) * per), stencil.get(k * per..(k + 1) * per)) else {
                return;
            };
            self.r.upload_depth(flushed, texture, (first + k as u32, level), size, rect, d, s);
        }
    }

    /// Writes `pixels` into the box at `origin` of `extent` of level `level` of `image`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn tex_sub_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        level: i32,
        origin: [i32; 3],
        extent: [i32; 3],
        format: u32,
        pixel_type: u32,
        pixels: Blob<'_>,
    ) -> GlResult {
        // ES 3.0's GL_HALF_FLOAT is GL_HALF_FLOAT_OES's data; only images made by
        // glTexStorage* in a half-float format take it yet (`sized_accepts`).
        let es3_half = ctx.es3() && pixel_type == HALF_FLOAT;
        let given_type = pixel_type;
        let pixel_type = if es3_half { HALF_FLOAT_OES } else { pixel_type };
        // ES 3.0's signed normalized data (BYTE) goes only to images of its sized formats.
        let es3_byte = ctx.es3() && pixel_type == BYTE;
        // ES 3.0's integer data goes only to images of integer formats (`sized_accepts`).
        let int_data = ctx.es3()
            && crate::integer::is_integer_format(format)
            && matches!(
                pixel_type,
                BYTE | UNSIGNED_BYTE | SHORT | UNSIGNED_SHORT | INT | UNSIGNED_INT | UNSIGNED_INT_2_10_10_10_REV_EXT
            );
        let storage = match upload_storage(format, pixel_type) {
            _ if int_data => Storage::Int { signed: false, bits: 32 },
            // ES 3.0's packed float data goes only to images of their formats.
            _ if ctx.es3() && crate::packed_float::is_packed_float_type(pixel_type) => Storage::Half,
            Err(GlError::InvalidEnum) if es3_byte => Storage::Half,
            // ES 3.0's float depths (the images that take them decide by their sized format).
            Err(GlError::InvalidOperation) if ctx.es3() && (format, pixel_type) == (DEPTH_COMPONENT, FLOAT) => {
                Storage::Depth
            }
            Err(GlError::InvalidEnum)
                if ctx.es3() && (format, pixel_type) == (DEPTH_STENCIL_OES, FLOAT_32_UNSIGNED_INT_24_8_REV) =>
            {
                Storage::DepthStencil
            }
            s => s?,
        };
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let unpack = Unpack::of(&ctx.pixel_store);
        let fits = |t: &Texture, img: &TextureImage| {
            let fits = match Compressed::from_gl(t.format) {
                // An image made by glTexStorage* takes what ES 3.0's table gives its format,
                // converted to its storage.
                None if t.sized != 0 => sized_accepts(t.sized, format, given_type),
                Some(Compressed::S3tc(_)) => internal_accepts(t.format, format, gpu.features),
                // ASTC and ETC2 images take no uncompressed data: Mesa finds no format to
                // convert it to, which is GL_INVALID_VALUE.
                Some(Compressed::Astc(_) | Compressed::AstcSrgb(_) | Compressed::Etc2(_) | Compressed::Etc2Srgb(_)) => {
                    return Err(GlError::InvalidValue)
                }
                // ETC1 images cannot be updated in part (OES_compressed_ETC1_RGB8_texture), nor
                // sRGB S3TC images by uncompressed data.
                Some(Compressed::Etc1 | Compressed::S3tcSrgb(_)) => false,
                // ES 2.0: the format must be the image's (RGBA and BGRA count as one,
                // MESA_bgra); the type must give the same storage.
                None => !es3_half && !es3_byte && same_layout(t.format, format) && storage == img.storage,
            };
            if fits {
                Ok(())
            } else {
                Err(GlError::InvalidOperation)
            }
        };
        let SubImage { texture: t, region, layers, size } = sub_image(gpu, ctx, image, level, origin, extent, fits)?;
        let (w, h) = (region.width, region.height);
        if pixels.is_empty() || w == 0 || h == 0 || layers == 0 {
            // No data (a null pointer): nothing to write.
            return Ok(());
        }
        let Some(img) = &t.gpu else { return Ok(()) };
        if storage.is_depth() {
            // 2D images, cube faces and 2D arrays hold depth, layer after layer.
            let rows = (h * layers) as usize;
            let (depths, stencil) = depth_stencil_values(pixels.as_bytes(), w as usize, rows, pixel_type, unpack)
                .ok_or(GlError::InvalidOperation)?;
            let texture = img.texture.clone();
            let rect = [region.x, region.y, w, h];
            let at = (region.face, region.level);
            self.upload_depth_layers(flushed, &texture, at, size, rect, layers, (&depths, &stencil));
            return Ok(());
        }
        let target_storage = if matches!(img.storage, Storage::Native(_)) { Storage::Rgba8 } else { img.storage };
        let rows = (h * layers) as usize;
        let round = crate::packed_float::rounding(t.sized);
        let data = to_storage_rounded(
            pixels.as_bytes(),
            w as usize,
            rows,
            (format, pixel_type),
            unpack,
            target_storage,
            round,
        )
        .ok_or(GlError::InvalidOperation)?;
        t.decompress(gpu, flushed, &account, uid)?;
        if let Some(img) = &t.gpu {
            write_layers(img, gpu, flushed, region, layers, &data);
        }
        Ok(())
    }
}

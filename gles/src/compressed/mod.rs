//! Compressed texture images, for every shape of image (`teximage`'s one path):
//! `glCompressedTexImage2D`/`3DOES` and `glCompressedTexSubImage2D`/`3DOES` for
//! `EXT_texture_compression_s3tc` (and its sRGB forms, `EXT_texture_compression_s3tc_srgb`),
//! `OES_compressed_ETC1_RGB8_texture` (with `EXT_compressed_ETC1_RGB8_sub_texture`) and
//! `KHR_texture_compression_astc_ldr` (in its linear and sRGB forms; 3D images by
//! `KHR_texture_compression_astc_sliced_3d`, slice after slice). Where the device has the block
//! format (and a 2D image's size is a whole number of blocks, as wgpu requires) the blocks are
//! uploaded as they are; otherwise they are decoded here, to RGBA8, or for the sRGB forms to
//! linear RGBA16F.

pub mod astc;
pub mod etc1;
pub mod etc2;
pub mod s3tc;

use strata_protocol::Blob;

use crate::context::Context;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::{Compressed, Storage};
use crate::objects::image::Region;
use crate::objects::texture::Texture;
use crate::teximage::{define_level, image_texture, sub_image, validate_size, write_layers, SubImage};
use crate::typed::ImageTarget;
use crate::GlesExecutor;

/// Compressed `data` of `layers` layers of `w`×`h` texels one after another, decoded layer by
/// layer.
fn decode_layers(c: Compressed, data: &[u8], w: u32, h: u32, layers: u32) -> Vec<u8> {
    let layer = c.image_size(w, h).max(1);
    data.chunks_exact(layer).take(layers as usize).flat_map(|l| c.decode_for(l, w, h)).collect()
}

/// Whether `data` holds exactly `layers` layers of `w`×`h` texels in `c`.
fn sized(c: Compressed, data: &Blob<'_>, w: u32, h: u32, layers: u32) -> bool {
    c.image_size(w, h).checked_mul(layers as usize) == Some(data.len())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// (Re)specifies level `level` of `image` as `size` (width, height, layers) of compressed
    /// `data`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn compressed_tex_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        level: i32,
        internalformat: u32,
        [width, height, depth]: [i32; 3],
        border: i32,
        data: Blob<'_>,
    ) -> GlResult {
        // Only ASTC has 3D images (GL_KHR_texture_compression_astc_sliced_3d); ES 3.0 makes a
        // 3D image of its ETC2 formats GL_INVALID_OPERATION, the extensions' formats an
        // unknown enum.
        let c = Compressed::offered_gl(internalformat, self.gpu.features, ctx.es3()).ok_or(GlError::InvalidEnum)?;
        match c {
            Compressed::Etc2(_) | Compressed::Etc2Srgb(_) if image.three_d => return Err(GlError::InvalidOperation),
            Compressed::Astc(_) | Compressed::AstcSrgb(_) => {}
            _ if image.three_d => return Err(GlError::InvalidEnum),
            _ => {}
        }
        validate_size(&self.gpu, image, level, [width, height, depth], border)?;
        let (w, h, d, level) = (width as u32, height as u32, depth as u32, level as u32);
        if !sized(c, &data, w, h, d) {
            return Err(GlError::InvalidValue);
        }
        let uid = self.next_uid();
        let account = self.account.clone();
        let gpu = &self.gpu;
        let name = image_texture(ctx, image);
        let t = ctx.objects.texture_mut(image.binding(), name).ok_or(GlError::InvalidOperation)?;
        crate::texstorage::mutable(t)?;
        if level == 0 {
            // Blocks go up as they are only into a 2D image of whole blocks.
            let (bw, bh) = c.block_size();
            let whole_blocks = !image.three_d && !image.array && w > 0 && h > 0 && w % bw == 0 && h % bh == 0;
            let native = whole_blocks && c.native_on(gpu.features).is_some();
            let storage = if native { Storage::Native(c) } else { c.decoded_storage() };
            t.ensure_volume(gpu, &account, uid, (w, h, d), storage)?;
            t.format = internalformat;
        }
        let same = t.format == internalformat;
        if !define_level(t, image.face, level, [w, h, d], same) {
            return Ok(());
        }
        let Some(img) = &mut t.gpu else { return Ok(()) };
        let region = Region { face: image.face, level, x: 0, y: 0, width: w, height: h };
        match img.storage {
            Storage::Native(_) => img.write_blocks(gpu, flushed, region, data.as_bytes()),
            _ => write_layers(img, gpu, flushed, region, d, &decode_layers(c, data.as_bytes(), w, h, d)),
        }
        Ok(())
    }

    /// Writes compressed `data` into the box at `origin` of `extent` of level `level` of
    /// `image`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn compressed_tex_sub_image(
        &mut self,
        ctx: &mut Context,
        flushed: &Flushed,
        image: ImageTarget,
        level: i32,
        origin: [i32; 3],
        extent: [i32; 3],
        format: u32,
        data: Blob<'_>,
    ) -> GlResult {
        // As on Mesa, a format that is not an offered compressed one cannot match the image,
        // whatever the level and the rectangle.
        let c = Compressed::offered_gl(format, self.gpu.features, ctx.es3()).ok_or(GlError::InvalidOperation)?;
        let gpu = &self.gpu;
        // An image is updated only by data of its own format (ETC1's too, by
        // `EXT_compressed_ETC1_RGB8_sub_texture`).
        let fits = |t: &Texture, _: &_| if t.format == format { Ok(()) } else { Err(GlError::InvalidOperation) };
        // As on Mesa, data of the wrong size for the box in the format named is refused before
        // the texture is looked at (a negative size counts as none).
        let [w, h, d] = extent.map(|n| n.max(0) as u32);
        if !sized(c, &data, w, h, d) {
            return Err(GlError::InvalidValue);
        }
        let SubImage { texture: t, region, layers, .. } = sub_image(gpu, ctx, image, level, origin, extent, fits)?;
        let Some(img) = &mut t.gpu else { return Ok(()) };
        let (w, h) = (region.width, region.height);
        match img.storage {
            Storage::Native(_) => img.write_blocks(gpu, flushed, region, data.as_bytes()),
            _ => write_layers(img, gpu, flushed, region, layers, &decode_layers(c, data.as_bytes(), w, h, layers)),
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::enums::ETC1_RGB8_OES;
    use super::*;

    /// The levels of a KTX 1 file (little-endian): its internal format, level-0 size, and
    /// each level's bytes.
    pub(in crate::compressed) fn ktx_levels(file: &[u8]) -> (u32, u32, u32, Vec<Vec<u8>>) {
        let word = |i: usize| u32::from_le_bytes(file[12 + 4 * i..16 + 4 * i].try_into().expect("word"));
        assert_eq!(word(0), 0x0403_0201, "little-endian KTX");
        let (internal, width, height, levels, kv) = (word(4), word(6), word(7), word(11), word(12));
        let mut at = 64 + kv as usize;
        let mut out = Vec::new();
        for _ in 0..levels {
            let size = u32::from_le_bytes(file[at..at + 4].try_into().expect("size")) as usize;
            out.push(file[at + 4..at + 4 + size].to_vec());
            at += 4 + size.div_ceil(4) * 4;
        }
        (internal, width, height, out)
    }

    /// piglit's ETC1 mip chain and its decompressed RGB reference (produced by an independent
    /// ETC1 decoder), as Debian's piglit package installs them.
    #[test]
    fn etc1_matches_piglit_reference_images() {
        let dir = "/usr/lib/x86_64-linux-gnu/piglit/tests/spec/oes_compressed_etc1_rgb8_texture";
        let (Ok(etc), Ok(rgb)) = (
            std::fs::read(format!("{dir}/waffles-compressed-etc1-64x32-miptree.ktx")),
            std::fs::read(format!("{dir}/waffles-decompressed-rgb-64x32-miptree.ktx")),
        ) else {
            assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "piglit's ETC1 images are missing");
            eprintln!("SKIPPED: piglit's ETC1 images are not installed (tools/install-deps installs piglit)");
            return;
        };
        let (internal, mut w, mut h, blocks) = ktx_levels(&etc);
        let (_, _, _, reference) = ktx_levels(&rgb);
        assert_eq!(internal, ETC1_RGB8_OES);
        assert_eq!(blocks.len(), 7);
        for (level, (b, r)) in blocks.iter().zip(&reference).enumerate() {
            let decoded = Compressed::Etc1.decode(b, w, h);
            // Reference rows are RGB, padded to 4 bytes.
            let row = (w as usize * 3).div_ceil(4) * 4;
            for y in 0..h as usize {
                for x in 0..w as usize {
                    let want = &r[y * row + x * 3..][..3];
                    let got = &decoded[(y * w as usize + x) * 4..][..4];
                    assert_eq!(&got[..3], want, "level {level} texel ({x}, {y})");
                    assert_eq!(got[3], 255);
                }
            }
            w = (w / 2).max(1);
            h = (h / 2).max(1);
        }
    }
}

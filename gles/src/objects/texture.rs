//! A texture object: its parameters, its levels defined so far, and its image.

use std::sync::Arc;

use strata_device::account::Account;
use strata_device::Gpu;

use crate::enums::*;
use crate::error::GlResult;
use crate::flushed::Flushed;
use crate::formats::Storage;
use crate::objects::image::Region;
use crate::objects::image::TextureImage;

/// Sampling state of a texture (ES 2.0 keeps it in the texture object).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SamplerState {
    /// `TEXTURE_MIN_FILTER`.
    pub min: u32,
    /// `TEXTURE_MAG_FILTER`.
    pub mag: u32,
    /// `TEXTURE_WRAP_S`.
    pub wrap_s: u32,
    /// `TEXTURE_WRAP_T`.
    pub wrap_t: u32,
    /// `TEXTURE_WRAP_R_OES` (`GL_OES_texture_3D`; every texture has it).
    pub wrap_r: u32,
    /// `TEXTURE_MAX_ANISOTROPY_EXT` (`GL_EXT_texture_filter_anisotropic`), as `f32` bits:
    /// from 1 to [`MAX_ANISOTROPY`].
    pub anisotropy: u32,
    /// `TEXTURE_MAX_LEVEL_APPLE` (`GL_APPLE_texture_max_level`, core in ES 3.0): the last level
    /// sampled, and the last a mipmapped texture needs. A texture's, never a sampler object's.
    pub max_level: u32,
    /// `GL_TEXTURE_BASE_LEVEL` (ES 3.0): the first level sampled. A texture's.
    pub base_level: u32,
    /// `GL_TEXTURE_MIN_LOD` (ES 3.0), as `f32` bits: the least level of detail sampled.
    pub min_lod: u32,
    /// `GL_TEXTURE_MAX_LOD` (ES 3.0), as `f32` bits: the greatest level of detail sampled.
    pub max_lod: u32,
    /// `GL_TEXTURE_COMPARE_MODE` (ES 3.0): `GL_NONE` or `GL_COMPARE_REF_TO_TEXTURE`.
    pub compare_mode: u32,
    /// `GL_TEXTURE_COMPARE_FUNC` (ES 3.0).
    pub compare_func: u32,
}

impl Default for SamplerState {
    fn default() -> Self {
        SamplerState {
            min: NEAREST_MIPMAP_LINEAR,
            mag: LINEAR,
            wrap_s: REPEAT,
            wrap_t: REPEAT,
            wrap_r: REPEAT,
            anisotropy: 1.0f32.to_bits(),
            max_level: 1000,
            base_level: 0,
            min_lod: (-1000.0f32).to_bits(),
            max_lod: 1000.0f32.to_bits(),
            compare_mode: 0,
            compare_func: LEQUAL,
        }
    }
}

impl SamplerState {
    /// Whether the minification filter reads mipmaps.
    pub fn uses_mipmaps(&self) -> bool {
        !matches!(self.min, NEAREST | LINEAR)
    }

    /// Whether `GL_MIRROR_CLAMP_TO_EDGE_EXT` wraps s, t and r: the sampler clamps to the edge
    /// and the shader mirrors the coordinate (`glsl::link`'s `strata_wrap`).
    pub fn mirror_clamp(&self) -> [bool; 3] {
        [self.wrap_s, self.wrap_t, self.wrap_r].map(|w| w == MIRROR_CLAMP_TO_EDGE_EXT)
    }

    /// Whether s, t or r wraps by `GL_CLAMP_TO_BORDER_EXT` (r counts only for 3D textures,
    /// `three_d`).
    pub fn clamps_to_border(&self, three_d: bool) -> bool {
        self.wrap_s == CLAMP_TO_BORDER_EXT
            || self.wrap_t == CLAMP_TO_BORDER_EXT
            || (three_d && self.wrap_r == CLAMP_TO_BORDER_EXT)
    }

    /// Whether either filter interpolates between texels or levels.
    pub fn filters_linearly(&self) -> bool {
        self.mag == LINEAR || !matches!(self.min, NEAREST | NEAREST_MIPMAP_NEAREST)
    }
}

/// A texture object.
#[derive(Default)]
pub struct Texture {
    /// `TEXTURE_2D` or `TEXTURE_CUBE_MAP` once bound, 0 before.
    pub target: u32,
    /// Sampling state.
    pub sampler: SamplerState,
    /// The GPU image, its views, base size, mip count and storage.
    pub gpu: Option<TextureImage>,
    /// Per face: bitmask of the levels that have been specified.
    pub defined: [u32; 6],
    /// Internal format of level 0 (`RGBA`, `LUMINANCE`, `BGRA_EXT`, a compressed format, …).
    pub format: u32,
    /// Unique id for caches; changes when the image is recreated.
    pub uid: u64,
    /// Whether level 0 was specified as `GL_HALF_FLOAT_OES` (half-float images of other
    /// types, 2_10_10_10, are not renderable).
    pub half_float: bool,
    /// `GL_TEXTURE_BORDER_COLOR_EXT` (`GL_EXT_texture_border_clamp`), as set: kept out of
    /// [`SamplerState`], which keys the device's samplers, since the shader applies it.
    pub border: [f32; 4],
    /// `GL_TEXTURE_IMMUTABLE_LEVELS`: the levels `glTexStorage*` made; 0 while the texture's
    /// images may still be respecified (`GL_TEXTURE_IMMUTABLE_FORMAT` false).
    pub immutable_levels: u32,
    /// The sized internal format `glTexStorage*` gave, which decides the data its images take;
    /// 0 for a texture whose images were specified one by one.
    pub sized: u32,
    /// `GL_TEXTURE_SWIZZLE_R`…`_A` (ES 3.0): kept out of [`SamplerState`] too, since the
    /// shader applies it.
    pub swizzle: Swizzle,
}

/// A texture's swizzle: the source of each of red, green, blue and alpha (`GL_RED`,
/// `GL_GREEN`, `GL_BLUE`, `GL_ALPHA`, `GL_ZERO` or `GL_ONE`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Swizzle(pub [u32; 4]);

impl Default for Swizzle {
    fn default() -> Self {
        Swizzle([RED_EXT, GREEN, BLUE, ALPHA])
    }
}

impl Swizzle {
    /// The sources as the shader's swizzle helper reads them (1 to 4 red to alpha, 5 zero, 6
    /// one), or all 0 where every channel is kept.
    pub fn selectors(self) -> [f32; 4] {
        if self == Swizzle::default() {
            return [0.0; 4];
        }
        self.0.map(|s| match s {
            RED_EXT => 1.0,
            GREEN => 2.0,
            BLUE => 3.0,
            ALPHA => 4.0,
            ZERO => 5.0,
            _ => 6.0,
        })
    }
}

impl Texture {
    /// Whether every level of every face is defined, consistently with level 0 (the mipmap
    /// completeness of GL ES 2.0 §3.7.10, whatever the filter).
    pub fn levels_complete(&self) -> bool {
        let Some(img) = &self.gpu else { return false };
        let faces = if self.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
        let all = ((1u64 << img.levels) - 1) as u32;
        self.defined[..faces].iter().all(|d| d & all == all)
    }

    /// The first and last level `s` reads (its base and max level; ES 3.0 §3.8.10 clamps an
    /// immutable texture's to the levels it has).
    pub fn level_range(&self, s: &SamplerState) -> (u32, u32) {
        match self.immutable_levels.checked_sub(1) {
            Some(last) => {
                let base = s.base_level.min(last);
                (base, s.max_level.max(base).min(last))
            }
            None => (s.base_level, s.max_level),
        }
    }

    /// Whether sampling with `s` (the texture's state, or a sampler object's over it) would
    /// read defined data (GL ES 2.0 §3.7.10, ES 3.0 §3.8.13 completeness): the base level, and
    /// with a mipmap filter every level from it to the max level or the chain's end; a float
    /// image the device cannot filter is incomplete with a linear filter
    /// (`OES_texture_float_linear` not offered), and an integer image always is.
    pub fn complete_with(&self, s: &SamplerState) -> bool {
        let Some(img) = &self.gpu else { return false };
        if img.storage == Storage::Float && !img.filterable && s.filters_linearly() {
            return false;
        }
        // ES 3.0 §3.8.13: an integer image with a linear filter.
        if img.storage.is_int() && s.filters_linearly() {
            return false;
        }
        let faces = if self.target == TEXTURE_CUBE_MAP { 6 } else { 1 };
        let (base, max) = self.level_range(s);
        let last = if s.uses_mipmaps() { max.min(img.levels.saturating_sub(1)) } else { base };
        if base >= img.levels || base > last {
            return false;
        }
        let need = ((1u64 << (last + 1)) - (1u64 << base)) as u32;
        self.defined[..faces].iter().all(|d| d & need == need)
    }
}

impl SamplerState {
    /// A sampler object's state (this) over a texture's (`texture`): everything from the
    /// object but the levels, which are the texture's.
    pub fn over(self, texture: &SamplerState) -> SamplerState {
        SamplerState { max_level: texture.max_level, base_level: texture.base_level, ..self }
    }
}

impl Texture {
    /// Gives the texture an image of `storage` of `width`×`height` with its full mip chain,
    /// unless it already has one of that size and storage; a new image
    /// has no level defined. Beyond the client's quota the texture is left without an image.
    pub fn ensure_image(
        &mut self,
        gpu: &Gpu,
        account: &Arc<Account>,
        uid: u64,
        width: u32,
        height: u32,
        storage: Storage,
    ) -> GlResult {
        self.ensure_volume(gpu, account, uid, (width, height, 1), storage)
    }

    /// [`Self::ensure_image`] of `depth` slices for a 3D texture (`GL_OES_texture_3D`).
    pub fn ensure_volume(
        &mut self,
        gpu: &Gpu,
        account: &Arc<Account>,
        uid: u64,
        (width, height, depth): (u32, u32, u32),
        storage: Storage,
    ) -> GlResult {
        let depth = if matches!(self.target, TEXTURE_3D_OES | TEXTURE_2D_ARRAY) { depth } else { 1 };
        // An image an EGLImage shares is left to it: respecifying the texture orphans it.
        if self.gpu.as_ref().is_some_and(|i| {
            (i.width, i.height, i.depth) == (width, height, depth.max(1)) && i.storage == storage && !i.shared()
        }) {
            return Ok(());
        }
        // The old image's memory is given back before the new one is reserved.
        self.gpu = None;
        self.defined = [0; 6];
        self.uid = uid;
        self.gpu = Some(TextureImage::new(gpu, account, self.target, (width, height, depth), storage)?);
        Ok(())
    }

    /// Turns a natively compressed image into an RGBA8 one holding the decoded levels, so that
    /// uncompressed data can be written to it; other images are left as they are.
    pub fn decompress(&mut self, gpu: &Gpu, flushed: &Flushed, account: &Arc<Account>, uid: u64) -> GlResult {
        let Some(old) = self.gpu.take_if(|i| matches!(i.storage, Storage::Native(_))) else { return Ok(()) };
        let Storage::Native(c) = old.storage else { return Ok(()) };
        let img = TextureImage::new(gpu, account, self.target, (old.width, old.height, old.depth), Storage::Rgba8)?;
        for (&(face, level), blocks) in &old.blocks {
            let (width, height) = img.level_size(level);
            let region = Region { face, level, x: 0, y: 0, width, height };
            img.write(gpu, flushed, region, &c.decode(blocks, width, height));
        }
        self.gpu = Some(img);
        self.uid = uid;
        Ok(())
    }
}

//! A texture's GPU image: allocation for each storage (colour, float, depth, depth-stencil,
//! native compressed blocks), writes of whole levels and sub-rectangles, and the switch of a
//! natively compressed image to RGBA8 when uncompressed data arrives for it.

use std::collections::HashMap;
use std::sync::Arc;

use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::Storage;
use strata_device::account::{Account, Reservation};
use strata_device::Gpu;

/// A texture's GPU image.
pub struct TextureImage {
    /// The texture.
    pub texture: wgpu::Texture,
    /// The view draws sample: all levels (and faces); the depth aspect of a depth-stencil image.
    pub view: wgpu::TextureView,
    /// Level-0 width.
    pub width: u32,
    /// Level-0 height.
    pub height: u32,
    /// Level-0 depth: the slices of a 3D image (`GL_OES_texture_3D`), the layers of a 2D
    /// array (ES 3.0), 1 for others.
    pub depth: u32,
    /// Whether this is a 2D array's image, whose layers do not shrink with the level.
    pub array: bool,
    /// Mip levels allocated.
    pub mips: u32,
    /// Levels of GL's full mip chain for this size (completeness is judged against these).
    pub levels: u32,
    /// How the texels are kept.
    pub storage: Storage,
    /// Whether the image can be sampled with linear filtering.
    pub filterable: bool,
    /// For natively compressed images: the blocks of every specified level, by (face, level),
    /// kept so that the image can be decoded to RGBA8 if uncompressed data is written to it.
    pub blocks: HashMap<(u32, u32), Vec<u8>>,
    /// Where GL's face 0, level 0 lies in `texture`: (0, 0) but for an EGLImage sibling, whose
    /// one level is a level (and face) of the texture the image was made from.
    pub base: Subresource,
    /// The GPU memory it holds against its client's quota, shared with the EGLImages made from
    /// it and their siblings (so that it is held while any of them lives).
    pub reserved: Arc<Reservation>,
}

/// One level of one array layer of a wgpu texture.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Subresource {
    /// Array layer (cube face).
    pub layer: u32,
    /// Mip level.
    pub level: u32,
}

impl Subresource {
    /// A view of just this level and layer, as a 2D image.
    pub fn view(self, texture: &wgpu::Texture, aspect: wgpu::TextureAspect) -> wgpu::TextureView {
        texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2),
            aspect,
            base_mip_level: self.level,
            mip_level_count: Some(1),
            base_array_layer: self.layer,
            array_layer_count: Some(1),
            ..Default::default()
        })
    }
}

/// A rectangle of one level of one face.
#[derive(Debug, Clone, Copy)]
pub struct Region {
    /// Cube face (array layer), 0 for 2D.
    pub face: u32,
    /// Mip level.
    pub level: u32,
    /// Left column.
    pub x: u32,
    /// Bottom row (memory row 0).
    pub y: u32,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
}

impl TextureImage {
    /// Allocates an image of `storage` for a texture of `target` (`depth` slices for a 3D
    /// one), reserving its memory first.
    pub(crate) fn new(
        gpu: &Gpu,
        account: &Arc<Account>,
        target: u32,
        size: (u32, u32, u32),
        storage: Storage,
    ) -> GlResult<Self> {
        Self::with_levels(gpu, account, target, size, storage, None)
    }

    /// [`Self::new`] with `levels` levels where given (immutable storage: exactly those levels
    /// are allocated, and they are the chain completeness is judged against), else GL's full
    /// chain.
    pub(crate) fn with_levels(
        gpu: &Gpu,
        account: &Arc<Account>,
        target: u32,
        (width, height, depth): (u32, u32, u32),
        storage: Storage,
        levels: Option<u32>,
    ) -> GlResult<Self> {
        let three_d = target == TEXTURE_3D_OES;
        let array = target == TEXTURE_2D_ARRAY;
        let depth = if three_d || array { depth.max(1) } else { 1 };
        let layers = if target == TEXTURE_CUBE_MAP { 6 } else { depth };
        // A 2D array's layers keep their number at every level.
        let full = 32 - width.max(height).max(if array { 1 } else { depth }).max(1).leading_zeros();
        let (levels, mips) = match levels {
            Some(n) => (n, n),
            None => (full, full),
        };
        let bytes = if three_d {
            crate::objects::image::volume_bytes(width, height, depth, mips, storage)
        } else {
            crate::objects::image::image_bytes(width, height, layers, mips, storage)
        };
        let reserved = account.reserve(bytes).map_err(|_| GlError::OutOfMemory)?;
        let mut usage = wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST;
        if storage.attachable() {
            usage |= wgpu::TextureUsages::RENDER_ATTACHMENT;
        }
        // Colour copies out, and depth and stencil reads (GL_NV_read_stencil copies that aspect).
        usage |= wgpu::TextureUsages::COPY_SRC;
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("gl texture"),
            size: wgpu::Extent3d { width: width.max(1), height: height.max(1), depth_or_array_layers: layers },
            mip_level_count: mips,
            sample_count: 1,
            dimension: if three_d { wgpu::TextureDimension::D3 } else { wgpu::TextureDimension::D2 },
            format: storage.wgpu(),
            usage,
            view_formats: &[],
        });
        let dim = match layers {
            _ if three_d => wgpu::TextureViewDimension::D3,
            _ if array => wgpu::TextureViewDimension::D2Array,
            6 => wgpu::TextureViewDimension::Cube,
            _ => wgpu::TextureViewDimension::D2,
        };
        let aspect = if storage.is_depth() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
        let view =
            texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), aspect, ..Default::default() });
        let filterable = match storage {
            Storage::Float => gpu.features.contains(wgpu::Features::FLOAT32_FILTERABLE),
            s => !s.is_depth() && !s.is_int(),
        };
        Ok(TextureImage {
            texture,
            view,
            width,
            height,
            depth,
            array,
            mips,
            levels,
            storage,
            filterable,
            blocks: HashMap::new(),
            base: Subresource::default(),
            reserved: Arc::new(reserved),
        })
    }

    /// An image whose one level is `sub` of `texture` (an EGLImage's), `width`×`height`, kept
    /// as `storage`; its memory stays held by `reserved`.
    pub fn sibling(
        texture: wgpu::Texture,
        sub: Subresource,
        (width, height): (u32, u32),
        storage: Storage,
        filterable: bool,
        reserved: Arc<Reservation>,
    ) -> Self {
        let view = sub.view(&texture, wgpu::TextureAspect::All);
        TextureImage {
            texture,
            view,
            width,
            height,
            depth: 1,
            array: false,
            mips: 1,
            levels: 32 - width.max(height).max(1).leading_zeros(),
            storage,
            filterable,
            blocks: HashMap::new(),
            base: sub,
            reserved,
        }
    }

    /// Where `level` of `face` lies in the wgpu texture.
    pub fn at(&self, face: u32, level: u32) -> Subresource {
        Subresource { layer: self.base.layer + face, level: self.base.level + level }
    }

    /// Whether an EGLImage or a sibling shares the image.
    pub fn shared(&self) -> bool {
        Arc::strong_count(&self.reserved) > 1
    }

    /// Width and height of `level`.
    pub fn level_size(&self, level: u32) -> (u32, u32) {
        ((self.width >> level).max(1), (self.height >> level).max(1))
    }

    /// The slices of `level` (1 but for a 3D image), or a 2D array's layers.
    pub fn level_depth(&self, level: u32) -> u32 {
        if self.array {
            self.depth
        } else {
            (self.depth >> level).max(1)
        }
    }

    /// The faces of a 2D image (1) or a cube map (6); 1 for an EGLImage's sibling and for a 3D
    /// image, whose slices are not layers.
    pub fn layers(&self) -> u32 {
        if self.three_d() || self.base != Subresource::default() {
            1
        } else {
            self.texture.depth_or_array_layers()
        }
    }

    /// Whether this is a 3D image (`GL_OES_texture_3D`).
    pub fn three_d(&self) -> bool {
        self.texture.dimension() == wgpu::TextureDimension::D3
    }

    /// The view draws sample from level `base` on (`GL_TEXTURE_BASE_LEVEL`): the whole
    /// image's view for 0, else one of the levels from `base`.
    pub fn view_from(&self, base: u32) -> wgpu::TextureView {
        if base == 0 || base >= self.mips {
            return self.view.clone();
        }
        let dimension = match self.layers() {
            _ if self.three_d() => wgpu::TextureViewDimension::D3,
            _ if self.array => wgpu::TextureViewDimension::D2Array,
            6 => wgpu::TextureViewDimension::Cube,
            _ => wgpu::TextureViewDimension::D2,
        };
        let aspect = if self.storage.is_depth() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
        self.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(dimension),
            aspect,
            base_mip_level: base,
            mip_level_count: Some(self.mips - base),
            ..Default::default()
        })
    }

    /// A view of its faces as a 2D array from level `base` on: how integer cube maps are
    /// fetched texel by texel (`glsl::int_samplers`).
    pub fn faces_view_from(&self, base: u32) -> wgpu::TextureView {
        self.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            base_mip_level: base.min(self.mips.saturating_sub(1)),
            mip_level_count: Some(self.mips - base.min(self.mips.saturating_sub(1))),
            ..Default::default()
        })
    }

    /// A view for rendering into `level` of `face` (a 2D image's or cube face's), or into
    /// slice `face` of a 3D image's level, with the slice the render pass must name.
    pub fn attach_view(&self, face: u32, level: u32) -> (wgpu::TextureView, Option<u32>) {
        let at = self.at(face, level);
        if !self.three_d() {
            return (at.view(&self.texture, wgpu::TextureAspect::All), None);
        }
        let view = self.texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D3),
            base_mip_level: at.level,
            mip_level_count: Some(1),
            ..Default::default()
        });
        (view, Some(at.layer))
    }

    /// Writes tightly packed texels of the image's storage (RGBA8, RGBA16F or RGBA32F) into
    /// `r`, or, for a natively compressed image, whole blocks covering `r` (rows of blocks).
    pub fn write(&self, gpu: &Gpu, _: &Flushed, r: Region, data: &[u8]) {
        if r.width == 0 || r.height == 0 {
            return;
        }
        let (width, height, bytes_per_row) = match self.storage {
            Storage::Native(c) => {
                // Copies of block formats cover whole blocks, clipped to the level's
                // block-rounded size.
                let ((bw, bh), (across, down)) = (c.block_size(), c.blocks(r.width, r.height));
                let (lw, lh) = self.level_size(r.level);
                let (level_w, level_h) = (lw.div_ceil(bw) * bw, lh.div_ceil(bh) * bh);
                ((across * bw).min(level_w - r.x), (down * bh).min(level_h - r.y), across * c.block_bytes() as u32)
            }
            s => (r.width, r.height, r.width * s.texel_bytes()),
        };
        gpu.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &self.texture,
                mip_level: self.at(r.face, r.level).level,
                origin: wgpu::Origin3d { x: r.x, y: r.y, z: self.at(r.face, r.level).layer },
                aspect: wgpu::TextureAspect::All,
            },
            data,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(bytes_per_row), rows_per_image: None },
            wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        );
    }

    /// Writes compressed blocks covering `r` (a block-aligned rectangle of one level) and
    /// records them, so the level can still be decoded later.
    pub fn write_blocks(&mut self, gpu: &Gpu, flushed: &Flushed, r: Region, data: &[u8]) {
        let Storage::Native(c) = self.storage else { return };
        if r.width == 0 || r.height == 0 {
            return;
        }
        let (lw, lh) = self.level_size(r.level);
        let (bb, (bw, bh)) = (c.block_bytes(), c.block_size());
        let level_row = c.blocks(lw, lh).0 as usize * bb;
        let full = self.blocks.entry((r.face, r.level)).or_insert_with(|| vec![0; c.image_size(lw, lh)]);
        let (across, down) = c.blocks(r.width, r.height);
        let row = across as usize * bb;
        for (i, src) in data.chunks_exact(row).take(down as usize).enumerate() {
            let at = ((r.y / bh) as usize + i) * level_row + (r.x / bw) as usize * bb;
            if let Some(dst) = full.get_mut(at..at + row) {
                dst.copy_from_slice(src);
            }
        }
        self.write(gpu, flushed, r, data);
    }
}

/// Bytes of a texture image of `width`×`height` with `layers` faces and `mips` levels.
pub fn image_bytes(width: u32, height: u32, layers: u32, mips: u32, storage: Storage) -> u64 {
    (0..mips)
        .map(|l| {
            let (w, h) = ((width >> l).max(1) as u64, (height >> l).max(1) as u64);
            match storage {
                // Native blocks are kept on the device and, for decoding later, in the daemon.
                Storage::Native(c) => 2 * c.image_size(w as u32, h as u32) as u64,
                s => w * h * u64::from(s.texel_bytes()),
            }
        })
        .sum::<u64>()
        * u64::from(layers)
}

/// The bytes a 3D image of `width`×`height`×`depth` with `mips` levels holds (each level
/// halves the depth too).
pub fn volume_bytes(width: u32, height: u32, depth: u32, mips: u32, storage: Storage) -> u64 {
    (0..mips).map(|l| image_bytes(width >> l, height >> l, (depth >> l).max(1), 1, storage)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    pub(crate) fn image_bytes_count_every_level_and_face() {
        assert_eq!(image_bytes(4, 4, 1, 1, Storage::Rgba8), 64);
        assert_eq!(image_bytes(4, 4, 1, 3, Storage::Rgba8), 64 + 16 + 4);
        assert_eq!(image_bytes(4, 4, 6, 1, Storage::Float), 6 * 16 * 16);
        assert_eq!(volume_bytes(4, 4, 2, 3, Storage::Rgba8), 4 * (32 + 4 + 1));
    }
}

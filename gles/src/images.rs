//! A texture's GPU image: allocation for each storage (colour, float, depth, depth-stencil,
//! native compressed blocks), writes of whole levels and sub-rectangles, and the switch of a
//! natively compressed image to RGBA8 when uncompressed data arrives for it.

use std::collections::HashMap;
use std::sync::Arc;

use super::dispatch::Flushed;
use super::enums::*;
use super::error::{GlError, GlResult};
use super::formats::Storage;
use super::textures::Texture;
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
    /// Level-0 depth: the slices of a 3D image (`GL_OES_texture_3D`), 1 for others.
    pub depth: u32,
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
    fn new(
        gpu: &Gpu,
        account: &Arc<Account>,
        target: u32,
        (width, height, depth): (u32, u32, u32),
        storage: Storage,
    ) -> GlResult<Self> {
        let three_d = target == TEXTURE_3D_OES;
        let depth = if three_d { depth.max(1) } else { 1 };
        let layers = if target == TEXTURE_CUBE_MAP { 6 } else { depth };
        let levels = 32 - width.max(height).max(depth).max(1).leading_zeros();
        let mips = if storage.is_depth() { 1 } else { levels };
        let bytes = if three_d {
            super::account::volume_bytes(width, height, depth, mips, storage)
        } else {
            super::account::image_bytes(width, height, layers, mips, storage)
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
            6 => wgpu::TextureViewDimension::Cube,
            _ => wgpu::TextureViewDimension::D2,
        };
        let aspect = if storage.is_depth() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
        let view =
            texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dim), aspect, ..Default::default() });
        let filterable = match storage {
            Storage::Float => gpu.features.contains(wgpu::Features::FLOAT32_FILTERABLE),
            s => !s.is_depth(),
        };
        Ok(TextureImage {
            texture,
            view,
            width,
            height,
            depth,
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

    /// The slices of `level` (1 but for a 3D image).
    pub fn level_depth(&self, level: u32) -> u32 {
        (self.depth >> level).max(1)
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

impl Texture {
    /// Gives the texture an image of `storage` of `width`×`height` with its full mip chain
    /// (one level for depth), unless it already has one of that size and storage; a new image
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
        let depth = if self.target == TEXTURE_3D_OES { depth } else { 1 };
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

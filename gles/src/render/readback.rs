//! Readback, depth uploads, and waiting for the GPU. Reads and waits first submit the open
//! pass; a depth upload runs in a `[Flush]` command, after it.

use crate::flushed::Flushed;
use crate::render::{Renderer, Target};

impl Renderer {
    /// Reads `[x, y, w, h]` of the target's colour image as tightly packed RGBA8 rows, bottom
    /// row first (GL order, which is also memory order here).
    pub fn read_rgba(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<u8>> {
        let format = target.color_format()?;
        if !matches!(format, wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb) {
            // Converted as GL converts a float (or a 10-bit value) to an 8-bit normalised one:
            // clamped, rounded.
            let floats = self.read_floats(target, rect)?;
            let to_u8 = |v: f32| (if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) } * 255.0).round() as u8;
            return Some(floats.into_iter().flat_map(|p| p.map(to_u8)).collect());
        }
        self.flush();
        let (tex, _) = target.color.as_ref()?;
        let at = target.color_at;
        self.gpu.read_texels(&self.lane, tex, (at.layer, at.level), rect, wgpu::TextureAspect::All, 4)
    }

    /// Reads `[x, y, w, h]` of a half-float colour image (`GL_EXT_color_buffer_half_float`)
    /// as four half floats per pixel, rows bottom first.
    pub fn read_half(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.read_stored(target, rect)
    }

    /// Reads `[x, y, w, h]` of the target's colour image as RGBA floats, rows bottom first:
    /// half-float, 32-bit float, packed float and 10-bit images as GL reads them as floats
    /// (channels the format lacks 0, a lacking alpha 1), 8-bit ones as their bytes / 255.
    pub fn read_floats(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<[f32; 4]>> {
        let format = target.color_format()?;
        let stored = self.read_stored(target, rect)?;
        let texel = format.block_copy_size(None)? as usize;
        let word = |b: &[u8]| u32::from_ne_bytes([b[0], b[1], b[2], b[3]]);
        let decode = |t: &[u8]| -> [f32; 4] {
            use wgpu::TextureFormat as F;
            match format {
                F::Rgba16Float => {
                    [0, 1, 2, 3].map(|i| half::f16::from_bits(u16::from_ne_bytes([t[2 * i], t[2 * i + 1]])).to_f32())
                }
                F::Rgba32Float => {
                    [0, 1, 2, 3].map(|i| f32::from_ne_bytes([t[4 * i], t[4 * i + 1], t[4 * i + 2], t[4 * i + 3]]))
                }
                F::Rg11b10Ufloat => {
                    let [r, g, b] = crate::packed_float::decode_11_11_10(word(t));
                    [r, g, b, 1.0]
                }
                F::Rgb10a2Unorm => {
                    let v = word(t);
                    let unorm =
                        |shift: u32, bits: u32| ((v >> shift) & ((1 << bits) - 1)) as f32 / ((1 << bits) - 1) as f32;
                    [unorm(0, 10), unorm(10, 10), unorm(20, 10), unorm(30, 2)]
                }
                _ => [0, 1, 2, 3].map(|i| f32::from(t[i]) / 255.0),
            }
        };
        Some(stored.chunks_exact(texel).map(|t| crate::render::targets::stored(target.absent, decode(t))).collect())
    }

    /// Reads `[x, y, w, h]` of the target's colour image as its texels are stored (integer
    /// images among them), rows bottom first.
    pub fn read_stored(&mut self, target: &Target, rect: [u32; 4]) -> Option<Vec<u8>> {
        self.flush();
        let (tex, _) = target.color.as_ref()?;
        let at = target.color_at;
        let bytes = tex.format().block_copy_size(None)?;
        self.gpu.read_texels(&self.lane, tex, (at.layer, at.level), rect, wgpu::TextureAspect::All, bytes)
    }

    /// Reads `[x, y, w, h]` of the target's depth (through the depth reader, as floats in
    /// [0, 1] as stored) and, with `stencil`, its stencil; rows bottom first. `None` without
    /// the image or the aspect.
    pub fn read_depth_stencil(
        &mut self,
        target: &Target,
        rect: [u32; 4],
        stencil: bool,
    ) -> Option<(Vec<f32>, Vec<u8>)> {
        self.flush();
        let (tex, layer, level) = target.depth_image.as_ref()?;
        let (layer, level) = (*layer, *level);
        let format = tex.format();
        let depths = if format.has_depth_aspect() {
            let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
            let size = (target.width, target.height);
            let out = self.gpu.texture_2d("depth read", wgpu::TextureFormat::R32Float, size, usage);
            let (bgl, pipeline) = strata_scene::depth::Depth::of(&self.gpu).reader();
            let aspect = wgpu::TextureAspect::DepthOnly;
            let src = tex.create_view(&wgpu::TextureViewDescriptor {
                aspect,
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: layer,
                array_layer_count: Some(1),
                base_mip_level: level,
                mip_level_count: Some(1),
                ..Default::default()
            });
            let group = self.gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("depth read"),
                layout: &bgl,
                entries: &[wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&src) }],
            });
            let dst = out.create_view(&Default::default());
            let mut enc = self.gpu.device.create_command_encoder(&Default::default());
            strata_device::fullscreen_pass(&mut enc, "depth read", &dst, &pipeline, &group);
            self.gpu.submit(&self.lane, vec![enc.finish()]);
            let bytes = self.gpu.read_texels(&self.lane, &out, (0, 0), rect, wgpu::TextureAspect::All, 4)?;
            bytes.chunks_exact(4).map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]])).collect()
        } else {
            Vec::new()
        };
        let stencils = match stencil && format.has_stencil_aspect() {
            true => {
                // wgpu copies depth-stencil aspects whole: the rectangle is cut out here.
                let (tw, th) = ((tex.width() >> level).max(1), (tex.height() >> level).max(1));
                let all = self.gpu.read_texels(
                    &self.lane,
                    tex,
                    (layer, level),
                    [0, 0, tw, th],
                    wgpu::TextureAspect::StencilOnly,
                    1,
                )?;
                let [x, y, w, h] = rect;
                (y..y + h).flat_map(|r| all[(r * tw + x) as usize..(r * tw + x + w) as usize].to_vec()).collect()
            }
            false => Vec::new(),
        };
        Some((depths, stencils))
    }

    /// Waits until the GPU has finished everything this client submitted.
    pub fn finish(&mut self) {
        self.flush();
        self.lane.wait_idle(&self.gpu.device);
    }

    /// A fence after everything recorded so far, which is submitted: its mark.
    pub fn fence(&mut self) -> u64 {
        self.flush();
        self.gpu.mark(&self.lane)
    }

    /// Writes depth values (normalised, rows bottom-up) and optionally stencil values into the
    /// rectangle `[x, y, w, h]` of the array layer (a cube face) and mip level `at` of a `size`
    /// (that level's) depth or depth-stencil texture.
    #[allow(clippy::too_many_arguments)]
    pub fn upload_depth(
        &mut self,
        _: &Flushed,
        tex: &wgpu::Texture,
        at: (u32, u32),
        size: (u32, u32),
        rect: [u32; 4],
        depths: &[f32],
        stencil: Option<&[u8]>,
    ) {
        strata_scene::depth::Depth::for_lane(&self.gpu, &self.lane).write_region(tex, at, size, rect, depths, stencil);
    }
}

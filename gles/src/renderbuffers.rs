//! Renderbuffer objects: names, bindings, storage of each renderable format (ES 2.0's and its
//! extensions', ES 3.0's sRGB, float depth and integer ones), and their parameters.

use crate::channels::{absent_channels, color_bits, is_half_renderbuffer};
use crate::context::Context;
use crate::enums::SAMPLES as GL_SAMPLES;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::formats::{Storage, COLOR_FORMAT, HALF_FORMAT};
use crate::limits::{MAX_TEXTURE, SAMPLES};
use crate::objects::framebuffer::Renderbuffer;
use crate::render::Target;
use crate::GlesExecutor;
use strata_device::account::Kind;
use strata_protocol::Slice;

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glGenRenderbuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        self.admit(ctx, Kind::Renderbuffer, ctx.objects.renderbuffers.fresh(names.iter()))?;
        ctx.objects.renderbuffers.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteRenderbuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.objects.renderbuffers.delete(names.iter()) {
            ctx.objects.forget_label(RENDERBUFFER, n);
            if ctx.bindings.renderbuffer == n {
                ctx.bindings.renderbuffer = 0;
            }
        }
        Ok(())
    }

    pub(super) fn glBindRenderbuffer(&mut self, ctx: &mut Context, target: u32, renderbuffer: u32) -> GlResult {
        if target != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        self.admit(ctx, Kind::Renderbuffer, ctx.objects.renderbuffers.fresh([renderbuffer]))?;
        ctx.objects.renderbuffers.bind(renderbuffer);
        ctx.bindings.renderbuffer = renderbuffer;
        Ok(())
    }

    pub(super) fn glIsRenderbuffer(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.renderbuffers.is(name)
    }

    pub(super) fn glRenderbufferStorage(
        &mut self,
        ctx: &mut Context,
        target: u32,
        internalformat: u32,
        width: i32,
        height: i32,
    ) -> GlResult {
        self.renderbuffer_storage(ctx, target, None, internalformat, width, height)
    }

    /// Storage for the bound renderbuffer, checked in the order of Mesa's `fbobject.c`: the
    /// target, the format, the size, then (for `glRenderbufferStorageMultisample`, `samples`
    /// `Some`) the sample count. Any count above 0 makes an image of [`SAMPLES`] samples.
    fn renderbuffer_storage(
        &mut self,
        ctx: &mut Context,
        target: u32,
        samples: Option<i32>,
        internalformat: u32,
        width: i32,
        height: i32,
    ) -> GlResult {
        if target != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        let format = self.renderbuffer_format(ctx.es3(), internalformat)?;
        if width < 0 || height < 0 || width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(GlError::InvalidValue);
        }
        let samples = match samples {
            Some(n) if n < 0 => return Err(GlError::InvalidValue),
            // ES 3.0 §4.4.2.1: integer formats are never multisampled, and no format has more
            // samples than `glGetInternalformativ` lists for it.
            Some(n)
                if n > 0 && (crate::integer::IntFormat::from_gl(internalformat).is_some() || n > SAMPLES as i32) =>
            {
                return Err(GlError::InvalidOperation)
            }
            Some(n) if n > 0 => {
                if !self.multisamples(format) {
                    tracing::warn!("glRenderbufferStorageMultisample: the device cannot multisample {format:?}");
                    return Err(GlError::InvalidOperation);
                }
                SAMPLES
            }
            _ => 1,
        };
        let uid = self.next_uid();
        let name = ctx.bindings.renderbuffer;
        let Some(rb) = ctx.objects.renderbuffers.get_mut(&name).filter(|_| name != 0) else {
            return Err(GlError::InvalidOperation);
        };
        // The old image's memory is given back before the new one's is reserved.
        *rb = Renderbuffer::default();
        let texel = match format {
            wgpu::TextureFormat::Stencil8 => 1,
            wgpu::TextureFormat::Depth16Unorm => 2,
            HALF_FORMAT | wgpu::TextureFormat::Depth32FloatStencil8 => 8,
            f => f.block_copy_size(None).map_or(4, u64::from),
        };
        let bytes = u64::from((width as u32).max(1)) * u64::from((height as u32).max(1)) * texel * u64::from(samples);
        let reserved = Some(self.reserve(bytes)?);
        let gpu = &self.gpu;
        let size = ((width as u32).max(1), (height as u32).max(1));
        // Sampled too: depth reads (GL_NV_read_depth) pass through the depth reader.
        // Written to as well: a texture made from it through an EGLImage takes uploads.
        let usage = match samples {
            1 => {
                wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST
                    | wgpu::TextureUsages::TEXTURE_BINDING
            }
            // A multisample image is only drawn to and resolved (`render::resolve`).
            _ => wgpu::TextureUsages::RENDER_ATTACHMENT,
        };
        let tex = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("renderbuffer"),
            size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: samples,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let view = tex.create_view(&Default::default());
        let absent = absent_channels(internalformat);
        let rgba = matches!(format, COLOR_FORMAT | HALF_FORMAT | wgpu::TextureFormat::Rgba32Float);
        if !absent.is_empty() && rgba && width > 0 && height > 0 {
            // Absent channels read as 0 (alpha 1); draws never change them (see `Target`).
            let (w, h) = (width as u32, height as u32);
            let color = (tex.clone(), view.clone());
            let t = Target::color_only((uid, 2), color, (w, h), absent);
            self.r.clear(&t, Some((t.stored([0.0; 4]), wgpu::ColorWrites::ALL, None)), None, None, None);
        }
        let rb = ctx.objects.renderbuffers.get_mut(&name).ok_or(GlError::InvalidOperation)?;
        *rb = Renderbuffer {
            format: internalformat,
            width: width as u32,
            height: height as u32,
            gpu: Some((tex, view)),
            uid,
            reserved: reserved.map(std::sync::Arc::new),
            at: Default::default(),
        };
        Ok(())
    }

    /// ES 3.0's multisample renderbuffers: a count of 0 is `glRenderbufferStorage`'s image; 1 to
    /// [`SAMPLES`] make an image of [`SAMPLES`] samples, which draws rasterize at each sample
    /// and `glBlitFramebuffer` resolves.
    pub(super) fn glRenderbufferStorageMultisample(
        &mut self,
        ctx: &mut Context,
        target: u32,
        samples: i32,
        internalformat: u32,
        width: i32,
        height: i32,
    ) -> GlResult {
        self.renderbuffer_storage(ctx, target, Some(samples), internalformat, width, height)
    }

    /// The image format a renderbuffer of `internalformat` is stored in; `GL_INVALID_ENUM` for a
    /// format that is not renderable (in an ES 3.0 context if `es3`).
    fn renderbuffer_format(&self, es3: bool, internalformat: u32) -> GlResult<wgpu::TextureFormat> {
        Ok(match internalformat {
            RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES | R8_EXT | RG8_EXT => COLOR_FORMAT,
            f if is_half_renderbuffer(f) => HALF_FORMAT,
            DEPTH_COMPONENT16 => wgpu::TextureFormat::Depth16Unorm,
            DEPTH_COMPONENT24_OES => wgpu::TextureFormat::Depth24Plus,
            DEPTH24_STENCIL8_OES => wgpu::TextureFormat::Depth24PlusStencil8,
            STENCIL_INDEX8 => wgpu::TextureFormat::Stencil8,
            // ES 3.0's renderable formats beyond ES 2.0's extensions.
            SRGB8_ALPHA8 if es3 => wgpu::TextureFormat::Rgba8UnormSrgb,
            DEPTH_COMPONENT32F if es3 => wgpu::TextureFormat::Depth32Float,
            DEPTH32F_STENCIL8 if es3 => {
                if !self.gpu.features.contains(wgpu::Features::DEPTH32FLOAT_STENCIL8) {
                    tracing::warn!("glRenderbufferStorage: the device has no 32-bit float depth with stencil");
                    return Err(GlError::InvalidEnum);
                }
                wgpu::TextureFormat::Depth32FloatStencil8
            }
            // GL_EXT_color_buffer_float (ES 3.0): 32-bit float red, red-green and RGBA kept as
            // RGBA32F, packed floats in the device's format where it renders to it (else as half
            // floats), and ES 3.0's RGB10_A2 at its own precision.
            R32F | RG32F | RGBA32F if es3 => wgpu::TextureFormat::Rgba32Float,
            crate::packed_float::R11F_G11F_B10F if es3 => Storage::Rg11b10.on(self.gpu.features).wgpu(),
            RGB10_A2_EXT if es3 => wgpu::TextureFormat::Rgb10a2Unorm,
            // ES 3.0's integer formats but the RGB ones.
            f if es3 && crate::integer::IntFormat::from_gl(f).is_some_and(|f| f.renderable()) => {
                crate::integer::IntFormat::from_gl(f).map_or(COLOR_FORMAT, |f| f.wgpu())
            }
            _ => return Err(GlError::InvalidEnum),
        })
    }

    /// `glGetInternalformativ` (ES 3.0): a renderable format's sample counts (`GL_SAMPLES`:
    /// [`SAMPLES`] if the device multisamples it) or their number (`GL_NUM_SAMPLE_COUNTS`);
    /// checked in the order of Mesa's `formatquery.c`. Integer formats have none.
    pub(super) fn glGetInternalformativ(
        &mut self,
        ctx: &mut Context,
        target: u32,
        internalformat: u32,
        pname: u32,
        buf_size: i32,
    ) -> Vec<i32> {
        let counts = || -> GlResult<Vec<i32>> {
            if target != RENDERBUFFER || !matches!(pname, GL_SAMPLES | NUM_SAMPLE_COUNTS) {
                return Err(GlError::InvalidEnum);
            }
            let format = self.renderbuffer_format(true, internalformat)?;
            if buf_size < 0 {
                return Err(GlError::InvalidValue);
            }
            let int = crate::integer::IntFormat::from_gl(internalformat).is_some();
            let counts = if !int && self.multisamples(format) { vec![SAMPLES as i32] } else { Vec::new() };
            Ok(if pname == NUM_SAMPLE_COUNTS { vec![counts.len() as i32] } else { counts })
        };
        counts().unwrap_or_else(|e| {
            ctx.record(e);
            Vec::new()
        })
    }

    /// Whether the device draws into `format` with [`SAMPLES`] samples and resolves it.
    pub(crate) fn multisamples(&self, format: wgpu::TextureFormat) -> bool {
        let features = self.gpu.device.features();
        let flags = match features.contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES) {
            true => self.gpu.adapter.get_texture_format_features(format).flags,
            false => format.guaranteed_format_features(features).flags,
        };
        let resolves =
            format.is_depth_stencil_format() || flags.contains(wgpu::TextureFormatFeatureFlags::MULTISAMPLE_RESOLVE);
        flags.sample_count_supported(SAMPLES) && resolves
    }

    pub(super) fn glGetRenderbufferParameteriv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> i32 {
        let rb = ctx.objects.renderbuffers.get(&ctx.bindings.renderbuffer);
        let v = match (target, pname, rb) {
            (RENDERBUFFER, RENDERBUFFER_WIDTH, Some(rb)) => Ok(rb.width as i32),
            (RENDERBUFFER, RENDERBUFFER_HEIGHT, Some(rb)) => Ok(rb.height as i32),
            (RENDERBUFFER, RENDERBUFFER_SAMPLES, Some(rb)) if ctx.es3() => Ok(rb.samples() as i32),
            (RENDERBUFFER, RENDERBUFFER_INTERNAL_FORMAT, Some(rb)) => {
                Ok(if rb.format == 0 { RGBA4 as i32 } else { rb.format as i32 })
            }
            (RENDERBUFFER, RENDERBUFFER_RED_SIZE..=RENDERBUFFER_STENCIL_SIZE, Some(rb)) => {
                Ok(renderbuffer_bits(rb.format)[(pname - RENDERBUFFER_RED_SIZE) as usize])
            }
            (RENDERBUFFER, _, None) => Err(GlError::InvalidOperation),
            _ => Err(GlError::InvalidEnum),
        };
        v.unwrap_or_else(|e| {
            ctx.record(e);
            0
        })
    }
}

/// Red, green, blue, alpha, depth and stencil bits a renderbuffer of `format` stores: colour is
/// stored as RGBA8 whatever the format (a format without alpha has none), depth and stencil as
/// their formats name (none before storage is given).
pub(super) fn renderbuffer_bits(format: u32) -> [i32; 6] {
    match format {
        RGBA4
        | RGB5_A1
        | RGBA8_OES
        | RGB565
        | RGB8_OES
        | R8_EXT
        | RG8_EXT
        | RGBA16F_EXT
        | RGB16F_EXT
        | RG16F_EXT
        | R16F_EXT
        | R32F
        | RG32F
        | RGBA32F
        | RGB10_A2_EXT
        | crate::packed_float::R11F_G11F_B10F => {
            let [r, g, b, a] = color_bits(format);
            [r, g, b, a, 0, 0]
        }
        DEPTH_COMPONENT16 => [0, 0, 0, 0, 16, 0],
        DEPTH_COMPONENT24_OES => [0, 0, 0, 0, 24, 0],
        DEPTH24_STENCIL8_OES => [0, 0, 0, 0, 24, 8],
        SRGB8_ALPHA8 => [8, 8, 8, 8, 0, 0],
        DEPTH_COMPONENT32F => [0, 0, 0, 0, 32, 0],
        DEPTH32F_STENCIL8 => [0, 0, 0, 0, 32, 8],
        STENCIL_INDEX8 => [0, 0, 0, 0, 0, 8],
        f => match crate::integer::IntFormat::from_gl(f) {
            Some(i) => {
                let [r, g, b, a] = i.color_bits();
                [r, g, b, a, 0, 0]
            }
            None => [0; 6],
        },
    }
}

//! Framebuffer and renderbuffer objects: names, bindings, storage, attachments, completeness,
//! and the render target the current framebuffer resolves to.

use strata_protocol::Slice;

use super::context::{Context, MAX_TEXTURE};
use super::conv::ImageTarget;
use super::enums::*;
use super::error::{GlError, GlResult};
use super::formats::{absent_channels, color_bits, Compressed, Storage};
use super::render::{Target, COLOR_FORMAT};
use super::teximage::MAX_LEVEL;
use super::GlesExecutor;
use crate::quota::Kind;

/// Where one attachment of a framebuffer object comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Attachment {
    /// Nothing attached.
    #[default]
    None,
    /// A texture level (cube maps: face 0..6).
    Texture {
        /// Texture name.
        name: u32,
        /// Mip level.
        level: u32,
        /// Cube face, 0 for 2D.
        face: u32,
    },
    /// A renderbuffer.
    Renderbuffer(u32),
}

/// A framebuffer object.
#[derive(Default, Clone)]
pub struct Framebuffer {
    /// `COLOR_ATTACHMENT0`.
    pub color: Attachment,
    /// `DEPTH_ATTACHMENT`.
    pub depth: Attachment,
    /// `STENCIL_ATTACHMENT`.
    pub stencil: Attachment,
    /// Reads select no colour buffer (`glReadBufferNV(GL_NONE)`, `GL_NV_read_buffer`).
    pub read_none: bool,
}

/// A renderbuffer.
#[derive(Default)]
pub struct Renderbuffer {
    /// Internal format enum, 0 until storage is allocated.
    pub format: u32,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// The GPU image.
    pub gpu: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// Unique id for caches.
    pub uid: u64,
    /// The image's memory, held against the client's quota.
    pub _reserved: Option<crate::quota::Reservation>,
}

/// A resolved depth/stencil attachment: view, format, renderbuffer uid, width, height.
type DepthAttachment = (wgpu::TextureView, wgpu::TextureFormat, u64, u32, u32);

/// Attaches `a` to `attachment` of the bound framebuffer object.
fn set_attachment(ctx: &mut Context, attachment: u32, a: Attachment) -> GlResult {
    let bound = ctx.bindings.framebuffer;
    let fb = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0).ok_or(GlError::InvalidOperation)?;
    match attachment {
        COLOR_ATTACHMENT0 => fb.color = a,
        DEPTH_ATTACHMENT => fb.depth = a,
        STENCIL_ATTACHMENT => fb.stencil = a,
        _ => return Err(GlError::InvalidEnum),
    }
    Ok(())
}

/// The render target of framebuffer object `ctx.bindings.framebuffer`, or why it is incomplete
/// (a `GL_FRAMEBUFFER_*` status).
fn resolve_object(ctx: &Context) -> Result<Target, u32> {
    let bound = ctx.bindings.framebuffer;
    let fb = ctx.objects.framebuffers.get(&bound).cloned().unwrap_or_default();
    let mut size: Option<(u32, u32)> = None;
    let mut same = |w: u32, h: u32| -> Result<(), u32> {
        match size {
            Some(s) if s != (w, h) => Err(FRAMEBUFFER_INCOMPLETE_DIMENSIONS),
            _ => {
                size = Some((w, h));
                Ok(())
            }
        }
    };
    let mut key = (bound as u64) << 32;
    let mut absent = wgpu::ColorWrites::empty();
    let color = match fb.color {
        Attachment::None => None,
        Attachment::Texture { name, level, face } => {
            let t = ctx.objects.textures.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            let img = t.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            // ES 2.0 renders only into 8-bit colour (no float colour buffers are offered), and
            // never into compressed images.
            if !img.storage.color_renderable() || Compressed::from_gl(t.format).is_some() {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            // A level above 0 is attachable only while the texture's levels are complete (as
            // Mesa decides with GL_OES_fbo_render_mipmap).
            if t.defined[face as usize] & (1 << level) == 0 || (level > 0 && !t.levels_complete()) {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            same((img.width >> level).max(1), (img.height >> level).max(1))?;
            absent = absent_channels(t.format);
            key ^= t.uid.wrapping_mul(31).wrapping_add(u64::from(level) * 7 + u64::from(face));
            let view = img.texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_mip_level: level,
                mip_level_count: Some(1),
                base_array_layer: face,
                array_layer_count: Some(1),
                ..Default::default()
            });
            Some((img.texture.clone(), view))
        }
        Attachment::Renderbuffer(name) => {
            let rb = ctx.objects.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            if !matches!(rb.format, RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES | R8_EXT | RG8_EXT) {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            same(rb.width, rb.height)?;
            absent = absent_channels(rb.format);
            key ^= rb.uid.wrapping_mul(31);
            Some((tex.clone(), view.clone()))
        }
    };
    let ds = |a: Attachment, ok: &[u32]| -> Result<Option<DepthAttachment>, u32> {
        match a {
            Attachment::None => Ok(None),
            Attachment::Texture { name, .. } => {
                let t = ctx.objects.textures.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                let img = t.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                // A depth texture is a depth attachment; a depth-stencil one is either.
                let fits = match img.storage {
                    Storage::Depth => ok.contains(&DEPTH_COMPONENT16),
                    Storage::DepthStencil => ok.contains(&DEPTH24_STENCIL8_OES),
                    _ => false,
                };
                if !fits {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
                let view = img.texture.create_view(&Default::default());
                Ok(Some((view, img.storage.wgpu(), t.uid, img.width, img.height)))
            }
            Attachment::Renderbuffer(name) => {
                let rb = ctx.objects.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
                if !ok.contains(&rb.format) {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
                Ok(Some((view.clone(), tex.format(), rb.uid, rb.width, rb.height)))
            }
        }
    };
    let depth = ds(fb.depth, &[DEPTH_COMPONENT16, DEPTH_COMPONENT24_OES, DEPTH24_STENCIL8_OES])?;
    let stencil = ds(fb.stencil, &[STENCIL_INDEX8, DEPTH24_STENCIL8_OES])?;
    let depth = match (depth, stencil) {
        (Some(d), Some(s)) if d.2 != s.2 => return Err(FRAMEBUFFER_UNSUPPORTED),
        (Some(d), _) | (None, Some(d)) => Some(d),
        (None, None) => None,
    };
    if let Some(d) = &depth {
        same(d.3, d.4)?;
        key ^= d.2.wrapping_mul(131);
    }
    let (width, height) = size.ok_or(FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT)?;
    Ok(Target { key: (key, 1), color, depth: depth.map(|d| (d.0, d.1)), width, height, absent })
}

#[allow(non_snake_case)]
impl GlesExecutor {
    /// What draws, clears and reads address: the current surface for framebuffer 0, else the
    /// bound framebuffer object; `Err` is the `GL_FRAMEBUFFER_*` status that makes it
    /// incomplete.
    pub(super) fn draw_target(&self, ctx: &Context) -> Result<Target, u32> {
        let (_, sid) = self.current.ok_or(FRAMEBUFFER_UNSUPPORTED)?;
        if ctx.bindings.framebuffer == 0 {
            if sid == 0 {
                // Current with no surface (EGL_KHR_surfaceless_context).
                return Err(FRAMEBUFFER_UNDEFINED_OES);
            }
            return self.surfaces.get(&sid).map(|s| s.target.clone()).ok_or(FRAMEBUFFER_UNSUPPORTED);
        }
        resolve_object(ctx)
    }

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
        if target != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        let format = match internalformat {
            RGBA4 | RGB5_A1 | RGB565 | RGBA8_OES | RGB8_OES | R8_EXT | RG8_EXT => COLOR_FORMAT,
            DEPTH_COMPONENT16 => wgpu::TextureFormat::Depth16Unorm,
            DEPTH_COMPONENT24_OES => wgpu::TextureFormat::Depth24Plus,
            DEPTH24_STENCIL8_OES => wgpu::TextureFormat::Depth24PlusStencil8,
            STENCIL_INDEX8 => wgpu::TextureFormat::Stencil8,
            _ => return Err(GlError::InvalidEnum),
        };
        if width < 0 || height < 0 || width as u32 > MAX_TEXTURE || height as u32 > MAX_TEXTURE {
            return Err(GlError::InvalidValue);
        }
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
            _ => 4,
        };
        let bytes = u64::from((width as u32).max(1)) * u64::from((height as u32).max(1)) * texel;
        let reserved = Some(self.reserve(bytes)?);
        let gpu = &self.gpu;
        let size = ((width as u32).max(1), (height as u32).max(1));
        let usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let tex = gpu.texture_2d("renderbuffer", format, size, usage);
        let view = tex.create_view(&Default::default());
        let absent = absent_channels(internalformat);
        if !absent.is_empty() && format == COLOR_FORMAT && width > 0 && height > 0 {
            // Absent channels read as 0 (alpha 1); draws never change them (see `Target`).
            let (w, h) = (width as u32, height as u32);
            let color = Some((tex.clone(), view.clone()));
            let t = Target { key: (uid, 2), color, depth: None, width: w, height: h, absent };
            self.r.clear(&t, Some((t.stored([0.0; 4]), wgpu::ColorWrites::ALL)), None, None, None);
        }
        let rb = ctx.objects.renderbuffers.get_mut(&name).ok_or(GlError::InvalidOperation)?;
        *rb = Renderbuffer {
            format: internalformat,
            width: width as u32,
            height: height as u32,
            gpu: Some((tex, view)),
            uid,
            _reserved: reserved,
        };
        Ok(())
    }

    pub(super) fn glGetRenderbufferParameteriv(&mut self, ctx: &mut Context, target: u32, pname: u32) -> i32 {
        let rb = ctx.objects.renderbuffers.get(&ctx.bindings.renderbuffer);
        let v = match (target, pname, rb) {
            (RENDERBUFFER, RENDERBUFFER_WIDTH, Some(rb)) => Ok(rb.width as i32),
            (RENDERBUFFER, RENDERBUFFER_HEIGHT, Some(rb)) => Ok(rb.height as i32),
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

    pub(super) fn glGenFramebuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        self.admit(ctx, Kind::Framebuffer, ctx.objects.framebuffers.fresh(names.iter()))?;
        ctx.objects.framebuffers.generate(names.iter());
        Ok(())
    }

    pub(super) fn glDeleteFramebuffers(&mut self, ctx: &mut Context, names: Slice<'_, u32>) -> GlResult {
        for n in ctx.objects.framebuffers.delete(names.iter()) {
            ctx.objects.forget_label(FRAMEBUFFER, n);
            if ctx.bindings.framebuffer == n {
                ctx.bindings.framebuffer = 0;
            }
        }
        Ok(())
    }

    pub(super) fn glBindFramebuffer(&mut self, ctx: &mut Context, target: u32, framebuffer: u32) -> GlResult {
        if target != FRAMEBUFFER {
            return Err(GlError::InvalidEnum);
        }
        self.admit(ctx, Kind::Framebuffer, ctx.objects.framebuffers.fresh([framebuffer]))?;
        ctx.objects.framebuffers.bind(framebuffer);
        ctx.bindings.framebuffer = framebuffer;
        Ok(())
    }

    pub(super) fn glIsFramebuffer(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.framebuffers.is(name)
    }

    pub(super) fn glFramebufferTexture2D(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        textarget: u32,
        texture: u32,
        level: i32,
    ) -> GlResult {
        if target != FRAMEBUFFER {
            return Err(GlError::InvalidEnum);
        }
        let face = ImageTarget::from_gl(textarget)?.face;
        // GL_OES_fbo_render_mipmap: any level a texture can have.
        if !(0..=MAX_LEVEL).contains(&level) && texture != 0 {
            return Err(GlError::InvalidValue);
        }
        if texture != 0 && !ctx.objects.textures.contains_key(&texture) {
            return Err(GlError::InvalidOperation);
        }
        let a = if texture == 0 {
            Attachment::None
        } else {
            Attachment::Texture { name: texture, level: level as u32, face }
        };
        set_attachment(ctx, attachment, a)
    }

    pub(super) fn glFramebufferRenderbuffer(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        renderbuffertarget: u32,
        renderbuffer: u32,
    ) -> GlResult {
        if target != FRAMEBUFFER || renderbuffertarget != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        if renderbuffer != 0 && !ctx.objects.renderbuffers.contains_key(&renderbuffer) {
            return Err(GlError::InvalidOperation);
        }
        let a = if renderbuffer == 0 { Attachment::None } else { Attachment::Renderbuffer(renderbuffer) };
        set_attachment(ctx, attachment, a)
    }

    pub(super) fn glGetFramebufferAttachmentParameteriv(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        pname: u32,
    ) -> i32 {
        let fb = ctx.objects.framebuffers.get(&ctx.bindings.framebuffer);
        let a = match (target, fb, attachment) {
            (FRAMEBUFFER, Some(fb), COLOR_ATTACHMENT0) => fb.color,
            (FRAMEBUFFER, Some(fb), DEPTH_ATTACHMENT) => fb.depth,
            (FRAMEBUFFER, Some(fb), STENCIL_ATTACHMENT) => fb.stencil,
            (FRAMEBUFFER, None, _) => {
                ctx.record(GlError::InvalidOperation);
                return 0;
            }
            _ => {
                ctx.record(GlError::InvalidEnum);
                return 0;
            }
        };
        match (pname, a) {
            (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::None) => NONE as i32,
            (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::Texture { .. }) => TEXTURE as i32,
            (FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, Attachment::Renderbuffer(_)) => RENDERBUFFER as i32,
            (FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, Attachment::Texture { name, .. }) => name as i32,
            (FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, Attachment::Renderbuffer(n)) => n as i32,
            (FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL, Attachment::Texture { level, .. }) => level as i32,
            (FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE, Attachment::Texture { face, .. }) => {
                if face == 0 {
                    0
                } else {
                    (TEXTURE_CUBE_MAP_POSITIVE_X + face) as i32
                }
            }
            _ => {
                ctx.record(GlError::InvalidEnum);
                0
            }
        }
    }

    pub(super) fn glCheckFramebufferStatus(&mut self, ctx: &mut Context, target: u32) -> u32 {
        if target != FRAMEBUFFER {
            ctx.record(GlError::InvalidEnum);
            return 0;
        }
        match self.draw_target(ctx) {
            Ok(_) => FRAMEBUFFER_COMPLETE,
            Err(status) => status,
        }
    }

    /// `EXT_discard_framebuffer`. Validated as the extension specifies; the contents are kept,
    /// which the extension allows (a discard only makes them undefined).
    pub(super) fn glDiscardFramebufferEXT(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachments: Slice<'_, u32>,
    ) -> GlResult {
        if target != FRAMEBUFFER {
            return Err(GlError::InvalidEnum);
        }
        let valid: [u32; 3] = if ctx.bindings.framebuffer == 0 {
            [COLOR_EXT, DEPTH_EXT, STENCIL_EXT]
        } else {
            [COLOR_ATTACHMENT0, DEPTH_ATTACHMENT, STENCIL_ATTACHMENT]
        };
        if attachments.iter().any(|a| !valid.contains(&a)) {
            return Err(GlError::InvalidEnum);
        }
        Ok(())
    }
}

/// Red, green, blue, alpha, depth and stencil bits a renderbuffer of `format` stores: colour is
/// stored as RGBA8 whatever the format (a format without alpha has none), depth and stencil as
/// their formats name (none before storage is given).
fn renderbuffer_bits(format: u32) -> [i32; 6] {
    match format {
        RGBA4 | RGB5_A1 | RGBA8_OES | RGB565 | RGB8_OES | R8_EXT | RG8_EXT => {
            let [r, g, b, a] = color_bits(format);
            [r, g, b, a, 0, 0]
        }
        DEPTH_COMPONENT16 => [0, 0, 0, 0, 16, 0],
        DEPTH_COMPONENT24_OES => [0, 0, 0, 0, 24, 0],
        DEPTH24_STENCIL8_OES => [0, 0, 0, 0, 24, 8],
        STENCIL_INDEX8 => [0, 0, 0, 0, 0, 8],
        _ => [0; 6],
    }
}

//! What draws, clears and reads address: the current surface for framebuffer 0, else the
//! images attached to the bound framebuffer object, checked for completeness. Draws address
//! the draw buffers (`GL_EXT_draw_buffers`: fragment output `i` writes the attachment draw
//! buffer `i` names); reads address the read buffer (`GL_NV_read_buffer`).

use std::hash::{Hash, Hasher};

use crate::channels::absent_channels;
use crate::context::Context;
use crate::enums::*;
use crate::formats::{Compressed, Storage};
use crate::objects::framebuffer::{Attachment, Purpose};
use crate::objects::image::Subresource;
use crate::render::Target;
use crate::GlesExecutor;

/// A resolved depth/stencil attachment: view, format, image uid, width, height, and the image
/// with its layer and level.
type DepthAttachment = (wgpu::TextureView, wgpu::TextureFormat, u64, u32, u32, (wgpu::Texture, u32, u32));

/// A resolved colour attachment.
#[derive(Clone)]
struct ColorImage {
    /// The texture.
    texture: wgpu::Texture,
    /// A view of the attached level (and face).
    view: wgpu::TextureView,
    /// The channels its format lacks.
    absent: wgpu::ColorWrites,
    /// What identifies the image: uid, level, face.
    id: (u64, u32, u32),
    /// The level and layer of `texture` the view shows (the slice, of a 3D image).
    at: Subresource,
    /// The slice of a 3D image the render pass names (`GL_OES_texture_3D`).
    slice: Option<u32>,
    /// Width and height.
    size: (u32, u32),
}

/// Colour attachment `a` of `ctx`'s objects, or why it makes the framebuffer incomplete.
fn color_attachment(ctx: &Context, a: Attachment) -> Result<Option<ColorImage>, u32> {
    Ok(Some(match a {
        Attachment::None => return Ok(None),
        Attachment::Texture { name, level, face } => {
            let t = ctx.objects.textures.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            let img = t.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            // 8-bit and half-float colour (`GL_EXT_color_buffer_half_float`); as on Mesa, a
            // float image is unsupported and a compressed one incomplete. ES 3.0 renders into
            // 32-bit float, packed float and 10-bit images too (`GL_EXT_color_buffer_float`).
            let es3 = ctx.es3();
            if img.storage == Storage::Float {
                if !es3 {
                    return Err(FRAMEBUFFER_UNSUPPORTED);
                }
                crate::formats::float_attachment(t.format, t.sized)?;
            } else {
                // R11F_G11F_B10F kept as half floats (a device that cannot render to its
                // packed format) renders as one.
                let half = t.half_float || (es3 && t.sized == crate::packed_float::R11F_G11F_B10F);
                if !img.storage.color_renderable(t.format, half, es3) || Compressed::from_gl(t.format).is_some() {
                    return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
                }
            }
            // A level above 0 is attachable only while the texture's levels are complete (as
            // Mesa decides with GL_OES_fbo_render_mipmap). A 3D image's `face` is the slice,
            // which must lie in the level.
            let defined = if img.three_d() || img.array { 0 } else { face };
            // A slice of a 3D texture whose name now holds another texture is no face of it.
            let Some(levels) = t.defined.get(defined as usize).filter(|_| img.three_d() || face < img.layers()) else {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            };
            if levels & (1 << level) == 0
                || (level > 0 && !t.levels_complete())
                || (img.three_d() && face >= img.level_depth(level))
            {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            let (view, slice) = img.attach_view(face, level);
            ColorImage {
                texture: img.texture.clone(),
                view,
                absent: absent_channels(t.format),
                id: (t.uid, level, face),
                at: img.at(face, level),
                slice,
                size: ((img.width >> level).max(1), (img.height >> level).max(1)),
            }
        }
        Attachment::Renderbuffer(name) => {
            let rb = ctx.objects.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            if !rb.is_color() {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            ColorImage {
                texture: tex.clone(),
                view: view.clone(),
                absent: absent_channels(rb.format),
                id: (rb.uid, 0, 0),
                at: rb.at,
                slice: None,
                size: (rb.width, rb.height),
            }
        }
    }))
}

/// Depth or stencil attachment `a`, which must be one of the formats `ok`.
fn depth_attachment(ctx: &Context, a: Attachment, ok: &[u32]) -> Result<Option<DepthAttachment>, u32> {
    match a {
        Attachment::None => Ok(None),
        Attachment::Texture { name, face, level } => {
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
            // The level of a cube face (OES_depth_texture_cube_map) or of a 2D array's layer
            // must be defined; a level above 0 only while the levels are complete.
            let defined = if img.array { 0 } else { face };
            let levels = t.defined.get(defined as usize).copied().unwrap_or(0);
            if face >= img.layers()
                || level >= img.mips
                || levels & (1 << level) == 0
                || (level > 0 && !t.levels_complete())
            {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            let view = img.texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2),
                base_array_layer: face,
                array_layer_count: Some(1),
                base_mip_level: level,
                mip_level_count: Some(1),
                ..Default::default()
            });
            let id = t.uid ^ u64::from(face) << 56 ^ u64::from(level) << 48;
            let (w, h) = img.level_size(level);
            Ok(Some((view, img.storage.wgpu(), id, w, h, (img.texture.clone(), face, level))))
        }
        Attachment::Renderbuffer(name) => {
            let rb = ctx.objects.renderbuffers.get(&name).ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            let (tex, view) = rb.gpu.as_ref().ok_or(FRAMEBUFFER_INCOMPLETE_ATTACHMENT)?;
            if !ok.contains(&rb.format) {
                return Err(FRAMEBUFFER_INCOMPLETE_ATTACHMENT);
            }
            Ok(Some((view.clone(), tex.format(), rb.uid, rb.width, rb.height, (tex.clone(), 0, 0))))
        }
    }
}

/// The render target of framebuffer object `bound` for `purpose`, or why it is incomplete (a
/// `GL_FRAMEBUFFER_*` status). Every attachment counts for completeness, whichever buffers are
/// selected.
fn resolve_object(ctx: &Context, bound: u32, purpose: Purpose) -> Result<Target, u32> {
    let fb = ctx.objects.framebuffers.get(&bound).cloned().unwrap_or_default();
    let mut size: Option<(u32, u32)> = None;
    let mut same = |(w, h): (u32, u32)| -> Result<(), u32> {
        match size {
            Some(s) if s != (w, h) => Err(FRAMEBUFFER_INCOMPLETE_DIMENSIONS),
            _ => {
                size = Some((w, h));
                Ok(())
            }
        }
    };
    let mut colors = Vec::with_capacity(fb.colors.len());
    for a in fb.colors {
        let c = color_attachment(ctx, a)?;
        if let Some(c) = &c {
            same(c.size)?;
        }
        colors.push(c);
    }
    let depths =
        [DEPTH_COMPONENT16, DEPTH_COMPONENT24_OES, DEPTH24_STENCIL8_OES, DEPTH_COMPONENT32F, DEPTH32F_STENCIL8];
    let depth = depth_attachment(ctx, fb.depth, &depths)?;
    let stencil = depth_attachment(ctx, fb.stencil, &[STENCIL_INDEX8, DEPTH24_STENCIL8_OES, DEPTH32F_STENCIL8])?;
    let depth = match (depth, stencil) {
        (Some(d), Some(s)) if d.2 != s.2 => return Err(FRAMEBUFFER_UNSUPPORTED),
        (Some(d), _) | (None, Some(d)) => Some(d),
        (None, None) => None,
    };
    if let Some(d) = &depth {
        same((d.3, d.4))?;
    }
    // ES 3.0 §4.4.4.2: every attachment has the same number of samples.
    let counts = colors.iter().flatten().map(|c| c.texture.sample_count());
    let mut counts = counts.chain(depth.iter().map(|d| d.5 .0.sample_count()));
    let samples = counts.next().unwrap_or(1);
    if counts.any(|n| n != samples) {
        return Err(FRAMEBUFFER_INCOMPLETE_MULTISAMPLE);
    }
    let (width, height) = size.ok_or(FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT)?;
    // Per slot (fragment output, or the one read slot), the attachment it addresses.
    let selected =
        |buffer: u32| buffer.checked_sub(COLOR_ATTACHMENT0).and_then(|i| colors.get(i as usize).cloned().flatten());
    let slots: Vec<Option<ColorImage>> = match purpose {
        Purpose::Draw => fb.draw_buffers.iter().map(|b| selected(*b)).collect(),
        Purpose::Read => vec![selected(fb.read)],
    };
    // Passes are batched by this key: the framebuffer, and each slot's image.
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (bound, purpose == Purpose::Draw).hash(&mut h);
    for s in &slots {
        s.as_ref().map(|c| c.id).hash(&mut h);
    }
    depth.as_ref().map(|d| d.2).hash(&mut h);
    let slices = slots.iter().map(|s| s.as_ref().and_then(|c| c.slice)).collect();
    let mut slots = slots.into_iter();
    let first = slots.next().flatten();
    let mut more: Vec<_> = slots.map(|s| s.map(|c| (c.view, c.absent, c.texture.format()))).collect();
    while more.last().is_some_and(|m| m.is_none()) {
        more.pop();
    }
    Ok(Target {
        key: (h.finish(), 1),
        absent: first.as_ref().map_or(wgpu::ColorWrites::empty(), |c| c.absent),
        color_at: first.as_ref().map_or_else(Subresource::default, |c| c.at),
        color: first.map(|c| (c.texture, c.view)),
        more,
        slices,
        srgb: false,
        depth_image: depth.as_ref().map(|d| d.5.clone()),
        depth: depth.map(|d| (d.0, d.1)),
        width,
        height,
        samples,
    })
}

impl GlesExecutor {
    /// What draws and clears address: the current surface for framebuffer 0 (without its
    /// colour image while its draw buffer is `GL_NONE`), else the bound framebuffer object's
    /// draw buffers; `Err` is the `GL_FRAMEBUFFER_*` status that makes it incomplete.
    pub(super) fn draw_target(&self, ctx: &Context) -> Result<Target, u32> {
        self.target(ctx, Purpose::Draw)
    }

    /// What reads and copies address: as [`Self::draw_target`] for the framebuffer bound for
    /// reading, with its read buffer as the colour image.
    pub(super) fn read_target(&self, ctx: &Context) -> Result<Target, u32> {
        self.target(ctx, Purpose::Read)
    }

    fn target(&self, ctx: &Context, purpose: Purpose) -> Result<Target, u32> {
        let (_, sid) = self.current.ok_or(FRAMEBUFFER_UNSUPPORTED)?;
        let bound = match purpose {
            Purpose::Draw => ctx.bindings.framebuffer,
            Purpose::Read => ctx.bindings.read_framebuffer,
        };
        if bound != 0 {
            return resolve_object(ctx, bound, purpose);
        }
        if sid == 0 {
            // Current with no surface (EGL_KHR_surfaceless_context).
            return Err(FRAMEBUFFER_UNDEFINED_OES);
        }
        let mut t = self.surfaces.get(&sid).map(|s| s.target.clone()).ok_or(FRAMEBUFFER_UNSUPPORTED)?;
        if purpose == Purpose::Draw && ctx.draw_none {
            t.color = None;
            t.key.1 = 4;
        }
        Ok(t)
    }
}

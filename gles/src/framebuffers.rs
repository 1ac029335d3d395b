//! Framebuffer objects: names, bindings, attachments, completeness, and the render target the
//! current framebuffer resolves to (renderbuffers are in `renderbuffers`).
//!
//! `GL_EXT_draw_buffers` / `GL_NV_draw_buffers`: `glDrawBuffersEXT` selects, per fragment
//! output, the colour buffer it writes. The default framebuffer has one output, `GL_BACK` or
//! `GL_NONE`; a framebuffer object's output `i` writes `GL_COLOR_ATTACHMENTi` or nothing.
//! Validated in Mesa's order, which was probed: the count, then each buffer in turn.
//!
//! `GL_NV_read_buffer`: `glReadBufferNV` selects the colour buffer that `glReadPixels` and the
//! texture copies read: `GL_BACK` or `GL_NONE` for the default framebuffer, and one of the
//! colour attachments (`GL_NV_fbo_color_attachments`) or `GL_NONE` for a framebuffer object,
//! each of which keeps its own. It applies to the framebuffer bound for reading. Reading with `GL_NONE` selected, or from an attachment with
//! no image, is `GL_INVALID_OPERATION`, as on Mesa.

use crate::attachment_info as info;
use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::formats::Storage;
use crate::limits::max_3d_size;
use crate::limits::MAX_DRAW_BUFFERS;
use crate::objects::framebuffer::{color_slot, Attachment};
use crate::teximage::{max_level, volume_target};
use crate::typed::ImageTarget;
use crate::GlesExecutor;
use strata_device::account::Kind;
use strata_protocol::Slice;

/// The framebuffer an attachment call or status query of `target` addresses: the draw
/// framebuffer for `GL_FRAMEBUFFER` (and ES 3.0's `GL_DRAW_FRAMEBUFFER`), the read framebuffer
/// for ES 3.0's `GL_READ_FRAMEBUFFER`; `GL_INVALID_ENUM` for another target.
pub(super) fn framebuffer_of(ctx: &Context, target: u32) -> GlResult<u32> {
    match target {
        FRAMEBUFFER => Ok(ctx.bindings.framebuffer),
        DRAW_FRAMEBUFFER if ctx.es3() => Ok(ctx.bindings.framebuffer),
        READ_FRAMEBUFFER if ctx.es3() => Ok(ctx.bindings.read_framebuffer),
        _ => Err(GlError::InvalidEnum),
    }
}

/// Attaches `a` to `attachment` of framebuffer object `bound`.
pub(super) fn set_attachment(ctx: &mut Context, bound: u32, attachment: u32, a: Attachment) -> GlResult {
    let es3 = ctx.es3();
    let fb = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0).ok_or(GlError::InvalidOperation)?;
    match attachment {
        DEPTH_ATTACHMENT => fb.depth = a,
        STENCIL_ATTACHMENT => fb.stencil = a,
        DEPTH_STENCIL_ATTACHMENT if es3 => {
            fb.depth = a;
            fb.stencil = a;
        }
        _ => fb.colors[color_slot(attachment, 16).ok_or(GlError::InvalidEnum)??] = a,
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
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
            if ctx.bindings.read_framebuffer == n {
                ctx.bindings.read_framebuffer = 0;
            }
        }
        Ok(())
    }

    pub(super) fn glBindFramebuffer(&mut self, ctx: &mut Context, target: u32, framebuffer: u32) -> GlResult {
        let (draw, read) = match target {
            FRAMEBUFFER => (true, true),
            DRAW_FRAMEBUFFER => (true, false),
            READ_FRAMEBUFFER => (false, true),
            _ => return Err(GlError::InvalidEnum),
        };
        self.admit(ctx, Kind::Framebuffer, ctx.objects.framebuffers.fresh([framebuffer]))?;
        ctx.objects.framebuffers.bind(framebuffer);
        if draw {
            ctx.bindings.framebuffer = framebuffer;
        }
        if read {
            ctx.bindings.read_framebuffer = framebuffer;
        }
        Ok(())
    }

    pub(super) fn glIsFramebuffer(&mut self, ctx: &mut Context, name: u32) -> bool {
        ctx.objects.framebuffers.is(name)
    }

    /// Attaches level `level` of `texture` (0: detaches) at `attachment` of the bound
    /// framebuffer: a 2D image or the cube face `textarget` names (`layer: None`), or slice
    /// `layer` of a 3D image. The checks are Mesa's for every shape, in its order: the texture,
    /// the target named (against the call's shape and the texture's), the slice, the level.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn framebuffer_texture(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        textarget: u32,
        texture: u32,
        level: i32,
        layer: Option<i32>,
    ) -> GlResult {
        let fb = framebuffer_of(ctx, target)?;
        if texture == 0 {
            return set_attachment(ctx, fb, attachment, Attachment::None);
        }
        let t = ctx.objects.textures.get(&texture).ok_or(GlError::InvalidOperation)?;
        // The target named: an unknown one is GL_INVALID_ENUM; one of the other call's shape,
        // or not the texture's (a face for a cube map), GL_INVALID_OPERATION.
        let image = match textarget {
            TEXTURE_3D_OES => volume_target(textarget)?,
            other => ImageTarget::from_gl(other)?,
        };
        let expected = match (image.three_d, image.cube) {
            (true, _) => TEXTURE_3D_OES,
            (_, true) => TEXTURE_CUBE_MAP,
            _ => TEXTURE_2D,
        };
        if image.three_d != layer.is_some() || t.target != expected {
            return Err(GlError::InvalidOperation);
        }
        let layer = layer.unwrap_or(0);
        // GL_OES_fbo_render_mipmap: any level a texture can have (an immutable one: the
        // levels it was given, as Mesa checks).
        if !(0..max_3d_size(&self.gpu) as i32).contains(&layer)
            || !(0..=max_level(&self.gpu, image)).contains(&level)
            || beyond_immutable(t, level)
        {
            return Err(GlError::InvalidValue);
        }
        let face = image.face + layer as u32;
        set_attachment(ctx, fb, attachment, Attachment::Texture { name: texture, level: level as u32, face })
    }

    /// ES 3.0's attachment of one layer of a 2D array or one slice of a 3D texture, the
    /// texture's own target deciding which.
    pub(super) fn glFramebufferTextureLayer(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        texture: u32,
        level: i32,
        layer: i32,
    ) -> GlResult {
        let fb = framebuffer_of(ctx, target)?;
        // Framebuffer 0 has no attachments to set, whatever the texture (Mesa's first check).
        if fb == 0 {
            return Err(GlError::InvalidOperation);
        }
        if texture == 0 {
            return set_attachment(ctx, fb, attachment, Attachment::None);
        }
        let t = ctx.objects.textures.get(&texture).ok_or(GlError::InvalidOperation)?;
        match t.target {
            TEXTURE_3D_OES => {
                self.framebuffer_texture(ctx, target, attachment, TEXTURE_3D_OES, texture, level, Some(layer))
            }
            TEXTURE_2D_ARRAY => {
                let layers = crate::limits::max_array_layers(&self.gpu) as i32;
                if !(0..layers).contains(&layer)
                    || !(0..=crate::limits::MAX_LEVEL).contains(&level)
                    || beyond_immutable(t, level)
                {
                    return Err(GlError::InvalidValue);
                }
                let a = Attachment::Texture { name: texture, level: level as u32, face: layer as u32 };
                set_attachment(ctx, fb, attachment, a)
            }
            _ => Err(GlError::InvalidOperation),
        }
    }

    pub(super) fn glFramebufferRenderbuffer(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        renderbuffertarget: u32,
        renderbuffer: u32,
    ) -> GlResult {
        let fb = framebuffer_of(ctx, target)?;
        if renderbuffertarget != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        if renderbuffer != 0 && !ctx.objects.renderbuffers.contains_key(&renderbuffer) {
            return Err(GlError::InvalidOperation);
        }
        let a = if renderbuffer == 0 { Attachment::None } else { Attachment::Renderbuffer(renderbuffer) };
        set_attachment(ctx, fb, attachment, a)
    }

    pub(super) fn glGetFramebufferAttachmentParameteriv(
        &mut self,
        ctx: &mut Context,
        target: u32,
        attachment: u32,
        pname: u32,
    ) -> i32 {
        let es3 = ctx.es3();
        let Ok(bound) = framebuffer_of(ctx, target) else {
            ctx.record(GlError::InvalidEnum);
            return 0;
        };
        let fb = ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0);
        let a = match (FRAMEBUFFER, fb, attachment) {
            (FRAMEBUFFER, Some(fb), _) if color_slot(attachment, 16).is_some() => match color_slot(attachment, 16) {
                Some(Ok(i)) => fb.colors[i],
                _ => {
                    ctx.record(GlError::InvalidOperation);
                    return 0;
                }
            },
            (FRAMEBUFFER, Some(fb), DEPTH_ATTACHMENT) => fb.depth,
            (FRAMEBUFFER, Some(fb), STENCIL_ATTACHMENT) => fb.stencil,
            // ES 3.0: one image at both, or the question has no answer.
            (FRAMEBUFFER, Some(fb), DEPTH_STENCIL_ATTACHMENT) if es3 && fb.depth == fb.stencil => fb.depth,
            (FRAMEBUFFER, Some(_), DEPTH_STENCIL_ATTACHMENT) if es3 => {
                ctx.record(GlError::InvalidOperation);
                return 0;
            }
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
            // The face of a cube map, the slice of a 3D texture (`GL_OES_texture_3D`); 0 for
            // other textures.
            (FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE, Attachment::Texture { name, face, .. }) => {
                match ctx.objects.textures.get(&name).map(|t| t.target) {
                    Some(TEXTURE_CUBE_MAP) => (TEXTURE_CUBE_MAP_POSITIVE_X + face) as i32,
                    _ => 0,
                }
            }
            // ES 3.0's GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LAYER: a 2D array's layer too.
            (FRAMEBUFFER_ATTACHMENT_TEXTURE_3D_ZOFFSET_OES, Attachment::Texture { name, face, .. }) => {
                match ctx.objects.textures.get(&name).map(|t| t.target) {
                    Some(TEXTURE_3D_OES | TEXTURE_2D_ARRAY) => face as i32,
                    _ => 0,
                }
            }
            // ES 3.0's GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING: sRGB for an sRGB texture.
            (FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, Attachment::Texture { name, .. }) if es3 => {
                let srgb = ctx.objects.textures.get(&name).and_then(|t| t.gpu.as_ref()).map(|i| i.storage);
                if srgb == Some(Storage::Srgb8) {
                    SRGB as i32
                } else {
                    LINEAR as i32
                }
            }
            (FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, Attachment::Renderbuffer(_)) if es3 => LINEAR as i32,
            // ES 3.0: the image's bits and the kind of its components; nothing to ask of no
            // image.
            (FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, Attachment::None) if es3 => 0,
            (
                FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL
                | FRAMEBUFFER_ATTACHMENT_TEXTURE_CUBE_MAP_FACE
                | FRAMEBUFFER_ATTACHMENT_TEXTURE_3D_ZOFFSET_OES
                | FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING
                | info::COMPONENT_TYPE..=info::STENCIL_SIZE,
                Attachment::None,
            ) if es3 => {
                ctx.record(GlError::InvalidOperation);
                0
            }
            (info::COMPONENT_TYPE, a) if es3 => {
                if attachment == DEPTH_STENCIL_ATTACHMENT {
                    // Two images' kinds have no one answer.
                    ctx.record(GlError::InvalidOperation);
                    return 0;
                }
                info::component_type(ctx, a, attachment == STENCIL_ATTACHMENT) as i32
            }
            (info::RED_SIZE..=info::STENCIL_SIZE, a) if es3 => {
                info::attachment_bits(ctx, a, crate::renderbuffers::renderbuffer_bits)
                    [(pname - info::RED_SIZE) as usize]
            }
            _ => {
                ctx.record(GlError::InvalidEnum);
                0
            }
        }
    }

    pub(super) fn glCheckFramebufferStatus(&mut self, ctx: &mut Context, target: u32) -> u32 {
        if framebuffer_of(ctx, target).is_err() {
            ctx.record(GlError::InvalidEnum);
            return 0;
        }
        let status = match target {
            READ_FRAMEBUFFER => self.read_target(ctx),
            _ => self.draw_target(ctx),
        };
        match status {
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

/// `GL_DRAW_BUFFERi_EXT`: what fragment output `i` writes.
pub(super) fn draw_buffer(ctx: &Context, i: usize) -> u32 {
    let bound = ctx.bindings.framebuffer;
    match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb.draw_buffers.get(i).copied().unwrap_or(NONE),
        None if i == 0 && !ctx.draw_none => BACK,
        None => NONE,
    }
}

/// Whether `buffer` is an enum a draw buffer can name at all (Mesa answers
/// `GL_INVALID_OPERATION` for these when they do not fit, `GL_INVALID_ENUM` for the rest).
fn known(buffer: u32) -> bool {
    buffer == BACK || (COLOR_ATTACHMENT0..COLOR_ATTACHMENT0 + 32).contains(&buffer)
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glDrawBuffersEXT(&mut self, ctx: &mut Context, buffers: strata_protocol::Slice<'_, u32>) -> GlResult {
        let bufs: Vec<u32> = buffers.iter().collect();
        if bufs.len() > MAX_DRAW_BUFFERS {
            return Err(GlError::InvalidValue);
        }
        let bound = ctx.bindings.framebuffer;
        let Some(fb) = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0) else {
            // The default framebuffer: exactly one buffer, the back buffer or none.
            ctx.draw_none = match bufs.as_slice() {
                [BACK] => false,
                [NONE] => true,
                _ => return Err(GlError::InvalidOperation),
            };
            return Ok(());
        };
        for (i, b) in bufs.iter().enumerate() {
            if *b == NONE || *b == COLOR_ATTACHMENT0 + i as u32 {
                continue;
            }
            return Err(if known(*b) { GlError::InvalidOperation } else { GlError::InvalidEnum });
        }
        fb.draw_buffers = [NONE; MAX_DRAW_BUFFERS];
        fb.draw_buffers[..bufs.len()].copy_from_slice(&bufs);
        Ok(())
    }
}

/// `GL_READ_BUFFER_NV`: the colour buffer reads use, or `GL_NONE`.
pub(super) fn read_buffer(ctx: &Context) -> u32 {
    let bound = ctx.bindings.read_framebuffer;
    match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb.read,
        None if ctx.read_none => NONE,
        None => BACK,
    }
}

/// `GL_INVALID_OPERATION` where reads have no colour buffer selected, or the selected
/// attachment has no image.
pub(super) fn read_selected(ctx: &Context) -> GlResult {
    let bound = ctx.bindings.read_framebuffer;
    let attached = match ctx.objects.framebuffers.get(&bound).filter(|_| bound != 0) {
        Some(fb) => fb
            .read
            .checked_sub(COLOR_ATTACHMENT0)
            .and_then(|i| fb.colors.get(i as usize))
            .is_some_and(|a| *a != Attachment::None),
        None => !ctx.read_none,
    };
    if !attached {
        return Err(GlError::InvalidOperation);
    }
    Ok(())
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn glReadBufferNV(&mut self, ctx: &mut Context, mode: u32) -> GlResult {
        let bound = ctx.bindings.read_framebuffer;
        let fb = ctx.objects.framebuffers.get_mut(&bound).filter(|_| bound != 0);
        match (mode, fb) {
            (NONE, Some(fb)) => fb.read = NONE,
            (NONE, None) => ctx.read_none = true,
            (BACK, None) => ctx.read_none = false,
            // The other framebuffer's buffers, and attachments past the ones Strata has.
            (BACK, Some(_)) => return Err(GlError::InvalidOperation),
            (_, fb) => match (color_slot(mode, 32).ok_or(GlError::InvalidEnum)??, fb) {
                (_, Some(fb)) => fb.read = mode,
                (_, None) => return Err(GlError::InvalidOperation),
            },
        }
        Ok(())
    }
}

/// Whether `level` lies past the levels immutable texture `t` was given.
fn beyond_immutable(t: &crate::objects::texture::Texture, level: i32) -> bool {
    t.immutable_levels > 0 && level >= t.immutable_levels as i32
}

//! EGLImages (`EGL_KHR_image_base`) of a client's textures and renderbuffers
//! (`EGL_KHR_gl_texture_2D_image`, `EGL_KHR_gl_texture_cubemap_image`,
//! `EGL_KHR_gl_renderbuffer_image`), and the textures and renderbuffers made from them
//! (`GL_OES_EGL_image`, `GL_OES_EGL_image_external`).
//!
//! An image is one level of one face of a colour image: the wgpu texture it lies in, which
//! level and layer, and the memory reservation, all shared. As on Mesa, an image of a cube
//! map's face is made and a renderbuffer takes it, but a texture does not
//! (`GL_INVALID_OPERATION`). A sibling made from it samples,
//! renders into and takes uploads on that level and layer (its one level 0), so that every
//! sibling and the source see each other's writes, in any of the client's contexts (which
//! share no objects otherwise). Respecifying a sibling's or the source's image gives it a new
//! one and leaves the others the old (orphaning, `ensure_image`); deleting the source leaves
//! the image whole.

use strata_protocol::wire::EglHandle;
use strata_protocol::{EglResult, Slice};

use crate::context::Context;
use crate::enums::*;
use crate::error::{GlError, GlResult};
use crate::flushed::Flushed;
use crate::formats::COLOR_FORMAT;
use crate::formats::{is_color_format, Storage};
use crate::limits::MAX_IMAGES;
use crate::objects::egl_image::EglImage;
use crate::objects::framebuffer::Renderbuffer;
use crate::objects::image::TextureImage;
use crate::GlesExecutor;

const EGL_GL_TEXTURE_2D_KHR: i32 = 0x30B1;
const EGL_GL_TEXTURE_CUBE_MAP_POSITIVE_X_KHR: i32 = 0x30B3;
const EGL_GL_TEXTURE_CUBE_MAP_NEGATIVE_Z_KHR: i32 = 0x30B8;
const EGL_GL_RENDERBUFFER_KHR: i32 = 0x30B9;
const EGL_GL_TEXTURE_LEVEL_KHR: i32 = 0x30BC;
const EGL_IMAGE_PRESERVED_KHR: i32 = 0x30D2;

/// The unsized format a texture made from a renderbuffer's image has: the sized renderbuffer
/// formats' base formats, as ES 2.0 textures have no sized formats.
fn texture_format(format: u32) -> u32 {
    match format {
        RGBA4 | RGB5_A1 | RGBA8_OES => RGBA,
        RGB565 | RGB8_OES => RGB,
        R8_EXT => RED_EXT,
        RG8_EXT => RG_EXT,
        f => f,
    }
}

/// The level asked for by `attribs` (pairs ending in `EGL_NONE`): `EGL_GL_TEXTURE_LEVEL_KHR`,
/// 0 without it; any attribute but it and `EGL_IMAGE_PRESERVED_KHR` is `EGL_BAD_PARAMETER`,
/// as Mesa answers.
fn parse_attribs(attribs: &[i32]) -> EglResult<u32> {
    let mut level = 0;
    for pair in attribs.chunks(2) {
        match *pair {
            [EGL_NONE, ..] | [] => break,
            [EGL_GL_TEXTURE_LEVEL_KHR, v] => level = u32::try_from(v).map_err(|_| EGL_BAD_PARAMETER)?,
            [EGL_IMAGE_PRESERVED_KHR, _] => {}
            _ => return Err(EGL_BAD_PARAMETER),
        }
    }
    Ok(level)
}

/// The image of `level` of `face` of texture `name` of `ctx`, which must be a defined colour
/// level (a texture of `cube` target), else `EGL_BAD_PARAMETER`.
fn texture_image(ctx: &Context, name: u32, cube: bool, face: u32, level: u32) -> EglResult<EglImage> {
    let t = ctx.objects.textures.get(&name).filter(|_| name != 0).ok_or(EGL_BAD_PARAMETER)?;
    if t.target != if cube { TEXTURE_CUBE_MAP } else { TEXTURE_2D } {
        return Err(EGL_BAD_PARAMETER);
    }
    let img = t.gpu.as_ref().ok_or(EGL_BAD_PARAMETER)?;
    if level >= 32 || t.defined[face as usize] & (1 << level) == 0 || level >= img.mips {
        return Err(EGL_BAD_PARAMETER);
    }
    // EGL_KHR_gl_texture_2D_image: an incomplete texture offers level 0 alone, and only while
    // no other level is specified.
    if !t.levels_complete() && (level != 0 || t.defined.iter().any(|d| d & !1 != 0)) {
        return Err(EGL_BAD_PARAMETER);
    }
    // Depth and block-compressed images are not offered as EGLImages.
    if !matches!(img.storage, Storage::Rgba8 | Storage::Half | Storage::Float) {
        return Err(EGL_BAD_PARAMETER);
    }
    Ok(EglImage {
        texture: img.texture.clone(),
        at: img.at(face, level),
        size: img.level_size(level),
        storage: img.storage,
        filterable: img.filterable,
        format: t.format,
        reserved: img.reserved.clone(),
        face: cube,
    })
}

/// The image of renderbuffer `name` of `ctx`: its storage must be colour; a renderbuffer
/// without storage is `EGL_BAD_ALLOC`, as Mesa answers, and name 0 or a multisample image
/// `EGL_BAD_PARAMETER`.
fn renderbuffer_image(ctx: &Context, name: u32) -> EglResult<EglImage> {
    if name == 0 {
        return Err(EGL_BAD_PARAMETER);
    }
    let rb = ctx.objects.renderbuffers.get(&name).ok_or(EGL_BAD_ALLOC)?;
    let ((texture, _), reserved) = rb.gpu.as_ref().zip(rb.reserved.as_ref()).ok_or(EGL_BAD_ALLOC)?;
    let single = rb.samples() == 0;
    if !rb.is_color() || !single || texture.format() != COLOR_FORMAT || rb.width == 0 || rb.height == 0 {
        return Err(EGL_BAD_PARAMETER);
    }
    Ok(EglImage {
        texture: texture.clone(),
        at: rb.at,
        size: (rb.width, rb.height),
        storage: Storage::Rgba8,
        filterable: true,
        format: rb.format,
        reserved: reserved.clone(),
        face: false,
    })
}

#[allow(non_snake_case)]
impl GlesExecutor {
    pub(super) fn eglCreateImageKHR(
        &mut self,
        display: EglHandle,
        context: EglHandle,
        target: i32,
        buffer: u32,
        attribs: Slice<'_, i32>,
    ) -> EglResult<EglHandle> {
        self.check_display(display)?;
        self.contexts.get(&context).ok_or(EGL_BAD_CONTEXT)?;
        // A context's textures and renderbuffers are its share group's.
        let ctx = self.contexts.get(&self.holder(context)).ok_or(EGL_BAD_CONTEXT)?;
        let level = parse_attribs(&attribs.to_vec())?;
        let image = match target {
            EGL_GL_TEXTURE_2D_KHR => texture_image(ctx, buffer, false, 0, level)?,
            EGL_GL_TEXTURE_CUBE_MAP_POSITIVE_X_KHR..=EGL_GL_TEXTURE_CUBE_MAP_NEGATIVE_Z_KHR => {
                let face = (target - EGL_GL_TEXTURE_CUBE_MAP_POSITIVE_X_KHR) as u32;
                texture_image(ctx, buffer, true, face, level)?
            }
            EGL_GL_RENDERBUFFER_KHR if level == 0 => renderbuffer_image(ctx, buffer)?,
            _ => return Err(EGL_BAD_PARAMETER),
        };
        // The memory is the source's, already held; the handles are bounded.
        if self.images.len() >= MAX_IMAGES {
            return Err(EGL_BAD_ALLOC);
        }
        let id = self.next_handle;
        self.next_handle += 1;
        self.images.insert(id, image);
        Ok(id)
    }

    pub(super) fn eglDestroyImageKHR(&mut self, display: EglHandle, image: EglHandle) -> EglResult<()> {
        self.check_display(display)?;
        self.images.remove(&image).map(|_| ()).ok_or(EGL_BAD_PARAMETER)
    }

    pub(super) fn glEGLImageTargetTexture2DOES(
        &mut self,
        ctx: &mut Context,
        _: &Flushed,
        target: u32,
        image: EglHandle,
    ) -> GlResult {
        let slot = match target {
            TEXTURE_2D => crate::typed::TextureTarget::TwoD,
            TEXTURE_EXTERNAL_OES => crate::typed::TextureTarget::External,
            _ => return Err(GlError::InvalidEnum),
        };
        let img = self.images.get(&image).ok_or(GlError::InvalidValue)?;
        let name = ctx.bindings.texture(slot);
        let t = ctx.objects.textures.get_mut(&name).filter(|_| name != 0).ok_or(GlError::InvalidOperation)?;
        if img.face {
            return Err(GlError::InvalidOperation);
        }
        let sibling = TextureImage::sibling(
            img.texture.clone(),
            img.at,
            img.size,
            img.storage,
            img.filterable,
            img.reserved.clone(),
        );
        let format = texture_format(img.format);
        t.gpu = Some(sibling);
        t.defined = [1, 0, 0, 0, 0, 0];
        t.format = format;
        t.uid = self.next_uid();
        Ok(())
    }

    pub(super) fn glEGLImageTargetRenderbufferStorageOES(
        &mut self,
        ctx: &mut Context,
        _: &Flushed,
        target: u32,
        image: EglHandle,
    ) -> GlResult {
        if target != RENDERBUFFER {
            return Err(GlError::InvalidEnum);
        }
        let name = ctx.bindings.renderbuffer;
        if name == 0 || ctx.objects.renderbuffers.get(&name).is_none() {
            return Err(GlError::InvalidOperation);
        }
        let uid = self.next_uid();
        let img = self.images.get(&image).ok_or(GlError::InvalidValue)?;
        // Only 8-bit colour images are renderable (ES 2.0 has no float colour buffers).
        if img.storage != Storage::Rgba8 || !is_color_format(texture_format(img.format)) {
            return Err(GlError::InvalidOperation);
        }
        let view = img.at.view(&img.texture, wgpu::TextureAspect::All);
        let rb = Renderbuffer {
            format: img.format,
            width: img.size.0,
            height: img.size.1,
            gpu: Some((img.texture.clone(), view)),
            uid,
            reserved: Some(img.reserved.clone()),
            at: img.at,
        };
        if let Some(slot) = ctx.objects.renderbuffers.get_mut(&name) {
            *slot = rb;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attributes_are_the_level_and_preserved() {
        assert_eq!(parse_attribs(&[EGL_NONE]), Ok(0));
        assert_eq!(parse_attribs(&[EGL_GL_TEXTURE_LEVEL_KHR, 3, EGL_IMAGE_PRESERVED_KHR, 1, EGL_NONE]), Ok(3));
        assert_eq!(parse_attribs(&[EGL_GL_TEXTURE_LEVEL_KHR, -1, EGL_NONE]), Err(EGL_BAD_PARAMETER));
        assert_eq!(parse_attribs(&[0x1234, 1, EGL_NONE]), Err(EGL_BAD_PARAMETER));
        assert_eq!(texture_format(RGB565), RGB);
        assert_eq!(texture_format(RGBA), RGBA);
    }
}

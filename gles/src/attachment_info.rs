//! What ES 3.0's framebuffer attachment queries answer beyond ES 2.0's
//! (`glGetFramebufferAttachmentParameteriv`): an attached image's red, green, blue, alpha,
//! depth and stencil bits (`GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE` …) and the kind of its
//! components (`GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE`), from its format as Strata keeps it.

use crate::channels::texture_color_bits;
use crate::context::Context;
use crate::enums::*;
use crate::formats::Storage;
use crate::objects::framebuffer::Attachment;

/// `GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE`.
pub const COMPONENT_TYPE: u32 = 0x8211;
/// `GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE`; green, blue, alpha, depth and stencil follow it.
pub const RED_SIZE: u32 = 0x8212;
/// `GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE`.
pub const STENCIL_SIZE: u32 = 0x8217;
/// `GL_UNSIGNED_NORMALIZED`.
const UNSIGNED_NORMALIZED: u32 = 0x8C17;
/// `GL_SIGNED_NORMALIZED`.
const SIGNED_NORMALIZED: u32 = 0x8F9C;

/// The format an attached texture was made in: its sized format where it has one.
fn texture_format(ctx: &Context, name: u32) -> Option<(u32, Storage)> {
    let t = ctx.objects.textures.get(&name)?;
    let storage = t.gpu.as_ref()?.storage;
    Some((if t.sized != 0 { t.sized } else { t.format }, storage))
}

/// Red, green, blue, alpha, depth and stencil bits of attachment `a` (`renderbuffer_bits`
/// answers for renderbuffers).
pub fn attachment_bits(ctx: &Context, a: Attachment, renderbuffer_bits: fn(u32) -> [i32; 6]) -> [i32; 6] {
    match a {
        Attachment::None => [0; 6],
        Attachment::Renderbuffer(n) => {
            ctx.objects.renderbuffers.get(&n).map_or([0; 6], |rb| renderbuffer_bits(rb.format))
        }
        Attachment::Texture { name, .. } => {
            let Some((format, storage)) = texture_format(ctx, name) else { return [0; 6] };
            let depth = match format {
                DEPTH_COMPONENT16 => 16,
                DEPTH_COMPONENT32F | DEPTH32F_STENCIL8 => 32,
                _ => 24,
            };
            match storage {
                Storage::Depth => [0, 0, 0, 0, depth, 0],
                Storage::DepthStencil => [0, 0, 0, 0, depth, 8],
                s => {
                    let base = ctx.objects.textures.get(&name).map_or(format, |t| t.format);
                    let [r, g, b, al] = texture_color_bits(base, Some(s));
                    [r, g, b, al, 0, 0]
                }
            }
        }
    }
}

/// The kind of attachment `a`'s components as `GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE`
/// names it; `stencil`: the stencil attachment is asked about.
pub fn component_type(ctx: &Context, a: Attachment, stencil: bool) -> u32 {
    if stencil {
        return UNSIGNED_INT;
    }
    let (format, storage) = match a {
        Attachment::None => return NONE,
        Attachment::Renderbuffer(n) => (ctx.objects.renderbuffers.get(&n).map_or(0, |rb| rb.format), None),
        Attachment::Texture { name, .. } => match texture_format(ctx, name) {
            Some((f, s)) => (f, Some(s)),
            None => return NONE,
        },
    };
    if let Some(i) = crate::integer::IntFormat::from_gl(format) {
        return if i.signed { INT } else { UNSIGNED_INT };
    }
    match (format, storage) {
        (DEPTH_COMPONENT32F | DEPTH32F_STENCIL8, _) => FLOAT,
        (R8_SNORM | RG8_SNORM | RGB8_SNORM | RGBA8_SNORM, _) => SIGNED_NORMALIZED,
        (_, Some(Storage::Half | Storage::Float | Storage::Rg11b10)) => FLOAT,
        (f, None) if crate::channels::is_half_renderbuffer(f) || crate::channels::is_float_renderbuffer(f) => FLOAT,
        _ => UNSIGNED_NORMALIZED,
    }
}

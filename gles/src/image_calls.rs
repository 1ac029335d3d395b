//! The texture image calls of every shape, in one table: each entry point names its image's
//! shape (a 2D image or cube face from its target, or a 3D image) and its box (the first texel
//! and layer, the size and layers), and hands the rest to the one path the shapes share:
//! specification and sub-images (`teximage`), compressed uploads (`compressed`), copies from
//! the framebuffer (`copyimage`) and attachments (`framebuffers`). A 2D image is one layer
//! deep; a 3D image's slices are its layers. The next shape (a 2D array's layers) adds rows.

use strata_protocol::Blob;

use crate::context::Context;
use crate::error::GlResult;
use crate::flushed::Flushed;
use crate::teximage::layered_target;
use crate::typed::ImageTarget;
use crate::GlesExecutor;

/// Defines the entry points of the table: each takes the call's arguments after the context
/// (and, where the call writes an image, the flush proof) and evaluates its path.
macro_rules! image_calls {
    ($( fn $name:ident ( $s:ident $(, $arg:ident : $ty:ty)* ) => $path:expr ; )*) => {
        #[allow(non_snake_case)]
        impl GlesExecutor {
            $(
                #[allow(clippy::too_many_arguments)]
                pub(super) fn $name(&mut $s $(, $arg: $ty)*) -> GlResult {
                    $path
                }
            )*
        }
    };
}

image_calls! {
    fn glTexImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, internal: i32, w: i32, h: i32,
        border: i32, format: u32, ty: u32, pixels: Option<Blob<'_>>)
        => self.tex_image(ctx, f, ImageTarget::from_gl(target)?, level, internal as u32, [w, h, 1], border, format, ty, pixels);
    fn glTexImage3DOES(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, internal: u32, w: i32, h: i32,
        d: i32, border: i32, format: u32, ty: u32, pixels: Option<Blob<'_>>)
        => self.tex_image(ctx, f, layered_target(target, ctx.es3())?, level, internal, [w, h, d], border, format, ty, pixels);
    fn glTexSubImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, x: i32, y: i32, w: i32, h: i32,
        format: u32, ty: u32, pixels: Blob<'_>)
        => self.tex_sub_image(ctx, f, ImageTarget::from_gl(target)?, level, [x, y, 0], [w, h, 1], format, ty, pixels);
    fn glTexSubImage3DOES(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, x: i32, y: i32, z: i32,
        w: i32, h: i32, d: i32, format: u32, ty: u32, pixels: Blob<'_>)
        => self.tex_sub_image(ctx, f, layered_target(target, ctx.es3())?, level, [x, y, z], [w, h, d], format, ty, pixels);
    fn glCompressedTexImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, internal: u32, w: i32,
        h: i32, border: i32, data: Blob<'_>)
        => self.compressed_tex_image(ctx, f, ImageTarget::from_gl(target)?, level, internal, [w, h, 1], border, data);
    fn glCompressedTexImage3DOES(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, internal: u32, w: i32,
        h: i32, d: i32, border: i32, data: Blob<'_>)
        => self.compressed_tex_image(ctx, f, layered_target(target, ctx.es3())?, level, internal, [w, h, d], border, data);
    fn glCompressedTexSubImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, x: i32, y: i32, w: i32,
        h: i32, format: u32, data: Blob<'_>)
        => self.compressed_tex_sub_image(ctx, f, ImageTarget::from_gl(target)?, level, [x, y, 0], [w, h, 1], format, data);
    fn glCompressedTexSubImage3DOES(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, x: i32, y: i32,
        z: i32, w: i32, h: i32, d: i32, format: u32, data: Blob<'_>)
        => self.compressed_tex_sub_image(ctx, f, layered_target(target, ctx.es3())?, level, [x, y, z], [w, h, d], format, data);
    // A copy's target is checked after the read framebuffer, as on Mesa.
    fn glCopyTexImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, internal: u32, x: i32, y: i32,
        w: i32, h: i32, border: i32)
        => self.copy_tex(ctx, f, ImageTarget::from_gl(target), level, Some(internal), [0, 0, 0], x, y, w, h, border);
    fn glCopyTexSubImage2D(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, xo: i32, yo: i32, x: i32,
        y: i32, w: i32, h: i32)
        => self.copy_tex(ctx, f, ImageTarget::from_gl(target), level, None, [xo, yo, 0], x, y, w, h, 0);
    fn glCopyTexSubImage3DOES(self, ctx: &mut Context, f: &Flushed, target: u32, level: i32, xo: i32, yo: i32,
        zo: i32, x: i32, y: i32, w: i32, h: i32)
        => self.copy_tex(ctx, f, layered_target(target, ctx.es3()), level, None, [xo, yo, zo], x, y, w, h, 0);
    fn glFramebufferTexture2D(self, ctx: &mut Context, target: u32, attachment: u32, textarget: u32, texture: u32,
        level: i32)
        => self.framebuffer_texture(ctx, target, attachment, textarget, texture, level, None);
    fn glFramebufferTexture3DOES(self, ctx: &mut Context, target: u32, attachment: u32, textarget: u32, texture: u32,
        level: i32, z: i32)
        => self.framebuffer_texture(ctx, target, attachment, textarget, texture, level, Some(z));
}

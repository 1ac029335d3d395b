//! `GL_OES_texture_3D` forwarded to Mesa, through its extension entry points.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::{opt_ptr, Arms, Ptr};

impl Arms<'_> {
    pub(super) fn glTexImage3DOES(
        &mut self,
        target: &GLenum,
        level: &GLint,
        internalformat: &GLenum,
        width: &GLsizei,
        height: &GLsizei,
        depth: &GLsizei,
        border: &GLint,
        format: &GLenum,
        pixel_type: &GLenum,
        pixels: &Option<Blob<'_>>,
    ) -> Result<(), ClientError> {
        let p = opt_ptr(pixels);
        ext!(
            self,
            "glTexImage3DOES",
            fn(u32, i32, u32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
            *target,
            *level,
            *internalformat,
            *width,
            *height,
            *depth,
            *border,
            *format,
            *pixel_type,
            p
        );
        Ok(())
    }

    pub(super) fn glTexSubImage3DOES(
        &mut self,
        target: &GLenum,
        level: &GLint,
        xoffset: &GLint,
        yoffset: &GLint,
        zoffset: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        depth: &GLsizei,
        format: &GLenum,
        pixel_type: &GLenum,
        pixels: &Blob<'_>,
    ) -> Result<(), ClientError> {
        ext!(
            self,
            "glTexSubImage3DOES",
            fn(u32, i32, i32, i32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
            *target,
            *level,
            *xoffset,
            *yoffset,
            *zoffset,
            *width,
            *height,
            *depth,
            *format,
            *pixel_type,
            pixels.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glCompressedTexImage3DOES(
        &mut self,
        target: &GLenum,
        level: &GLint,
        internalformat: &GLenum,
        width: &GLsizei,
        height: &GLsizei,
        depth: &GLsizei,
        border: &GLint,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        ext!(
            self,
            "glCompressedTexImage3DOES",
            fn(u32, i32, u32, i32, i32, i32, i32, i32, *const u8) -> (),
            *target,
            *level,
            *internalformat,
            *width,
            *height,
            *depth,
            *border,
            data.len() as i32,
            data.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glCompressedTexSubImage3DOES(
        &mut self,
        target: &GLenum,
        level: &GLint,
        xoffset: &GLint,
        yoffset: &GLint,
        zoffset: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        depth: &GLsizei,
        format: &GLenum,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        ext!(
            self,
            "glCompressedTexSubImage3DOES",
            fn(u32, i32, i32, i32, i32, i32, i32, i32, u32, i32, *const u8) -> (),
            *target,
            *level,
            *xoffset,
            *yoffset,
            *zoffset,
            *width,
            *height,
            *depth,
            *format,
            data.len() as i32,
            data.as_bytes().as_ptr()
        );
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glCopyTexSubImage3DOES(
        &mut self,
        target: &GLenum,
        level: &GLint,
        xoffset: &GLint,
        yoffset: &GLint,
        zoffset: &GLint,
        x: &GLint,
        y: &GLint,
        width: &GLsizei,
        height: &GLsizei,
    ) -> Result<(), ClientError> {
        ext!(
            self,
            "glCopyTexSubImage3DOES",
            fn(u32, i32, i32, i32, i32, i32, i32, i32, i32) -> (),
            *target,
            *level,
            *xoffset,
            *yoffset,
            *zoffset,
            *x,
            *y,
            *width,
            *height
        );
        Ok(())
    }

    pub(super) fn glFramebufferTexture3DOES(
        &mut self,
        target: &GLenum,
        attachment: &GLenum,
        textarget: &GLenum,
        texture: &GLuint,
        level: &GLint,
        zoffset: &GLint,
    ) -> Result<(), ClientError> {
        ext!(
            self,
            "glFramebufferTexture3DOES",
            fn(u32, u32, u32, u32, i32, i32) -> (),
            *target,
            *attachment,
            *textarget,
            *texture,
            *level,
            *zoffset
        );
        Ok(())
    }
}

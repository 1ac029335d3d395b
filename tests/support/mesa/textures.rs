//! The Mesa reference's arms for textures: binding, images, copies, parameters and mipmaps.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glCompressedTexImage2D(
        &mut self,
        target: &GLenum,
        level: &GLint,
        internalformat: &GLenum,
        width: &GLsizei,
        height: &GLsizei,
        border: &GLint,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glCompressedTexImage2D",
            fn(u32, i32, u32, i32, i32, i32, i32, *const u8) -> (),
            *target,
            *level,
            *internalformat,
            *width,
            *height,
            *border,
            data.len() as i32,
            data.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glCompressedTexSubImage2D(
        &mut self,
        target: &GLenum,
        level: &GLint,
        xoffset: &GLint,
        yoffset: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        format: &GLenum,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glCompressedTexSubImage2D",
            fn(u32, i32, i32, i32, i32, i32, u32, i32, *const u8) -> (),
            *target,
            *level,
            *xoffset,
            *yoffset,
            *width,
            *height,
            *format,
            data.len() as i32,
            data.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glDeleteTextures(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let v = names.to_vec();
        call!(self, "glDeleteTextures", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr());
        Ok(())
    }

    // Names are the client's own: binding an unused name creates the object in ES 2.0.
    pub(super) fn glGenTextures(&mut self, _names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        Ok(())
    }

    pub(super) fn glTexImage2D(
        &mut self,
        target: &GLenum,
        level: &GLint,
        internalformat: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        border: &GLint,
        format: &GLenum,
        pixel_type: &GLenum,
        pixels: &Option<Blob<'_>>,
    ) -> Result<(), ClientError> {
        let p = opt_ptr(pixels);
        call!(
            self,
            "glTexImage2D",
            fn(u32, i32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
            *target,
            *level,
            *internalformat,
            *width,
            *height,
            *border,
            *format,
            *pixel_type,
            p
        );
        Ok(())
    }

    pub(super) fn glTexParameterfv(
        &mut self,
        target: &GLenum,
        pname: &GLenum,
        params: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        let v = params.to_vec();
        if v.is_empty() {
            return Err(unsupported("glTexParameterfv without a value"));
        }
        call!(self, "glTexParameterfv", fn(u32, u32, *const f32) -> (), *target, *pname, v.as_ptr());
        Ok(())
    }

    pub(super) fn glTexParameteriv(
        &mut self,
        target: &GLenum,
        pname: &GLenum,
        params: &Slice<'_, GLint>,
    ) -> Result<(), ClientError> {
        let v = params.to_vec();
        if v.is_empty() {
            return Err(unsupported("glTexParameteriv without a value"));
        }
        call!(self, "glTexParameteriv", fn(u32, u32, *const i32) -> (), *target, *pname, v.as_ptr());
        Ok(())
    }

    pub(super) fn glTexSubImage2D(
        &mut self,
        target: &GLenum,
        level: &GLint,
        xoffset: &GLint,
        yoffset: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        format: &GLenum,
        pixel_type: &GLenum,
        pixels: &Blob<'_>,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glTexSubImage2D",
            fn(u32, i32, i32, i32, i32, i32, u32, u32, *const u8) -> (),
            *target,
            *level,
            *xoffset,
            *yoffset,
            *width,
            *height,
            *format,
            *pixel_type,
            pixels.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glGetTexParameterfv(&mut self, target: &GLenum, pname: &GLenum) -> Result<Vec<GLfloat>, ClientError> {
        let mut v = [f32::from_bits(FLOAT_SENTINEL); 16];
        call!(self, "glGetTexParameterfv", fn(u32, u32, *mut f32) -> (), *target, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
    }

    pub(super) fn glGetTexParameteriv(&mut self, target: &GLenum, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        let mut v = [INT_SENTINEL; 16];
        call!(self, "glGetTexParameteriv", fn(u32, u32, *mut i32) -> (), *target, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glIsTexture(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsTexture", fn(u32) -> u8, *name) != 0)
    }
}

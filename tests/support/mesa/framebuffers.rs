//! The Mesa reference's arms for framebuffers, renderbuffers and readback.

use strata_client::ClientError;
use strata_protocol::commands::*;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glDeleteFramebuffers(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let v = names.to_vec();
        call!(self, "glDeleteFramebuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr());
        Ok(())
    }

    pub(super) fn glDeleteRenderbuffers(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let v = names.to_vec();
        call!(self, "glDeleteRenderbuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr());
        Ok(())
    }

    // Names are the client's own: binding an unused name creates the object in ES 2.0.
    pub(super) fn glGenFramebuffers(&mut self, _names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        Ok(())
    }

    // Names are the client's own: binding an unused name creates the object in ES 2.0.
    pub(super) fn glGenRenderbuffers(&mut self, _names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        Ok(())
    }

    pub(super) fn glCheckFramebufferStatus(&mut self, target: &GLenum) -> Result<GLenum, ClientError> {
        Ok(call!(self, "glCheckFramebufferStatus", fn(u32) -> u32, *target))
    }

    pub(super) fn glGetFramebufferAttachmentParameteriv(
        &mut self,
        target: &GLenum,
        attachment: &GLenum,
        pname: &GLenum,
    ) -> Result<GLint, ClientError> {
        let mut v = 0i32;
        call!(
            self,
            "glGetFramebufferAttachmentParameteriv",
            fn(u32, u32, u32, *mut i32) -> (),
            *target,
            *attachment,
            *pname,
            &mut v
        );
        Ok(v)
    }

    pub(super) fn glGetRenderbufferParameteriv(
        &mut self,
        target: &GLenum,
        pname: &GLenum,
    ) -> Result<GLint, ClientError> {
        let mut v = 0i32;
        call!(self, "glGetRenderbufferParameteriv", fn(u32, u32, *mut i32) -> (), *target, *pname, &mut v);
        Ok(v)
    }

    pub(super) fn glIsFramebuffer(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsFramebuffer", fn(u32) -> u8, *name) != 0)
    }

    pub(super) fn glIsRenderbuffer(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsRenderbuffer", fn(u32) -> u8, *name) != 0)
    }

    pub(super) fn glReadPixels(
        &mut self,
        x: &GLint,
        y: &GLint,
        width: &GLsizei,
        height: &GLsizei,
        format: &GLenum,
        pixel_type: &GLenum,
    ) -> Result<Bytes, ClientError> {
        let mut out = vec![0u8; (*width as usize) * (*height as usize) * 4 + 16];
        call!(
            self,
            "glReadPixels",
            fn(i32, i32, i32, i32, u32, u32, *mut u8) -> (),
            *x,
            *y,
            *width,
            *height,
            *format,
            *pixel_type,
            out.as_mut_ptr()
        );
        out.truncate((*width as usize) * (*height as usize) * 4);
        Ok(Bytes(out))
    }
}

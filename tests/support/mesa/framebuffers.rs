//! The Mesa reference's arms for framebuffers, renderbuffers and readback.

use strata_client::ClientError;
use strata_protocol::commands::*;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glGetInternalformativ(
        &mut self,
        target: &GLenum,
        internalformat: &GLenum,
        pname: &GLenum,
        buf_size: &GLsizei,
    ) -> Result<Vec<GLint>, ClientError> {
        let mut v = [INT_SENTINEL; 16];
        let n = (*buf_size).min(16);
        call!(
            self,
            "glGetInternalformativ",
            fn(u32, u32, u32, i32, *mut i32) -> (),
            *target,
            *internalformat,
            *pname,
            n,
            v.as_mut_ptr()
        );
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

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
        // The packed rectangle's size: the format's bytes per pixel, rows padded to Mesa's
        // pack alignment, the last row unpadded.
        let (w, h) = ((*width).max(0) as usize, (*height).max(0) as usize);
        let components = match *format {
            // RGBA, BGRA, RGBA_INTEGER.
            0x1908 | 0x80E1 | 0x8D99 => 4,
            0x1907 | 0x8D98 => 3,
            0x190A | 0x8227 | 0x8228 => 2,
            _ => 1,
        };
        let bpp = match *pixel_type {
            0x1400 | 0x1401 => components,
            0x8363 | 0x8033 | 0x8034 | 0x8365 | 0x8366 => 2,
            // SHORT, UNSIGNED_SHORT (depth: GL_NV_read_depth), HALF_FLOAT_OES, HALF_FLOAT.
            0x1402 | 0x1403 | 0x8D61 | 0x140B => components * 2,
            // UNSIGNED_INT_2_10_10_10_REV, UNSIGNED_INT_24_8: one word.
            0x8368 | 0x84FA => 4,
            _ => components * 4,
        };
        let mut align = 4i32;
        call!(self, "glGetIntegerv", fn(u32, *mut i32) -> (), 0x0D05, &mut align);
        let align = align.max(1) as usize;
        let size = if w == 0 || h == 0 { 0 } else { (w * bpp).div_ceil(align) * align * (h - 1) + w * bpp };
        let mut out = vec![0u8; size + 16];
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
        out.truncate(size);
        Ok(Bytes(out))
    }
}

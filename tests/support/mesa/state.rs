//! The Mesa reference's arms for fixed-function state, clears, flushes and the state queries.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

/// `GL_VERTEX_ARRAY_BINDING_OES`.
const GL_VERTEX_ARRAY_BINDING_OES: u32 = 0x85B5;
/// `GL_NUM_COMPRESSED_TEXTURE_FORMATS`.
const GL_NUM_COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A2;
/// `GL_COMPRESSED_TEXTURE_FORMATS`.
const GL_COMPRESSED_TEXTURE_FORMATS: u32 = 0x86A3;
/// `GL_SHADER_BINARY_FORMATS`.
const GL_SHADER_BINARY_FORMATS: u32 = 0x8DF8;
/// `GL_NUM_SHADER_BINARY_FORMATS`.
const GL_NUM_SHADER_BINARY_FORMATS: u32 = 0x8DF9;

impl Arms<'_> {
    pub(super) fn glBlendColor(
        &mut self,
        red: &GLfloat,
        green: &GLfloat,
        blue: &GLfloat,
        alpha: &GLfloat,
    ) -> Result<(), ClientError> {
        call!(self, "glBlendColor", fn(f32, f32, f32, f32) -> (), *red, *green, *blue, *alpha);
        Ok(())
    }

    pub(super) fn glBlendEquation(&mut self, mode: &GLenum) -> Result<(), ClientError> {
        call!(self, "glBlendEquation", fn(u32) -> (), *mode);
        Ok(())
    }

    pub(super) fn glBlendEquationSeparate(
        &mut self,
        mode_rgb: &GLenum,
        mode_alpha: &GLenum,
    ) -> Result<(), ClientError> {
        call!(self, "glBlendEquationSeparate", fn(u32, u32) -> (), *mode_rgb, *mode_alpha);
        Ok(())
    }

    pub(super) fn glBlendFunc(&mut self, sfactor: &GLenum, dfactor: &GLenum) -> Result<(), ClientError> {
        call!(self, "glBlendFunc", fn(u32, u32) -> (), *sfactor, *dfactor);
        Ok(())
    }

    pub(super) fn glBlendFuncSeparate(
        &mut self,
        src_rgb: &GLenum,
        dst_rgb: &GLenum,
        src_alpha: &GLenum,
        dst_alpha: &GLenum,
    ) -> Result<(), ClientError> {
        call!(self, "glBlendFuncSeparate", fn(u32, u32, u32, u32) -> (), *src_rgb, *dst_rgb, *src_alpha, *dst_alpha);
        Ok(())
    }

    pub(super) fn glClear(&mut self, mask: &GLbitfield) -> Result<(), ClientError> {
        call!(self, "glClear", fn(u32) -> (), *mask);
        Ok(())
    }

    pub(super) fn glClearColor(
        &mut self,
        red: &GLfloat,
        green: &GLfloat,
        blue: &GLfloat,
        alpha: &GLfloat,
    ) -> Result<(), ClientError> {
        call!(self, "glClearColor", fn(f32, f32, f32, f32) -> (), *red, *green, *blue, *alpha);
        Ok(())
    }

    pub(super) fn glClearDepthf(&mut self, depth: &GLfloat) -> Result<(), ClientError> {
        call!(self, "glClearDepthf", fn(f32) -> (), *depth);
        Ok(())
    }

    pub(super) fn glClearStencil(&mut self, s: &GLint) -> Result<(), ClientError> {
        call!(self, "glClearStencil", fn(i32) -> (), *s);
        Ok(())
    }

    pub(super) fn glColorMask(
        &mut self,
        red: &bool,
        green: &bool,
        blue: &bool,
        alpha: &bool,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glColorMask",
            fn(u8, u8, u8, u8) -> (),
            u8::from(*red),
            u8::from(*green),
            u8::from(*blue),
            u8::from(*alpha)
        );
        Ok(())
    }

    pub(super) fn glCullFace(&mut self, mode: &GLenum) -> Result<(), ClientError> {
        call!(self, "glCullFace", fn(u32) -> (), *mode);
        Ok(())
    }

    pub(super) fn glDepthFunc(&mut self, func: &GLenum) -> Result<(), ClientError> {
        call!(self, "glDepthFunc", fn(u32) -> (), *func);
        Ok(())
    }

    pub(super) fn glDepthMask(&mut self, flag: &bool) -> Result<(), ClientError> {
        call!(self, "glDepthMask", fn(u8) -> (), u8::from(*flag));
        Ok(())
    }

    pub(super) fn glDepthRangef(&mut self, near: &GLfloat, far: &GLfloat) -> Result<(), ClientError> {
        call!(self, "glDepthRangef", fn(f32, f32) -> (), *near, *far);
        Ok(())
    }

    pub(super) fn glDisable(&mut self, cap: &GLenum) -> Result<(), ClientError> {
        call!(self, "glDisable", fn(u32) -> (), *cap);
        Ok(())
    }

    pub(super) fn glEnable(&mut self, cap: &GLenum) -> Result<(), ClientError> {
        call!(self, "glEnable", fn(u32) -> (), *cap);
        Ok(())
    }

    pub(super) fn glFlush(&mut self) -> Result<(), ClientError> {
        call!(self, "glFlush", fn() -> (),);
        Ok(())
    }

    pub(super) fn glFrontFace(&mut self, mode: &GLenum) -> Result<(), ClientError> {
        call!(self, "glFrontFace", fn(u32) -> (), *mode);
        Ok(())
    }

    pub(super) fn glHint(&mut self, target: &GLenum, mode: &GLenum) -> Result<(), ClientError> {
        call!(self, "glHint", fn(u32, u32) -> (), *target, *mode);
        Ok(())
    }

    pub(super) fn glLineWidth(&mut self, width: &GLfloat) -> Result<(), ClientError> {
        call!(self, "glLineWidth", fn(f32) -> (), *width);
        Ok(())
    }

    pub(super) fn glPolygonOffset(&mut self, factor: &GLfloat, units: &GLfloat) -> Result<(), ClientError> {
        call!(self, "glPolygonOffset", fn(f32, f32) -> (), *factor, *units);
        Ok(())
    }

    pub(super) fn glSampleCoverage(&mut self, value: &GLfloat, invert: &bool) -> Result<(), ClientError> {
        call!(self, "glSampleCoverage", fn(f32, u8) -> (), *value, u8::from(*invert));
        Ok(())
    }

    pub(super) fn glScissor(
        &mut self,
        x: &GLint,
        y: &GLint,
        width: &GLsizei,
        height: &GLsizei,
    ) -> Result<(), ClientError> {
        call!(self, "glScissor", fn(i32, i32, i32, i32) -> (), *x, *y, *width, *height);
        Ok(())
    }

    pub(super) fn glStencilFunc(&mut self, func: &GLenum, reference: &GLint, mask: &GLuint) -> Result<(), ClientError> {
        call!(self, "glStencilFunc", fn(u32, i32, u32) -> (), *func, *reference, *mask);
        Ok(())
    }

    pub(super) fn glStencilFuncSeparate(
        &mut self,
        face: &GLenum,
        func: &GLenum,
        reference: &GLint,
        mask: &GLuint,
    ) -> Result<(), ClientError> {
        call!(self, "glStencilFuncSeparate", fn(u32, u32, i32, u32) -> (), *face, *func, *reference, *mask);
        Ok(())
    }

    pub(super) fn glStencilMask(&mut self, mask: &GLuint) -> Result<(), ClientError> {
        call!(self, "glStencilMask", fn(u32) -> (), *mask);
        Ok(())
    }

    pub(super) fn glStencilMaskSeparate(&mut self, face: &GLenum, mask: &GLuint) -> Result<(), ClientError> {
        call!(self, "glStencilMaskSeparate", fn(u32, u32) -> (), *face, *mask);
        Ok(())
    }

    pub(super) fn glStencilOp(&mut self, fail: &GLenum, zfail: &GLenum, zpass: &GLenum) -> Result<(), ClientError> {
        call!(self, "glStencilOp", fn(u32, u32, u32) -> (), *fail, *zfail, *zpass);
        Ok(())
    }

    pub(super) fn glStencilOpSeparate(
        &mut self,
        face: &GLenum,
        fail: &GLenum,
        zfail: &GLenum,
        zpass: &GLenum,
    ) -> Result<(), ClientError> {
        call!(self, "glStencilOpSeparate", fn(u32, u32, u32, u32) -> (), *face, *fail, *zfail, *zpass);
        Ok(())
    }

    pub(super) fn glViewport(
        &mut self,
        x: &GLint,
        y: &GLint,
        width: &GLsizei,
        height: &GLsizei,
    ) -> Result<(), ClientError> {
        call!(self, "glViewport", fn(i32, i32, i32, i32) -> (), *x, *y, *width, *height);
        Ok(())
    }

    /// Room for what a state query of `pname` writes: 16 values, or for the two lists the
    /// count their companion query gives (Mesa lists dozens of compressed formats).
    fn slots(&mut self, pname: u32) -> Result<usize, ClientError> {
        let count = match pname {
            GL_COMPRESSED_TEXTURE_FORMATS => GL_NUM_COMPRESSED_TEXTURE_FORMATS,
            GL_SHADER_BINARY_FORMATS => GL_NUM_SHADER_BINARY_FORMATS,
            _ => return Ok(16),
        };
        let mut n = 0i32;
        call!(self, "glGetIntegerv", fn(u32, *mut i32) -> (), count, &mut n);
        Ok(16 + n.max(0) as usize)
    }

    pub(super) fn glFinish(&mut self) -> Result<(), ClientError> {
        call!(self, "glFinish", fn() -> (),);
        Ok(())
    }

    pub(super) fn glGetBooleanv(&mut self, pname: &GLenum) -> Result<Vec<bool>, ClientError> {
        let mut v = vec![BOOL_SENTINEL; self.slots(*pname)?];
        call!(self, "glGetBooleanv", fn(u32, *mut u8) -> (), *pname, v.as_mut_ptr());
        Ok(v.iter().take_while(|x| **x != BOOL_SENTINEL).map(|x| *x != 0).collect())
    }

    pub(super) fn glGetError(&mut self) -> Result<GLenum, ClientError> {
        Ok(call!(self, "glGetError", fn() -> u32,))
    }

    pub(super) fn glGetFloatv(&mut self, pname: &GLenum) -> Result<Vec<GLfloat>, ClientError> {
        let mut v = vec![f32::from_bits(FLOAT_SENTINEL); self.slots(*pname)?];
        call!(self, "glGetFloatv", fn(u32, *mut f32) -> (), *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
    }

    // The values a query writes: everything before the first untouched sentinel.
    pub(super) fn glGetIntegerv(&mut self, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        if *pname == GL_VERTEX_ARRAY_BINDING_OES {
            // The binding in the client's names.
            let mut v = 0i32;
            call!(self, "glGetIntegerv", fn(u32, *mut i32) -> (), *pname, &mut v);
            let client = self.vaos.iter().find(|(_, &real)| real as i32 == v).map_or(v, |(&c, _)| c as i32);
            return Ok(vec![client]);
        }
        let mut v = vec![INT_SENTINEL; self.slots(*pname)?];
        call!(self, "glGetIntegerv", fn(u32, *mut i32) -> (), *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetString(&mut self, name: &GLenum) -> Result<Option<String>, ClientError> {
        let p = call!(self, "glGetString", fn(u32) -> *const u8, *name);
        Ok(self.string(p))
    }

    pub(super) fn glIsEnabled(&mut self, cap: &GLenum) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsEnabled", fn(u32) -> u8, *cap) != 0)
    }
}

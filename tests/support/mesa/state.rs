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

    pub(super) fn glDepthMask(&mut self, flag: &bool) -> Result<(), ClientError> {
        call!(self, "glDepthMask", fn(u8) -> (), u8::from(*flag));
        Ok(())
    }

    pub(super) fn glSampleCoverage(&mut self, value: &GLfloat, invert: &bool) -> Result<(), ClientError> {
        call!(self, "glSampleCoverage", fn(f32, u8) -> (), *value, u8::from(*invert));
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

    pub(super) fn glGetStringi(&mut self, name: &GLenum, index: &GLuint) -> Result<Option<String>, ClientError> {
        let p = call!(self, "glGetStringi", fn(u32, u32) -> *const u8, *name, *index);
        Ok(self.string(p))
    }

    pub(super) fn glIsEnabled(&mut self, cap: &GLenum) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsEnabled", fn(u32) -> u8, *cap) != 0)
    }
}

//! ES 3.0's sampler objects forwarded to Mesa, the client's names mapped to the ones Mesa
//! generates (a name Mesa never generated stays one it does not know).

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    /// Mesa's name for the client's sampler `n`.
    fn sampler(&self, n: u32) -> u32 {
        self.samplers.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    pub(super) fn glGenSamplers(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        for n in names.iter() {
            let mut real = 0u32;
            call!(self, "glGenSamplers", fn(i32, *mut u32) -> (), 1, &mut real);
            self.samplers.insert(n, real);
        }
        Ok(())
    }

    pub(super) fn glDeleteSamplers(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let real: Vec<u32> = names.iter().map(|n| self.sampler(n)).collect();
        call!(self, "glDeleteSamplers", fn(i32, *const u32) -> (), real.len() as i32, real.as_ptr());
        Ok(())
    }

    pub(super) fn glIsSampler(&mut self, sampler: &GLuint) -> Result<bool, ClientError> {
        let s = self.sampler(*sampler);
        Ok(call!(self, "glIsSampler", fn(u32) -> u8, s) != 0)
    }

    pub(super) fn glBindSampler(&mut self, unit: &GLuint, sampler: &GLuint) -> Result<(), ClientError> {
        let s = self.sampler(*sampler);
        call!(self, "glBindSampler", fn(u32, u32) -> (), *unit, s);
        Ok(())
    }

    pub(super) fn glSamplerParameteri(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
        param: &GLint,
    ) -> Result<(), ClientError> {
        let s = self.sampler(*sampler);
        call!(self, "glSamplerParameteri", fn(u32, u32, i32) -> (), s, *pname, *param);
        Ok(())
    }

    pub(super) fn glSamplerParameterf(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
        param: &GLfloat,
    ) -> Result<(), ClientError> {
        let s = self.sampler(*sampler);
        call!(self, "glSamplerParameterf", fn(u32, u32, f32) -> (), s, *pname, *param);
        Ok(())
    }

    pub(super) fn glSamplerParameteriv(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
        params: &Slice<'_, GLint>,
    ) -> Result<(), ClientError> {
        let (s, v) = (self.sampler(*sampler), params.to_vec());
        call!(self, "glSamplerParameteriv", fn(u32, u32, *const i32) -> (), s, *pname, v.as_ptr());
        Ok(())
    }

    pub(super) fn glSamplerParameterfv(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
        params: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        let (s, v) = (self.sampler(*sampler), params.to_vec());
        call!(self, "glSamplerParameterfv", fn(u32, u32, *const f32) -> (), s, *pname, v.as_ptr());
        Ok(())
    }

    pub(super) fn glGetSamplerParameteriv(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
    ) -> Result<Vec<GLint>, ClientError> {
        let s = self.sampler(*sampler);
        let mut v = [INT_SENTINEL; 16];
        call!(self, "glGetSamplerParameteriv", fn(u32, u32, *mut i32) -> (), s, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetSamplerParameterfv(
        &mut self,
        sampler: &GLuint,
        pname: &GLenum,
    ) -> Result<Vec<GLfloat>, ClientError> {
        let s = self.sampler(*sampler);
        let mut v = [f32::from_bits(FLOAT_SENTINEL); 16];
        call!(self, "glGetSamplerParameterfv", fn(u32, u32, *mut f32) -> (), s, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
    }
}

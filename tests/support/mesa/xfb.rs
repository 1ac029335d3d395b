//! ES 3.0's transform feedback forwarded to Mesa, the client's object names mapped to the ones
//! Mesa generates (a name Mesa never generated stays one it does not know).

use strata_client::ClientError;
use strata_protocol::commands::ActiveVariable;
use strata_protocol::wire::*;

use super::{Arms, Ptr};

impl Arms<'_> {
    /// Mesa's name for the client's transform feedback object `n`.
    fn xfb(&self, n: u32) -> u32 {
        self.xfbs.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    pub(super) fn glGenTransformFeedbacks(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        for n in names.iter() {
            let mut real = 0u32;
            call!(self, "glGenTransformFeedbacks", fn(i32, *mut u32) -> (), 1, &mut real);
            self.xfbs.insert(n, real);
        }
        Ok(())
    }

    pub(super) fn glDeleteTransformFeedbacks(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let real: Vec<u32> = names.iter().map(|n| self.xfb(n)).collect();
        call!(self, "glDeleteTransformFeedbacks", fn(i32, *const u32) -> (), real.len() as i32, real.as_ptr());
        Ok(())
    }

    pub(super) fn glIsTransformFeedback(&mut self, id: &GLuint) -> Result<bool, ClientError> {
        let x = self.xfb(*id);
        Ok(call!(self, "glIsTransformFeedback", fn(u32) -> u8, x) != 0)
    }

    pub(super) fn glBindTransformFeedback(&mut self, target: &GLenum, id: &GLuint) -> Result<(), ClientError> {
        let x = self.xfb(*id);
        call!(self, "glBindTransformFeedback", fn(u32, u32) -> (), *target, x);
        Ok(())
    }

    pub(super) fn glBeginTransformFeedback(&mut self, mode: &GLenum) -> Result<(), ClientError> {
        call!(self, "glBeginTransformFeedback", fn(u32) -> (), *mode);
        Ok(())
    }

    pub(super) fn glEndTransformFeedback(&mut self) -> Result<(), ClientError> {
        call!(self, "glEndTransformFeedback", fn() -> (),);
        Ok(())
    }

    pub(super) fn glPauseTransformFeedback(&mut self) -> Result<(), ClientError> {
        call!(self, "glPauseTransformFeedback", fn() -> (),);
        Ok(())
    }

    pub(super) fn glResumeTransformFeedback(&mut self) -> Result<(), ClientError> {
        call!(self, "glResumeTransformFeedback", fn() -> (),);
        Ok(())
    }

    pub(super) fn glTransformFeedbackVaryings(
        &mut self,
        program: &GLuint,
        count: &GLsizei,
        names: &Text<'_>,
        buffer_mode: &GLenum,
    ) -> Result<(), ClientError> {
        let p = self.shader(*program);
        let owned = super::c_lines(names)?;
        let ptrs: Vec<*const i8> = owned.iter().map(|c| c.as_ptr()).collect();
        call!(
            self,
            "glTransformFeedbackVaryings",
            fn(u32, i32, *const *const i8, u32) -> (),
            p,
            *count,
            ptrs.as_ptr(),
            *buffer_mode
        );
        Ok(())
    }

    pub(super) fn glGetTransformFeedbackVarying(
        &mut self,
        program: &GLuint,
        index: &GLuint,
    ) -> Result<Option<ActiveVariable>, ClientError> {
        self.active_variable("glGetTransformFeedbackVarying", *program, *index)
    }
}

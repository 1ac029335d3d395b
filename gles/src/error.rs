//! GL errors: the codes a call records instead of acting (ES 2.0 §2.5), and the rule that the
//! first recorded error stays until `glGetError` reads it.

use crate::enums::*;

/// An error a GL call records; the call then changes nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum GlError {
    /// `GL_INVALID_ENUM`: an enum argument out of range.
    #[error("GL_INVALID_ENUM")]
    InvalidEnum,
    /// `GL_INVALID_VALUE`: a numeric argument out of range.
    #[error("GL_INVALID_VALUE")]
    InvalidValue,
    /// `GL_INVALID_OPERATION`: not allowed in the current state.
    #[error("GL_INVALID_OPERATION")]
    InvalidOperation,
    /// `GL_INVALID_FRAMEBUFFER_OPERATION`: the framebuffer is not complete.
    #[error("GL_INVALID_FRAMEBUFFER_OPERATION")]
    InvalidFramebufferOperation,
    /// `GL_OUT_OF_MEMORY`: too large, or the GPU rejected the work.
    #[error("GL_OUT_OF_MEMORY")]
    OutOfMemory,
    /// `GL_STACK_OVERFLOW_KHR`: a debug group pushed onto a full stack.
    #[error("GL_STACK_OVERFLOW")]
    StackOverflow,
    /// `GL_STACK_UNDERFLOW_KHR`: the default debug group popped.
    #[error("GL_STACK_UNDERFLOW")]
    StackUnderflow,
}

impl GlError {
    /// The enum `glGetError` returns for this error.
    pub fn as_gl(self) -> u32 {
        match self {
            GlError::InvalidEnum => INVALID_ENUM,
            GlError::InvalidValue => INVALID_VALUE,
            GlError::InvalidOperation => INVALID_OPERATION,
            GlError::InvalidFramebufferOperation => INVALID_FRAMEBUFFER_OPERATION,
            GlError::OutOfMemory => OUT_OF_MEMORY,
            GlError::StackOverflow => STACK_OVERFLOW,
            GlError::StackUnderflow => STACK_UNDERFLOW,
        }
    }
}

/// What a validating call returns: the validated value, or the error to record.
pub type GlResult<T = ()> = Result<T, GlError>;

/// A context's error flag: the first error recorded wins until `glGetError` takes it.
#[derive(Debug, Default)]
pub struct ErrorFlag(Option<GlError>);

impl ErrorFlag {
    /// Records `e` unless an earlier error is still pending.
    pub fn record(&mut self, e: GlError) {
        if self.0.is_none() {
            self.0 = Some(e);
        }
    }

    /// `glGetError`: the pending error's enum (or `GL_NO_ERROR`), clearing it.
    pub fn take(&mut self) -> u32 {
        self.0.take().map_or(NO_ERROR, GlError::as_gl)
    }
}

/// An error with all its sources, for logs (wgpu's top-level text is only "Validation Error").
pub fn error_chain(e: &wgpu::Error) -> String {
    let mut s = match e {
        wgpu::Error::Validation { description, .. } => description.clone(),
        other => other.to_string(),
    };
    let mut src = std::error::Error::source(e);
    while let Some(x) = src {
        s.push_str(": ");
        s.push_str(&x.to_string());
        src = x.source();
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_error_wins_until_read() {
        let mut flag = ErrorFlag::default();
        assert_eq!(flag.take(), NO_ERROR);
        flag.record(GlError::InvalidValue);
        flag.record(GlError::InvalidEnum);
        assert_eq!(flag.take(), INVALID_VALUE);
        assert_eq!(flag.take(), NO_ERROR);
        flag.record(GlError::OutOfMemory);
        assert_eq!(flag.take(), OUT_OF_MEMORY);
    }
}

//! `glXGetProcAddressARB` and `glXGetProcAddress`, answered like `eglGetProcAddress` for the
//! shim's GL entry points. Some GLES programs resolve extension entry points through libGL's
//! GLX query even under EGL (piglit's utility library, built with GLX, does); with the shim
//! also installed as `libGL.so.1`, they get the shim's functions instead of libGL's dispatch
//! stubs, which would call nothing without a GLX context. No other GLX call is provided.

use std::ffi::{c_char, CStr};

use crate::types::*;

/// The address of one of the shim's GL entry points (`None` for EGL names and unknown ones).
fn gl_proc(name: *const GLubyte) -> EglProc {
    if name.is_null() {
        return None;
    }
    // SAFETY: the application passes a NUL-terminated name.
    let name = unsafe { CStr::from_ptr(name.cast::<c_char>()) };
    let f = crate::gl::lookup(name.to_bytes())?;
    // SAFETY: a non-null address of one of the shim's own `extern "C"` functions; the caller
    // casts it back to the right prototype, as glXGetProcAddress specifies.
    Some(unsafe { std::mem::transmute::<*const std::ffi::c_void, unsafe extern "C" fn()>(f) })
}

crate::entry_points! {
    /// A GL entry point of the shim, by name.
    fn glXGetProcAddressARB(name: *const GLubyte) -> EglProc {
        gl_proc(name)
    }

    /// A GL entry point of the shim, by name.
    fn glXGetProcAddress(name: *const GLubyte) -> EglProc {
        gl_proc(name)
    }
}

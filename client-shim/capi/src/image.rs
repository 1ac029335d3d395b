//! EGLImages (`EGL_KHR_image_base`, with `EGL_KHR_gl_texture_2D_image`,
//! `EGL_KHR_gl_texture_cubemap_image` and `EGL_KHR_gl_renderbuffer_image`). The daemon keeps
//! the images; an `EGLImageKHR` is its handle. The GL calls that make textures and
//! renderbuffers of them (`GL_OES_EGL_image`, `GL_OES_EGL_image_external`) are in
//! `gl/egl_image.rs`.

use std::ffi::c_void;

use strata_protocol::{Calls, Slice};

use crate::display::{daemon, initialized};
use crate::state::{answer, process};
use crate::types::*;

/// `EGLImageKHR`.
pub type EGLImageKHR = *mut c_void;
/// `EGLClientBuffer`: for the GL targets, a texture or renderbuffer name.
pub type EGLClientBuffer = *mut c_void;

/// Longest attribute list read (pairs), against unterminated lists.
const MAX_ATTRIBS: usize = 64;

/// Reads an `EGL_NONE`-terminated list of pairs (a null list is empty).
unsafe fn attribs(list: *const EGLint) -> Result<Vec<EGLint>, EGLint> {
    let mut out = Vec::new();
    if !list.is_null() {
        for i in 0..MAX_ATTRIBS {
            // SAFETY: the application promises an EGL_NONE-terminated list of pairs.
            let a = unsafe { *list.add(2 * i) };
            if a == EGL_NONE {
                break;
            }
            // SAFETY: as above; a non-NONE attribute is followed by its value.
            out.extend([a, unsafe { *list.add(2 * i + 1) }]);
        }
    }
    out.push(EGL_NONE);
    Ok(out)
}

/// A handle the application passed, as the daemon's number (an impossible one if it is none).
pub(crate) fn handle(p: *mut c_void) -> u32 {
    u32::try_from(p as usize).unwrap_or(u32::MAX)
}

/// `eglCreateImageKHR` for the GL targets: `ctx` must be a live context of `dpy`.
fn create(
    dpy: EGLDisplay,
    ctx: EGLContext,
    target: EGLenum,
    buffer: EGLClientBuffer,
    list: *const EGLint,
) -> Result<u32, EGLint> {
    let mut p = process();
    initialized(&mut p, dpy)?;
    let d_ctx = p.daemon_context(handle(ctx)).ok_or(EGL_BAD_CONTEXT)?;
    let name = u32::try_from(buffer as usize).map_err(|_| EGL_BAD_PARAMETER)?;
    // SAFETY: the application passes an EGL_NONE-terminated list or null.
    let a = unsafe { attribs(list) }?;
    daemon(&mut p, |c, dd| c.eglCreateImageKHR(dd, d_ctx, target as EGLint, name, Slice::new(&a)))
}

crate::entry::entry_points! {
    /// An EGLImage of a level (and face) of a texture, or of a renderbuffer, of `ctx`.
    fn eglCreateImageKHR(dpy: EGLDisplay, ctx: EGLContext, target: EGLenum, buffer: EGLClientBuffer, attrib_list: *const EGLint) -> EGLImageKHR {
        answer(create(dpy, ctx, target, buffer, attrib_list).map(|h| h as usize as EGLImageKHR), std::ptr::null_mut())
    }

    /// Destroys an EGLImage; the textures and renderbuffers made from it keep their image.
    fn eglDestroyImageKHR(dpy: EGLDisplay, image: EGLImageKHR) -> EGLBoolean {
        let r = {
            let mut p = process();
            initialized(&mut p, dpy).and_then(|_| daemon(&mut p, |c, dd| c.eglDestroyImageKHR(dd, handle(image))))
        };
        answer(r.map(|()| EGL_TRUE), EGL_FALSE)
    }
}

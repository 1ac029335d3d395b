//! `GL_OES_EGL_image` (and `GL_OES_EGL_image_external`): the GL calls that make a texture or a
//! renderbuffer of an EGLImage (see [`crate::image`]), whose handle the daemon knows.

use std::ffi::c_void;

use strata_protocol::Calls;

use super::with_gl;
use crate::image::handle;
use crate::types::*;

crate::entry::entry_points! {
    /// The texture bound to `target` (`GL_TEXTURE_2D`, `GL_TEXTURE_EXTERNAL_OES`) takes the
    /// image's contents, shared with it.
    fn glEGLImageTargetTexture2DOES(target: GLenum, image: *mut c_void) {
        with_gl("glEGLImageTargetTexture2DOES", (), |gl| gl.conn.glEGLImageTargetTexture2DOES(target, handle(image)))
    }

    /// The bound renderbuffer takes the image's contents, shared with it.
    fn glEGLImageTargetRenderbufferStorageOES(target: GLenum, image: *mut c_void) {
        with_gl("glEGLImageTargetRenderbufferStorageOES", (), |gl| {
            gl.conn.glEGLImageTargetRenderbufferStorageOES(target, handle(image))
        })
    }
}

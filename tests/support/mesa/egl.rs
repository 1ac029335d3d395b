//! The Mesa reference's arms for the calls the reference does not run: EGL (it draws on a context of its own) and Strata's own.

use strata_client::ClientError;
use strata_protocol::commands::*;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn eglGetDisplay(&mut self, native_display: &u64) -> Result<EglHandle, ClientError> {
        let _ = native_display;
        Err(unsupported("eglGetDisplay (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglGetPlatformDisplay(
        &mut self,
        platform: &GLenum,
        native_display: &u64,
        attribs: &Slice<'_, EGLint>,
    ) -> Result<EglHandle, ClientError> {
        let _ = (platform, native_display, attribs);
        Err(unsupported("eglGetPlatformDisplay (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglInitialize(&mut self, display: &EglHandle) -> Result<EglResult<(EGLint, EGLint)>, ClientError> {
        let _ = display;
        Err(unsupported("eglInitialize (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglChooseConfig(
        &mut self,
        display: &EglHandle,
        attribs: &Slice<'_, EGLint>,
        config_size: &EGLint,
    ) -> Result<EglResult<Vec<EglHandle>>, ClientError> {
        let _ = (display, attribs, config_size);
        Err(unsupported("eglChooseConfig (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglGetConfigAttrib(
        &mut self,
        display: &EglHandle,
        config: &EglHandle,
        attribute: &EGLint,
    ) -> Result<EglResult<EGLint>, ClientError> {
        let _ = (display, config, attribute);
        Err(unsupported("eglGetConfigAttrib (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglCreateWindowSurface(
        &mut self,
        display: &EglHandle,
        config: &EglHandle,
        native_window: &u64,
        x: &GLint,
        y: &GLint,
        z: &GLfloat,
        width: &GLsizei,
        height: &GLsizei,
        attribs: &Slice<'_, EGLint>,
    ) -> Result<EglResult<EglHandle>, ClientError> {
        let _ = (display, config, native_window, x, y, z, width, height, attribs);
        Err(unsupported("eglCreateWindowSurface (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglCreatePbufferSurface(
        &mut self,
        display: &EglHandle,
        config: &EglHandle,
        attribs: &Slice<'_, EGLint>,
    ) -> Result<EglResult<EglHandle>, ClientError> {
        let _ = (display, config, attribs);
        Err(unsupported("eglCreatePbufferSurface (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglCreateContext(
        &mut self,
        display: &EglHandle,
        config: &EglHandle,
        share_context: &EglHandle,
        attribs: &Slice<'_, EGLint>,
    ) -> Result<EglResult<EglHandle>, ClientError> {
        let _ = (display, config, share_context, attribs);
        Err(unsupported("eglCreateContext (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglMakeCurrent(
        &mut self,
        display: &EglHandle,
        draw: &EglHandle,
        read: &EglHandle,
        context: &EglHandle,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, draw, read, context);
        Err(unsupported("eglMakeCurrent (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglSwapInterval(
        &mut self,
        display: &EglHandle,
        interval: &EGLint,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, interval);
        Err(unsupported("eglSwapInterval (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglQuerySurface(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
        attribute: &EGLint,
    ) -> Result<EglResult<EGLint>, ClientError> {
        let _ = (display, surface, attribute);
        Err(unsupported("eglQuerySurface (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglDestroySurface(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, surface);
        Err(unsupported("eglDestroySurface (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglDestroyContext(
        &mut self,
        display: &EglHandle,
        context: &EglHandle,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, context);
        Err(unsupported("eglDestroyContext (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglTerminate(&mut self, display: &EglHandle) -> Result<EglResult<()>, ClientError> {
        let _ = display;
        Err(unsupported("eglTerminate (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn strataPing(&mut self, token: &u64) -> Result<u64, ClientError> {
        let _ = token;
        Err(unsupported("strataPing (Strata's own call)"))
    }

    pub(super) fn strataVerify(&mut self, commands: &u64, crc32: &u32) -> Result<StreamTally, ClientError> {
        let _ = (commands, crc32);
        Err(unsupported("strataVerify (Strata's own call)"))
    }

    pub(super) fn strataStats(&mut self) -> Result<ExecStats, ClientError> {
        Err(unsupported("strataStats (Strata's own call)"))
    }

    pub(super) fn strataFence(&mut self) -> Result<u64, ClientError> {
        Err(unsupported("strataFence (Strata's own call; the reference's fences are EGL's)"))
    }

    pub(super) fn strataReadSurface(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
    ) -> Result<EglResult<Bytes>, ClientError> {
        let _ = (display, surface);
        Err(unsupported("strataReadSurface (Strata's own call)"))
    }

    pub(super) fn eglSwapBuffers(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, surface);
        Err(unsupported("eglSwapBuffers (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglSwapBuffersWithDamageKHR(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
        rects: &Slice<'_, EGLint>,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, surface, rects);
        Err(unsupported("eglSwapBuffersWithDamageKHR (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn strataResizeSurface(
        &mut self,
        display: &EglHandle,
        surface: &EglHandle,
        width: &GLsizei,
        height: &GLsizei,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, surface, width, height);
        Err(unsupported("strataResizeSurface (Strata's own call)"))
    }

    pub(super) fn eglQueryContext(
        &mut self,
        display: &EglHandle,
        context: &EglHandle,
        attribute: &EGLint,
    ) -> Result<EglResult<EGLint>, ClientError> {
        let _ = (display, context, attribute);
        Err(unsupported("eglQueryContext (EGL: the reference draws on a context of its own)"))
    }

    pub(super) fn eglCreateImageKHR(
        &mut self,
        display: &EglHandle,
        context: &EglHandle,
        target: &EGLint,
        buffer: &GLuint,
        attribs: &Slice<'_, EGLint>,
    ) -> Result<EglResult<EglHandle>, ClientError> {
        let _ = (display, context, target, buffer, attribs);
        Err(unsupported("eglCreateImageKHR (EGL: tests/client_calls.rs compares EGLImages with Mesa)"))
    }

    pub(super) fn eglDestroyImageKHR(
        &mut self,
        display: &EglHandle,
        image: &EglHandle,
    ) -> Result<EglResult<()>, ClientError> {
        let _ = (display, image);
        Err(unsupported("eglDestroyImageKHR (EGL: tests/client_calls.rs compares EGLImages with Mesa)"))
    }

    pub(super) fn glEGLImageTargetTexture2DOES(
        &mut self,
        target: &GLenum,
        image: &EglHandle,
    ) -> Result<(), ClientError> {
        let _ = (target, image);
        Err(unsupported("glEGLImageTargetTexture2DOES (its images are EGL's: tests/client_calls.rs)"))
    }

    pub(super) fn glEGLImageTargetRenderbufferStorageOES(
        &mut self,
        target: &GLenum,
        image: &EglHandle,
    ) -> Result<(), ClientError> {
        let _ = (target, image);
        Err(unsupported("glEGLImageTargetRenderbufferStorageOES (its images are EGL's: tests/client_calls.rs)"))
    }
}

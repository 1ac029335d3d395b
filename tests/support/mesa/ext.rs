//! The extension calls the Mesa reference forwards: `GL_OES_vertex_array_object` and
//! `GL_KHR_debug`, looked up with `eglGetProcAddress` (glvnd's libGLESv2 exports only core
//! entry points). The debug callback is the client library's, so `strataDebugCallback` and
//! `strataDebugMessages` have no Mesa counterpart and say so, as do the sync-object labels,
//! which ES 2.0 has no objects for.

use std::ffi::CString;

use strata_client::ClientError;
use strata_protocol::wire::*;
use strata_protocol::{Bytes, DebugMessage};

use super::{unsupported, Arms, MesaGl, Ptr};

impl MesaGl {
    /// Mesa's name for the client's vertex array `n` (one Mesa never generated if it has none).
    fn vao(&self, n: u32) -> u32 {
        self.vaos.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    /// Mesa's name for object `name` in label namespace `identifier`.
    fn object_for(&self, identifier: u32, name: u32) -> u32 {
        match identifier {
            // GL_KHR_debug's and GL_EXT_debug_label's names of shaders, programs and VAOs.
            0x82E1 | 0x82E2 | 0x8B48 | 0x8B40 => self.shader(name),
            0x8074 | 0x9154 => self.vao(name),
            _ => name,
        }
    }

    /// An extension entry point, by `eglGetProcAddress`.
    pub(super) fn ext(&mut self, name: &'static str) -> Result<Ptr, ClientError> {
        if let Some(p) = self.fns.get(name) {
            return Ok(*p);
        }
        let c = CString::new(name).map_err(|_| unsupported(name))?;
        // SAFETY: eglGetProcAddress has this prototype; it returns null for unknown names.
        let p = unsafe {
            let get: libloading::Symbol<unsafe extern "C" fn(*const i8) -> Ptr> =
                self._egl.get(b"eglGetProcAddress\0").map_err(|_| unsupported(name))?;
            get(c.as_ptr())
        };
        if p.is_null() {
            return Err(unsupported(name));
        }
        self.fns.insert(name, p);
        Ok(p)
    }
}

macro_rules! ext {
    ($self:ident, $name:expr, fn($($t:ty),*) -> $r:ty, $($a:expr),*) => {{
        let f = $self.ext($name)?;
        // SAFETY: the extension entry point of that name, with that C signature.
        let f: unsafe extern "C" fn($($t),*) -> $r = unsafe { std::mem::transmute::<Ptr, _>(f) };
        unsafe { f($($a),*) }
    }};
}

/// A text argument: `None` becomes NULL.
fn text_ptr(b: Option<&[u8]>) -> *const u8 {
    b.map_or(std::ptr::null(), <[u8]>::as_ptr)
}

impl Arms<'_> {
    pub(super) fn glGenVertexArraysOES(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        for n in names.iter() {
            let mut real = 0u32;
            ext!(self, "glGenVertexArraysOES", fn(i32, *mut u32) -> (), 1, &mut real);
            self.vaos.insert(n, real);
        }
        Ok(())
    }

    pub(super) fn glBindVertexArrayOES(&mut self, array: &GLuint) -> Result<(), ClientError> {
        let a = self.vao(*array);
        ext!(self, "glBindVertexArrayOES", fn(u32) -> (), a);
        Ok(())
    }

    pub(super) fn glDeleteVertexArraysOES(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let v: Vec<u32> = names.iter().map(|n| self.vao(n)).collect();
        for n in names.iter() {
            self.vaos.remove(&n);
        }
        ext!(self, "glDeleteVertexArraysOES", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr());
        Ok(())
    }

    pub(super) fn glDebugMessageControlKHR(
        &mut self,
        source: &GLenum,
        ty: &GLenum,
        severity: &GLenum,
        count: &GLsizei,
        ids: &Slice<'_, GLuint>,
        enabled: &bool,
    ) -> Result<(), ClientError> {
        let v = ids.to_vec();
        let p = if v.is_empty() { std::ptr::null() } else { v.as_ptr() };
        ext!(
            self,
            "glDebugMessageControlKHR",
            fn(u32, u32, u32, i32, *const u32, u8) -> (),
            *source,
            *ty,
            *severity,
            *count,
            p,
            u8::from(*enabled)
        );
        Ok(())
    }

    pub(super) fn glDebugMessageInsertKHR(
        &mut self,
        source: &GLenum,
        ty: &GLenum,
        id: &GLuint,
        severity: &GLenum,
        length: &GLsizei,
        text: &Blob<'_>,
    ) -> Result<(), ClientError> {
        let z = nul_terminated(text.as_bytes(), *length);
        ext!(
            self,
            "glDebugMessageInsertKHR",
            fn(u32, u32, u32, u32, i32, *const u8) -> (),
            *source,
            *ty,
            *id,
            *severity,
            *length,
            z.as_ptr()
        );
        Ok(())
    }

    pub(super) fn glPushDebugGroupKHR(
        &mut self,
        source: &GLenum,
        id: &GLuint,
        length: &GLsizei,
        text: &Blob<'_>,
    ) -> Result<(), ClientError> {
        let z = nul_terminated(text.as_bytes(), *length);
        ext!(self, "glPushDebugGroupKHR", fn(u32, u32, i32, *const u8) -> (), *source, *id, *length, z.as_ptr());
        Ok(())
    }

    pub(super) fn glPopDebugGroupKHR(&mut self) -> Result<(), ClientError> {
        ext!(self, "glPopDebugGroupKHR", fn() -> (),);
        Ok(())
    }

    pub(super) fn glObjectLabelKHR(
        &mut self,
        identifier: &GLenum,
        name: &GLuint,
        length: &GLsizei,
        label: &Option<Blob<'_>>,
    ) -> Result<(), ClientError> {
        let z = label.as_ref().map(|l| nul_terminated(l.as_bytes(), *length));
        let p = text_ptr(z.as_deref());
        let (identifier, name) = (*identifier, self.object_for(*identifier, *name));
        ext!(self, "glObjectLabelKHR", fn(u32, u32, i32, *const u8) -> (), identifier, name, *length, p);
        Ok(())
    }

    pub(super) fn glObjectPtrLabelKHR(
        &mut self,
        ptr: &u64,
        length: &GLsizei,
        label: &Option<Blob<'_>>,
    ) -> Result<(), ClientError> {
        let _ = (ptr, length, label);
        Err(unsupported("glObjectPtrLabelKHR: sync objects are not part of ES 2.0, so the reference has none to label"))
    }

    pub(super) fn strataDebugCallback(&mut self, installed: &bool) -> Result<(), ClientError> {
        let _ = installed;
        Err(unsupported("strataDebugCallback: the debug callback is the client library's; Mesa's log is read instead"))
    }

    pub(super) fn glDiscardFramebufferEXT(
        &mut self,
        target: &GLenum,
        attachments: &Slice<'_, GLenum>,
    ) -> Result<(), ClientError> {
        let list: Vec<u32> = attachments.iter().collect();
        let n = list.len() as i32;
        call!(self, "glDiscardFramebufferEXT", fn(u32, i32, *const u32) -> (), *target, n, list.as_ptr());
        Ok(())
    }

    pub(super) fn glDrawBuffersEXT(&mut self, buffers: &Slice<'_, GLenum>) -> Result<(), ClientError> {
        let list: Vec<u32> = buffers.iter().collect();
        ext!(self, "glDrawBuffersEXT", fn(i32, *const u32) -> (), list.len() as i32, list.as_ptr());
        Ok(())
    }

    pub(super) fn glIsVertexArrayOES(&mut self, array: &GLuint) -> Result<bool, ClientError> {
        let a = self.vao(*array);
        Ok(ext!(self, "glIsVertexArrayOES", fn(u32) -> u8, a) != 0)
    }

    pub(super) fn glGetDebugMessageLogKHR(
        &mut self,
        count: &GLuint,
        buf_size: &GLsizei,
        log: &bool,
    ) -> Result<Vec<DebugMessage>, ClientError> {
        let n = *count as usize;
        let (mut sources, mut types, mut ids, mut severities, mut lengths) =
            (vec![0u32; n], vec![0u32; n], vec![0u32; n], vec![0u32; n], vec![0i32; n]);
        let mut text = vec![0u8; (*buf_size).max(0) as usize];
        let tp = if *log { text.as_mut_ptr() } else { std::ptr::null_mut() };
        let got = ext!(
            self,
            "glGetDebugMessageLogKHR",
            fn(u32, i32, *mut u32, *mut u32, *mut u32, *mut u32, *mut i32, *mut u8) -> u32,
            *count,
            *buf_size,
            sources.as_mut_ptr(),
            types.as_mut_ptr(),
            ids.as_mut_ptr(),
            severities.as_mut_ptr(),
            lengths.as_mut_ptr(),
            tp
        ) as usize;
        let mut at = 0usize;
        let mut out = Vec::new();
        for i in 0..got.min(n) {
            let len = (lengths[i].max(1) - 1) as usize;
            let t = if *log { text.get(at..at + len).map(<[u8]>::to_vec).unwrap_or_default() } else { Vec::new() };
            at += len + 1;
            out.push(DebugMessage {
                source: sources[i],
                ty: types[i],
                id: ids[i],
                severity: severities[i],
                text: Bytes(t),
            });
        }
        Ok(out)
    }

    pub(super) fn glGetObjectLabelKHR(
        &mut self,
        identifier: &GLenum,
        name: &GLuint,
        buf_size: &GLsizei,
    ) -> Result<Option<Bytes>, ClientError> {
        let name = self.object_for(*identifier, *name);
        let mut buf = vec![0u8; (*buf_size).max(1) as usize];
        // Left at -1 when the call fails with a GL error.
        let mut len = -1i32;
        ext!(
            self,
            "glGetObjectLabelKHR",
            fn(u32, u32, i32, *mut i32, *mut u8) -> (),
            *identifier,
            name,
            *buf_size,
            &mut len,
            buf.as_mut_ptr()
        );
        buf.truncate(len.max(0) as usize);
        Ok((len >= 0).then_some(Bytes(buf)))
    }

    pub(super) fn glLabelObjectEXT(
        &mut self,
        object_type: &GLenum,
        object: &GLuint,
        length: &GLsizei,
        label: &Option<Blob<'_>>,
    ) -> Result<(), ClientError> {
        let object = self.object_for(*object_type, *object);
        // A length of 0 reads a NUL-terminated label: end the bytes with one.
        let text: Option<Vec<u8>> = label.as_ref().map(|l| [l.as_bytes(), &[0]].concat());
        let p = text.as_ref().map_or(std::ptr::null(), |t| t.as_ptr());
        ext!(self, "glLabelObjectEXT", fn(u32, u32, i32, *const u8) -> (), *object_type, object, *length, p);
        Ok(())
    }

    pub(super) fn glGetObjectLabelEXT(
        &mut self,
        object_type: &GLenum,
        object: &GLuint,
        buf_size: &GLsizei,
    ) -> Result<Option<Bytes>, ClientError> {
        let object = self.object_for(*object_type, *object);
        let mut buf = vec![0u8; (*buf_size).max(1) as usize];
        // Left at -1 when the call fails with a GL error.
        let mut len = -1i32;
        ext!(
            self,
            "glGetObjectLabelEXT",
            fn(u32, u32, i32, *mut i32, *mut u8) -> (),
            *object_type,
            object,
            *buf_size,
            &mut len,
            buf.as_mut_ptr()
        );
        buf.truncate(len.max(0) as usize);
        Ok((len >= 0).then_some(Bytes(buf)))
    }

    pub(super) fn glGetObjectPtrLabelKHR(
        &mut self,
        ptr: &u64,
        buf_size: &GLsizei,
    ) -> Result<Option<Bytes>, ClientError> {
        let _ = (ptr, buf_size);
        Err(unsupported(
            "glGetObjectPtrLabelKHR: sync objects are not part of ES 2.0, so the reference has none to label",
        ))
    }

    pub(super) fn strataDebugMessages(&mut self) -> Result<Vec<DebugMessage>, ClientError> {
        Err(unsupported("strataDebugMessages: the debug callback is the client library's; Mesa's log is read instead"))
    }
}

/// `text` as the C call expects it: with a negative length, NUL-terminated.
fn nul_terminated(text: &[u8], length: i32) -> Vec<u8> {
    let mut v = text.to_vec();
    if length < 0 {
        v.push(0);
    }
    v
}

//! The extension calls the Mesa reference forwards: `GL_OES_vertex_array_object` and
//! `GL_KHR_debug`, looked up with `eglGetProcAddress` (glvnd's libGLESv2 exports only core
//! entry points). The debug callback is the client library's, so `strataDebugCallback` and
//! `strataDebugMessages` have no Mesa counterpart and are not forwarded.

use std::ffi::CString;

use strata_client::ClientError;
use strata_protocol::{Bytes, Command, DebugMessage, Reply};

use super::{unsupported, MesaGl, Ptr};

impl MesaGl {
    /// Mesa's name for the client's vertex array `n` (one Mesa never generated if it has none).
    fn vao(&self, n: u32) -> u32 {
        self.vaos.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    /// Mesa's name for object `name` in label namespace `identifier`.
    fn object_for(&self, identifier: u32, name: u32) -> u32 {
        match identifier {
            0x82E1 | 0x82E2 => self.shader(name),
            0x8074 => self.vao(name),
            _ => name,
        }
    }

    /// An extension entry point, by `eglGetProcAddress`.
    fn ext(&mut self, name: &'static str) -> Result<Ptr, ClientError> {
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
    ($self:ident, $name:literal, fn($($t:ty),*) -> $r:ty, $($a:expr),*) => {{
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

/// Forwards an asynchronous extension command.
pub(super) fn send(m: &mut MesaGl, cmd: &Command<'_>) -> Result<(), ClientError> {
    use Command as C;
    match cmd {
        C::GenVertexArraysOES { names } => {
            for n in names.iter() {
                let mut real = 0u32;
                ext!(m, "glGenVertexArraysOES", fn(i32, *mut u32) -> (), 1, &mut real);
                m.vaos.insert(n, real);
            }
        }
        C::BindVertexArrayOES { array } => {
            let a = m.vao(*array);
            ext!(m, "glBindVertexArrayOES", fn(u32) -> (), a)
        }
        C::DeleteVertexArraysOES { names } => {
            let v: Vec<u32> = names.iter().map(|n| m.vao(n)).collect();
            for n in names.iter() {
                m.vaos.remove(&n);
            }
            ext!(m, "glDeleteVertexArraysOES", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr())
        }
        C::DebugMessageControlKHR { source, ty, severity, count, ids, enabled } => {
            let v = ids.to_vec();
            let p = if v.is_empty() { std::ptr::null() } else { v.as_ptr() };
            ext!(
                m,
                "glDebugMessageControlKHR",
                fn(u32, u32, u32, i32, *const u32, u8) -> (),
                *source,
                *ty,
                *severity,
                *count,
                p,
                u8::from(*enabled)
            )
        }
        C::DebugMessageInsertKHR { source, ty, id, severity, length, text } => {
            let z = nul_terminated(text.as_bytes(), *length);
            ext!(
                m,
                "glDebugMessageInsertKHR",
                fn(u32, u32, u32, u32, i32, *const u8) -> (),
                *source,
                *ty,
                *id,
                *severity,
                *length,
                z.as_ptr()
            )
        }
        C::PushDebugGroupKHR { source, id, length, text } => {
            let z = nul_terminated(text.as_bytes(), *length);
            ext!(m, "glPushDebugGroupKHR", fn(u32, u32, i32, *const u8) -> (), *source, *id, *length, z.as_ptr())
        }
        C::PopDebugGroupKHR {} => ext!(m, "glPopDebugGroupKHR", fn() -> (),),
        C::ObjectLabelKHR { identifier, name, length, label } => {
            let z = label.as_ref().map(|l| nul_terminated(l.as_bytes(), *length));
            let p = text_ptr(z.as_deref());
            let (identifier, name) = (*identifier, m.object_for(*identifier, *name));
            ext!(m, "glObjectLabelKHR", fn(u32, u32, i32, *const u8) -> (), identifier, name, *length, p)
        }
        other => return Err(unsupported(other.opcode().name())),
    }
    Ok(())
}

/// Forwards a synchronous extension command; `None` if it is not one.
pub(super) fn call(m: &mut MesaGl, cmd: &Command<'_>) -> Option<Result<Reply, ClientError>> {
    use Command as C;
    let r = (|| {
        Ok(match cmd {
            C::IsVertexArrayOES { array } => {
                let a = m.vao(*array);
                Reply::IsVertexArrayOES(ext!(m, "glIsVertexArrayOES", fn(u32) -> u8, a) != 0)
            }
            // The binding in the client's names.
            C::GetIntegerv { pname: 0x85B5 } => {
                let mut v = 0i32;
                call!(m, "glGetIntegerv", fn(u32, *mut i32) -> (), 0x85B5, &mut v);
                let client = m.vaos.iter().find(|(_, &real)| real as i32 == v).map_or(v, |(&c, _)| c as i32);
                Reply::GetIntegerv(vec![client])
            }
            C::GetObjectLabelKHR { identifier, name, buf_size } => {
                let name = m.object_for(*identifier, *name);
                let mut buf = vec![0u8; (*buf_size).max(1) as usize];
                // Left at -1 when the call fails with a GL error.
                let mut len = -1i32;
                ext!(
                    m,
                    "glGetObjectLabelKHR",
                    fn(u32, u32, i32, *mut i32, *mut u8) -> (),
                    *identifier,
                    name,
                    *buf_size,
                    &mut len,
                    buf.as_mut_ptr()
                );
                buf.truncate(len.max(0) as usize);
                Reply::GetObjectLabelKHR((len >= 0).then_some(Bytes(buf)))
            }
            C::GetDebugMessageLogKHR { count, buf_size, log } => {
                let n = *count as usize;
                let (mut sources, mut types, mut ids, mut severities, mut lengths) =
                    (vec![0u32; n], vec![0u32; n], vec![0u32; n], vec![0u32; n], vec![0i32; n]);
                let mut text = vec![0u8; (*buf_size).max(0) as usize];
                let tp = if *log { text.as_mut_ptr() } else { std::ptr::null_mut() };
                let got = ext!(
                    m,
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
                    let t =
                        if *log { text.get(at..at + len).map(<[u8]>::to_vec).unwrap_or_default() } else { Vec::new() };
                    at += len + 1;
                    out.push(DebugMessage {
                        source: sources[i],
                        ty: types[i],
                        id: ids[i],
                        severity: severities[i],
                        text: Bytes(t),
                    });
                }
                Reply::GetDebugMessageLogKHR(out)
            }
            _ => return Err(unsupported("")),
        })
    })();
    match r {
        Err(ClientError::Unsupported(why)) if why.ends_with("forward ") => None,
        r => Some(r),
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

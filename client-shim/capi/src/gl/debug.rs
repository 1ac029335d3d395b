//! `GL_KHR_debug`'s entry points (and `GL_EXT_debug_label`'s): message control and insertion,
//! the callback, the message log, debug groups and object labels. The daemon keeps everything
//! but the callback and the two enables the library needs to deliver messages to it, which
//! the context keeps (see `gl/debug_callback.rs`).

use std::ffi::c_void;

use strata_protocol::commands::{MAX_DEBUG_MESSAGE_LENGTH, MAX_LABEL_LENGTH};
use strata_protocol::{Blob, Calls};

use super::with_gl;
use crate::gl_state::DebugProc;
use crate::types::*;

/// `GL_DEBUG_OUTPUT_KHR`.
const GL_DEBUG_OUTPUT: GLenum = 0x92E0;
/// `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR`.
const GL_DEBUG_OUTPUT_SYNCHRONOUS: GLenum = 0x8242;
/// `GL_DEBUG_CALLBACK_FUNCTION_KHR`.
const GL_DEBUG_CALLBACK_FUNCTION: GLenum = 0x8244;
/// `GL_DEBUG_CALLBACK_USER_PARAM_KHR`.
const GL_DEBUG_CALLBACK_USER_PARAM: GLenum = 0x8245;

/// The text an application passes with a length: `length` bytes, or with a negative `length`
/// the bytes before the NUL; at most `max` of either, which is enough for the daemon to refuse
/// a text that is too long.
///
/// # Safety
/// A non-null `text` must hold `length` bytes, or be NUL-terminated when `length` is negative.
unsafe fn text<'a>(text: *const GLchar, length: GLsizei, max: GLsizei) -> &'a [u8] {
    if text.is_null() {
        return &[];
    }
    let max = max.max(0) as usize;
    let n = if length >= 0 {
        (length as usize).min(max)
    } else {
        // A bounded strlen: the text may be longer than `max`, and may not even end.
        // SAFETY: a NUL-terminated string is readable up to its NUL.
        (0..max).find(|&i| unsafe { *text.add(i) } == 0).unwrap_or(max)
    };
    // SAFETY: `n` bytes are readable, as established above.
    unsafe { std::slice::from_raw_parts(text.cast::<u8>(), n) }
}

/// Copies a label as `glGetObjectLabelKHR` specifies: with a null `label` only the length;
/// otherwise at most `buf_size - 1` bytes and a NUL.
///
/// # Safety
/// `label` (if non-null) must have room for `buf_size` bytes; `length` (if non-null) an int.
unsafe fn copy_label(s: &[u8], buf_size: GLsizei, length: *mut GLsizei, label: *mut GLchar) {
    let n = if label.is_null() {
        s.len()
    } else {
        let n = s.len().min((buf_size.max(1) - 1) as usize);
        if buf_size > 0 {
            // SAFETY: see the function's contract.
            unsafe {
                std::ptr::copy_nonoverlapping(s.as_ptr().cast::<GLchar>(), label, n);
                *label.add(n) = 0;
            }
        }
        n
    };
    if !length.is_null() {
        // SAFETY: see the function's contract.
        unsafe { *length = n as GLsizei };
    }
}

/// Tracks the two debug enables the library needs, and forwards the call.
fn set_enabled(name: &'static str, cap: GLenum, on: bool) {
    with_gl(name, (), |gl| {
        match cap {
            GL_DEBUG_OUTPUT => gl.st.debug.output = on,
            GL_DEBUG_OUTPUT_SYNCHRONOUS => gl.st.debug.synchronous = on,
            // GL_PRIMITIVE_RESTART_FIXED_INDEX (ES 3.0).
            0x8D69 => gl.st.restart = on,
            _ => {}
        }
        if on {
            gl.conn.glEnable(cap)
        } else {
            gl.conn.glDisable(cap)
        }
    })
}

/// Writes `v` to an optional application array at `i`.
///
/// # Safety
/// A non-null `arr` must have room for more than `i` values.
unsafe fn put_at<T>(arr: *mut T, i: usize, v: T) {
    if !arr.is_null() {
        // SAFETY: see the function's contract.
        unsafe { *arr.add(i) = v };
    }
}

crate::entry::entry_points! {
    /// Forwarded; the library also notes `GL_DEBUG_OUTPUT_KHR` and its synchronous variant.
    fn glEnable(cap: GLenum) {
        set_enabled("glEnable", cap, true)
    }

    /// Forwarded; the library also notes `GL_DEBUG_OUTPUT_KHR` and its synchronous variant.
    fn glDisable(cap: GLenum) {
        set_enabled("glDisable", cap, false)
    }

    /// The first `count` ids travel with the call.
    fn glDebugMessageControlKHR(source: GLenum, ty: GLenum, severity: GLenum, count: GLsizei, ids: *const GLuint, enabled: GLboolean) {
        with_gl("glDebugMessageControlKHR", (), |gl| {
            let v: &[GLuint] = if ids.is_null() || count <= 0 {
                &[]
            } else {
                // SAFETY: the application passes `count` ids.
                unsafe { std::slice::from_raw_parts(ids, count as usize) }
            };
            gl.conn.glDebugMessageControlKHR(source, ty, severity, count, strata_protocol::Slice::new(v), enabled != 0)
        })
    }

    /// The message's text travels with the call.
    fn glDebugMessageInsertKHR(source: GLenum, ty: GLenum, id: GLuint, severity: GLenum, length: GLsizei, buf: *const GLchar) {
        with_gl("glDebugMessageInsertKHR", (), |gl| {
            // SAFETY: `buf` holds `length` bytes, or is NUL-terminated.
            let t = unsafe { text(buf, length, MAX_DEBUG_MESSAGE_LENGTH) };
            gl.conn.glDebugMessageInsertKHR(source, ty, id, severity, length, Blob::borrowed(t))
        })
    }

    /// Installs (or with NULL removes) the callback, which runs in this process.
    fn glDebugMessageCallbackKHR(callback: DebugProc, user_param: *const c_void) {
        with_gl("glDebugMessageCallbackKHR", (), |gl| {
            gl.st.debug.callback = callback;
            gl.st.debug.user = user_param as usize;
            gl.conn.strataDebugCallback(callback.is_some())
        })
    }

    /// Fetches up to `count` logged messages into the application's arrays.
    fn glGetDebugMessageLogKHR(
        count: GLuint,
        buf_size: GLsizei,
        sources: *mut GLenum,
        types: *mut GLenum,
        ids: *mut GLuint,
        severities: *mut GLenum,
        lengths: *mut GLsizei,
        message_log: *mut GLchar,
    ) -> GLuint {
        with_gl("glGetDebugMessageLogKHR", 0, |gl| {
            let messages = gl.conn.glGetDebugMessageLogKHR(count, buf_size, !message_log.is_null())?;
            let mut at = 0usize;
            for (i, m) in messages.iter().enumerate() {
                let text = &m.text.0;
                // SAFETY: the application's arrays have room for `count` entries, and its log
                // for `buf_size` bytes, which the daemon kept the messages within.
                unsafe {
                    put_at(sources, i, m.source);
                    put_at(types, i, m.ty);
                    put_at(ids, i, m.id);
                    put_at(severities, i, m.severity);
                    put_at(lengths, i, text.len() as GLsizei + 1);
                    if !message_log.is_null() {
                        std::ptr::copy_nonoverlapping(text.as_ptr().cast::<GLchar>(), message_log.add(at), text.len());
                        *message_log.add(at + text.len()) = 0;
                    }
                }
                at += text.len() + 1;
            }
            Ok(messages.len() as GLuint)
        })
    }

    /// The group's message travels with the call.
    fn glPushDebugGroupKHR(source: GLenum, id: GLuint, length: GLsizei, message: *const GLchar) {
        with_gl("glPushDebugGroupKHR", (), |gl| {
            // SAFETY: `message` holds `length` bytes, or is NUL-terminated.
            let t = unsafe { text(message, length, MAX_DEBUG_MESSAGE_LENGTH) };
            gl.conn.glPushDebugGroupKHR(source, id, length, Blob::borrowed(t))
        })
    }

    /// Pops the active debug group.
    fn glPopDebugGroupKHR() {
        with_gl("glPopDebugGroupKHR", (), |gl| gl.conn.glPopDebugGroupKHR())
    }

    /// The label travels with the call (NULL removes it).
    fn glObjectLabelKHR(identifier: GLenum, name: GLuint, length: GLsizei, label: *const GLchar) {
        with_gl("glObjectLabelKHR", (), |gl| {
            // SAFETY: `label` holds `length` bytes, or is NUL-terminated.
            let t = (!label.is_null()).then(|| Blob::borrowed(unsafe { text(label, length, MAX_LABEL_LENGTH) }));
            gl.conn.glObjectLabelKHR(identifier, name, length, t)
        })
    }

    /// The label, truncated to `buf_size`.
    fn glGetObjectLabelKHR(identifier: GLenum, name: GLuint, buf_size: GLsizei, length: *mut GLsizei, label: *mut GLchar) {
        with_gl("glGetObjectLabelKHR", (), |gl| {
            if let Some(s) = gl.conn.glGetObjectLabelKHR(identifier, name, buf_size)? {
                // SAFETY: out-pointers as the extension specifies.
                unsafe { copy_label(&s.0, buf_size, length, label) };
            }
            Ok(())
        })
    }

    /// `GL_EXT_debug_label`: a length of 0 sends the whole NUL-terminated label; a negative
    /// one nothing (the daemon reports the error).
    fn glLabelObjectEXT(object_type: GLenum, object: GLuint, length: GLsizei, label: *const GLchar) {
        with_gl("glLabelObjectEXT", (), |gl| {
            let len = if length == 0 { -1 } else { length };
            // SAFETY: `label` holds `length` bytes, or is NUL-terminated.
            let t = (!label.is_null() && length >= 0).then(|| Blob::borrowed(unsafe { text(label, len, MAX_LABEL_LENGTH) }));
            gl.conn.glLabelObjectEXT(object_type, object, length, t)
        })
    }

    /// `GL_EXT_debug_label`: the label truncated to `buf_size`, and with a `buf_size` of 0 only
    /// its whole length.
    fn glGetObjectLabelEXT(object_type: GLenum, object: GLuint, buf_size: GLsizei, length: *mut GLsizei, label: *mut GLchar) {
        with_gl("glGetObjectLabelEXT", (), |gl| {
            if let Some(s) = gl.conn.glGetObjectLabelEXT(object_type, object, buf_size)? {
                let label = if buf_size == 0 { std::ptr::null_mut() } else { label };
                // SAFETY: out-pointers as the extension specifies.
                unsafe { copy_label(&s.0, buf_size, length, label) };
            }
            Ok(())
        })
    }

    /// Labels a sync object (ES 2.0 has none: the daemon reports the error).
    fn glObjectPtrLabelKHR(ptr: *const c_void, length: GLsizei, label: *const GLchar) {
        with_gl("glObjectPtrLabelKHR", (), |gl| {
            // SAFETY: `label` holds `length` bytes, or is NUL-terminated.
            let t = (!label.is_null()).then(|| Blob::borrowed(unsafe { text(label, length, MAX_LABEL_LENGTH) }));
            gl.conn.glObjectPtrLabelKHR(ptr as usize as u64, length, t)
        })
    }

    /// A sync object's label (ES 2.0 has none: the daemon reports the error).
    fn glGetObjectPtrLabelKHR(ptr: *const c_void, buf_size: GLsizei, length: *mut GLsizei, label: *mut GLchar) {
        with_gl("glGetObjectPtrLabelKHR", (), |gl| {
            if let Some(s) = gl.conn.glGetObjectPtrLabelKHR(ptr as usize as u64, buf_size)? {
                // SAFETY: out-pointers as the extension specifies.
                unsafe { copy_label(&s.0, buf_size, length, label) };
            }
            Ok(())
        })
    }

    /// The debug callback and its user parameter, which the library holds.
    fn glGetPointervKHR(pname: GLenum, params: *mut *mut c_void) {
        with_gl("glGetPointervKHR", (), |gl| {
            let v = match pname {
                GL_DEBUG_CALLBACK_FUNCTION => gl.st.debug.callback.map_or(std::ptr::null_mut(), |f| f as *mut c_void),
                GL_DEBUG_CALLBACK_USER_PARAM => gl.st.debug.user as *mut c_void,
                _ => {
                    gl.st.err(GL_INVALID_ENUM);
                    return Ok(());
                }
            };
            if !params.is_null() {
                // SAFETY: `params` points at one pointer.
                unsafe { *params = v };
            }
            Ok(())
        })
    }
}

/// Reads a NUL-terminated C string for logging (tests).
#[cfg(test)]
fn c_text(p: *const GLchar) -> String {
    // SAFETY: the tests pass NUL-terminated strings.
    unsafe { std::ffi::CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texts_are_bounded_and_labels_truncate_as_specified() {
        let s = c"hello";
        // SAFETY: a NUL-terminated literal.
        assert_eq!(unsafe { text(s.as_ptr(), -1, 100) }, b"hello");
        // SAFETY: as above; the bound stops the scan before the NUL.
        assert_eq!(unsafe { text(s.as_ptr(), -1, 3) }, b"hel");
        // SAFETY: five readable bytes.
        assert_eq!(unsafe { text(s.as_ptr(), 2, 100) }, b"he");
        let mut out = [1 as GLchar; 8];
        let mut len = -1;
        // SAFETY: an eight-byte buffer and an int.
        unsafe { copy_label(b"Test Label", 5, &mut len, out.as_mut_ptr()) };
        assert_eq!((c_text(out.as_ptr()), len), ("Test".to_string(), 4));
        // SAFETY: a null label and an int.
        unsafe { copy_label(b"Test Label", 5, &mut len, std::ptr::null_mut()) };
        assert_eq!(len, 10, "a null label reports the whole length");
    }
}

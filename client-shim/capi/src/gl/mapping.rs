//! `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range`. The daemon validates each map and answers
//! the mapped bytes; the library hands the application memory of its own holding them. What
//! the application changed goes back at `glFlushMappedBufferRangeEXT` (for a map with
//! `GL_MAP_FLUSH_EXPLICIT_BIT_EXT`) or at `glUnmapBufferOES`: the span from the first to the
//! last byte that differs from what the daemon answered, or the whole range where the map
//! invalidated it (its old bytes are not fetched, so a byte written unchanged cannot be told
//! from one not written). That memory, and what the daemon answered, is a `Mapping` (in
//! `gl_state.rs`), which the process keeps by buffer name.

use std::collections::HashMap;
use std::ffi::c_void;

use strata_protocol::{Blob, Calls};

use super::{put, with_gl, Gl};
use crate::gl_state::{Mapping, MAP_FLUSH_EXPLICIT, MAP_WRITE};
use crate::types::*;

/// Copies `bytes` written at `offset` into the process's shadow of buffer `name`.
fn shadow_write(shadows: &mut HashMap<u32, Vec<u8>>, name: u32, offset: usize, bytes: &[u8]) {
    if let Some(dst) = shadows.get_mut(&name).and_then(|s| s.get_mut(offset..offset + bytes.len())) {
        dst.copy_from_slice(bytes);
    }
}

/// Records the mapping the daemon accepted for the buffer bound to `target`; its pointer.
fn hand_out(gl: &mut Gl<'_>, target: GLenum, m: Mapping) -> *mut c_void {
    match gl.st.bound(target) {
        Some(name) => {
            gl.maps.insert(name, m);
            gl.maps.get_mut(&name).map_or(std::ptr::null_mut(), Mapping::ptr)
        }
        None => std::ptr::null_mut(),
    }
}

crate::entry::entry_points! {
    /// `GL_OES_mapbuffer`: the whole buffer, to write.
    fn glMapBufferOES(target: GLenum, access: GLenum) -> *mut c_void {
        with_gl("glMapBufferOES", std::ptr::null_mut(), |gl| {
            let Some(bytes) = gl.conn.glMapBufferOES(target, access)? else { return Ok(std::ptr::null_mut()) };
            let m = Mapping::new(0, bytes.0.len(), MAP_WRITE, bytes.0);
            Ok(hand_out(gl, target, m))
        })
    }

    /// `GL_EXT_map_buffer_range`: `length` bytes at `offset`, with `access`.
    fn glMapBufferRangeEXT(target: GLenum, offset: GLintptr, length: GLsizeiptr, access: GLbitfield) -> *mut c_void {
        with_gl("glMapBufferRangeEXT", std::ptr::null_mut(), |gl| {
            let reply = gl.conn.glMapBufferRangeEXT(target, offset as i64, length as i64, access)?;
            let Some(bytes) = reply else { return Ok(std::ptr::null_mut()) };
            // The daemon accepted the range: both are non-negative.
            let m = Mapping::new(offset as usize, length as usize, access, bytes.0);
            Ok(hand_out(gl, target, m))
        })
    }

    /// `GL_EXT_map_buffer_range`: sends the flushed range of an explicitly flushed mapping.
    fn glFlushMappedBufferRangeEXT(target: GLenum, offset: GLintptr, length: GLsizeiptr) {
        with_gl("glFlushMappedBufferRangeEXT", (), |gl| {
            let name = gl.st.bound(target).unwrap_or(0);
            let flushed = gl.maps.get(&name).filter(|m| m.access & MAP_FLUSH_EXPLICIT != 0).and_then(|m| {
                let (o, l) = (usize::try_from(offset).ok()?, usize::try_from(length).ok()?);
                m.bytes().get(o..o.checked_add(l)?).map(|b| (m.offset + o, b))
            });
            // A flush the mapping does not allow goes without bytes: the daemon reports it.
            let (at, data) = flushed.unwrap_or((0, &[]));
            gl.conn.glFlushMappedBufferRangeEXT(target, offset as i64, length as i64, Blob::borrowed(data))?;
            shadow_write(gl.shadows, name, at, data);
            Ok(())
        })
    }

    /// `GL_OES_mapbuffer`: ends the mapping, sending what the application changed.
    fn glUnmapBufferOES(target: GLenum) -> GLboolean {
        with_gl("glUnmapBufferOES", 0, |gl| {
            let name = gl.st.bound(target).unwrap_or(0);
            let m = gl.maps.remove(&name);
            let (at, data) = m.as_ref().map_or((0, &[][..]), Mapping::written);
            gl.conn.glUnmapBufferOES(target, at as i64, Blob::borrowed(data))?;
            shadow_write(gl.shadows, name, at, data);
            Ok(GLboolean::from(m.is_some()))
        })
    }

    /// `GL_OES_mapbuffer`: the mapped pointer (null when not mapped).
    fn glGetBufferPointervOES(target: GLenum, pname: GLenum, params: *mut *mut c_void) {
        with_gl("glGetBufferPointervOES", (), |gl| {
            let Some(name) = gl.st.bound(target).filter(|_| pname == GL_BUFFER_MAP_POINTER_OES) else {
                gl.st.err(GL_INVALID_ENUM);
                return Ok(());
            };
            if name == 0 {
                gl.st.err(GL_INVALID_OPERATION);
                return Ok(());
            }
            let ptr = gl.maps.get_mut(&name).map_or(std::ptr::null_mut(), Mapping::ptr);
            // SAFETY: `params` points at one pointer.
            unsafe { put(params, ptr) };
            Ok(())
        })
    }
}

//! `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range`. The daemon validates each map and answers
//! the mapped bytes; the library hands the application memory of its own holding them. What
//! the application changed goes back at `glFlushMappedBufferRangeEXT` (for a map with
//! `GL_MAP_FLUSH_EXPLICIT_BIT_EXT`) or at `glUnmapBufferOES`: the span from the first to the
//! last byte that differs from what the daemon answered, or the whole range where the map
//! invalidated it (its old bytes are not fetched, so a byte written unchanged cannot be told
//! from one not written).

use super::*;

/// `GL_MAP_WRITE_BIT_EXT`.
const MAP_WRITE: u32 = 0x2;
/// `GL_MAP_FLUSH_EXPLICIT_BIT_EXT`.
const MAP_FLUSH_EXPLICIT: u32 = 0x10;
/// The alignment of a mapping's pointer less its offset, as on Mesa (`GL_MIN_MAP_BUFFER_ALIGNMENT`).
const ALIGN: usize = 64;

/// A mapped buffer as the library holds it.
pub(crate) struct Mapping {
    /// The memory handed out is `mem[start..start + length]`.
    mem: Vec<u8>,
    /// Where the handed-out memory starts in `mem`: its address less the mapped offset is a
    /// multiple of [`ALIGN`].
    start: usize,
    /// The mapped bytes.
    length: usize,
    /// The mapped range's first byte in the buffer.
    offset: usize,
    /// The bytes as the daemon answered them; `None` where the map invalidated them.
    before: Option<Vec<u8>>,
    /// The map's `GL_MAP_*_BIT_EXT` flags.
    access: u32,
}

impl Mapping {
    /// Memory for `length` bytes at `offset` holding `answered` (empty: invalidated).
    fn new(offset: usize, length: usize, access: u32, answered: Vec<u8>) -> Mapping {
        let mut mem = vec![0u8; length + ALIGN];
        let base = mem.as_ptr() as usize % ALIGN;
        let start = (offset % ALIGN + ALIGN - base) % ALIGN;
        let before = (answered.len() == length).then(|| {
            mem[start..start + length].copy_from_slice(&answered);
            answered
        });
        Mapping { mem, start, length, offset, before, access }
    }

    /// The pointer handed to the application.
    fn ptr(&mut self) -> *mut c_void {
        self.mem[self.start..].as_mut_ptr().cast()
    }

    /// The mapped bytes as the application left them.
    fn bytes(&self) -> &[u8] {
        &self.mem[self.start..self.start + self.length]
    }

    /// What `glUnmapBufferOES` writes back: the buffer offset and the bytes changed (none for a
    /// map that only reads, or whose writes were flushed explicitly).
    fn written(&self) -> (usize, &[u8]) {
        if self.access & MAP_WRITE == 0 || self.access & MAP_FLUSH_EXPLICIT != 0 {
            return (0, &[]);
        }
        let now = self.bytes();
        let Some(before) = &self.before else { return (self.offset, now) };
        let differs = |(a, b): (&u8, &u8)| a != b;
        match (now.iter().zip(before).position(differs), now.iter().zip(before).rposition(differs)) {
            (Some(first), Some(last)) => (self.offset + first, &now[first..=last]),
            _ => (0, &[]),
        }
    }
}

/// Copies `bytes` written at `offset` into the context's shadow of buffer `name`.
fn shadow_write(st: &mut GlState, name: u32, offset: usize, bytes: &[u8]) {
    if let Some(dst) = st.buffers.get_mut(&name).and_then(|s| s.get_mut(offset..offset + bytes.len())) {
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

crate::entry_points! {
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
            shadow_write(gl.st, name, at, data);
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
            shadow_write(gl.st, name, at, data);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The handed-out pointer less the offset is aligned, and only the bytes that changed go
    /// back: none for an unchanged or read-only map, all for an invalidated one.
    #[test]
    fn mappings_align_and_send_back_what_changed() {
        for offset in [0, 1, 63, 64, 100] {
            let mut m = Mapping::new(offset, 8, MAP_WRITE, vec![7; 8]);
            assert_eq!((m.ptr() as usize).wrapping_sub(offset) % ALIGN, 0, "offset {offset}");
            assert_eq!(m.written(), (0, &[][..]));
            m.mem[m.start + 2] = 1;
            m.mem[m.start + 5] = 2;
            assert_eq!(m.written(), (offset + 2, &[1, 7, 7, 2][..]));
        }
        let mut read = Mapping::new(0, 4, 0x1, vec![1; 4]);
        read.mem[read.start] = 9;
        assert_eq!(read.written(), (0, &[][..]));
        let invalidated = Mapping::new(4, 3, MAP_WRITE | 0x4, Vec::new());
        assert_eq!(invalidated.written(), (4, &[0, 0, 0][..]));
        let explicit = Mapping::new(0, 2, MAP_WRITE | MAP_FLUSH_EXPLICIT, vec![0; 2]);
        assert_eq!(explicit.written(), (0, &[][..]));
    }
}

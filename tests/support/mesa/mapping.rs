//! `GL_OES_mapbuffer` and `GL_EXT_map_buffer_range` as the protocol carries them: a map answers
//! the mapped bytes (none where the map invalidates them), and the bytes an application wrote
//! come back with the flush or the unmap, which write them through Mesa's own mapping first.

use strata_client::ClientError;
use strata_protocol::wire::*;
use strata_protocol::{Blob, Bytes};

use super::{Arms, Ptr};

/// `GL_BUFFER_MAP_POINTER_OES`.
const MAP_POINTER: u32 = 0x88BD;
/// `GL_BUFFER_MAP_OFFSET` and `GL_BUFFER_MAP_LENGTH`.
const MAP_OFFSET: u32 = 0x9121;
const MAP_LENGTH: u32 = 0x9120;
/// `GL_BUFFER_SIZE`.
const BUFFER_SIZE: u32 = 0x8764;
/// `GL_MAP_INVALIDATE_RANGE_BIT_EXT | GL_MAP_INVALIDATE_BUFFER_BIT_EXT`.
const INVALIDATES: u32 = 0x4 | 0x8;

impl Arms<'_> {
    /// A buffer parameter of `target`'s buffer.
    fn buffer_int(&mut self, target: u32, pname: u32) -> Result<i32, ClientError> {
        let mut v = 0i32;
        call!(self, "glGetBufferParameteriv", fn(u32, u32, *mut i32) -> (), target, pname, &mut v);
        Ok(v)
    }

    /// Writes `data` at buffer offset `at` through Mesa's mapping of `target`'s buffer, where
    /// it lies within it.
    fn write_mapped(&mut self, target: u32, at: i64, data: &[u8]) -> Result<(), ClientError> {
        if data.is_empty() {
            return Ok(());
        }
        let mut p: Ptr = std::ptr::null();
        ext!(self, "glGetBufferPointervOES", fn(u32, u32, *mut Ptr) -> (), target, MAP_POINTER, &mut p);
        let (offset, length) = (self.buffer_int(target, MAP_OFFSET)?, self.buffer_int(target, MAP_LENGTH)?);
        let start = at - i64::from(offset);
        if !p.is_null() && start >= 0 && start + data.len() as i64 <= i64::from(length) {
            // SAFETY: the range lies within Mesa's mapping, which is writable memory.
            unsafe { std::ptr::copy_nonoverlapping(data.as_ptr(), (p as *mut u8).add(start as usize), data.len()) };
        }
        Ok(())
    }

    /// The `len` bytes at `p`, or none for a failed map.
    fn answered(p: Ptr, len: i64) -> Option<Bytes> {
        // SAFETY: a non-null map holds `len` bytes.
        (!p.is_null()).then(|| Bytes(unsafe { std::slice::from_raw_parts(p as *const u8, len as usize) }.to_vec()))
    }

    pub(super) fn glMapBufferOES(&mut self, target: &GLenum, access: &GLenum) -> Result<Option<Bytes>, ClientError> {
        let p = ext!(self, "glMapBufferOES", fn(u32, u32) -> Ptr, *target, *access);
        let size = if p.is_null() { 0 } else { self.buffer_int(*target, BUFFER_SIZE)? };
        Ok(Self::answered(p, i64::from(size)))
    }

    pub(super) fn glMapBufferRangeEXT(
        &mut self,
        target: &GLenum,
        offset: &i64,
        length: &i64,
        access: &GLbitfield,
    ) -> Result<Option<Bytes>, ClientError> {
        let p = ext!(
            self,
            "glMapBufferRangeEXT",
            fn(u32, isize, isize, u32) -> Ptr,
            *target,
            *offset as isize,
            *length as isize,
            *access
        );
        let shown = if *access & INVALIDATES != 0 { 0 } else { *length };
        Ok(Self::answered(p, shown))
    }

    pub(super) fn glFlushMappedBufferRangeEXT(
        &mut self,
        target: &GLenum,
        offset: &i64,
        length: &i64,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        if data.len() as i64 == *length && *offset >= 0 {
            let at = i64::from(self.buffer_int(*target, MAP_OFFSET)?) + offset;
            self.write_mapped(*target, at, data.as_bytes())?;
        }
        ext!(
            self,
            "glFlushMappedBufferRangeEXT",
            fn(u32, isize, isize) -> (),
            *target,
            *offset as isize,
            *length as isize
        );
        Ok(())
    }

    pub(super) fn glUnmapBufferOES(
        &mut self,
        target: &GLenum,
        offset: &i64,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        self.write_mapped(*target, *offset, data.as_bytes())?;
        ext!(self, "glUnmapBufferOES", fn(u32) -> u8, *target);
        Ok(())
    }
}

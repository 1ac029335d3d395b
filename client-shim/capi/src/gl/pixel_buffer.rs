//! `GL_NV_pixel_buffer_object`: while a buffer is bound to `GL_PIXEL_UNPACK_BUFFER_NV`, an
//! upload's pointer is an offset into it, and while one is bound to `GL_PIXEL_PACK_BUFFER_NV`,
//! `glReadPixels` writes into it. The library keeps every buffer's contents (the shadow), so
//! it reads uploads from the shadow and writes reads into the buffer as `glBufferSubData`
//! does, shadow included. As on Mesa, a range past the buffer's end, an offset that is not a
//! multiple of the type's size, or a mapped buffer is `GL_INVALID_OPERATION`.

use std::ffi::c_void;

use strata_client::ClientError;
use strata_protocol::{Blob, Calls};

use super::pixels::{packed_rows, pixel_size, upload_size};
use super::{type_size, Gl};
use crate::types::*;

/// Bytes of one element of `ty` (a packed type's whole pixel): what an offset must be a
/// multiple of.
pub(super) fn element_size(ty: GLenum) -> usize {
    match ty {
        0x8363 | 0x8033 | 0x8034 | 0x8365 | 0x8366 => 2,
        0x84FA | 0x8368 => 4,
        _ => type_size(ty).unwrap_or(1),
    }
}

/// The `len` bytes at `offset` of buffer `name`, for a transfer whose offsets must be multiples
/// of `align`; `None` (and `GL_INVALID_OPERATION`) for a mapped buffer or a range that does not
/// fit.
fn range(gl: &mut Gl<'_>, name: u32, offset: usize, len: usize, align: usize) -> Option<std::ops::Range<usize>> {
    let size = gl.shadows.get(&name).map_or(0, Vec::len);
    let fits = offset.is_multiple_of(align.max(1)) && offset.checked_add(len).is_some_and(|end| end <= size);
    if gl.maps.contains_key(&name) || !fits {
        gl.st.err(GL_INVALID_OPERATION);
        return None;
    }
    Some(offset..offset + len)
}

/// What an upload reads: `None` where no unpack buffer is bound (the pointer is the
/// application's), else the `len` bytes at offset `ptr` of the unpack buffer, or `Some(None)`
/// where they cannot be read (the error is recorded).
pub(super) fn unpack(gl: &mut Gl<'_>, ptr: *const c_void, len: usize, align: usize) -> Option<Option<Vec<u8>>> {
    let name = gl.st.unpack_buffer;
    if name == 0 {
        return None;
    }
    let r = range(gl, name, ptr as usize, len, align);
    Some(r.and_then(|r| gl.shadows.get(&name).and_then(|b| b.get(r)).map(<[u8]>::to_vec)))
}

/// The bytes an uncompressed upload of `width`×`height` `format`/`ty` pixels reads from the
/// unpack buffer: as [`unpack`], with `Some(Some(empty))` for a format the library does not
/// know (the daemon then refuses it).
pub(super) fn unpack_pixels(
    gl: &mut Gl<'_>,
    ptr: *const c_void,
    [width, height]: [GLsizei; 2],
    format: GLenum,
    ty: GLenum,
) -> Option<Option<Vec<u8>>> {
    if gl.st.unpack_buffer == 0 {
        return None;
    }
    let Some(bpp) = pixel_size(format, ty) else { return Some(Some(Vec::new())) };
    let len = upload_size(width, height, bpp, gl.st.unpack_alignment, gl.st.unpack_rows);
    unpack(gl, ptr, len, element_size(ty))
}

/// `glReadPixels` into the pack buffer at offset `ptr`, if one is bound (`false` if none is).
pub(super) fn pack(
    gl: &mut Gl<'_>,
    [x, y, width, height]: [GLint; 4],
    format: GLenum,
    ty: GLenum,
    ptr: *mut c_void,
) -> Result<bool, ClientError> {
    let name = gl.st.pack_buffer;
    if name == 0 {
        return Ok(false);
    }
    let data = gl.conn.glReadPixels(x, y, width, height, format, ty)?;
    let Some(bpp) = pixel_size(format, ty).filter(|_| !data.0.is_empty()) else { return Ok(true) };
    let rows: Vec<_> = packed_rows(&data.0, width as usize, height as usize, bpp, gl.st.pack).collect();
    let need = rows.iter().map(|(at, row)| at + row.len()).max().unwrap_or(0);
    let Some(r) = range(gl, name, ptr as usize, need, element_size(ty)) else { return Ok(true) };
    let Some(shadow) = gl.shadows.get_mut(&name) else { return Ok(true) };
    let dst = &mut shadow[r.clone()];
    for (at, row) in rows {
        dst[at..at + row.len()].copy_from_slice(row);
    }
    let bytes = dst.to_vec();
    gl.conn.glBufferSubData(PIXEL_PACK_BUFFER_NV, r.start as i64, Blob::borrowed(&bytes))?;
    Ok(true)
}

/// `GL_PIXEL_PACK_BUFFER_NV`.
pub(crate) const PIXEL_PACK_BUFFER_NV: GLenum = 0x88EB;
/// `GL_PIXEL_UNPACK_BUFFER_NV`.
pub(crate) const PIXEL_UNPACK_BUFFER_NV: GLenum = 0x88EC;

//! `GL_OES_texture_3D`: 3D images travel as their slices one after another, which the unpack
//! state lays out as one image of `height` × `depth` rows (ES 2.0 has no image height).

use std::ffi::c_void;

use strata_protocol::{Blob, Calls};

use super::pixel_buffer::{unpack, unpack_pixels};
use super::pixels::tex_image_bytes;
use super::{sized_bytes, with_gl, Gl};
use crate::types::*;

/// The rows an upload of `height` rows per slice and `depth` slices reads: none where a size
/// is not positive or beyond any 3D image (the daemon refuses such sizes before reading).
fn rows(width: GLsizei, height: GLsizei, depth: GLsizei) -> GLsizei {
    const MOST: GLsizei = 2048;
    if [width, height, depth].iter().any(|&n| !(1..=MOST).contains(&n)) {
        return 0;
    }
    height * depth
}

/// The pixels an upload of a `width`×`height`×`depth` box reads, from the unpack buffer or
/// the application (`None`: no data).
fn volume_bytes(
    gl: &mut Gl<'_>,
    [width, height, depth]: [GLsizei; 3],
    format: GLenum,
    ty: GLenum,
    pixels: *const c_void,
) -> Option<Vec<u8>> {
    let rows = rows(width, height, depth);
    if let Some(from) = unpack_pixels(gl, pixels, [width, rows], format, ty) {
        return from;
    }
    if rows == 0 {
        return (!pixels.is_null()).then(Vec::new);
    }
    tex_image_bytes(gl.st, width, rows, format, ty, pixels).map(<[u8]>::to_vec)
}

/// The bytes of compressed data the application passes: `image_size` of them; for a null
/// pointer (an image of undefined contents) as many zeros, so that the daemon checks the size
/// the application gave.
///
/// # Safety
/// `data` holds `image_size` bytes.
unsafe fn compressed(gl: &mut Gl<'_>, data: *const c_void, image_size: GLsizei) -> Option<Vec<u8>> {
    if let Some(from) = unpack(gl, data, image_size.max(0) as usize, 1) {
        return from;
    }
    if data.is_null() && image_size > 0 {
        return Some(vec![0; image_size as usize]);
    }
    // SAFETY: see the function's contract.
    unsafe { sized_bytes(gl.st, data, image_size as isize) }.map(<[u8]>::to_vec)
}

crate::entry::entry_points! {
    /// Copies the slices an upload of this size, format and alignment reads.
    fn glTexImage3DOES(
        target: GLenum,
        level: GLint,
        internalformat: GLenum,
        width: GLsizei,
        height: GLsizei,
        depth: GLsizei,
        border: GLint,
        format: GLenum,
        ty: GLenum,
        pixels: *const c_void,
    ) {
        with_gl("glTexImage3DOES", (), |gl| {
            let data = volume_bytes(gl, [width, height, depth], format, ty, pixels);
            let data = data.as_deref().map(Blob::borrowed);
            gl.conn.glTexImage3DOES(target, level, internalformat, width, height, depth, border, format, ty, data)
        })
    }

    /// Copies the slices a sub-image upload reads.
    fn glTexSubImage3DOES(
        target: GLenum,
        level: GLint,
        xoffset: GLint,
        yoffset: GLint,
        zoffset: GLint,
        width: GLsizei,
        height: GLsizei,
        depth: GLsizei,
        format: GLenum,
        ty: GLenum,
        pixels: *const c_void,
    ) {
        with_gl("glTexSubImage3DOES", (), |gl| {
            let data = volume_bytes(gl, [width, height, depth], format, ty, pixels).unwrap_or_default();
            gl.conn.glTexSubImage3DOES(
                target,
                level,
                xoffset,
                yoffset,
                zoffset,
                width,
                height,
                depth,
                format,
                ty,
                Blob::borrowed(&data),
            )
        })
    }

    /// Copies `image_size` bytes.
    fn glCompressedTexImage3DOES(
        target: GLenum,
        level: GLint,
        internalformat: GLenum,
        width: GLsizei,
        height: GLsizei,
        depth: GLsizei,
        border: GLint,
        image_size: GLsizei,
        data: *const c_void,
    ) {
        with_gl("glCompressedTexImage3DOES", (), |gl| {
            // SAFETY: `data` holds `image_size` bytes.
            let Some(d) = (unsafe { compressed(gl, data, image_size) }) else { return Ok(()) };
            let d = Blob::borrowed(&d);
            gl.conn.glCompressedTexImage3DOES(target, level, internalformat, width, height, depth, border, d)
        })
    }

    /// Copies `image_size` bytes.
    fn glCompressedTexSubImage3DOES(
        target: GLenum,
        level: GLint,
        xoffset: GLint,
        yoffset: GLint,
        zoffset: GLint,
        width: GLsizei,
        height: GLsizei,
        depth: GLsizei,
        format: GLenum,
        image_size: GLsizei,
        data: *const c_void,
    ) {
        with_gl("glCompressedTexSubImage3DOES", (), |gl| {
            // SAFETY: `data` holds `image_size` bytes.
            let Some(d) = (unsafe { compressed(gl, data, image_size) }) else { return Ok(()) };
            let d = Blob::borrowed(&d);
            gl.conn.glCompressedTexSubImage3DOES(target, level, xoffset, yoffset, zoffset, width, height, depth, format, d)
        })
    }

    /// Sent as it is.
    fn glCopyTexSubImage3DOES(
        target: GLenum,
        level: GLint,
        xoffset: GLint,
        yoffset: GLint,
        zoffset: GLint,
        x: GLint,
        y: GLint,
        width: GLsizei,
        height: GLsizei,
    ) {
        with_gl("glCopyTexSubImage3DOES", (), |gl| {
            gl.conn.glCopyTexSubImage3DOES(target, level, xoffset, yoffset, zoffset, x, y, width, height)
        })
    }

    /// Sent as it is.
    fn glFramebufferTexture3DOES(
        target: GLenum,
        attachment: GLenum,
        textarget: GLenum,
        texture: GLuint,
        level: GLint,
        zoffset: GLint,
    ) {
        with_gl("glFramebufferTexture3DOES", (), |gl| {
            gl.conn.glFramebufferTexture3DOES(target, attachment, textarget, texture, level, zoffset)
        })
    }
}

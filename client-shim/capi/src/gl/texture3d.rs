//! `GL_OES_texture_3D`: 3D images travel as their slices one after another, which the unpack
//! state lays out as one image of `height` × `depth` rows (ES 2.0 has no image height; ES 3.0's
//! `GL_UNPACK_IMAGE_HEIGHT` and `GL_UNPACK_SKIP_IMAGES` are resolved here, the slices gathered
//! into that layout).

use std::ffi::c_void;

use strata_protocol::{Blob, Calls};

use super::pixel_buffer::{unpack, unpack_pixels};
use super::pixels::{pixel_size, tex_image_bytes, upload_size};
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
    let data = !pixels.is_null() || gl.st.unpack_buffer != 0;
    if let Some(bpp) = pixel_size(format, ty).filter(|_| gl.st.unpack_images != [0, 0] && rows > 0 && data) {
        // Short data (a pixel buffer too small) reads as none: the daemon then refuses it.
        return Some(gathered(gl, [width, height, depth], (format, ty, bpp), pixels).unwrap_or_default());
    }
    if let Some(from) = unpack_pixels(gl, pixels, [width, rows], format, ty) {
        return from;
    }
    if rows == 0 {
        return (!pixels.is_null()).then(Vec::new);
    }
    tex_image_bytes(gl.st, width, rows, format, ty, pixels).map(<[u8]>::to_vec)
}

/// The slices of a `width`×`height`×`depth` upload of `bpp`-byte pixels laid out by ES 3.0's
/// image height and skipped images, gathered as the slices of an upload without them.
fn gathered(
    gl: &mut Gl<'_>,
    [width, height, depth]: [GLsizei; 3],
    (format, ty, bpp): (GLenum, GLenum, usize),
    pixels: *const c_void,
) -> Option<Vec<u8>> {
    let [image_height, skip_images] = gl.st.unpack_images;
    {
        // The images as the application lays them out: `skip_images` of `image_height` rows
        // first, then each slice that many rows after the last.
        let per_image = if image_height > 0 { image_height } else { height as usize };
        let span = skip_images.checked_add(depth as usize - 1)?.checked_mul(per_image)?.checked_add(height as usize)?;
        let span = GLsizei::try_from(span).ok()?;
        let source = match unpack_pixels(gl, pixels, [width, span], format, ty) {
            Some(from) => from?,
            None => tex_image_bytes(gl.st, width, span, format, ty, pixels)?.to_vec(),
        };
        let (align, [row_length, skip_rows, skip_pixels]) = (gl.st.unpack_alignment, gl.st.unpack_rows);
        let stride = (if row_length > 0 { row_length } else { width as usize } * bpp).div_ceil(align) * align;
        let mut out = vec![0; upload_size(width, height * depth, bpp, align, gl.st.unpack_rows)];
        let row_bytes = width as usize * bpp;
        for z in 0..depth as usize {
            for y in 0..height as usize {
                let from = ((skip_images + z) * per_image + skip_rows + y) * stride + skip_pixels * bpp;
                let to = (skip_rows + z * height as usize + y) * stride + skip_pixels * bpp;
                let row = source.get(from..from + row_bytes)?;
                out.get_mut(to..to + row_bytes)?.copy_from_slice(row);
            }
        }
        Some(out)
    }
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

//! Pixel layouts in the application's memory: the bytes a pixel of each format and type takes,
//! how many bytes an upload reads under the unpack state, and where `glReadPixels` puts each
//! row under the pack state.

use std::ffi::c_void;

use strata_client::ClientError;
use strata_protocol::Calls;

use super::{bytes, type_size, write_out, Gl};
use crate::gl_state::{GlState, Pack};
use crate::types::*;

/// Bytes per pixel of an upload in `format`/`ty`, if the combination is known.
pub(super) fn pixel_size(format: GLenum, ty: GLenum) -> Option<usize> {
    let components = match format {
        0x1906 | 0x1909 | 0x1902 => 1, // ALPHA, LUMINANCE, DEPTH_COMPONENT
        0x1901 => 1,                   // STENCIL_INDEX_OES (GL_NV_read_stencil)
        0x1903 | 0x8D94 => 1,          // RED_EXT, RED_INTEGER
        0x190A | 0x8227 | 0x8228 => 2, // LUMINANCE_ALPHA, RG_EXT, RG_INTEGER
        0x1907 | 0x8D98 => 3,          // RGB, RGB_INTEGER
        0x1908 | 0x80E1 | 0x8D99 => 4, // RGBA, BGRA_EXT, RGBA_INTEGER
        0x84F9 => 1,                   // DEPTH_STENCIL_OES (one packed 32-bit value)
        _ => return None,
    };
    match ty {
        // 5_6_5, 4_4_4_4, 5_5_5_1, and EXT_read_format_bgra's 4_4_4_4_REV and 1_5_5_5_REV.
        0x8363 | 0x8033 | 0x8034 | 0x8365 | 0x8366 => Some(2),
        0x84FA | 0x8368 => Some(4), // UNSIGNED_INT_24_8_OES, UNSIGNED_INT_2_10_10_10_REV_EXT
        // ES 3.0: UNSIGNED_INT_10F_11F_11F_REV and UNSIGNED_INT_5_9_9_9_REV, one word;
        // FLOAT_32_UNSIGNED_INT_24_8_REV, two.
        0x8C3B | 0x8C3E => Some(4),
        0x8DAD => Some(8),
        0x140B => Some(2 * components), // HALF_FLOAT: reads of half-float colour buffers
        _ => type_size(ty).map(|s| s * components),
    }
}

/// Where `glReadPixels`' rows go: each row of `data` (`height` rows of `width` pixels of `bpp`
/// bytes, packed by `pack.alignment`) with its byte offset from the application's pointer,
/// after the row length, the skipped rows and pixels, and the row order of `pack`.
pub(super) fn packed_rows(
    data: &[u8],
    width: usize,
    height: usize,
    bpp: usize,
    pack: Pack,
) -> impl Iterator<Item = (usize, &[u8])> {
    let a = pack.alignment.max(1);
    let [row_length, skip_rows, skip_pixels] = pack.rows;
    let src_stride = (width * bpp).div_ceil(a) * a;
    let stride = (if row_length > 0 { row_length } else { width }).saturating_mul(bpp).div_ceil(a) * a;
    let start = skip_rows.saturating_mul(stride).saturating_add(skip_pixels.saturating_mul(bpp));
    (0..height).filter_map(move |r| {
        let row = data.get(r * src_stride..r * src_stride + width * bpp)?;
        let dst_row = if pack.reverse { height - 1 - r } else { r };
        Some((start.saturating_add(dst_row.saturating_mul(stride)), row))
    })
}

/// Bytes an upload of `width`×`height` pixels reads from its pointer, honouring the unpack
/// alignment and `[row length, skip rows, skip pixels]`.
pub(super) fn upload_size(width: i32, height: i32, bpp: usize, alignment: usize, rows: [usize; 3]) -> usize {
    if width <= 0 || height <= 0 {
        return 0;
    }
    let (w, h) = (width as usize, height as usize);
    let [row_length, skip_rows, skip_pixels] = rows;
    let size = || {
        let stride = (if row_length > 0 { row_length } else { w }).checked_mul(bpp)?.div_ceil(alignment) * alignment;
        (skip_rows + h - 1).checked_mul(stride)?.checked_add((skip_pixels + w).checked_mul(bpp)?)
    };
    // Absurd skips read nothing; the daemon then finds the data short.
    size().unwrap_or(0)
}

pub(super) fn tex_image_bytes<'a>(
    st: &GlState,
    width: GLsizei,
    height: GLsizei,
    format: GLenum,
    ty: GLenum,
    pixels: *const c_void,
) -> Option<&'a [u8]> {
    let bpp = pixel_size(format, ty)?;
    if pixels.is_null() {
        return None;
    }
    // SAFETY: the application's pixels hold `upload_size` bytes for these dimensions and the
    // current unpack state.
    Some(unsafe { bytes(pixels, upload_size(width, height, bpp, st.unpack_alignment, st.unpack_rows)) })
}

/// `glReadPixels` of `[x, y, width, height]` into the application's `pixels`. The daemon
/// returns the rows packed by `PACK_ALIGNMENT` (nothing on error); they are laid out here by the
/// rest of the pack state. With a `limit` (the bounded reads of `GL_EXT_robustness`), a read
/// that does not fit in that many bytes is `GL_INVALID_OPERATION` and writes nothing.
///
/// # Safety
/// A non-null `pixels` has room for the rectangle as the pack state lays it out, or for
/// `limit` bytes where there is one.
pub(super) unsafe fn read_pixels(
    gl: &mut Gl<'_>,
    [x, y, width, height]: [GLint; 4],
    format: GLenum,
    ty: GLenum,
    pixels: *mut c_void,
    limit: Option<usize>,
) -> Result<(), ClientError> {
    let data = gl.conn.glReadPixels(x, y, width, height, format, ty)?;
    let Some(bpp) = pixel_size(format, ty).filter(|_| !data.0.is_empty()) else {
        if limit.is_none() {
            // SAFETY: see the function's contract (a format whose size the library does not
            // know is written as the daemon packed it).
            unsafe { write_out(pixels.cast::<u8>(), &data.0) };
        }
        return Ok(());
    };
    let rows: Vec<_> = packed_rows(&data.0, width as usize, height as usize, bpp, gl.st.pack).collect();
    let need = rows.iter().map(|(at, row)| at + row.len()).max().unwrap_or(0);
    if limit.is_some_and(|l| need > l) {
        gl.st.err(GL_INVALID_OPERATION);
        return Ok(());
    }
    if !pixels.is_null() {
        for (at, row) in rows {
            // SAFETY: see the function's contract: every row ends within the destination.
            unsafe { write_out(pixels.cast::<u8>().add(at), row) };
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Upload sizes follow the unpack rules of ES 2.0 §3.7.1 and `EXT_unpack_subimage`: rows of
    /// `ROW_LENGTH` (or the width) pixels padded to the alignment, skipped rows and pixels
    /// included, and only the last row's own pixels read.
    #[test]
    fn upload_sizes_cover_exactly_the_pixels_read() {
        // 3 RGB pixels = 9 bytes, padded to 12 with alignment 4; the last row is not padded.
        assert_eq!(upload_size(3, 2, 3, 4, [0, 0, 0]), 12 + 9);
        // Row length 8 RGBA (32 bytes), 2 skipped rows, 3 skipped pixels: rows 2 and 3 are read,
        // the last one up to pixel 3 + 4.
        assert_eq!(upload_size(4, 2, 4, 4, [8, 2, 3]), 3 * 32 + 7 * 4);
        assert_eq!(upload_size(0, 5, 4, 4, [0, 0, 0]), 0);
        // Skips that overflow read nothing rather than wrapping.
        assert_eq!(upload_size(4, 4, 4, 4, [usize::MAX, 0, 0]), 0);
    }

    #[test]
    fn pixel_sizes_of_the_texture_extensions() {
        assert_eq!(pixel_size(0x1908, 0x1406), Some(16)); // RGBA FLOAT
        assert_eq!(pixel_size(0x190A, 0x8D61), Some(4)); // LUMINANCE_ALPHA HALF_FLOAT_OES
        assert_eq!(pixel_size(0x80E1, 0x1401), Some(4)); // BGRA_EXT UNSIGNED_BYTE
        assert_eq!(pixel_size(0x84F9, 0x84FA), Some(4)); // DEPTH_STENCIL_OES UNSIGNED_INT_24_8_OES
        assert_eq!(pixel_size(0x1903, 0x1401), Some(1)); // RED_EXT UNSIGNED_BYTE
        assert_eq!(pixel_size(0x8227, 0x1406), Some(8)); // RG_EXT FLOAT
        assert_eq!(pixel_size(0x1234, 0x1401), None);
        // ES 3.0's integer, packed float and float depth-stencil data.
        assert_eq!(pixel_size(0x8D94, 0x1403), Some(2)); // RED_INTEGER UNSIGNED_SHORT
        assert_eq!(pixel_size(0x8D99, 0x1404), Some(16)); // RGBA_INTEGER INT
        assert_eq!(pixel_size(0x8D98, 0x1400), Some(3)); // RGB_INTEGER BYTE
        assert_eq!(pixel_size(0x8228, 0x1405), Some(8)); // RG_INTEGER UNSIGNED_INT
        assert_eq!(pixel_size(0x1907, 0x8C3B), Some(4)); // RGB UNSIGNED_INT_10F_11F_11F_REV
        assert_eq!(pixel_size(0x84F9, 0x8DAD), Some(8)); // DEPTH_STENCIL FLOAT_32_UNSIGNED_INT_24_8_REV
    }

    /// Rows go where `NV_pack_subimage` and `ANGLE_pack_reverse_row_order` put them: two rows of
    /// 3 RGB pixels (9 bytes, 12 with alignment 4) into rows of 5 pixels, after one skipped row
    /// and 2 skipped pixels; reversed, the top row first.
    #[test]
    fn read_rows_follow_the_pack_state() {
        let data: Vec<u8> = (0..21).collect();
        let pack = Pack { alignment: 4, rows: [5, 1, 2], reverse: false };
        let rows: Vec<_> = packed_rows(&data, 3, 2, 3, pack).collect();
        // Stride: 5 × 3 = 15, aligned to 16; start: 16 + 2 × 3.
        assert_eq!(rows, vec![(22, &data[0..9]), (38, &data[12..21])]);
        let rows: Vec<_> = packed_rows(&data, 3, 2, 3, Pack { reverse: true, ..pack }).collect();
        assert_eq!(rows, vec![(38, &data[0..9]), (22, &data[12..21])]);
        let tight = Pack { alignment: 1, rows: [0; 3], reverse: false };
        let rows: Vec<_> = packed_rows(&data[..18], 3, 2, 3, tight).collect();
        assert_eq!(rows, vec![(0, &data[0..9]), (9, &data[9..18])]);
    }
}

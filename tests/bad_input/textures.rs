//! Misuse of the texture formats and texture-side extensions: float, half-float, BGRA,
//! depth-stencil and compressed images, unpack state and framebuffer attachments. Every call
//! records the error the extensions specify and leaves the texture as it was.

use super::programs::*;
use strata_client::ClientError;
use strata_protocol::{Blob, Slice};

const INVALID_ENUM: u32 = 0x0500;
const INVALID_VALUE: u32 = 0x0501;
const INVALID_OPERATION: u32 = 0x0502;
const BGRA_EXT: u32 = 0x80E1;
const DEPTH_STENCIL_OES: u32 = 0x84F9;
const UNSIGNED_INT_24_8_OES: u32 = 0x84FA;
const DEPTH24_STENCIL8_OES: u32 = 0x88F0;
const DXT1_RGB: u32 = 0x83F0;
const DXT5: u32 = 0x83F3;
const ETC1_RGB8_OES: u32 = 0x8D64;
const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
const UNPACK_SKIP_ROWS: u32 = 0x0CF3;
const FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;
const FRAMEBUFFER_UNSUPPORTED: u32 = 0x8CDD;

/// Reads the GL error and has `check` judge it against `want`.
fn expect(gl: Gl<'_>, check: &mut dyn FnMut(&str, u32, u32), what: &str, want: u32) -> Result<(), ClientError> {
    let got = gl.glGetError()?;
    check(what, got, want);
    Ok(())
}

/// Runs the misuse sequence; `check(what, got, want)` judges each GL error (and each state
/// read back, as the value got and the value wanted).
pub fn misuse(gl: Gl<'_>, check: &mut dyn FnMut(&str, u32, u32)) -> Result<(), ClientError> {
    let n = &mut Names::starting_at(60_000);
    expect(gl, check, "clean start", 0)?;

    // Unpack state (EXT_unpack_subimage).
    gl.glPixelStorei(UNPACK_ROW_LENGTH, -1)?;
    expect(gl, check, "negative UNPACK_ROW_LENGTH", INVALID_VALUE)?;
    let row_length = gl.glGetIntegerv(UNPACK_ROW_LENGTH)?.first().copied().unwrap_or(-1);
    check("UNPACK_ROW_LENGTH unchanged", row_length as u32, 0);

    // An 8-bit RGBA texture, opaque red; nothing below may change it.
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    let red: Vec<u8> = [255u8, 0, 0, 255].repeat(16);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&red)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    expect(gl, check, "valid RGBA texture", 0)?;
    let floats = f32s(&[0.0; 64]);
    gl.glTexImage2D(TEXTURE_2D, 0, BGRA_EXT as i32, 4, 4, 0, BGRA_EXT, FLOAT, Some(Blob::borrowed(&floats)))?;
    expect(gl, check, "BGRA with FLOAT", INVALID_OPERATION)?;
    // MESA_bgra: an RGBA image takes BGRA data (the same red, so the image stays as it was);
    // an RGB one does not.
    let red_bgra: Vec<u8> = red.chunks_exact(4).flat_map(|p| [p[2], p[1], p[0], p[3]]).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, BGRA_EXT, UNSIGNED_BYTE, Some(Blob::borrowed(&red_bgra)))?;
    expect(gl, check, "BGRA data for an RGBA internal format", 0)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 4, 4, 0, BGRA_EXT, UNSIGNED_BYTE, Some(Blob::borrowed(&red)))?;
    expect(gl, check, "BGRA data for an RGB internal format", INVALID_OPERATION)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, 0x1234, Some(Blob::borrowed(&red)))?;
    expect(gl, check, "unknown type", INVALID_ENUM)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_INT_24_8_OES, Some(Blob::borrowed(&red)))?;
    expect(gl, check, "RGBA with UNSIGNED_INT_24_8_OES", INVALID_OPERATION)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, HALF_FLOAT_OES, Some(Blob::borrowed(&[0u8; 100])))?;
    expect(gl, check, "half-float data shorter than the image", INVALID_OPERATION)?;
    gl.glTexSubImage2D(TEXTURE_2D, 40, 0, 0, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&red))?;
    expect(gl, check, "sub-image of level 40", INVALID_VALUE)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 1 << 30)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 2, 2, RGBA, UNSIGNED_BYTE, Blob::borrowed(&red))?;
    expect(gl, check, "sub-image skipping 2^30 rows of 64 bytes", INVALID_OPERATION)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 0)?;

    // Depth-stencil images (OES_packed_depth_stencil + OES_depth_texture): 2D, level 0,
    // DEPTH_STENCIL_OES for both formats, UNSIGNED_INT_24_8_OES only.
    let (ds, cube) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, ds)?;
    let (f, ty) = (DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES);
    gl.glTexImage2D(TEXTURE_2D, 0, f as i32, 4, 4, 0, f, ty, None)?;
    expect(gl, check, "valid depth-stencil texture", 0)?;
    gl.glTexImage2D(TEXTURE_2D, 0, f as i32, 4, 4, 0, f, UNSIGNED_INT, None)?;
    expect(gl, check, "DEPTH_STENCIL_OES with UNSIGNED_INT", INVALID_ENUM)?;
    // GL_OES_required_internalformat: a sized format takes the format and type it fits.
    gl.glTexImage2D(TEXTURE_2D, 0, DEPTH24_STENCIL8_OES as i32, 4, 4, 0, f, ty, None)?;
    expect(gl, check, "sized depth-stencil internal format", 0)?;
    gl.glTexImage2D(TEXTURE_2D, 0, 0x8058, 4, 4, 0, f, ty, None)?;
    expect(gl, check, "a sized internal format the format does not fit", INVALID_OPERATION)?;
    gl.glTexImage2D(TEXTURE_2D, 1, f as i32, 2, 2, 0, f, ty, None)?;
    expect(gl, check, "depth-stencil level 1", INVALID_OPERATION)?;
    gl.glBindTexture(TEXTURE_CUBE_MAP, cube)?;
    // OES_depth_texture_cube_map takes it (as Mesa does: tests/programs/depth_cube.rs).
    gl.glTexImage2D(TEXTURE_CUBE_MAP_POSITIVE_X, 0, f as i32, 4, 4, 0, f, ty, None)?;
    expect(gl, check, "depth-stencil cube face", 0)?;
    gl.glTexImage2D(TEXTURE_CUBE_MAP_POSITIVE_X, 1, f as i32, 2, 2, 0, f, ty, None)?;
    expect(gl, check, "depth-stencil cube face, level 1", INVALID_OPERATION)?;

    // Compressed images.
    let (dxt, etc) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, dxt)?;
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, 0x1234, 8, 8, 0, Blob::borrowed(&[0; 32]))?;
    expect(gl, check, "unknown compressed format", INVALID_ENUM)?;
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, DXT1_RGB, 8, 8, 0, Blob::borrowed(&[0; 31]))?;
    expect(gl, check, "DXT1 image size one byte short", INVALID_VALUE)?;
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, DXT5, 8, 8, 0, Blob::borrowed(&[0; 64]))?;
    expect(gl, check, "valid DXT5 image", 0)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 2, 0, 4, 4, DXT5, Blob::borrowed(&[0; 16]))?;
    expect(gl, check, "DXT5 update off the block grid", INVALID_OPERATION)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 4, 4, 4, 4, DXT1_RGB, Blob::borrowed(&[0; 8]))?;
    expect(gl, check, "DXT1 data into a DXT5 image", INVALID_OPERATION)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 4, 4, 4, 4, DXT5, Blob::borrowed(&[0; 8]))?;
    expect(gl, check, "DXT5 update of the wrong size", INVALID_VALUE)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 8, 0, 4, 4, DXT5, Blob::borrowed(&[0; 16]))?;
    expect(gl, check, "DXT5 update outside the image", INVALID_VALUE)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 4, 4, RGBA, UNSIGNED_BYTE, Blob::borrowed(&red))?;
    expect(gl, check, "uncompressed update of DXT5 off the block grid", INVALID_OPERATION)?;
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 0, 0, 0, 0, 4, 4)?;
    expect(gl, check, "copy into a compressed image", INVALID_OPERATION)?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    expect(gl, check, "mipmaps of a compressed image", INVALID_OPERATION)?;
    gl.glBindTexture(TEXTURE_2D, etc)?;
    gl.glCompressedTexImage2D(TEXTURE_2D, 0, ETC1_RGB8_OES, 8, 8, 0, Blob::borrowed(&[0; 32]))?;
    expect(gl, check, "valid ETC1 image", 0)?;
    // EXT_compressed_ETC1_RGB8_sub_texture: whole blocks may be replaced, but not from off a
    // block boundary.
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, ETC1_RGB8_OES, Blob::borrowed(&[0; 8]))?;
    expect(gl, check, "ETC1 partial update", 0)?;
    gl.glCompressedTexSubImage2D(TEXTURE_2D, 0, 2, 0, 4, 4, ETC1_RGB8_OES, Blob::borrowed(&[0; 8]))?;
    expect(gl, check, "ETC1 update off a block boundary", INVALID_OPERATION)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 4, 4, RGB, UNSIGNED_BYTE, Blob::borrowed(&red))?;
    expect(gl, check, "uncompressed update of ETC1", INVALID_OPERATION)?;

    // The RGBA texture is still opaque red.
    gl.glBindTexture(TEXTURE_2D, t)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    textured_quad(gl, n, 0.0, 1.0)?;
    let px = gl.glReadPixels(W / 2, H / 2, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
    check("texture unchanged (red)", u32::from_le_bytes(px[..4].try_into().unwrap_or([0; 4])), 0xFF00_00FF);
    expect(gl, check, "drawing it", 0)
}

/// ES 2.0 renders into 8-bit colour only (no `EXT_color_buffer_*` is offered): a float
/// texture is not a complete colour attachment.
pub fn float_attachment(gl: Gl<'_>, check: &mut dyn FnMut(&str, u32, u32)) -> Result<(), ClientError> {
    let n = &mut Names::starting_at(70_000);
    let (t, fb) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, FLOAT, None)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    // Unsupported, as Mesa answers (half-float colour is renderable, float is not).
    check("float colour attachment", gl.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_UNSUPPORTED);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, None)?;
    check("8-bit colour attachment", gl.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    check("no error", gl.glGetError()?, 0);
    Ok(())
}

/// A slice of a 3D texture (`GL_OES_texture_3D`) attached to a framebuffer that is not bound
/// while the texture is deleted: the name, made a 2D texture (and a cube map) again, is no
/// longer what the attachment named, and the framebuffer is incomplete, not a face past the
/// image's.
pub fn stale_slice_attachment(gl: Gl<'_>, check: &mut dyn FnMut(&str, u32, u32)) -> Result<(), ClientError> {
    const TEXTURE_3D: u32 = 0x806F;
    const INCOMPLETE_ATTACHMENT: u32 = 0x8CD6;
    const DEPTH_COMPONENT: u32 = 0x1902;
    let n = &mut Names::starting_at(71_000);
    let (t, fb) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_3D, t)?;
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGBA, 4, 4, 8, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_3D, t, 0, 7)?;
    check("slice 7 attached", gl.glCheckFramebufferStatus(FRAMEBUFFER)?, FRAMEBUFFER_COMPLETE);
    // The same slice as a second framebuffer's depth attachment, beside a colour texture.
    let (colour, fb2) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, colour)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb2)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, colour, 0)?;
    gl.glFramebufferTexture3DOES(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_3D, t, 0, 7)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glDeleteTextures(Slice::new(&[t]))?;
    let images = [
        (TEXTURE_2D, TEXTURE_2D, RGBA, UNSIGNED_BYTE),
        (0x8513, 0x8515, RGBA, UNSIGNED_BYTE),
        (TEXTURE_2D, TEXTURE_2D, DEPTH_COMPONENT, UNSIGNED_INT),
    ];
    for (target, image, format, ty) in images {
        gl.glBindTexture(target, t)?;
        gl.glTexImage2D(image, 0, format as i32, 4, 4, 0, format, ty, None)?;
        for f in [fb, fb2] {
            gl.glBindFramebuffer(FRAMEBUFFER, f)?;
            check("the name holds another texture", gl.glCheckFramebufferStatus(FRAMEBUFFER)?, INCOMPLETE_ATTACHMENT);
            gl.glClear(0x4000)?;
            check("a clear of it", gl.glGetError()?, 0x0506);
        }
        gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
        gl.glDeleteTextures(Slice::new(&[t]))?;
    }
    check("no error", gl.glGetError()?, 0);
    Ok(())
}

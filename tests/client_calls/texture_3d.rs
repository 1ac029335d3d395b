//! `GL_OES_texture_3D` through the C entry points, where the library lays out what it sends:
//! 3D images whose rows the unpack state pads and strides (alignment, row length, skipped
//! rows and pixels), from application memory and from an unpack buffer at an offset, drawn
//! across their slices; ASTC slices (`GL_KHR_texture_compression_astc_sliced_3d`); a slice rendered into, copied into and read back; and
//! sizes the library sends no data for.

use super::*;

const TEXTURE_3D: u32 = 0x806F;
const RGBA: u32 = 0x1908;
const RGB: u32 = 0x1907;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNPACK: u32 = 0x88EC;
const STREAM_DRAW: u32 = 0x88E0;
const UNPACK_ALIGNMENT: u32 = 0x0CF5;
const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
const UNPACK_SKIP_ROWS: u32 = 0x0CF3;
const UNPACK_SKIP_PIXELS: u32 = 0x0CF4;
const FRAMEBUFFER: u32 = 0x8D40;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const ASTC_4X4: u32 = 0x93B0;

/// Samples the bound 3D texture with r running across the window.
const FS_3D: &str = "#extension GL_OES_texture_3D : enable
    precision mediump float; uniform lowp sampler3D s; varying vec2 uv;
    void main() { gl_FragColor = texture3D(s, vec3(uv, uv.x * 0.5 + uv.y * 0.5)); }";

/// An LDR void-extent ASTC block: one colour of 16-bit channels for the whole block.
fn void_extent(rgba: [u16; 4]) -> Vec<u8> {
    let mut b = vec![0xFC, 0xFD, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF];
    b.extend(rgba.iter().flat_map(|c| c.to_le_bytes()));
    b
}

/// The 3D texture sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    r.program(TEXTURED_VS, FS_3D);
    // SAFETY: GL calls with a current context; every pointer holds what the unpack state makes
    // the call read; with an unpack buffer bound, pointers are offsets.
    unsafe {
        (gl.viewport)(0, 0, 16, 16);
        let mut t = 0;
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_3D, t);
        (gl.tex_parameteri)(TEXTURE_3D, 0x2801, 0x2600);
        (gl.tex_parameteri)(TEXTURE_3D, 0x2800, 0x2600);
        // RGB rows of 3 pixels padded to 12 bytes: 3 rows by 3 slices.
        let padded: Vec<u8> = (0..12 * 9).map(|i: u32| (i * 37 + 11) as u8).collect();
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGB, 3, 3, 3, 0, RGB, UNSIGNED_BYTE, padded.as_ptr().cast());
        r.textured("a 3×3×3 RGB image with alignment 4");
        // Row length 5, two rows and one pixel skipped, alignment 1: a 2×2×2 box.
        (gl.pixel_store_i)(UNPACK_ALIGNMENT, 1);
        (gl.pixel_store_i)(UNPACK_ROW_LENGTH, 5);
        (gl.pixel_store_i)(UNPACK_SKIP_ROWS, 2);
        (gl.pixel_store_i)(UNPACK_SKIP_PIXELS, 1);
        let strided: Vec<u8> = (0..3 * 5 * 6).map(|i: u32| (i * 53 + 3) as u8).collect();
        (gl.tex_sub_image_3d)(TEXTURE_3D, 0, 1, 0, 1, 2, 2, 2, RGB, UNSIGNED_BYTE, strided.as_ptr().cast());
        r.textured("a 2×2×2 box with row length 5 and skips");
        for p in [UNPACK_ROW_LENGTH, UNPACK_SKIP_ROWS, UNPACK_SKIP_PIXELS] {
            (gl.pixel_store_i)(p, 0);
        }
        // From an unpack buffer at offset 8: a 2×2×2 RGBA image.
        let mut b = 0;
        (gl.gen_buffers)(1, &mut b);
        (gl.bind_buffer)(UNPACK, b);
        let texels: Vec<u8> = (0..8 + 32).map(|i: u32| (i * 29 + 7) as u8).collect();
        (gl.buffer_data)(UNPACK, texels.len() as isize, texels.as_ptr().cast(), STREAM_DRAW);
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 2, 2, 2, 0, RGBA, UNSIGNED_BYTE, 8 as Ptr);
        r.textured("a 2×2×2 image from offset 8");
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 2, 2, 3, 0, RGBA, UNSIGNED_BYTE, 8 as Ptr);
        r.note("an image reaching past the buffer's end");
        (gl.bind_buffer)(UNPACK, 0);
        // ASTC: two void-extent slices.
        let mut blocks = void_extent([0xFFFF, 0x8000, 0x2000, 0xFFFF]);
        blocks.extend(void_extent([0x1000, 0x4000, 0xF000, 0xC000]));
        (gl.compressed_tex_image_3d)(TEXTURE_3D, 0, ASTC_4X4, 4, 4, 2, 0, 32, blocks.as_ptr().cast());
        r.textured("two ASTC slices");
        (gl.compressed_tex_image_3d)(TEXTURE_3D, 0, ASTC_4X4, 4, 4, 2, 0, -1, blocks.as_ptr().cast());
        r.note("a negative image size");
        // Sizes the library sends no data for: negative and huge.
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 2, -2, -2, 0, RGBA, UNSIGNED_BYTE, texels.as_ptr().cast());
        r.note("negative height and depth");
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 2, 2, 1 << 20, 0, RGBA, UNSIGNED_BYTE, texels.as_ptr().cast());
        r.note("a million slices");
        // Slice 1 of a 4×4×2 image as the framebuffer's colour: cleared, read, then the window
        // copied into slice 0.
        (gl.tex_image_3d)(TEXTURE_3D, 0, RGBA, 4, 4, 2, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        r.note("an image without data");
        // (Whose texels GL leaves undefined: they are written before they are drawn.)
        let grey = [0x40u8; 4 * 4 * 2 * 4];
        (gl.tex_sub_image_3d)(TEXTURE_3D, 0, 0, 0, 0, 4, 4, 2, RGBA, UNSIGNED_BYTE, grey.as_ptr().cast());
        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        (gl.framebuffer_texture_3d)(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_3D, t, 0, 1);
        let status = (gl.check_framebuffer_status)(FRAMEBUFFER);
        r.note(&format!("slice 1 attached: status {status:#x}"));
        (gl.clear_color)(0.6, 0.2, 0.8, 1.0);
        (gl.clear)(0x4000);
        let mut px = [0u8; 16];
        (gl.read_pixels)(0, 0, 2, 2, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note(&format!("slice 1 read {px:?}"));
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        (gl.clear_color)(0.1, 0.9, 0.3, 0.5);
        (gl.clear)(0x4000);
        (gl.copy_tex_sub_image_3d)(TEXTURE_3D, 0, 1, 1, 0, 0, 0, 2, 3);
        r.note("a copy into slice 0");
        r.textured("slice 0 copied into, slice 1 cleared");
        (gl.delete_textures)(1, &t);
    }
}

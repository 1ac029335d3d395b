//! `GL_NV_pixel_buffer_object` through the C entry points: uploads (whole, in part, with unpack
//! state, compressed) that read an unpack buffer at an offset, drawn and read back; reads
//! into a pack buffer at an offset with pack state, mapped to see them; the bindings and their
//! queries; and the errors of ranges past the end, misaligned offsets and mapped buffers.

use super::*;

const PACK: u32 = 0x88EB;
const UNPACK: u32 = 0x88EC;
const PACK_BINDING: u32 = 0x88ED;
const UNPACK_BINDING: u32 = 0x88EF;
const TEXTURE_2D: u32 = 0x0DE1;
const RGBA: u32 = 0x1908;
const RGB: u32 = 0x1907;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNSIGNED_SHORT_565: u32 = 0x8363;
const FLOAT: u32 = 0x1406;
const ETC1: u32 = 0x8D64;
const STREAM_DRAW: u32 = 0x88E0;
const MAP_READ: u32 = 0x0001;
const MAP_WRITE: u32 = 0x0002;
const UNPACK_ALIGNMENT: u32 = 0x0CF5;
const PACK_ALIGNMENT: u32 = 0x0D05;
const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
const PACK_ROW_LENGTH: u32 = 0x0D02;

const QUAD: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];

impl Run {
    /// Draws the bound texture over the window and logs every third pixel of every third row.
    pub(super) fn textured(&mut self, what: &str) {
        let gl = self.gl;
        let mut px = [0u8; 16 * 16 * 4];
        // SAFETY: a context is current; no pack buffer is bound while the window is read; the
        // quad lives through the draw.
        unsafe {
            (gl.bind_buffer)(0x8892, 0);
            (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, QUAD.as_ptr().cast());
            (gl.enable_vertex_attrib_array)(0);
            (gl.draw_arrays)(0x0005, 0, 4);
            (gl.bind_buffer)(PACK, 0);
            (gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        }
        let grid: Vec<String> = (0..16)
            .step_by(3)
            .flat_map(|y| (0..16).step_by(3).map(move |x| (y * 16 + x) * 4))
            .map(|i| format!("{:02x}{:02x}{:02x}{:02x}", px[i], px[i + 1], px[i + 2], px[i + 3]))
            .collect();
        self.note(what);
        self.log.push(format!("{what}: pixels {}", grid.join(" ")));
    }

    /// Logs `len` bytes of buffer `name` from offset 0, mapped for reading.
    fn buffer_bytes(&mut self, what: &str, name: u32, len: usize) {
        let gl = self.gl;
        // SAFETY: a context is current; a mapped range holds `len` bytes.
        let bytes = unsafe {
            (gl.bind_buffer)(PACK, name);
            let p = (gl.map_range)(PACK, 0, len as isize, MAP_READ);
            let v = if p.is_null() { Vec::new() } else { std::slice::from_raw_parts(p.cast::<u8>(), len).to_vec() };
            (gl.unmap)(PACK);
            v
        };
        let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
        self.note(&format!("{what}: {hex}"));
    }
}

/// The pixel buffer sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; with a pixel buffer bound, pointers are offsets
    // (never dereferenced); otherwise every pointer is valid for the call.
    unsafe {
        r.program(TEXTURED_VS, TEXTURED_FS);
        let mut names = [0u32; 3];
        (gl.gen_buffers)(3, names.as_mut_ptr());
        let [unpack, pack, other] = names;
        let mut t = 0;
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_2D, t);
        (gl.tex_parameteri)(TEXTURE_2D, 0x2801, 0x2600);
        (gl.tex_parameteri)(TEXTURE_2D, 0x2800, 0x2600);

        // An unpack buffer: 16 bytes of padding, then 4×4 RGBA texels, then 2×2 more.
        let texels: Vec<u8> = (0..16 + 64 + 16).map(|i: u32| (i * 29 + 7) as u8).collect();
        (gl.bind_buffer)(UNPACK, unpack);
        (gl.buffer_data)(UNPACK, texels.len() as isize, texels.as_ptr().cast(), STREAM_DRAW);
        let mut v = -1;
        (gl.get_integerv)(UNPACK_BINDING, &mut v);
        r.note(&format!("unpack binding is the buffer: {}", v == unpack as i32));
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, 16 as Ptr);
        r.textured("a 4×4 image from offset 16");
        (gl.tex_sub_image_2d)(TEXTURE_2D, 0, 1, 1, 2, 2, RGBA, UNSIGNED_BYTE, 80 as Ptr);
        r.textured("a 2×2 part from offset 80");
        // Row length 3 and alignment 1: RGB rows of 3 pixels, 2 of them read.
        (gl.pixel_store_i)(UNPACK_ROW_LENGTH, 3);
        (gl.pixel_store_i)(UNPACK_ALIGNMENT, 1);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGB as i32, 2, 2, 0, RGB, UNSIGNED_BYTE, 5 as Ptr);
        r.textured("an RGB 2×2 image with row length 3 from offset 5");
        (gl.pixel_store_i)(UNPACK_ROW_LENGTH, 0);
        (gl.pixel_store_i)(UNPACK_ALIGNMENT, 4);
        // The errors: past the end, a misaligned offset for a 16-bit type, a mapped buffer.
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, 40 as Ptr);
        r.note("an image reaching past the end");
        (gl.tex_sub_image_2d)(TEXTURE_2D, 0, 0, 0, 2, 2, RGB, UNSIGNED_SHORT_565, 1 as Ptr);
        r.note("a 5_6_5 part at an odd offset");
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGB as i32, 2, 2, 0, RGB, UNSIGNED_SHORT_565, 2 as Ptr);
        r.note("a 5_6_5 image at an even offset");
        (gl.map_range)(UNPACK, 0, 8, MAP_WRITE);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        r.note("an image while the buffer is mapped");
        (gl.unmap)(UNPACK);
        // ETC1 blocks from the buffer (an individual-mode block: differential ones may
        // overflow, which ETC1 leaves undefined).
        (gl.compressed_tex_image_2d)(TEXTURE_2D, 0, ETC1, 4, 4, 0, 8, 18 as Ptr);
        r.textured("an ETC1 block from offset 18");
        (gl.compressed_tex_image_2d)(TEXTURE_2D, 0, ETC1, 4, 4, 0, 8, 92 as Ptr);
        r.note("an ETC1 block past the end");
        // A buffer without contents.
        (gl.bind_buffer)(UNPACK, other);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        r.note("an image from a buffer with no data store");
        (gl.bind_buffer)(UNPACK, 0);

        // A pack buffer: the window cleared in two colours, read at offset 8 with alignment 8.
        (gl.bind_buffer)(PACK, pack);
        let zeros = [0u8; 64];
        (gl.buffer_data)(PACK, 64, zeros.as_ptr().cast(), STREAM_DRAW);
        (gl.get_integerv)(PACK_BINDING, &mut v);
        r.note(&format!("pack binding is the buffer: {}", v == pack as i32));
        (gl.clear_color)(0.2, 0.4, 0.6, 0.8);
        (gl.clear)(0x4000);
        (gl.enable)(0x0C11);
        (gl.scissor)(1, 0, 8, 8);
        (gl.clear_color)(1.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        (gl.disable)(0x0C11);
        (gl.bind_buffer)(PACK, pack);
        (gl.pixel_store_i)(PACK_ALIGNMENT, 8);
        (gl.read_pixels)(0, 0, 3, 2, RGBA, UNSIGNED_BYTE, 8 as Ptr);
        r.note("a 3×2 read at offset 8, alignment 8");
        r.buffer_bytes("the pack buffer", pack, 64);
        (gl.bind_buffer)(PACK, pack);
        (gl.pixel_store_i)(PACK_ALIGNMENT, 4);
        (gl.pixel_store_i)(PACK_ROW_LENGTH, 3);
        (gl.read_pixels)(0, 0, 2, 2, RGBA, UNSIGNED_BYTE, 36 as Ptr);
        r.note("a 2×2 read with row length 3 at offset 36");
        (gl.pixel_store_i)(PACK_ROW_LENGTH, 0);
        r.buffer_bytes("the pack buffer again", pack, 64);
        (gl.bind_buffer)(PACK, pack);
        (gl.read_pixels)(0, 0, 4, 4, RGBA, UNSIGNED_BYTE, 4 as Ptr);
        r.note("a read reaching past the end");
        (gl.read_pixels)(0, 0, 1, 1, RGB, UNSIGNED_SHORT_565, 3 as Ptr);
        r.note("a 5_6_5 read at an odd offset");
        (gl.map_range)(PACK, 0, 8, MAP_READ);
        (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, std::ptr::null_mut());
        r.note("a read while the buffer is mapped");
        (gl.unmap)(PACK);
        r.buffer_bytes("the pack buffer after the refused reads", pack, 64);

        // Deleting the buffers unbinds them.
        (gl.delete_buffers)(3, names.as_ptr());
        (gl.get_integerv)(PACK_BINDING, &mut v);
        r.note(&format!("pack binding after deletion: {v}"));
        (gl.get_integerv)(UNPACK_BINDING, &mut v);
        r.note(&format!("unpack binding after deletion: {v}"));
        (gl.pixel_store_i)(PACK_ALIGNMENT, 4);
    }
}

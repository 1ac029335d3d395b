//! Pixel transfer through the application's memory: where `glReadPixels` puts each row under
//! `GL_PACK_ALIGNMENT`, `GL_NV_pack_subimage`'s row length and skips and
//! `GL_ANGLE_pack_reverse_row_order` (every byte of the destination compared, so that a row
//! written where it should not be, or a gap overwritten, shows), and how many bytes uploads of
//! `GL_EXT_texture_rg`'s formats and of rows laid out by `GL_EXT_unpack_subimage` read.

use super::*;

const PACK_ALIGNMENT: u32 = 0x0D05;
const PACK_ROW_LENGTH: u32 = 0x0D02;
const PACK_SKIP_ROWS: u32 = 0x0D03;
const PACK_SKIP_PIXELS: u32 = 0x0D04;
const PACK_REVERSE_ROW_ORDER: u32 = 0x93A4;
const UNPACK_ALIGNMENT: u32 = 0x0CF5;
const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
const UNPACK_SKIP_PIXELS: u32 = 0x0CF4;
const RGBA: u32 = 0x1908;
const RGB: u32 = 0x1907;
const BGRA: u32 = 0x80E1;
const RED: u32 = 0x1903;
const RG: u32 = 0x8227;
const UNSIGNED_BYTE: u32 = 0x1401;
const TEXTURE_2D: u32 = 0x0DE1;
/// What the destination holds before a read: bytes no read may change keep it.
const UNTOUCHED: u8 = 0xAB;

/// A colour of its own for every pixel, from its window position (no value is a rounding tie).
const VS: &str = "attribute vec2 pos; varying vec2 uv; \
                  void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS_POSITION: &str = "precision highp float; \
                           void main() { gl_FragColor = vec4(gl_FragCoord.xy / 16.0, 0.25, 1.0); }";
const FS_TEXTURE: &str = "precision mediump float; varying vec2 uv; uniform sampler2D t; \
                          void main() { gl_FragColor = texture2D(t, uv); }";

/// The changed bytes of `mem`, as runs of offset and bytes.
fn changes(mem: &[u8]) -> String {
    let mut out = String::new();
    let mut i = 0;
    while i < mem.len() {
        if mem[i] == UNTOUCHED {
            i += 1;
            continue;
        }
        let start = i;
        while i < mem.len() && mem[i] != UNTOUCHED {
            i += 1;
        }
        out += &format!(" @{start}:{:02x?}", &mem[start..i]);
    }
    out
}

impl Run {
    /// Sets a pixel-store parameter and logs the error and what it reads back as.
    fn store(&mut self, pname: u32, param: i32) {
        let mut v = -7;
        // SAFETY: a context is current; one GLint out.
        unsafe {
            (self.gl.pixel_store_i)(pname, param);
            let e = (self.gl.get_error)();
            (self.gl.get_integerv)(pname, &mut v);
            self.log.push(format!("pixel store {pname:#x} = {param}: error {e:#x}, reads {v}"));
        }
    }

    /// Draws a full-window quad with the current program.
    fn quad(&mut self) {
        let v: Vec<u8> = [-1.0f32, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0].iter().flat_map(|f| f.to_ne_bytes()).collect();
        let gl = self.gl;
        // SAFETY: a context is current; the vertices are copied by glBufferData.
        unsafe {
            let mut b = 0;
            (gl.gen_buffers)(1, &mut b);
            (gl.bind_buffer)(ARRAY, b);
            (gl.buffer_data)(ARRAY, v.len() as isize, v.as_ptr().cast(), STATIC_DRAW);
            (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, std::ptr::null());
            (gl.enable_vertex_attrib_array)(0);
            (gl.draw_arrays)(0x0005, 0, 4);
        }
        self.note("quad");
    }

    /// Reads `rect` as `format` and `ty` into memory holding [`UNTOUCHED`] and logs what changed.
    fn read(&mut self, what: &str, [x, y, w, h]: [i32; 4], format: u32, ty: u32) {
        let mut mem = vec![UNTOUCHED; 1024];
        // SAFETY: a context is current; 1024 bytes hold every read below as its pack state
        // lays it out.
        unsafe { (self.gl.read_pixels)(x, y, w, h, format, ty, mem.as_mut_ptr().cast()) };
        self.note(&format!("read {what}"));
        self.log.push(format!("  wrote{}", changes(&mem)));
    }
}

/// The pack and upload sequence.
pub fn sequence(r: &mut Run) {
    // The parameters: their defaults, a negative value, and another.
    for pname in [PACK_ROW_LENGTH, PACK_SKIP_ROWS, PACK_SKIP_PIXELS, PACK_REVERSE_ROW_ORDER] {
        let mut v = -7;
        // SAFETY: a context is current; one GLint out.
        unsafe { (r.gl.get_integerv)(pname, &mut v) };
        r.note(&format!("{pname:#x} starts at {v}"));
        for param in [-1, 2, 0] {
            r.store(pname, param);
        }
    }
    r.program(VS, FS_POSITION);
    // SAFETY: a context is current.
    unsafe { (r.gl.viewport)(0, 0, 16, 16) };
    r.quad();
    let rect = [2, 3, 5, 3];
    // (what, alignment, row length, skipped rows, skipped pixels, reversed, format, type).
    let reads = [
        ("by default", 4, 0, 0, 0, 0, RGBA, UNSIGNED_BYTE),
        ("alignment 1", 1, 0, 0, 0, 0, BGRA, UNSIGNED_BYTE),
        ("row length 7, alignment 8", 8, 7, 0, 0, 0, RGBA, UNSIGNED_BYTE),
        ("row length 7", 4, 7, 0, 0, 0, RGBA, UNSIGNED_BYTE),
        ("row length 7, 2 rows and 3 pixels skipped", 4, 7, 2, 3, 0, RGBA, UNSIGNED_BYTE),
        ("reversed", 4, 0, 0, 0, 1, RGBA, UNSIGNED_BYTE),
        // Mesa writes reversed rows after skipped rows before the destination (its first
        // row goes where the skipped rows' last would be, and the rest below it), so no
        // reversed read here skips rows; the library's placement of those is unit-tested.
        ("reversed, row length 9, 2 pixels skipped, alignment 8", 8, 9, 0, 2, 1, BGRA, UNSIGNED_BYTE),
        ("reversed, row length 6, a pixel skipped, alignment 2", 2, 6, 0, 1, 1, BGRA, UNSIGNED_BYTE),
    ];
    for (what, align, row_length, skip_rows, skip_pixels, reverse, format, ty) in reads {
        for (pname, v) in [
            (PACK_ALIGNMENT, align),
            (PACK_ROW_LENGTH, row_length),
            (PACK_SKIP_ROWS, skip_rows),
            (PACK_SKIP_PIXELS, skip_pixels),
            (PACK_REVERSE_ROW_ORDER, reverse),
        ] {
            // SAFETY: a context is current.
            unsafe { (r.gl.pixel_store_i)(pname, v) };
        }
        r.read(what, rect, format, ty);
    }
    r.read("an empty rectangle", [2, 3, 0, 3], RGBA, UNSIGNED_BYTE);
    r.read("a rectangle in error", [2, 3, -1, 3], RGBA, UNSIGNED_BYTE);
    for pname in [PACK_ROW_LENGTH, PACK_SKIP_ROWS, PACK_SKIP_PIXELS, PACK_REVERSE_ROW_ORDER] {
        // SAFETY: a context is current.
        unsafe { (r.gl.pixel_store_i)(pname, 0) };
    }
    // Uploads: 3×2 RED and RG images with rows of 3 and 6 bytes (alignment 1), and RGB rows
    // taken from inside wider rows (row length 5, one pixel skipped), each drawn and read.
    r.program(VS, FS_TEXTURE);
    let gl = r.gl;
    let texels: Vec<u8> = (0..60).map(|i| (i * 17 + 5) as u8).collect();
    // SAFETY: a context is current; `texels` holds what each upload reads.
    unsafe {
        let mut t = 0;
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_2D, t);
        for (p, v) in [(0x2801, 0x2600), (0x2800, 0x2600), (0x2802, 0x812F), (0x2803, 0x812F)] {
            (gl.tex_parameteri)(TEXTURE_2D, p, v);
        }
        (gl.pixel_store_i)(UNPACK_ALIGNMENT, 1);
        for (what, format) in [("RED", RED), ("RG", RG)] {
            (gl.tex_image_2d)(TEXTURE_2D, 0, format as i32, 3, 2, 0, format, UNSIGNED_BYTE, texels.as_ptr().cast());
            r.note(&format!("upload {what}"));
            r.quad();
            r.read(&format!("drawn from {what}, bottom"), [0, 4, 16, 1], RGBA, UNSIGNED_BYTE);
            r.read(&format!("drawn from {what}, top"), [0, 12, 16, 1], RGBA, UNSIGNED_BYTE);
        }
        (gl.pixel_store_i)(UNPACK_ROW_LENGTH, 5);
        (gl.pixel_store_i)(UNPACK_SKIP_PIXELS, 1);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGB as i32, 3, 2, 0, RGB, UNSIGNED_BYTE, texels.as_ptr().cast());
        r.note("upload RGB from wider rows");
        (gl.tex_sub_image_2d)(TEXTURE_2D, 0, 1, 1, 2, 1, RGB, UNSIGNED_BYTE, texels[30..].as_ptr().cast());
        r.note("update RGB from wider rows");
        (gl.pixel_store_i)(UNPACK_ROW_LENGTH, 0);
        (gl.pixel_store_i)(UNPACK_SKIP_PIXELS, 0);
        r.quad();
        r.read("drawn from RGB, bottom", [0, 4, 16, 1], RGBA, UNSIGNED_BYTE);
        r.read("drawn from RGB, top", [0, 12, 16, 1], RGBA, UNSIGNED_BYTE);
    }
}

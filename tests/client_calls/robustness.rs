//! `GL_EXT_robustness` and `GL_KHR_robustness`: the reset status, the context's strategy and
//! robust access, and reads bounded by the application's buffer size (pixels, under the pack
//! state too, and uniforms), each with the error order Mesa has.

use super::*;

const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNTOUCHED: u8 = 0xAB;

/// A uniform the bounded queries read.
const VS: &str = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "precision mediump float; uniform vec4 u; void main() { gl_FragColor = u; }";

impl Run {
    /// Reads `rect` into a buffer of 64 bytes said to hold `buf_size`; logs the error and the
    /// bytes written.
    fn readn(&mut self, what: &str, khr: bool, rect: [i32; 4], format: u32, buf_size: i32) {
        let mut mem = [UNTOUCHED; 64];
        let [x, y, w, h] = rect;
        let f = if khr { self.gl.readn_pixels_khr } else { self.gl.readn_pixels_ext };
        // SAFETY: a context is current; `buf_size` never exceeds the 64 bytes there are.
        unsafe { f(x, y, w, h, format, UNSIGNED_BYTE, buf_size.min(64), mem.as_mut_ptr().cast()) };
        self.note(&format!("readn {what}"));
        let written = mem.iter().filter(|&&b| b != UNTOUCHED).count();
        self.log.push(format!("  {written} bytes written, first {:?}", &mem[..8]));
    }
}

/// The robustness sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls on the current context; every out-pointer has room for what it gets.
    unsafe {
        r.log.push(format!("reset status {:#x} {:#x}", (gl.reset_status_ext)(), (gl.reset_status_khr)()));
        let mut v = [-7i32; 4];
        (gl.get_integerv)(0x8256, v.as_mut_ptr());
        r.note(&format!("reset notification strategy {:#x}", v[0]));
        let mut b = [7u8; 4];
        (gl.get_booleanv)(0x90F3, b.as_mut_ptr());
        r.note(&format!("robust access {}", b[0]));
        (gl.viewport)(0, 0, 16, 16);
        (gl.clear_color)(0.25, 0.5, 0.75, 1.0);
        (gl.clear)(0x4000);
        // 2×2 RGBA pixels: 16 bytes.
        for (what, khr, buf) in
            [("exact", false, 16), ("a byte short", false, 15), ("exact, KHR", true, 16), ("none", true, 0)]
        {
            r.readn(what, khr, [1, 1, 2, 2], RGBA, buf);
        }
        r.readn("an empty rectangle", false, [1, 1, 0, 2], RGBA, 0);
        r.readn("a negative width, short", false, [1, 1, -2, 2], RGBA, 4);
        // Rows of 5 pixels: the second row ends at 20 + 8 bytes.
        (gl.pixel_store_i)(0x0D02, 5);
        r.readn("row length 5, 28 bytes", false, [1, 1, 2, 2], RGBA, 28);
        r.readn("row length 5, 27 bytes", false, [1, 1, 2, 2], RGBA, 27);
        (gl.pixel_store_i)(0x0D02, 0);
        // A vec4 uniform: 16 bytes.
        let p = r.program(VS, FS);
        let u = (gl.get_uniform_location)(p, c"u".as_ptr());
        (gl.uniform4f)(u, 0.5, 1.5, -2.0, 4.0);
        for (buf, loc) in [(16, u), (12, u), (16, u + 7), (0, -1)] {
            let mut f = [-9.0f32; 4];
            (gl.getn_uniform_fv)(p, loc, buf, f.as_mut_ptr());
            r.note(&format!("uniform floats into {buf} bytes at {} {f:?}", loc - u));
            let mut i = [-9i32; 4];
            (gl.getn_uniform_iv)(p, loc, buf, i.as_mut_ptr());
            r.note(&format!("uniform integers into {buf} bytes at {} {i:?}", loc - u));
        }
    }
}

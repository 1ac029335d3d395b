//! `GL_EXT_draw_buffers` and `GL_NV_draw_buffers` through the C entry points: counts the
//! library refuses before reading the list, both names of the call, the selections read back,
//! and one draw into two attachments, each read back.

use super::*;

const FRAMEBUFFER: u32 = 0x8D40;
const CA0: u32 = 0x8CE0;
const TEXTURE_2D: u32 = 0x0DE1;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const DRAW_BUFFER0: u32 = 0x8825;
const BACK: u32 = 0x0405;

const VS: &str = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "#extension GL_EXT_draw_buffers : require
    precision mediump float;
    void main() { gl_FragData[0] = vec4(1.0, 0.5, 0.0, 1.0); gl_FragData[1] = vec4(0.0, 0.25, 1.0, 0.5); }";

impl Run {
    /// Calls `glDrawBuffersNV` (`nv`) or `glDrawBuffersEXT` with `n` and `list`; logs the error.
    fn draw_buffers(&mut self, what: &str, nv: bool, n: i32, list: Option<&[u32]>) {
        let f = if nv { self.gl.draw_buffers_nv } else { self.gl.draw_buffers_ext };
        // SAFETY: a context is current; `list` holds `n` enums, or is NULL where the count is
        // one both libraries refuse before reading it.
        unsafe { f(n, list.map_or(std::ptr::null(), <[u32]>::as_ptr)) };
        self.note(what);
    }

    /// Logs the first `n` draw buffers.
    fn selections(&mut self, n: u32) {
        let mut v = Vec::new();
        for i in 0..n {
            let mut x = [-7i32; 4];
            // SAFETY: a context is current; room for four values.
            unsafe { (self.gl.get_integerv)(DRAW_BUFFER0 + i, x.as_mut_ptr()) };
            v.push(format!("{:#x}", x[0]));
        }
        self.note(&format!("draw buffers {}", v.join(" ")));
    }
}

/// The draw-buffers sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    r.draw_buffers("EXT, count -1, no list", false, -1, None);
    r.draw_buffers("NV, count 9, no list", true, 9, None);
    r.draw_buffers("NV, back", true, 1, Some(&[BACK]));
    r.draw_buffers("EXT, none", false, 1, Some(&[0]));
    r.selections(2);
    r.draw_buffers("EXT, back", false, 1, Some(&[BACK]));
    // SAFETY: GL calls on the current context; every out-pointer has room.
    unsafe {
        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        let mut tex = [0u32; 2];
        (gl.gen_textures)(2, tex.as_mut_ptr());
        for (i, t) in tex.iter().enumerate() {
            (gl.bind_texture)(TEXTURE_2D, *t);
            (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
            (gl.framebuffer_texture_2d)(FRAMEBUFFER, CA0 + i as u32, TEXTURE_2D, *t, 0);
        }
        r.note(&format!("status {:#x}", (gl.check_framebuffer_status)(FRAMEBUFFER)));
        r.selections(3);
        r.draw_buffers("NV, both", true, 2, Some(&[CA0, CA0 + 1]));
        r.selections(3);
        r.draw_buffers("EXT, swapped", false, 2, Some(&[CA0 + 1, CA0]));
        r.draw_buffers("EXT, count 0", false, 0, None);
        r.selections(3);
        r.draw_buffers("EXT, both", false, 2, Some(&[CA0, CA0 + 1]));
        (gl.viewport)(0, 0, 8, 8);
        (gl.clear_color)(0.2, 0.2, 0.2, 0.2);
        (gl.clear)(0x4000);
        r.program(VS, FS);
        let quad: [f32; 12] = [-1.0, -1.0, 0.0, -1.0, 0.0, 1.0, -1.0, -1.0, 0.0, 1.0, -1.0, 1.0];
        (gl.bind_buffer)(0x8892, 0);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.draw_arrays)(0x0004, 0, 6);
        r.note("draw");
        for i in 0..2 {
            (gl.read_buffer_nv)(CA0 + i);
            for x in [1, 6] {
                let mut px = [0u8; 4];
                (gl.read_pixels)(x, 3, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
                r.note(&format!("attachment {i} at x {x}: {px:?}"));
            }
        }
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
    }
}

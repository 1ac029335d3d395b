//! `GL_EXT_draw_elements_base_vertex` and `GL_OES_draw_elements_base_vertex` through the C
//! entry points an application resolves: one index list drawn at two base vertices, from an
//! element buffer by the EXT name and from a client index array by the OES name, each picking
//! one of four coloured quads; and the errors of a bad mode, type and count.

use super::*;

const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNSIGNED_SHORT: u32 = 0x1403;
const FLOAT: u32 = 0x1406;
const TRIANGLES: u32 = 0x0004;
const ELEMENT_ARRAY: u32 = 0x8893;

const VS: &str = "attribute vec2 pos; attribute vec4 color; varying vec4 c;
    void main() { c = color; gl_Position = vec4(pos, 0.0, 1.0); }";
const FS: &str = "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }";

/// One quad's four corners, two triangles.
const INDICES: [u16; 6] = [0, 1, 2, 1, 3, 2];

/// Four quads, one in each quarter of the surface (bottom left, bottom right, top left, top
/// right): positions of 16 vertices, then their colours (red, green, blue, white).
fn vertices() -> Vec<f32> {
    let mut pos = Vec::new();
    let mut col = Vec::new();
    let colours = [[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0], [1.0, 1.0, 1.0, 1.0]];
    for (k, colour) in colours.iter().enumerate() {
        let (x0, y0) = (-1.0 + (k % 2) as f32, -1.0 + (k / 2) as f32);
        for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            pos.extend([x0 + dx, y0 + dy]);
            col.extend(*colour);
        }
    }
    pos.extend(col);
    pos
}

impl Run {
    /// Logs the pixel at the middle of each quarter of the 16×16 surface, and the error.
    fn quarters(&mut self, what: &str) {
        let mut px = [0u8; 16 * 16 * 4];
        // SAFETY: a context is current; room for the surface's pixels.
        unsafe { (self.gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
        let at = |x: usize, y: usize| {
            let i = (y * 16 + x) * 4;
            format!("{:02x}{:02x}{:02x}{:02x}", px[i], px[i + 1], px[i + 2], px[i + 3])
        };
        let shown = format!("{} {} {} {}", at(4, 4), at(12, 4), at(4, 12), at(12, 12));
        self.note(&format!("{what}: quarters {shown}"));
    }
}

/// The base-vertex sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    let program = r.program(VS, FS);
    let data = vertices();
    // SAFETY: GL calls on the current context; every pointer is to live memory of the size given.
    unsafe {
        let mut bufs = [0u32; 2];
        (gl.gen_buffers)(2, bufs.as_mut_ptr());
        (gl.bind_buffer)(ARRAY, bufs[0]);
        (gl.buffer_data)(ARRAY, (data.len() * 4) as isize, data.as_ptr().cast(), STATIC_DRAW);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, std::ptr::null());
        (gl.vertex_attrib_pointer)(1, 4, FLOAT, 0, 0, (16 * 2 * 4) as *const c_void);
        (gl.enable_vertex_attrib_array)(0);
        (gl.enable_vertex_attrib_array)(1);
        (gl.viewport)(0, 0, 16, 16);
        (gl.clear_color)(0.0, 0.0, 0.0, 1.0);
        (gl.clear)(0x4000);
        r.note("set up");
        // The EXT name, indices from an element buffer, based at the second quad.
        (gl.bind_buffer)(ELEMENT_ARRAY, bufs[1]);
        (gl.buffer_data)(ELEMENT_ARRAY, 12, INDICES.as_ptr().cast(), STATIC_DRAW);
        (gl.draw_elements_base_vertex_ext)(TRIANGLES, 6, UNSIGNED_SHORT, std::ptr::null(), 4);
        r.quarters("EXT, element buffer, base 4");
        // The OES name, indices from the application's memory, based at the third quad.
        (gl.bind_buffer)(ELEMENT_ARRAY, 0);
        (gl.draw_elements_base_vertex_oes)(TRIANGLES, 6, UNSIGNED_SHORT, INDICES.as_ptr().cast(), 8);
        r.quarters("OES, client indices, base 8");
        // Base 0 draws the first quad, as glDrawElements does.
        (gl.draw_elements_base_vertex_ext)(TRIANGLES, 6, UNSIGNED_SHORT, INDICES.as_ptr().cast(), 0);
        r.quarters("EXT, client indices, base 0");
        (gl.draw_elements_base_vertex_ext)(0x7FFF, 6, UNSIGNED_SHORT, INDICES.as_ptr().cast(), 12);
        r.note("EXT, a mode that is none");
        (gl.draw_elements_base_vertex_oes)(TRIANGLES, 6, FLOAT, INDICES.as_ptr().cast(), 12);
        r.note("OES, a type that is none");
        (gl.draw_elements_base_vertex_ext)(TRIANGLES, -1, UNSIGNED_SHORT, INDICES.as_ptr().cast(), 12);
        r.note("EXT, a negative count");
        r.quarters("after the refused draws");
        (gl.disable_vertex_attrib_array)(1);
        (gl.bind_buffer)(ARRAY, 0);
        (gl.delete_buffers)(2, bufs.as_ptr());
        (gl.delete_program)(program);
    }
}

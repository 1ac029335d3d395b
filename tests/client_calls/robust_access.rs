//! `EGL_EXT_create_context_robustness` and `GL_KHR_robust_buffer_access_behavior` through the
//! C entry points: the context attributes and their errors, the robust context's state, and
//! draws that read past their arrays or their index data, which draw reading zeros.

use super::*;

const ROBUST_ACCESS_EXT: i32 = 0x30BF;
const RESET_STRATEGY_EXT: i32 = 0x3138;
const LOSE_ON_RESET: i32 = 0x31BF;
const FLAGS_KHR: i32 = 0x30FC;
const ROBUST_BIT_KHR: i32 = 0x4;
const CONTEXT_ROBUST_ACCESS: u32 = 0x90F3;
const RESET_NOTIFICATION_STRATEGY: u32 = 0x8256;
const ELEMENT_ARRAY: u32 = 0x8893;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNSIGNED_SHORT: u32 = 0x1403;
const FLOAT: u32 = 0x1406;
const TRIANGLES: u32 = 0x0004;
const TRIANGLE_FAN: u32 = 0x0006;
const POINTS: u32 = 0x0000;

const VS: &str = "attribute vec4 pos; attribute vec4 color; varying vec4 v;
    void main() { v = color; gl_Position = pos; gl_PointSize = 3.0; }";
const FS: &str = "precision mediump float; varying vec4 v; void main() { gl_FragColor = v; }";

impl Run {
    /// Creates a context with `attribs` (after the client version); logs whether it was made
    /// and EGL's error.
    pub(super) fn context_with(&mut self, what: &str, attribs: &[i32]) -> Ptr {
        let list: Vec<i32> = [0x3098, 2].iter().chain(attribs).chain(&[NONE]).copied().collect();
        // SAFETY: EGL's prototypes; a NONE-terminated list.
        let (ctx, e) = unsafe {
            let ctx =
                (self.gl.egl_create_context)(self.egl.display, self.egl.config, std::ptr::null_mut(), list.as_ptr());
            (ctx, (self.gl.egl_get_error)())
        };
        self.log.push(format!("context {what}: made {}, EGL error {e:#x}", !ctx.is_null()));
        ctx
    }

    /// Clears, runs `draw`, logs its error and every fifth pixel of the 16×16 surface.
    fn drawn(&mut self, what: &str, draw: impl FnOnce(&Api)) {
        let gl = self.gl;
        let mut px = [0u8; 16 * 16 * 4];
        // SAFETY: a context is current; room for the surface's pixels.
        unsafe {
            (gl.clear_color)(0.5, 0.5, 0.5, 0.5);
            (gl.clear)(0x4000);
            draw(&gl);
            self.note(what);
            (gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        }
        let grid: Vec<String> = (0..16)
            .step_by(5)
            .flat_map(|y| (0..16).step_by(5).map(move |x| (y * 16 + x) * 4))
            .map(|i| format!("{:02x}{:02x}{:02x}{:02x}", px[i], px[i + 1], px[i + 2], px[i + 3]))
            .collect();
        self.log.push(format!("{what}: pixels {}", grid.join(" ")));
    }
}

/// The robust-access sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    let plain = r.context_with("plain", &[]);
    let robust = r.context_with("robust", &[ROBUST_ACCESS_EXT, 1]);
    let five = r.context_with("robust access 5", &[ROBUST_ACCESS_EXT, 5]);
    r.context_with("robust by the KHR flag", &[FLAGS_KHR, ROBUST_BIT_KHR]);
    let lose = r.context_with("losing on reset", &[RESET_STRATEGY_EXT, LOSE_ON_RESET]);
    r.context_with("reset strategy 7", &[RESET_STRATEGY_EXT, 7]);
    for (what, ctx) in [("plain", plain), ("robust", robust), ("robust access 5", five), ("losing on reset", lose)] {
        // SAFETY: this run's handles.
        unsafe { (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx) };
        let mut b = [7u8; 4];
        let mut strategy = [-1i32; 4];
        // SAFETY: a context is current; room for four values.
        unsafe {
            (gl.get_booleanv)(CONTEXT_ROBUST_ACCESS, b.as_mut_ptr());
            (gl.get_integerv)(RESET_NOTIFICATION_STRATEGY, strategy.as_mut_ptr());
        }
        r.note(&format!("{what}: robust access {}, reset strategy {:#x}", b[0], strategy[0]));
    }
    // SAFETY: this run's handles.
    unsafe { (gl.egl_make_current)(egl.display, egl.surface, egl.surface, robust) };
    r.program(VS, FS);
    let pos: [f32; 12] = [-1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, -1.0, 1.0, 1.0, -1.0, 1.0];
    let color: [f32; 12] = [1.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0];
    let indices: [u16; 6] = [0, 1, 2, 0, 2, 500];
    // SAFETY: GL calls on the current context; the arrays outlive the draws.
    unsafe {
        let mut b = [0u32; 3];
        (gl.gen_buffers)(3, b.as_mut_ptr());
        (gl.bind_buffer)(ARRAY, b[0]);
        (gl.buffer_data)(ARRAY, 48, pos.as_ptr().cast(), STATIC_DRAW);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, std::ptr::null());
        (gl.enable_vertex_attrib_array)(0);
        // Three colours for six vertices.
        (gl.bind_buffer)(ARRAY, b[1]);
        (gl.buffer_data)(ARRAY, 48, color.as_ptr().cast(), STATIC_DRAW);
        (gl.vertex_attrib_pointer)(1, 4, FLOAT, 0, 0, std::ptr::null());
        (gl.enable_vertex_attrib_array)(1);
        (gl.bind_buffer)(ELEMENT_ARRAY, b[2]);
        (gl.buffer_data)(ELEMENT_ARRAY, 12, indices.as_ptr().cast(), STATIC_DRAW);
    }
    r.drawn("six vertices from three colours", |gl| unsafe { (gl.draw_arrays)(TRIANGLES, 0, 6) });
    r.drawn("an index past every array", |gl| unsafe {
        (gl.draw_elements)(TRIANGLES, 6, UNSIGNED_SHORT, std::ptr::null())
    });
    r.drawn("indices past the element buffer", |gl| unsafe {
        (gl.draw_elements)(TRIANGLES, 12, UNSIGNED_SHORT, std::ptr::null())
    });
    r.drawn("a fan from vertex 1", |gl| unsafe { (gl.draw_arrays)(TRIANGLE_FAN, 1, 5) });
    r.drawn("points past the arrays", |gl| unsafe { (gl.draw_arrays)(POINTS, 1, 8) });
    // The plain context keeps GL's undefined behaviour for what lies past an array.
    // SAFETY: this run's handles.
    unsafe {
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        for ctx in [plain, robust, five, lose] {
            (gl.egl_destroy_context)(egl.display, ctx);
        }
    }
}

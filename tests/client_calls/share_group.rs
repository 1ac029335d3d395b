//! EGL share groups: a context made with another as its `share_context` sees the other's
//! buffers, textures, shaders, programs and framebuffers (ES 2.0 shares them all), not its
//! vertex arrays, whichever of the two is current; a context outside the group sees none of
//! them; what one uploads the other draws with, an element buffer's indices included (the
//! library reads them for a draw from client arrays); two threads draw at once, each with a
//! context of the group; a program deleted in one context while the other uses it stays until
//! that one stops; the group outlives the context that made its objects; a share context that
//! is no context is `EGL_BAD_CONTEXT`.

use super::*;

const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const UNSIGNED_SHORT: u32 = 0x1403;
const FLOAT: u32 = 0x1406;
const TEXTURE_2D: u32 = 0x0DE1;
const ELEMENT_ARRAY: u32 = 0x8893;
const FRAMEBUFFER: u32 = 0x8D40;
const TRIANGLE_FAN: u32 = 0x0006;
const TRIANGLES: u32 = 0x0004;
const NEAREST: i32 = 0x2600;
const MIN_FILTER: u32 = 0x2801;
const MAG_FILTER: u32 = 0x2800;
const VERSION: [i32; 3] = [0x3098, 2, NONE];

/// A window-filling quad.
const QUAD: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0];

/// The four quadrants' pixels of the current 16×16 surface.
///
/// # Safety
/// A context is current.
unsafe fn quadrant_pixels(gl: &Api) -> String {
    let mut px = [0u8; 16 * 16 * 4];
    // SAFETY: room for the surface's pixels.
    unsafe { (gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast()) };
    let at = |x: usize, y: usize| {
        let i = (y * 16 + x) * 4;
        format!("{:02x}{:02x}{:02x}{:02x}", px[i], px[i + 1], px[i + 2], px[i + 3])
    };
    format!("{} {} {} {}", at(4, 4), at(12, 4), at(4, 12), at(12, 12))
}

/// Clears the current 16×16 surface and draws the quad from the bound buffer.
///
/// # Safety
/// A context is current, with a program and the quad's buffer bound.
unsafe fn draw_quad(gl: &Api) {
    // SAFETY: see the function's contract.
    unsafe {
        (gl.viewport)(0, 0, 16, 16);
        (gl.clear_color)(0.0, 0.0, 0.0, 1.0);
        (gl.clear)(0x4000);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, std::ptr::null());
        (gl.enable_vertex_attrib_array)(0);
        (gl.draw_arrays)(TRIANGLE_FAN, 0, 4);
    }
}

impl Run {
    /// Logs which of the objects `names` (buffer, texture, program, framebuffer, vertex
    /// array) the current context knows.
    fn knows(&mut self, what: &str, [b, t, p, f, v]: [u32; 5]) {
        let gl = self.gl;
        // SAFETY: a context is current.
        let k = unsafe {
            [(gl.is_buffer)(b), (gl.is_texture)(t), (gl.is_program)(p), (gl.is_framebuffer)(f), (gl.is_vertex_array)(v)]
        };
        let [b, t, p, f, v] = k;
        self.note(&format!("{what}: buffer {b} texture {t} program {p} framebuffer {f} vertex array {v}"));
    }

    /// Clears, runs `draw`, and logs the error and the four quadrants' pixels.
    fn quadrants(&mut self, what: &str, draw: impl FnOnce(&Api)) {
        let gl = self.gl;
        // SAFETY: a context is current.
        let px = unsafe {
            (gl.viewport)(0, 0, 16, 16);
            (gl.clear_color)(0.0, 0.0, 0.0, 1.0);
            (gl.clear)(0x4000);
            draw(&gl);
            self.note(what);
            quadrant_pixels(&gl)
        };
        self.log.push(format!("{what}: pixels {px}"));
    }

    /// Makes `ctx` current on the run's pbuffer; logs the answer.
    fn current_on_pbuffer(&mut self, what: &str, ctx: Ptr) {
        let (gl, egl) = (self.gl, self.egl);
        // SAFETY: EGL's prototype with this run's handles.
        let ok = unsafe { (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx) };
        self.egl_note(what, i64::from(ok));
    }
}

/// The share-group sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    // SAFETY: GL and EGL calls with this run's handles; every pointer passed holds what the
    // call reads or writes.
    unsafe {
        let bogus = (gl.egl_create_context)(egl.display, egl.config, 0x5EA1_0000 as Ptr, VERSION.as_ptr());
        r.log.push(format!("share with no context: made {}, EGL error {:#x}", !bogus.is_null(), (gl.egl_get_error)()));
        // The run's context makes the objects: a program, a texture of four colours, the
        // quad's vertices, its indices, a framebuffer and a vertex array.
        let p = r.program(TEXTURED_VS, TEXTURED_FS);
        let mut t = 0;
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_2D, t);
        (gl.tex_parameteri)(TEXTURE_2D, MIN_FILTER, NEAREST);
        (gl.tex_parameteri)(TEXTURE_2D, MAG_FILTER, NEAREST);
        let texels: [u8; 16] = [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255];
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, texels.as_ptr().cast());
        let mut b = [0; 2];
        (gl.gen_buffers)(2, b.as_mut_ptr());
        (gl.bind_buffer)(ARRAY, b[0]);
        (gl.buffer_data)(ARRAY, std::mem::size_of_val(&QUAD) as isize, QUAD.as_ptr().cast(), STATIC_DRAW);
        let indices: [u16; 6] = [0, 1, 2, 0, 2, 3];
        (gl.bind_buffer)(ELEMENT_ARRAY, b[1]);
        (gl.buffer_data)(ELEMENT_ARRAY, 12, indices.as_ptr().cast(), STATIC_DRAW);
        let mut f = 0;
        (gl.gen_framebuffers)(1, &mut f);
        (gl.bind_framebuffer)(FRAMEBUFFER, f);
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        let mut v = 0;
        (gl.gen_vertex_arrays)(1, &mut v);
        (gl.bind_vertex_array)(v);
        (gl.bind_vertex_array)(0);
        r.note("objects made");
        let names = [b[0], t, p, f, v];

        let shared = (gl.egl_create_context)(egl.display, egl.config, egl.context, VERSION.as_ptr());
        r.log.push(format!("sharing context: made {}, EGL error {:#x}", !shared.is_null(), (gl.egl_get_error)()));
        if shared.is_null() {
            return;
        }
        r.current_on_pbuffer("the sharing context current", shared);
        r.knows("the sharing context", names);
        // Its own bindings: the program, texture and buffers bound again.
        r.quadrants("drawn from the shared buffer", |gl| {
            (gl.use_program)(p);
            (gl.bind_texture)(TEXTURE_2D, t);
            (gl.bind_buffer)(ARRAY, b[0]);
            draw_quad(gl);
        });
        r.quadrants("drawn from a client array with the shared indices", |gl| {
            (gl.bind_buffer)(ARRAY, 0);
            (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, QUAD.as_ptr().cast());
            (gl.bind_buffer)(ELEMENT_ARRAY, b[1]);
            (gl.draw_elements)(TRIANGLES, 6, UNSIGNED_SHORT, std::ptr::null());
        });
        // What it uploads, the other context draws.
        let green = [0u8, 255, 0, 255].repeat(4);
        (gl.tex_sub_image_2d)(TEXTURE_2D, 0, 0, 0, 2, 2, RGBA, UNSIGNED_BYTE, green.as_ptr().cast());
        (gl.bind_buffer)(ARRAY, b[0]);
        r.note("uploaded");
        r.current_on_pbuffer("the first context current again", egl.context);
        r.quadrants("the first context draws the upload", |gl| {
            (gl.bind_buffer)(ARRAY, b[0]);
            draw_quad(gl);
        });

        // A context outside the group sees none of it.
        let other = (gl.egl_create_context)(egl.display, egl.config, std::ptr::null_mut(), VERSION.as_ptr());
        r.current_on_pbuffer("a context of its own current", other);
        r.knows("a context of its own", names);
        r.current_on_pbuffer("the first context current again", egl.context);
        r.egl_note("destroy it", i64::from((gl.egl_destroy_context)(egl.display, other)));

        // Two threads draw at once, each with a context of the group on a pbuffer of its own.
        let second = (gl.egl_create_pbuffer)(egl.display, egl.config, [0x3057, 16, 0x3056, 16, NONE].as_ptr());
        let (api, dpy, surface, ctx) = (gl, egl.display as usize, second as usize, shared as usize);
        let thread = std::thread::spawn(move || {
            let (dpy, surface, ctx) = (dpy as Ptr, surface as Ptr, ctx as Ptr);
            // EGL and GL calls with the run's display, its own pbuffer and the sharing context,
            // whose program, texture and buffer are bound (inside the unsafe block above).
            let current = (api.egl_make_current)(dpy, surface, surface, ctx);
            for _ in 0..20 {
                draw_quad(&api);
            }
            let px = quadrant_pixels(&api);
            let error = (api.get_error)();
            (api.egl_make_current)(dpy, std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut());
            format!("current {current}, error {error:#x}, pixels {px}")
        });
        for _ in 0..20 {
            draw_quad(&gl);
        }
        let px = quadrant_pixels(&gl);
        r.note(&format!("drawn at once, this thread: pixels {px}"));
        let theirs = thread.join().unwrap_or_else(|_| "the thread panicked".into());
        r.log.push(format!("drawn at once, the other thread: {theirs}"));
        r.egl_note("its pbuffer destroyed", i64::from((gl.egl_destroy_surface)(egl.display, second)));

        // A program deleted in the sharing context while the first uses it stays until then.
        r.current_on_pbuffer("the sharing context current", shared);
        (gl.use_program)(0);
        (gl.delete_program)(p);
        r.note("the program deleted in the sharing context");
        r.knows("the sharing context after", names);
        r.current_on_pbuffer("the first context current again", egl.context);
        r.quadrants("the first context still draws with it", |gl| draw_quad(gl));
        (gl.use_program)(0);
        r.knows("once the first context stops using it", names);

        // The group outlives the sharing context.
        r.egl_note("destroy the sharing context", i64::from((gl.egl_destroy_context)(egl.display, shared)));
        r.knows("the first context after", names);
        let p2 = r.program(TEXTURED_VS, TEXTURED_FS);
        r.quadrants("drawn after", |gl| draw_quad(gl));
        (gl.disable_vertex_attrib_array)(0);
        (gl.bind_buffer)(ARRAY, 0);
        (gl.bind_buffer)(ELEMENT_ARRAY, 0);
        (gl.delete_buffers)(2, b.as_ptr());
        (gl.delete_textures)(1, &t);
        (gl.use_program)(0);
        (gl.delete_program)(p2);
        (gl.delete_framebuffers)(1, &f);
        (gl.delete_vertex_arrays)(1, &v);
        r.note("cleaned up");
    }
}

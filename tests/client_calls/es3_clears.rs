//! ES 3.0's `glClearBuffer*` and `glGetFragDataLocation` in an ES 3.0 context: one draw buffer
//! of two cleared at a time (whole, under a scissor, under a colour mask, a draw buffer set to
//! `GL_NONE`), the depth and the stencil cleared on their own and together and then tested by
//! draws, every call's errors; fragment output locations by name, and their errors.

use std::ffi::CString;

use super::*;

const FRAMEBUFFER: u32 = 0x8D40;
const RENDERBUFFER: u32 = 0x8D41;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const DEPTH_STENCIL_ATTACHMENT: u32 = 0x821A;
const DEPTH24_STENCIL8: u32 = 0x88F0;
const TEXTURE_2D: u32 = 0x0DE1;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const FLOAT: u32 = 0x1406;
const COLOR: u32 = 0x1800;
const DEPTH: u32 = 0x1801;
const STENCIL: u32 = 0x1802;
const DEPTH_STENCIL: u32 = 0x84F9;
const NONE_BUFFER: u32 = 0;
const SCISSOR_TEST: u32 = 0x0C11;
const DEPTH_TEST: u32 = 0x0B71;
const STENCIL_TEST: u32 = 0x0B90;
const LESS: u32 = 0x0201;
const EQUAL: u32 = 0x0202;
const TRIANGLE_STRIP: u32 = 0x0005;

/// A blue quad at the depth the uniform `z` gives.
const VS_Z: &str = "#version 300 es
    layout(location = 0) in vec2 pos; uniform float z;
    void main() { gl_Position = vec4(pos, z, 1.0); }";
const FS_BLUE: &str = "#version 300 es
    precision mediump float; out vec4 o; void main() { o = vec4(0.0, 0.0, 1.0, 1.0); }";
/// Two outputs at locations 1 and 0.
const FS_TWO: &str = "#version 300 es
    precision mediump float; layout(location = 1) out vec4 a; layout(location = 0) out vec4 b;
    void main() { a = vec4(1.0); b = vec4(0.5); }";
/// One output without a location.
const FS_LONE: &str = "#version 300 es
    precision mediump float; out vec4 lone; void main() { lone = vec4(1.0); }";
const VS_100: &str = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";
const FS_100: &str = "precision mediump float; void main() { gl_FragColor = vec4(1.0); }";

/// Logs colour attachment `i`'s pixels at three places (left, middle, right of row 8).
fn pixels(r: &mut Run, i: u32, what: &str) {
    let mut px = vec![0u8; 16 * 16 * 4];
    // SAFETY: a context is current; `px` holds the 16×16 RGBA8 pixels.
    unsafe {
        (r.gl.core_read_buffer)(COLOR_ATTACHMENT0 + i);
        (r.gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
    }
    let at = |x: usize, y: usize| px[(y * 16 + x) * 4..(y * 16 + x) * 4 + 4].to_vec();
    r.note(&format!("{what}, buffer {i}: {:?} {:?} {:?}", at(1, 8), at(8, 8), at(14, 8)));
}

/// Logs `name`'s location in `program` (`what`).
fn location(r: &mut Run, program: u32, what: &str, name: &str) {
    let c = CString::new(name).expect("a name");
    // SAFETY: a context is current; `c` is NUL-terminated.
    let l = unsafe { (r.gl.get_frag_data_location)(program, c.as_ptr()) };
    r.note(&format!("glGetFragDataLocation({what}, {name:?}) = {l}"));
}

/// The clear-buffer sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; every pointer holds what the call reads or
    // writes; the client array outlives the draws that read it.
    unsafe {
        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        let mut tex = [0u32; 2];
        (gl.gen_textures)(2, tex.as_mut_ptr());
        for (i, &t) in tex.iter().enumerate() {
            (gl.bind_texture)(TEXTURE_2D, t);
            (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 16, 16, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
            (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0 + i as u32, TEXTURE_2D, t, 0);
        }
        let mut rb = 0;
        (gl.gen_renderbuffers)(1, &mut rb);
        (gl.bind_renderbuffer)(RENDERBUFFER, rb);
        (gl.renderbuffer_storage)(RENDERBUFFER, DEPTH24_STENCIL8, 16, 16);
        (gl.framebuffer_renderbuffer)(FRAMEBUFFER, DEPTH_STENCIL_ATTACHMENT, RENDERBUFFER, rb);
        r.note(&format!("framebuffer status {:#x}", (gl.check_framebuffer_status)(FRAMEBUFFER)));
        (gl.viewport)(0, 0, 16, 16);
        (gl.core_draw_buffers)(2, [COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1].as_ptr());

        // Each draw buffer on its own.
        (gl.clear_buffer_fv)(COLOR, 0, [1.0, 0.0, 0.0, 1.0].as_ptr());
        (gl.clear_buffer_fv)(COLOR, 1, [0.0, 1.0, 0.0, 1.0].as_ptr());
        pixels(r, 0, "buffer 0 red");
        pixels(r, 1, "buffer 1 green");
        // Under a scissor, values past [0, 1] clamped in a normalized image.
        (gl.enable)(SCISSOR_TEST);
        (gl.scissor)(4, 0, 8, 16);
        (gl.clear_buffer_fv)(COLOR, 1, [2.0, -1.0, 0.5, 1.0].as_ptr());
        (gl.disable)(SCISSOR_TEST);
        pixels(r, 0, "buffer 1 cleared in a scissor");
        pixels(r, 1, "buffer 1 cleared in a scissor");
        // Under a colour mask.
        (gl.color_mask)(0, 1, 1, 1);
        (gl.clear_buffer_fv)(COLOR, 0, [1.0, 1.0, 1.0, 1.0].as_ptr());
        (gl.color_mask)(1, 1, 1, 1);
        pixels(r, 0, "buffer 0 cleared without red");
        // A draw buffer set to GL_NONE clears nothing.
        (gl.core_draw_buffers)(2, [NONE_BUFFER, COLOR_ATTACHMENT0 + 1].as_ptr());
        (gl.clear_buffer_fv)(COLOR, 0, [0.0, 0.0, 0.0, 0.0].as_ptr());
        r.note("a clear of a draw buffer that is GL_NONE");
        pixels(r, 0, "after clearing a GL_NONE draw buffer");
        (gl.clear_buffer_fv)(COLOR, 1, [0.0, 0.0, 0.0, 1.0].as_ptr());
        pixels(r, 1, "draw buffer 1 of (NONE, COLOR1)");
        (gl.core_draw_buffers)(1, [COLOR_ATTACHMENT0].as_ptr());

        // The depth, then a quad in front of it and one behind.
        let p = r.program(VS_Z, FS_BLUE);
        let z = (gl.get_uniform_location)(p, c"z".as_ptr());
        let quad: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        // A client array: no buffer bound (an earlier sequence may have left one).
        (gl.bind_buffer)(ARRAY, 0);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.enable)(DEPTH_TEST);
        (gl.depth_func)(LESS);
        (gl.clear_buffer_fv)(COLOR, 0, [0.0, 0.0, 0.0, 1.0].as_ptr());
        (gl.clear_buffer_fv)(DEPTH, 0, [0.25].as_ptr());
        r.note("glClearBufferfv of the depth");
        for (depth, what) in [(0.0f32, "behind the cleared depth"), (-0.8, "in front of it")] {
            (gl.uniform1f)(z, depth);
            (gl.draw_arrays)(TRIANGLE_STRIP, 0, 4);
            pixels(r, 0, &format!("a quad {what}"));
        }
        (gl.disable)(DEPTH_TEST);
        // The stencil, then a draw where it equals the value.
        (gl.enable)(STENCIL_TEST);
        for (clear, what) in [(5, "the stencil 5"), (3, "the stencil 3")] {
            (gl.clear_buffer_fv)(COLOR, 0, [0.0, 0.0, 0.0, 1.0].as_ptr());
            (gl.clear_buffer_iv)(STENCIL, 0, [clear].as_ptr());
            (gl.stencil_func)(EQUAL, 5, 0xff);
            (gl.draw_arrays)(TRIANGLE_STRIP, 0, 4);
            pixels(r, 0, &format!("a quad drawn where the stencil is 5, cleared to {what}"));
        }
        // Both together.
        (gl.clear_buffer_fv)(COLOR, 0, [0.0, 0.0, 0.0, 1.0].as_ptr());
        (gl.clear_buffer_fi)(DEPTH_STENCIL, 0, 0.75, 5);
        (gl.enable)(DEPTH_TEST);
        (gl.uniform1f)(z, 0.0);
        (gl.draw_arrays)(TRIANGLE_STRIP, 0, 4);
        pixels(r, 0, "a quad in front of depth 0.75 where the stencil is 5");
        (gl.disable)(DEPTH_TEST);
        (gl.disable)(STENCIL_TEST);

        // The errors.
        let four = [0.0f32; 4];
        let ints = [0i32; 4];
        let uints = [0u32; 4];
        for (buffer, drawbuffer) in
            [(STENCIL, 0), (DEPTH_STENCIL, 0), (COLOR, -1), (COLOR, 32), (DEPTH, 1), (0x1234, 0)]
        {
            (gl.clear_buffer_fv)(buffer, drawbuffer, four.as_ptr());
            r.note(&format!("glClearBufferfv({buffer:#x}, {drawbuffer})"));
        }
        for (buffer, drawbuffer) in [(DEPTH, 0), (STENCIL, 1), (COLOR, 32), (DEPTH_STENCIL, 0)] {
            (gl.clear_buffer_iv)(buffer, drawbuffer, ints.as_ptr());
            r.note(&format!("glClearBufferiv({buffer:#x}, {drawbuffer})"));
        }
        for (buffer, drawbuffer) in [(STENCIL, 0), (DEPTH, 0), (COLOR, -1)] {
            (gl.clear_buffer_uiv)(buffer, drawbuffer, uints.as_ptr());
            r.note(&format!("glClearBufferuiv({buffer:#x}, {drawbuffer})"));
        }
        for (buffer, drawbuffer) in [(COLOR, 0), (DEPTH, 0), (DEPTH_STENCIL, 1), (DEPTH_STENCIL, 0)] {
            (gl.clear_buffer_fi)(buffer, drawbuffer, 1.0, 0);
            r.note(&format!("glClearBufferfi({buffer:#x}, {drawbuffer})"));
        }
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        (gl.delete_framebuffers)(1, &fb);

        // Fragment output locations.
        let two = r.program(VS_Z, FS_TWO);
        for name in ["a", "b", "c", "gl_FragColor", ""] {
            location(r, two, "two outputs", name);
        }
        let lone = r.program(VS_Z, FS_LONE);
        location(r, lone, "one output", "lone");
        let old = r.program(VS_100, FS_100);
        location(r, old, "GLSL ES 1.00", "gl_FragColor");
        let unlinked = (gl.create_program)();
        location(r, unlinked, "not linked", "a");
        location(r, 0xBEEF, "no program", "a");
        let shader = (gl.create_shader)(0x8B30);
        location(r, shader, "a shader", "a");
    }
}

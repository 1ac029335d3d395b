//! `EGL_KHR_gl_colorspace`: pbuffers asked for sRGB and linear colour, queried; an sRGB one
//! cleared, drawn over with blending (which adds in linear terms), copied into a texture's
//! image (a new image cannot be: ES 2.0 has no sRGB format for it) and read back as the
//! encoded bytes it stores, also after a swap (which a pbuffer's shows nothing); and a colour
//! space that is neither.

use super::*;

const COLORSPACE: i32 = 0x309D;
const SRGB: i32 = 0x3089;
const LINEAR: i32 = 0x308A;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
const TEXTURE_2D: u32 = 0x0DE1;

/// A fragment stage of one colour.
const FS_QUARTER: &str = "precision mediump float; void main() { gl_FragColor = vec4(0.25, 0.5, 0.125, 0.25); }";
const VS_QUAD: &str = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";

/// The colour space sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    // SAFETY: EGL and GL calls with a context; NONE-terminated lists; room for the pixels.
    unsafe {
        let make = |space: i32| {
            let attribs = [0x3057, 4, 0x3056, 4, COLORSPACE, space, NONE];
            (gl.egl_create_pbuffer)(egl.display, egl.config, attribs.as_ptr())
        };
        let bad = make(0x1234);
        r.log.push(format!(
            "a colour space that is neither: made {}, error {:#x}",
            !bad.is_null(),
            (gl.egl_get_error)()
        ));
        let (srgb, linear) = (make(SRGB), make(LINEAR));
        for (what, s) in [("sRGB", srgb), ("linear", linear), ("the first", egl.surface)] {
            let mut v = -1;
            let ok = (gl.egl_query_surface)(egl.display, s, COLORSPACE, &mut v);
            r.log.push(format!("{what} surface's colour space: {ok} {v:#x}"));
        }
        for (what, s) in [("sRGB", srgb), ("linear", linear)] {
            (gl.egl_make_current)(egl.display, s, s, egl.context);
            (gl.viewport)(0, 0, 4, 4);
            (gl.disable)(0x0BE2);
            (gl.clear_color)(0.5, 0.2, 0.8, 0.5);
            (gl.clear)(0x4000);
            let mut px = [0u8; 4];
            (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
            r.note(&format!("{what}: cleared, read {px:?}"));
            // One draw adds a quarter (and so on) to a cleared quarter, blending ONE, ONE.
            (gl.clear_color)(0.25, 0.5, 0.125, 0.25);
            (gl.clear)(0x4000);
            r.program(VS_QUAD, FS_QUARTER);
            (gl.enable)(0x0BE2);
            (gl.blend_func)(1, 1);
            let quad = [-1.0f32, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
            (gl.bind_buffer)(ARRAY, 0);
            (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, quad.as_ptr().cast());
            (gl.enable_vertex_attrib_array)(0);
            (gl.draw_arrays)(0x0005, 0, 4);
            (gl.disable)(0x0BE2);
            (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
            r.note(&format!("{what}: blended, read {px:?}"));
            // A pbuffer's swap shows nothing and keeps the contents (the library answers it
            // without waiting for the daemon).
            let ok = (gl.egl_swap_buffers)(egl.display, s);
            r.log.push(format!("{what}: swapped {ok}, error {:#x}", (gl.egl_get_error)()));
            (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
            r.note(&format!("{what}: after the swap, read {px:?}"));
            // The stored bytes copied into a texture, then read through a framebuffer.
            let mut t = 0;
            (gl.gen_textures)(1, &mut t);
            (gl.bind_texture)(TEXTURE_2D, t);
            (gl.copy_tex_image_2d)(TEXTURE_2D, 0, RGBA, 0, 0, 2, 2, 0);
            r.note(&format!("{what}: a new image copied"));
            (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
            (gl.copy_tex_sub_image_2d)(TEXTURE_2D, 0, 0, 0, 0, 0, 2, 2);
            let mut fb = 0;
            (gl.gen_framebuffers)(1, &mut fb);
            (gl.bind_framebuffer)(0x8D40, fb);
            (gl.framebuffer_texture_2d)(0x8D40, 0x8CE0, TEXTURE_2D, t, 0);
            (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
            r.note(&format!("{what}: copied into a texture, read {px:?}"));
            (gl.bind_framebuffer)(0x8D40, 0);
            (gl.delete_textures)(1, &t);
        }
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        for s in [srgb, linear] {
            (gl.egl_destroy_surface)(egl.display, s);
        }
        r.note("back on the first surface");
    }
}

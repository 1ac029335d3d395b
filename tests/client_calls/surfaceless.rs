//! `EGL_KHR_surfaceless_context` and `GL_OES_surfaceless_context`: a context made current with
//! no surface has no default framebuffer (its status, bits, read format, clears and reads),
//! renders into a framebuffer object, and takes its viewport from the first surface it is
//! later made current with.

use super::*;

const EGL_NO_SURFACE: Ptr = std::ptr::null_mut();
const EGL_DRAW: i32 = 0x3059;
const EGL_READ: i32 = 0x305A;
const FRAMEBUFFER: u32 = 0x8D40;
const COLOR_ATTACHMENT0: u32 = 0x8CE0;
const TEXTURE_2D: u32 = 0x0DE1;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;

impl Run {
    /// Makes `context` current on `draw` and `read`; logs the answer and EGL's error.
    fn make_current(&mut self, what: &str, draw: Ptr, read: Ptr, context: Ptr) {
        // SAFETY: EGL's prototypes; the handles are this run's or EGL_NO_*.
        let (ok, e) =
            unsafe { ((self.gl.egl_make_current)(self.egl.display, draw, read, context), (self.gl.egl_get_error)()) };
        self.log.push(format!("make current {what}: {ok}, EGL error {e:#x}"));
    }

    /// Logs one integer state's values (`n` of them), and the error.
    fn integers(&mut self, what: &str, pname: u32, n: usize) {
        let mut v = [-7i32; 4];
        // SAFETY: a context is current; room for four values.
        unsafe { (self.gl.get_integerv)(pname, v.as_mut_ptr()) };
        self.note(&format!("{what} {:?}", &v[..n]));
    }
}

/// The surfaceless sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    // SAFETY: EGL and GL calls with this run's handles; every out-pointer has room.
    unsafe {
        let ctx = (gl.egl_create_context)(egl.display, egl.config, std::ptr::null_mut(), [0x3098, 2, NONE].as_ptr());
        r.log.push(format!("second context made: {}", !ctx.is_null()));
        r.make_current("with no surface", EGL_NO_SURFACE, EGL_NO_SURFACE, ctx);
        let (draw, read) = ((gl.egl_get_current_surface)(EGL_DRAW), (gl.egl_get_current_surface)(EGL_READ));
        r.log.push(format!("current surfaces: none {} {}", draw.is_null(), read.is_null()));
        r.integers("viewport", 0x0BA2, 4);
        r.integers("scissor box", 0x0C10, 4);
        for (what, pname) in
            [("red bits", 0x0D52), ("alpha bits", 0x0D55), ("depth bits", 0x0D56), ("stencil bits", 0x0D57)]
        {
            r.integers(what, pname, 1);
        }
        r.integers("read format", 0x8B9B, 1);
        r.integers("read type", 0x8B9A, 1);
        let status = (gl.check_framebuffer_status)(FRAMEBUFFER);
        r.note(&format!("framebuffer 0's status {status:#x}"));
        (gl.clear)(0x4000);
        r.note("clear");
        let mut px = [0u8; 4];
        (gl.read_pixels)(0, 0, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note("read");
        let ok = (gl.egl_swap_interval)(egl.display, 1);
        r.log.push(format!("swap interval: {ok}, EGL error {:#x}", (gl.egl_get_error)()));
        // A framebuffer object works as anywhere.
        let (mut t, mut fb) = (0, 0);
        (gl.gen_textures)(1, &mut t);
        (gl.bind_texture)(TEXTURE_2D, t);
        (gl.tex_image_2d)(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, std::ptr::null());
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(FRAMEBUFFER, fb);
        (gl.framebuffer_texture_2d)(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0);
        let status = (gl.check_framebuffer_status)(FRAMEBUFFER);
        r.note(&format!("a framebuffer object's status {status:#x}"));
        (gl.viewport)(0, 0, 4, 4);
        (gl.clear_color)(1.0, 0.5, 0.25, 1.0);
        (gl.clear)(0x4000);
        (gl.read_pixels)(1, 1, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note(&format!("cleared and read {px:?}"));
        r.integers("read format of the object", 0x8B9B, 1);
        (gl.bind_framebuffer)(FRAMEBUFFER, 0);
        // Made current with a surface at last: the viewport the application set is replaced
        // by the surface's size, as a first binding to a surface sets it.
        r.make_current("with the pbuffer", egl.surface, egl.surface, ctx);
        r.integers("viewport with a surface", 0x0BA2, 4);
        let status = (gl.check_framebuffer_status)(FRAMEBUFFER);
        r.note(&format!("framebuffer 0's status with a surface {status:#x}"));
        // Back to no surface, then the first context again.
        r.make_current("with no surface again", EGL_NO_SURFACE, EGL_NO_SURFACE, ctx);
        r.integers("viewport kept", 0x0BA2, 4);
        r.make_current("the first context", egl.surface, egl.surface, egl.context);
        let ok = (gl.egl_destroy_context)(egl.display, ctx);
        r.log.push(format!("second context destroyed: {ok}"));
    }
}

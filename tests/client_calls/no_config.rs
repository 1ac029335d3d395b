//! `EGL_KHR_no_config_context`: a context made with `EGL_NO_CONFIG_KHR`, its config id, and
//! framebuffer 0's bits following each surface it is made current with (two configs that
//! differ in alpha and depth), with no surface, shared, drawing; a config that is none.

use super::*;

const EGL_CONFIG_ID: i32 = 0x3028;
const ALPHA_SIZE: i32 = 0x3021;
const DEPTH_SIZE: i32 = 0x3025;
const RED_SIZE: i32 = 0x3024;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;

impl Run {
    /// A pbuffer of the first config with `alpha` and `depth` bits (at least), and that config.
    fn pbuffer_with(&mut self, alpha: i32, depth: i32) -> (Ptr, Ptr) {
        let want =
            [0x3033, 1, 0x3040, 4, RED_SIZE, 8, 0x3023, 8, 0x3022, 8, ALPHA_SIZE, alpha, DEPTH_SIZE, depth, NONE];
        let (mut config, mut n) = (std::ptr::null_mut(), 0);
        // SAFETY: EGL's prototypes; a NONE-terminated list and room for one config.
        let surface = unsafe {
            (self.gl.egl_choose_config)(self.egl.display, want.as_ptr(), &mut config, 1, &mut n);
            (self.gl.egl_create_pbuffer)(self.egl.display, config, [0x3057, 8, 0x3056, 8, NONE].as_ptr())
        };
        self.log.push(format!("pbuffer with alpha {alpha}, depth {depth}: made {}", !surface.is_null()));
        (surface, config)
    }

    /// Logs whether framebuffer 0's alpha and depth bits are `config`'s, and the error.
    fn bits_of(&mut self, what: &str, config: Ptr) {
        let mut want = Vec::new();
        let mut got = Vec::new();
        for (attrib, pname) in [(ALPHA_SIZE, 0x0D55), (DEPTH_SIZE, 0x0D56), (RED_SIZE, 0x0D52)] {
            let (mut w, mut g) = (-1, [-1i32; 4]);
            // SAFETY: EGL's and GL's prototypes; room for the values.
            unsafe {
                (self.gl.egl_get_config_attrib)(self.egl.display, config, attrib, &mut w);
                (self.gl.get_integerv)(pname, g.as_mut_ptr());
            }
            want.push(w);
            got.push(g[0]);
        }
        self.note(&format!("{what}: alpha, depth and red bits are the surface config's: {}", want == got));
    }
}

/// The no-config sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    let attribs = [0x3098, 2, NONE];
    // SAFETY: EGL and GL calls with this run's handles; every out-pointer has room.
    unsafe {
        let ctx = (gl.egl_create_context)(egl.display, std::ptr::null_mut(), std::ptr::null_mut(), attribs.as_ptr());
        r.log.push(format!("no-config context: made {}, EGL error {:#x}", !ctx.is_null(), (gl.egl_get_error)()));
        let mut id = -1;
        let ok = (gl.egl_query_context)(egl.display, ctx, EGL_CONFIG_ID, &mut id);
        r.log.push(format!("its config id: {id} ({ok})"));
        let (a, config_a) = r.pbuffer_with(8, 0);
        let (b, config_b) = r.pbuffer_with(0, 24);
        for (what, s, c) in [("the first surface", a, config_a), ("the second surface", b, config_b)] {
            let ok = (gl.egl_make_current)(egl.display, s, s, ctx);
            r.log.push(format!("current with {what}: {ok}, EGL error {:#x}", (gl.egl_get_error)()));
            r.bits_of(what, c);
        }
        (gl.clear_color)(0.25, 0.5, 0.75, 1.0);
        (gl.clear)(0x4000);
        let mut px = [0u8; 4];
        (gl.read_pixels)(2, 2, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note(&format!("cleared and read {px:?}"));
        let ok = (gl.egl_make_current)(egl.display, std::ptr::null_mut(), std::ptr::null_mut(), ctx);
        r.log.push(format!("current with no surface: {ok}, EGL error {:#x}", (gl.egl_get_error)()));
        let shared = (gl.egl_create_context)(egl.display, std::ptr::null_mut(), ctx, attribs.as_ptr());
        r.log.push(format!(
            "a shared no-config context: made {}, EGL error {:#x}",
            !shared.is_null(),
            (gl.egl_get_error)()
        ));
        let bad = (gl.egl_create_context)(egl.display, 0x1234 as Ptr, std::ptr::null_mut(), attribs.as_ptr());
        r.log.push(format!("a config that is none: made {}, EGL error {:#x}", !bad.is_null(), (gl.egl_get_error)()));
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        for c in [ctx, shared] {
            (gl.egl_destroy_context)(egl.display, c);
        }
        for s in [a, b] {
            (gl.egl_destroy_surface)(egl.display, s);
        }
    }
}

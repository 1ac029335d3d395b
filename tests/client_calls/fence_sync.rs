//! `EGL_KHR_fence_sync`, `EGL_KHR_reusable_sync` and `EGL_KHR_wait_sync`, with
//! `GL_OES_EGL_sync` in the GL extension string: fences' attributes, their status before and
//! after `glFinish`, fences signalled by polls alone, waits that poll and waits that block, the
//! errors for bad displays, types, attributes and handles, a fence asked for with no context
//! current; a reusable sync signalled and unsignalled, waited for with a timeout, and
//! signalled by another thread while this one waits. (A sync destroyed while another thread
//! waits on it is not compared: Mesa frees it under the waiter. `tests/egl_threads.rs` holds
//! Strata to the extension's words instead.)

use super::*;

const SYNC_FENCE: u32 = 0x30F9;
const SYNC_REUSABLE: u32 = 0x30FA;
const SYNC_TYPE: i32 = 0x30F7;
const SYNC_STATUS: i32 = 0x30F1;
const SYNC_CONDITION: i32 = 0x30F8;
const SIGNALED: i32 = 0x30F2;
const UNSIGNALED: i32 = 0x30F3;
const TIMEOUT_EXPIRED: i32 = 0x30F5;
const CONDITION_SATISFIED: i32 = 0x30F6;
const FOREVER: u64 = u64::MAX;

/// A fragment stage slow enough that a 256×256 image of it takes milliseconds on a CPU
/// rasterizer: a fence made right after drawing it is not yet signalled.
pub(super) const SLOW_FS: &str = "precision highp float;
    void main() {
        float x = gl_FragCoord.x * 0.001;
        for (int i = 0; i < 200; i++) { x = fract(sin(x * 12.9898 + float(i)) * 43758.5453); }
        gl_FragColor = vec4(x, 0.0, 0.0, 1.0);
    }";

/// Not a sync: the address of a constant of this program, as piglit passes.
static CANARY: u32 = 0x3141_5926;

impl Run {
    /// Creates a sync; logs whether one came and EGL's error.
    fn create_sync(&mut self, what: &str, dpy: Ptr, ty: u32, attribs: *const i32) -> Ptr {
        // SAFETY: EGL's prototype; `attribs` is NULL or EGL_NONE-terminated.
        let (s, e) = unsafe { ((self.gl.egl_create_sync)(dpy, ty, attribs), (self.gl.egl_get_error)()) };
        self.log.push(format!("create {what}: made {}, EGL error {e:#x}", !s.is_null()));
        s
    }

    /// Logs `f`'s answer and EGL's error.
    pub(super) fn egl_note(&mut self, what: &str, answer: i64) {
        // SAFETY: eglGetError's prototype.
        let e = unsafe { (self.gl.egl_get_error)() };
        self.log.push(format!("{what}: {answer:#x}, EGL error {e:#x}"));
    }

    /// Logs a sync attribute, with the value left where the call fails.
    fn sync_attrib(&mut self, what: &str, sync: Ptr, attribute: i32) {
        let mut v = 0x3141_5926;
        // SAFETY: EGL's prototype; one value.
        let ok = unsafe { (self.gl.egl_get_sync_attrib)(self.egl.display, sync, attribute, &mut v) };
        self.egl_note(&format!("{what} (value {v:#x})"), i64::from(ok));
    }
}

/// Whether `signalled` answers true within 2 s of asking every millisecond. How long it took
/// goes to the test's output, not into the comparison.
pub(super) fn polled(signalled: impl Fn() -> bool) -> bool {
    let start = std::time::Instant::now();
    let deadline = start + std::time::Duration::from_secs(2);
    while std::time::Instant::now() < deadline {
        if signalled() {
            eprintln!("a fence signalled by polls after {:.1} ms", start.elapsed().as_secs_f64() * 1e3);
            return true;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
    false
}

/// The fence-sync sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    let canary = std::ptr::addr_of!(CANARY) as Ptr;
    // SAFETY: glGetString's prototype; the answer is NUL-terminated or NULL.
    let extensions = unsafe {
        let s = (gl.get_string)(0x1F03);
        if s.is_null() {
            String::new()
        } else {
            std::ffi::CStr::from_ptr(s.cast()).to_string_lossy().into_owned()
        }
    };
    r.log.push(format!("GL_OES_EGL_sync offered: {}", extensions.split(' ').any(|e| e == "GL_OES_EGL_sync")));
    r.create_sync("of an unknown type", egl.display, SYNC_TYPE as u32, std::ptr::null());
    r.create_sync("with an attribute", egl.display, SYNC_FENCE, [0x3098, 2, NONE].as_ptr());
    r.create_sync("on no display", std::ptr::null_mut(), SYNC_FENCE, std::ptr::null());
    let s = r.create_sync("a fence", egl.display, SYNC_FENCE, [NONE].as_ptr());
    r.sync_attrib("type", s, SYNC_TYPE);
    r.sync_attrib("condition", s, SYNC_CONDITION);
    r.sync_attrib("an attribute no sync has", s, 0x3094);
    let mut v = 0;
    // SAFETY: GL and EGL calls with this run's handles; every out-pointer has room.
    unsafe {
        let ok = (gl.egl_get_sync_attrib)(egl.display, s, SYNC_STATUS, &mut v);
        r.egl_note(&format!("status is one of the two {}", v == SIGNALED || v == UNSIGNALED), i64::from(ok));
        // A poll, then a finish: the fence is done.
        (gl.clear)(0x4000);
        let w = (gl.egl_client_wait_sync)(egl.display, s, 0, 0);
        r.egl_note(&format!("poll answers one of the two {}", w == TIMEOUT_EXPIRED || w == CONDITION_SATISFIED), 0);
        (gl.finish)();
        r.sync_attrib("status after glFinish", s, SYNC_STATUS);
        let w = (gl.egl_client_wait_sync)(egl.display, s, 0, 0);
        r.egl_note("poll after glFinish", i64::from(w));
        r.egl_note("destroy", i64::from((gl.egl_destroy_sync)(egl.display, s)));
        r.egl_note("destroy again", i64::from((gl.egl_destroy_sync)(egl.display, s)));
        // Polls alone signal a fence once its work is done, as frame pacers rely on: a draw,
        // a fence, then polls and no glFinish, by a wait with no timeout and by the status.
        (gl.clear)(0x4000);
        let s = r.create_sync("a fence to poll", egl.display, SYNC_FENCE, std::ptr::null());
        let by_wait = polled(|| (gl.egl_client_wait_sync)(egl.display, s, 0, 0) == CONDITION_SATISFIED);
        r.log.push(format!("signalled by polls with no timeout alone: {by_wait}"));
        (gl.egl_destroy_sync)(egl.display, s);
        (gl.clear)(0x4000);
        let s = r.create_sync("another fence to poll", egl.display, SYNC_FENCE, std::ptr::null());
        let by_status = polled(|| {
            let mut v = 0;
            (gl.egl_get_sync_attrib)(egl.display, s, SYNC_STATUS, &mut v);
            v == SIGNALED
        });
        r.log.push(format!("signalled by status queries alone: {by_status}"));
        (gl.egl_destroy_sync)(egl.display, s);
        // A fence never signals early: right after slow work it is not signalled, and polls
        // alone see it signalled once the work is done.
        let program = r.program("attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }", SLOW_FS);
        let (mut fb, mut tex, mut buf) = (0, 0, 0);
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(0x8D40, fb);
        (gl.gen_textures)(1, &mut tex);
        (gl.bind_texture)(0x0DE1, tex);
        (gl.tex_image_2d)(0x0DE1, 0, 0x1908, 256, 256, 0, 0x1908, 0x1401, std::ptr::null());
        (gl.framebuffer_texture_2d)(0x8D40, 0x8CE0, 0x0DE1, tex, 0);
        (gl.viewport)(0, 0, 256, 256);
        (gl.gen_buffers)(1, &mut buf);
        (gl.bind_buffer)(ARRAY, buf);
        let quad: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        (gl.buffer_data)(ARRAY, 32, quad.as_ptr().cast(), STATIC_DRAW);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, std::ptr::null());
        (gl.enable_vertex_attrib_array)(0);
        (gl.finish)();
        for _ in 0..4 {
            (gl.draw_arrays)(0x0005, 0, 4);
        }
        let s = r.create_sync("a fence after slow work", egl.display, SYNC_FENCE, std::ptr::null());
        let at_once = (gl.egl_client_wait_sync)(egl.display, s, 0, 0);
        r.egl_note("polled at once", i64::from(at_once));
        let then = polled(|| (gl.egl_client_wait_sync)(egl.display, s, 0, 0) == CONDITION_SATISFIED);
        r.log.push(format!("then signalled by polls: {then}"));
        (gl.egl_destroy_sync)(egl.display, s);
        (gl.bind_framebuffer)(0x8D40, 0);
        (gl.delete_framebuffers)(1, &fb);
        (gl.delete_textures)(1, &tex);
        (gl.delete_buffers)(1, &buf);
        (gl.delete_program)(program);
        (gl.viewport)(0, 0, 16, 16);
        r.note("slow work undone");
        // Waits that block, with and without a flush asked for.
        let s = r.create_sync("another fence", egl.display, SYNC_FENCE, std::ptr::null());
        (gl.clear)(0x4000);
        r.egl_note("wait 0.5 s", i64::from((gl.egl_client_wait_sync)(egl.display, s, 1, 500_000_000)));
        r.sync_attrib("status after the wait", s, SYNC_STATUS);
        r.egl_note("wait forever", i64::from((gl.egl_client_wait_sync)(egl.display, s, 0, FOREVER)));
        r.egl_note("server wait", i64::from((gl.egl_wait_sync)(egl.display, s, 0)));
        r.egl_note("server wait with a flag", i64::from((gl.egl_wait_sync)(egl.display, s, 1)));
        // Handles that are no syncs.
        r.sync_attrib("type of no sync", canary, SYNC_TYPE);
        r.egl_note("wait for no sync", i64::from((gl.egl_client_wait_sync)(egl.display, canary, 0, 0)));
        r.egl_note("server wait for no sync", i64::from((gl.egl_wait_sync)(egl.display, canary, 0)));
        r.egl_note("destroy no sync", i64::from((gl.egl_destroy_sync)(egl.display, canary)));
        // With no context current there is nothing to fence; a fence made before stays.
        let ok = (gl.egl_make_current)(egl.display, std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null_mut());
        r.egl_note("release", i64::from(ok));
        r.create_sync("with no context", egl.display, SYNC_FENCE, std::ptr::null());
        r.egl_note("wait with no context", i64::from((gl.egl_client_wait_sync)(egl.display, s, 0, FOREVER)));
        r.egl_note("server wait with no context", i64::from((gl.egl_wait_sync)(egl.display, s, 0)));
        // A reusable sync needs no context, and only the application signals it.
        let u = r.create_sync("a reusable sync", egl.display, SYNC_REUSABLE, std::ptr::null());
        r.sync_attrib("its type", u, SYNC_TYPE);
        r.sync_attrib("its status", u, SYNC_STATUS);
        r.sync_attrib("its condition", u, SYNC_CONDITION);
        r.egl_note("wait 1 ms", i64::from((gl.egl_client_wait_sync)(egl.display, u, 0, 1_000_000)));
        r.egl_note("signal with a bad mode", i64::from((gl.egl_signal_sync)(egl.display, u, 0x1234)));
        r.egl_note("signal", i64::from((gl.egl_signal_sync)(egl.display, u, SIGNALED as u32)));
        r.sync_attrib("status once signalled", u, SYNC_STATUS);
        r.egl_note("wait forever, signalled", i64::from((gl.egl_client_wait_sync)(egl.display, u, 0, FOREVER)));
        r.egl_note("unsignal", i64::from((gl.egl_signal_sync)(egl.display, u, UNSIGNALED as u32)));
        r.egl_note("poll", i64::from((gl.egl_client_wait_sync)(egl.display, u, 0, 0)));
        // Signalled by another thread while this one waits.
        let (signal, display, handle) = (gl.egl_signal_sync, egl.display as usize, u as usize);
        let other = std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_millis(50));
            // EGL's prototype with the run's display and sync (inside the unsafe block above).
            signal(display as Ptr, handle as Ptr, SIGNALED as u32)
        });
        r.egl_note(
            "wait forever, signalled by another thread",
            i64::from((gl.egl_client_wait_sync)(egl.display, u, 0, FOREVER)),
        );
        let signalled = other.join().unwrap_or(0);
        r.log.push(format!("the other thread's signal: {signalled:#x}"));
        let ok = (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        r.egl_note("current again", i64::from(ok));
        r.egl_note("server wait for it", i64::from((gl.egl_wait_sync)(egl.display, u, 0)));
        r.create_sync(
            "a reusable sync with an attribute",
            egl.display,
            SYNC_REUSABLE,
            [SYNC_STATUS, SIGNALED, NONE].as_ptr(),
        );
        let f = r.create_sync("a fence", egl.display, SYNC_FENCE, std::ptr::null());
        r.egl_note("signal a fence", i64::from((gl.egl_signal_sync)(egl.display, f, SIGNALED as u32)));
        r.egl_note("destroy", i64::from((gl.egl_destroy_sync)(egl.display, s)));
        r.egl_note("destroy the reusable sync", i64::from((gl.egl_destroy_sync)(egl.display, u)));
        r.egl_note("destroy the fence", i64::from((gl.egl_destroy_sync)(egl.display, f)));
        r.egl_note("signal it destroyed", i64::from((gl.egl_signal_sync)(egl.display, u, SIGNALED as u32)));
    }
}

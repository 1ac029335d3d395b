//! ES 3.0's sync objects in an ES 3.0 context: a fence's parameters, its status and waits
//! before and after `glFinish`, a fence signalled by polls alone, a fence not signalled right
//! after slow work and signalled by a wait, server waits, deletion, and every call's errors
//! (conditions, flags, timeouts, names that are no sync, a negative size).

use super::fence_sync::{polled, SLOW_FS};
use super::*;

const SYNC_GPU_COMMANDS_COMPLETE: u32 = 0x9117;
const SYNC_FLUSH_COMMANDS_BIT: u32 = 0x1;
const TIMEOUT_IGNORED: u64 = u64::MAX;
const OBJECT_TYPE: u32 = 0x9112;
const SYNC_CONDITION: u32 = 0x9113;
const SYNC_STATUS: u32 = 0x9114;
const SYNC_FLAGS: u32 = 0x9115;
const SIGNALED: i32 = 0x9119;
const UNSIGNALED: i32 = 0x9118;
const ALREADY_SIGNALED: u32 = 0x911A;
const TIMEOUT_EXPIRED: u32 = 0x911B;
const CONDITION_SATISFIED: u32 = 0x911C;
const MAX_SERVER_WAIT_TIMEOUT: u32 = 0x9111;

/// Not a sync: the address of a constant of this program.
static CANARY: u32 = 0x2718_2818;

impl Run {
    /// Logs one parameter of `sync`, its length, and the error.
    fn synciv(&mut self, what: &str, sync: Ptr, pname: u32, buf_size: i32) {
        let (mut len, mut v) = (-7, [-7i32; 2]);
        // SAFETY: a context is current; `v` has room for two values, `len` for one.
        unsafe { (self.gl.get_synciv)(sync, pname, buf_size, &mut len, v.as_mut_ptr()) };
        self.note(&format!("glGetSynciv {what} ({pname:#x}, size {buf_size}): {:#x} {:#x} length {len}", v[0], v[1]));
    }
}

/// The sync object sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    let canary = std::ptr::addr_of!(CANARY) as Ptr;
    // SAFETY: GL calls with a current context; every out-pointer has room for what it gets.
    unsafe {
        let mut t = -1i64;
        (gl.core_get_integer64v)(MAX_SERVER_WAIT_TIMEOUT, &mut t);
        r.note(&format!("GL_MAX_SERVER_WAIT_TIMEOUT at least 0: {}", t >= 0));
        for (condition, flags) in [(0x9116, 0), (SYNC_GPU_COMMANDS_COMPLETE, 1)] {
            let s = (gl.fence_sync)(condition, flags);
            r.note(&format!("glFenceSync({condition:#x}, {flags}): null {}", s.is_null()));
        }
        (gl.clear)(0x4000);
        let s = (gl.fence_sync)(SYNC_GPU_COMMANDS_COMPLETE, 0);
        r.note(&format!("a fence: null {}, glIsSync {}", s.is_null(), (gl.is_sync)(s)));
        r.synciv("type", s, OBJECT_TYPE, 1);
        r.synciv("condition", s, SYNC_CONDITION, 2);
        r.synciv("flags", s, SYNC_FLAGS, 1);
        r.synciv("type into no room", s, OBJECT_TYPE, 0);
        r.synciv("type with a negative size", s, OBJECT_TYPE, -1);
        r.synciv("a name no sync has", s, 0x9116, 1);
        let mut v = 0;
        (gl.get_synciv)(s, SYNC_STATUS, 1, std::ptr::null_mut(), &mut v);
        r.note(&format!("status is one of the two: {}", v == SIGNALED || v == UNSIGNALED));
        let w = (gl.client_wait_sync)(s, 0, 0);
        r.note(&format!("a poll answers one of the two: {}", w == TIMEOUT_EXPIRED || w == ALREADY_SIGNALED));
        (gl.finish)();
        r.synciv("status after glFinish", s, SYNC_STATUS, 1);
        let w = (gl.client_wait_sync)(s, 0, 0);
        r.note(&format!("a poll after glFinish: {w:#x}"));
        let w = (gl.client_wait_sync)(s, SYNC_FLUSH_COMMANDS_BIT, 1_000_000);
        r.note(&format!("a wait after glFinish: {w:#x}"));
        (gl.wait_sync)(s, 0, TIMEOUT_IGNORED);
        r.note("glWaitSync");
        (gl.wait_sync)(s, 1, TIMEOUT_IGNORED);
        r.note("glWaitSync with a flag");
        (gl.wait_sync)(s, 0, 5);
        r.note("glWaitSync with a timeout");
        let w = (gl.client_wait_sync)(s, 2, 0);
        r.note(&format!("glClientWaitSync with an unknown flag: {w:#x}"));
        (gl.delete_sync)(s);
        r.note(&format!("deleted: glIsSync {}", (gl.is_sync)(s)));
        (gl.delete_sync)(s);
        r.note("deleted again");
        (gl.delete_sync)(std::ptr::null_mut());
        r.note("glDeleteSync(0)");

        // Names that are no sync.
        for (what, name) in [("null", std::ptr::null_mut()), ("a canary", canary)] {
            r.note(&format!("glIsSync of {what}: {}", (gl.is_sync)(name)));
            let w = (gl.client_wait_sync)(name, 0, 0);
            r.note(&format!("glClientWaitSync of {what}: {w:#x}"));
            (gl.wait_sync)(name, 0, TIMEOUT_IGNORED);
            r.note(&format!("glWaitSync of {what}"));
            r.synciv(&format!("of {what}"), name, OBJECT_TYPE, 1);
        }

        // Polls alone signal a fence once its work is done.
        (gl.clear)(0x4000);
        let s = (gl.fence_sync)(SYNC_GPU_COMMANDS_COMPLETE, 0);
        let by_wait = polled(|| (gl.client_wait_sync)(s, 0, 0) == ALREADY_SIGNALED);
        r.note(&format!("signalled by polls with no timeout alone: {by_wait}"));
        (gl.delete_sync)(s);
        (gl.clear)(0x4000);
        let s = (gl.fence_sync)(SYNC_GPU_COMMANDS_COMPLETE, 0);
        let by_status = polled(|| {
            let mut v = 0;
            (gl.get_synciv)(s, SYNC_STATUS, 1, std::ptr::null_mut(), &mut v);
            v == SIGNALED
        });
        r.note(&format!("signalled by status queries alone: {by_status}"));
        (gl.delete_sync)(s);

        // Right after slow work a fence is not signalled; a wait sees it become so.
        let vs = "attribute vec2 pos; void main() { gl_Position = vec4(pos, 0.0, 1.0); }";
        let program = r.program(vs, SLOW_FS);
        let (mut fb, mut tex) = (0, 0);
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(0x8D40, fb);
        (gl.gen_textures)(1, &mut tex);
        (gl.bind_texture)(0x0DE1, tex);
        (gl.tex_image_2d)(0x0DE1, 0, 0x1908, 256, 256, 0, 0x1908, 0x1401, std::ptr::null());
        (gl.framebuffer_texture_2d)(0x8D40, 0x8CE0, 0x0DE1, tex, 0);
        (gl.viewport)(0, 0, 256, 256);
        let quad: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        // A client array: no buffer bound (an earlier sequence may have left one).
        (gl.bind_buffer)(ARRAY, 0);
        (gl.vertex_attrib_pointer)(0, 2, 0x1406, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.finish)();
        for _ in 0..4 {
            (gl.draw_arrays)(0x0005, 0, 4);
        }
        let s = (gl.fence_sync)(SYNC_GPU_COMMANDS_COMPLETE, 0);
        r.synciv("status right after slow work", s, SYNC_STATUS, 1);
        let w = (gl.client_wait_sync)(s, SYNC_FLUSH_COMMANDS_BIT, 10_000_000_000);
        r.note(&format!("a wait for it: {w:#x} (GL_CONDITION_SATISFIED {})", w == CONDITION_SATISFIED));
        r.synciv("status after the wait", s, SYNC_STATUS, 1);
        (gl.delete_sync)(s);
        (gl.disable_vertex_attrib_array)(0);
        (gl.bind_framebuffer)(0x8D40, 0);
        (gl.delete_framebuffers)(1, &fb);
        (gl.delete_textures)(1, &tex);
        (gl.delete_program)(program);
        (gl.viewport)(0, 0, 16, 16);
    }
}

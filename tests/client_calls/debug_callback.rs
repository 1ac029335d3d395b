//! `GL_KHR_debug`'s callback through the C entry points: a debug context starts with debug
//! output enabled, so a callback installed there receives the `GL_INVALID_ENUM` of an unknown
//! capability without the application enabling anything; with output disabled it receives
//! nothing; with error messages turned off by `glDebugMessageControlKHR` it receives nothing,
//! and again once they are turned back on; with synchronous output it has the message before
//! the call returns; a callback
//! that itself calls GL (which KHR_debug leaves undefined) gets its answer, and the program goes
//! on; and a context that is not a debug context starts with output disabled.

use std::sync::Mutex;

use super::*;

const FLAGS_KHR: i32 = 0x30FC;
const DEBUG_BIT_KHR: i32 = 0x1;
const DEBUG_OUTPUT: u32 = 0x92E0;
const DEBUG_OUTPUT_SYNCHRONOUS: u32 = 0x8242;
const DONT_CARE: u32 = 0x1100;
const TYPE_ERROR: u32 = 0x824C;
/// Not a capability.
const UNKNOWN_CAP: u32 = 0x7FFF;

/// What the callback was called with, once.
struct Received {
    source: u32,
    ty: u32,
    severity: u32,
    /// Whether the message had an id (its value is each implementation's own).
    id: bool,
    /// Whether the message had text.
    text: bool,
    /// Whether the user parameter was the one installed.
    ours: bool,
}

/// What the callback has been called with.
static RECEIVED: Mutex<Vec<Received>> = Mutex::new(Vec::new());

/// The user parameter installed with the callback.
static USER: u32 = 0x0DEB_0600;

/// The application's callback: records the message.
unsafe extern "C" fn callback(
    source: u32,
    ty: u32,
    id: u32,
    severity: u32,
    length: i32,
    message: *const i8,
    user: *const c_void,
) {
    let text = !message.is_null() && length > 0;
    let ours = std::ptr::eq(user, std::ptr::addr_of!(USER).cast());
    let m = Received { source, ty, severity, id: id != 0, text, ours };
    RECEIVED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(m);
}

/// The entry points a callback that calls GL uses (set before it is installed).
static API: Mutex<Option<Api>> = Mutex::new(None);

/// What the GL-calling callback's own call answered, each time it was called.
static ANSWERS: Mutex<Vec<u8>> = Mutex::new(Vec::new());

/// A callback that calls GL itself: asks whether debug output is enabled.
unsafe extern "C" fn calling_back(
    _source: u32,
    _ty: u32,
    _id: u32,
    _severity: u32,
    _length: i32,
    _message: *const i8,
    _user: *const c_void,
) {
    let api = *API.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some(gl) = api {
        // SAFETY: glIsEnabled's prototype, on the thread whose context is current.
        let on = unsafe { (gl.is_enabled)(DEBUG_OUTPUT) };
        ANSWERS.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(on);
    }
}

impl Run {
    /// Logs and forgets what the callback has received since the last call.
    fn received(&mut self, what: &str) {
        let got: Vec<_> = std::mem::take(&mut *RECEIVED.lock().unwrap_or_else(std::sync::PoisonError::into_inner));
        let shown: Vec<String> = got
            .iter()
            .map(|m| {
                let Received { source, ty, severity, id, text, ours } = m;
                format!("source {source:#x} type {ty:#x} severity {severity:#x} id {id} text {text} user {ours}")
            })
            .collect();
        self.log.push(format!("{what}: {} messages [{}]", got.len(), shown.join("; ")));
    }

    /// Logs whether `cap` is enabled, and the error.
    fn enabled(&mut self, what: &str, cap: u32) {
        // SAFETY: a context is current.
        let on = unsafe { (self.gl.is_enabled)(cap) };
        self.note(&format!("{what} enabled {on}"));
    }
}

/// The debug-callback sequence.
pub fn sequence(r: &mut Run) {
    let (gl, egl) = (r.gl, r.egl);
    let user = std::ptr::addr_of!(USER).cast::<c_void>();
    let ctx = r.context_with("debug", &[FLAGS_KHR, DEBUG_BIT_KHR]);
    if ctx.is_null() {
        return;
    }
    // SAFETY: GL and EGL calls with this run's handles; the callback outlives every context.
    unsafe {
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, ctx);
        r.enabled("debug context: output", DEBUG_OUTPUT);
        r.enabled("debug context: synchronous output", DEBUG_OUTPUT_SYNCHRONOUS);
        (gl.debug_message_callback)(Some(callback), user);
        r.note("callback installed");
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        r.received("an unknown capability, then glFinish");
        r.note("the error");
        (gl.disable)(DEBUG_OUTPUT);
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        r.received("output disabled");
        r.note("the error");
        (gl.enable)(DEBUG_OUTPUT);
        // Error messages turned off, from any source and of any severity: none comes.
        (gl.debug_message_control)(DONT_CARE, TYPE_ERROR, DONT_CARE, 0, std::ptr::null(), 0);
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        r.received("error messages turned off");
        r.note("the error");
        (gl.debug_message_control)(DONT_CARE, TYPE_ERROR, DONT_CARE, 0, std::ptr::null(), 1);
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        r.received("error messages turned on again");
        r.note("the error");
        (gl.enable)(DEBUG_OUTPUT_SYNCHRONOUS);
        (gl.enable)(UNKNOWN_CAP);
        r.received("synchronous output, before any other call");
        r.note("the error");
        // A callback that calls GL: with synchronous output, from inside the call that failed.
        *API.lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(gl);
        (gl.debug_message_callback)(Some(calling_back), user);
        (gl.enable)(UNKNOWN_CAP);
        (gl.disable)(DEBUG_OUTPUT_SYNCHRONOUS);
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        let answers = std::mem::take(&mut *ANSWERS.lock().unwrap_or_else(std::sync::PoisonError::into_inner));
        r.log.push(format!("a callback calling glIsEnabled(GL_DEBUG_OUTPUT), twice: answered {answers:?}"));
        r.note("the error after it");
        r.enabled("output still", DEBUG_OUTPUT);
        (gl.debug_message_callback)(None, std::ptr::null());
        (gl.egl_make_current)(egl.display, egl.surface, egl.surface, egl.context);
        (gl.egl_destroy_context)(egl.display, ctx);
        // A context that is not a debug context: output starts disabled.
        r.enabled("plain context: output", DEBUG_OUTPUT);
        (gl.debug_message_callback)(Some(callback), user);
        (gl.enable)(UNKNOWN_CAP);
        (gl.finish)();
        r.received("plain context, an unknown capability");
        r.note("the error");
        (gl.debug_message_callback)(None, std::ptr::null());
    }
}

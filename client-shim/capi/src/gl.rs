//! What every GL entry point runs on: `with_gl`, which runs a call against the calling
//! thread's current context (with no current context every call does nothing, as GL
//! specifies), and the functions that marshal pointers: arrays and strings in and out,
//! client-side vertex and index arrays, and interned strings.
//!
//! The entry points themselves are in the modules below, one per family or extension, which
//! the registry lists; this file uses none of them.

use std::collections::HashMap;
use std::ffi::{c_void, CStr, CString};
use std::sync::{LazyLock, Mutex};

use strata_client::vertex_wire::{self, VertexWire};
use strata_client::{ClientError, Connection};
use strata_protocol::{Blob, Calls};

use crate::gl_state::{ClientArray, GlState, Mapping, MAX_ATTRIBS};
use crate::state::{self, process};
use crate::surface::ensure_bound;
use crate::types::*;
use debug_callback::Delivery;

/// What a GL entry point works with: the connection and the current context's client state.
pub(crate) struct Gl<'a> {
    /// The daemon connection.
    pub conn: &'a mut Connection,
    /// The current context's client-side state.
    pub st: &'a mut GlState,
    /// The process's name counter.
    pub next_name: &'a mut u32,
    /// The process's mapped buffers, by name (names are the process's, so one table serves
    /// every share group).
    pub maps: &'a mut HashMap<u32, Mapping>,
    /// The copies of the share group's buffers' contents, by name (see `Process::shadows`).
    pub shadows: &'a mut HashMap<u32, Vec<u8>>,
}

impl Gl<'_> {
    /// Allocates `n` object names.
    pub(crate) fn names(&mut self, n: usize) -> Vec<u32> {
        let start = *self.next_name;
        *self.next_name = self.next_name.wrapping_add(n as u32);
        (0..n as u32).map(|i| start.wrapping_add(i)).collect()
    }
}

/// A GL call as `STRATA_CHECK_ERRORS` names it: the entry point and, for calls that have
/// them, its scalar arguments shown when it raises an error. A bare name has none.
pub(crate) struct Call<'a> {
    /// The entry point's name.
    pub name: &'static str,
    /// The arguments' text, made only when an error is logged.
    pub args: &'a dyn Fn() -> String,
}

impl From<&'static str> for Call<'static> {
    fn from(name: &'static str) -> Self {
        Call { name, args: &String::new }
    }
}

/// A call argument as `STRATA_CHECK_ERRORS` shows it: enums in hex, numbers as they are.
pub(crate) trait ShowArg {
    /// The argument's text.
    fn show(&self) -> String;
}

impl ShowArg for u32 {
    fn show(&self) -> String {
        format!("{self:#x}")
    }
}

macro_rules! show_plain {
    ($($t:ty),*) => { $( impl ShowArg for $t { fn show(&self) -> String { self.to_string() } } )* };
}
show_plain!(i32, f32, u8);

/// Runs a GL call against the calling thread's current context. Without one, or once the
/// daemon is gone, it returns `default` (and the latter records `GL_CONTEXT_LOST`). Debug
/// messages fetched for the application's callback after the call (see [`debug_callback`]) are
/// delivered once the library's lock is released. With `STRATA_CHECK_ERRORS`, an error it raises is
/// logged with the call's arguments.
pub(crate) fn with_gl<'a, R>(
    call: impl Into<Call<'a>>,
    default: R,
    f: impl FnOnce(&mut Gl<'_>) -> Result<R, ClientError>,
) -> R {
    let Call { name, args } = call.into();
    let mut delivery = None;
    let r = with_gl_locked(name, args, default, f, &mut delivery);
    if let Some(d) = delivery {
        d.deliver();
    }
    r
}

/// [`with_gl`] under the library's lock; the messages for the callback go to `delivery`.
fn with_gl_locked<R>(
    name: &'static str,
    args: &dyn Fn() -> String,
    default: R,
    f: impl FnOnce(&mut Gl<'_>) -> Result<R, ClientError>,
    delivery: &mut Option<Delivery>,
) -> R {
    let Some(cur) = state::current() else { return default };
    let mut guard = process();
    let p = &mut *guard;
    // The thread's context may have been lost with a connection that was replaced since.
    if p.lost || p.conn.is_none() || p.live_context(cur.context).is_none() {
        if let Some(c) = p.contexts.get_mut(&cur.context) {
            c.gl.err(GL_CONTEXT_LOST);
        }
        return default;
    }
    // Another thread's context may be current on the daemon: switch back to ours.
    if let Err(e) = ensure_bound(p, &cur) {
        if !p.lost {
            tracing::warn!("strata-egl: {name}: re-binding the thread's context failed with EGL error {e:#x}");
        }
        return default;
    }
    let state::Process { conn: Some(conn), contexts, next_name, maps, shadows, .. } = p else { return default };
    let Some(ctx) = contexts.get_mut(&cur.context) else { return default };
    let shadows = shadows.entry(ctx.group).or_default();
    let mut result = f(&mut Gl { conn, st: &mut ctx.gl, next_name, maps, shadows });
    if check_errors() && name != "glGetError" && result.is_ok() {
        // Debugging aid: name the call that raised each GL error (one round trip per call).
        match conn.glGetError() {
            Ok(GL_NO_ERROR) => {}
            Ok(e) => {
                tracing::warn!("strata-egl: {name}({}) raised GL error {e:#x}", args());
                ctx.gl.err(e);
            }
            Err(e) => result = Err(e),
        }
    }
    if result.is_ok() {
        match debug_callback::pull(conn, &ctx.gl, name) {
            Ok(d) => *delivery = d,
            Err(e) => result = Err(e),
        }
    }
    match result {
        Ok(r) => r,
        Err(ClientError::Unsupported(why)) => {
            state::log_once(&format!("{name}: stratad does not support it: {why}"));
            ctx.gl.err(GL_INVALID_OPERATION);
            default
        }
        Err(e) => {
            p.lose(&e);
            default
        }
    }
}

/// Whether `STRATA_CHECK_ERRORS=1` asks for every GL error to be logged with its call.
fn check_errors() -> bool {
    static ON: LazyLock<bool> = LazyLock::new(|| std::env::var_os("STRATA_CHECK_ERRORS").is_some_and(|v| v == "1"));
    *ON
}

/// Bytes of one component of a vertex attribute or index type.
fn type_size(ty: GLenum) -> Option<usize> {
    Some(match ty {
        0x1400 | 0x1401 => 1,                   // BYTE, UNSIGNED_BYTE
        0x1402 | 0x1403 | 0x8D61 | 0x140B => 2, // SHORT, UNSIGNED_SHORT, HALF_FLOAT_OES, HALF_FLOAT
        0x1404 | 0x1405 | 0x1406 | 0x140C => 4, // INT, UNSIGNED_INT, FLOAT, FIXED
        _ => return None,
    })
}

/// Bytes of one element of `size` components of a vertex attribute's `ty`: ES 3.0's packed
/// `GL_INT_2_10_10_10_REV` and `GL_UNSIGNED_INT_2_10_10_10_REV` hold four in 32 bits.
fn element_size(ty: GLenum, size: i32) -> Option<usize> {
    match ty {
        0x8D9F | 0x8368 => Some(4),
        _ => Some(type_size(ty)? * size.clamp(1, 4) as usize),
    }
}

/// Borrows `len` bytes of application memory (empty for a null pointer).
///
/// # Safety
/// A non-null `ptr` must be valid for `len` bytes, as GL requires of the application.
unsafe fn bytes<'a>(ptr: *const c_void, len: usize) -> &'a [u8] {
    if ptr.is_null() || len == 0 {
        &[]
    } else {
        // SAFETY: see the function's contract.
        unsafe { std::slice::from_raw_parts(ptr.cast::<u8>(), len) }
    }
}

/// Borrows `size` bytes of application memory for a call whose size argument the application
/// gives; a negative size records `GL_INVALID_VALUE` and gives `None`.
///
/// # Safety
/// A non-null `ptr` must be valid for `size` bytes, as GL requires of the application.
unsafe fn sized_bytes<'a>(st: &mut GlState, ptr: *const c_void, size: isize) -> Option<&'a [u8]> {
    let Ok(len) = usize::try_from(size) else {
        st.err(GL_INVALID_VALUE);
        return None;
    };
    // SAFETY: see the function's contract.
    Some(unsafe { bytes(ptr, len) })
}

/// Borrows `n` values of application memory (empty for a null pointer or negative count).
///
/// # Safety
/// A non-null `ptr` must be valid for `n` values.
pub(crate) unsafe fn values<'a, T>(ptr: *const T, n: i64) -> &'a [T] {
    if ptr.is_null() || n <= 0 {
        &[]
    } else {
        // SAFETY: see the function's contract.
        unsafe { std::slice::from_raw_parts(ptr, n as usize) }
    }
}

/// Writes `src` into an application array (nothing for a null pointer).
///
/// # Safety
/// A non-null `dst` must have room for `src.len()` values, as the GL query specifies.
unsafe fn write_out<T: Copy>(dst: *mut T, src: &[T]) {
    if !dst.is_null() {
        // SAFETY: see the function's contract.
        unsafe { std::ptr::copy_nonoverlapping(src.as_ptr(), dst, src.len()) };
    }
}

/// Writes one value through an optional out-pointer.
///
/// # Safety
/// A non-null `dst` must point at a `T`.
unsafe fn put<T>(dst: *mut T, v: T) {
    if !dst.is_null() {
        // SAFETY: see the function's contract.
        unsafe { *dst = v };
    }
}

/// Copies `s` into a caller buffer of `buf_size` bytes, NUL-terminated and truncated as GL
/// specifies, and stores the length written (without the NUL).
///
/// # Safety
/// `out` (if non-null) must have room for `buf_size` bytes; `length` (if non-null) an int.
unsafe fn copy_string(s: &str, buf_size: GLsizei, length: *mut GLsizei, out: *mut GLchar) {
    let n = if buf_size <= 0 || out.is_null() { 0 } else { s.len().min(buf_size as usize - 1) };
    // SAFETY: see the function's contract.
    unsafe {
        if !out.is_null() && buf_size > 0 {
            std::ptr::copy_nonoverlapping(s.as_ptr().cast::<GLchar>(), out, n);
            *out.add(n) = 0;
        }
        put(length, n as GLsizei);
    }
}

/// Reads a NUL-terminated name from the application (`None` for null or non-UTF-8).
///
/// # Safety
/// A non-null `name` must be NUL-terminated.
unsafe fn c_name<'a>(name: *const GLchar) -> Option<&'a str> {
    if name.is_null() {
        return None;
    }
    // SAFETY: see the function's contract.
    unsafe { CStr::from_ptr(name) }.to_str().ok()
}

/// `count` NUL-terminated names as one text of lines, as the commands that take lists of names
/// carry them (a name that is no string is an empty line, which no variable has).
///
/// # Safety
/// `names` holds `count` pointers, each null or to a NUL-terminated string.
unsafe fn name_lines(names: *const *const GLchar, count: GLsizei) -> String {
    let mut text = String::new();
    // SAFETY: see the function's contract.
    for &n in unsafe { values(names, i64::from(count)) } {
        // SAFETY: each is NUL-terminated.
        text.push_str(unsafe { c_name(n) }.unwrap_or(""));
        text.push('\n');
    }
    text
}

/// A string that stays valid for the rest of the process (what `glGetString` returns).
fn intern(s: String) -> *const GLubyte {
    static STRINGS: LazyLock<Mutex<HashMap<String, &'static CStr>>> = LazyLock::new(|| Mutex::new(HashMap::new()));
    let mut strings = STRINGS.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(c) = strings.get(&s) {
        return c.as_ptr().cast();
    }
    let Ok(c) = CString::new(s.clone()) else { return std::ptr::null() };
    let c: &'static CStr = Box::leak(c.into_boxed_c_str());
    strings.insert(s, c);
    c.as_ptr().cast()
}

/// Sends the bytes of every enabled client-side array that a draw of `vertices` vertices reads;
/// `GL_FLOAT` ones in the daemon's vertex wire format.
fn send_client_arrays(gl: &mut Gl<'_>, vertices: u64, instances: u64) -> Result<(), ClientError> {
    if vertices == 0 {
        return Ok(());
    }
    for i in 0..MAX_ATTRIBS {
        let a = gl.st.attribs[i];
        let (true, Some(ClientArray { ptr, size, ty, stride })) = (a.enabled, a.client) else { continue };
        // An attribute with a divisor (ES 3.0) reads one element per `divisor` instances.
        let vertices = match a.divisor {
            0 => vertices,
            d => instances.max(1).div_ceil(u64::from(d)),
        };
        let Some(element) = element_size(ty, size) else { continue };
        let stride = if stride > 0 { stride as usize } else { element };
        let Some(len) = (vertices - 1).checked_mul(stride as u64).and_then(|n| n.checked_add(element as u64)) else {
            continue;
        };
        // SAFETY: the application promised `ptr` holds every vertex the draw reads.
        let data = unsafe { bytes(ptr as *const c_void, len as usize) };
        let wire = gl.conn.vertex_wire();
        // GL_FLOAT arrays go as the daemon asked (packed); everything else as it is.
        match (ty, wire) {
            (_, VertexWire::Float) => gl.conn.strataVertexAttribData(i as u32, Blob::borrowed(data))?,
            (GL_FLOAT, _) => {
                let Some(packed) = vertex_wire::pack(wire, data, element / 4, stride, vertices as usize) else {
                    continue;
                };
                gl.conn.strataVertexAttribDataPacked(i as u32, wire.gl_type(), Blob::owned(packed))?;
            }
            _ => gl.conn.strataVertexAttribData(i as u32, Blob::borrowed(data))?,
        }
    }
    Ok(())
}

/// Whether any enabled attribute reads a client-side array.
fn uses_client_arrays(st: &GlState) -> bool {
    st.attribs.iter().any(|a| a.enabled && a.client.is_some())
}

/// One more than the largest index in `data` (indices of type `ty`) that reads a vertex (all of
/// them, or with primitive restart (`restart`) all but the all-ones index), 0 if none.
fn vertex_count(data: &[u8], ty: GLenum, restart: bool) -> u64 {
    // With primitive restart, the type's all-ones index restarts and reads no vertex.
    let read = |i: u32, all_ones: u32| !(restart && i == all_ones);
    let max = match ty {
        GL_UNSIGNED_BYTE => data.iter().map(|&b| u32::from(b)).filter(|&i| read(i, 0xFF)).max(),
        GL_UNSIGNED_SHORT => {
            data.chunks_exact(2).map(|c| u32::from(u16::from_ne_bytes([c[0], c[1]]))).filter(|&i| read(i, 0xFFFF)).max()
        }
        GL_UNSIGNED_INT => data
            .chunks_exact(4)
            .map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .filter(|&i| read(i, u32::MAX))
            .max(),
        _ => None,
    };
    max.map_or(0, |m| u64::from(m) + 1)
}

/// Delivering `GL_KHR_debug` messages to the application's callback.
pub(crate) mod debug_callback;

/// Pixel sizes and row layouts of uploads and reads.
mod pixels;

/// Pixel pack and unpack buffers (`GL_NV_pixel_buffer_object`).
mod pixel_buffer;

/// The entry points that carry only scalars: one line each, generated.
pub mod simple;

/// The generated families of entry points that marshal pointers the same way.
pub mod families;

/// The hand-written entry points: everything that marshals pointers or keeps client state.
pub mod hand;

/// Element draws (`glDrawElements` and its base-vertex forms) and multi-draws.
pub mod draws;

/// Mapped buffers (`GL_OES_mapbuffer`, `GL_EXT_map_buffer_range`).
pub mod mapping;

/// The reset status and bounded reads (`GL_EXT_robustness`, `GL_KHR_robustness`).
pub mod robustness;

/// Vertex array objects (`GL_OES_vertex_array_object`).
pub mod vao;

/// Debug output, groups and labels (`GL_KHR_debug`, `GL_EXT_debug_label`).
pub mod debug;

/// Discarding framebuffer contents (`GL_EXT_discard_framebuffer`).
pub mod discard;

/// Several draw buffers (`GL_EXT_draw_buffers`, `GL_NV_draw_buffers`).
pub mod draw_buffers;

/// Fragment outputs' indices (`GL_EXT_blend_func_extended`).
pub mod blend_extended;

/// Program binaries (`GL_OES_get_program_binary`).
pub mod program_binary;

/// Program pipelines' programs (`GL_EXT_separate_shader_objects`).
pub mod separate;

/// Border colours' integer forms (`GL_EXT_texture_border_clamp`, `GL_OES_texture_border_clamp`).
pub mod border;

/// 3D textures (`GL_OES_texture_3D`).
pub mod texture3d;

/// Textures and renderbuffers of EGLImages (`GL_OES_EGL_image`).
pub mod egl_image;

/// ES 3.0's uniform buffer bindings and block queries.
pub mod uniform_blocks;

/// ES 3.0's integer vertex attributes and divisors.
pub mod vertex_es3;

/// ES 3.0's core names for what ES 2.0 extensions gave, as aliases of the extensions' entry points.
pub mod es3_aliases;

/// ES 3.0's clears of one buffer and fragment output locations.
pub mod es3_calls;

/// ES 3.0's sync objects (`glFenceSync` and the rest).
pub mod sync_objects;

#[cfg(test)]
mod tests {
    use super::*;

    /// The all-ones index restarts only with primitive restart: it then reads no vertex.
    #[test]
    fn restart_indices_read_no_vertex() {
        let ints: Vec<u8> = [3u32, u32::MAX, 7].iter().flat_map(|i| i.to_ne_bytes()).collect();
        assert_eq!(vertex_count(&ints, GL_UNSIGNED_INT, true), 8);
        assert_eq!(vertex_count(&ints, GL_UNSIGNED_INT, false), u64::from(u32::MAX) + 1);
        assert_eq!(vertex_count(&[255, 4], GL_UNSIGNED_BYTE, true), 5);
        assert_eq!(vertex_count(&[255], GL_UNSIGNED_BYTE, true), 0);
    }
}

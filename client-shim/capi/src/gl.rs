//! The GLES 2.0 entry points and those of the extensions.
//!
//! Calls that map one-to-one onto a protocol command are generated from the table in
//! [`simple`]; the ones below marshal pointers: arrays and strings in and out, client-side
//! vertex and index arrays, buffer shadows for mapping, and client-allocated object names.
//! With no current context every call does nothing, as GL specifies.

use std::collections::HashMap;
use std::ffi::{c_void, CStr, CString};
use std::sync::{LazyLock, Mutex};

use strata_client::vertex_wire::{self, VertexWire};
use strata_client::{ClientError, Connection};
use strata_protocol::{Blob, Calls, Slice, Text};

use crate::state::{self, process, ClientArray, GlState};
use crate::types::*;

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
    pub maps: &'a mut HashMap<u32, mapping::Mapping>,
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
/// messages fetched for the application's callback after the call (see `debug`) are delivered
/// once the library's lock is released. With `STRATA_CHECK_ERRORS`, an error it raises is
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
    delivery: &mut Option<crate::debug::Delivery>,
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
    if let Err(e) = crate::surface::ensure_bound(p, &cur) {
        if !p.lost {
            tracing::warn!("strata-egl: {name}: re-binding the thread's context failed with EGL error {e:#x}");
        }
        return default;
    }
    let state::Process { conn: Some(conn), contexts, next_name, maps, .. } = p else { return default };
    let Some(ctx) = contexts.get_mut(&cur.context) else { return default };
    let mut result = f(&mut Gl { conn, st: &mut ctx.gl, next_name, maps });
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
        match crate::debug::pull(conn, &ctx.gl, name) {
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

/// Converts a C argument to the protocol's type.
trait Wire {
    type Out;
    fn wire(self) -> Self::Out;
}

macro_rules! wire_identity {
    ($($t:ty),*) => { $( impl Wire for $t { type Out = $t; fn wire(self) -> $t { self } } )* };
}
wire_identity!(u32, i32, f32);

impl Wire for GLboolean {
    type Out = bool;
    fn wire(self) -> bool {
        self != 0
    }
}

/// Converts a protocol result to the C return type.
trait ToC<C> {
    fn to_c(self) -> C;
}

impl ToC<()> for () {
    fn to_c(self) {}
}

impl ToC<GLenum> for GLenum {
    fn to_c(self) -> GLenum {
        self
    }
}

impl ToC<GLboolean> for bool {
    fn to_c(self) -> GLboolean {
        self as GLboolean
    }
}

/// Generates entry points that map one-to-one onto a `Calls` method of the same name.
macro_rules! simple_calls {
    ($( fn $name:ident ( $( $arg:ident : $ty:ty ),* ) $( -> $ret:ty )? ; )*) => {
        crate::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`, forwarded to the daemon as it is.")]
                fn $name( $( $arg : $ty ),* ) $( -> $ret )? {
                    let args = || -> String { Vec::<String>::from([$( ShowArg::show(&$arg) ),*]).join(", ") };
                    with_gl(Call { name: stringify!($name), args: &args }, crate::Fallback::fallback(), |gl| {
                        Ok(ToC::to_c(gl.conn.$name( $( Wire::wire($arg) ),* )?))
                    })
                }
            )*
        }
    };
}

/// The entry points that carry only scalars: one line each, generated.
pub mod simple {
    use super::*;

    simple_calls! {
        fn glActiveTexture(texture: GLenum);
        fn glAttachShader(program: GLuint, shader: GLuint);
        fn glBindFramebuffer(target: GLenum, framebuffer: GLuint);
        fn glBindRenderbuffer(target: GLenum, renderbuffer: GLuint);
        fn glBindTexture(target: GLenum, texture: GLuint);
        fn glBlendColor(red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat);
        fn glBlendEquation(mode: GLenum);
        fn glBlendEquationSeparate(mode_rgb: GLenum, mode_alpha: GLenum);
        fn glBlendFunc(sfactor: GLenum, dfactor: GLenum);
        fn glBlendFuncSeparate(src_rgb: GLenum, dst_rgb: GLenum, src_alpha: GLenum, dst_alpha: GLenum);
        fn glClear(mask: GLbitfield);
        fn glClearColor(red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat);
        fn glClearDepthf(depth: GLfloat);
        fn glClearStencil(s: GLint);
        fn glColorMask(red: GLboolean, green: GLboolean, blue: GLboolean, alpha: GLboolean);
        fn glCompileShader(shader: GLuint);
        fn glCopyTexImage2D(target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, width: GLsizei, height: GLsizei, border: GLint);
        fn glCopyTexSubImage2D(target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei);
        fn glCullFace(mode: GLenum);
        fn glDeleteProgram(program: GLuint);
        fn glDeleteShader(shader: GLuint);
        fn glDepthFunc(func: GLenum);
        fn glDepthMask(flag: GLboolean);
        fn glDepthRangef(near: GLfloat, far: GLfloat);
        fn glDetachShader(program: GLuint, shader: GLuint);
        fn glFlush();
        fn glFramebufferRenderbuffer(target: GLenum, attachment: GLenum, renderbuffertarget: GLenum, renderbuffer: GLuint);
        fn glFramebufferTexture2D(target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint);
        fn glFrontFace(mode: GLenum);
        fn glGenerateMipmap(target: GLenum);
        fn glHint(target: GLenum, mode: GLenum);
        fn glLineWidth(width: GLfloat);
        fn glLinkProgram(program: GLuint);
        fn glPolygonOffset(factor: GLfloat, units: GLfloat);
        fn glPolygonOffsetClampEXT(factor: GLfloat, units: GLfloat, clamp: GLfloat);
        fn glClipControlEXT(origin: GLenum, depth: GLenum);
        fn glMaxShaderCompilerThreadsKHR(count: GLuint);
        fn glReadBufferNV(mode: GLenum);
        fn glReleaseShaderCompiler();
        fn glRenderbufferStorage(target: GLenum, internalformat: GLenum, width: GLsizei, height: GLsizei);
        fn glSampleCoverage(value: GLfloat, invert: GLboolean);
        fn glScissor(x: GLint, y: GLint, width: GLsizei, height: GLsizei);
        fn glStencilFunc(func: GLenum, reference: GLint, mask: GLuint);
        fn glStencilFuncSeparate(face: GLenum, func: GLenum, reference: GLint, mask: GLuint);
        fn glStencilMask(mask: GLuint);
        fn glStencilMaskSeparate(face: GLenum, mask: GLuint);
        fn glStencilOp(fail: GLenum, zfail: GLenum, zpass: GLenum);
        fn glStencilOpSeparate(face: GLenum, fail: GLenum, zfail: GLenum, zpass: GLenum);
        fn glTexParameterf(target: GLenum, pname: GLenum, param: GLfloat);
        fn glTexParameteri(target: GLenum, pname: GLenum, param: GLint);
        fn glUniform1f(location: GLint, x: GLfloat);
        fn glUniform1i(location: GLint, x: GLint);
        fn glUniform2f(location: GLint, x: GLfloat, y: GLfloat);
        fn glUniform2i(location: GLint, x: GLint, y: GLint);
        fn glUniform3f(location: GLint, x: GLfloat, y: GLfloat, z: GLfloat);
        fn glUniform3i(location: GLint, x: GLint, y: GLint, z: GLint);
        fn glUniform4f(location: GLint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat);
        fn glUniform4i(location: GLint, x: GLint, y: GLint, z: GLint, w: GLint);
        fn glBeginConditionalRenderNV(id: GLuint, mode: GLenum);
        fn glEndConditionalRenderNV();
        fn glBeginQueryEXT(target: GLenum, id: GLuint);
        fn glEndQueryEXT(target: GLenum);
        fn glQueryCounterEXT(id: GLuint, target: GLenum);
        fn glBindProgramPipelineEXT(pipeline: GLuint);
        fn glUseProgramStagesEXT(pipeline: GLuint, stages: GLbitfield, program: GLuint);
        fn glActiveShaderProgramEXT(pipeline: GLuint, program: GLuint);
        fn glProgramParameteriEXT(program: GLuint, pname: GLenum, value: GLint);
        fn glValidateProgramPipelineEXT(pipeline: GLuint);
        fn glUseProgram(program: GLuint);
        fn glValidateProgram(program: GLuint);
        fn glVertexAttrib1f(index: GLuint, x: GLfloat);
        fn glVertexAttrib2f(index: GLuint, x: GLfloat, y: GLfloat);
        fn glVertexAttrib3f(index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat);
        fn glVertexAttrib4f(index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat);
        fn glCheckFramebufferStatus(target: GLenum) -> GLenum;
        fn glIsBuffer(name: GLuint) -> GLboolean;
        fn glIsEnabled(cap: GLenum) -> GLboolean;
        fn glIsFramebuffer(name: GLuint) -> GLboolean;
        fn glIsProgram(name: GLuint) -> GLboolean;
        fn glIsRenderbuffer(name: GLuint) -> GLboolean;
        fn glIsShader(name: GLuint) -> GLboolean;
        fn glIsTexture(name: GLuint) -> GLboolean;
        fn glIsQueryEXT(id: GLuint) -> GLboolean;
        fn glIsProgramPipelineEXT(pipeline: GLuint) -> GLboolean;
    }
}

/// Bytes of one component of a vertex attribute or index type.
fn type_size(ty: GLenum) -> Option<usize> {
    Some(match ty {
        0x1400 | 0x1401 => 1,                   // BYTE, UNSIGNED_BYTE
        0x1402 | 0x1403 | 0x8D61 => 2,          // SHORT, UNSIGNED_SHORT, HALF_FLOAT_OES
        0x1404 | 0x1405 | 0x1406 | 0x140C => 4, // INT, UNSIGNED_INT, FLOAT, FIXED
        _ => return None,
    })
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
fn send_client_arrays(gl: &mut Gl<'_>, vertices: u64) -> Result<(), ClientError> {
    if vertices == 0 {
        return Ok(());
    }
    for i in 0..state::MAX_ATTRIBS {
        let a = gl.st.attribs[i];
        let (true, Some(ClientArray { ptr, size, ty, stride })) = (a.enabled, a.client) else { continue };
        let Some(component) = type_size(ty) else { continue };
        let element = component * size.clamp(1, 4) as usize;
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

/// One more than the largest index in `data` (indices of type `ty`), 0 if empty.
fn vertex_count(data: &[u8], ty: GLenum) -> u64 {
    let max = match ty {
        GL_UNSIGNED_BYTE => data.iter().map(|&b| u32::from(b)).max(),
        GL_UNSIGNED_SHORT => data.chunks_exact(2).map(|c| u32::from(u16::from_ne_bytes([c[0], c[1]]))).max(),
        GL_UNSIGNED_INT => data.chunks_exact(4).map(|c| u32::from_ne_bytes([c[0], c[1], c[2], c[3]])).max(),
        _ => None,
    };
    max.map_or(0, |m| u64::from(m) + 1)
}

mod families;
mod pixel_buffer;
mod pixels;
pub use families::{active, attrib, delete, get_arrays, get_int, get_strings, matrix, names, uniforms};
use pixels::{read_pixels, tex_image_bytes};

/// The GL entry-point modules, listed once: [`lookup`] searches them in order, and the tests
/// check every name they export.
macro_rules! gl_modules {
    ($($($seg:ident)::+),* $(,)?) => {
        /// The names of every GL entry point, by module.
        #[cfg(test)]
        pub(crate) const MODULE_NAMES: &[&[&str]] = &[$($($seg)::+::NAMES),*];

        /// The address of a GL entry point, by name.
        pub(crate) fn lookup(name: &[u8]) -> Option<*const c_void> {
            None$(.or_else(|| $($seg)::+::lookup(name)))*
        }
    };
}

gl_modules!(
    simple,
    uniforms,
    matrix,
    attrib,
    names,
    delete,
    get_int,
    get_arrays,
    get_strings,
    active,
    hand,
    draws,
    mapping,
    robustness,
    crate::vao,
    crate::debug,
    crate::discard,
    crate::draw_buffers,
    crate::blend_extended,
    program_binary,
    separate,
    separate::scalars,
    separate::arrays,
    separate::matrices,
    border,
    texture3d,
    crate::image::targets,
);

/// The hand-written entry points: everything that marshals pointers or keeps client state.
pub mod hand;

/// Element draws (`glDrawElements` and its base-vertex forms) and multi-draws.
pub mod draws;

/// Mapped buffers (`GL_OES_mapbuffer`, `GL_EXT_map_buffer_range`).
pub mod mapping;

/// The reset status and bounded reads (`GL_EXT_robustness`, `GL_KHR_robustness`).
pub mod robustness;

/// Program binaries (`GL_OES_get_program_binary`).
pub mod program_binary;

/// Program pipelines' programs (`GL_EXT_separate_shader_objects`).
pub mod separate;

/// Border colours' integer forms (`GL_EXT_texture_border_clamp`, `GL_OES_texture_border_clamp`).
pub mod border;

/// 3D textures (`GL_OES_texture_3D`).
pub mod texture3d;

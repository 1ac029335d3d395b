//! Programs for object-like extensions: `GL_OES_vertex_array_object` and `GL_KHR_debug`.
//! Query results are drawn as colours, so the image compares them with Mesa's.

use super::*;

const VERTEX_ARRAY_BINDING_OES: u32 = 0x85B5;
const DEBUG_OUTPUT_KHR: u32 = 0x92E0;
const DEBUG_SOURCE_APPLICATION_KHR: u32 = 0x824A;
const DEBUG_TYPE_MARKER_KHR: u32 = 0x8268;
const DEBUG_TYPE_OTHER_KHR: u32 = 0x8251;
const DEBUG_SEVERITY_NOTIFICATION_KHR: u32 = 0x826B;
const DEBUG_SEVERITY_HIGH_KHR: u32 = 0x9146;
const DEBUG_LOGGED_MESSAGES_KHR: u32 = 0x9145;
const DEBUG_GROUP_STACK_DEPTH_KHR: u32 = 0x826D;
const BUFFER_KHR: u32 = 0x82E0;
const DONT_CARE: u32 = 0x1100;
const ELEMENT_ARRAY_BUFFER_BINDING: u32 = 0x8895;

/// Clears the rectangle `(x, y, 16, 16)` with `c` (the program's way of showing a value).
fn patch(gl: Gl<'_>, x: i32, y: i32, c: [f32; 4]) -> R {
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(x, y, 16, 16)?;
    gl.glClearColor(c[0], c[1], c[2], c[3])?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glDisable(SCISSOR_TEST)
}

/// A value in 0..=8 as a grey level, so a wrong count shows.
fn level(v: i64) -> [f32; 4] {
    let g = (v.clamp(0, 8) as f32) / 8.0;
    [g, 1.0 - g, 0.5, 1.0]
}

/// Two vertex arrays with different buffers, layouts and element buffers, drawn alternately;
/// then the default vertex array, which must have kept its own state.
fn vao_switch(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    // The default vertex array: a tightly packed triangle at the bottom, constant colour.
    buffer(gl, n, ARRAY_BUFFER, &f32s(&[-0.9, -0.9, 0.0, -0.5, -0.9, 0.0, -0.7, -0.5, 0.0]))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glVertexAttrib4f(1, 1.0, 1.0, 0.0, 1.0)?;
    let (a, b) = (n.next(), n.next());
    gl.glGenVertexArraysOES(Slice::new(&[a, b]))?;
    // Array a: interleaved position + colour, drawn with an element buffer.
    gl.glBindVertexArrayOES(a)?;
    let v =
        [-0.4f32, -0.4, 0.0, 1.0, 0.0, 0.0, 1.0, 0.4, -0.4, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.4, 0.0, 0.0, 0.0, 1.0, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 0, 3, FLOAT, false, 28, 0)?;
    attrib(gl, 1, 4, FLOAT, false, 28, 12)?;
    let elements = buffer(gl, n, ELEMENT_ARRAY_BUFFER, &[0u8, 1, 2])?;
    // Array b: positions only at the top right; its colour attribute stays disabled.
    gl.glBindVertexArrayOES(b)?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&[0.5, 0.5, 0.0, 0.95, 0.5, 0.0, 0.95, 0.95, 0.0]))?;
    attrib(gl, 0, 3, FLOAT, false, 0, 0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)?;
    gl.glBindVertexArrayOES(a)?;
    gl.glDrawElements(TRIANGLES, 3, UNSIGNED_BYTE, 0)?;
    gl.glBindVertexArrayOES(0)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)?;
    // The element array binding belongs to the vertex array: none in the default one.
    let in_default = gl.glGetIntegerv(ELEMENT_ARRAY_BUFFER_BINDING)?.first().copied().unwrap_or(-1);
    gl.glBindVertexArrayOES(a)?;
    let in_a = gl.glGetIntegerv(ELEMENT_ARRAY_BUFFER_BINDING)?.first().copied().unwrap_or(-1);
    gl.glBindVertexArrayOES(0)?;
    let ok = in_default == 0 && in_a == elements as i32;
    patch(gl, 32, 48, if ok { [0.0, 1.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0, 1.0] })?;
    // Queries as patches: the binding after deleting the bound array, and IsVertexArray.
    gl.glBindVertexArrayOES(b)?;
    gl.glDeleteVertexArraysOES(Slice::new(&[b]))?;
    let binding = gl.glGetIntegerv(VERTEX_ARRAY_BINDING_OES)?.first().copied().unwrap_or(-1);
    patch(gl, 0, 48, if binding == 0 { [0.0, 1.0, 0.0, 1.0] } else { [1.0, 0.0, 0.0, 1.0] })?;
    let alive = [gl.glIsVertexArrayOES(a)?, gl.glIsVertexArrayOES(b)?];
    patch(gl, 16, 48, [f32::from(u8::from(alive[0])), f32::from(u8::from(alive[1])), 0.25, 1.0])
}

/// Debug messages and groups with debug output on: the log's count and ids, the group stack
/// depth and a label's length, shown as patches.
fn khr_debug_log(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(DEBUG_OUTPUT_KHR)?;
    // Drop whatever the implementation logged so far (start-up messages differ).
    let _ = gl.glGetDebugMessageLogKHR(64, 0, false)?;
    let msg = |s: &str| Blob::borrowed(s.as_bytes()).into_owned();
    gl.glDebugMessageInsertKHR(
        DEBUG_SOURCE_APPLICATION_KHR,
        DEBUG_TYPE_MARKER_KHR,
        7,
        DEBUG_SEVERITY_NOTIFICATION_KHR,
        5,
        msg("hello"),
    )?;
    // Messages of type OTHER are muted, so the next one is not logged.
    gl.glDebugMessageControlKHR(DONT_CARE, DEBUG_TYPE_OTHER_KHR, DONT_CARE, 0, Slice::new(&[]), false)?;
    gl.glDebugMessageInsertKHR(
        DEBUG_SOURCE_APPLICATION_KHR,
        DEBUG_TYPE_OTHER_KHR,
        8,
        DEBUG_SEVERITY_HIGH_KHR,
        -1,
        msg("muted"),
    )?;
    gl.glPushDebugGroupKHR(DEBUG_SOURCE_APPLICATION_KHR, 9, -1, msg("group"))?;
    let depth = gl.glGetIntegerv(DEBUG_GROUP_STACK_DEPTH_KHR)?.first().copied().unwrap_or(-1);
    gl.glPopDebugGroupKHR()?;
    let logged = gl.glGetIntegerv(DEBUG_LOGGED_MESSAGES_KHR)?.first().copied().unwrap_or(-1);
    let log = gl.glGetDebugMessageLogKHR(16, 4096, true)?;
    patch(gl, 0, 0, level(i64::from(depth)))?;
    patch(gl, 16, 0, level(i64::from(logged)))?;
    patch(gl, 32, 0, level(log.len() as i64))?;
    let ids: Vec<u32> = log.iter().map(|m| m.id).collect();
    let texts_ok = log.first().is_some_and(|m| m.text.0 == b"hello");
    patch(gl, 48, 0, [f32::from(u8::from(ids == [7, 9, 9])), f32::from(u8::from(texts_ok)), 0.5, 1.0])?;
    // A label on a buffer, read back.
    let buf = buffer(gl, n, ARRAY_BUFFER, &[0u8; 16])?;
    gl.glObjectLabelKHR(BUFFER_KHR, buf, -1, Some(msg("vertices")))?;
    let label = gl.glGetObjectLabelKHR(BUFFER_KHR, buf, 64)?;
    patch(gl, 0, 16, level(label.map_or(0, |l| l.0.len() as i64)))
}

/// The programs of this file.
pub fn all() -> Vec<Case> {
    vec![
        Case { name: "vao_switch", run: vao_switch, tol: DEFAULT, expects_error: false },
        Case { name: "khr_debug_log", run: khr_debug_log, tol: DEFAULT, expects_error: false },
    ]
}

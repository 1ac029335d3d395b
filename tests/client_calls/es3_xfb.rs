//! ES 3.0's transform feedback in an ES 3.0 context: varyings captured interleaved (a vector,
//! `gl_Position`, an integer) and separately (into ranges of two buffers), from triangles with
//! the rasterizer discarding and from points drawn instanced; what the buffers hold read back
//! through a mapping and drawn from; the objects, the bindings and the state; pause and resume;
//! the primitives-written query; and the errors: modes, indexed draws, too small a buffer,
//! calls refused while capturing, varyings that are no output, bad names and limits.

use std::ffi::CString;

use super::*;

const TRANSFORM_FEEDBACK: u32 = 0x8E22;
const TF_BUFFER: u32 = 0x8C8E;
const INTERLEAVED: u32 = 0x8C8C;
const SEPARATE: u32 = 0x8C8D;
const RASTERIZER_DISCARD: u32 = 0x8C89;
const PRIMITIVES_WRITTEN: u32 = 0x8C88;
const QUERY_RESULT: u32 = 0x8866;
const POINTS: u32 = 0x0000;
const LINES: u32 = 0x0001;
const TRIANGLES: u32 = 0x0004;
const FLOAT: u32 = 0x1406;
const MAP_READ: u32 = 0x0001;
const LINK_STATUS: u32 = 0x8B82;
const RGBA: u32 = 0x1908;
const UNSIGNED_BYTE: u32 = 0x1401;
/// `glGetProgramiv`'s names.
const BUFFER_MODE: u32 = 0x8C7F;
const VARYINGS: u32 = 0x8C83;
const VARYING_MAX_LENGTH: u32 = 0x8C76;
/// `glGetIntegerv`'s and `glGetIntegeri_v`'s names.
const XFB_BINDING: u32 = 0x8E25;
const XFB_ACTIVE: u32 = 0x8E24;
const XFB_PAUSED: u32 = 0x8E23;
const XFB_BUFFER_BINDING: u32 = 0x8C8F;
const XFB_BUFFER_START: u32 = 0x8C84;
const XFB_BUFFER_SIZE: u32 = 0x8C85;
const MAX_INTERLEAVED: u32 = 0x8C8A;
const MAX_SEPARATE_ATTRIBS: u32 = 0x8C8B;
const MAX_SEPARATE_COMPONENTS: u32 = 0x8C80;

/// Doubles of the position, `gl_Position` as given, an integer and a scale.
const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    out vec4 twice; flat out int id; out float scale;
    void main() { twice = pos * 2.0; id = gl_VertexID * 3 - 1; scale = pos.x + 0.5; gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision mediump float; in vec4 twice; flat in int id; in float scale; out vec4 o;
    void main() { o = vec4(twice.x * 0.0 + 1.0, float(id) * 0.0, scale * 0.0, 1.0); }";
/// Draws the captured positions: a red triangle where they are.
const VS_DRAW: &str = "#version 300 es
    layout(location = 0) in vec4 pos; void main() { gl_Position = pos; }";
const FS_RED: &str = "#version 300 es
    precision mediump float; out vec4 o; void main() { o = vec4(1.0, 0.0, 0.0, 1.0); }";

/// A program of `vs` and `fs` capturing `names` in `mode`; logs its link status.
fn xfb_program(r: &mut Run, what: &str, names: &[&str], mode: u32) -> u32 {
    let gl = r.gl;
    let owned: Vec<CString> = names.iter().map(|n| CString::new(*n).expect("a name")).collect();
    let ptrs: Vec<*const i8> = owned.iter().map(|c| c.as_ptr()).collect();
    // SAFETY: a context is current; the strings are NUL-terminated.
    unsafe {
        let p = (gl.create_program)();
        for (ty, src) in [(0x8B31, VS), (0x8B30, FS)] {
            let s = (gl.create_shader)(ty);
            let src = CString::new(src).expect("source");
            (gl.shader_source)(s, 1, &src.as_ptr(), std::ptr::null());
            (gl.compile_shader)(s);
            (gl.attach_shader)(p, s);
        }
        (gl.transform_feedback_varyings)(p, ptrs.len() as i32, ptrs.as_ptr(), mode);
        r.note(&format!("glTransformFeedbackVaryings ({what})"));
        (gl.link_program)(p);
        let mut ok = -1;
        (gl.get_programiv)(p, LINK_STATUS, &mut ok);
        r.note(&format!("link ({what}): {ok}"));
        p
    }
}

/// Logs `buffer`'s first `n` words as floats and as integers, mapped through the generic
/// transform feedback binding.
fn words(r: &mut Run, what: &str, buffer: u32, n: usize) {
    let gl = r.gl;
    // SAFETY: a context is current; the mapping holds `n` words when it is not null.
    unsafe {
        (gl.bind_buffer)(TF_BUFFER, buffer);
        let p = (gl.core_map_buffer_range)(TF_BUFFER, 0, (n * 4) as isize, MAP_READ);
        if p.is_null() {
            r.note(&format!("{what}: no mapping"));
            return;
        }
        let w = std::slice::from_raw_parts(p.cast::<u32>(), n).to_vec();
        (gl.core_unmap_buffer)(TF_BUFFER);
        let shown: Vec<String> = w
            .iter()
            .map(|&x| {
                if (x as i32).unsigned_abs() < 1000 {
                    format!("i{}", x as i32)
                } else {
                    format!("{}", f32::from_bits(x))
                }
            })
            .collect();
        r.note(&format!("{what}: {}", shown.join(" ")));
    }
}

/// Logs integer state `pname`, or whether it is `name` (names differ between the two).
fn int(r: &mut Run, pname: u32, name: Option<u32>) {
    let mut v = -7;
    // SAFETY: a context is current; one value.
    unsafe { (r.gl.get_integerv)(pname, &mut v) };
    match name {
        Some(n) => r.note(&format!("glGetIntegerv({pname:#x}) is the name: {}", v as u32 == n)),
        None => r.note(&format!("glGetIntegerv({pname:#x}) = {v}")),
    }
}

/// Logs indexed state `pname` at `index`, or whether it is `name`.
fn indexed(r: &mut Run, pname: u32, index: u32, name: Option<u32>) {
    let mut v = -7;
    // SAFETY: a context is current; one value.
    unsafe { (r.gl.get_integeri_v)(pname, index, &mut v) };
    match name {
        Some(n) => r.note(&format!("glGetIntegeri_v({pname:#x}, {index}) is the name: {}", v as u32 == n)),
        None => r.note(&format!("glGetIntegeri_v({pname:#x}, {index}) = {v}")),
    }
}

/// The transform feedback sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; every pointer holds what the call reads or
    // writes; client arrays outlive the draws that read them.
    unsafe {
        (gl.viewport)(0, 0, 16, 16);
        for pname in [MAX_INTERLEAVED, MAX_SEPARATE_ATTRIBS, MAX_SEPARATE_COMPONENTS, XFB_BINDING, XFB_ACTIVE] {
            int(r, pname, None);
        }
        let p = xfb_program(r, "interleaved", &["twice", "gl_Position", "id"], INTERLEAVED);
        for pname in [BUFFER_MODE, VARYINGS, VARYING_MAX_LENGTH] {
            let mut v = -7;
            (gl.get_programiv)(p, pname, &mut v);
            r.note(&format!("glGetProgramiv({pname:#x}) = {v}"));
        }
        for i in 0..4 {
            let (mut len, mut size, mut ty, mut name) = (-7, -7, 0u32, [0i8; 32]);
            (gl.get_transform_feedback_varying)(p, i, 32, &mut len, &mut size, &mut ty, name.as_mut_ptr());
            let n = std::ffi::CStr::from_ptr(name.as_ptr()).to_string_lossy().into_owned();
            r.note(&format!("varying {i}: length {len} size {size} type {ty:#x} name {n:?}"));
        }
        let mut xfb = 0;
        (gl.gen_transform_feedbacks)(1, &mut xfb);
        r.note(&format!("glIsTransformFeedback before binding: {}", (gl.is_transform_feedback)(xfb)));
        (gl.bind_transform_feedback)(TRANSFORM_FEEDBACK, xfb);
        r.note(&format!("glIsTransformFeedback bound: {}", (gl.is_transform_feedback)(xfb)));
        int(r, XFB_BINDING, Some(xfb));
        let mut bufs = [0u32; 3];
        (gl.gen_buffers)(3, bufs.as_mut_ptr());
        for &b in &bufs {
            (gl.bind_buffer)(TF_BUFFER, b);
            (gl.buffer_data)(TF_BUFFER, 512, [0u8; 512].as_ptr().cast(), STATIC_DRAW);
        }
        (gl.bind_buffer_base)(TF_BUFFER, 0, bufs[0]);
        indexed(r, XFB_BUFFER_BINDING, 0, Some(bufs[0]));
        indexed(r, XFB_BUFFER_START, 0, None);
        int(r, XFB_BUFFER_BINDING, Some(bufs[0]));

        // Two triangles and a part, captured with the rasterizer discarding.
        let tri: [f32; 28] = [
            -1.0, -1.0, 0.0, 1.0, 1.0, -1.0, 0.0, 1.0, -1.0, 1.0, 0.0, 1.0, //
            0.5, 0.5, 0.25, 1.0, 0.75, 0.5, 0.25, 1.0, 0.5, 0.75, 0.25, 1.0, 0.0, 0.0, 0.0, 1.0,
        ];
        (gl.bind_buffer)(ARRAY, 0);
        (gl.vertex_attrib_pointer)(0, 4, FLOAT, 0, 0, tri.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.use_program)(p);
        let mut q = 0;
        (gl.core_gen_queries)(1, &mut q);
        (gl.core_begin_query)(PRIMITIVES_WRITTEN, q);
        r.note("glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN)");
        (gl.enable)(RASTERIZER_DISCARD);
        r.note(&format!("rasterizer discard: {}", (gl.is_enabled)(RASTERIZER_DISCARD)));
        (gl.clear_color)(0.0, 0.0, 1.0, 1.0);
        (gl.clear)(0x4000);
        r.note("glClear with the rasterizer discarding");
        (gl.begin_transform_feedback)(TRIANGLES);
        r.note("glBeginTransformFeedback(GL_TRIANGLES)");
        int(r, XFB_ACTIVE, None);
        (gl.draw_arrays)(TRIANGLES, 0, 3);
        r.note("a triangle captured");
        (gl.draw_arrays)(LINES, 0, 2);
        r.note("lines while capturing triangles");
        (gl.draw_elements)(TRIANGLES, 3, 0x1403, [0u16, 1, 2].as_ptr().cast());
        r.note("an indexed draw while capturing");
        (gl.use_program)(0);
        r.note("glUseProgram while capturing");
        (gl.bind_buffer_base)(TF_BUFFER, 0, bufs[1]);
        r.note("glBindBufferBase while capturing");
        (gl.bind_transform_feedback)(TRANSFORM_FEEDBACK, 0);
        r.note("glBindTransformFeedback while capturing");
        (gl.link_program)(p);
        r.note("glLinkProgram of the captured program");
        (gl.begin_transform_feedback)(TRIANGLES);
        r.note("glBeginTransformFeedback again");
        (gl.resume_transform_feedback)();
        r.note("glResumeTransformFeedback unpaused");
        (gl.pause_transform_feedback)();
        int(r, XFB_PAUSED, None);
        (gl.draw_arrays)(TRIANGLES, 0, 3);
        r.note("a draw while paused");
        (gl.pause_transform_feedback)();
        r.note("glPauseTransformFeedback paused");
        (gl.resume_transform_feedback)();
        // Four vertices: the fourth starts a triangle that is not finished.
        (gl.draw_arrays)(TRIANGLES, 3, 4);
        r.note("a triangle and a vertex captured");
        // A strip of four: two triangles, recorded on their own, right after the triangle.
        (gl.draw_arrays)(0x0005, 0, 4);
        r.note("a strip captured as triangles");
        (gl.end_transform_feedback)();
        r.note("glEndTransformFeedback");
        (gl.end_transform_feedback)();
        r.note("glEndTransformFeedback again");
        (gl.core_end_query)(PRIMITIVES_WRITTEN);
        let mut n = 0u32;
        (gl.get_query_object_uiv_core)(q, QUERY_RESULT, &mut n);
        r.note(&format!("primitives written: {n}"));
        (gl.disable)(RASTERIZER_DISCARD);
        let mut px = [0u8; 4];
        (gl.read_pixels)(4, 4, 1, 1, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        r.note(&format!("the window after a discarded clear and discarded draws: {px:?}"));
        // Twelve vertices captured, and nothing after them.
        words(r, "interleaved", bufs[0], 117);

        // What was captured drawn from: gl_Position is the second vector of each record.
        let draw = r.program(VS_DRAW, FS_RED);
        (gl.bind_buffer)(ARRAY, bufs[0]);
        (gl.vertex_attrib_pointer)(0, 4, FLOAT, 0, 36, 16 as *const c_void);
        (gl.clear_color)(0.0, 0.0, 0.0, 1.0);
        (gl.clear)(0x4000);
        (gl.draw_arrays)(TRIANGLES, 0, 12);
        let mut px = vec![0u8; 16 * 16 * 4];
        (gl.read_pixels)(0, 0, 16, 16, RGBA, UNSIGNED_BYTE, px.as_mut_ptr().cast());
        let red = px.chunks(4).filter(|p| p[0] > 128).count();
        r.note(&format!("pixels drawn from the captured positions: {red}"));
        (gl.bind_buffer)(ARRAY, 0);
        (gl.delete_program)(draw);

        // The program's binary captures what it does.
        let mut len = 0;
        (gl.get_programiv)(p, 0x8741, &mut len);
        let mut bin = vec![0u8; len.max(0) as usize];
        let (mut got, mut format) = (0, 0u32);
        (gl.get_program_binary)(p, len, &mut got, &mut format, bin.as_mut_ptr().cast());
        let q = (gl.create_program)();
        (gl.program_binary)(q, format, bin.as_ptr().cast(), got);
        let (mut ok, mut varyings) = (-1, -1);
        (gl.get_programiv)(q, LINK_STATUS, &mut ok);
        (gl.get_programiv)(q, VARYINGS, &mut varyings);
        r.note(&format!("a program from the binary: linked {ok}, {varyings} varyings"));
        (gl.use_program)(q);
        (gl.vertex_attrib_pointer)(0, 4, FLOAT, 0, 0, tri.as_ptr().cast());
        (gl.bind_buffer_base)(TF_BUFFER, 0, bufs[2]);
        (gl.begin_transform_feedback)(POINTS);
        (gl.draw_arrays)(POINTS, 4, 2);
        (gl.end_transform_feedback)();
        words(r, "captured by the binary's program", bufs[2], 18);
        (gl.delete_program)(q);

        // Separate buffers, ranges of two, from points drawn twice over.
        let s = xfb_program(r, "separate", &["scale", "twice"], SEPARATE);
        (gl.use_program)(s);
        (gl.vertex_attrib_pointer)(0, 4, FLOAT, 0, 0, tri.as_ptr().cast());
        (gl.bind_buffer_range)(TF_BUFFER, 0, bufs[1], 16, 64);
        (gl.bind_buffer_range)(TF_BUFFER, 1, bufs[2], 32, 128);
        indexed(r, XFB_BUFFER_START, 1, None);
        indexed(r, XFB_BUFFER_SIZE, 1, None);
        (gl.begin_transform_feedback)(POINTS);
        (gl.draw_arrays)(POINTS, 1, 3);
        (gl.core_draw_arrays_instanced)(POINTS, 4, 2, 2);
        r.note("points captured, then instanced points");
        // Too many for the ranges left: nothing is drawn or captured.
        (gl.draw_arrays)(POINTS, 0, 7);
        r.note("more points than the buffers hold");
        (gl.end_transform_feedback)();
        words(r, "separate, buffer 1", bufs[1], 14);
        words(r, "separate, buffer 2", bufs[2], 40);

        // The errors.
        (gl.begin_transform_feedback)(0x0005);
        r.note("glBeginTransformFeedback(GL_TRIANGLE_STRIP)");
        (gl.bind_transform_feedback)(0x1234, 0);
        r.note("glBindTransformFeedback of another target");
        (gl.bind_transform_feedback)(TRANSFORM_FEEDBACK, 999);
        r.note("glBindTransformFeedback of no object");
        (gl.pause_transform_feedback)();
        r.note("glPauseTransformFeedback inactive");
        (gl.bind_buffer_range)(TF_BUFFER, 0, bufs[1], 2, 64);
        r.note("glBindBufferRange at an odd offset");
        (gl.bind_buffer_range)(TF_BUFFER, 0, bufs[1], 0, 6);
        r.note("glBindBufferRange of an odd size");
        (gl.bind_buffer_base)(TF_BUFFER, 4, bufs[1]);
        r.note("glBindBufferBase past the bindings");
        let name = c"twice";
        (gl.transform_feedback_varyings)(s, 1, &name.as_ptr(), 0x1234);
        r.note("glTransformFeedbackVaryings of another mode");
        (gl.transform_feedback_varyings)(s, -1, &name.as_ptr(), INTERLEAVED);
        r.note("glTransformFeedbackVaryings of -1");
        let five = [name.as_ptr(); 5];
        (gl.transform_feedback_varyings)(s, 5, five.as_ptr(), SEPARATE);
        r.note("glTransformFeedbackVaryings of five separate");
        (gl.transform_feedback_varyings)(0xBEEF, 1, &name.as_ptr(), INTERLEAVED);
        r.note("glTransformFeedbackVaryings of no program");
        xfb_program(r, "no such output", &["nothing"], INTERLEAVED);
        xfb_program(r, "one named twice", &["twice", "twice"], INTERLEAVED);
        let plain = r.program(VS, FS);
        (gl.begin_transform_feedback)(POINTS);
        r.note("glBeginTransformFeedback with nothing to capture");
        (gl.use_program)(p);
        (gl.bind_buffer_base)(TF_BUFFER, 0, 0);
        (gl.begin_transform_feedback)(TRIANGLES);
        r.note("glBeginTransformFeedback with no buffer bound");
        (gl.bind_buffer_base)(TF_BUFFER, 0, bufs[0]);
        (gl.begin_transform_feedback)(TRIANGLES);
        (gl.delete_transform_feedbacks)(1, &xfb);
        r.note("glDeleteTransformFeedbacks of the active one");
        (gl.end_transform_feedback)();
        (gl.bind_transform_feedback)(TRANSFORM_FEEDBACK, 0);
        (gl.delete_transform_feedbacks)(1, &xfb);
        r.note(&format!("deleted: glIsTransformFeedback {}", (gl.is_transform_feedback)(xfb)));
        (gl.disable_vertex_attrib_array)(0);
        (gl.delete_program)(plain);
    }
}

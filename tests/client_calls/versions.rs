//! An ES 2.0 context's answers to OpenGL ES 3.0: ES 3.0's core names for what extensions gave
//! work as the extensions' entry points (Mesa's dispatch makes them aliases); its new entry
//! points resolve but record
//! `GL_INVALID_OPERATION` and do nothing, its version queries are `GL_INVALID_ENUM`, the version
//! strings say 2.0, and a `#version 300 es` shader compiles (Mesa held to ES 2.0 compiles it).

use super::*;

const EXTENSIONS: u32 = 0x1F03;
const VERSION: u32 = 0x1F02;
const MAJOR_VERSION: u32 = 0x821B;
const NUM_EXTENSIONS: u32 = 0x821D;
const VERTEX_SHADER: u32 = 0x8B31;
const COMPILE_STATUS: u32 = 0x8B81;

/// The version sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls with a current context; out-pointers hold what the queries write, and the
    // strings are NUL-terminated.
    unsafe {
        let mut vao = 0;
        (gl.core_gen_vertex_arrays)(1, &mut vao);
        r.note(&format!("glGenVertexArrays (ES 3.0's name) in an ES 2.0 context: name {}", vao != 0));
        let mut q = 0;
        (gl.core_gen_queries)(1, &mut q);
        r.note(&format!("glGenQueries (ES 3.0's name) in an ES 2.0 context: name {}", q != 0));
        (gl.uniform1ui)(0, 5);
        r.note("glUniform1ui in an ES 2.0 context");
        (gl.draw_range_elements)(0x0004, 0, 2, 3, 0x1401, [0u8, 1, 2].as_ptr().cast());
        r.note("glDrawRangeElements in an ES 2.0 context");
        (gl.clear_buffer_fv)(0x1800, 0, [0.0f32; 4].as_ptr());
        r.note("glClearBufferfv in an ES 2.0 context");
        let l = (gl.get_frag_data_location)(1, c"o".as_ptr());
        r.note(&format!("glGetFragDataLocation in an ES 2.0 context: {l}"));
        (gl.enable)(0x8D69);
        r.note("glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX) in an ES 2.0 context");
        (gl.enable)(0x8C89);
        r.note("glEnable(GL_RASTERIZER_DISCARD) in an ES 2.0 context");
        (gl.begin_transform_feedback)(0x0004);
        r.note("glBeginTransformFeedback in an ES 2.0 context");
        // ES 3.0's attribute types: GL_INT, GL_UNSIGNED_INT, GL_HALF_FLOAT, the packed two.
        (gl.bind_buffer)(ARRAY, 0);
        for ty in [0x1404u32, 0x1405, 0x140B, 0x8D9F, 0x8368] {
            (gl.vertex_attrib_pointer)(1, 4, ty, 0, 0, std::ptr::null());
            r.note(&format!("glVertexAttribPointer of type {ty:#x} in an ES 2.0 context"));
        }
        // Immutable texture storage, and its queries.
        let mut tex = 0;
        (gl.gen_textures)(1, &mut tex);
        (gl.bind_texture)(0x0DE1, tex);
        (gl.tex_storage_2d)(0x0DE1, 1, 0x8058, 4, 4);
        r.note("glTexStorage2D in an ES 2.0 context");
        // ES 3.0's texture parameters: base level, levels of detail, comparison, immutability.
        for pname in [0x912Fu32, 0x82DF, 0x813C, 0x813A, 0x813B, 0x884C, 0x884D] {
            let mut v = -7;
            (gl.get_tex_parameteriv)(0x0DE1, pname, &mut v);
            r.note(&format!("glGetTexParameteriv({pname:#x}) = {v}"));
            (gl.tex_parameteri)(0x0DE1, pname, 0);
            r.note(&format!("glTexParameteri({pname:#x})"));
        }
        // 2D array textures.
        (gl.bind_texture)(0x8C1A, tex);
        r.note("glBindTexture(GL_TEXTURE_2D_ARRAY) in an ES 2.0 context");
        let mut v = -7;
        (gl.get_integerv)(0x8C1D, &mut v);
        r.note(&format!("GL_TEXTURE_BINDING_2D_ARRAY in an ES 2.0 context: {v}"));
        // The draw and read framebuffer targets of attachments and status.
        let mut fb = 0;
        (gl.gen_framebuffers)(1, &mut fb);
        (gl.bind_framebuffer)(0x8D40, fb);
        (gl.framebuffer_texture_2d)(0x8CA9, 0x8CE0, 0x0DE1, tex, 0);
        r.note("glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER) in an ES 2.0 context");
        let status = (gl.check_framebuffer_status)(0x8CA8);
        r.note(&format!("glCheckFramebufferStatus(GL_READ_FRAMEBUFFER) in an ES 2.0 context: {status:#x}"));
        (gl.bind_framebuffer)(0x8D40, 0);
        // Sampler objects.
        let mut sampler = 0;
        (gl.gen_samplers)(1, &mut sampler);
        r.note("glGenSamplers in an ES 2.0 context");
        (gl.bind_sampler)(0, sampler);
        r.note("glBindSampler in an ES 2.0 context");
        let s = (gl.fence_sync)(0x9117, 0);
        r.note(&format!("glFenceSync in an ES 2.0 context: null {}", s.is_null()));
        let w = (gl.client_wait_sync)(s, 0, 0);
        r.note(&format!("glClientWaitSync in an ES 2.0 context: {w:#x}"));
        let s = (gl.get_string_i)(EXTENSIONS, 0);
        r.note(&format!("glGetStringi in an ES 2.0 context: null {}", s.is_null()));
        for pname in [MAJOR_VERSION, NUM_EXTENSIONS] {
            let mut v = -7;
            (gl.get_integerv)(pname, &mut v);
            r.note(&format!("glGetIntegerv({pname:#x}) = {v}"));
        }
        let version = std::ffi::CStr::from_ptr((gl.get_string)(VERSION).cast()).to_string_lossy().into_owned();
        r.note(&format!("GL_VERSION starts {:?}", version.split(' ').take(3).collect::<Vec<_>>()));
        let shader = (gl.create_shader)(VERTEX_SHADER);
        let src = c"#version 300 es\nin vec4 p; out vec4 c; void main() { c = p; gl_Position = p; }";
        (gl.shader_source)(shader, 1, &src.as_ptr(), std::ptr::null());
        (gl.compile_shader)(shader);
        let mut ok = -1;
        (gl.get_shaderiv)(shader, COMPILE_STATUS, &mut ok);
        r.note(&format!("a 300 es shader compiles: {ok}"));
    }
}

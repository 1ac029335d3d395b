//! `GL_EXT_separate_shader_objects` through the C entry points: separable programs of one
//! stage (linked, and made by `glCreateShaderProgramvEXT`), pipelines drawing the vertex
//! stage of one with the fragment stage of another, each program's uniforms kept apart where
//! their names clash (a vector, a boolean, a `mat2`, a sampler), written by
//! `glProgramUniform*EXT` and through the active program, a program in use overriding the
//! pipeline, validation (interfaces that differ in precision, a program active for only some
//! of its stages), the state queries, deletion while in use, the directive and macro, and the
//! errors of every call.

use super::*;

const SEPARABLE: u32 = 0x8258;
const ACTIVE_PROGRAM: u32 = 0x8259;
const PIPELINE_BINDING: u32 = 0x825A;
const VERTEX_SHADER: u32 = 0x8B31;
const FRAGMENT_SHADER: u32 = 0x8B30;
const VALIDATE_STATUS: u32 = 0x8B83;
const INFO_LOG_LENGTH: u32 = 0x8B84;
const LINK_STATUS: u32 = 0x8B82;
const DELETE_STATUS: u32 = 0x8B80;
const CURRENT_PROGRAM: u32 = 0x8B8D;
const VERTEX_BIT: u32 = 1;
const FRAGMENT_BIT: u32 = 2;
const ALL_BITS: u32 = u32::MAX;
const FLOAT: u32 = 0x1406;
/// A name no object has (each library names objects its own way, from 1 up).
const UNNAMED: u32 = 0x7FFF_0000;

/// A vertex stage: the position, and a colour from its own uniforms (`k`, `flip`, `m`).
const VS: &str = "attribute vec2 pos; uniform vec4 k; uniform bool flip; uniform mat2 m; varying vec4 c; varying vec2 uv;
    void main() { c = flip ? k.wzyx : k; c.xy += m[1] * 0.25; uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";
/// A fragment stage with uniforms of the same names and types, and a sampler.
const FS: &str = "precision mediump float; varying highp vec4 c; varying highp vec2 uv; uniform highp vec4 k;
    uniform bool flip; uniform mat2 m; uniform sampler2D s;
    void main() { vec4 t = texture2D(s, uv); gl_FragColor = c * 0.5 + (flip ? k.yxwz : k) * 0.25 + t * 0.25 + vec4(m[0], 0.0, 0.0); }";
/// A fragment stage whose varying differs in precision from the vertex stage's.
const FS_LOWP: &str = "precision mediump float; varying lowp vec4 c; void main() { gl_FragColor = c; }";
/// A fragment stage reading a varying no vertex stage writes.
const FS_OTHER: &str = "precision mediump float; varying highp vec4 other; void main() { gl_FragColor = other; }";
/// A whole program's stages.
const FULL_VS: &str = "attribute vec2 pos; varying highp vec4 c; void main() { c = vec4(0.2, 0.4, 0.6, 1.0); gl_Position = vec4(pos, 0.0, 1.0); }";
const FULL_FS: &str = "precision mediump float; varying highp vec4 c; void main() { gl_FragColor = c.zyxw; }";

impl Run {
    /// A program of the given stages, made separable (or not) before its link.
    fn separable(&mut self, what: &str, stages: &[(u32, &str)], separable: i32) -> u32 {
        let gl = self.gl;
        // SAFETY: a context is current; the strings are NUL-terminated.
        unsafe {
            let p = (gl.create_program)();
            (gl.program_parameteri)(p, SEPARABLE, separable);
            for &(ty, src) in stages {
                let s = (gl.create_shader)(ty);
                let src = CString::new(src).expect("source");
                (gl.shader_source)(s, 1, &src.as_ptr(), std::ptr::null());
                (gl.compile_shader)(s);
                (gl.attach_shader)(p, s);
            }
            (gl.bind_attrib_location)(p, 0, c"pos".as_ptr());
            (gl.link_program)(p);
            let (mut ok, mut sep) = (-1, -1);
            (gl.get_programiv)(p, LINK_STATUS, &mut ok);
            (gl.get_programiv)(p, SEPARABLE, &mut sep);
            self.note(&format!("{what}: linked {ok}, separable {sep}"));
            p
        }
    }

    /// Logs every state `glGetProgramPipelineivEXT` answers, programs as their names here.
    fn pipeline_state(&mut self, what: &str, pipeline: u32, names: &[(u32, &str)]) {
        let name = |v: i32| names.iter().find(|(n, _)| *n as i32 == v).map_or(v.to_string(), |(_, s)| s.to_string());
        for (pname, label) in [
            (ACTIVE_PROGRAM, "active"),
            (VERTEX_SHADER, "vertex"),
            (FRAGMENT_SHADER, "fragment"),
            (VALIDATE_STATUS, "validated"),
            (INFO_LOG_LENGTH, "log length"),
        ] {
            let mut v = -7;
            // SAFETY: a context is current; room for one value.
            unsafe { (self.gl.get_program_pipeline_iv)(pipeline, pname, &mut v) };
            let v =
                if matches!(pname, ACTIVE_PROGRAM | VERTEX_SHADER | FRAGMENT_SHADER) { name(v) } else { v.to_string() };
            self.note(&format!("{what}: {label} {v}"));
        }
    }

    /// Clears, draws the window-filling quad and logs the pixel at (3, 3).
    fn draw_pixel(&mut self, what: &str) {
        let gl = self.gl;
        let mut px = [0u8; 4];
        // SAFETY: a context is current; the quad's array is alive through the draw.
        unsafe {
            (gl.clear)(0x4000);
            (gl.draw_arrays)(0x0005, 0, 4);
            self.note(&format!("{what}: draw"));
            (gl.read_pixels)(3, 3, 1, 1, 0x1908, 0x1401, px.as_mut_ptr().cast());
        }
        self.log.push(format!("{what}: pixel {px:?}"));
    }

    /// Validates `pipeline`; logs the status and whether the log says anything.
    fn validate(&mut self, what: &str, pipeline: u32) {
        let gl = self.gl;
        let (mut status, mut len) = (-1, -1);
        let mut buf = [0u8; 256];
        // SAFETY: a context is current; `buf` has room for 256 bytes.
        unsafe {
            (gl.validate_program_pipeline)(pipeline);
            (gl.get_program_pipeline_iv)(pipeline, VALIDATE_STATUS, &mut status);
            (gl.get_program_pipeline_info_log)(pipeline, 256, &mut len, buf.as_mut_ptr().cast());
        }
        self.note(&format!("{what}: validated {status}, log written {}", len > 0));
    }
}

/// The separate shader objects sequence.
pub fn sequence(r: &mut Run) {
    let gl = r.gl;
    // SAFETY: GL calls on the current context; every pointer is valid for the call.
    unsafe {
        (gl.use_program)(0);
        let quad = [-1.0f32, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];
        (gl.bind_buffer)(ARRAY, 0);
        (gl.vertex_attrib_pointer)(0, 2, FLOAT, 0, 0, quad.as_ptr().cast());
        (gl.enable_vertex_attrib_array)(0);
        (gl.clear_color)(0.0, 0.0, 0.0, 0.0);
        let mut tex = 0;
        (gl.gen_textures)(1, &mut tex);
        (gl.active_texture)(0x84C0 + 3);
        (gl.bind_texture)(0x0DE1, tex);
        (gl.tex_parameteri)(0x0DE1, 0x2801, 0x2600);
        (gl.tex_image_2d)(0x0DE1, 0, 0x1908, 1, 1, 0, 0x1908, 0x1401, [200u8, 40, 120, 255].as_ptr().cast());
        (gl.active_texture)(0x84C0);

        // Programs: one stage each, linked; the same stage unseparable; both stages separable.
        let v = r.separable("vertex alone", &[(VERTEX_SHADER, VS)], 1);
        let f = r.separable("fragment alone", &[(FRAGMENT_SHADER, FS)], 1);
        r.separable("vertex alone, not separable", &[(VERTEX_SHADER, VS)], 0);
        let both = r.separable("both stages, separable", &[(VERTEX_SHADER, FULL_VS), (FRAGMENT_SHADER, FULL_FS)], 1);
        let full =
            r.separable("both stages, not separable", &[(VERTEX_SHADER, FULL_VS), (FRAGMENT_SHADER, FULL_FS)], 0);
        let src = |s: &str| CString::new(s).expect("source");
        let lowp = src(FS_LOWP);
        let f_lowp = (gl.create_shader_program)(FRAGMENT_SHADER, 1, &lowp.as_ptr());
        r.note(&format!("created from source: {}", f_lowp != 0));
        let other = src(FS_OTHER);
        let f_other = (gl.create_shader_program)(FRAGMENT_SHADER, 1, &other.as_ptr());
        let broken = src("void main() { gl_FragColor = vec4(1.0) }");
        let f_broken = (gl.create_shader_program)(FRAGMENT_SHADER, 1, &broken.as_ptr());
        let (mut ok, mut sep, mut attached) = (-1, -1, -1);
        (gl.get_programiv)(f_broken, LINK_STATUS, &mut ok);
        (gl.get_programiv)(f_broken, SEPARABLE, &mut sep);
        (gl.get_programiv)(f_broken, 0x8B85, &mut attached);
        let mut len = -1;
        (gl.get_programiv)(f_broken, INFO_LOG_LENGTH, &mut len);
        r.note(&format!(
            "a source that does not compile: linked {ok}, separable {sep}, attached {attached}, log {}",
            len > 1
        ));
        let bad = (gl.create_shader_program)(0x1234, 1, &lowp.as_ptr());
        r.note(&format!("a bad type makes {bad}"));
        let names = [(v, "V"), (f, "F"), (both, "B"), (f_lowp, "L"), (f_other, "O")];

        // The directive and the macro of GLSL ES 1.00.
        let directive = "#extension GL_EXT_separate_shader_objects : require\n#ifndef GL_EXT_separate_shader_objects\n#error no macro\n#endif\nprecision mediump float; void main() { gl_FragColor = vec4(GL_EXT_separate_shader_objects); }";
        let d = src(directive);
        let p = (gl.create_shader_program)(FRAGMENT_SHADER, 1, &d.as_ptr());
        (gl.get_programiv)(p, LINK_STATUS, &mut ok);
        r.note(&format!("the directive and macro: linked {ok}"));

        // Uniforms of each program, by glProgramUniform*EXT.
        let loc = |p: u32, n: &std::ffi::CStr| (gl.get_uniform_location)(p, n.as_ptr());
        (gl.program_uniform4f)(v, loc(v, c"k"), 0.8, 0.4, 0.2, 0.6);
        (gl.program_uniform1i)(v, loc(v, c"flip"), 1);
        (gl.program_uniform_matrix2fv)(v, loc(v, c"m"), 1, 0, [0.0f32, 0.0, 0.4, 0.8].as_ptr());
        (gl.program_uniform4fv)(f, loc(f, c"k"), 1, [0.1f32, 0.3, 0.5, 0.7].as_ptr());
        (gl.program_uniform1i)(f, loc(f, c"flip"), 0);
        (gl.program_uniform_matrix2fv)(f, loc(f, c"m"), 1, 0, [0.2f32, 0.1, 0.0, 0.0].as_ptr());
        (gl.program_uniform1iv)(f, loc(f, c"s"), 1, [3].as_ptr());
        r.note("program uniforms");
        let mut back = [0f32; 4];
        (gl.get_uniformfv)(v, loc(v, c"k"), back.as_mut_ptr());
        r.note(&format!("the vertex program's k {back:?}"));

        // A pipeline: named, bound, given stages.
        let mut pl = [0u32; 2];
        (gl.gen_program_pipelines)(2, pl.as_mut_ptr());
        r.note(&format!("a pipeline before binding: {}", (gl.is_program_pipeline)(pl[0])));
        (gl.bind_program_pipeline)(pl[0]);
        r.note(&format!("after binding: {}", (gl.is_program_pipeline)(pl[0])));
        r.pipeline_state("empty", pl[0], &names);
        r.draw_pixel("an empty pipeline");
        (gl.use_program_stages)(pl[0], VERTEX_BIT, v);
        (gl.use_program_stages)(pl[0], FRAGMENT_BIT, f);
        r.note("stages");
        r.pipeline_state("V and F", pl[0], &names);
        r.validate("V and F", pl[0]);
        r.draw_pixel("V and F");
        let mut current = -1;
        (gl.get_integerv)(CURRENT_PROGRAM, &mut current);
        r.note(&format!("the program in use {current}"));
        (gl.get_integerv)(PIPELINE_BINDING, &mut current);
        r.note("the pipeline binding");

        // glUniform* writes the active program, once there is one.
        (gl.uniform4f)(loc(f, c"k"), 0.0, 0.0, 0.0, 0.0);
        r.note("glUniform4f with no active program");
        (gl.active_shader_program)(pl[0], f);
        r.note("active F");
        (gl.get_integerv)(CURRENT_PROGRAM, &mut current);
        r.note(&format!("the program in use with F active {current}"));
        (gl.uniform4f)(loc(f, c"k"), 0.9, 0.1, 0.2, 0.3);
        r.note("glUniform4f on the active program");
        r.pipeline_state("active F", pl[0], &names);
        r.draw_pixel("F's k written through the active program");
        (gl.program_uniform1i)(v, loc(v, c"flip"), 0);
        r.draw_pixel("V's flip cleared");

        // A program in use overrides the pipeline.
        (gl.use_program)(full);
        r.draw_pixel("a program in use");
        (gl.use_program)(0);
        r.draw_pixel("the pipeline again");

        // One program for both stages; then for one stage only.
        (gl.use_program_stages)(pl[0], ALL_BITS, both);
        r.pipeline_state("B for both", pl[0], &names);
        r.draw_pixel("B for both");
        (gl.use_program_stages)(pl[0], FRAGMENT_BIT, f);
        r.validate("B's vertex stage only", pl[0]);
        r.draw_pixel("B's vertex stage only");
        (gl.use_program_stages)(pl[0], ALL_BITS, v);
        r.pipeline_state("V for all", pl[0], &names);
        r.validate("V alone", pl[0]);
        r.draw_pixel("V alone");

        // Interfaces that differ.
        (gl.use_program_stages)(pl[0], FRAGMENT_BIT, f_lowp);
        r.validate("a varying of another precision", pl[0]);
        r.draw_pixel("a varying of another precision");
        (gl.use_program_stages)(pl[0], FRAGMENT_BIT, f_other);
        r.validate("a varying no stage writes", pl[0]);
        r.draw_pixel("a varying no stage writes");
        (gl.use_program_stages)(pl[0], FRAGMENT_BIT, f);
        r.validate("V and F again", pl[0]);

        // Errors.
        (gl.use_program_stages)(pl[0], VERTEX_BIT, full);
        r.note("stages of an unseparable program");
        (gl.use_program_stages)(pl[0], 4, v);
        r.note("an unknown stage bit");
        (gl.use_program_stages)(UNNAMED, VERTEX_BIT, v);
        r.note("stages of a pipeline never named");
        (gl.bind_program_pipeline)(UNNAMED);
        r.note("binding a pipeline never named");
        (gl.use_program_stages)(pl[0], VERTEX_BIT, UNNAMED);
        r.note("stages of no program");
        let shader = (gl.create_shader)(VERTEX_SHADER);
        (gl.use_program_stages)(pl[0], VERTEX_BIT, shader);
        r.note("stages of a shader");
        let unlinked = (gl.create_program)();
        (gl.program_parameteri)(unlinked, SEPARABLE, 1);
        (gl.use_program_stages)(pl[0], VERTEX_BIT, unlinked);
        r.note("stages of an unlinked program");
        (gl.active_shader_program)(pl[0], unlinked);
        r.note("an unlinked active program");
        (gl.active_shader_program)(UNNAMED, v);
        r.note("the active program of a pipeline never named");
        (gl.active_shader_program)(pl[0], UNNAMED);
        r.note("no program active");
        (gl.program_parameteri)(v, 0x1234, 1);
        r.note("an unknown program parameter");
        (gl.program_parameteri)(v, SEPARABLE, 5);
        r.note("a separable value neither true nor false");
        (gl.program_parameteri)(UNNAMED, SEPARABLE, 1);
        r.note("the parameter of no program");
        (gl.program_uniform4f)(UNNAMED, 0, 1.0, 1.0, 1.0, 1.0);
        r.note("a uniform of no program");
        (gl.program_uniform4f)(unlinked, 0, 1.0, 1.0, 1.0, 1.0);
        r.note("a uniform of an unlinked program");
        (gl.program_uniform4f)(v, 99, 1.0, 1.0, 1.0, 1.0);
        r.note("a location the program lacks");
        (gl.program_uniform4f)(v, -1, 1.0, 1.0, 1.0, 1.0);
        r.note("location -1");
        (gl.program_uniform1f)(v, loc(v, c"k"), 1.0);
        r.note("a uniform of another size");
        (gl.program_uniform4fv)(v, loc(v, c"k"), -1, [0f32; 4].as_ptr());
        r.note("a negative count");
        (gl.program_uniform_matrix2fv)(v, loc(v, c"m"), 1, 1, [0f32; 4].as_ptr());
        r.note("a transposed matrix");
        let mut x = -7;
        (gl.get_program_pipeline_iv)(pl[0], 0x1234, &mut x);
        r.note(&format!("an unknown pipeline state leaves {x}"));
        (gl.get_program_pipeline_iv)(UNNAMED, ACTIVE_PROGRAM, &mut x);
        r.note(&format!("the state of a pipeline never named leaves {x}"));
        let mut buf = [0u8; 8];
        (gl.get_program_pipeline_info_log)(UNNAMED, 8, &mut x, buf.as_mut_ptr().cast());
        r.note("the log of a pipeline never named");
        (gl.gen_program_pipelines)(-1, pl.as_mut_ptr());
        r.note("a negative count of pipelines");
        r.note(&format!("a second pipeline, never bound: {}", (gl.is_program_pipeline)(pl[1])));

        // Deletion: a program a pipeline uses stays until it does not; the bound pipeline.
        (gl.delete_program)(v);
        let mut status = -1;
        (gl.get_programiv)(v, DELETE_STATUS, &mut status);
        r.note(&format!("the vertex program deleted while the pipeline uses it: {status}"));
        r.draw_pixel("after the deletion");
        (gl.use_program_stages)(pl[0], VERTEX_BIT, 0);
        (gl.get_programiv)(v, DELETE_STATUS, &mut status);
        r.note("once the pipeline lets it go, the name is no program");
        (gl.delete_program_pipelines)(2, pl.as_ptr());
        r.note(&format!("deleted: {}", (gl.is_program_pipeline)(pl[0])));
        r.draw_pixel("the bound pipeline deleted");
        (gl.bind_program_pipeline)(0);
        r.note("binding none");
    }
}

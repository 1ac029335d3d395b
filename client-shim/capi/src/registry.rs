//! Every entry point by name. The modules that define entry points are listed here, once and
//! nowhere else: `proc_address`, what `eglGetProcAddress` answers, searches them all, and
//! `glXGetProcAddress` the GL ones. Those two queries are the only entry points that need the
//! list, so they are defined here too, and this module is the top of the library: no other
//! module uses it.
//!
//! `glXGetProcAddressARB` and `glXGetProcAddress` answer like `eglGetProcAddress` for the
//! shim's GL entry points. Some GLES programs resolve extension entry points through libGL's
//! GLX query even under EGL (piglit's utility library, built with GLX, does); with the shim
//! also installed as `libGL.so.1`, they get the shim's functions instead of libGL's dispatch
//! stubs, which would call nothing without a GLX context. No other GLX call is provided.
//!
//! The dispatch table the library shares with glvnd (see `glvnd.rs`) answers from the same
//! lookup. That table follows the current context, which the state below every module of
//! entry points sets, so this module hands the lookup down as the library is loaded, before
//! any entry point runs.

use std::ffi::{c_char, c_void, CStr};

use crate::glvnd;
use crate::types::*;

/// Lists the modules that define entry points, EGL-side and GL, each once; defines the lookup
/// of each group's entry points by name and, for the tests, the names of every module's.
macro_rules! entry_point_modules {
    (egl: [$($($egl:ident)::+),* $(,)?], gl: [$($($gl:ident)::+),* $(,)?] $(,)?) => {
        /// The address of an EGL-side entry point (other than this module's), by name.
        fn egl_lookup(name: &[u8]) -> Option<*const c_void> {
            None$(.or_else(|| $($egl)::+::lookup(name)))*
        }

        /// The address of a GL entry point, by name: what `glXGetProcAddress` answers.
        fn gl_lookup(name: &[u8]) -> Option<*const c_void> {
            None$(.or_else(|| $($gl)::+::lookup(name)))*
        }

        /// The names of the entry points of every listed module, by module.
        #[cfg(test)]
        const MODULE_NAMES: &[&[&str]] = &[$($($egl)::+::NAMES,)* $($($gl)::+::NAMES),*];
    };
}

entry_point_modules! {
    egl: [
        crate::egl,
        // With its fences, `glFinish`, which `glXGetProcAddress` therefore does not answer.
        crate::sync,
        crate::image,
    ],
    gl: [
        crate::gl::simple,
        crate::gl::families::uniforms,
        crate::gl::families::matrix,
        crate::gl::families::attrib,
        crate::gl::families::names,
        crate::gl::families::delete,
        crate::gl::families::get_int,
        crate::gl::families::get_arrays,
        crate::gl::families::get_strings,
        crate::gl::families::active,
        crate::gl::hand,
        crate::gl::draws,
        crate::gl::mapping,
        crate::gl::robustness,
        crate::gl::vao,
        crate::gl::debug,
        crate::gl::discard,
        crate::gl::draw_buffers,
        crate::gl::blend_extended,
        crate::gl::program_binary,
        crate::gl::separate,
        crate::gl::separate::scalars,
        crate::gl::separate::arrays,
        crate::gl::separate::matrices,
        crate::gl::border,
        crate::gl::texture3d,
        crate::gl::egl_image,
        crate::gl::es3_aliases,
        crate::gl::uniform_blocks,
        crate::gl::vertex_es3,
        crate::gl::es3_calls,
        crate::gl::sync_objects,
    ],
}

/// The address of any exported EGL or GL entry point, by name.
pub(crate) fn proc_address(name: &[u8]) -> Option<*const c_void> {
    egl_lookup(name).or_else(|| gl_lookup(name)).or_else(|| lookup(name))
}

/// Every exported entry point's name.
#[cfg(test)]
pub(crate) fn exported_names() -> Vec<&'static str> {
    MODULE_NAMES.iter().flat_map(|m| m.iter()).chain(NAMES).copied().collect()
}

/// The address of one of the shim's GL entry points (`None` for EGL names and unknown ones).
fn gl_proc(name: *const GLubyte) -> EglProc {
    if name.is_null() {
        return None;
    }
    // SAFETY: the application passes a NUL-terminated name.
    let name = unsafe { CStr::from_ptr(name.cast::<c_char>()) };
    let f = gl_lookup(name.to_bytes())?;
    // SAFETY: a non-null address of one of the shim's own `extern "C"` functions; the caller
    // casts it back to the right prototype, as glXGetProcAddress specifies.
    Some(unsafe { std::mem::transmute::<*const c_void, unsafe extern "C" fn()>(f) })
}

crate::entry::entry_points! {
    /// The address of any EGL or GLES 2.0 entry point the shim exports (and `GL_OES_mapbuffer`).
    fn eglGetProcAddress(name: *const c_char) -> EglProc {
        if name.is_null() {
            return None;
        }
        // SAFETY: the application passes a NUL-terminated name.
        let name = unsafe { CStr::from_ptr(name) };
        match proc_address(name.to_bytes()) {
            // SAFETY: a non-null address of one of the shim's own `extern "C"` functions; the
            // caller casts it back to the right prototype, as eglGetProcAddress specifies.
            Some(f) => Some(unsafe { std::mem::transmute::<*const c_void, unsafe extern "C" fn()>(f) }),
            None => {
                tracing::debug!("strata-egl: eglGetProcAddress({name:?}): no such entry point");
                None
            }
        }
    }

    /// A GL entry point of the shim, by name.
    fn glXGetProcAddressARB(name: *const GLubyte) -> EglProc {
        gl_proc(name)
    }

    /// A GL entry point of the shim, by name.
    fn glXGetProcAddress(name: *const GLubyte) -> EglProc {
        gl_proc(name)
    }
}

/// Gives glvnd's dispatch table the lookup of every entry point, [`proc_address`].
extern "C" fn install_glvnd_lookup() {
    glvnd::install_lookup(proc_address);
}

/// Runs [`install_glvnd_lookup`] as the library is loaded, before any entry point can make a
/// context current (and so need the table).
#[used]
#[link_section = ".init_array"]
static INSTALL_GLVND_LOOKUP: extern "C" fn() = install_glvnd_lookup;

#[cfg(test)]
mod tests {
    use super::*;

    /// Names declared with `prefix` in a Khronos header, e.g. `GL_APICALL` in `GLES2/gl2.h`.
    fn declared(header: &str, prefix: &str) -> Option<Vec<String>> {
        let text = std::fs::read_to_string(header).ok()?;
        let mut names = Vec::new();
        for line in text.lines().filter(|l| l.starts_with(prefix)) {
            let before_paren = line.split('(').next().unwrap_or_default();
            if let Some(name) = before_paren.split_whitespace().last() {
                names.push(name.to_string());
            }
        }
        Some(names)
    }

    #[test]
    fn every_gles2_entry_point_is_exported_and_resolvable() {
        let Some(names) = declared("/usr/include/GLES2/gl2.h", "GL_APICALL") else {
            assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "GLES2/gl2.h missing");
            eprintln!("skipping: /usr/include/GLES2/gl2.h not installed (libgles-dev)");
            return;
        };
        assert_eq!(names.len(), 142, "gl2.h declares the 142 ES 2.0 entry points");
        let exported = exported_names();
        for n in &names {
            assert!(exported.contains(&n.as_str()), "{n} is not exported");
            assert!(proc_address(n.as_bytes()).is_some(), "eglGetProcAddress cannot resolve {n}");
        }
    }

    #[test]
    fn every_entry_point_of_the_offered_extensions_is_exported_and_resolvable() {
        offered_sections_resolve(
            "GLES2/gl2ext.h",
            "GL_APICALL",
            &[
                ("GL_KHR_debug", 11),
                ("GL_OES_vertex_array_object", 4),
                ("GL_OES_mapbuffer", 3),
                ("GL_EXT_map_buffer_range", 2),
                ("GL_EXT_robustness", 4),
                ("GL_KHR_robustness", 5),
                ("GL_EXT_draw_buffers", 1),
                ("GL_NV_draw_buffers", 1),
                ("GL_EXT_blend_func_extended", 4),
                ("GL_OES_get_program_binary", 2),
                ("GL_EXT_clip_control", 1),
                ("GL_OES_EGL_image", 2),
                ("GL_EXT_disjoint_timer_query", 12),
                ("GL_EXT_separate_shader_objects", 30),
                ("GL_EXT_texture_border_clamp", 4),
                ("GL_OES_texture_border_clamp", 4),
                ("GL_OES_texture_3D", 6),
            ],
        );
    }

    #[test]
    fn every_entry_point_of_the_offered_egl_extensions_is_exported_and_resolvable() {
        offered_sections_resolve(
            "EGL/eglext.h",
            "EGLAPI",
            &[
                ("EGL_KHR_fence_sync", 4),
                ("EGL_KHR_reusable_sync", 1),
                ("EGL_KHR_wait_sync", 1),
                ("EGL_KHR_image", 2),
                ("EGL_KHR_swap_buffers_with_damage", 1),
            ],
        );
    }

    /// Entry points of an offered extension's section that only an ES 3.0 context can use
    /// (unsigned and non-square matrix uniforms, which GLSL ES 1.00 has none of, and sampler
    /// objects), by prefix.
    const NEED_ES3: &[&str] = &[
        "glProgramUniform1ui",
        "glProgramUniform2ui",
        "glProgramUniform3ui",
        "glProgramUniform4ui",
        "glProgramUniformMatrix2x",
        "glProgramUniformMatrix3x",
        "glProgramUniformMatrix4x",
        // Sampler objects.
        "glSamplerParameterI",
        "glGetSamplerParameterI",
    ];

    /// Each extension's section of the Khronos header `header` (under /usr/include) declares
    /// `count` entry points (lines starting with `prefix`, besides those [`NEED_ES3`] names);
    /// each is exported and resolvable.
    fn offered_sections_resolve(header: &str, prefix: &str, extensions: &[(&str, usize)]) {
        let Some(text) = std::fs::read_to_string(format!("/usr/include/{header}")).ok() else {
            assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "{header} missing");
            eprintln!("skipping: /usr/include/{header} not installed");
            return;
        };
        let exported = exported_names();
        for &(ext, count) in extensions {
            let start = text.find(&format!("#ifndef {ext}\n")).unwrap_or_else(|| panic!("{ext} not in {header}"));
            let end = text[start..].find(&format!("#endif /* {ext} */")).map(|e| start + e).expect("section end");
            let names: Vec<&str> = text[start..end]
                .lines()
                .filter(|l| l.starts_with(prefix))
                .filter_map(|l| l.split('(').next()?.split_whitespace().last())
                .filter(|n| !NEED_ES3.iter().any(|es3| n.starts_with(es3)))
                .collect();
            assert_eq!(names.len(), count, "{ext} declares {count} entry points");
            for n in names {
                assert!(exported.contains(&n), "{n} ({ext}) is not exported");
                assert!(proc_address(n.as_bytes()).is_some(), "eglGetProcAddress cannot resolve {n}");
            }
        }
    }

    #[test]
    fn every_egl_1_4_entry_point_is_exported_and_resolvable() {
        let Some(text) = std::fs::read_to_string("/usr/include/EGL/egl.h").ok() else {
            assert!(std::env::var_os("STRATA_REQUIRE_ORACLES").is_none(), "EGL/egl.h missing");
            eprintln!("skipping: /usr/include/EGL/egl.h not installed (libegl-dev)");
            return;
        };
        // Only the EGL 1.0 to 1.4 sections: 1.5 adds sync, image and platform calls.
        let end = text.find("#ifndef EGL_VERSION_1_5").expect("egl.h has an EGL 1.5 section");
        let names: Vec<&str> = text[..end]
            .lines()
            .filter(|l| l.starts_with("EGLAPI"))
            .filter_map(|l| l.split('(').next()?.split_whitespace().last())
            .collect();
        assert_eq!(names.len(), 34, "EGL 1.4 has 34 entry points");
        let exported = exported_names();
        for n in names {
            assert!(exported.contains(&n), "{n} is not exported");
            assert!(proc_address(n.as_bytes()).is_some(), "eglGetProcAddress cannot resolve {n}");
        }
        for n in ["eglGetPlatformDisplay", "eglGetPlatformDisplayEXT", "eglCreatePlatformWindowSurfaceEXT"] {
            assert!(proc_address(n.as_bytes()).is_some(), "{n}");
        }
        assert!(proc_address(b"glNoSuchCall").is_none());
    }

    #[test]
    fn extension_entry_points_are_exported_and_resolvable_both_ways() {
        let exported = exported_names();
        // The entry points of the extensions the daemon advertises.
        const EXTENSION_ENTRY_POINTS: &[&str] = &[
            "glDiscardFramebufferEXT",
            "glDrawBuffersEXT",
            "glDrawBuffersNV",
            "glBindFragDataLocationIndexedEXT",
            "glBindFragDataLocationEXT",
            "glGetFragDataIndexEXT",
            "glGetProgramResourceLocationIndexEXT",
            "glPolygonOffsetClampEXT",
            "glMaxShaderCompilerThreadsKHR",
            "glDrawElementsBaseVertexOES",
            "glDrawElementsBaseVertexEXT",
            "glMultiDrawArraysEXT",
            "glMultiDrawElementsEXT",
            "glMultiDrawElementsBaseVertexEXT",
            "glDrawArraysInstancedEXT",
            "glDrawElementsInstancedEXT",
            "glLabelObjectEXT",
            "glGetObjectLabelEXT",
            "glReadBufferNV",
            "glMapBufferOES",
            "glUnmapBufferOES",
            "glGetBufferPointervOES",
            "glMapBufferRangeEXT",
            "glFlushMappedBufferRangeEXT",
            "glGenQueriesEXT",
            "glDeleteQueriesEXT",
            "glIsQueryEXT",
            "glBeginQueryEXT",
            "glEndQueryEXT",
            "glGetQueryivEXT",
            "glGetQueryObjectuivEXT",
            "glBeginConditionalRenderNV",
            "glEndConditionalRenderNV",
            "glGetGraphicsResetStatusEXT",
            "glReadnPixelsEXT",
            "glGetnUniformfvEXT",
            "glGetnUniformivEXT",
            "glGetGraphicsResetStatusKHR",
            "glReadnPixelsKHR",
            "glGetnUniformfvKHR",
            "glGetnUniformivKHR",
            "glGetnUniformuivKHR",
            "glGetProgramBinaryOES",
            "glProgramBinaryOES",
            "glClipControlEXT",
            "glEGLImageTargetTexture2DOES",
            "glEGLImageTargetRenderbufferStorageOES",
            "glQueryCounterEXT",
            "glGetQueryObjectivEXT",
            "glGetQueryObjecti64vEXT",
            "glGetQueryObjectui64vEXT",
            "glGetInteger64vEXT",
            "glCreateShaderProgramvEXT",
            "glUseProgramStagesEXT",
            "glProgramUniform4fEXT",
            "glProgramUniformMatrix4fvEXT",
            "glTexParameterIivEXT",
            "glGetTexParameterIuivOES",
            "glTexImage3DOES",
            "glFramebufferTexture3DOES",
        ];
        for &n in EXTENSION_ENTRY_POINTS {
            assert!(exported.contains(&n), "{n} is not exported");
            let egl = proc_address(n.as_bytes()).expect("eglGetProcAddress resolves it");
            let name = std::ffi::CString::new(n).expect("a C name");
            // SAFETY: a NUL-terminated name.
            let glx = unsafe { glXGetProcAddressARB(name.as_ptr().cast()) };
            let glx = glx.expect("glXGetProcAddressARB resolves it");
            assert_eq!(glx as *const c_void, egl, "{n}: the same function both ways");
        }
        // The GLX query answers GL names only.
        let egl_name = std::ffi::CString::new("eglGetDisplay").expect("a C name");
        // SAFETY: a NUL-terminated name.
        assert!(unsafe { glXGetProcAddressARB(egl_name.as_ptr().cast()) }.is_none());
    }
}

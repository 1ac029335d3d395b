//! A drop-in `libEGL.so.1` and `libGLESv2.so.2`: the EGL 1.4 and GLES 2.0 C ABI, implemented
//! by streaming every call to `stratad` through [`strata_client::Connection`].
//!
//! One shared object provides both libraries (`tools/build-shim` installs it under both names).
//! Every entry point is `extern "C"`, catches panics, and checks the application's pointers for
//! null. Calls that map one-to-one onto a protocol command are generated from the table in
//! [`gl`]; the rest marshal pointers by hand.
#![allow(non_snake_case, clippy::missing_safety_doc)]
#![warn(missing_docs)]

pub mod blend_extended;
mod context;
pub mod debug;
pub mod discard;
mod display;
pub mod draw_buffers;
pub mod egl;
pub mod gl;
mod glvnd;
pub mod glx;
pub mod image;
mod input;
mod state;
mod surface;
pub mod sync;
mod types;
pub mod vao;
mod x11;

pub use types::*;

use std::ffi::c_void;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The value an entry point returns when it cannot run (a caught panic).
pub(crate) trait Fallback {
    /// The neutral value: zero, false or null.
    fn fallback() -> Self;
}

macro_rules! zero_fallback {
    ($($t:ty),*) => { $( impl Fallback for $t { fn fallback() -> Self { 0 as $t } } )* };
}
zero_fallback!(u8, u32, i32, f32, usize);

impl Fallback for () {
    fn fallback() -> Self {}
}

impl<T> Fallback for *const T {
    fn fallback() -> Self {
        std::ptr::null()
    }
}

impl<T> Fallback for *mut T {
    fn fallback() -> Self {
        std::ptr::null_mut()
    }
}

impl Fallback for Option<unsafe extern "C" fn()> {
    fn fallback() -> Self {
        None
    }
}

/// Runs an entry point's body: never lets a panic unwind into C.
pub(crate) fn guard<R: Fallback>(name: &'static str, body: impl FnOnce() -> R) -> R {
    state::init_logging();
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(r) => r,
        Err(_) => {
            tracing::error!("internal error (panic) in {name}; returning a neutral value");
            R::fallback()
        }
    }
}

/// Defines `extern "C"` entry points whose bodies run inside [`guard`], and a lookup of their
/// addresses by name for `eglGetProcAddress`.
macro_rules! entry_points {
    ($( $(#[$attr:meta])* fn $name:ident ( $( $arg:ident : $ty:ty ),* $(,)? ) $( -> $ret:ty )? $body:block )*) => {
        $(
            $(#[$attr])*
            #[no_mangle]
            pub unsafe extern "C" fn $name( $( $arg : $ty ),* ) $( -> $ret )? {
                $crate::guard(stringify!($name), move || $body)
            }
        )*

        /// The address of the entry point named `name`, if this module defines it.
        pub(crate) fn lookup(name: &[u8]) -> Option<*const std::ffi::c_void> {
            match name {
                $( n if n == stringify!($name).as_bytes() => Some($name as *const std::ffi::c_void), )*
                _ => None,
            }
        }

        /// The names of the entry points this module defines.
        #[allow(dead_code)]
        pub(crate) const NAMES: &[&str] = &[ $( stringify!($name) ),* ];
    };
}
pub(crate) use entry_points;

/// The address of any exported EGL or GL entry point, by name.
pub(crate) fn proc_address(name: &[u8]) -> Option<*const c_void> {
    egl::lookup(name)
        .or_else(|| sync::lookup(name))
        .or_else(|| image::lookup(name))
        .or_else(|| gl::lookup(name))
        .or_else(|| glx::lookup(name))
}

/// Every exported entry point's name.
#[cfg(test)]
pub(crate) fn exported_names() -> Vec<&'static str> {
    egl::NAMES
        .iter()
        .chain(sync::NAMES)
        .chain(image::NAMES)
        .chain(gl::MODULE_NAMES.iter().flat_map(|m| m.iter()))
        .copied()
        .collect()
}

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
            let glx = unsafe { glx::glXGetProcAddressARB(name.as_ptr().cast()) };
            let glx = glx.expect("glXGetProcAddressARB resolves it");
            assert_eq!(glx as *const c_void, egl, "{n}: the same function both ways");
        }
        // The GLX query answers GL names only.
        let egl_name = std::ffi::CString::new("eglGetDisplay").expect("a C name");
        // SAFETY: a NUL-terminated name.
        assert!(unsafe { glx::glXGetProcAddressARB(egl_name.as_ptr().cast()) }.is_none());
    }
}

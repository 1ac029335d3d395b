//! The drop-in libEGL/libGLESv2 loaded into the test process, for tests that call the C
//! entry points as an application does.

use std::ffi::c_void;

/// A C pointer (display, config, surface, context).
pub type Ptr = *mut c_void;

/// The EGL and GLES entry points the tests call, resolved from the drop-in libraries.
#[derive(Clone, Copy)]
pub struct Egl {
    pub get_error: unsafe extern "C" fn() -> i32,
    pub get_display: unsafe extern "C" fn(Ptr) -> Ptr,
    pub initialize: unsafe extern "C" fn(Ptr, *mut i32, *mut i32) -> u32,
    pub terminate: unsafe extern "C" fn(Ptr) -> u32,
    pub choose_config: unsafe extern "C" fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32,
    pub bind_api: unsafe extern "C" fn(u32) -> u32,
    pub create_pbuffer: unsafe extern "C" fn(Ptr, Ptr, *const i32) -> Ptr,
    pub destroy_surface: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    pub query_surface: unsafe extern "C" fn(Ptr, Ptr, i32, *mut i32) -> u32,
    pub create_context: unsafe extern "C" fn(Ptr, Ptr, Ptr, *const i32) -> Ptr,
    pub destroy_context: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    pub query_context: unsafe extern "C" fn(Ptr, Ptr, i32, *mut i32) -> u32,
    pub make_current: unsafe extern "C" fn(Ptr, Ptr, Ptr, Ptr) -> u32,
    pub current_context: unsafe extern "C" fn() -> Ptr,
    pub swap_buffers: unsafe extern "C" fn(Ptr, Ptr) -> u32,
    pub gl_get_error: unsafe extern "C" fn() -> u32,
    pub clear_color: unsafe extern "C" fn(f32, f32, f32, f32),
    pub clear: unsafe extern "C" fn(u32),
    pub finish: unsafe extern "C" fn(),
    pub read_pixels: unsafe extern "C" fn(i32, i32, i32, i32, u32, u32, *mut c_void),
}

// SAFETY: plain function pointers into a library that stays loaded for the whole test.
unsafe impl Send for Egl {}

/// Resolves every entry point of [`Egl`] from `lib`; panics naming a missing one.
pub fn load(lib: &libloading::Library) -> Egl {
    // SAFETY: each symbol is declared with its C prototype from egl.h / gl2.h.
    unsafe {
        macro_rules! sym {
            ($name:literal) => {
                *lib.get($name).unwrap_or_else(|e| panic!("{}: {e}", String::from_utf8_lossy($name)))
            };
        }
        Egl {
            get_error: sym!(b"eglGetError"),
            get_display: sym!(b"eglGetDisplay"),
            initialize: sym!(b"eglInitialize"),
            terminate: sym!(b"eglTerminate"),
            choose_config: sym!(b"eglChooseConfig"),
            bind_api: sym!(b"eglBindAPI"),
            create_pbuffer: sym!(b"eglCreatePbufferSurface"),
            destroy_surface: sym!(b"eglDestroySurface"),
            query_surface: sym!(b"eglQuerySurface"),
            create_context: sym!(b"eglCreateContext"),
            destroy_context: sym!(b"eglDestroyContext"),
            query_context: sym!(b"eglQueryContext"),
            make_current: sym!(b"eglMakeCurrent"),
            current_context: sym!(b"eglGetCurrentContext"),
            swap_buffers: sym!(b"eglSwapBuffers"),
            gl_get_error: sym!(b"glGetError"),
            clear_color: sym!(b"glClearColor"),
            clear: sym!(b"glClear"),
            finish: sym!(b"glFinish"),
            read_pixels: sym!(b"glReadPixels"),
        }
    }
}

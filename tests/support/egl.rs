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

/// Resolves one C entry point of `lib` by name; panics naming a missing one.
///
/// # Safety
/// `T` must be the entry point's C prototype.
pub unsafe fn sym<T: Copy>(lib: &libloading::Library, name: &[u8]) -> T {
    // SAFETY: see the function's contract.
    unsafe { *lib.get::<T>(name).unwrap_or_else(|e| panic!("{}: {e}", String::from_utf8_lossy(name))) }
}

/// Resolves every entry point of [`Egl`] from `lib`; panics naming a missing one.
pub fn load(lib: &libloading::Library) -> Egl {
    // SAFETY: each symbol is declared with its C prototype from egl.h / gl2.h.
    unsafe {
        Egl {
            get_error: sym(lib, b"eglGetError"),
            get_display: sym(lib, b"eglGetDisplay"),
            initialize: sym(lib, b"eglInitialize"),
            terminate: sym(lib, b"eglTerminate"),
            choose_config: sym(lib, b"eglChooseConfig"),
            bind_api: sym(lib, b"eglBindAPI"),
            create_pbuffer: sym(lib, b"eglCreatePbufferSurface"),
            destroy_surface: sym(lib, b"eglDestroySurface"),
            query_surface: sym(lib, b"eglQuerySurface"),
            create_context: sym(lib, b"eglCreateContext"),
            destroy_context: sym(lib, b"eglDestroyContext"),
            query_context: sym(lib, b"eglQueryContext"),
            make_current: sym(lib, b"eglMakeCurrent"),
            current_context: sym(lib, b"eglGetCurrentContext"),
            swap_buffers: sym(lib, b"eglSwapBuffers"),
            gl_get_error: sym(lib, b"glGetError"),
            clear_color: sym(lib, b"glClearColor"),
            clear: sym(lib, b"glClear"),
            finish: sym(lib, b"glFinish"),
            read_pixels: sym(lib, b"glReadPixels"),
        }
    }
}

//! The C types of `EGL/egl.h` and `GLES2/gl2.h` on Linux, and the enumerants the shim uses.

use std::ffi::{c_char, c_ulong, c_void};

/// `EGLBoolean`.
pub type EGLBoolean = u32;
/// `EGLint`.
pub type EGLint = i32;
/// `EGLenum`.
pub type EGLenum = u32;
/// `EGLDisplay`.
pub type EGLDisplay = *mut c_void;
/// `EGLConfig`.
pub type EGLConfig = *mut c_void;
/// `EGLSurface`.
pub type EGLSurface = *mut c_void;
/// `EGLContext`.
pub type EGLContext = *mut c_void;
/// `EGLClientBuffer`.
pub type EGLClientBuffer = *mut c_void;
/// `EGLNativeDisplayType` (an X11 `Display *`).
pub type EGLNativeDisplayType = *mut c_void;
/// `EGLNativeWindowType` (an X11 `Window`).
pub type EGLNativeWindowType = c_ulong;
/// `EGLNativePixmapType` (an X11 `Pixmap`).
pub type EGLNativePixmapType = c_ulong;
/// `EGLAttrib`.
pub type EGLAttrib = isize;
/// `__eglMustCastToProperFunctionPointerType`.
pub type EglProc = Option<unsafe extern "C" fn()>;

/// `GLenum`.
pub type GLenum = u32;
/// `GLboolean`.
pub type GLboolean = u8;
/// `GLbitfield`.
pub type GLbitfield = u32;
/// `GLint`.
pub type GLint = i32;
/// `GLuint`.
pub type GLuint = u32;
/// `GLint64` (`GL_EXT_disjoint_timer_query`).
pub type GLint64 = i64;
/// `GLuint64`.
pub type GLuint64 = u64;
/// `GLsizei`.
pub type GLsizei = i32;
/// `GLfloat`.
pub type GLfloat = f32;
/// `GLclampf`.
pub type GLclampf = f32;
/// `GLubyte`.
pub type GLubyte = u8;
/// `GLchar`.
pub type GLchar = c_char;
/// `GLintptr`.
pub type GLintptr = isize;
/// `GLsizeiptr`.
pub type GLsizeiptr = isize;

/// `EGL_FALSE`.
pub const EGL_FALSE: EGLBoolean = 0;
/// `EGL_TRUE`.
pub const EGL_TRUE: EGLBoolean = 1;
/// `EGL_SUCCESS`.
pub const EGL_SUCCESS: EGLint = 0x3000;
/// `EGL_NOT_INITIALIZED`.
pub const EGL_NOT_INITIALIZED: EGLint = 0x3001;
/// `EGL_BAD_ACCESS`.
pub const EGL_BAD_ACCESS: EGLint = 0x3002;
/// `EGL_BAD_ALLOC`.
pub const EGL_BAD_ALLOC: EGLint = 0x3003;
/// `EGL_BAD_ATTRIBUTE`.
pub const EGL_BAD_ATTRIBUTE: EGLint = 0x3004;
/// `EGL_BAD_CONFIG`.
pub const EGL_BAD_CONFIG: EGLint = 0x3005;
/// `EGL_BAD_CONTEXT`.
pub const EGL_BAD_CONTEXT: EGLint = 0x3006;
/// `EGL_BAD_DISPLAY`.
pub const EGL_BAD_DISPLAY: EGLint = 0x3008;
/// `EGL_BAD_MATCH`.
pub const EGL_BAD_MATCH: EGLint = 0x3009;
/// `EGL_BAD_NATIVE_PIXMAP`.
pub const EGL_BAD_NATIVE_PIXMAP: EGLint = 0x300A;
/// `EGL_BAD_NATIVE_WINDOW`.
pub const EGL_BAD_NATIVE_WINDOW: EGLint = 0x300B;
/// `EGL_BAD_PARAMETER`.
pub const EGL_BAD_PARAMETER: EGLint = 0x300C;
/// `EGL_BAD_SURFACE`.
pub const EGL_BAD_SURFACE: EGLint = 0x300D;
/// `EGL_CONTEXT_LOST`.
pub const EGL_CONTEXT_LOST: EGLint = 0x300E;
/// `EGL_CONFIG_ID`.
pub const EGL_CONFIG_ID: EGLint = 0x3028;
/// `EGL_NATIVE_VISUAL_ID`.
pub const EGL_NATIVE_VISUAL_ID: EGLint = 0x302E;
/// `EGL_NONE`.
pub const EGL_NONE: EGLint = 0x3038;
/// `EGL_VENDOR`.
pub const EGL_VENDOR: EGLint = 0x3053;
/// `EGL_VERSION`.
pub const EGL_VERSION: EGLint = 0x3054;
/// `EGL_EXTENSIONS`.
pub const EGL_EXTENSIONS: EGLint = 0x3055;
/// `EGL_CLIENT_APIS`.
pub const EGL_CLIENT_APIS: EGLint = 0x308D;
/// `EGL_RENDER_BUFFER`.
pub const EGL_RENDER_BUFFER: EGLint = 0x3086;
/// `EGL_BACK_BUFFER`.
pub const EGL_BACK_BUFFER: EGLint = 0x3084;
/// `EGL_SINGLE_BUFFER`.
pub const EGL_SINGLE_BUFFER: EGLint = 0x3085;
/// `EGL_CONTEXT_CLIENT_TYPE`.
pub const EGL_CONTEXT_CLIENT_TYPE: EGLint = 0x3097;
/// `EGL_CONTEXT_CLIENT_VERSION`.
pub const EGL_CONTEXT_CLIENT_VERSION: EGLint = 0x3098;
/// `EGL_CONTEXT_PRIORITY_LEVEL_IMG` (`EGL_IMG_context_priority`): answered by the daemon.
pub const EGL_CONTEXT_PRIORITY_LEVEL_IMG: EGLint = 0x3100;
/// `EGL_OPENGL_ES_API`.
pub const EGL_OPENGL_ES_API: EGLenum = 0x30A0;
/// `EGL_DRAW`.
pub const EGL_DRAW: EGLint = 0x3059;
/// `EGL_READ`.
pub const EGL_READ: EGLint = 0x305A;
/// `EGL_PLATFORM_X11_KHR` (and `EGL_PLATFORM_X11_EXT`).
pub const EGL_PLATFORM_X11_KHR: EGLenum = 0x31D5;

/// `GL_NO_ERROR`.
pub const GL_NO_ERROR: GLenum = 0;
/// `GL_INVALID_ENUM`.
pub const GL_INVALID_ENUM: GLenum = 0x0500;
/// `GL_UNIFORM_BUFFER` (ES 3.0).
pub const GL_UNIFORM_BUFFER: GLenum = 0x8A11;
/// `GL_COPY_READ_BUFFER` (ES 3.0).
pub const GL_COPY_READ_BUFFER: GLenum = 0x8F36;
/// `GL_COPY_WRITE_BUFFER` (ES 3.0).
pub const GL_COPY_WRITE_BUFFER: GLenum = 0x8F37;
/// `GL_TRANSFORM_FEEDBACK_BUFFER` (ES 3.0).
pub const GL_TRANSFORM_FEEDBACK_BUFFER: GLenum = 0x8C8E;
/// `GL_INVALID_VALUE`.
pub const GL_INVALID_VALUE: GLenum = 0x0501;
/// `GL_INVALID_OPERATION`.
pub const GL_INVALID_OPERATION: GLenum = 0x0502;
/// `GL_CONTEXT_LOST` (`KHR_robustness`): the daemon went away.
pub const GL_CONTEXT_LOST: GLenum = 0x0507;
/// `GL_ARRAY_BUFFER`.
pub const GL_ARRAY_BUFFER: GLenum = 0x8892;
/// `GL_ELEMENT_ARRAY_BUFFER`.
pub const GL_ELEMENT_ARRAY_BUFFER: GLenum = 0x8893;
/// `GL_UNPACK_ALIGNMENT`.
pub const GL_UNPACK_ALIGNMENT: GLenum = 0x0CF5;
/// `GL_PACK_ALIGNMENT`.
pub const GL_PACK_ALIGNMENT: GLenum = 0x0D05;
/// `GL_EXTENSIONS`.
pub const GL_EXTENSIONS: GLenum = 0x1F03;
/// `GL_WRITE_ONLY_OES`.
pub const GL_WRITE_ONLY_OES: GLenum = 0x88B9;
/// `GL_BUFFER_ACCESS_OES`.
pub const GL_BUFFER_ACCESS_OES: GLenum = 0x88BB;
/// `GL_BUFFER_MAPPED_OES`.
pub const GL_BUFFER_MAPPED_OES: GLenum = 0x88BC;
/// `GL_BUFFER_MAP_POINTER_OES`.
pub const GL_BUFFER_MAP_POINTER_OES: GLenum = 0x88BD;
/// `GL_VERTEX_ATTRIB_ARRAY_POINTER`.
pub const GL_VERTEX_ATTRIB_ARRAY_POINTER: GLenum = 0x8645;
/// `GL_UNSIGNED_BYTE`.
pub const GL_UNSIGNED_BYTE: GLenum = 0x1401;
/// `GL_UNSIGNED_SHORT`.
pub const GL_UNSIGNED_SHORT: GLenum = 0x1403;
/// `GL_FLOAT`.
pub const GL_FLOAT: GLenum = 0x1406;
/// `GL_UNSIGNED_INT`.
pub const GL_UNSIGNED_INT: GLenum = 0x1405;

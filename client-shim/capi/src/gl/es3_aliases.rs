//! OpenGL ES 3.0's core names for what ES 2.0 extensions already gave: each is the extension's
//! entry point (whose command the daemon runs) under its core name. As on Mesa, whose dispatch
//! gives an alias the function of the extension it names, they work in ES 2.0 contexts too
//! wherever the extension is offered (`versions` in `tests/client_calls.rs`).

use std::ffi::c_void;

use super::families::{delete, get_arrays, names};
use super::{draw_buffers, draws, mapping, program_binary, simple, texture3d, vao};
use crate::types::*;

/// Defines each core entry point as its extension's.
macro_rules! es3_aliases {
    ($( fn $core:ident => $module:ident :: $ext:ident ( $( $arg:ident : $ty:ty ),* ) $( -> $ret:ty )? ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($core), "` (ES 3.0): `", stringify!($ext), "`.")]
                fn $core( $( $arg : $ty ),* ) $( -> $ret )? {
                    // SAFETY: the extension's entry point has the same C signature, and gets the
                    // caller's arguments as they are.
                    unsafe { $module::$ext( $( $arg ),* ) }
                }
            )*
        }
    };
}

es3_aliases! {
    fn glGenVertexArrays => vao::glGenVertexArraysOES(n: GLsizei, arrays: *mut GLuint);
    fn glBindVertexArray => vao::glBindVertexArrayOES(array: GLuint);
    fn glDeleteVertexArrays => vao::glDeleteVertexArraysOES(n: GLsizei, arrays: *const GLuint);
    fn glIsVertexArray => vao::glIsVertexArrayOES(array: GLuint) -> GLboolean;
    fn glDrawArraysInstanced => draws::glDrawArraysInstancedEXT(mode: GLenum, first: GLint, count: GLsizei, instances: GLsizei);
    fn glDrawElementsInstanced => draws::glDrawElementsInstancedEXT(mode: GLenum, count: GLsizei, ty: GLenum, indices: *const c_void, instances: GLsizei);
    fn glMapBufferRange => mapping::glMapBufferRangeEXT(target: GLenum, offset: GLintptr, length: GLsizeiptr, access: GLbitfield) -> *mut c_void;
    fn glFlushMappedBufferRange => mapping::glFlushMappedBufferRangeEXT(target: GLenum, offset: GLintptr, length: GLsizeiptr);
    fn glUnmapBuffer => mapping::glUnmapBufferOES(target: GLenum) -> GLboolean;
    fn glGetBufferPointerv => mapping::glGetBufferPointervOES(target: GLenum, pname: GLenum, params: *mut *mut c_void);
    fn glDrawBuffers => draw_buffers::glDrawBuffersEXT(n: GLsizei, bufs: *const GLenum);
    fn glReadBuffer => simple::glReadBufferNV(mode: GLenum);
    fn glTexImage3D => texture3d::glTexImage3DOES(target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, ty: GLenum, pixels: *const c_void);
    fn glTexSubImage3D => texture3d::glTexSubImage3DOES(target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, ty: GLenum, pixels: *const c_void);
    fn glCopyTexSubImage3D => texture3d::glCopyTexSubImage3DOES(target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei);
    fn glCompressedTexImage3D => texture3d::glCompressedTexImage3DOES(target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, size: GLsizei, data: *const c_void);
    fn glCompressedTexSubImage3D => texture3d::glCompressedTexSubImage3DOES(target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, size: GLsizei, data: *const c_void);
    fn glGenQueries => names::glGenQueriesEXT(n: GLsizei, ids: *mut GLuint);
    fn glDeleteQueries => delete::glDeleteQueriesEXT(n: GLsizei, ids: *const GLuint);
    fn glIsQuery => simple::glIsQueryEXT(id: GLuint) -> GLboolean;
    fn glBeginQuery => simple::glBeginQueryEXT(target: GLenum, id: GLuint);
    fn glEndQuery => simple::glEndQueryEXT(target: GLenum);
    fn glGetQueryiv => get_arrays::glGetQueryivEXT(target: GLenum, pname: GLenum, params: *mut GLint);
    fn glGetQueryObjectuiv => get_arrays::glGetQueryObjectuivEXT(id: GLuint, pname: GLenum, params: *mut GLuint);
    fn glGetInteger64v => get_arrays::glGetInteger64vEXT(pname: GLenum, params: *mut GLint64);
    fn glProgramBinary => program_binary::glProgramBinaryOES(program: GLuint, format: GLenum, binary: *const c_void, length: GLint);
    fn glGetProgramBinary => program_binary::glGetProgramBinaryOES(program: GLuint, buf_size: GLsizei, length: *mut GLsizei, format: *mut GLenum, binary: *mut c_void);
    fn glProgramParameteri => simple::glProgramParameteriEXT(program: GLuint, pname: GLenum, value: GLint);
}

//! The GL entry points that carry only scalars and map one-to-one onto a protocol command of
//! the same name: one line each, generated.

use strata_protocol::Calls;

use super::{with_gl, Call, ShowArg};
use crate::entry::Fallback;
use crate::types::*;

/// Converts a C argument to the protocol's type.
trait Wire {
    type Out;
    fn wire(self) -> Self::Out;
}

macro_rules! wire_identity {
    ($($t:ty),*) => { $( impl Wire for $t { type Out = $t; fn wire(self) -> $t { self } } )* };
}
wire_identity!(u32, i32, f32);

impl Wire for GLboolean {
    type Out = bool;
    fn wire(self) -> bool {
        self != 0
    }
}

/// Converts a protocol result to the C return type.
trait ToC<C> {
    fn to_c(self) -> C;
}

impl ToC<()> for () {
    fn to_c(self) {}
}

impl ToC<GLenum> for GLenum {
    fn to_c(self) -> GLenum {
        self
    }
}

impl ToC<GLboolean> for bool {
    fn to_c(self) -> GLboolean {
        self as GLboolean
    }
}

/// Generates entry points that map one-to-one onto a `Calls` method of the same name.
macro_rules! simple_calls {
    ($( fn $name:ident ( $( $arg:ident : $ty:ty ),* ) $( -> $ret:ty )? ; )*) => {
        crate::entry::entry_points! {
            $(
                #[doc = concat!("`", stringify!($name), "`, forwarded to the daemon as it is.")]
                fn $name( $( $arg : $ty ),* ) $( -> $ret )? {
                    let args = || -> String { Vec::<String>::from([$( ShowArg::show(&$arg) ),*]).join(", ") };
                    with_gl(Call { name: stringify!($name), args: &args }, Fallback::fallback(), |gl| {
                        Ok(ToC::to_c(gl.conn.$name( $( Wire::wire($arg) ),* )?))
                    })
                }
            )*
        }
    };
}

simple_calls! {
    fn glActiveTexture(texture: GLenum);
    fn glAttachShader(program: GLuint, shader: GLuint);
    fn glBindFramebuffer(target: GLenum, framebuffer: GLuint);
    fn glBindRenderbuffer(target: GLenum, renderbuffer: GLuint);
    fn glBindTexture(target: GLenum, texture: GLuint);
    fn glBlendColor(red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat);
    fn glBlendEquation(mode: GLenum);
    fn glBlendEquationSeparate(mode_rgb: GLenum, mode_alpha: GLenum);
    fn glBlendFunc(sfactor: GLenum, dfactor: GLenum);
    fn glBlendFuncSeparate(src_rgb: GLenum, dst_rgb: GLenum, src_alpha: GLenum, dst_alpha: GLenum);
    fn glClear(mask: GLbitfield);
    fn glClearColor(red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat);
    fn glClearDepthf(depth: GLfloat);
    fn glClearStencil(s: GLint);
    fn glColorMask(red: GLboolean, green: GLboolean, blue: GLboolean, alpha: GLboolean);
    fn glCompileShader(shader: GLuint);
    fn glCopyTexImage2D(target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, width: GLsizei, height: GLsizei, border: GLint);
    fn glCopyTexSubImage2D(target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei);
    fn glCullFace(mode: GLenum);
    fn glDeleteProgram(program: GLuint);
    fn glDeleteShader(shader: GLuint);
    fn glDepthFunc(func: GLenum);
    fn glDepthMask(flag: GLboolean);
    fn glDepthRangef(near: GLfloat, far: GLfloat);
    fn glDetachShader(program: GLuint, shader: GLuint);
    fn glFlush();
    fn glFramebufferRenderbuffer(target: GLenum, attachment: GLenum, renderbuffertarget: GLenum, renderbuffer: GLuint);
    fn glFramebufferTexture2D(target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint);
    fn glFrontFace(mode: GLenum);
    fn glGenerateMipmap(target: GLenum);
    fn glHint(target: GLenum, mode: GLenum);
    fn glLineWidth(width: GLfloat);
    fn glLinkProgram(program: GLuint);
    fn glPolygonOffset(factor: GLfloat, units: GLfloat);
    fn glPolygonOffsetClampEXT(factor: GLfloat, units: GLfloat, clamp: GLfloat);
    fn glClipControlEXT(origin: GLenum, depth: GLenum);
    fn glMaxShaderCompilerThreadsKHR(count: GLuint);
    fn glReadBufferNV(mode: GLenum);
    fn glReleaseShaderCompiler();
    fn glRenderbufferStorage(target: GLenum, internalformat: GLenum, width: GLsizei, height: GLsizei);
    fn glSampleCoverage(value: GLfloat, invert: GLboolean);
    fn glScissor(x: GLint, y: GLint, width: GLsizei, height: GLsizei);
    fn glStencilFunc(func: GLenum, reference: GLint, mask: GLuint);
    fn glStencilFuncSeparate(face: GLenum, func: GLenum, reference: GLint, mask: GLuint);
    fn glStencilMask(mask: GLuint);
    fn glStencilMaskSeparate(face: GLenum, mask: GLuint);
    fn glStencilOp(fail: GLenum, zfail: GLenum, zpass: GLenum);
    fn glStencilOpSeparate(face: GLenum, fail: GLenum, zfail: GLenum, zpass: GLenum);
    fn glTexParameterf(target: GLenum, pname: GLenum, param: GLfloat);
    fn glTexParameteri(target: GLenum, pname: GLenum, param: GLint);
    fn glUniform1f(location: GLint, x: GLfloat);
    fn glUniform1i(location: GLint, x: GLint);
    fn glUniform2f(location: GLint, x: GLfloat, y: GLfloat);
    fn glUniform2i(location: GLint, x: GLint, y: GLint);
    fn glUniform3f(location: GLint, x: GLfloat, y: GLfloat, z: GLfloat);
    fn glUniform3i(location: GLint, x: GLint, y: GLint, z: GLint);
    fn glUniform4f(location: GLint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat);
    fn glUniform4i(location: GLint, x: GLint, y: GLint, z: GLint, w: GLint);
    fn glUniformBlockBinding(program: GLuint, index: GLuint, binding: GLuint);
    fn glVertexAttribI4i(index: GLuint, x: GLint, y: GLint, z: GLint, w: GLint);
    fn glVertexAttribI4ui(index: GLuint, x: GLuint, y: GLuint, z: GLuint, w: GLuint);
    fn glUniform1ui(location: GLint, x: GLuint);
    fn glUniform2ui(location: GLint, x: GLuint, y: GLuint);
    fn glUniform3ui(location: GLint, x: GLuint, y: GLuint, z: GLuint);
    fn glUniform4ui(location: GLint, x: GLuint, y: GLuint, z: GLuint, w: GLuint);
    fn glBeginConditionalRenderNV(id: GLuint, mode: GLenum);
    fn glEndConditionalRenderNV();
    fn glBeginQueryEXT(target: GLenum, id: GLuint);
    fn glEndQueryEXT(target: GLenum);
    fn glQueryCounterEXT(id: GLuint, target: GLenum);
    fn glBindProgramPipelineEXT(pipeline: GLuint);
    fn glUseProgramStagesEXT(pipeline: GLuint, stages: GLbitfield, program: GLuint);
    fn glActiveShaderProgramEXT(pipeline: GLuint, program: GLuint);
    fn glProgramParameteriEXT(program: GLuint, pname: GLenum, value: GLint);
    fn glValidateProgramPipelineEXT(pipeline: GLuint);
    fn glUseProgram(program: GLuint);
    fn glValidateProgram(program: GLuint);
    fn glVertexAttrib1f(index: GLuint, x: GLfloat);
    fn glVertexAttrib2f(index: GLuint, x: GLfloat, y: GLfloat);
    fn glVertexAttrib3f(index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat);
    fn glVertexAttrib4f(index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat);
    fn glCheckFramebufferStatus(target: GLenum) -> GLenum;
    fn glIsBuffer(name: GLuint) -> GLboolean;
    fn glIsEnabled(cap: GLenum) -> GLboolean;
    fn glIsFramebuffer(name: GLuint) -> GLboolean;
    fn glIsProgram(name: GLuint) -> GLboolean;
    fn glIsRenderbuffer(name: GLuint) -> GLboolean;
    fn glIsShader(name: GLuint) -> GLboolean;
    fn glIsTexture(name: GLuint) -> GLboolean;
    fn glIsQueryEXT(id: GLuint) -> GLboolean;
    fn glIsProgramPipelineEXT(pipeline: GLuint) -> GLboolean;
    fn glBindTransformFeedback(target: GLenum, id: GLuint);
    fn glBeginTransformFeedback(mode: GLenum);
    fn glEndTransformFeedback();
    fn glPauseTransformFeedback();
    fn glResumeTransformFeedback();
    fn glIsTransformFeedback(id: GLuint) -> GLboolean;
    fn glBindSampler(unit: GLuint, sampler: GLuint);
    fn glSamplerParameteri(sampler: GLuint, pname: GLenum, param: GLint);
    fn glSamplerParameterf(sampler: GLuint, pname: GLenum, param: GLfloat);
    fn glIsSampler(sampler: GLuint) -> GLboolean;
    fn glBlitFramebuffer(src_x0: GLint, src_y0: GLint, src_x1: GLint, src_y1: GLint, dst_x0: GLint, dst_y0: GLint, dst_x1: GLint, dst_y1: GLint, mask: GLbitfield, filter: GLenum);
    fn glRenderbufferStorageMultisample(target: GLenum, samples: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei);
    fn glFramebufferTextureLayer(target: GLenum, attachment: GLenum, texture: GLuint, level: GLint, layer: GLint);
    fn glTexStorage2D(target: GLenum, levels: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei);
    fn glTexStorage3D(target: GLenum, levels: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei);
}

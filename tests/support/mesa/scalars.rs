//! The reference's arms for calls that carry only scalars, one row each: each passes its
//! arguments to the Mesa entry point of the same name, whose C types the row gives.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

/// Generates one arm per row: `glName(arg: ProtocolType => CType, ...)`.
macro_rules! scalar_arms {
    ($( $gl:ident ( $( $a:ident : $t:ty => $c:ty ),* ); )*) => {
        #[allow(non_snake_case)]
        impl Arms<'_> {
            $( pub(super) fn $gl(&mut self, $( $a: &$t ),*) -> Result<(), ClientError> {
                call!(self, stringify!($gl), fn($($c),*) -> (), $( *$a ),*);
                Ok(())
            } )*
        }
    };
}

scalar_arms! {
    // framebuffers (the rest of the family in mesa/framebuffers.rs)
    glBindFramebuffer(target: GLenum => u32, framebuffer: GLuint => u32);
    glBindRenderbuffer(target: GLenum => u32, renderbuffer: GLuint => u32);
    glFramebufferRenderbuffer(target: GLenum => u32, attachment: GLenum => u32, renderbuffertarget: GLenum => u32, renderbuffer: GLuint => u32);
    glFramebufferTexture2D(target: GLenum => u32, attachment: GLenum => u32, textarget: GLenum => u32, texture: GLuint => u32, level: GLint => i32);
    glRenderbufferStorage(target: GLenum => u32, internalformat: GLenum => u32, width: GLsizei => i32, height: GLsizei => i32);
    // programs (the rest of the family in mesa/programs.rs)
    glReleaseShaderCompiler();
    glUniform1f(location: GLint => i32, x: GLfloat => f32);
    glUniform1i(location: GLint => i32, x: GLint => i32);
    glUniform2f(location: GLint => i32, x: GLfloat => f32, y: GLfloat => f32);
    glUniform2i(location: GLint => i32, x: GLint => i32, y: GLint => i32);
    glUniform3f(location: GLint => i32, x: GLfloat => f32, y: GLfloat => f32, z: GLfloat => f32);
    glUniform3i(location: GLint => i32, x: GLint => i32, y: GLint => i32, z: GLint => i32);
    glUniform4f(location: GLint => i32, x: GLfloat => f32, y: GLfloat => f32, z: GLfloat => f32, w: GLfloat => f32);
    glUniform4i(location: GLint => i32, x: GLint => i32, y: GLint => i32, z: GLint => i32, w: GLint => i32);
    glUniform1ui(location: GLint => i32, x: GLuint => u32);
    glVertexAttribDivisor(index: GLuint => u32, divisor: GLuint => u32);
    glVertexAttribI4i(index: GLuint => u32, x: GLint => i32, y: GLint => i32, z: GLint => i32, w: GLint => i32);
    glClearBufferfi(buffer: GLenum => u32, drawbuffer: GLint => i32, depth: GLfloat => f32, stencil: GLint => i32);
    glVertexAttribI4ui(index: GLuint => u32, x: GLuint => u32, y: GLuint => u32, z: GLuint => u32, w: GLuint => u32);
    glUniform2ui(location: GLint => i32, x: GLuint => u32, y: GLuint => u32);
    glUniform3ui(location: GLint => i32, x: GLuint => u32, y: GLuint => u32, z: GLuint => u32);
    glUniform4ui(location: GLint => i32, x: GLuint => u32, y: GLuint => u32, z: GLuint => u32, w: GLuint => u32);
    glRenderbufferStorageMultisample(target: GLenum => u32, samples: GLsizei => i32, internalformat: GLenum => u32, width: GLsizei => i32, height: GLsizei => i32);
    glFramebufferTextureLayer(target: GLenum => u32, attachment: GLenum => u32, texture: GLuint => u32, level: GLint => i32, layer: GLint => i32);
    glBlitFramebuffer(src_x0: GLint => i32, src_y0: GLint => i32, src_x1: GLint => i32, src_y1: GLint => i32, dst_x0: GLint => i32, dst_y0: GLint => i32, dst_x1: GLint => i32, dst_y1: GLint => i32, mask: GLbitfield => u32, filter: GLenum => u32);
    glTexStorage2D(target: GLenum => u32, levels: GLsizei => i32, internalformat: GLenum => u32, width: GLsizei => i32, height: GLsizei => i32);
    glTexStorage3D(target: GLenum => u32, levels: GLsizei => i32, internalformat: GLenum => u32, width: GLsizei => i32, height: GLsizei => i32, depth: GLsizei => i32);
    // state (the rest of the family in mesa/state.rs)
    glBlendColor(red: GLfloat => f32, green: GLfloat => f32, blue: GLfloat => f32, alpha: GLfloat => f32);
    glBlendEquation(mode: GLenum => u32);
    glBlendEquationSeparate(mode_rgb: GLenum => u32, mode_alpha: GLenum => u32);
    glBlendFunc(sfactor: GLenum => u32, dfactor: GLenum => u32);
    glBlendFuncSeparate(src_rgb: GLenum => u32, dst_rgb: GLenum => u32, src_alpha: GLenum => u32, dst_alpha: GLenum => u32);
    glClear(mask: GLbitfield => u32);
    glClearColor(red: GLfloat => f32, green: GLfloat => f32, blue: GLfloat => f32, alpha: GLfloat => f32);
    glClearDepthf(depth: GLfloat => f32);
    glClearStencil(s: GLint => i32);
    glCullFace(mode: GLenum => u32);
    glDepthFunc(func: GLenum => u32);
    glDepthRangef(near: GLfloat => f32, far: GLfloat => f32);
    glDisable(cap: GLenum => u32);
    glEnable(cap: GLenum => u32);
    glFlush();
    glFrontFace(mode: GLenum => u32);
    glHint(target: GLenum => u32, mode: GLenum => u32);
    glLineWidth(width: GLfloat => f32);
    glPolygonOffset(factor: GLfloat => f32, units: GLfloat => f32);
    glPolygonOffsetClampEXT(factor: GLfloat => f32, units: GLfloat => f32, clamp: GLfloat => f32);
    glClipControlEXT(origin: GLenum => u32, depth: GLenum => u32);
    glMaxShaderCompilerThreadsKHR(count: GLuint => u32);
    glReadBufferNV(mode: GLenum => u32);
    glScissor(x: GLint => i32, y: GLint => i32, width: GLsizei => i32, height: GLsizei => i32);
    glStencilFunc(func: GLenum => u32, reference: GLint => i32, mask: GLuint => u32);
    glStencilFuncSeparate(face: GLenum => u32, func: GLenum => u32, reference: GLint => i32, mask: GLuint => u32);
    glStencilMask(mask: GLuint => u32);
    glStencilMaskSeparate(face: GLenum => u32, mask: GLuint => u32);
    glStencilOp(fail: GLenum => u32, zfail: GLenum => u32, zpass: GLenum => u32);
    glStencilOpSeparate(face: GLenum => u32, fail: GLenum => u32, zfail: GLenum => u32, zpass: GLenum => u32);
    glViewport(x: GLint => i32, y: GLint => i32, width: GLsizei => i32, height: GLsizei => i32);
    glFinish();
    // textures (the rest of the family in mesa/textures.rs)
    glActiveTexture(texture: GLenum => u32);
    glBindTexture(target: GLenum => u32, texture: GLuint => u32);
    glCopyTexImage2D(target: GLenum => u32, level: GLint => i32, internalformat: GLenum => u32, x: GLint => i32, y: GLint => i32, width: GLsizei => i32, height: GLsizei => i32, border: GLint => i32);
    glCopyTexSubImage2D(target: GLenum => u32, level: GLint => i32, xoffset: GLint => i32, yoffset: GLint => i32, x: GLint => i32, y: GLint => i32, width: GLsizei => i32, height: GLsizei => i32);
    glGenerateMipmap(target: GLenum => u32);
    glPixelStorei(pname: GLenum => u32, param: GLint => i32);
    glTexParameterf(target: GLenum => u32, pname: GLenum => u32, param: GLfloat => f32);
    glTexParameteri(target: GLenum => u32, pname: GLenum => u32, param: GLint => i32);
    // vertices (the rest of the family in mesa/vertices.rs)
    glBindBuffer(target: GLenum => u32, buffer: GLuint => u32);
    glDisableVertexAttribArray(index: GLuint => u32);
    glDrawArrays(mode: GLenum => u32, first: GLint => i32, count: GLsizei => i32);
    glEnableVertexAttribArray(index: GLuint => u32);
    glVertexAttrib1f(index: GLuint => u32, x: GLfloat => f32);
    glVertexAttrib2f(index: GLuint => u32, x: GLfloat => f32, y: GLfloat => f32);
    glVertexAttrib3f(index: GLuint => u32, x: GLfloat => f32, y: GLfloat => f32, z: GLfloat => f32);
    glVertexAttrib4f(index: GLuint => u32, x: GLfloat => f32, y: GLfloat => f32, z: GLfloat => f32, w: GLfloat => f32);
}

//! The command set, defined once: every EGL 1.4 call an application makes, every GLES 2.0
//! entry point, and Strata's own calls. Wire order is table order; append, never reorder.
//!
//! Pointer arguments become owned data or offsets: arrays travel as [`Slice`], bulk data as
//! [`Blob`], strings as [`Text`]. Object names are allocated by the client, so `glGen*`
//! and `glCreate*` carry the chosen names and need no reply.

use serde::{Deserialize, Serialize};

use crate::command_set::command_set;
use crate::wire::*;

/// Result of an EGL call: the value, or the EGL error code (`EGL_BAD_*`).
pub type EglResult<T> = Result<T, EGLint>;

pub use crate::replies::*;

command_set! {
    async {
        glActiveTexture [Context] => ActiveTexture { texture: GLenum };
        glAttachShader [Context] => AttachShader { program: GLuint, shader: GLuint };
        glBindAttribLocation [Context] => BindAttribLocation { program: GLuint, index: GLuint, name: Text<'a> };
        glBindBuffer [Context] => BindBuffer { target: GLenum, buffer: GLuint };
        glBindFramebuffer [Context] => BindFramebuffer { target: GLenum, framebuffer: GLuint };
        glBindRenderbuffer [Context] => BindRenderbuffer { target: GLenum, renderbuffer: GLuint };
        glBindTexture [Context] => BindTexture { target: GLenum, texture: GLuint };
        glBlendColor [Context] => BlendColor { red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat };
        glBlendEquation [Context] => BlendEquation { mode: GLenum };
        glBlendEquationSeparate [Context] => BlendEquationSeparate { mode_rgb: GLenum, mode_alpha: GLenum };
        glBlendFunc [Context] => BlendFunc { sfactor: GLenum, dfactor: GLenum };
        glBlendFuncSeparate [Context] => BlendFuncSeparate { src_rgb: GLenum, dst_rgb: GLenum, src_alpha: GLenum, dst_alpha: GLenum };
        /// `data` is `None` when the application passed NULL (allocate only).
        glBufferData [Context, Flush] => BufferData { target: GLenum, size: i64, data: Option<Blob<'a>>, usage: GLenum };
        glBufferSubData [Context, Flush] => BufferSubData { target: GLenum, offset: i64, data: Blob<'a> };
        glClear [Context] => Clear { mask: GLbitfield };
        glClearColor [Context] => ClearColor { red: GLfloat, green: GLfloat, blue: GLfloat, alpha: GLfloat };
        glClearDepthf [Context] => ClearDepthf { depth: GLfloat };
        glClearStencil [Context] => ClearStencil { s: GLint };
        glColorMask [Context] => ColorMask { red: bool, green: bool, blue: bool, alpha: bool };
        glCompileShader [Context] => CompileShader { shader: GLuint };
        glCompressedTexImage2D [Context, Flush] => CompressedTexImage2D { target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, border: GLint, data: Blob<'a> };
        glCompressedTexSubImage2D [Context, Flush] => CompressedTexSubImage2D { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, data: Blob<'a> };
        glCopyTexImage2D [Context, Flush] => CopyTexImage2D { target: GLenum, level: GLint, internalformat: GLenum, x: GLint, y: GLint, width: GLsizei, height: GLsizei, border: GLint };
        glCopyTexSubImage2D [Context, Flush] => CopyTexSubImage2D { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei };
        /// `name` is the program name the client allocated.
        glCreateProgram [Context] => CreateProgram { name: GLuint };
        /// `name` is the shader name the client allocated.
        glCreateShader [Context] => CreateShader { shader_type: GLenum, name: GLuint };
        glCullFace [Context] => CullFace { mode: GLenum };
        glDeleteBuffers [Context] => DeleteBuffers { names: Slice<'a, GLuint> };
        glDeleteFramebuffers [Context] => DeleteFramebuffers { names: Slice<'a, GLuint> };
        glDeleteProgram [Context] => DeleteProgram { program: GLuint };
        glDeleteRenderbuffers [Context] => DeleteRenderbuffers { names: Slice<'a, GLuint> };
        glDeleteShader [Context] => DeleteShader { shader: GLuint };
        glDeleteTextures [Context] => DeleteTextures { names: Slice<'a, GLuint> };
        glDepthFunc [Context] => DepthFunc { func: GLenum };
        glDepthMask [Context] => DepthMask { flag: bool };
        glDepthRangef [Context] => DepthRangef { near: GLfloat, far: GLfloat };
        glDetachShader [Context] => DetachShader { program: GLuint, shader: GLuint };
        glDisable [Context] => Disable { cap: GLenum };
        glDisableVertexAttribArray [Context] => DisableVertexAttribArray { index: GLuint };
        glDrawArrays [Context] => DrawArrays { mode: GLenum, first: GLint, count: GLsizei };
        /// `offset` is the byte offset into the bound `GL_ELEMENT_ARRAY_BUFFER`.
        glDrawElements [Context] => DrawElements { mode: GLenum, count: GLsizei, index_type: GLenum, offset: u64 };
        glEnable [Context] => Enable { cap: GLenum };
        glEnableVertexAttribArray [Context] => EnableVertexAttribArray { index: GLuint };
        glFlush [Context] => Flush {};
        glFramebufferRenderbuffer [Context] => FramebufferRenderbuffer { target: GLenum, attachment: GLenum, renderbuffertarget: GLenum, renderbuffer: GLuint };
        glFramebufferTexture2D [Context] => FramebufferTexture2D { target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint };
        glFrontFace [Context] => FrontFace { mode: GLenum };
        glGenBuffers [Context] => GenBuffers { names: Slice<'a, GLuint> };
        glGenerateMipmap [Context, Flush] => GenerateMipmap { target: GLenum };
        glGenFramebuffers [Context] => GenFramebuffers { names: Slice<'a, GLuint> };
        glGenRenderbuffers [Context] => GenRenderbuffers { names: Slice<'a, GLuint> };
        glGenTextures [Context] => GenTextures { names: Slice<'a, GLuint> };
        glHint [Context] => Hint { target: GLenum, mode: GLenum };
        glLineWidth [Context] => LineWidth { width: GLfloat };
        glLinkProgram [Context] => LinkProgram { program: GLuint };
        glPixelStorei [Context] => PixelStorei { pname: GLenum, param: GLint };
        glPolygonOffset [Context] => PolygonOffset { factor: GLfloat, units: GLfloat };
        glReleaseShaderCompiler [Context] => ReleaseShaderCompiler {};
        glRenderbufferStorage [Context] => RenderbufferStorage { target: GLenum, internalformat: GLenum, width: GLsizei, height: GLsizei };
        glSampleCoverage [Context] => SampleCoverage { value: GLfloat, invert: bool };
        glScissor [Context] => Scissor { x: GLint, y: GLint, width: GLsizei, height: GLsizei };
        glShaderBinary [Context] => ShaderBinary { shaders: Slice<'a, GLuint>, binary_format: GLenum, binary: Blob<'a> };
        /// The client joins the application's string array into one source.
        glShaderSource [Context] => ShaderSource { shader: GLuint, source: Text<'a> };
        glStencilFunc [Context] => StencilFunc { func: GLenum, reference: GLint, mask: GLuint };
        glStencilFuncSeparate [Context] => StencilFuncSeparate { face: GLenum, func: GLenum, reference: GLint, mask: GLuint };
        glStencilMask [Context] => StencilMask { mask: GLuint };
        glStencilMaskSeparate [Context] => StencilMaskSeparate { face: GLenum, mask: GLuint };
        glStencilOp [Context] => StencilOp { fail: GLenum, zfail: GLenum, zpass: GLenum };
        glStencilOpSeparate [Context] => StencilOpSeparate { face: GLenum, fail: GLenum, zfail: GLenum, zpass: GLenum };
        /// `pixels` is `None` when the application passed NULL (allocate only).
        glTexImage2D [Context, Flush] => TexImage2D { target: GLenum, level: GLint, internalformat: GLint, width: GLsizei, height: GLsizei, border: GLint, format: GLenum, pixel_type: GLenum, pixels: Option<Blob<'a>> };
        glTexParameterf [Context] => TexParameterf { target: GLenum, pname: GLenum, param: GLfloat };
        glTexParameterfv [Context] => TexParameterfv { target: GLenum, pname: GLenum, params: Slice<'a, GLfloat> };
        glTexParameteri [Context] => TexParameteri { target: GLenum, pname: GLenum, param: GLint };
        glTexParameteriv [Context] => TexParameteriv { target: GLenum, pname: GLenum, params: Slice<'a, GLint> };
        glTexSubImage2D [Context, Flush] => TexSubImage2D { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, width: GLsizei, height: GLsizei, format: GLenum, pixel_type: GLenum, pixels: Blob<'a> };
        glUniform1f [Context] => Uniform1f { location: GLint, x: GLfloat };
        glUniform1fv [Context] => Uniform1fv { location: GLint, values: Slice<'a, GLfloat> };
        glUniform1i [Context] => Uniform1i { location: GLint, x: GLint };
        glUniform1iv [Context] => Uniform1iv { location: GLint, values: Slice<'a, GLint> };
        glUniform2f [Context] => Uniform2f { location: GLint, x: GLfloat, y: GLfloat };
        glUniform2fv [Context] => Uniform2fv { location: GLint, values: Slice<'a, GLfloat> };
        glUniform2i [Context] => Uniform2i { location: GLint, x: GLint, y: GLint };
        glUniform2iv [Context] => Uniform2iv { location: GLint, values: Slice<'a, GLint> };
        glUniform3f [Context] => Uniform3f { location: GLint, x: GLfloat, y: GLfloat, z: GLfloat };
        glUniform3fv [Context] => Uniform3fv { location: GLint, values: Slice<'a, GLfloat> };
        glUniform3i [Context] => Uniform3i { location: GLint, x: GLint, y: GLint, z: GLint };
        glUniform3iv [Context] => Uniform3iv { location: GLint, values: Slice<'a, GLint> };
        glUniform4f [Context] => Uniform4f { location: GLint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat };
        glUniform4fv [Context] => Uniform4fv { location: GLint, values: Slice<'a, GLfloat> };
        glUniform4i [Context] => Uniform4i { location: GLint, x: GLint, y: GLint, z: GLint, w: GLint };
        glUniform4iv [Context] => Uniform4iv { location: GLint, values: Slice<'a, GLint> };
        glUniformMatrix2fv [Context] => UniformMatrix2fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix3fv [Context] => UniformMatrix3fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix4fv [Context] => UniformMatrix4fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUseProgram [Context] => UseProgram { program: GLuint };
        glValidateProgram [Context] => ValidateProgram { program: GLuint };
        glVertexAttrib1f [Context] => VertexAttrib1f { index: GLuint, x: GLfloat };
        glVertexAttrib1fv [Context] => VertexAttrib1fv { index: GLuint, values: Slice<'a, GLfloat> };
        glVertexAttrib2f [Context] => VertexAttrib2f { index: GLuint, x: GLfloat, y: GLfloat };
        glVertexAttrib2fv [Context] => VertexAttrib2fv { index: GLuint, values: Slice<'a, GLfloat> };
        glVertexAttrib3f [Context] => VertexAttrib3f { index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat };
        glVertexAttrib3fv [Context] => VertexAttrib3fv { index: GLuint, values: Slice<'a, GLfloat> };
        glVertexAttrib4f [Context] => VertexAttrib4f { index: GLuint, x: GLfloat, y: GLfloat, z: GLfloat, w: GLfloat };
        glVertexAttrib4fv [Context] => VertexAttrib4fv { index: GLuint, values: Slice<'a, GLfloat> };
        /// `offset` is the byte offset into the bound `GL_ARRAY_BUFFER`.
        glVertexAttribPointer [Context] => VertexAttribPointer { index: GLuint, size: GLint, attrib_type: GLenum, normalized: bool, stride: GLsizei, offset: u64 };
        glViewport [Context] => Viewport { x: GLint, y: GLint, width: GLsizei, height: GLsizei };
        /// A client-side vertex array, copied at draw time: the bytes of attribute `index`
        /// from the array's start through the last vertex the next draw reads.
        strataVertexAttribData [Context] => VertexAttribData { index: GLuint, data: Blob<'a> };
        /// `glDrawElements` with a client-side index array.
        strataDrawElementsData [Context] => DrawElementsData { mode: GLenum, count: GLsizei, index_type: GLenum, indices: Blob<'a> };
        glGenVertexArraysOES [Context] => GenVertexArraysOES { names: Slice<'a, GLuint> };
        glBindVertexArrayOES [Context] => BindVertexArrayOES { array: GLuint };
        glDeleteVertexArraysOES [Context] => DeleteVertexArraysOES { names: Slice<'a, GLuint> };
        /// `ids` holds the first `count` ids (none when `count` is not positive).
        glDebugMessageControlKHR [Context] => DebugMessageControlKHR { source: GLenum, ty: GLenum, severity: GLenum, count: GLsizei, ids: Slice<'a, GLuint>, enabled: bool };
        /// `text` holds the message: `length` bytes, or with a negative `length` the bytes before
        /// the NUL, at most `MAX_DEBUG_MESSAGE_LENGTH` of either (enough to refuse a longer one).
        glDebugMessageInsertKHR [Context] => DebugMessageInsertKHR { source: GLenum, ty: GLenum, id: GLuint, severity: GLenum, length: GLsizei, text: Blob<'a> };
        /// `text` as for `glDebugMessageInsertKHR`.
        glPushDebugGroupKHR [Context] => PushDebugGroupKHR { source: GLenum, id: GLuint, length: GLsizei, text: Blob<'a> };
        glPopDebugGroupKHR [Context] => PopDebugGroupKHR {};
        /// `label` is `None` for NULL (remove the label); else as `text` of `glDebugMessageInsertKHR`
        /// with `MAX_LABEL_LENGTH`.
        glObjectLabelKHR [Context] => ObjectLabelKHR { identifier: GLenum, name: GLuint, length: GLsizei, label: Option<Blob<'a>> };
        /// `ptr` is the application's sync object pointer.
        glObjectPtrLabelKHR [Context] => ObjectPtrLabelKHR { ptr: u64, length: GLsizei, label: Option<Blob<'a>> };
        /// Whether the application has a `GL_KHR_debug` callback: while it has, new messages
        /// wait for `strataDebugMessages` instead of entering the message log.
        strataDebugCallback [Context] => DebugCallback { installed: bool };
        /// `GL_EXT_discard_framebuffer`: the listed attachments' contents may be discarded.
        glDiscardFramebufferEXT [Context] => DiscardFramebufferEXT { target: GLenum, attachments: Slice<'a, GLenum> };
        /// A client-side `GL_FLOAT` array that the client converted for the wire (`stratad
        /// serve --vertex-wire`): components of `attrib_type` (`GL_HALF_FLOAT_OES` or `GL_FIXED`;
        /// `GL_FLOAT` is accepted too), tightly packed, which the next draw reads in place of the
        /// pointer's type and stride. Queries still answer what the application set.
        strataVertexAttribDataPacked [Context] => VertexAttribDataPacked { index: GLuint, attrib_type: GLenum, data: Blob<'a> };
        /// `GL_EXT_polygon_offset_clamp`: polygon offset whose size `clamp` bounds (a positive
        /// clamp is the largest offset, a negative one the smallest; 0 bounds nothing).
        glPolygonOffsetClampEXT [Context] => PolygonOffsetClampEXT { factor: GLfloat, units: GLfloat, clamp: GLfloat };
        /// `GL_KHR_parallel_shader_compile`: the compiler threads the application would like
        /// (a hint; `0xFFFFFFFF`: the implementation's choice).
        glMaxShaderCompilerThreadsKHR [Context] => MaxShaderCompilerThreadsKHR { count: GLuint };
        /// `GL_OES_draw_elements_base_vertex`: `glDrawElements` with `base_vertex` added to
        /// every index.
        glDrawElementsBaseVertexOES [Context] => DrawElementsBaseVertexOES { mode: GLenum, count: GLsizei, index_type: GLenum, offset: u64, base_vertex: GLint };
        /// `glDrawElementsBaseVertexOES` with a client-side index array.
        strataDrawElementsBaseVertexData [Context] => DrawElementsBaseVertexData { mode: GLenum, count: GLsizei, index_type: GLenum, indices: Blob<'a>, base_vertex: GLint };
        /// `GL_EXT_multi_draw_arrays`: `glDrawArrays` for each of the first `drawcount`
        /// (`first`, `count`) pairs.
        glMultiDrawArraysEXT [Context] => MultiDrawArraysEXT { mode: GLenum, first: Slice<'a, GLint>, count: Slice<'a, GLsizei>, drawcount: GLsizei };
        /// `GL_EXT_multi_draw_arrays`: `glDrawElements` from the element buffer for each of the
        /// first `drawcount` (`count`, byte offset) pairs.
        glMultiDrawElementsEXT [Context] => MultiDrawElementsEXT { mode: GLenum, count: Slice<'a, GLsizei>, index_type: GLenum, offsets: Slice<'a, u64>, drawcount: GLsizei };
        /// `GL_OES_draw_elements_base_vertex` with `GL_EXT_multi_draw_arrays`:
        /// `glMultiDrawElementsEXT` with a base vertex for each draw.
        glMultiDrawElementsBaseVertexEXT [Context] => MultiDrawElementsBaseVertexEXT { mode: GLenum, count: Slice<'a, GLsizei>, index_type: GLenum, offsets: Slice<'a, u64>, drawcount: GLsizei, base_vertex: Slice<'a, GLint> };
        /// `GL_EXT_draw_instanced`: `glDrawArrays` `primcount` times, each instance's
        /// `gl_InstanceIDEXT` its number.
        glDrawArraysInstancedEXT [Context] => DrawArraysInstancedEXT { mode: GLenum, first: GLint, count: GLsizei, primcount: GLsizei };
        /// `GL_EXT_draw_instanced`: `glDrawElements` `primcount` times.
        glDrawElementsInstancedEXT [Context] => DrawElementsInstancedEXT { mode: GLenum, count: GLsizei, index_type: GLenum, offset: u64, primcount: GLsizei };
        /// `glDrawElementsInstancedEXT` with a client-side index array.
        strataDrawElementsInstancedData [Context] => DrawElementsInstancedData { mode: GLenum, count: GLsizei, index_type: GLenum, indices: Blob<'a>, primcount: GLsizei };
        /// `GL_EXT_debug_label`: labels an object of `object_type` (a length of 0: the label
        /// is NUL-terminated, and sent whole).
        glLabelObjectEXT [Context] => LabelObjectEXT { object_type: GLenum, object: GLuint, length: GLsizei, label: Option<Blob<'a>> };
        /// `GL_NV_read_buffer`: the colour buffer reads use (`GL_BACK`, `GL_COLOR_ATTACHMENT0`
        /// or `GL_NONE`).
        glReadBufferNV [Context] => ReadBufferNV { mode: GLenum };
        /// `GL_OES_mapbuffer` / `GL_EXT_map_buffer_range`: ends the mapping of the buffer bound
        /// to `target`, first writing `data` at byte `offset` (what the application changed).
        glUnmapBufferOES [Context, Flush] => UnmapBufferOES { target: GLenum, offset: i64, data: Blob<'a> };
        /// `GL_EXT_map_buffer_range`: makes the `length` bytes at `offset` within the mapping
        /// (`data`, sent whole) the buffer's contents.
        glFlushMappedBufferRangeEXT [Context, Flush] => FlushMappedBufferRangeEXT { target: GLenum, offset: i64, length: i64, data: Blob<'a> };
        /// `GL_EXT_occlusion_query_boolean`: query names (allocated by the client).
        glGenQueriesEXT [Context] => GenQueriesEXT { names: Slice<'a, GLuint> };
        glDeleteQueriesEXT [Context] => DeleteQueriesEXT { names: Slice<'a, GLuint> };
        /// Starts occlusion query `id`: the draws until `glEndQueryEXT` count for it.
        glBeginQueryEXT [Context] => BeginQueryEXT { target: GLenum, id: GLuint };
        glEndQueryEXT [Context] => EndQueryEXT { target: GLenum };
        /// `GL_NV_conditional_render`: draws and clears until `glEndConditionalRenderNV` are
        /// done only if occlusion query `id` passed a sample.
        glBeginConditionalRenderNV [Context] => BeginConditionalRenderNV { id: GLuint, mode: GLenum };
        glEndConditionalRenderNV [Context] => EndConditionalRenderNV {};
        /// `GL_EXT_draw_buffers` / `GL_NV_draw_buffers`: the colour buffer each fragment output
        /// writes (`GL_NONE`, `GL_BACK` or `GL_COLOR_ATTACHMENTi`); at most `MAX_DRAW_BUFFERS`.
        glDrawBuffersEXT [Context] => DrawBuffersEXT { buffers: Slice<'a, GLenum> };
        /// `GL_OES_get_program_binary`: links `program` from a binary `glGetProgramBinaryOES`
        /// answered; `binary` holds the first `length` bytes (none for a negative `length`).
        glProgramBinaryOES [Context] => ProgramBinaryOES { program: GLuint, binary_format: GLenum, length: GLsizei, binary: Blob<'a> };
        /// `GL_EXT_clip_control`: the window origin (`GL_LOWER_LEFT_EXT`, `GL_UPPER_LEFT_EXT`)
        /// and the clip depth range (`GL_NEGATIVE_ONE_TO_ONE_EXT`, `GL_ZERO_TO_ONE_EXT`).
        glClipControlEXT [Context] => ClipControlEXT { origin: GLenum, depth: GLenum };
        /// `GL_EXT_disjoint_timer_query`: query `id` records the device's time once the
        /// commands before it have completed.
        glQueryCounterEXT [Context] => QueryCounterEXT { id: GLuint, target: GLenum };
        /// `GL_OES_EGL_image` (and `GL_OES_EGL_image_external`): the bound texture's image
        /// becomes the EGLImage's.
        glEGLImageTargetTexture2DOES [Context, Flush] => EGLImageTargetTexture2DOES { target: GLenum, image: EglHandle };
        /// `GL_OES_EGL_image`: the bound renderbuffer's image becomes the EGLImage's.
        glEGLImageTargetRenderbufferStorageOES [Context, Flush] => EGLImageTargetRenderbufferStorageOES { target: GLenum, image: EglHandle };
        /// `GL_EXT_separate_shader_objects`: program pipeline names (allocated by the client).
        glGenProgramPipelinesEXT [Context] => GenProgramPipelinesEXT { names: Slice<'a, GLuint> };
        glDeleteProgramPipelinesEXT [Context] => DeleteProgramPipelinesEXT { names: Slice<'a, GLuint> };
        /// The pipeline whose stages draw while no program is in use (0: none).
        glBindProgramPipelineEXT [Context] => BindProgramPipelineEXT { pipeline: GLuint };
        /// `program`'s executables serve `pipeline`'s `stages` (`GL_VERTEX_SHADER_BIT_EXT`,
        /// `GL_FRAGMENT_SHADER_BIT_EXT`); program 0 empties them.
        glUseProgramStagesEXT [Context] => UseProgramStagesEXT { pipeline: GLuint, stages: GLbitfield, program: GLuint };
        /// The program `glUniform*` writes while `pipeline` is bound and no program is in use.
        glActiveShaderProgramEXT [Context] => ActiveShaderProgramEXT { pipeline: GLuint, program: GLuint };
        /// `GL_PROGRAM_SEPARABLE_EXT`: whether the next link makes a program pipelines can use.
        glProgramParameteriEXT [Context] => ProgramParameteriEXT { program: GLuint, pname: GLenum, value: GLint };
        /// Checks that `pipeline`'s stages can draw together (`GL_VALIDATE_STATUS`, info log).
        glValidateProgramPipelineEXT [Context] => ValidateProgramPipelineEXT { pipeline: GLuint };
        /// Compiles `source` as one stage (`shader_type`) and links it alone into the separable
        /// program `name` (allocated by the client); a failed compile is the program's link log.
        glCreateShaderProgramvEXT [Context] => CreateShaderProgramvEXT { shader_type: GLenum, name: GLuint, source: Text<'a> };
        /// `glUniform*` on `program`'s uniforms, whether or not it is in use (the library sends
        /// the scalar forms as one-element arrays).
        glProgramUniform1fvEXT [Context] => ProgramUniform1fvEXT { program: GLuint, location: GLint, values: Slice<'a, GLfloat> };
        glProgramUniform2fvEXT [Context] => ProgramUniform2fvEXT { program: GLuint, location: GLint, values: Slice<'a, GLfloat> };
        glProgramUniform3fvEXT [Context] => ProgramUniform3fvEXT { program: GLuint, location: GLint, values: Slice<'a, GLfloat> };
        glProgramUniform4fvEXT [Context] => ProgramUniform4fvEXT { program: GLuint, location: GLint, values: Slice<'a, GLfloat> };
        glProgramUniform1ivEXT [Context] => ProgramUniform1ivEXT { program: GLuint, location: GLint, values: Slice<'a, GLint> };
        glProgramUniform2ivEXT [Context] => ProgramUniform2ivEXT { program: GLuint, location: GLint, values: Slice<'a, GLint> };
        glProgramUniform3ivEXT [Context] => ProgramUniform3ivEXT { program: GLuint, location: GLint, values: Slice<'a, GLint> };
        glProgramUniform4ivEXT [Context] => ProgramUniform4ivEXT { program: GLuint, location: GLint, values: Slice<'a, GLint> };
        glProgramUniformMatrix2fvEXT [Context] => ProgramUniformMatrix2fvEXT { program: GLuint, location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glProgramUniformMatrix3fvEXT [Context] => ProgramUniformMatrix3fvEXT { program: GLuint, location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glProgramUniformMatrix4fvEXT [Context] => ProgramUniformMatrix4fvEXT { program: GLuint, location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        /// `GL_OES_texture_3D`: a 3D image, its slices one after another (`None`: no data).
        glTexImage3DOES [Context, Flush] => TexImage3DOES { target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, format: GLenum, pixel_type: GLenum, pixels: Option<Blob<'a>> };
        /// A box of a 3D image.
        glTexSubImage3DOES [Context, Flush] => TexSubImage3DOES { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, pixel_type: GLenum, pixels: Blob<'a> };
        /// A rectangle of the read buffer copied into slice `zoffset` of a 3D image.
        glCopyTexSubImage3DOES [Context, Flush] => CopyTexSubImage3DOES { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, x: GLint, y: GLint, width: GLsizei, height: GLsizei };
        /// A compressed 3D image (`GL_KHR_texture_compression_astc_sliced_3d`: ASTC slices).
        glCompressedTexImage3DOES [Context, Flush] => CompressedTexImage3DOES { target: GLenum, level: GLint, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei, border: GLint, data: Blob<'a> };
        /// A box of a compressed 3D image, in whole blocks.
        glCompressedTexSubImage3DOES [Context, Flush] => CompressedTexSubImage3DOES { target: GLenum, level: GLint, xoffset: GLint, yoffset: GLint, zoffset: GLint, width: GLsizei, height: GLsizei, depth: GLsizei, format: GLenum, data: Blob<'a> };
        /// Slice `zoffset` of a 3D texture's `level` as a framebuffer attachment.
        glFramebufferTexture3DOES [Context] => FramebufferTexture3DOES { target: GLenum, attachment: GLenum, textarget: GLenum, texture: GLuint, level: GLint, zoffset: GLint };
        glUniform1ui [Context, Es3] => Uniform1ui { location: GLint, x: GLuint };
        glUniform2ui [Context, Es3] => Uniform2ui { location: GLint, x: GLuint, y: GLuint };
        glUniform3ui [Context, Es3] => Uniform3ui { location: GLint, x: GLuint, y: GLuint, z: GLuint };
        glUniform4ui [Context, Es3] => Uniform4ui { location: GLint, x: GLuint, y: GLuint, z: GLuint, w: GLuint };
        glUniform1uiv [Context, Es3] => Uniform1uiv { location: GLint, values: Slice<'a, GLuint> };
        glUniform2uiv [Context, Es3] => Uniform2uiv { location: GLint, values: Slice<'a, GLuint> };
        glUniform3uiv [Context, Es3] => Uniform3uiv { location: GLint, values: Slice<'a, GLuint> };
        glUniform4uiv [Context, Es3] => Uniform4uiv { location: GLint, values: Slice<'a, GLuint> };
        glUniformMatrix2x3fv [Context, Es3] => UniformMatrix2x3fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix3x2fv [Context, Es3] => UniformMatrix3x2fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix2x4fv [Context, Es3] => UniformMatrix2x4fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix4x2fv [Context, Es3] => UniformMatrix4x2fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix3x4fv [Context, Es3] => UniformMatrix3x4fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glUniformMatrix4x3fv [Context, Es3] => UniformMatrix4x3fv { location: GLint, transpose: bool, values: Slice<'a, GLfloat> };
        glBindBufferBase [Context, Es3] => BindBufferBase { target: GLenum, index: GLuint, buffer: GLuint };
        glBindBufferRange [Context, Es3] => BindBufferRange { target: GLenum, index: GLuint, buffer: GLuint, offset: i64, size: i64 };
        glUniformBlockBinding [Context, Es3] => UniformBlockBinding { program: GLuint, index: GLuint, binding: GLuint };
        glVertexAttribDivisor [Context, Es3] => VertexAttribDivisor { index: GLuint, divisor: GLuint };
        glCopyBufferSubData [Context, Flush, Es3] => CopyBufferSubData { read_target: GLenum, write_target: GLenum, read_offset: i64, write_offset: i64, size: i64 };
        glInvalidateFramebuffer [Context, Es3] => InvalidateFramebuffer { target: GLenum, attachments: Slice<'a, GLenum> };
        glInvalidateSubFramebuffer [Context, Es3] => InvalidateSubFramebuffer { target: GLenum, attachments: Slice<'a, GLenum>, x: GLint, y: GLint, width: GLsizei, height: GLsizei };
        /// `offset` is the byte offset into the bound `GL_ARRAY_BUFFER`, or with none bound a
        /// client array's address (its bytes follow in `strataVertexAttribData`).
        glVertexAttribIPointer [Context, Es3] => VertexAttribIPointer { index: GLuint, size: GLint, attrib_type: GLenum, stride: GLsizei, offset: u64 };
        glVertexAttribI4i [Context, Es3] => VertexAttribI4i { index: GLuint, x: GLint, y: GLint, z: GLint, w: GLint };
        glVertexAttribI4ui [Context, Es3] => VertexAttribI4ui { index: GLuint, x: GLuint, y: GLuint, z: GLuint, w: GLuint };
        /// `values`: four for a colour, one for the depth or the stencil.
        glClearBufferfv [Context, Es3] => ClearBufferfv { buffer: GLenum, drawbuffer: GLint, values: Slice<'a, GLfloat> };
        glClearBufferiv [Context, Es3] => ClearBufferiv { buffer: GLenum, drawbuffer: GLint, values: Slice<'a, GLint> };
        glClearBufferuiv [Context, Es3] => ClearBufferuiv { buffer: GLenum, drawbuffer: GLint, values: Slice<'a, GLuint> };
        glClearBufferfi [Context, Es3] => ClearBufferfi { buffer: GLenum, drawbuffer: GLint, depth: GLfloat, stencil: GLint };
        glGenTransformFeedbacks [Context, Es3] => GenTransformFeedbacks { names: Slice<'a, GLuint> };
        glDeleteTransformFeedbacks [Context, Es3] => DeleteTransformFeedbacks { names: Slice<'a, GLuint> };
        glBindTransformFeedback [Context, Es3] => BindTransformFeedback { target: GLenum, id: GLuint };
        glBeginTransformFeedback [Context, Es3] => BeginTransformFeedback { mode: GLenum };
        /// Ends capture; the captured buffers' contents are read back for the daemon's copies.
        glEndTransformFeedback [Context, Es3] => EndTransformFeedback {};
        glPauseTransformFeedback [Context, Es3] => PauseTransformFeedback {};
        glResumeTransformFeedback [Context, Es3] => ResumeTransformFeedback {};
        /// `names`: the `count` varyings' names, each ended by a newline.
        glTransformFeedbackVaryings [Context, Es3] => TransformFeedbackVaryings { program: GLuint, count: GLsizei, names: Text<'a>, buffer_mode: GLenum };
        /// Immutable storage: every level of the bound texture at once, its contents undefined.
        glTexStorage2D [Context, Es3] => TexStorage2D { target: GLenum, levels: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei };
        glTexStorage3D [Context, Es3] => TexStorage3D { target: GLenum, levels: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei, depth: GLsizei };
        /// `names` are the sampler names the client allocated.
        glGenSamplers [Context, Es3] => GenSamplers { names: Slice<'a, GLuint> };
        glDeleteSamplers [Context, Es3] => DeleteSamplers { names: Slice<'a, GLuint> };
        glBindSampler [Context, Es3] => BindSampler { unit: GLuint, sampler: GLuint };
        glSamplerParameteri [Context, Es3] => SamplerParameteri { sampler: GLuint, pname: GLenum, param: GLint };
        glSamplerParameterf [Context, Es3] => SamplerParameterf { sampler: GLuint, pname: GLenum, param: GLfloat };
        glSamplerParameteriv [Context, Es3] => SamplerParameteriv { sampler: GLuint, pname: GLenum, params: Slice<'a, GLint> };
        glSamplerParameterfv [Context, Es3] => SamplerParameterfv { sampler: GLuint, pname: GLenum, params: Slice<'a, GLfloat> };
        glRenderbufferStorageMultisample [Context, Es3] => RenderbufferStorageMultisample { target: GLenum, samples: GLsizei, internalformat: GLenum, width: GLsizei, height: GLsizei };
        glFramebufferTextureLayer [Context, Es3] => FramebufferTextureLayer { target: GLenum, attachment: GLenum, texture: GLuint, level: GLint, layer: GLint };
        glBlitFramebuffer [Context, Flush, Es3] => BlitFramebuffer { src_x0: GLint, src_y0: GLint, src_x1: GLint, src_y1: GLint, dst_x0: GLint, dst_y0: GLint, dst_x1: GLint, dst_y1: GLint, mask: GLbitfield, filter: GLenum };
    }
    sync {
        glCheckFramebufferStatus [Context] => CheckFramebufferStatus { target: GLenum } -> GLenum;
        glFinish [Context] => Finish {} -> ();
        glGetActiveAttrib [Context] => GetActiveAttrib { program: GLuint, index: GLuint } -> Option<ActiveVariable>;
        glGetActiveUniform [Context] => GetActiveUniform { program: GLuint, index: GLuint } -> Option<ActiveVariable>;
        glGetAttachedShaders [Context] => GetAttachedShaders { program: GLuint } -> Vec<GLuint>;
        glGetAttribLocation [Context] => GetAttribLocation { program: GLuint, name: Text<'a> } -> GLint;
        glGetBooleanv [Context] => GetBooleanv { pname: GLenum } -> Vec<bool>;
        glGetBufferParameteriv [Context] => GetBufferParameteriv { target: GLenum, pname: GLenum } -> GLint;
        glGetError [Context] => GetError {} -> GLenum;
        glGetFloatv [Context] => GetFloatv { pname: GLenum } -> Vec<GLfloat>;
        glGetFramebufferAttachmentParameteriv [Context] => GetFramebufferAttachmentParameteriv { target: GLenum, attachment: GLenum, pname: GLenum } -> GLint;
        glGetIntegerv [Context] => GetIntegerv { pname: GLenum } -> Vec<GLint>;
        glGetProgramiv [Context] => GetProgramiv { program: GLuint, pname: GLenum } -> GLint;
        glGetProgramInfoLog [Context] => GetProgramInfoLog { program: GLuint } -> String;
        glGetRenderbufferParameteriv [Context] => GetRenderbufferParameteriv { target: GLenum, pname: GLenum } -> GLint;
        glGetShaderiv [Context] => GetShaderiv { shader: GLuint, pname: GLenum } -> GLint;
        glGetShaderInfoLog [Context] => GetShaderInfoLog { shader: GLuint } -> String;
        /// Reply: (range, precision).
        glGetShaderPrecisionFormat [Context] => GetShaderPrecisionFormat { shader_type: GLenum, precision_type: GLenum } -> ([GLint; 2], GLint);
        glGetShaderSource [Context] => GetShaderSource { shader: GLuint } -> String;
        /// `None` stands for the NULL a driver returns on error.
        glGetString [Context] => GetString { name: GLenum } -> Option<String>;
        glGetTexParameterfv [Context] => GetTexParameterfv { target: GLenum, pname: GLenum } -> Vec<GLfloat>;
        glGetTexParameteriv [Context] => GetTexParameteriv { target: GLenum, pname: GLenum } -> Vec<GLint>;
        glGetUniformfv [Context] => GetUniformfv { program: GLuint, location: GLint } -> Vec<GLfloat>;
        glGetUniformiv [Context] => GetUniformiv { program: GLuint, location: GLint } -> Vec<GLint>;
        glGetUniformLocation [Context] => GetUniformLocation { program: GLuint, name: Text<'a> } -> GLint;
        glGetVertexAttribfv [Context] => GetVertexAttribfv { index: GLuint, pname: GLenum } -> Vec<GLfloat>;
        glGetVertexAttribiv [Context] => GetVertexAttribiv { index: GLuint, pname: GLenum } -> Vec<GLint>;
        glGetVertexAttribPointerv [Context] => GetVertexAttribPointerv { index: GLuint, pname: GLenum } -> u64;
        glIsBuffer [Context] => IsBuffer { name: GLuint } -> bool;
        glIsEnabled [Context] => IsEnabled { cap: GLenum } -> bool;
        glIsFramebuffer [Context] => IsFramebuffer { name: GLuint } -> bool;
        glIsProgram [Context] => IsProgram { name: GLuint } -> bool;
        glIsRenderbuffer [Context] => IsRenderbuffer { name: GLuint } -> bool;
        glIsShader [Context] => IsShader { name: GLuint } -> bool;
        glIsTexture [Context] => IsTexture { name: GLuint } -> bool;
        glReadPixels [Context] => ReadPixels { x: GLint, y: GLint, width: GLsizei, height: GLsizei, format: GLenum, pixel_type: GLenum } -> Bytes;
        eglGetDisplay [NoContext] => GetDisplay { native_display: u64 } -> EglHandle;
        eglGetPlatformDisplay [NoContext] => GetPlatformDisplay { platform: GLenum, native_display: u64, attribs: Slice<'a, EGLint> } -> EglHandle;
        /// Reply: (major, minor) version.
        eglInitialize [NoContext] => Initialize { display: EglHandle } -> EglResult<(EGLint, EGLint)>;
        eglChooseConfig [NoContext] => ChooseConfig { display: EglHandle, attribs: Slice<'a, EGLint>, config_size: EGLint } -> EglResult<Vec<EglHandle>>;
        eglGetConfigAttrib [NoContext] => GetConfigAttrib { display: EglHandle, config: EglHandle, attribute: EGLint } -> EglResult<EGLint>;
        /// Placement (x, y, z, width, height) of the daemon-owned surface.
        eglCreateWindowSurface [NoContext] => CreateWindowSurface { display: EglHandle, config: EglHandle, native_window: u64, x: GLint, y: GLint, z: GLfloat, width: GLsizei, height: GLsizei, attribs: Slice<'a, EGLint> } -> EglResult<EglHandle>;
        eglCreatePbufferSurface [NoContext] => CreatePbufferSurface { display: EglHandle, config: EglHandle, attribs: Slice<'a, EGLint> } -> EglResult<EglHandle>;
        eglCreateContext [NoContext] => CreateContext { display: EglHandle, config: EglHandle, share_context: EglHandle, attribs: Slice<'a, EGLint> } -> EglResult<EglHandle>;
        eglMakeCurrent [NoContext] => MakeCurrent { display: EglHandle, draw: EglHandle, read: EglHandle, context: EglHandle } -> EglResult<()>;
        eglSwapInterval [NoContext] => SwapInterval { display: EglHandle, interval: EGLint } -> EglResult<()>;
        eglQuerySurface [NoContext] => QuerySurface { display: EglHandle, surface: EglHandle, attribute: EGLint } -> EglResult<EGLint>;
        eglDestroySurface [NoContext] => DestroySurface { display: EglHandle, surface: EglHandle } -> EglResult<()>;
        eglDestroyContext [NoContext] => DestroyContext { display: EglHandle, context: EglHandle } -> EglResult<()>;
        eglTerminate [NoContext] => Terminate { display: EglHandle } -> EglResult<()>;
        /// Round trip: every earlier command has been decoded when the token comes back.
        strataPing [NoContext] => Ping { token: u64 } -> u64;
        /// The daemon compares the client's count and CRC-32 of all earlier messages with its own.
        strataVerify [Context] => Verify { commands: u64, crc32: u32 } -> StreamTally;
        /// The executor's counters for this client.
        strataStats [NoContext] => Stats {} -> ExecStats;
        /// Blocks while the surface has K frames in flight (and, with a swap interval n ≥ 1,
        /// until n output frames have passed since the previous swap).
        eglSwapBuffers [NoContext] => SwapBuffers { display: EglHandle, surface: EglHandle } -> EglResult<()>;
        glIsVertexArrayOES [Context] => IsVertexArrayOES { array: GLuint } -> bool;
        /// At most `count` messages, oldest first; with `log` (the application passed a message
        /// buffer) only as many as fit in `buf_size` bytes with their NULs.
        glGetDebugMessageLogKHR [Context] => GetDebugMessageLogKHR { count: GLuint, buf_size: GLsizei, log: bool } -> Vec<DebugMessage>;
        /// The whole label (the client truncates it to `buf_size`), `None` after a GL error.
        glGetObjectLabelKHR [Context] => GetObjectLabelKHR { identifier: GLenum, name: GLuint, buf_size: GLsizei } -> Option<Bytes>;
        /// `GL_EXT_debug_label`: an object's label (whole; the caller truncates), or `None`
        /// after a GL error.
        glGetObjectLabelEXT [Context] => GetObjectLabelEXT { object_type: GLenum, object: GLuint, buf_size: GLsizei } -> Option<Bytes>;
        /// As `glGetObjectLabelKHR`, for a sync object.
        glGetObjectPtrLabelKHR [Context] => GetObjectPtrLabelKHR { ptr: u64, buf_size: GLsizei } -> Option<Bytes>;
        /// The messages generated for the application's debug callback since the last call.
        strataDebugMessages [Context] => DebugMessages {} -> Vec<DebugMessage>;
        /// Reallocates a window surface's colour and depth images at a new size, keeping its
        /// id, placement, depth layer, normal, swap interval and pacing; the last shown frame
        /// stays on screen until the next swap.
        strataResizeSurface [NoContext] => ResizeSurface { display: EglHandle, surface: EglHandle, width: GLsizei, height: GLsizei } -> EglResult<()>;
        /// A context attribute only the daemon knows (`EGL_CONTEXT_PRIORITY_LEVEL_IMG`: the class
        /// its client is scheduled in).
        eglQueryContext [NoContext] => QueryContext { display: EglHandle, context: EglHandle, attribute: EGLint } -> EglResult<EGLint>;
        /// `GL_OES_mapbuffer`: maps the whole buffer bound to `target`. Reply: its contents
        /// (`None` on error).
        glMapBufferOES [Context] => MapBufferOES { target: GLenum, access: GLenum } -> Option<Bytes>;
        /// `GL_EXT_map_buffer_range`: maps `length` bytes at `offset`. Reply: their contents,
        /// empty where `access` invalidates them (`None` on error).
        glMapBufferRangeEXT [Context] => MapBufferRangeEXT { target: GLenum, offset: i64, length: i64, access: GLbitfield } -> Option<Bytes>;
        glIsQueryEXT [Context] => IsQueryEXT { id: GLuint } -> bool;
        /// `GL_CURRENT_QUERY_EXT` of `target` (nothing on error).
        glGetQueryivEXT [Context] => GetQueryivEXT { target: GLenum, pname: GLenum } -> Vec<GLint>;
        /// A query's result or its availability (nothing on error); the result waits for the
        /// draws it counts.
        glGetQueryObjectuivEXT [Context] => GetQueryObjectuivEXT { id: GLuint, pname: GLenum } -> Vec<GLuint>;
        /// `GL_OES_get_program_binary`: the binary of `program`'s last link, if `buf_size` bytes
        /// hold it. Reply: `None` for an error found before the length is written (a bad name
        /// or a negative size), `Some(None)` for one found after it is set to 0, else the
        /// binary's format and bytes.
        glGetProgramBinaryOES [Context] => GetProgramBinaryOES { program: GLuint, buf_size: GLsizei } -> Option<Option<(GLenum, Bytes)>>;
        /// `GL_EXT_disjoint_timer_query`: a query's result or availability in the caller's type
        /// (nothing on error); a result waits for the commands it measures.
        glGetQueryObjectivEXT [Context] => GetQueryObjectivEXT { id: GLuint, pname: GLenum } -> Vec<GLint>;
        glGetQueryObjecti64vEXT [Context] => GetQueryObjecti64vEXT { id: GLuint, pname: GLenum } -> Vec<i64>;
        glGetQueryObjectui64vEXT [Context] => GetQueryObjectui64vEXT { id: GLuint, pname: GLenum } -> Vec<u64>;
        /// A state value as 64-bit integers; `GL_TIMESTAMP_EXT` is the device's time now.
        glGetInteger64vEXT [Context] => GetInteger64vEXT { pname: GLenum } -> Vec<i64>;
        /// `EGL_KHR_image_base`: an EGLImage of one level (and face) of a texture, or of a
        /// renderbuffer, of `context`'s objects (`EGL_KHR_gl_texture_2D_image`,
        /// `EGL_KHR_gl_texture_cubemap_image`, `EGL_KHR_gl_renderbuffer_image`). Reply: its handle.
        eglCreateImageKHR [NoContext] => CreateImageKHR { display: EglHandle, context: EglHandle, target: EGLint, buffer: GLuint, attribs: Slice<'a, EGLint> } -> EglResult<EglHandle>;
        eglDestroyImageKHR [NoContext] => DestroyImageKHR { display: EglHandle, image: EglHandle } -> EglResult<()>;
        /// `GL_EXT_separate_shader_objects`: whether `pipeline` names a pipeline object.
        glIsProgramPipelineEXT [Context] => IsProgramPipelineEXT { pipeline: GLuint } -> bool;
        /// A pipeline's state (`GL_ACTIVE_PROGRAM_EXT`, a stage's program, validation, log
        /// length); nothing on error.
        glGetProgramPipelineivEXT [Context] => GetProgramPipelineivEXT { pipeline: GLuint, pname: GLenum } -> Vec<GLint>;
        glGetProgramPipelineInfoLogEXT [Context] => GetProgramPipelineInfoLogEXT { pipeline: GLuint } -> String;
        /// `EGL_KHR_swap_buffers_with_damage`: `eglSwapBuffers`, the frame having changed only
        /// within `rects` (x, y, width, height quadruples from the surface's bottom left).
        eglSwapBuffersWithDamageKHR [NoContext] => SwapBuffersWithDamageKHR { display: EglHandle, surface: EglHandle, rects: Slice<'a, EGLint> } -> EglResult<()>;
        /// `EGL_KHR_fence_sync`'s fence: flushes the context's commands and marks the point
        /// after them. Reply: the mark, which the segment's fence word reaches once the commands
        /// before it have completed (`segment::FenceWord`).
        strataFence [Context] => Fence {} -> u64;
        /// The colour of one of the client's surfaces, as RGBA8 rows from the bottom, whatever
        /// the framebuffer bindings and pack state (the library puts a pixmap surface's
        /// contents into its X pixmap with it, and `eglCopyBuffers`' into any pixmap).
        strataReadSurface [NoContext] => ReadSurface { display: EglHandle, surface: EglHandle } -> EglResult<Bytes>;
        /// One extension of `GL_EXTENSIONS` by index (`None` after an error).
        glGetStringi [Context, Es3] => GetStringi { name: GLenum, index: GLuint } -> Option<String>;
        /// A uniform's values as unsigned integers (nothing on error).
        glGetUniformuiv [Context, Es3] => GetUniformuiv { program: GLuint, location: GLint } -> Vec<GLuint>;
        /// A uniform block's index by name (`GL_INVALID_INDEX` if none).
        glGetUniformBlockIndex [Context, Es3] => GetUniformBlockIndex { program: GLuint, name: Text<'a> } -> GLuint;
        /// A uniform block's parameter (nothing on error).
        glGetActiveUniformBlockiv [Context, Es3] => GetActiveUniformBlockiv { program: GLuint, index: GLuint, pname: GLenum } -> Vec<GLint>;
        /// A uniform block's whole name (`None` on error; the client truncates).
        glGetActiveUniformBlockName [Context, Es3] => GetActiveUniformBlockName { program: GLuint, index: GLuint } -> Option<String>;
        /// An indexed binding's state (nothing on error).
        glGetIntegeri_v [Context, Es3] => GetIntegeriV { target: GLenum, index: GLuint } -> Vec<GLint>;
        glGetInteger64i_v [Context, Es3] => GetInteger64iV { target: GLenum, index: GLuint } -> Vec<i64>;
        /// A buffer's parameter as a 64-bit integer (0 on error).
        glGetBufferParameteri64v [Context, Es3] => GetBufferParameteri64v { target: GLenum, pname: GLenum } -> i64;
        /// An attribute's state as integers (nothing on error).
        glGetVertexAttribIiv [Context, Es3] => GetVertexAttribIiv { index: GLuint, pname: GLenum } -> Vec<GLint>;
        glGetVertexAttribIuiv [Context, Es3] => GetVertexAttribIuiv { index: GLuint, pname: GLenum } -> Vec<GLuint>;
        /// A fragment output's location by name (-1 if none).
        glGetFragDataLocation [Context, Es3] => GetFragDataLocation { program: GLuint, name: Text<'a> } -> GLint;
        glIsTransformFeedback [Context, Es3] => IsTransformFeedback { id: GLuint } -> bool;
        /// `names`: the `count` names, each ended by a newline; an index per name.
        glGetUniformIndices [Context, Es3] => GetUniformIndices { program: GLuint, count: GLsizei, names: Text<'a> } -> Vec<GLuint>;
        /// A value per index (nothing on error).
        glGetActiveUniformsiv [Context, Es3] => GetActiveUniformsiv { program: GLuint, indices: Slice<'a, GLuint>, pname: GLenum } -> Vec<GLint>;
        /// A captured varying's size, type and name (`None` on error).
        glGetTransformFeedbackVarying [Context, Es3] => GetTransformFeedbackVarying { program: GLuint, index: GLuint } -> Option<ActiveVariable>;
        glIsSampler [Context, Es3] => IsSampler { sampler: GLuint } -> bool;
        /// The parameter's values (nothing on error).
        glGetSamplerParameteriv [Context, Es3] => GetSamplerParameteriv { sampler: GLuint, pname: GLenum } -> Vec<GLint>;
        /// The parameter's values (nothing on error).
        glGetSamplerParameterfv [Context, Es3] => GetSamplerParameterfv { sampler: GLuint, pname: GLenum } -> Vec<GLfloat>;
        /// A renderable format's sample counts, or their number (nothing on error).
        glGetInternalformativ [Context, Es3] => GetInternalformativ { target: GLenum, internalformat: GLenum, pname: GLenum, buf_size: GLsizei } -> Vec<GLint>;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codec::{decode_command, encode_to_vec};

    #[test]
    fn packed_vertex_data_names_its_type_and_is_appended() {
        let data = [0x00u8, 0x3C, 0x00, 0x40];
        let cmd = Command::VertexAttribDataPacked { index: 3, attrib_type: 0x8D61, data: Blob::borrowed(&data) };
        let bytes = encode_to_vec(&cmd).expect("encode");
        match decode_command(&bytes).expect("decode") {
            Command::VertexAttribDataPacked { index: 3, attrib_type: 0x8D61, data: d } => {
                assert_eq!(d.as_bytes(), data)
            }
            other => panic!("decoded {other:?}"),
        }
        // Wire order is table order: the new command comes after every earlier one.
        let pos = |op: Opcode| Opcode::ALL.iter().position(|&o| o == op).expect("listed");
        assert!(pos(Opcode::VertexAttribDataPacked) > pos(Opcode::DiscardFramebufferEXT));
        assert!(pos(Opcode::VertexAttribDataPacked) > pos(Opcode::VertexAttribData));
    }

    #[test]
    fn egl_calls_need_no_context_and_gl_calls_do() {
        for &op in Opcode::ALL {
            if op.name().starts_with("egl") {
                assert!(!op.needs_context(), "{} needs no current context", op.name());
            }
            if op.name().starts_with("gl") {
                assert!(op.needs_context(), "{} does nothing without a current context", op.name());
            }
        }
    }

    #[test]
    fn every_image_and_buffer_upload_flushes_first() {
        for &op in Opcode::ALL {
            let n = op.name();
            // A blit reads what pending draws write and writes an image they may read.
            let upload = n.starts_with("gl")
                && (n.contains("Image")
                    || n.contains("Mipmap")
                    || (n.contains("Buffer") && n.ends_with("Data"))
                    || n.contains("UnmapBuffer")
                    || n.contains("FlushMappedBuffer")
                    || n == "glBlitFramebuffer");
            assert_eq!(op.flushes_first(), upload, "{n}: the flush rule");
            assert!(!op.flushes_first() || op.needs_context(), "{n}: a flush needs a context");
        }
    }
}

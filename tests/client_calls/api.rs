//! The entry points `tests/client_calls.rs` calls: each one's field name, C name and prototype,
//! resolved through an EGL library's `eglGetProcAddress`.

use std::ffi::c_void;

use super::{DebugProc, GetProc, Ptr};

/// Declares [`Api`]: each entry point's field name, C name and prototype.
macro_rules! api {
    ($($field:ident = $name:literal : fn($($arg:ty),*) $(-> $ret:ty)?;)*) => {
        /// The GL entry points the sequence calls, resolved through `eglGetProcAddress`.
        #[derive(Clone, Copy)]
        pub(super) struct Api {
            $(pub(super) $field: unsafe extern "C" fn($($arg),*) $(-> $ret)?,)*
        }

        impl Api {
            /// Resolves every entry point; the name of the first that is missing.
            pub(super) fn resolve(get_proc: GetProc<'_>) -> Result<Api, String> {
                Ok(Api {
                    $($field: {
                        let p = get_proc($name);
                        if p.is_null() {
                            return Err(format!("{} unresolved", $name));
                        }
                        // SAFETY: the entry point has the prototype gl2.h / gl2ext.h gives it.
                        unsafe { std::mem::transmute::<Ptr, unsafe extern "C" fn($($arg),*) $(-> $ret)?>(p) }
                    },)*
                })
            }
        }
    };
}

api! {
    get_error = "glGetError": fn() -> u32;
    gen_buffers = "glGenBuffers": fn(i32, *mut u32);
    bind_buffer = "glBindBuffer": fn(u32, u32);
    buffer_data = "glBufferData": fn(u32, isize, *const c_void, u32);
    buffer_sub_data = "glBufferSubData": fn(u32, isize, isize, *const c_void);
    delete_buffers = "glDeleteBuffers": fn(i32, *const u32);
    get_buffer_parameteriv = "glGetBufferParameteriv": fn(u32, u32, *mut i32);
    map = "glMapBufferOES": fn(u32, u32) -> Ptr;
    unmap = "glUnmapBufferOES": fn(u32) -> u8;
    get_pointer = "glGetBufferPointervOES": fn(u32, u32, *mut Ptr);
    map_range = "glMapBufferRangeEXT": fn(u32, isize, isize, u32) -> Ptr;
    flush_range = "glFlushMappedBufferRangeEXT": fn(u32, isize, isize);
    create_shader = "glCreateShader": fn(u32) -> u32;
    shader_source = "glShaderSource": fn(u32, i32, *const *const i8, *const i32);
    compile_shader = "glCompileShader": fn(u32);
    create_program = "glCreateProgram": fn() -> u32;
    attach_shader = "glAttachShader": fn(u32, u32);
    bind_attrib_location = "glBindAttribLocation": fn(u32, u32, *const i8);
    link_program = "glLinkProgram": fn(u32);
    use_program = "glUseProgram": fn(u32);
    vertex_attrib_pointer = "glVertexAttribPointer": fn(u32, i32, u32, u8, i32, *const c_void);
    enable_vertex_attrib_array = "glEnableVertexAttribArray": fn(u32);
    draw_arrays = "glDrawArrays": fn(u32, i32, i32);
    viewport = "glViewport": fn(i32, i32, i32, i32);
    clear_color = "glClearColor": fn(f32, f32, f32, f32);
    clear = "glClear": fn(u32);
    read_pixels = "glReadPixels": fn(i32, i32, i32, i32, u32, u32, *mut c_void);
    pixel_store_i = "glPixelStorei": fn(u32, i32);
    get_integerv = "glGetIntegerv": fn(u32, *mut i32);
    gen_textures = "glGenTextures": fn(i32, *mut u32);
    bind_texture = "glBindTexture": fn(u32, u32);
    tex_parameteri = "glTexParameteri": fn(u32, u32, i32);
    tex_image_2d = "glTexImage2D": fn(u32, i32, i32, i32, i32, i32, u32, u32, *const c_void);
    tex_sub_image_2d = "glTexSubImage2D": fn(u32, i32, i32, i32, i32, i32, u32, u32, *const c_void);
    check_framebuffer_status = "glCheckFramebufferStatus": fn(u32) -> u32;
    gen_framebuffers = "glGenFramebuffers": fn(i32, *mut u32);
    bind_framebuffer = "glBindFramebuffer": fn(u32, u32);
    framebuffer_texture_2d = "glFramebufferTexture2D": fn(u32, u32, u32, u32, i32);
    egl_make_current = "eglMakeCurrent": fn(Ptr, Ptr, Ptr, Ptr) -> u32;
    egl_create_context = "eglCreateContext": fn(Ptr, Ptr, Ptr, *const i32) -> Ptr;
    egl_destroy_context = "eglDestroyContext": fn(Ptr, Ptr) -> u32;
    egl_get_current_surface = "eglGetCurrentSurface": fn(i32) -> Ptr;
    egl_get_error = "eglGetError": fn() -> i32;
    egl_swap_interval = "eglSwapInterval": fn(Ptr, i32) -> u32;
    reset_status_ext = "glGetGraphicsResetStatusEXT": fn() -> u32;
    reset_status_khr = "glGetGraphicsResetStatusKHR": fn() -> u32;
    readn_pixels_ext = "glReadnPixelsEXT": fn(i32, i32, i32, i32, u32, u32, i32, *mut c_void);
    readn_pixels_khr = "glReadnPixelsKHR": fn(i32, i32, i32, i32, u32, u32, i32, *mut c_void);
    getn_uniform_fv = "glGetnUniformfvEXT": fn(u32, i32, i32, *mut f32);
    getn_uniform_iv = "glGetnUniformivKHR": fn(u32, i32, i32, *mut i32);
    get_uniform_location = "glGetUniformLocation": fn(u32, *const i8) -> i32;
    uniform4f = "glUniform4f": fn(i32, f32, f32, f32, f32);
    get_booleanv = "glGetBooleanv": fn(u32, *mut u8);
    draw_buffers_ext = "glDrawBuffersEXT": fn(i32, *const u32);
    draw_buffers_nv = "glDrawBuffersNV": fn(i32, *const u32);
    read_buffer_nv = "glReadBufferNV": fn(u32);
    finish = "glFinish": fn();
    get_string = "glGetString": fn(u32) -> *const u8;
    get_string_i = "glGetStringi": fn(u32, u32) -> *const u8;
    uniform1ui = "glUniform1ui": fn(i32, u32);
    core_gen_vertex_arrays = "glGenVertexArrays": fn(i32, *mut u32);
    core_bind_vertex_array = "glBindVertexArray": fn(u32);
    core_is_vertex_array = "glIsVertexArray": fn(u32) -> u8;
    core_delete_vertex_arrays = "glDeleteVertexArrays": fn(i32, *const u32);
    core_draw_arrays_instanced = "glDrawArraysInstanced": fn(u32, i32, i32, i32);
    core_draw_elements_instanced = "glDrawElementsInstanced": fn(u32, i32, u32, *const c_void, i32);
    core_map_buffer_range = "glMapBufferRange": fn(u32, isize, isize, u32) -> Ptr;
    core_flush_mapped_buffer_range = "glFlushMappedBufferRange": fn(u32, isize, isize);
    core_unmap_buffer = "glUnmapBuffer": fn(u32) -> u8;
    core_get_buffer_pointerv = "glGetBufferPointerv": fn(u32, u32, *mut Ptr);
    core_draw_buffers = "glDrawBuffers": fn(i32, *const u32);
    core_read_buffer = "glReadBuffer": fn(u32);
    core_tex_image_3d = "glTexImage3D": fn(u32, i32, i32, i32, i32, i32, i32, u32, u32, *const c_void);
    core_gen_queries = "glGenQueries": fn(i32, *mut u32);
    core_begin_query = "glBeginQuery": fn(u32, u32);
    core_end_query = "glEndQuery": fn(u32);
    core_is_query = "glIsQuery": fn(u32) -> u8;
    core_get_query_object_uiv = "glGetQueryObjectuiv": fn(u32, u32, *mut u32);
    core_delete_queries = "glDeleteQueries": fn(i32, *const u32);
    core_get_integer64v = "glGetInteger64v": fn(u32, *mut i64);
    core_vertex_attrib_divisor = "glVertexAttribDivisor": fn(u32, u32);
    copy_buffer_sub_data = "glCopyBufferSubData": fn(u32, u32, isize, isize, isize);
    draw_range_elements = "glDrawRangeElements": fn(u32, u32, u32, i32, u32, *const c_void);
    invalidate_framebuffer = "glInvalidateFramebuffer": fn(u32, i32, *const u32);
    invalidate_sub_framebuffer = "glInvalidateSubFramebuffer": fn(u32, i32, *const u32, i32, i32, i32, i32);
    get_buffer_parameteri64v = "glGetBufferParameteri64v": fn(u32, u32, *mut i64);
    egl_create_sync = "eglCreateSyncKHR": fn(Ptr, u32, *const i32) -> Ptr;
    egl_destroy_sync = "eglDestroySyncKHR": fn(Ptr, Ptr) -> u32;
    egl_client_wait_sync = "eglClientWaitSyncKHR": fn(Ptr, Ptr, i32, u64) -> i32;
    egl_get_sync_attrib = "eglGetSyncAttribKHR": fn(Ptr, Ptr, i32, *mut i32) -> u32;
    egl_wait_sync = "eglWaitSyncKHR": fn(Ptr, Ptr, i32) -> i32;
    egl_signal_sync = "eglSignalSyncKHR": fn(Ptr, Ptr, u32) -> u32;
    get_programiv = "glGetProgramiv": fn(u32, u32, *mut i32);
    get_program_binary = "glGetProgramBinaryOES": fn(u32, i32, *mut i32, *mut u32, *mut c_void);
    program_binary = "glProgramBinaryOES": fn(u32, u32, *const c_void, i32);
    draw_elements = "glDrawElements": fn(u32, i32, u32, *const c_void);
    egl_choose_config = "eglChooseConfig": fn(Ptr, *const i32, *mut Ptr, i32, *mut i32) -> u32;
    egl_create_pbuffer = "eglCreatePbufferSurface": fn(Ptr, Ptr, *const i32) -> Ptr;
    egl_destroy_surface = "eglDestroySurface": fn(Ptr, Ptr) -> u32;
    egl_query_context = "eglQueryContext": fn(Ptr, Ptr, i32, *mut i32) -> u32;
    egl_get_config_attrib = "eglGetConfigAttrib": fn(Ptr, Ptr, i32, *mut i32) -> u32;
    egl_create_image = "eglCreateImageKHR": fn(Ptr, Ptr, u32, Ptr, *const i32) -> Ptr;
    egl_destroy_image = "eglDestroyImageKHR": fn(Ptr, Ptr) -> u32;
    egl_image_target_texture = "glEGLImageTargetTexture2DOES": fn(u32, Ptr);
    egl_image_target_renderbuffer = "glEGLImageTargetRenderbufferStorageOES": fn(u32, Ptr);
    gen_renderbuffers = "glGenRenderbuffers": fn(i32, *mut u32);
    bind_renderbuffer = "glBindRenderbuffer": fn(u32, u32);
    renderbuffer_storage = "glRenderbufferStorage": fn(u32, u32, i32, i32);
    framebuffer_renderbuffer = "glFramebufferRenderbuffer": fn(u32, u32, u32, u32);
    get_renderbuffer_parameteriv = "glGetRenderbufferParameteriv": fn(u32, u32, *mut i32);
    get_tex_parameteriv = "glGetTexParameteriv": fn(u32, u32, *mut i32);
    generate_mipmap = "glGenerateMipmap": fn(u32);
    delete_textures = "glDeleteTextures": fn(i32, *const u32);
    get_shaderiv = "glGetShaderiv": fn(u32, u32, *mut i32);
    enable = "glEnable": fn(u32);
    is_enabled = "glIsEnabled": fn(u32) -> u8;
    is_buffer = "glIsBuffer": fn(u32) -> u8;
    is_texture = "glIsTexture": fn(u32) -> u8;
    is_program = "glIsProgram": fn(u32) -> u8;
    is_framebuffer = "glIsFramebuffer": fn(u32) -> u8;
    disable_vertex_attrib_array = "glDisableVertexAttribArray": fn(u32);
    delete_framebuffers = "glDeleteFramebuffers": fn(i32, *const u32);
    gen_vertex_arrays = "glGenVertexArraysOES": fn(i32, *mut u32);
    bind_vertex_array = "glBindVertexArrayOES": fn(u32);
    is_vertex_array = "glIsVertexArrayOES": fn(u32) -> u8;
    delete_vertex_arrays = "glDeleteVertexArraysOES": fn(i32, *const u32);
    debug_message_callback = "glDebugMessageCallbackKHR": fn(DebugProc, *const c_void);
    debug_message_control = "glDebugMessageControlKHR": fn(u32, u32, u32, i32, *const u32, u8);
    disable = "glDisable": fn(u32);
    scissor = "glScissor": fn(i32, i32, i32, i32);
    compressed_tex_image_2d = "glCompressedTexImage2D": fn(u32, i32, u32, i32, i32, i32, i32, *const c_void);
    gen_queries = "glGenQueriesEXT": fn(i32, *mut u32);
    delete_queries = "glDeleteQueriesEXT": fn(i32, *const u32);
    is_query = "glIsQueryEXT": fn(u32) -> u8;
    begin_query = "glBeginQueryEXT": fn(u32, u32);
    end_query = "glEndQueryEXT": fn(u32);
    query_counter = "glQueryCounterEXT": fn(u32, u32);
    get_query_iv = "glGetQueryivEXT": fn(u32, u32, *mut i32);
    get_query_object_iv = "glGetQueryObjectivEXT": fn(u32, u32, *mut i32);
    get_query_object_uiv = "glGetQueryObjectuivEXT": fn(u32, u32, *mut u32);
    get_query_object_i64v = "glGetQueryObjecti64vEXT": fn(u32, u32, *mut i64);
    get_query_object_ui64v = "glGetQueryObjectui64vEXT": fn(u32, u32, *mut u64);
    get_integer64v = "glGetInteger64vEXT": fn(u32, *mut i64);
    active_texture = "glActiveTexture": fn(u32);
    delete_program = "glDeleteProgram": fn(u32);
    get_uniformfv = "glGetUniformfv": fn(u32, i32, *mut f32);
    gen_program_pipelines = "glGenProgramPipelinesEXT": fn(i32, *mut u32);
    delete_program_pipelines = "glDeleteProgramPipelinesEXT": fn(i32, *const u32);
    bind_program_pipeline = "glBindProgramPipelineEXT": fn(u32);
    is_program_pipeline = "glIsProgramPipelineEXT": fn(u32) -> u8;
    use_program_stages = "glUseProgramStagesEXT": fn(u32, u32, u32);
    active_shader_program = "glActiveShaderProgramEXT": fn(u32, u32);
    program_parameteri = "glProgramParameteriEXT": fn(u32, u32, i32);
    validate_program_pipeline = "glValidateProgramPipelineEXT": fn(u32);
    get_program_pipeline_iv = "glGetProgramPipelineivEXT": fn(u32, u32, *mut i32);
    get_program_pipeline_info_log = "glGetProgramPipelineInfoLogEXT": fn(u32, i32, *mut i32, *mut i8);
    create_shader_program = "glCreateShaderProgramvEXT": fn(u32, i32, *const *const i8) -> u32;
    program_uniform1f = "glProgramUniform1fEXT": fn(u32, i32, f32);
    program_uniform4f = "glProgramUniform4fEXT": fn(u32, i32, f32, f32, f32, f32);
    program_uniform1i = "glProgramUniform1iEXT": fn(u32, i32, i32);
    program_uniform1iv = "glProgramUniform1ivEXT": fn(u32, i32, i32, *const i32);
    program_uniform4fv = "glProgramUniform4fvEXT": fn(u32, i32, i32, *const f32);
    program_uniform_matrix2fv = "glProgramUniformMatrix2fvEXT": fn(u32, i32, i32, u8, *const f32);
    tex_parameterfv = "glTexParameterfv": fn(u32, u32, *const f32);
    tex_parameteriv = "glTexParameteriv": fn(u32, u32, *const i32);
    get_tex_parameterfv = "glGetTexParameterfv": fn(u32, u32, *mut f32);
    tex_parameter_iiv_ext = "glTexParameterIivEXT": fn(u32, u32, *const i32);
    tex_parameter_iuiv_ext = "glTexParameterIuivEXT": fn(u32, u32, *const i32);
    tex_parameter_iiv_oes = "glTexParameterIivOES": fn(u32, u32, *const i32);
    tex_parameter_iuiv_oes = "glTexParameterIuivOES": fn(u32, u32, *const i32);
    get_tex_parameter_iiv_ext = "glGetTexParameterIivEXT": fn(u32, u32, *mut i32);
    get_tex_parameter_iuiv_ext = "glGetTexParameterIuivEXT": fn(u32, u32, *mut i32);
    get_tex_parameter_iiv_oes = "glGetTexParameterIivOES": fn(u32, u32, *mut i32);
    get_tex_parameter_iuiv_oes = "glGetTexParameterIuivOES": fn(u32, u32, *mut i32);
    egl_query_surface = "eglQuerySurface": fn(Ptr, Ptr, i32, *mut i32) -> u32;
    egl_swap_buffers = "eglSwapBuffers": fn(Ptr, Ptr) -> u32;
    blend_func = "glBlendFunc": fn(u32, u32);
    copy_tex_image_2d = "glCopyTexImage2D": fn(u32, i32, u32, i32, i32, i32, i32, i32);
    copy_tex_sub_image_2d = "glCopyTexSubImage2D": fn(u32, i32, i32, i32, i32, i32, i32, i32);
    tex_image_3d = "glTexImage3DOES": fn(u32, i32, u32, i32, i32, i32, i32, u32, u32, *const c_void);
    tex_sub_image_3d = "glTexSubImage3DOES": fn(u32, i32, i32, i32, i32, i32, i32, i32, u32, u32, *const c_void);
    compressed_tex_image_3d = "glCompressedTexImage3DOES": fn(u32, i32, u32, i32, i32, i32, i32, i32, *const c_void);
    copy_tex_sub_image_3d = "glCopyTexSubImage3DOES": fn(u32, i32, i32, i32, i32, i32, i32, i32, i32);
    framebuffer_texture_3d = "glFramebufferTexture3DOES": fn(u32, u32, u32, u32, i32, i32);
    compressed_tex_sub_image_2d = "glCompressedTexSubImage2D": fn(u32, i32, i32, i32, i32, i32, u32, i32, *const c_void);
    compressed_tex_sub_image_3d = "glCompressedTexSubImage3DOES": fn(u32, i32, i32, i32, i32, i32, i32, i32, u32, i32, *const c_void);
    draw_elements_base_vertex_ext = "glDrawElementsBaseVertexEXT": fn(u32, i32, u32, *const c_void, i32);
    draw_elements_base_vertex_oes = "glDrawElementsBaseVertexOES": fn(u32, i32, u32, *const c_void, i32);
    color_mask = "glColorMask": fn(u8, u8, u8, u8);
    uniform1f = "glUniform1f": fn(i32, f32);
    depth_func = "glDepthFunc": fn(u32);
    stencil_func = "glStencilFunc": fn(u32, i32, u32);
    clear_buffer_fv = "glClearBufferfv": fn(u32, i32, *const f32);
    clear_buffer_iv = "glClearBufferiv": fn(u32, i32, *const i32);
    clear_buffer_uiv = "glClearBufferuiv": fn(u32, i32, *const u32);
    clear_buffer_fi = "glClearBufferfi": fn(u32, i32, f32, i32);
    get_frag_data_location = "glGetFragDataLocation": fn(u32, *const i8) -> i32;
    fence_sync = "glFenceSync": fn(u32, u32) -> Ptr;
    is_sync = "glIsSync": fn(Ptr) -> u8;
    delete_sync = "glDeleteSync": fn(Ptr);
    client_wait_sync = "glClientWaitSync": fn(Ptr, u32, u64) -> u32;
    wait_sync = "glWaitSync": fn(Ptr, u32, u64);
    get_synciv = "glGetSynciv": fn(Ptr, u32, i32, *mut i32, *mut i32);
    gen_transform_feedbacks = "glGenTransformFeedbacks": fn(i32, *mut u32);
    delete_transform_feedbacks = "glDeleteTransformFeedbacks": fn(i32, *const u32);
    bind_transform_feedback = "glBindTransformFeedback": fn(u32, u32);
    is_transform_feedback = "glIsTransformFeedback": fn(u32) -> u8;
    begin_transform_feedback = "glBeginTransformFeedback": fn(u32);
    end_transform_feedback = "glEndTransformFeedback": fn();
    pause_transform_feedback = "glPauseTransformFeedback": fn();
    resume_transform_feedback = "glResumeTransformFeedback": fn();
    transform_feedback_varyings = "glTransformFeedbackVaryings": fn(u32, i32, *const *const i8, u32);
    get_transform_feedback_varying = "glGetTransformFeedbackVarying": fn(u32, u32, i32, *mut i32, *mut i32, *mut u32, *mut i8);
    tex_storage_2d = "glTexStorage2D": fn(u32, i32, u32, i32, i32);
    gen_samplers = "glGenSamplers": fn(i32, *mut u32);
    bind_sampler = "glBindSampler": fn(u32, u32);
    bind_buffer_base = "glBindBufferBase": fn(u32, u32, u32);
    bind_buffer_range = "glBindBufferRange": fn(u32, u32, u32, isize, isize);
    get_integeri_v = "glGetIntegeri_v": fn(u32, u32, *mut i32);
    get_query_object_uiv_core = "glGetQueryObjectuiv": fn(u32, u32, *mut u32);
    get_active_uniform = "glGetActiveUniform": fn(u32, u32, i32, *mut i32, *mut i32, *mut u32, *mut i8);
    get_uniform_indices = "glGetUniformIndices": fn(u32, i32, *const *const i8, *mut u32);
    get_active_uniformsiv = "glGetActiveUniformsiv": fn(u32, i32, *const u32, u32, *mut i32);
    get_active_uniform_blockiv = "glGetActiveUniformBlockiv": fn(u32, u32, u32, *mut i32);
}

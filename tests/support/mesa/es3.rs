//! The Mesa reference's arms for OpenGL ES 3.0's calls (in an ES 3.0 context; in an ES 2.0 one
//! Mesa records `GL_INVALID_OPERATION` for them, as Strata does).

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glGetUniformuiv(&mut self, program: &GLuint, location: &GLint) -> Result<Vec<GLuint>, ClientError> {
        let p = self.shader(*program);
        let mut v = [INT_SENTINEL as u32; 16];
        call!(self, "glGetUniformuiv", fn(u32, i32, *mut u32) -> (), p, *location, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL as u32).collect())
    }

    pub(super) fn glUniform1uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform1uiv", u32, location, values, 1)
    }

    pub(super) fn glUniform2uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform2uiv", u32, location, values, 2)
    }

    pub(super) fn glUniform3uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform3uiv", u32, location, values, 3)
    }

    pub(super) fn glUniform4uiv(&mut self, location: &GLint, values: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform4uiv", u32, location, values, 4)
    }
}

/// Generates the non-square `glUniformMatrix*fv` arms: `count` matrices of `n` floats.
macro_rules! matrix_arms {
    ($( $gl:ident = $name:literal, $n:literal; )*) => {
        #[allow(non_snake_case)]
        impl Arms<'_> {
            $( pub(super) fn $gl(&mut self, location: &GLint, transpose: &bool, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
                uniform_matrices!(self, $name, location, transpose, values, $n)
            } )*
        }
    };
}

matrix_arms! {
    glUniformMatrix2x3fv = "glUniformMatrix2x3fv", 6;
    glUniformMatrix3x2fv = "glUniformMatrix3x2fv", 6;
    glUniformMatrix2x4fv = "glUniformMatrix2x4fv", 8;
    glUniformMatrix4x2fv = "glUniformMatrix4x2fv", 8;
    glUniformMatrix3x4fv = "glUniformMatrix3x4fv", 12;
    glUniformMatrix4x3fv = "glUniformMatrix4x3fv", 12;
}

impl Arms<'_> {
    pub(super) fn glBindBufferBase(
        &mut self,
        target: &GLenum,
        index: &GLuint,
        buffer: &GLuint,
    ) -> Result<(), ClientError> {
        call!(self, "glBindBufferBase", fn(u32, u32, u32) -> (), *target, *index, *buffer);
        Ok(())
    }

    pub(super) fn glBindBufferRange(
        &mut self,
        target: &GLenum,
        index: &GLuint,
        buffer: &GLuint,
        offset: &i64,
        size: &i64,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glBindBufferRange",
            fn(u32, u32, u32, isize, isize) -> (),
            *target,
            *index,
            *buffer,
            *offset as isize,
            *size as isize
        );
        Ok(())
    }

    pub(super) fn glUniformBlockBinding(
        &mut self,
        program: &GLuint,
        index: &GLuint,
        binding: &GLuint,
    ) -> Result<(), ClientError> {
        let p = self.shader(*program);
        call!(self, "glUniformBlockBinding", fn(u32, u32, u32) -> (), p, *index, *binding);
        Ok(())
    }

    pub(super) fn glGetUniformBlockIndex(&mut self, program: &GLuint, name: &Text<'_>) -> Result<GLuint, ClientError> {
        let p = self.shader(*program);
        let name = std::ffi::CString::new(name.as_str()).map_err(|e| ClientError::Unsupported(e.to_string()))?;
        Ok(call!(self, "glGetUniformBlockIndex", fn(u32, *const i8) -> u32, p, name.as_ptr()))
    }

    pub(super) fn glGetActiveUniformBlockiv(
        &mut self,
        program: &GLuint,
        index: &GLuint,
        pname: &GLenum,
    ) -> Result<Vec<GLint>, ClientError> {
        let p = self.shader(*program);
        let mut v = [INT_SENTINEL; 64];
        call!(self, "glGetActiveUniformBlockiv", fn(u32, u32, u32, *mut i32) -> (), p, *index, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetActiveUniformBlockName(
        &mut self,
        program: &GLuint,
        index: &GLuint,
    ) -> Result<Option<String>, ClientError> {
        let p = self.shader(*program);
        let mut buf = vec![0u8; 256];
        let mut len = -1;
        call!(
            self,
            "glGetActiveUniformBlockName",
            fn(u32, u32, i32, *mut i32, *mut u8) -> (),
            p,
            *index,
            256,
            &mut len,
            buf.as_mut_ptr()
        );
        Ok((len >= 0).then(|| String::from_utf8_lossy(&buf[..len as usize]).into_owned()))
    }

    pub(super) fn glGetIntegeri_v(&mut self, target: &GLenum, index: &GLuint) -> Result<Vec<GLint>, ClientError> {
        let mut v = [INT_SENTINEL; 4];
        call!(self, "glGetIntegeri_v", fn(u32, u32, *mut i32) -> (), *target, *index, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetInteger64i_v(&mut self, target: &GLenum, index: &GLuint) -> Result<Vec<i64>, ClientError> {
        let sentinel = i64::from(INT_SENTINEL);
        let mut v = [sentinel; 4];
        call!(self, "glGetInteger64i_v", fn(u32, u32, *mut i64) -> (), *target, *index, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != sentinel).collect())
    }
}

impl Arms<'_> {
    pub(super) fn glCopyBufferSubData(
        &mut self,
        read_target: &GLenum,
        write_target: &GLenum,
        read_offset: &i64,
        write_offset: &i64,
        size: &i64,
    ) -> Result<(), ClientError> {
        let (r, w, n) = (*read_offset as isize, *write_offset as isize, *size as isize);
        call!(
            self,
            "glCopyBufferSubData",
            fn(u32, u32, isize, isize, isize) -> (),
            *read_target,
            *write_target,
            r,
            w,
            n
        );
        Ok(())
    }

    pub(super) fn glGetBufferParameteri64v(&mut self, target: &GLenum, pname: &GLenum) -> Result<i64, ClientError> {
        let mut v = 0i64;
        call!(self, "glGetBufferParameteri64v", fn(u32, u32, *mut i64) -> (), *target, *pname, &mut v);
        Ok(v)
    }
}

impl Arms<'_> {
    pub(super) fn glInvalidateFramebuffer(
        &mut self,
        target: &GLenum,
        attachments: &Slice<'_, GLenum>,
    ) -> Result<(), ClientError> {
        let list: Vec<u32> = attachments.iter().collect();
        call!(
            self,
            "glInvalidateFramebuffer",
            fn(u32, i32, *const u32) -> (),
            *target,
            list.len() as i32,
            list.as_ptr()
        );
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn glInvalidateSubFramebuffer(
        &mut self,
        target: &GLenum,
        attachments: &Slice<'_, GLenum>,
        x: &GLint,
        y: &GLint,
        width: &GLsizei,
        height: &GLsizei,
    ) -> Result<(), ClientError> {
        let list: Vec<u32> = attachments.iter().collect();
        let n = list.len() as i32;
        call!(
            self,
            "glInvalidateSubFramebuffer",
            fn(u32, i32, *const u32, i32, i32, i32, i32) -> (),
            *target,
            n,
            list.as_ptr(),
            *x,
            *y,
            *width,
            *height
        );
        Ok(())
    }
}

impl Arms<'_> {
    /// Buffer arrays only (`offset` into the bound array buffer): the ES 3.0 programs keep
    /// integer arrays in buffers.
    pub(super) fn glVertexAttribIPointer(
        &mut self,
        index: &GLuint,
        size: &GLint,
        attrib_type: &GLenum,
        stride: &GLsizei,
        offset: &u64,
    ) -> Result<(), ClientError> {
        let p = *offset as usize as *const std::ffi::c_void;
        call!(
            self,
            "glVertexAttribIPointer",
            fn(u32, i32, u32, i32, *const std::ffi::c_void) -> (),
            *index,
            *size,
            *attrib_type,
            *stride,
            p
        );
        Ok(())
    }

    pub(super) fn glGetVertexAttribIiv(&mut self, index: &GLuint, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        let mut v = [INT_SENTINEL; 4];
        call!(self, "glGetVertexAttribIiv", fn(u32, u32, *mut i32) -> (), *index, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetVertexAttribIuiv(&mut self, index: &GLuint, pname: &GLenum) -> Result<Vec<GLuint>, ClientError> {
        let mut v = [INT_SENTINEL as u32; 4];
        call!(self, "glGetVertexAttribIuiv", fn(u32, u32, *mut u32) -> (), *index, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL as u32).collect())
    }

    pub(super) fn glClearBufferfv(
        &mut self,
        buffer: &GLenum,
        drawbuffer: &GLint,
        values: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        let v: Vec<f32> = values.iter().collect();
        call!(self, "glClearBufferfv", fn(u32, i32, *const f32) -> (), *buffer, *drawbuffer, v.as_ptr());
        Ok(())
    }

    pub(super) fn glClearBufferiv(
        &mut self,
        buffer: &GLenum,
        drawbuffer: &GLint,
        values: &Slice<'_, GLint>,
    ) -> Result<(), ClientError> {
        let v: Vec<i32> = values.iter().collect();
        call!(self, "glClearBufferiv", fn(u32, i32, *const i32) -> (), *buffer, *drawbuffer, v.as_ptr());
        Ok(())
    }

    pub(super) fn glClearBufferuiv(
        &mut self,
        buffer: &GLenum,
        drawbuffer: &GLint,
        values: &Slice<'_, GLuint>,
    ) -> Result<(), ClientError> {
        let v: Vec<u32> = values.iter().collect();
        call!(self, "glClearBufferuiv", fn(u32, i32, *const u32) -> (), *buffer, *drawbuffer, v.as_ptr());
        Ok(())
    }

    pub(super) fn glGetFragDataLocation(&mut self, program: &GLuint, name: &Text<'_>) -> Result<GLint, ClientError> {
        let p = self.shader(*program);
        let name = std::ffi::CString::new(name.as_str()).map_err(|e| ClientError::Unsupported(e.to_string()))?;
        Ok(call!(self, "glGetFragDataLocation", fn(u32, *const i8) -> i32, p, name.as_ptr()))
    }

    pub(super) fn glGetUniformIndices(
        &mut self,
        program: &GLuint,
        count: &GLsizei,
        names: &Text<'_>,
    ) -> Result<Vec<GLuint>, ClientError> {
        let p = self.shader(*program);
        let owned = super::c_lines(names)?;
        let ptrs: Vec<*const i8> = owned.iter().map(|c| c.as_ptr()).collect();
        let mut out = vec![0xDEAD_BEEF_u32; ptrs.len()];
        call!(
            self,
            "glGetUniformIndices",
            fn(u32, i32, *const *const i8, *mut u32) -> (),
            p,
            *count,
            ptrs.as_ptr(),
            out.as_mut_ptr()
        );
        Ok(out)
    }

    pub(super) fn glGetActiveUniformsiv(
        &mut self,
        program: &GLuint,
        indices: &Slice<'_, GLuint>,
        pname: &GLenum,
    ) -> Result<Vec<GLint>, ClientError> {
        let p = self.shader(*program);
        let list: Vec<u32> = indices.iter().collect();
        let mut out = vec![i32::MIN; list.len()];
        call!(
            self,
            "glGetActiveUniformsiv",
            fn(u32, i32, *const u32, u32, *mut i32) -> (),
            p,
            list.len() as i32,
            list.as_ptr(),
            *pname,
            out.as_mut_ptr()
        );
        Ok(if out.contains(&i32::MIN) { Vec::new() } else { out })
    }
}

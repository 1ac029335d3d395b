//! The Mesa reference's arms for buffers, vertex attributes and draws.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::*;

impl Arms<'_> {
    pub(super) fn glBufferData(
        &mut self,
        target: &GLenum,
        size: &i64,
        data: &Option<Blob<'_>>,
        usage: &GLenum,
    ) -> Result<(), ClientError> {
        let p = opt_ptr(data);
        call!(self, "glBufferData", fn(u32, isize, *const u8, u32) -> (), *target, *size as isize, p, *usage);
        Ok(())
    }

    pub(super) fn glBufferSubData(
        &mut self,
        target: &GLenum,
        offset: &i64,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glBufferSubData",
            fn(u32, isize, isize, *const u8) -> (),
            *target,
            *offset as isize,
            data.len() as isize,
            data.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glDeleteBuffers(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let v = names.to_vec();
        call!(self, "glDeleteBuffers", fn(i32, *const u32) -> (), v.len() as i32, v.as_ptr());
        Ok(())
    }

    pub(super) fn glDrawElements(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        offset: &u64,
    ) -> Result<(), ClientError> {
        call!(self, "glDrawElements", fn(u32, i32, u32, usize) -> (), *mode, *count, *index_type, *offset as usize);
        Ok(())
    }

    // Names are the client's own: binding an unused name creates the object in ES 2.0.
    pub(super) fn glGenBuffers(&mut self, _names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        Ok(())
    }

    pub(super) fn glVertexAttrib1fv(&mut self, index: &GLuint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        let v = values.to_vec();
        if v.is_empty() {
            return Err(unsupported("glVertexAttrib1fv with fewer than 1 values"));
        }
        call!(self, "glVertexAttrib1fv", fn(u32, *const f32) -> (), *index, v.as_ptr());
        Ok(())
    }

    pub(super) fn glVertexAttrib2fv(&mut self, index: &GLuint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        let v = values.to_vec();
        if v.len() < 2 {
            return Err(unsupported("glVertexAttrib2fv with fewer than 2 values"));
        }
        call!(self, "glVertexAttrib2fv", fn(u32, *const f32) -> (), *index, v.as_ptr());
        Ok(())
    }

    pub(super) fn glVertexAttrib3fv(&mut self, index: &GLuint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        let v = values.to_vec();
        if v.len() < 3 {
            return Err(unsupported("glVertexAttrib3fv with fewer than 3 values"));
        }
        call!(self, "glVertexAttrib3fv", fn(u32, *const f32) -> (), *index, v.as_ptr());
        Ok(())
    }

    pub(super) fn glVertexAttrib4fv(&mut self, index: &GLuint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        let v = values.to_vec();
        if v.len() < 4 {
            return Err(unsupported("glVertexAttrib4fv with fewer than 4 values"));
        }
        call!(self, "glVertexAttrib4fv", fn(u32, *const f32) -> (), *index, v.as_ptr());
        Ok(())
    }

    pub(super) fn glVertexAttribPointer(
        &mut self,
        index: &GLuint,
        size: &GLint,
        attrib_type: &GLenum,
        normalized: &bool,
        stride: &GLsizei,
        offset: &u64,
    ) -> Result<(), ClientError> {
        self.client.insert(*index, ((*size, *attrib_type, *normalized, *stride), Vec::new()));
        call!(
            self,
            "glVertexAttribPointer",
            fn(u32, i32, u32, u8, i32, usize) -> (),
            *index,
            *size,
            *attrib_type,
            u8::from(*normalized),
            *stride,
            *offset as usize
        );
        Ok(())
    }

    pub(super) fn strataVertexAttribData(&mut self, index: &GLuint, data: &Blob<'_>) -> Result<(), ClientError> {
        let Some(((size, ty, norm, stride), bytes)) = self.client.get_mut(index) else {
            return Err(unsupported("client data for an attribute without a pointer"));
        };
        *bytes = data.as_bytes().to_vec();
        let (size, ty, norm, stride, ptr) = (*size, *ty, *norm, *stride, bytes.as_ptr());
        call!(
            self,
            "glVertexAttribPointer",
            fn(u32, i32, u32, u8, i32, *const u8) -> (),
            *index,
            size,
            ty,
            u8::from(norm),
            stride,
            ptr
        );
        Ok(())
    }

    pub(super) fn strataDrawElementsData(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        indices: &Blob<'_>,
    ) -> Result<(), ClientError> {
        call!(
            self,
            "glDrawElements",
            fn(u32, i32, u32, *const u8) -> (),
            *mode,
            *count,
            *index_type,
            indices.as_bytes().as_ptr()
        );
        Ok(())
    }

    pub(super) fn glDrawElementsBaseVertexOES(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        offset: &u64,
        base_vertex: &GLint,
    ) -> Result<(), ClientError> {
        let (m, c, t, o, b) = (*mode, *count, *index_type, *offset as usize, *base_vertex);
        call!(self, "glDrawElementsBaseVertexOES", fn(u32, i32, u32, usize, i32) -> (), m, c, t, o, b);
        Ok(())
    }

    pub(super) fn strataDrawElementsBaseVertexData(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        indices: &Blob<'_>,
        base_vertex: &GLint,
    ) -> Result<(), ClientError> {
        let (m, c, t, p, b) = (*mode, *count, *index_type, indices.as_bytes().as_ptr(), *base_vertex);
        call!(self, "glDrawElementsBaseVertexOES", fn(u32, i32, u32, *const u8, i32) -> (), m, c, t, p, b);
        Ok(())
    }

    pub(super) fn glMultiDrawArraysEXT(
        &mut self,
        mode: &GLenum,
        first: &Slice<'_, GLint>,
        count: &Slice<'_, GLsizei>,
        drawcount: &GLsizei,
    ) -> Result<(), ClientError> {
        let (f, c) = (padded(first, *drawcount), padded(count, *drawcount));
        let (m, n) = (*mode, *drawcount);
        call!(self, "glMultiDrawArraysEXT", fn(u32, *const i32, *const i32, i32) -> (), m, f.as_ptr(), c.as_ptr(), n);
        Ok(())
    }

    pub(super) fn glMultiDrawElementsEXT(
        &mut self,
        mode: &GLenum,
        count: &Slice<'_, GLsizei>,
        index_type: &GLenum,
        offsets: &Slice<'_, u64>,
        drawcount: &GLsizei,
    ) -> Result<(), ClientError> {
        let (c, o) = (padded(count, *drawcount), offsets_of(offsets, *drawcount));
        let (m, t, n) = (*mode, *index_type, *drawcount);
        call!(
            self,
            "glMultiDrawElementsEXT",
            fn(u32, *const i32, u32, *const usize, i32) -> (),
            m,
            c.as_ptr(),
            t,
            o.as_ptr(),
            n
        );
        Ok(())
    }

    pub(super) fn glMultiDrawElementsBaseVertexEXT(
        &mut self,
        mode: &GLenum,
        count: &Slice<'_, GLsizei>,
        index_type: &GLenum,
        offsets: &Slice<'_, u64>,
        drawcount: &GLsizei,
        base_vertex: &Slice<'_, GLint>,
    ) -> Result<(), ClientError> {
        let (c, o, b) = (padded(count, *drawcount), offsets_of(offsets, *drawcount), padded(base_vertex, *drawcount));
        let (m, t, n) = (*mode, *index_type, *drawcount);
        call!(
            self,
            "glMultiDrawElementsBaseVertexEXT",
            fn(u32, *const i32, u32, *const usize, i32, *const i32) -> (),
            m,
            c.as_ptr(),
            t,
            o.as_ptr(),
            n,
            b.as_ptr()
        );
        Ok(())
    }

    pub(super) fn glDrawArraysInstancedEXT(
        &mut self,
        mode: &GLenum,
        first: &GLint,
        count: &GLsizei,
        primcount: &GLsizei,
    ) -> Result<(), ClientError> {
        let (m, f, c, n) = (*mode, *first, *count, *primcount);
        call!(self, "glDrawArraysInstancedEXT", fn(u32, i32, i32, i32) -> (), m, f, c, n);
        Ok(())
    }

    pub(super) fn glDrawElementsInstancedEXT(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        offset: &u64,
        primcount: &GLsizei,
    ) -> Result<(), ClientError> {
        let (m, c, t, o, n) = (*mode, *count, *index_type, *offset as usize, *primcount);
        call!(self, "glDrawElementsInstancedEXT", fn(u32, i32, u32, usize, i32) -> (), m, c, t, o, n);
        Ok(())
    }

    pub(super) fn strataDrawElementsInstancedData(
        &mut self,
        mode: &GLenum,
        count: &GLsizei,
        index_type: &GLenum,
        indices: &Blob<'_>,
        primcount: &GLsizei,
    ) -> Result<(), ClientError> {
        let (m, c, t, p, n) = (*mode, *count, *index_type, indices.as_bytes().as_ptr(), *primcount);
        call!(self, "glDrawElementsInstancedEXT", fn(u32, i32, u32, *const u8, i32) -> (), m, c, t, p, n);
        Ok(())
    }

    pub(super) fn strataVertexAttribDataPacked(
        &mut self,
        index: &GLuint,
        attrib_type: &GLenum,
        data: &Blob<'_>,
    ) -> Result<(), ClientError> {
        let _ = (index, attrib_type, data);
        Err(unsupported(
            "strataVertexAttribDataPacked: the reference draws the application's own arrays, never a wire conversion",
        ))
    }

    pub(super) fn glGetBufferParameteriv(&mut self, target: &GLenum, pname: &GLenum) -> Result<GLint, ClientError> {
        let mut v = 0i32;
        call!(self, "glGetBufferParameteriv", fn(u32, u32, *mut i32) -> (), *target, *pname, &mut v);
        Ok(v)
    }

    pub(super) fn glGetVertexAttribfv(&mut self, index: &GLuint, pname: &GLenum) -> Result<Vec<GLfloat>, ClientError> {
        let mut v = [f32::from_bits(FLOAT_SENTINEL); 16];
        call!(self, "glGetVertexAttribfv", fn(u32, u32, *mut f32) -> (), *index, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
    }

    pub(super) fn glGetVertexAttribiv(&mut self, index: &GLuint, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        let mut v = [INT_SENTINEL; 16];
        call!(self, "glGetVertexAttribiv", fn(u32, u32, *mut i32) -> (), *index, *pname, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetVertexAttribPointerv(&mut self, index: &GLuint, pname: &GLenum) -> Result<u64, ClientError> {
        let mut p: *const u8 = std::ptr::null();
        call!(self, "glGetVertexAttribPointerv", fn(u32, u32, *mut *const u8) -> (), *index, *pname, &mut p);
        Ok(p as u64)
    }

    pub(super) fn glIsBuffer(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        Ok(call!(self, "glIsBuffer", fn(u32) -> u8, *name) != 0)
    }
}

/// A multi-draw's array, padded with zeros to the draw count so that Mesa reads only it.
fn padded(values: &Slice<'_, i32>, drawcount: i32) -> Vec<i32> {
    let mut v = values.to_vec();
    v.resize(v.len().max(drawcount.max(0) as usize), 0);
    v
}

/// A multi-draw's element-buffer offsets as the pointers GL takes, padded like [`padded`].
fn offsets_of(offsets: &Slice<'_, u64>, drawcount: i32) -> Vec<usize> {
    let mut v: Vec<usize> = offsets.iter().map(|o| o as usize).collect();
    v.resize(v.len().max(drawcount.max(0) as usize), 0);
    v
}

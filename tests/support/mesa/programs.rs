//! The Mesa reference's arms for shaders, programs and uniforms.

use strata_client::ClientError;
use strata_protocol::commands::*;
use strata_protocol::wire::*;

use super::*;

/// A `glUniform*v` call: `values` as `count` arrays of `n` components.
macro_rules! uniform_array {
    ($self:ident, $name:literal, $t:ty, $location:expr, $values:expr, $n:expr) => {{
        let v = $values.to_vec();
        call!($self, $name, fn(i32, i32, *const $t) -> (), *$location, v.len() as i32 / $n, v.as_ptr());
        Ok(())
    }};
}

/// A `glUniformMatrix*fv` call: `values` as `count` matrices of `n` floats.
macro_rules! uniform_matrices {
    ($self:ident, $name:literal, $location:expr, $transpose:expr, $values:expr, $n:expr) => {{
        let v = $values.to_vec();
        call!(
            $self,
            $name,
            fn(i32, i32, u8, *const f32) -> (),
            *$location,
            v.len() as i32 / $n,
            u8::from(*$transpose),
            v.as_ptr()
        );
        Ok(())
    }};
}

impl Arms<'_> {
    pub(super) fn glAttachShader(&mut self, program: &GLuint, shader: &GLuint) -> Result<(), ClientError> {
        let (p, s) = (self.shader(*program), self.shader(*shader));
        call!(self, "glAttachShader", fn(u32, u32) -> (), p, s);
        Ok(())
    }

    pub(super) fn glBindAttribLocation(
        &mut self,
        program: &GLuint,
        index: &GLuint,
        name: &Text<'_>,
    ) -> Result<(), ClientError> {
        let p = self.shader(*program);
        let n = cstr(name.as_str());
        call!(self, "glBindAttribLocation", fn(u32, u32, *const i8) -> (), p, *index, n.as_ptr());
        Ok(())
    }

    pub(super) fn glCompileShader(&mut self, shader: &GLuint) -> Result<(), ClientError> {
        let s = self.shader(*shader);
        call!(self, "glCompileShader", fn(u32) -> (), s);
        Ok(())
    }

    pub(super) fn glCreateProgram(&mut self, name: &GLuint) -> Result<(), ClientError> {
        let real = call!(self, "glCreateProgram", fn() -> u32,);
        self.shaders.insert(*name, real);
        Ok(())
    }

    pub(super) fn glCreateShader(&mut self, shader_type: &GLenum, name: &GLuint) -> Result<(), ClientError> {
        let real = call!(self, "glCreateShader", fn(u32) -> u32, *shader_type);
        self.shaders.insert(*name, real);
        Ok(())
    }

    pub(super) fn glDeleteProgram(&mut self, program: &GLuint) -> Result<(), ClientError> {
        let p = self.shader(*program);
        call!(self, "glDeleteProgram", fn(u32) -> (), p);
        Ok(())
    }

    pub(super) fn glDeleteShader(&mut self, shader: &GLuint) -> Result<(), ClientError> {
        let s = self.shader(*shader);
        call!(self, "glDeleteShader", fn(u32) -> (), s);
        Ok(())
    }

    pub(super) fn glDetachShader(&mut self, program: &GLuint, shader: &GLuint) -> Result<(), ClientError> {
        let (p, s) = (self.shader(*program), self.shader(*shader));
        call!(self, "glDetachShader", fn(u32, u32) -> (), p, s);
        Ok(())
    }

    pub(super) fn glLinkProgram(&mut self, program: &GLuint) -> Result<(), ClientError> {
        let p = self.shader(*program);
        call!(self, "glLinkProgram", fn(u32) -> (), p);
        Ok(())
    }

    pub(super) fn glShaderBinary(
        &mut self,
        shaders: &Slice<'_, GLuint>,
        binary_format: &GLenum,
        binary: &Blob<'_>,
    ) -> Result<(), ClientError> {
        let v: Vec<u32> = shaders.iter().map(|s| self.shader(s)).collect();
        let (format, bytes) = (*binary_format, binary.as_bytes());
        call!(
            self,
            "glShaderBinary",
            fn(i32, *const u32, u32, *const u8, i32) -> (),
            v.len() as i32,
            v.as_ptr(),
            format,
            bytes.as_ptr(),
            bytes.len() as i32
        );
        Ok(())
    }

    pub(super) fn glShaderSource(&mut self, shader: &GLuint, source: &Text<'_>) -> Result<(), ClientError> {
        let s = self.shader(*shader);
        let src = cstr(source.as_str());
        let p = src.as_ptr();
        call!(self, "glShaderSource", fn(u32, i32, *const *const i8, *const i32) -> (), s, 1, &p, std::ptr::null());
        Ok(())
    }

    pub(super) fn glUniform1fv(&mut self, location: &GLint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform1fv", f32, location, values, 1)
    }

    pub(super) fn glUniform1iv(&mut self, location: &GLint, values: &Slice<'_, GLint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform1iv", i32, location, values, 1)
    }

    pub(super) fn glUniform2fv(&mut self, location: &GLint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform2fv", f32, location, values, 2)
    }

    pub(super) fn glUniform2iv(&mut self, location: &GLint, values: &Slice<'_, GLint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform2iv", i32, location, values, 2)
    }

    pub(super) fn glUniform3fv(&mut self, location: &GLint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform3fv", f32, location, values, 3)
    }

    pub(super) fn glUniform3iv(&mut self, location: &GLint, values: &Slice<'_, GLint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform3iv", i32, location, values, 3)
    }

    pub(super) fn glUniform4fv(&mut self, location: &GLint, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform4fv", f32, location, values, 4)
    }

    pub(super) fn glUniform4iv(&mut self, location: &GLint, values: &Slice<'_, GLint>) -> Result<(), ClientError> {
        uniform_array!(self, "glUniform4iv", i32, location, values, 4)
    }

    pub(super) fn glUniformMatrix2fv(
        &mut self,
        location: &GLint,
        transpose: &bool,
        values: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        uniform_matrices!(self, "glUniformMatrix2fv", location, transpose, values, 4)
    }

    pub(super) fn glUniformMatrix3fv(
        &mut self,
        location: &GLint,
        transpose: &bool,
        values: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        uniform_matrices!(self, "glUniformMatrix3fv", location, transpose, values, 9)
    }

    pub(super) fn glUniformMatrix4fv(
        &mut self,
        location: &GLint,
        transpose: &bool,
        values: &Slice<'_, GLfloat>,
    ) -> Result<(), ClientError> {
        uniform_matrices!(self, "glUniformMatrix4fv", location, transpose, values, 16)
    }

    pub(super) fn glUseProgram(&mut self, program: &GLuint) -> Result<(), ClientError> {
        let p = self.shader(*program);
        call!(self, "glUseProgram", fn(u32) -> (), p);
        Ok(())
    }

    pub(super) fn glValidateProgram(&mut self, program: &GLuint) -> Result<(), ClientError> {
        let p = self.shader(*program);
        call!(self, "glValidateProgram", fn(u32) -> (), p);
        Ok(())
    }

    pub(super) fn glGetActiveAttrib(
        &mut self,
        program: &GLuint,
        index: &GLuint,
    ) -> Result<Option<ActiveVariable>, ClientError> {
        self.active_variable("glGetActiveAttrib", *program, *index)
    }

    pub(super) fn glGetActiveUniform(
        &mut self,
        program: &GLuint,
        index: &GLuint,
    ) -> Result<Option<ActiveVariable>, ClientError> {
        self.active_variable("glGetActiveUniform", *program, *index)
    }

    /// `glGetActiveAttrib` or `glGetActiveUniform` (`entry`, same C signature).
    pub(super) fn active_variable(
        &mut self,
        entry: &'static str,
        program: GLuint,
        index: GLuint,
    ) -> Result<Option<ActiveVariable>, ClientError> {
        let p = self.shader(program);
        let (mut len, mut size, mut ty) = (0i32, 0i32, 0u32);
        let mut buf = [0u8; 256];
        call!(
            self,
            entry,
            fn(u32, u32, i32, *mut i32, *mut i32, *mut u32, *mut u8) -> (),
            p,
            index,
            256,
            &mut len,
            &mut size,
            &mut ty,
            buf.as_mut_ptr()
        );
        Ok((len > 0).then(|| ActiveVariable {
            size,
            ty,
            name: String::from_utf8_lossy(&buf[..len as usize]).into_owned(),
        }))
    }

    pub(super) fn glGetAttachedShaders(&mut self, program: &GLuint) -> Result<Vec<GLuint>, ClientError> {
        let p = self.shader(*program);
        let mut real = [0u32; 64];
        let mut count = 0i32;
        call!(
            self,
            "glGetAttachedShaders",
            fn(u32, i32, *mut i32, *mut u32) -> (),
            p,
            64,
            &mut count,
            real.as_mut_ptr()
        );
        // Back to the client's names.
        Ok(real[..count.clamp(0, 64) as usize]
            .iter()
            .map(|r| self.shaders.iter().find(|(_, v)| *v == r).map_or(*r, |(c, _)| *c))
            .collect())
    }

    pub(super) fn glGetAttribLocation(&mut self, program: &GLuint, name: &Text<'_>) -> Result<GLint, ClientError> {
        let p = self.shader(*program);
        let n = cstr(name.as_str());
        Ok(call!(self, "glGetAttribLocation", fn(u32, *const i8) -> i32, p, n.as_ptr()))
    }

    pub(super) fn glGetProgramiv(&mut self, program: &GLuint, pname: &GLenum) -> Result<GLint, ClientError> {
        let p = self.shader(*program);
        let mut v = 0;
        call!(self, "glGetProgramiv", fn(u32, u32, *mut i32) -> (), p, *pname, &mut v);
        Ok(v)
    }

    pub(super) fn glGetProgramInfoLog(&mut self, program: &GLuint) -> Result<String, ClientError> {
        let p = self.shader(*program);
        self.log(p, true)
    }

    pub(super) fn glGetShaderiv(&mut self, shader: &GLuint, pname: &GLenum) -> Result<GLint, ClientError> {
        let s = self.shader(*shader);
        let mut v = 0;
        call!(self, "glGetShaderiv", fn(u32, u32, *mut i32) -> (), s, *pname, &mut v);
        Ok(v)
    }

    pub(super) fn glGetShaderInfoLog(&mut self, shader: &GLuint) -> Result<String, ClientError> {
        let s = self.shader(*shader);
        self.log(s, false)
    }

    pub(super) fn glGetShaderPrecisionFormat(
        &mut self,
        shader_type: &GLenum,
        precision_type: &GLenum,
    ) -> Result<([GLint; 2], GLint), ClientError> {
        let (mut range, mut precision) = ([0i32; 2], 0i32);
        call!(
            self,
            "glGetShaderPrecisionFormat",
            fn(u32, u32, *mut i32, *mut i32) -> (),
            *shader_type,
            *precision_type,
            range.as_mut_ptr(),
            &mut precision
        );
        Ok((range, precision))
    }

    pub(super) fn glGetShaderSource(&mut self, shader: &GLuint) -> Result<String, ClientError> {
        let s = self.shader(*shader);
        let mut len = 0i32;
        // GL_SHADER_SOURCE_LENGTH, with its NUL.
        call!(self, "glGetShaderiv", fn(u32, u32, *mut i32) -> (), s, 0x8B88, &mut len);
        let mut buf = vec![0u8; len.max(1) as usize];
        let mut got = 0i32;
        call!(
            self,
            "glGetShaderSource",
            fn(u32, i32, *mut i32, *mut u8) -> (),
            s,
            len.max(1),
            &mut got,
            buf.as_mut_ptr()
        );
        buf.truncate(got.max(0) as usize);
        Ok(String::from_utf8_lossy(&buf).into_owned())
    }

    pub(super) fn glGetUniformfv(&mut self, program: &GLuint, location: &GLint) -> Result<Vec<GLfloat>, ClientError> {
        let p = self.shader(*program);
        let mut v = [f32::from_bits(FLOAT_SENTINEL); 16];
        call!(self, "glGetUniformfv", fn(u32, i32, *mut f32) -> (), p, *location, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| x.to_bits() != FLOAT_SENTINEL).collect())
    }

    pub(super) fn glGetUniformiv(&mut self, program: &GLuint, location: &GLint) -> Result<Vec<GLint>, ClientError> {
        let p = self.shader(*program);
        let mut v = [INT_SENTINEL; 16];
        call!(self, "glGetUniformiv", fn(u32, i32, *mut i32) -> (), p, *location, v.as_mut_ptr());
        Ok(v.iter().copied().take_while(|x| *x != INT_SENTINEL).collect())
    }

    pub(super) fn glGetUniformLocation(&mut self, program: &GLuint, name: &Text<'_>) -> Result<GLint, ClientError> {
        let p = self.shader(*program);
        let n = cstr(name.as_str());
        Ok(call!(self, "glGetUniformLocation", fn(u32, *const i8) -> i32, p, n.as_ptr()))
    }

    pub(super) fn glIsProgram(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        // A name the reference never created is no object.
        let Some(&real) = self.shaders.get(name) else {
            return Ok(false);
        };
        Ok(call!(self, "glIsProgram", fn(u32) -> u8, real) != 0)
    }

    pub(super) fn glIsShader(&mut self, name: &GLuint) -> Result<bool, ClientError> {
        // A name the reference never created is no object.
        let Some(&real) = self.shaders.get(name) else {
            return Ok(false);
        };
        Ok(call!(self, "glIsShader", fn(u32) -> u8, real) != 0)
    }
}

impl Arms<'_> {
    pub(super) fn glProgramBinaryOES(
        &mut self,
        program: &GLuint,
        binary_format: &GLenum,
        length: &GLsizei,
        binary: &Blob<'_>,
    ) -> Result<(), ClientError> {
        let p = self.shader(*program);
        let b = binary.as_bytes();
        ext!(self, "glProgramBinaryOES", fn(u32, u32, *const u8, i32) -> (), p, *binary_format, b.as_ptr(), *length);
        Ok(())
    }

    pub(super) fn glGetProgramBinaryOES(
        &mut self,
        program: &GLuint,
        buf_size: &GLsizei,
    ) -> Result<Option<Option<(GLenum, Bytes)>>, ClientError> {
        let p = self.shader(*program);
        let mut buf = vec![0u8; (*buf_size).max(0) as usize];
        // Left at -1 where the call writes no length, 0 where it fails after writing it.
        let (mut len, mut format) = (-1i32, 0u32);
        ext!(
            self,
            "glGetProgramBinaryOES",
            fn(u32, i32, *mut i32, *mut u32, *mut u8) -> (),
            p,
            *buf_size,
            &mut len,
            &mut format,
            buf.as_mut_ptr()
        );
        buf.truncate(len.max(0) as usize);
        Ok(match len {
            ..0 => None,
            0 => Some(None),
            _ => Some(Some((format, Bytes(buf)))),
        })
    }
}

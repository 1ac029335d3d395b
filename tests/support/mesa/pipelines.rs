//! `GL_EXT_separate_shader_objects` forwarded to Mesa: the client's pipeline names mapped to
//! the ones Mesa generates, program names to Mesa's as everywhere.

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::{cstr, Arms, Ptr};

/// The `glProgramUniform*vEXT` arms: `values` as `count` elements of `n` components.
macro_rules! program_uniform_arms {
    ($( $name:ident : $t:ty, $n:literal; )*) => {
        impl Arms<'_> {
            $( pub(super) fn $name(&mut self, program: &GLuint, location: &GLint, values: &Slice<'_, $t>) -> Result<(), ClientError> {
                let (p, v) = (self.shader(*program), values.to_vec());
                ext!(self, stringify!($name), fn(u32, i32, i32, *const $t) -> (), p, *location, v.len() as i32 / $n, v.as_ptr());
                Ok(())
            } )*
        }
    };
}

/// The `glProgramUniformMatrix*fvEXT` arms: `values` as `count` matrices of `n` floats.
macro_rules! program_matrix_arms {
    ($( $name:ident : $n:literal; )*) => {
        impl Arms<'_> {
            $( pub(super) fn $name(&mut self, program: &GLuint, location: &GLint, transpose: &bool, values: &Slice<'_, GLfloat>) -> Result<(), ClientError> {
                let (p, v) = (self.shader(*program), values.to_vec());
                let (count, t) = (v.len() as i32 / $n, u8::from(*transpose));
                ext!(self, stringify!($name), fn(u32, i32, i32, u8, *const f32) -> (), p, *location, count, t, v.as_ptr());
                Ok(())
            } )*
        }
    };
}

program_uniform_arms! {
    glProgramUniform1fvEXT: f32, 1;
    glProgramUniform2fvEXT: f32, 2;
    glProgramUniform3fvEXT: f32, 3;
    glProgramUniform4fvEXT: f32, 4;
    glProgramUniform1ivEXT: i32, 1;
    glProgramUniform2ivEXT: i32, 2;
    glProgramUniform3ivEXT: i32, 3;
    glProgramUniform4ivEXT: i32, 4;
}

program_matrix_arms! {
    glProgramUniformMatrix2fvEXT: 4;
    glProgramUniformMatrix3fvEXT: 9;
    glProgramUniformMatrix4fvEXT: 16;
}

impl Arms<'_> {
    /// Mesa's name for the client's pipeline `n`.
    fn pipeline(&self, n: u32) -> u32 {
        self.pipelines.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    pub(super) fn glGenProgramPipelinesEXT(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        for n in names.iter() {
            let mut real = 0u32;
            ext!(self, "glGenProgramPipelinesEXT", fn(i32, *mut u32) -> (), 1, &mut real);
            self.pipelines.insert(n, real);
        }
        Ok(())
    }

    pub(super) fn glDeleteProgramPipelinesEXT(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let real: Vec<u32> = names.iter().map(|n| self.pipeline(n)).collect();
        ext!(self, "glDeleteProgramPipelinesEXT", fn(i32, *const u32) -> (), real.len() as i32, real.as_ptr());
        for n in names.iter() {
            self.pipelines.remove(&n);
        }
        Ok(())
    }

    pub(super) fn glBindProgramPipelineEXT(&mut self, pipeline: &GLuint) -> Result<(), ClientError> {
        let pl = self.pipeline(*pipeline);
        ext!(self, "glBindProgramPipelineEXT", fn(u32) -> (), pl);
        Ok(())
    }

    pub(super) fn glIsProgramPipelineEXT(&mut self, pipeline: &GLuint) -> Result<bool, ClientError> {
        let pl = self.pipeline(*pipeline);
        Ok(ext!(self, "glIsProgramPipelineEXT", fn(u32) -> u8, pl) != 0)
    }

    pub(super) fn glUseProgramStagesEXT(
        &mut self,
        pipeline: &GLuint,
        stages: &GLbitfield,
        program: &GLuint,
    ) -> Result<(), ClientError> {
        let (pl, p) = (self.pipeline(*pipeline), self.shader(*program));
        ext!(self, "glUseProgramStagesEXT", fn(u32, u32, u32) -> (), pl, *stages, p);
        Ok(())
    }

    pub(super) fn glActiveShaderProgramEXT(&mut self, pipeline: &GLuint, program: &GLuint) -> Result<(), ClientError> {
        let (pl, p) = (self.pipeline(*pipeline), self.shader(*program));
        ext!(self, "glActiveShaderProgramEXT", fn(u32, u32) -> (), pl, p);
        Ok(())
    }

    pub(super) fn glProgramParameteriEXT(
        &mut self,
        program: &GLuint,
        pname: &GLenum,
        value: &GLint,
    ) -> Result<(), ClientError> {
        let p = self.shader(*program);
        ext!(self, "glProgramParameteriEXT", fn(u32, u32, i32) -> (), p, *pname, *value);
        Ok(())
    }

    pub(super) fn glValidateProgramPipelineEXT(&mut self, pipeline: &GLuint) -> Result<(), ClientError> {
        let pl = self.pipeline(*pipeline);
        ext!(self, "glValidateProgramPipelineEXT", fn(u32) -> (), pl);
        Ok(())
    }

    pub(super) fn glCreateShaderProgramvEXT(
        &mut self,
        shader_type: &GLenum,
        name: &GLuint,
        source: &Text<'_>,
    ) -> Result<(), ClientError> {
        let src = cstr(source.as_str());
        let p = src.as_ptr();
        let real = ext!(self, "glCreateShaderProgramvEXT", fn(u32, i32, *const *const i8) -> u32, *shader_type, 1, &p);
        self.shaders.insert(*name, real);
        Ok(())
    }

    pub(super) fn glGetProgramPipelineivEXT(
        &mut self,
        pipeline: &GLuint,
        pname: &GLenum,
    ) -> Result<Vec<GLint>, ClientError> {
        let pl = self.pipeline(*pipeline);
        let mut v = i32::MIN;
        ext!(self, "glGetProgramPipelineivEXT", fn(u32, u32, *mut i32) -> (), pl, *pname, &mut v);
        if v == i32::MIN {
            return Ok(Vec::new());
        }
        // The stages' and the active program's names are the client's.
        const PROGRAMS: [u32; 3] = [0x8259, 0x8B31, 0x8B30];
        let client = self.shaders.iter().find(|(_, &r)| r as i32 == v && v != 0).map(|(&c, _)| c as i32);
        Ok(vec![if PROGRAMS.contains(pname) { client.unwrap_or(v) } else { v }])
    }

    pub(super) fn glGetProgramPipelineInfoLogEXT(&mut self, pipeline: &GLuint) -> Result<String, ClientError> {
        let pl = self.pipeline(*pipeline);
        let mut buf = vec![0u8; 4096];
        let mut len = 0i32;
        ext!(
            self,
            "glGetProgramPipelineInfoLogEXT",
            fn(u32, i32, *mut i32, *mut u8) -> (),
            pl,
            4096,
            &mut len,
            buf.as_mut_ptr()
        );
        buf.truncate(len.clamp(0, 4095) as usize);
        Ok(String::from_utf8_lossy(&buf).into_owned())
    }
}

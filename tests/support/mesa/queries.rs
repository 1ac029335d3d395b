//! `GL_EXT_occlusion_query_boolean` forwarded to Mesa, the client's query names mapped to the
//! ones Mesa generates (a name Mesa never generated stays one it does not know).

use strata_client::ClientError;
use strata_protocol::wire::*;

use super::{Arms, Ptr};

impl Arms<'_> {
    /// Mesa's name for the client's query `n`.
    fn query(&self, n: u32) -> u32 {
        self.queries.get(&n).copied().unwrap_or(if n == 0 { 0 } else { u32::MAX - n })
    }

    pub(super) fn glGenQueriesEXT(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        for n in names.iter() {
            let mut real = 0u32;
            ext!(self, "glGenQueriesEXT", fn(i32, *mut u32) -> (), 1, &mut real);
            self.queries.insert(n, real);
        }
        Ok(())
    }

    pub(super) fn glDeleteQueriesEXT(&mut self, names: &Slice<'_, GLuint>) -> Result<(), ClientError> {
        let real: Vec<u32> = names.iter().map(|n| self.query(n)).collect();
        ext!(self, "glDeleteQueriesEXT", fn(i32, *const u32) -> (), real.len() as i32, real.as_ptr());
        for n in names.iter() {
            self.queries.remove(&n);
        }
        Ok(())
    }

    pub(super) fn glIsQueryEXT(&mut self, id: &GLuint) -> Result<bool, ClientError> {
        let q = self.query(*id);
        Ok(ext!(self, "glIsQueryEXT", fn(u32) -> u8, q) != 0)
    }

    pub(super) fn glBeginQueryEXT(&mut self, target: &GLenum, id: &GLuint) -> Result<(), ClientError> {
        let q = self.query(*id);
        ext!(self, "glBeginQueryEXT", fn(u32, u32) -> (), *target, q);
        Ok(())
    }

    pub(super) fn glEndQueryEXT(&mut self, target: &GLenum) -> Result<(), ClientError> {
        ext!(self, "glEndQueryEXT", fn(u32) -> (), *target);
        Ok(())
    }

    pub(super) fn glGetQueryivEXT(&mut self, target: &GLenum, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        let mut v = i32::MIN;
        ext!(self, "glGetQueryivEXT", fn(u32, u32, *mut i32) -> (), *target, *pname, &mut v);
        // The client's name for the one Mesa answers.
        let client = self.queries.iter().find(|(_, &r)| r as i32 == v).map_or(v, |(&c, _)| c as i32);
        Ok(if v == i32::MIN { Vec::new() } else { vec![client] })
    }

    pub(super) fn glGetQueryObjectuivEXT(&mut self, id: &GLuint, pname: &GLenum) -> Result<Vec<GLuint>, ClientError> {
        let q = self.query(*id);
        let mut v = u32::MAX;
        ext!(self, "glGetQueryObjectuivEXT", fn(u32, u32, *mut u32) -> (), q, *pname, &mut v);
        Ok(if v == u32::MAX { Vec::new() } else { vec![v] })
    }

    pub(super) fn glGetQueryObjectivEXT(&mut self, id: &GLuint, pname: &GLenum) -> Result<Vec<GLint>, ClientError> {
        let q = self.query(*id);
        let mut v = i32::MIN;
        ext!(self, "glGetQueryObjectivEXT", fn(u32, u32, *mut i32) -> (), q, *pname, &mut v);
        Ok(if v == i32::MIN { Vec::new() } else { vec![v] })
    }

    pub(super) fn glGetQueryObjecti64vEXT(&mut self, id: &GLuint, pname: &GLenum) -> Result<Vec<i64>, ClientError> {
        let q = self.query(*id);
        let mut v = i64::MIN;
        ext!(self, "glGetQueryObjecti64vEXT", fn(u32, u32, *mut i64) -> (), q, *pname, &mut v);
        Ok(if v == i64::MIN { Vec::new() } else { vec![v] })
    }

    pub(super) fn glGetQueryObjectui64vEXT(&mut self, id: &GLuint, pname: &GLenum) -> Result<Vec<u64>, ClientError> {
        let q = self.query(*id);
        let mut v = u64::MAX;
        ext!(self, "glGetQueryObjectui64vEXT", fn(u32, u32, *mut u64) -> (), q, *pname, &mut v);
        Ok(if v == u64::MAX { Vec::new() } else { vec![v] })
    }

    pub(super) fn glGetInteger64vEXT(&mut self, pname: &GLenum) -> Result<Vec<i64>, ClientError> {
        let mut v = i64::MIN;
        ext!(self, "glGetInteger64vEXT", fn(u32, *mut i64) -> (), *pname, &mut v);
        Ok(if v == i64::MIN { Vec::new() } else { vec![v] })
    }

    pub(super) fn glQueryCounterEXT(&mut self, id: &GLuint, target: &GLenum) -> Result<(), ClientError> {
        let q = self.query(*id);
        ext!(self, "glQueryCounterEXT", fn(u32, u32) -> (), q, *target);
        Ok(())
    }

    pub(super) fn glBeginConditionalRenderNV(&mut self, id: &GLuint, mode: &GLenum) -> Result<(), ClientError> {
        let q = self.query(*id);
        ext!(self, "glBeginConditionalRenderNV", fn(u32, u32) -> (), q, *mode);
        Ok(())
    }

    pub(super) fn glEndConditionalRenderNV(&mut self) -> Result<(), ClientError> {
        ext!(self, "glEndConditionalRenderNV", fn() -> (),);
        Ok(())
    }
}

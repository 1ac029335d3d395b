//! The transport-only executor, for measuring the command stream without GL.

use strata_gles::execute::{ExecError, Executor};
use strata_protocol::{Command, Reply};

/// The transport-only executor: it answers Strata's own calls, stages every bulk payload the
/// way an upload would (one copy into daemon-owned memory), and reports every other
/// synchronous call as unsupported, because this build has no GLES back end.
#[derive(Default)]
pub struct Drain {
    staging: Vec<u8>,
    staged_bytes: u64,
}

impl Drain {
    /// Bulk bytes staged so far.
    pub fn staged_bytes(&self) -> u64 {
        self.staged_bytes
    }

    fn stage(&mut self, bytes: &[u8]) {
        self.staging.clear();
        self.staging.extend_from_slice(bytes);
        self.staged_bytes += bytes.len() as u64;
    }
}

impl Executor for Drain {
    fn execute(&mut self, cmd: Command<'_>) -> Result<Option<Reply>, ExecError> {
        let op = cmd.opcode();
        match &cmd {
            Command::Ping { token } => return Ok(Some(Reply::Ping(*token))),
            Command::BufferData { data: Some(d), .. }
            | Command::BufferSubData { data: d, .. }
            | Command::TexImage2D { pixels: Some(d), .. }
            | Command::TexSubImage2D { pixels: d, .. }
            | Command::CompressedTexImage2D { data: d, .. }
            | Command::CompressedTexSubImage2D { data: d, .. } => self.stage(d.as_bytes()),
            // Deliberately a catch-all: this executor measures transport, not GL. The GLES
            // executor's dispatch is generated from the command table and has no such arm.
            _ => {}
        }
        Ok(op
            .is_sync()
            .then(|| Reply::Unsupported(format!("{} needs the GLES executor, which this build lacks", op.name()))))
    }
}

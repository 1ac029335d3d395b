//! The transport-only executor, for measuring the command stream without GL.

use strata_gles::execute::{ExecError, Executor};
use strata_protocol::{Blob, Command, Opcode, Reply};

/// The transport-only executor: it answers Strata's own calls, stages every bulk payload the
/// way an upload would (one copy into daemon-owned memory: a streamed blob straight from the
/// ring), and reports every other synchronous call as unsupported, because this build has no
/// GLES back end.
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

    fn stage(&mut self, blob: &Blob<'_>) -> Result<(), ExecError> {
        // Kept between payloads, as a staging belt is: only growth is zeroed.
        self.staging.resize(blob.len(), 0);
        blob.read_into(&mut self.staging).map_err(|e| ExecError(e.to_string()))?;
        self.staged_bytes += blob.len() as u64;
        Ok(())
    }
}

/// The commands whose payload the executor stages.
const STAGED: &[Opcode] = &[
    Opcode::BufferData,
    Opcode::BufferSubData,
    Opcode::TexImage2D,
    Opcode::TexSubImage2D,
    Opcode::CompressedTexImage2D,
    Opcode::CompressedTexSubImage2D,
];

impl Executor for Drain {
    fn streams(&self, op: Opcode) -> bool {
        STAGED.contains(&op)
    }

    fn execute(&mut self, cmd: Command<'_>) -> Result<Option<Reply>, ExecError> {
        let op = cmd.opcode();
        match &cmd {
            Command::Ping { token } => return Ok(Some(Reply::Ping(*token))),
            Command::BufferData { data: Some(d), .. }
            | Command::BufferSubData { data: d, .. }
            | Command::TexImage2D { pixels: Some(d), .. }
            | Command::TexSubImage2D { pixels: d, .. }
            | Command::CompressedTexImage2D { data: d, .. }
            | Command::CompressedTexSubImage2D { data: d, .. } => self.stage(d)?,
            // Deliberately a catch-all: this executor measures transport, not GL. The GLES
            // executor's dispatch is generated from the command table and has no such arm.
            _ => {}
        }
        Ok(op
            .is_sync()
            .then(|| Reply::Unsupported(format!("{} needs the GLES executor, which this build lacks", op.name()))))
    }
}

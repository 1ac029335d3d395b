//! What a session does with each decoded command.

use strata_protocol::{Command, Opcode, Reply};

/// A failure that ends the client's session (GL misuse is not one: it becomes a GL error).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct ExecError(pub String);

/// Runs one client's decoded commands.
pub trait Executor: Send {
    /// Executes `cmd`; synchronous commands return their reply.
    fn execute(&mut self, cmd: Command<'_>) -> Result<Option<Reply>, ExecError>;

    /// Refuses a command of `op` without executing it (it exceeded the client's quota, which
    /// `why` says); synchronous commands still get a reply.
    fn refuse(&mut self, op: Opcode, why: &str) -> Option<Reply> {
        op.is_sync().then(|| Reply::Unsupported(format!("{} refused: {why}", op.name())))
    }

    /// Whether the executor reads a streamed blob of `op` itself, straight from the ring into
    /// its destination ([`strata_protocol::Blob::read_into`]); for any other command the
    /// session reads the blob into the daemon's memory first, and the executor sees its bytes.
    fn streams(&self, op: Opcode) -> bool {
        let _ = op;
        false
    }
}

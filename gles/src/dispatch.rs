//! What happens to every command before its handler runs, and the dispatch onto the handlers.
//!
//! - **Error scope.** Everything a command does on the device runs inside a wgpu validation
//!   scope; an error caught there (or in a pass flushed meanwhile) is logged against this client
//!   and recorded as `GL_OUT_OF_MEMORY`.
//! - **No current context.** GL calls without a current context have no effect; synchronous
//!   ones still get an answer (`Reply::Unsupported`), so the client never waits forever.
//! - **Flush rule.** A call that rewrites a buffer or texture a recorded draw may read first
//!   submits the pending pass, so the draw reads the old contents, as GL orders it. The table
//!   marks such calls `[Flush]`; their handlers are handed a [`Flushed`] proof, which the
//!   functions that write images and buffers require, so a handler that writes without the
//!   attribute does not compile.
//! - **ES 3.0's calls** (`[Es3]` in the table) in an ES 2.0 context record
//!   `GL_INVALID_OPERATION` and do nothing, as Mesa's dispatch answers them (`version`).
//! - **Dispatch.** The match is generated from the protocol's command table
//!   (`strata_protocol::command_table!`): each command calls the handler method named like its
//!   `Calls` method (`glBufferData`, `eglSwapBuffers`, `strataPing`) with its fields. A command
//!   without a handler does not compile. Asynchronous GL handlers return `GlResult<()>`, whose
//!   error is recorded here; synchronous handlers return the reply's value.

use strata_protocol::commands::*;
use strata_protocol::wire::*;
use strata_protocol::Opcode;
use tracing::warn;

use crate::context::Context;
use crate::error::{GlError, GlResult};
use crate::execute::{ExecError, Executor};
use crate::flushed::Flushed;
use crate::GlesExecutor;

/// One handler's call, as its attributes say: a `[Context]` command's handler is handed the
/// current context (`None` when there is none), a `[Context, Flush]` command's also the proof
/// that the pending pass was submitted first ([`Flushed`]), a `[NoContext]` command's runs on
/// the executor alone. Any other list of attributes does not compile.
macro_rules! handler_call {
    ($exec:ident . $gl:ident [Context] ( $( $arg:ident ),* )) => {
        $exec.with_current(|exec, ctx| exec.$gl(ctx, $( $arg ),*))
    };
    ($exec:ident . $gl:ident [Context, Flush] ( $( $arg:ident ),* )) => {
        $exec.with_current(|exec, ctx| {
            let flushed = exec.flush_first();
            exec.$gl(ctx, &flushed, $( $arg ),*)
        })
    };
    ($exec:ident . $gl:ident [Context, Es3] ( $( $arg:ident ),* )) => {
        $exec.with_current(|exec, ctx| {
            if ctx.es3() { exec.$gl(ctx, $( $arg ),*) } else { crate::version::not_in_es2(ctx) }
        })
    };
    ($exec:ident . $gl:ident [Context, Flush, Es3] ( $( $arg:ident ),* )) => {
        $exec.with_current(|exec, ctx| {
            if !ctx.es3() {
                return crate::version::not_in_es2(ctx);
            }
            let flushed = exec.flush_first();
            exec.$gl(ctx, &flushed, $( $arg ),*)
        })
    };
    ($exec:ident . $gl:ident [NoContext] ( $( $arg:ident ),* )) => {
        Some($exec.$gl($( $arg ),*))
    };
    ($exec:ident . $gl:ident [ $( $other:ident ),* ] $args:tt) => {
        compile_error!(concat!(
            stringify!($gl),
            ": the dispatch knows [Context], [Context, Flush], either with Es3, and [NoContext], not [",
            $( stringify!($other), " ", )* "]"
        ))
    };
}

/// Generates `GlesExecutor::dispatch` from the command table.
macro_rules! gles_dispatch {
    (
        async { $( $agl:ident [ $($aat:ident),+ ] => $av:ident { $( $af:ident : $aty:ty ),* } ; )* }
        sync { $( $sgl:ident [ $($sat:ident),+ ] => $sv:ident { $( $sf:ident : $sty:ty ),* } -> $ret:ty ; )* }
    ) => {
        impl GlesExecutor {
            /// Runs `cmd`'s handler; synchronous commands return their reply.
            fn dispatch(&mut self, cmd: Command<'_>) -> Option<Reply> {
                match cmd {
                    $( Command::$av { $( $af ),* } => {
                        let result: Option<GlResult> = handler_call!(self . $agl [ $($aat),+ ] ( $( $af ),* ));
                        if let Some(Err(e)) = result {
                            self.record(e);
                        }
                        None
                    } )*
                    $( Command::$sv { $( $sf ),* } => {
                        let value: Option<$ret> = handler_call!(self . $sgl [ $($sat),+ ] ( $( $sf ),* ));
                        Some(match value {
                            Some(v) => Reply::$sv(v),
                            None => Reply::Unsupported(concat!(stringify!($sgl), ": no current context").into()),
                        })
                    } )*
                }
            }
        }
    };
}

strata_protocol::command_table!(gles_dispatch);

impl Executor for GlesExecutor {
    fn execute(&mut self, cmd: Command<'_>) -> Result<Option<Reply>, ExecError> {
        let op = cmd.opcode();
        if self.gpu.is_lost() {
            // Only this client's device: it is told by the end of its session, and every
            // other client and the compositor go on.
            return Err(ExecError("its GPU device was lost".into()));
        }
        // Everything a command does on the device is charged to this client.
        let scope = self.gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let reply = if self.current.is_none() && op.needs_context() {
            // No current context: GL calls have no effect. Queries still get an answer.
            op.is_sync().then(|| Reply::Unsupported(format!("{}: no current context", op.name())))
        } else {
            // Debug messages about the errors a call records name it.
            if let Some(ctx) = self.current.and_then(|(c, _)| self.contexts.get_mut(&c)) {
                ctx.call = op.name();
            }
            self.dispatch(cmd)
        };
        let caught = pollster::block_on(scope.pop());
        if caught.is_some() || !self.r.errors.is_empty() {
            self.charge(caught);
        }
        self.publish_usage();
        Ok(reply)
    }

    fn refuse(&mut self, op: Opcode, why: &str) -> Option<Reply> {
        self.record(GlError::OutOfMemory);
        op.is_sync().then(|| Reply::Unsupported(format!("{} refused: {why}", op.name())))
    }

    fn streams(&self, op: Opcode) -> bool {
        // Their blobs go from the ring straight into the buffer's shadow.
        matches!(op, Opcode::BufferData | Opcode::BufferSubData)
    }
}

impl GlesExecutor {
    /// Runs `f` with the current context, taken out of the table meanwhile so that the
    /// handler holds it beside the executor; `None` when no context is current.
    fn with_current<R>(&mut self, f: impl FnOnce(&mut Self, &mut Context) -> R) -> Option<R> {
        let (cid, _) = self.current?;
        let mut ctx = self.contexts.remove(&cid)?;
        let result = f(self, &mut ctx);
        self.contexts.insert(cid, ctx);
        Some(result)
    }

    /// Submits the pending pass, if any, for a `[Flush]` command: the proof it did.
    fn flush_first(&mut self) -> Flushed {
        if self.r.pending() {
            self.r.flush();
        }
        Flushed::after_flush()
    }

    /// Records `e` in the current context, if there is one.
    pub(super) fn record(&mut self, e: GlError) {
        if let Some(ctx) = self.current.and_then(|(c, _)| self.contexts.get_mut(&c)) {
            ctx.record(e);
        }
    }

    /// A fresh id for cache keys (images, targets, programs).
    pub(super) fn next_uid(&mut self) -> u64 {
        self.uid += 1;
        self.uid
    }

    /// Logs every GPU error caught since the last command against this client and records
    /// `GL_OUT_OF_MEMORY` (after which GL leaves the state undefined, as a lost GPU would).
    fn charge(&mut self, extra: Option<wgpu::Error>) {
        let mut errors = std::mem::take(&mut self.r.errors);
        errors.extend(extra.map(|e| crate::error::error_chain(&e)));
        for e in errors {
            // The log target is the one operators' filters (and the misuse test) match.
            warn!(target: "strata_gles::state", "GPU validation error charged to this client: {e}");
            self.record(GlError::OutOfMemory);
        }
    }

    #[allow(non_snake_case)]
    pub(super) fn strataPing(&mut self, token: u64) -> u64 {
        token
    }

    #[allow(non_snake_case)]
    pub(super) fn strataStats(&mut self) -> ExecStats {
        ExecStats { pipeline_cache_misses: self.r.pipeline_misses, render_passes: self.r.passes, draws: self.r.draws }
    }

    /// The session answers `strataVerify` from its own stream tally before commands reach an
    /// executor; an executor keeps none, so it answers as a session without a tally does.
    #[allow(non_snake_case)]
    pub(super) fn strataVerify(&mut self, _ctx: &mut Context, _commands: u64, _crc32: u32) -> StreamTally {
        StreamTally { commands: 0, crc32: 0, matches: false }
    }
}

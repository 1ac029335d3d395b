//! Strata's wire protocol: the command set (defined once, in [`commands`]), the codec, the
//! shared-memory ring and segment, and the control-socket handshake.
#![warn(missing_docs)]

pub mod codec;
mod command_set;
pub mod commands;
pub mod control;
pub mod events;
pub mod fd_passing;
pub mod futex;
pub mod handshake;
pub mod input;
pub mod json_control;
pub mod projection;
pub mod properties;
pub mod replies;
pub mod ring;
pub mod segment;
pub mod surface_id;
pub mod tally;
pub mod window;
pub mod wire;

pub use command_set::Attribute;
pub use commands::{
    ActiveVariable, Bytes, Calls, Command, DebugMessage, EglResult, ExecStats, Opcode, Reply, ReplyMismatch,
    StreamTally,
};
pub use wire::{Blob, Slice, Text};

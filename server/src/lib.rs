//! stratad: accepts clients on a Unix socket, gives each a shared-memory segment and a decoder
//! thread, and runs their command streams.
#![warn(missing_docs)]

pub mod executor;
pub mod listener;
pub mod session;

pub use listener::{serve, DeviceMode, ExecutorKind, ServeOptions, ServerError};
pub mod compositor;
pub mod demo;
pub mod gles;
pub mod gpu;
pub mod identity;
pub mod input;
pub mod layout;
pub mod quota;
pub mod root;
pub mod scene;
pub mod schedule;
pub mod stats;
pub mod systemd;
pub mod window;

//! stratad: accepts clients on a Unix socket, gives each a shared-memory segment and a decoder
//! thread, and runs their command streams on the GLES executor (`strata-gles`), whose window
//! surfaces the scene (`strata-scene`) hands to the compositor (`strata-compositor`).
#![warn(missing_docs)]

pub mod drain;
pub mod listener;
pub mod session;

pub use listener::{serve, DeviceMode, ExecutorKind, ServeOptions, ServerError};
pub mod caps;
pub mod credentials;
pub mod demo;
pub mod identity;
pub mod input;
pub mod layout;
pub mod quota;
pub mod schedule;
pub mod stats;
pub mod systemd;

//! The client side of Strata: connect to `stratad`, then call typed EGL/GLES methods (from
//! [`strata_protocol::Calls`]) that are encoded straight into the shared-memory ring.
#![warn(missing_docs)]

pub mod connection;
pub mod control;
pub mod error;
pub mod input;
pub mod setup;
pub mod vertex_wire;
pub mod workload;

pub use connection::{ConnectOptions, Connection};
pub use control::ControlConnection;
pub use error::ClientError;
pub use strata_protocol::Calls;

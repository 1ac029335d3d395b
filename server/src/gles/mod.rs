//! The GLES 2.0 executor: runs one client's EGL/GLES command stream on wgpu.
//!
//! GL misuse never reaches wgpu: every call is validated against the client's GL state first,
//! and an invalid one records the GL error and changes nothing, as a driver would. What does
//! reach wgpu runs inside error scopes, so a wgpu validation error is logged against this client
//! and never panics the daemon.

pub mod egl;
pub mod enums;
pub mod glsl;
pub mod objects;
pub mod render;
mod state;

pub use state::GlesExecutor;

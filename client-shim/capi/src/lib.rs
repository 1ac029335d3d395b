//! A drop-in `libEGL.so.1` and `libGLESv2.so.2`: the EGL 1.4 and GLES 2.0 C ABI, implemented
//! by streaming every call to `stratad` through [`strata_client::Connection`].
//!
//! One shared object provides both libraries (`tools/build-shim` installs it under both names).
//! Every entry point is `extern "C"`, catches panics, and checks the application's pointers for
//! null. Calls that map one-to-one onto a protocol command are generated from the table in
//! [`gl::simple`]; the rest marshal pointers by hand.
//!
//! The modules form layers, and none uses a module of a layer above its own:
//!
//! - the C types (`types`), how an entry point runs (`entry`: the panic guard and the
//!   `entry_points!` macro), Xlib, input delivery and glvnd's dispatch table;
//! - the state: a context's client-side GL state (`gl_state`), then the process's and each
//!   thread's (`state`);
//! - the plumbing: on the EGL side displays and the daemon connection, surfaces and contexts;
//!   on the GL side [`gl`] itself (`with_gl` and the marshalling functions) with the debug
//!   callback's delivery and the pixel layouts;
//! - the entry points: [`egl`], [`sync`] and [`image`] on the EGL side, and the modules under
//!   [`gl`], one per family or extension;
//! - [`registry`], which lists every module of entry points once and answers
//!   `eglGetProcAddress` and `glXGetProcAddress` from that list.
#![allow(non_snake_case, clippy::missing_safety_doc)]
#![warn(missing_docs)]

mod context;
mod display;
pub mod egl;
mod entry;
pub mod gl;
mod gl_state;
mod glvnd;
pub mod image;
mod input;
mod pixmap;
pub mod registry;
mod state;
mod surface;
pub mod sync;
mod types;
mod x11;

pub use types::*;

//! The device layer: GPU devices (each on an instance of its own), their opening at a class's
//! priority, memory one device exports and another imports, the threads' scheduling, the one
//! door through which work reaches a queue ([`Lane`]), and each client's account of what it
//! holds. Nothing here knows OpenGL ES or the compositor.
#![warn(missing_docs)]

pub mod account;
mod gpu;
mod lane;
mod marks;
mod open;
mod passes;
mod process;
mod readback;
mod share;
mod threads;

pub use gpu::{Gpu, GpuError};
pub use lane::Lane;
pub use open::{priority_name, DeviceOptions};
pub use passes::{
    descriptor_2d, fullscreen_pass, fullscreen_pass_at, texture_entry, uniform_entry, VertexInput, SRGB_VIEW,
    UNFILTERED,
};
pub use process::{keep_freed_memory, settle_environment, MMAP_THRESHOLD, RASTERIZER_THREADS, TRIM_THRESHOLD};
pub use share::{shared_usage, DeviceIdentity, Exported, ShareError};
pub use threads::{
    nice_for, set_thread_class, set_thread_idle, set_thread_nice, set_thread_realtime, set_thread_slice, slice_for,
    HIGH_SLICE,
};

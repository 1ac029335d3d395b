//! The objects a client's GL contexts and EGL display hold, as plain data with the few
//! operations on themselves: the bottom layer of the executor, which imports nothing from the
//! handlers above it.

pub mod buffer;
pub mod debug;
pub mod egl_image;
pub mod framebuffer;
pub mod image;
pub mod pipeline;
pub mod program;
pub mod query;
pub mod sampler;
pub mod surface;
pub mod texture;
pub mod vertex_array;
pub mod window;
pub mod xfb;

//! Every limit the executor holds a client to, in one place: what programs query (`GL_MAX_*`),
//! how many objects of a kind one context may hold, and the daemon's own bounds on one call.

use strata_device::Gpu;

// What programs query.

/// `GL_MAX_VERTEX_ATTRIBS`.
pub const MAX_ATTRIBS: usize = 16;
/// Texture units (`GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS`): ES 3.0's minimum of 32.
pub const MAX_UNITS: usize = 32;
/// Texture units one stage may sample (`GL_MAX_TEXTURE_IMAGE_UNITS`,
/// `GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS`).
pub const MAX_STAGE_UNITS: usize = 16;
/// Colour attachments and draw buffers (`GL_EXT_draw_buffers`).
pub const MAX_DRAW_BUFFERS: usize = strata_protocol::commands::MAX_DRAW_BUFFERS as usize;
/// Largest texture, renderbuffer, viewport and surface dimension.
pub const MAX_TEXTURE: u32 = 8192;
/// Largest point size (`GL_ALIASED_POINT_SIZE_RANGE`): points are drawn as squares of two
/// triangles, so any size rasterises; this bounds what a shader can ask for.
pub const MAX_POINT_SIZE: f32 = 1024.0;
/// The largest mip level an image may be specified at (log2 of the maximum size).
pub const MAX_LEVEL: i32 = 13;
/// `GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT`: wgpu's largest anisotropy clamp (and Mesa's value).
pub const MAX_ANISOTROPY: f32 = 16.0;
/// Varying vectors a program may use: `GL_MAX_VARYING_VECTORS`.
pub const MAX_VARYING_VECTORS: u32 = 15;
/// `GL_MAX_DEBUG_LOGGED_MESSAGES_KHR`.
pub const MAX_LOGGED: usize = 64;
/// `GL_MAX_DEBUG_GROUP_STACK_DEPTH_KHR` (the default group included).
pub const MAX_GROUP_DEPTH: usize = 64;

/// `GL_MAX_3D_TEXTURE_SIZE_OES`: Mesa's 2048, or less where the device allows less.
pub fn max_3d_size(gpu: &Gpu) -> u32 {
    2048.min(gpu.limits.max_texture_dimension_3d)
}

/// The last level a 3D image may have (log2 of [`max_3d_size`]).
pub fn max_3d_level(gpu: &Gpu) -> i32 {
    31 - max_3d_size(gpu).max(1).leading_zeros() as i32
}

/// `GL_MAX_ARRAY_TEXTURE_LAYERS` (ES 3.0): ES 3.0's least, 256, where the device has that many.
pub fn max_array_layers(gpu: &Gpu) -> u32 {
    256.min(gpu.limits.max_texture_array_layers)
}

// Objects one context (or client) may hold beyond its quota's counts.

/// Query objects one context may hold: each may hold device query sets, so a client that
/// asks for more is told `GL_OUT_OF_MEMORY` (applications use tens).
pub const MAX_QUERIES: u64 = 16_384;
/// Program pipelines one context may hold: each may keep a linked executable, so a client
/// that asks for more is told `GL_OUT_OF_MEMORY` (applications use a handful).
pub const MAX_PIPELINES: u64 = 4096;
/// EGLImages one client may hold at once.
pub const MAX_IMAGES: usize = 65_536;
/// Reversed-Z stages one surface keeps (by linked program) before it forgets them all.
pub const MAX_REVERSED_STAGES: usize = 64;
/// Debug messages kept for the client's callback between two drains; later ones are dropped.
pub const MAX_PENDING: usize = 4096;
/// Message ids one debug group's rules may list in all (a quota, like every per-client
/// resource).
pub const MAX_RULE_IDS: usize = 1 << 16;

// The daemon's own bounds on one call.

/// The most bytes of converted vertex data one attribute of one draw may need.
pub const MAX_CONVERTED: usize = 256 << 20;
/// The most a buffer map answers: the mapped bytes travel in one reply.
pub const MAX_MAP: usize = strata_protocol::codec::MAX_MESSAGE_LEN / 2;
/// The largest `glReadPixels` reply: half the protocol's message limit.
pub const MAX_READ_BYTES: usize = strata_protocol::codec::MAX_MESSAGE_LEN / 2;
/// The longest varying array: more than all varying vectors together (checked at link), so
/// that no valid shader is refused, and small enough that its slots are cheap to list.
pub const MAX_VARYING_ARRAY: u32 = 256;
/// The largest uniform block: wgpu's guaranteed uniform binding size (64 KiB, 4096 vectors,
/// far above the 512 that `MAX_VERTEX_UNIFORM_VECTORS` + `MAX_FRAGMENT_UNIFORM_VECTORS` allow).
pub const MAX_BLOCK: u32 = 64 << 10;
/// The samples of every multisample image (`GL_MAX_SAMPLES`, and the one count
/// `glGetInternalformativ` lists): wgpu's one multisample count beyond 1 that every device has.
pub const SAMPLES: u32 = 4;
/// Samplers a program may declare (sampler sets are kept as 32-bit masks: depth-texture layouts).
pub const MAX_SAMPLERS: usize = 32;

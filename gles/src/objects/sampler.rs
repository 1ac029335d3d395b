//! A sampler object (ES 3.0): sampling state that, bound to a texture unit, overrides the
//! state of the textures read through that unit (all but their levels).

use crate::objects::texture::SamplerState;

/// A sampler object.
#[derive(Default)]
pub struct Sampler {
    /// Its filters, wraps, anisotropy, level-of-detail clamps and comparison (its levels are
    /// unused: a texture's always count).
    pub state: SamplerState,
    /// `GL_TEXTURE_BORDER_COLOR_EXT`, as set.
    pub border: [f32; 4],
}

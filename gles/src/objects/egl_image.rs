//! An EGLImage: a texture level's or renderbuffer's image, shared by its siblings.

use std::sync::Arc;

use strata_device::account::Reservation;

use crate::formats::Storage;
use crate::objects::image::Subresource;

/// An EGLImage: one level of one layer of a colour image.
pub struct EglImage {
    /// The wgpu texture it lies in.
    pub(crate) texture: wgpu::Texture,
    /// Which level and layer.
    pub(crate) at: Subresource,
    /// Width and height.
    pub(crate) size: (u32, u32),
    /// How the texels are kept (RGBA8, RGBA16F or RGBA32F).
    pub(crate) storage: Storage,
    /// Whether it can be filtered linearly.
    pub(crate) filterable: bool,
    /// The GL format of the source (`RGBA`, `RGB565`, …), which siblings take.
    pub(crate) format: u32,
    /// The memory, held until the last sibling and the image are gone.
    pub(crate) reserved: Arc<Reservation>,
    /// Whether it is a cube map's face, which (as on Mesa) a renderbuffer takes and a texture
    /// does not.
    pub(crate) face: bool,
}

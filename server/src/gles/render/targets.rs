//! Render targets: the images a draw, clear or read addresses.

/// Colour format of every colour target and texture.
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// A render target: what framebuffer 0 or a framebuffer object resolves to.
#[derive(Clone)]
pub struct Target {
    /// Identity for pass batching (surface or attachment ids).
    pub key: (u64, u64),
    /// Colour image: texture and single-level view.
    pub color: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// Depth/stencil view and its format.
    pub depth: Option<(wgpu::TextureView, wgpu::TextureFormat)>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The colour buffer has no alpha (an RGB renderbuffer or texture): alpha reads as 1, so
    /// draws leave it alone and clears set it to 1.
    pub opaque: bool,
}

impl Target {
    /// Whether the depth/stencil format has a depth aspect (a `STENCIL_INDEX8` attachment
    /// alone has none, and the depth test then passes as with no depth buffer).
    pub fn has_depth(&self) -> bool {
        matches!(self.depth, Some((_, f)) if f.has_depth_aspect())
    }

    /// Whether the depth/stencil format has a stencil aspect.
    pub fn has_stencil(&self) -> bool {
        matches!(self.depth, Some((_, f)) if f.has_stencil_aspect())
    }
}

//! Render targets: the images a draw, clear or read addresses.

use crate::formats::HALF_FORMAT;
use crate::objects::image::Subresource;

/// A render target: what framebuffer 0 or a framebuffer object resolves to.
#[derive(Clone)]
pub struct Target {
    /// Identity for pass batching (surface or attachment ids).
    pub key: (u64, u64),
    /// Colour image: texture and single-level view. For draws it is what fragment output 0
    /// writes; for reads, the read buffer.
    pub color: Option<(wgpu::Texture, wgpu::TextureView)>,
    /// The level and layer of the colour texture the view shows, which reads and copies
    /// address: (0, 0) but for a texture's level above 0, a cube face, or an EGLImage's.
    pub color_at: Subresource,
    /// What fragment outputs 1, 2, … write (`GL_EXT_draw_buffers`): a view, the channels its
    /// format lacks and its format, `None` for an output that writes nothing; empty for one
    /// colour image.
    pub more: Vec<Option<(wgpu::TextureView, wgpu::ColorWrites, wgpu::TextureFormat)>>,
    /// Whether the colour view is the sRGB view of its image (`EGL_KHR_gl_colorspace`): the
    /// first slot's format is then the image's with the sRGB suffix.
    pub srgb: bool,
    /// Per colour slot, the slice of a 3D image its view shows (`GL_OES_texture_3D`), which
    /// the render pass names; `None` (or no entry) for 2D images.
    pub slices: Vec<Option<u32>>,
    /// Depth/stencil view and its format.
    pub depth: Option<(wgpu::TextureView, wgpu::TextureFormat)>,
    /// The depth/stencil image itself, its array layer (a cube face) and its mip level, which
    /// reads of depth and stencil address.
    pub depth_image: Option<(wgpu::Texture, u32, u32)>,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The channels the colour buffer's format lacks (alpha of RGB, and green and blue of
    /// `GL_EXT_texture_rg`'s RED and RG): they read as 0 (colour) and 1 (alpha), so draws
    /// leave them alone and clears set them to those values.
    pub absent: wgpu::ColorWrites,
    /// The samples of every image (a complete framebuffer's all have the same): 1 for
    /// single-sample images, else `limits::SAMPLES`.
    pub samples: u32,
}

impl Target {
    /// A target of one colour image (`texture` and its single-level `view`) of `width`×`height`
    /// lacking the `absent` channels, with no depth, batched under `key`.
    pub fn color_only(
        key: (u64, u64),
        (texture, view): (wgpu::Texture, wgpu::TextureView),
        (width, height): (u32, u32),
        absent: wgpu::ColorWrites,
    ) -> Target {
        Target {
            key,
            color: Some((texture, view)),
            color_at: Subresource::default(),
            more: Vec::new(),
            slices: Vec::new(),
            srgb: false,
            depth: None,
            depth_image: None,
            width,
            height,
            absent,
            samples: 1,
        }
    }

    /// Whether the colour buffer has no alpha.
    pub fn opaque(&self) -> bool {
        self.absent.contains(wgpu::ColorWrites::ALPHA)
    }

    /// A clear colour as the buffer stores it: absent channels at 0, absent alpha at 1.
    pub fn stored(&self, c: [f32; 4]) -> [f32; 4] {
        stored(self.absent, c)
    }

    /// Per colour slot (fragment output), the view it writes, the channels its image lacks
    /// and its format (RGBA8, or RGBA16F for `GL_EXT_color_buffer_half_float`).
    pub fn slots(&self) -> Vec<Option<(&wgpu::TextureView, wgpu::ColorWrites, wgpu::TextureFormat)>> {
        let format = |t: &wgpu::Texture| if self.srgb { t.format().add_srgb_suffix() } else { t.format() };
        let first = self.color.as_ref().map(|(t, v)| (v, self.absent, format(t)));
        std::iter::once(first).chain(self.more.iter().map(|m| m.as_ref().map(|(v, a, f)| (v, *a, *f)))).collect()
    }

    /// Whether the colour image (the read buffer, for reads) is half-float
    /// (`GL_EXT_color_buffer_half_float`).
    pub fn half_float(&self) -> bool {
        self.color.as_ref().is_some_and(|(t, _)| t.format() == HALF_FORMAT)
    }

    /// Whether the colour image (the read buffer, for reads) holds floats that are not
    /// clamped: half-float, 32-bit float or packed float (`GL_EXT_color_buffer_float`).
    pub fn float(&self) -> bool {
        self.color_format().is_some_and(crate::formats::is_float_color)
    }

    /// Whether any colour slot holds unclamped floats (a clear then keeps its colour as given).
    pub fn any_float(&self) -> bool {
        self.slots().iter().flatten().any(|s| crate::formats::is_float_color(s.2))
    }

    /// The format of the colour image (the read buffer, for reads), as the image stores it.
    pub fn color_format(&self) -> Option<wgpu::TextureFormat> {
        self.color.as_ref().map(|(t, _)| t.format())
    }

    /// Whether any slot has a colour image.
    pub fn has_color(&self) -> bool {
        self.color.is_some() || self.more.iter().any(Option::is_some)
    }

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

/// Clear colour `c` as an image lacking the `absent` channels stores it: absent colour
/// channels at 0, absent alpha at 1.
pub fn stored(absent: wgpu::ColorWrites, mut c: [f32; 4]) -> [f32; 4] {
    for (i, ch) in [wgpu::ColorWrites::RED, wgpu::ColorWrites::GREEN, wgpu::ColorWrites::BLUE].iter().enumerate() {
        if absent.contains(*ch) {
            c[i] = 0.0;
        }
    }
    if absent.contains(wgpu::ColorWrites::ALPHA) {
        c[3] = 1.0;
    }
    c
}

//! What is composited and how: a surface's layer (rectangle, depth layer, images, normal,
//! projection, opacity and source region), the modes, the intermediate's format, the errors, and
//! what a composite did.

/// The part of a surface's image that is shown, stretched over its rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Source {
    /// The image's width and height.
    pub image: [i32; 2],
    /// The part shown: x, y (from the image's top), width, height, within the image.
    pub region: [i32; 4],
}

/// How a surface is shown beyond its placement: which part of its image, and how opaquely.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Props {
    /// The part of the image shown over the rectangle (scaled, and filtered bilinearly, where
    /// its size differs from the rectangle's; fetched exactly where it is the same); `None`: the
    /// whole image, whose size is the rectangle's.
    pub source: Option<Source>,
    /// Multiplies the selected premultiplied colour (its alpha): 0 shows nothing of it, 1 shows
    /// it as drawn. The surface still takes part in its group's depth select.
    pub opacity: f32,
}

impl Default for Props {
    fn default() -> Self {
        Props { source: None, opacity: 1.0 }
    }
}

impl Props {
    /// How the compositor shows scene surface `s` with opacity `opacity`: `None` where nothing
    /// of it can show (an empty rectangle or source region).
    pub fn of(s: &strata_scene::SceneSurface, opacity: f32) -> Option<Props> {
        if !s.can_show() {
            return None;
        }
        let region = s.source_region()?;
        let source = (!s.exact()).then_some(Source { image: s.image, region });
        Some(Props { source, opacity })
    }

    /// Whether the source is scaled to rectangle `rect` (sizes differ).
    pub fn scaled(&self, rect: [i32; 4]) -> bool {
        self.source.is_some_and(|s| s.region[2] != rect[2] || s.region[3] != rect[3])
    }

    /// The source in effect for rectangle `rect`: the image's size and the region shown.
    pub fn source_for(&self, rect: [i32; 4]) -> Source {
        self.source.unwrap_or(Source { image: [rect[2], rect[3]], region: [0, 0, rect[2], rect[3]] })
    }
}

/// One surface to composite.
pub struct Layer<'a> {
    /// x, y (from the output's top), width, height in output pixels: where the surface shows
    /// (its image's size unless `props.source` scales it).
    pub rect: [i32; 4],
    /// Depth layer: larger is farther; equal values form one group.
    pub z: f32,
    /// Colour (RGBA8, rows in GL order: bottom first).
    pub color: &'a wgpu::TextureView,
    /// Depth (a depth format, same size), or `None`: at its far plane everywhere (depth 1 when
    /// undeclared).
    pub depth: Option<&'a wgpu::TextureView>,
    /// The surface's normal for `NormalSource::PerSurface`.
    pub normal: [f32; 3],
    /// Its declared projection as the shader takes it (`Projection::shader_params`): kind (0
    /// orthographic, 1 perspective), near, far, reversed (0 or 1); `Projection::RAW` when
    /// undeclared, which compares its raw depth.
    pub projection: [f32; 4],
    /// Its colour has alpha 1 everywhere (a surface whose config has no alpha, whose alpha
    /// reads as 1): nothing beneath it can show, so culling may leave out what it covers
    /// (only where `props.opacity` is 1 too).
    pub opaque: bool,
    /// Which part of its image shows, and its opacity.
    pub props: Props,
}

/// How surfaces are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Mode {
    /// Per-fragment depth compositing within z-groups, with lighting (the thesis' design).
    #[default]
    #[value(name = "3d")]
    ThreeD,
    /// A 2D blitting compositor: painter's order by z (then stacking order), no depth, no
    /// lighting, every surface opaque, only the visible part of each copied.
    #[value(name = "2d")]
    TwoD,
}

/// The colour format of chained passes' intermediates (the last pass writes the output as
/// before).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Intermediate {
    /// RGBA8 unorm: holds a selected surface texel exactly (the default).
    #[default]
    #[value(name = "rgba8")]
    Rgba8,
    /// RGBA16 float: twice the bytes per pixel.
    #[value(name = "rgba16f")]
    Rgba16f,
}

impl Intermediate {
    /// Its texture format.
    pub fn format(self) -> wgpu::TextureFormat {
        match self {
            Intermediate::Rgba8 => wgpu::TextureFormat::Rgba8Unorm,
            Intermediate::Rgba16f => wgpu::TextureFormat::Rgba16Float,
        }
    }
}

/// A compositor configuration the device cannot honour, or a pass it cannot build.
#[derive(Debug, thiserror::Error)]
pub enum CompositorError {
    /// Fewer than 4 textures per pass cannot chain (intermediate + one new surface).
    #[error("--max-textures {0} is too small: chaining needs at least 4 (the intermediate's colour and depth plus one surface's)")]
    TooFewTextures(u32),
    /// More textures than the device samples per stage.
    #[error("--max-textures {requested} exceeds the device's limit of {device} sampled textures per shader stage")]
    ExceedsDevice {
        /// Requested.
        requested: u32,
        /// The device's limit.
        device: u32,
    },
    /// A pass shape's shader could not be composed from `shaders/composite.wgsl`.
    #[error("the compositor's shader for {kind} does not compose: {message}")]
    Shader {
        /// The pass shape (or the module) it failed for.
        kind: String,
        /// naga_oil's report, and the generated source.
        message: String,
    },
    /// A draw's images are not the ones its pass binds.
    #[error("a compositor draw of {kind} has {views} images where its pass binds {images}")]
    Views {
        /// The pass shape.
        kind: String,
        /// Images the draw has.
        views: usize,
        /// Images its pass binds.
        images: usize,
    },
}

/// What the last composite did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Cells the region was cut into.
    pub cells: usize,
    /// Cells (per z-group) where the depth select ran.
    pub selects: usize,
    /// Of those, cells that needed chained passes.
    pub chained: usize,
    /// Draw calls.
    pub draws: usize,
    /// Render passes.
    pub render_passes: usize,
    /// Surfaces not sampled in a cell (counted once per cell) because a nearer group of opaque
    /// surfaces covers it.
    pub culled: usize,
}

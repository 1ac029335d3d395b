//! What the renderer caches pipelines by: a draw's program, vertex layout, raster state and
//! targets, and a clear's targets and masks.

use crate::render::RasterState;

/// What selects a render pipeline.
#[derive(Clone, PartialEq, Eq, Hash)]
pub(crate) struct PipelineKey {
    pub(crate) program: u64,
    pub(crate) depth_mask: u32,
    pub(crate) inputs: Vec<(u32, wgpu::VertexFormat, u64, bool)>,
    pub(crate) raster: RasterState,
    /// Per colour slot, whether it has an image, the channels that image lacks, and its format.
    pub(crate) colors: Vec<Option<(wgpu::ColorWrites, wgpu::TextureFormat)>>,
    pub(crate) depth_format: Option<wgpu::TextureFormat>,
    /// The target's samples (1: single-sampled).
    pub(crate) samples: u32,
}

/// What selects a clear pipeline.
#[derive(Clone, PartialEq, Eq, Hash)]
pub(crate) struct ClearKey {
    pub(crate) color: Option<wgpu::ColorWrites>,
    /// The one colour slot a `glClearBuffer*` clears (`None`: all of them).
    pub(crate) only: Option<usize>,
    pub(crate) depth: Option<(wgpu::TextureFormat, bool, Option<u32>)>,
    /// Which colour slots have an image, and its format.
    pub(crate) slots: Vec<Option<wgpu::TextureFormat>>,
    /// The target's samples (1: single-sampled).
    pub(crate) samples: u32,
}

//! What a draw asks the renderer for: its program, target, vertex and index sources, raster
//! state and bound textures.

use std::sync::Arc;

use crate::objects::program::LinkedProgram;
use crate::objects::texture::SamplerState;
use crate::typed::ClipControl;

/// Where a draw's vertex or index bytes come from.
#[derive(Clone)]
pub enum Source {
    /// A client buffer object's GPU copy, at a byte offset.
    Buffer(wgpu::Buffer, u64),
    /// Bytes generated for this draw (converted attributes, constants, widened indices).
    Bytes(Vec<u8>),
}

/// One vertex input of a draw.
#[derive(Clone)]
pub struct VertexInput {
    /// Shader location.
    pub location: u32,
    /// Element format.
    pub format: wgpu::VertexFormat,
    /// Byte stride (0 for a constant).
    pub stride: u64,
    /// The bytes.
    pub source: Source,
    /// Stepped once per instance (an attribute with a divisor; constants step per instance
    /// too, having stride 0).
    pub per_instance: bool,
}

/// Fixed-function state that selects a pipeline.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct RasterState {
    /// Primitive topology.
    pub topology: wgpu::PrimitiveTopology,
    /// Index format of an indexed strip (wgpu requires it; restart can never trigger, see draw).
    pub strip_index: Option<wgpu::IndexFormat>,
    /// GL front face is CCW.
    pub front_ccw: bool,
    /// Face culled, if culling is on.
    pub cull: Option<wgpu::Face>,
    /// Depth test function (`None`: test off), and depth writes.
    pub depth: Option<(wgpu::CompareFunction, bool)>,
    /// Stencil state if the test is on.
    pub stencil: Option<wgpu::StencilState>,
    /// Polygon offset (factor bits, units, clamp bits).
    pub bias: Option<(u32, i32, u32)>,
    /// Blend state if blending is on.
    pub blend: Option<wgpu::BlendState>,
    /// Colour write mask.
    pub write_mask: wgpu::ColorWrites,
    /// `GL_POINTS` drawn as squares: four vertices per instance, one instance per point,
    /// every vertex input stepped per instance.
    pub points: bool,
    /// Reversed-Z framebuffer 0 (near and far bits): the vertex stage is its reversed-Z
    /// variant, so pipelines differ.
    pub reversed_z: Option<(u32, u32)>,
    /// `GL_DEPTH_CLAMP_EXT`: depth is clamped to the depth range instead of clipped (wgpu's
    /// unclipped depth, which is Vulkan's depth clamp).
    pub unclipped_depth: bool,
    /// `GL_EXT_clip_control`: the vertex stage is its variant, and with the upper-left origin
    /// the winding as wgpu sees it is GL's reversed.
    pub clip: ClipControl,
    /// The samples a multisample target's draws may cover (`GL_SAMPLE_COVERAGE`): all bits
    /// set but where the coverage value masks them.
    pub coverage_mask: u64,
    /// `GL_SAMPLE_ALPHA_TO_COVERAGE` on a multisample target.
    pub alpha_to_coverage: bool,
}

/// Everything a validated draw needs.
pub struct DrawSpec<'a> {
    /// The program.
    pub program: Arc<LinkedProgram>,
    /// Its vertex module for this draw (the points variant for `GL_POINTS`).
    pub vs: wgpu::ShaderModule,
    /// Its fragment module for this draw when not the program's (the reversed-Z variant of a
    /// stage reading `gl_FragCoord`).
    pub fs: Option<wgpu::ShaderModule>,
    /// Uniform block bytes.
    pub uniforms: std::borrow::Cow<'a, [u8]>,
    /// Per sampler: texture view, its uid, sampling state, and whether the image cannot be
    /// filtered (depth, or float without `FLOAT32_FILTERABLE`) (`None`: incomplete, sample black).
    pub textures: Vec<Option<(wgpu::TextureView, u64, SamplerState, bool)>>,
    /// Per uniform block of the program: the buffer and offset it reads (`None`: no buffer
    /// large enough is bound, and it reads zeros).
    pub blocks: Vec<Option<(wgpu::Buffer, u64)>>,
    /// Vertex inputs.
    pub inputs: Vec<VertexInput>,
    /// Indices, if indexed.
    pub index: Option<(Source, wgpu::IndexFormat)>,
    /// Vertices or indices to draw.
    pub count: u32,
    /// First vertex (non-indexed).
    pub first: u32,
    /// First instance and instance count (points: one instance per point; else 0 and 1).
    pub instances: (u32, u32),
    /// Fixed-function state.
    pub raster: RasterState,
    /// Viewport x, y, w, h, near, far.
    pub viewport: [f32; 6],
    /// Scissor rectangle, already clipped to the target.
    pub scissor: [u32; 4],
    /// Stencil reference.
    pub stencil_ref: u32,
    /// The back face's stencil reference, read mask and write mask where they differ from the
    /// front's: back-facing triangles are then drawn on their own with them.
    pub back_stencil: Option<(u32, u32, u32)>,
    /// Blend constant.
    pub blend_color: [f64; 4],
    /// A capturing draw's numbers (the capture block's bytes) and its buffers, by binding
    /// (transform feedback).
    pub capture: Option<(Vec<u8>, Vec<wgpu::Buffer>)>,
}

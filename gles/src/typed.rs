//! GL enums parsed once at the boundary into typed values: binding points, image targets,
//! capabilities, primitives and index types. Anything else is the GL error the parse gives.

use crate::enums::*;
use crate::error::{GlError, GlResult};

/// A buffer binding point (`glBindBuffer`, `glBufferData`, …).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BufferTarget {
    /// `GL_ARRAY_BUFFER`.
    Array,
    /// `GL_ELEMENT_ARRAY_BUFFER`.
    ElementArray,
    /// `GL_PIXEL_PACK_BUFFER_NV` (`GL_NV_pixel_buffer_object`): where `glReadPixels` writes;
    /// the library does the writing, so the daemon only keeps the buffer.
    PixelPack,
    /// `GL_PIXEL_UNPACK_BUFFER_NV`: what uploads read; the library reads it.
    PixelUnpack,
    /// `GL_UNIFORM_BUFFER` (ES 3.0): the generic binding beside the indexed ones that uniform
    /// blocks read.
    Uniform,
    /// `GL_COPY_READ_BUFFER` (ES 3.0): a binding for copies, which draws never read.
    CopyRead,
    /// `GL_COPY_WRITE_BUFFER` (ES 3.0).
    CopyWrite,
    /// `GL_TRANSFORM_FEEDBACK_BUFFER` (ES 3.0): the generic binding beside the indexed ones
    /// transform feedback writes.
    TransformFeedback,
}

/// `GL_UNIFORM_BUFFER`.
pub const UNIFORM_BUFFER: u32 = 0x8A11;
/// `GL_TRANSFORM_FEEDBACK_BUFFER`.
pub const TRANSFORM_FEEDBACK_BUFFER: u32 = 0x8C8E;
/// `GL_PRIMITIVE_RESTART_FIXED_INDEX` (ES 3.0).
pub const PRIMITIVE_RESTART_FIXED_INDEX: u32 = 0x8D69;
/// `GL_RASTERIZER_DISCARD` (ES 3.0).
pub const RASTERIZER_DISCARD: u32 = 0x8C89;

impl BufferTarget {
    /// Parses a buffer target of a context (`es3`: an ES 3.0 one, which has ES 3.0's targets);
    /// anything else is `GL_INVALID_ENUM`.
    pub fn from_gl(target: u32, es3: bool) -> GlResult<Self> {
        match target {
            ARRAY_BUFFER => Ok(BufferTarget::Array),
            ELEMENT_ARRAY_BUFFER => Ok(BufferTarget::ElementArray),
            PIXEL_PACK_BUFFER_NV => Ok(BufferTarget::PixelPack),
            PIXEL_UNPACK_BUFFER_NV => Ok(BufferTarget::PixelUnpack),
            UNIFORM_BUFFER if es3 => Ok(BufferTarget::Uniform),
            0x8F36 if es3 => Ok(BufferTarget::CopyRead),
            0x8F37 if es3 => Ok(BufferTarget::CopyWrite),
            TRANSFORM_FEEDBACK_BUFFER if es3 => Ok(BufferTarget::TransformFeedback),
            _ => Err(GlError::InvalidEnum),
        }
    }
}

/// A texture binding point of a texture unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureTarget {
    /// `GL_TEXTURE_2D`.
    TwoD,
    /// `GL_TEXTURE_CUBE_MAP`.
    CubeMap,
    /// `GL_TEXTURE_EXTERNAL_OES` (`GL_OES_EGL_image_external`): a 2D image from an EGLImage,
    /// sampled through `samplerExternalOES`.
    External,
    /// `GL_TEXTURE_3D_OES` (`GL_OES_texture_3D`).
    ThreeD,
    /// `GL_TEXTURE_2D_ARRAY` (ES 3.0).
    TwoDArray,
}

impl TextureTarget {
    /// Parses a texture target of a context of ES 3.0 (`es3`, which adds 2D arrays) or 2.0;
    /// anything else is `GL_INVALID_ENUM`.
    pub fn from_gl_in(target: u32, es3: bool) -> GlResult<Self> {
        if es3 && target == TEXTURE_2D_ARRAY {
            return Ok(TextureTarget::TwoDArray);
        }
        Self::from_gl(target)
    }

    /// Parses a texture target of ES 2.0 and its extensions; anything else is
    /// `GL_INVALID_ENUM`.
    pub fn from_gl(target: u32) -> GlResult<Self> {
        match target {
            TEXTURE_2D => Ok(TextureTarget::TwoD),
            TEXTURE_CUBE_MAP => Ok(TextureTarget::CubeMap),
            crate::enums::TEXTURE_EXTERNAL_OES => Ok(TextureTarget::External),
            TEXTURE_3D_OES => Ok(TextureTarget::ThreeD),
            _ => Err(GlError::InvalidEnum),
        }
    }

    /// The GL enum, as a texture object remembers its target.
    pub fn as_gl(self) -> u32 {
        match self {
            TextureTarget::TwoD => TEXTURE_2D,
            TextureTarget::CubeMap => TEXTURE_CUBE_MAP,
            TextureTarget::External => crate::enums::TEXTURE_EXTERNAL_OES,
            TextureTarget::ThreeD => TEXTURE_3D_OES,
            TextureTarget::TwoDArray => TEXTURE_2D_ARRAY,
        }
    }

    /// Index of this binding point in a texture unit.
    pub fn slot(self) -> usize {
        match self {
            TextureTarget::TwoD => 0,
            TextureTarget::CubeMap => 1,
            TextureTarget::External => 2,
            TextureTarget::ThreeD => 3,
            TextureTarget::TwoDArray => 4,
        }
    }
}

/// The image an upload or copy addresses: `GL_TEXTURE_2D`, one cube face, or a 3D image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ImageTarget {
    /// Array layer: the cube face (0..6), 0 for 2D and 3D.
    pub face: u32,
    /// Whether this is a cube face.
    pub cube: bool,
    /// Whether this is a 3D image (`GL_OES_texture_3D`).
    pub three_d: bool,
    /// Whether this is a 2D array's image (ES 3.0), whose layers take the place of a 3D
    /// image's slices but keep their number at every level.
    pub array: bool,
}

impl ImageTarget {
    /// Parses `GL_TEXTURE_2D` or `GL_TEXTURE_CUBE_MAP_*`; anything else is `GL_INVALID_ENUM`.
    pub fn from_gl(target: u32) -> GlResult<Self> {
        match target {
            TEXTURE_2D => Ok(ImageTarget { face: 0, cube: false, three_d: false, array: false }),
            t if (TEXTURE_CUBE_MAP_POSITIVE_X..TEXTURE_CUBE_MAP_POSITIVE_X + 6).contains(&t) => {
                Ok(ImageTarget { face: t - TEXTURE_CUBE_MAP_POSITIVE_X, cube: true, three_d: false, array: false })
            }
            _ => Err(GlError::InvalidEnum),
        }
    }

    /// The binding point whose texture holds this image.
    pub fn binding(self) -> TextureTarget {
        match (self.cube, self.three_d, self.array) {
            (true, _, _) => TextureTarget::CubeMap,
            (_, true, _) => TextureTarget::ThreeD,
            (_, _, true) => TextureTarget::TwoDArray,
            _ => TextureTarget::TwoD,
        }
    }
}

/// A capability of `glEnable`/`glDisable`/`glIsEnabled`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Capability {
    /// `GL_CULL_FACE`.
    CullFace,
    /// `GL_BLEND`.
    Blend,
    /// `GL_DEPTH_TEST`.
    DepthTest,
    /// `GL_SCISSOR_TEST`.
    ScissorTest,
    /// `GL_STENCIL_TEST`.
    StencilTest,
    /// `GL_POLYGON_OFFSET_FILL`.
    PolygonOffsetFill,
    /// `GL_DITHER`.
    Dither,
    /// `GL_SAMPLE_COVERAGE`.
    SampleCoverage,
    /// `GL_SAMPLE_ALPHA_TO_COVERAGE`.
    SampleAlphaToCoverage,
    /// `GL_DEBUG_OUTPUT_KHR`.
    DebugOutput,
    /// `GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR`.
    DebugOutputSynchronous,
    /// `GL_DEPTH_CLAMP_EXT` (`EXT_depth_clamp`, where the device has
    /// `wgpu::Features::DEPTH_CLIP_CONTROL`).
    DepthClamp,
    /// `GL_PRIMITIVE_RESTART_FIXED_INDEX` (ES 3.0).
    PrimitiveRestartFixedIndex,
    /// `GL_RASTERIZER_DISCARD` (ES 3.0).
    RasterizerDiscard,
}

impl Capability {
    /// Parses a capability the device with `features` has, in a context of ES 3.0 if `es3`;
    /// anything else is `GL_INVALID_ENUM`.
    pub fn on(cap: u32, features: wgpu::Features, es3: bool) -> GlResult<Self> {
        match Capability::from_gl(cap)? {
            Capability::DepthClamp if !features.contains(wgpu::Features::DEPTH_CLIP_CONTROL) => {
                Err(GlError::InvalidEnum)
            }
            Capability::PrimitiveRestartFixedIndex | Capability::RasterizerDiscard if !es3 => Err(GlError::InvalidEnum),
            c => Ok(c),
        }
    }

    /// Parses a capability; anything else is `GL_INVALID_ENUM`.
    pub fn from_gl(cap: u32) -> GlResult<Self> {
        Ok(match cap {
            CULL_FACE => Capability::CullFace,
            BLEND => Capability::Blend,
            DEPTH_TEST => Capability::DepthTest,
            SCISSOR_TEST => Capability::ScissorTest,
            STENCIL_TEST => Capability::StencilTest,
            POLYGON_OFFSET_FILL => Capability::PolygonOffsetFill,
            DITHER => Capability::Dither,
            SAMPLE_COVERAGE => Capability::SampleCoverage,
            SAMPLE_ALPHA_TO_COVERAGE => Capability::SampleAlphaToCoverage,
            DEBUG_OUTPUT => Capability::DebugOutput,
            DEBUG_OUTPUT_SYNCHRONOUS => Capability::DebugOutputSynchronous,
            DEPTH_CLAMP_EXT => Capability::DepthClamp,
            PRIMITIVE_RESTART_FIXED_INDEX => Capability::PrimitiveRestartFixedIndex,
            RASTERIZER_DISCARD => Capability::RasterizerDiscard,
            _ => return Err(GlError::InvalidEnum),
        })
    }
}

/// A draw call's primitive mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Primitive {
    /// `GL_POINTS`.
    Points,
    /// `GL_LINES`.
    Lines,
    /// `GL_LINE_LOOP`, drawn as a strip of generated indices.
    LineLoop,
    /// `GL_LINE_STRIP`.
    LineStrip,
    /// `GL_TRIANGLES`.
    Triangles,
    /// `GL_TRIANGLE_STRIP`.
    TriangleStrip,
    /// `GL_TRIANGLE_FAN`, drawn as a list of generated indices.
    TriangleFan,
}

impl Primitive {
    /// Parses a primitive mode; anything else is `GL_INVALID_ENUM`.
    pub fn from_gl(mode: u32) -> GlResult<Self> {
        Ok(match mode {
            POINTS => Primitive::Points,
            LINES => Primitive::Lines,
            LINE_LOOP => Primitive::LineLoop,
            LINE_STRIP => Primitive::LineStrip,
            TRIANGLES => Primitive::Triangles,
            TRIANGLE_STRIP => Primitive::TriangleStrip,
            TRIANGLE_FAN => Primitive::TriangleFan,
            _ => return Err(GlError::InvalidEnum),
        })
    }

    /// The wgpu topology the primitive is drawn with.
    pub fn topology(self) -> wgpu::PrimitiveTopology {
        match self {
            Primitive::Points => wgpu::PrimitiveTopology::PointList,
            Primitive::Lines => wgpu::PrimitiveTopology::LineList,
            Primitive::LineStrip | Primitive::LineLoop => wgpu::PrimitiveTopology::LineStrip,
            Primitive::Triangles | Primitive::TriangleFan => wgpu::PrimitiveTopology::TriangleList,
            Primitive::TriangleStrip => wgpu::PrimitiveTopology::TriangleStrip,
        }
    }

    /// Whether wgpu has no such primitive, so the draw uses generated indices.
    pub fn generates_indices(self) -> bool {
        matches!(self, Primitive::LineLoop | Primitive::TriangleFan)
    }

    /// The list wgpu draws this primitive's vertices as once they are rearranged: each
    /// primitive on its own (see `indices::Reorder`).
    pub fn list_topology(self) -> wgpu::PrimitiveTopology {
        match self {
            Primitive::Points => wgpu::PrimitiveTopology::PointList,
            Primitive::Lines | Primitive::LineStrip | Primitive::LineLoop => wgpu::PrimitiveTopology::LineList,
            Primitive::Triangles | Primitive::TriangleStrip | Primitive::TriangleFan => {
                wgpu::PrimitiveTopology::TriangleList
            }
        }
    }

    /// Whether this is a strip (whose indexed form restarts at the format's maximum in wgpu).
    pub fn is_strip(self) -> bool {
        matches!(self, Primitive::LineStrip | Primitive::TriangleStrip)
    }
}

/// The type of a draw's indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IndexType {
    /// `GL_UNSIGNED_BYTE`.
    U8,
    /// `GL_UNSIGNED_SHORT`.
    U16,
    /// `GL_UNSIGNED_INT` (`OES_element_index_uint`).
    U32,
}

impl IndexType {
    /// Parses an index type; anything else is `GL_INVALID_ENUM`.
    pub fn from_gl(ty: u32) -> GlResult<Self> {
        match ty {
            UNSIGNED_BYTE => Ok(IndexType::U8),
            UNSIGNED_SHORT => Ok(IndexType::U16),
            UNSIGNED_INT => Ok(IndexType::U32),
            _ => Err(GlError::InvalidEnum),
        }
    }

    /// Bytes per index.
    pub fn size(self) -> u64 {
        match self {
            IndexType::U8 => 1,
            IndexType::U16 => 2,
            IndexType::U32 => 4,
        }
    }

    /// The index `GL_PRIMITIVE_RESTART_FIXED_INDEX` restarts at: the type's largest value.
    pub fn restart_index(self) -> u32 {
        match self {
            IndexType::U8 => 0xFF,
            IndexType::U16 => 0xFFFF,
            IndexType::U32 => u32::MAX,
        }
    }
}

/// `GL_EXT_clip_control`'s state: the window origin and the clip depth range.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct ClipControl {
    /// `GL_UPPER_LEFT_EXT` (else `GL_LOWER_LEFT_EXT`): clip y points down the window.
    pub upper_left: bool,
    /// `GL_ZERO_TO_ONE_EXT` (else `GL_NEGATIVE_ONE_TO_ONE_EXT`): clip z ranges over [0, w].
    pub zero_to_one: bool,
}

//! The GLSL ES front end's vocabulary: shader stages, the types of variables and uniforms,
//! and a compiled shader's interface and what its checks learnt.

use std::collections::{HashMap, HashSet};

use glsl_lang::ast::{self, TypeSpecifierNonArrayData as T};

use crate::enums as gl;

/// A shader stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Vertex shader.
    Vertex,
    /// Fragment shader.
    Fragment,
}

/// The GLSL ES types an interface variable can have (ES 1.00's, and ES 3.00's unsigned ones).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum Ty {
    Float,
    Vec2,
    Vec3,
    Vec4,
    Int,
    IVec2,
    IVec3,
    IVec4,
    UInt,
    UVec2,
    UVec3,
    UVec4,
    Bool,
    BVec2,
    BVec3,
    BVec4,
    Mat2,
    Mat3,
    Mat4,
    /// GLSL ES 3.00's non-square matrices: `matCxR`, C columns of R rows.
    Mat2x3,
    Mat2x4,
    Mat3x2,
    Mat3x4,
    Mat4x2,
    Mat4x3,
    Sampler2D,
    SamplerCube,
    /// `samplerExternalOES` (`GL_OES_EGL_image_external`), sampled as a 2D image.
    SamplerExternal,
    /// `sampler3D` (`GL_OES_texture_3D`).
    Sampler3D,
    /// `sampler2DArray` (ES 3.0).
    Sampler2DArray,
    /// `sampler2DShadow` (ES 3.0): a depth image compared with a reference.
    Sampler2DShadow,
    /// `samplerCubeShadow` (ES 3.0).
    SamplerCubeShadow,
    /// `sampler2DArrayShadow` (ES 3.0).
    Sampler2DArrayShadow,
    /// `isampler2D` (ES 3.0): signed integers, fetched texel by texel (`glsl::int_samplers`).
    ISampler2D,
    /// `isampler3D`.
    ISampler3D,
    /// `isamplerCube`.
    ISamplerCube,
    /// `isampler2DArray`.
    ISampler2DArray,
    /// `usampler2D` (ES 3.0): unsigned integers.
    USampler2D,
    /// `usampler3D`.
    USampler3D,
    /// `usamplerCube`.
    USamplerCube,
    /// `usampler2DArray`.
    USampler2DArray,
}

/// `GL_UNSIGNED_INT_VEC2`..`4` (ES 3.0), as `glGetActiveUniform` reports them.
const UNSIGNED_INT_VEC2: u32 = 0x8DC6;
const UNSIGNED_INT_VEC3: u32 = 0x8DC7;
const UNSIGNED_INT_VEC4: u32 = 0x8DC8;

/// `GL_SAMPLER_2D_ARRAY` (ES 3.0), as `glGetActiveUniform` reports `sampler2DArray`.
const SAMPLER_2D_ARRAY: u32 = 0x8DC1;

/// `GL_SAMPLER_EXTERNAL_OES`, the type `glGetActiveUniform` reports for `samplerExternalOES`.
pub(crate) const SAMPLER_EXTERNAL_OES: u32 = 0x8D66;

impl Ty {
    pub(crate) fn from_spec(t: &T) -> Option<Ty> {
        Some(match t {
            T::Float => Ty::Float,
            T::Vec2 => Ty::Vec2,
            T::Vec3 => Ty::Vec3,
            T::Vec4 => Ty::Vec4,
            T::Int => Ty::Int,
            T::IVec2 => Ty::IVec2,
            T::IVec3 => Ty::IVec3,
            T::IVec4 => Ty::IVec4,
            T::UInt => Ty::UInt,
            T::UVec2 => Ty::UVec2,
            T::UVec3 => Ty::UVec3,
            T::UVec4 => Ty::UVec4,
            T::Bool => Ty::Bool,
            T::BVec2 => Ty::BVec2,
            T::BVec3 => Ty::BVec3,
            T::BVec4 => Ty::BVec4,
            T::Mat2 | T::Mat22 => Ty::Mat2,
            T::Mat3 | T::Mat33 => Ty::Mat3,
            T::Mat4 | T::Mat44 => Ty::Mat4,
            T::Mat23 => Ty::Mat2x3,
            T::Mat24 => Ty::Mat2x4,
            T::Mat32 => Ty::Mat3x2,
            T::Mat34 => Ty::Mat3x4,
            T::Mat42 => Ty::Mat4x2,
            T::Mat43 => Ty::Mat4x3,
            T::Sampler2D => Ty::Sampler2D,
            T::SamplerCube => Ty::SamplerCube,
            T::Sampler3D => Ty::Sampler3D,
            T::Sampler2DArray => Ty::Sampler2DArray,
            T::Sampler2DShadow => Ty::Sampler2DShadow,
            T::SamplerCubeShadow => Ty::SamplerCubeShadow,
            T::Sampler2DArrayShadow => Ty::Sampler2DArrayShadow,
            T::ISampler2D => Ty::ISampler2D,
            T::ISampler3D => Ty::ISampler3D,
            T::ISamplerCube => Ty::ISamplerCube,
            T::ISampler2DArray => Ty::ISampler2DArray,
            T::USampler2D => Ty::USampler2D,
            T::USampler3D => Ty::USampler3D,
            T::USamplerCube => Ty::USamplerCube,
            T::USampler2DArray => Ty::USampler2DArray,
            // The preprocessor spells `samplerExternalOES` so (see `preprocess::EXTERNAL_SPELLING`).
            T::Sampler2DRect => Ty::SamplerExternal,
            _ => return None,
        })
    }

    /// The GL enum `glGetActiveUniform` reports.
    pub fn gl_enum(self) -> u32 {
        match self {
            Ty::Float => gl::FLOAT,
            Ty::Vec2 => gl::FLOAT_VEC2,
            Ty::Vec3 => gl::FLOAT_VEC3,
            Ty::Vec4 => gl::FLOAT_VEC4,
            Ty::Int => gl::INT,
            Ty::IVec2 => gl::INT_VEC2,
            Ty::IVec3 => gl::INT_VEC3,
            Ty::IVec4 => gl::INT_VEC4,
            Ty::UInt => gl::UNSIGNED_INT,
            Ty::UVec2 => UNSIGNED_INT_VEC2,
            Ty::UVec3 => UNSIGNED_INT_VEC3,
            Ty::UVec4 => UNSIGNED_INT_VEC4,
            Ty::Bool => gl::BOOL,
            Ty::BVec2 => gl::BOOL_VEC2,
            Ty::BVec3 => gl::BOOL_VEC3,
            Ty::BVec4 => gl::BOOL_VEC4,
            Ty::Mat2 => gl::FLOAT_MAT2,
            Ty::Mat3 => gl::FLOAT_MAT3,
            Ty::Mat4 => gl::FLOAT_MAT4,
            Ty::Mat2x3 => 0x8B65,
            Ty::Mat2x4 => 0x8B66,
            Ty::Mat3x2 => 0x8B67,
            Ty::Mat3x4 => 0x8B68,
            Ty::Mat4x2 => 0x8B69,
            Ty::Mat4x3 => 0x8B6A,
            Ty::Sampler2D => gl::SAMPLER_2D,
            Ty::SamplerCube => gl::SAMPLER_CUBE,
            Ty::SamplerExternal => SAMPLER_EXTERNAL_OES,
            Ty::Sampler3D => gl::SAMPLER_3D_OES,
            Ty::Sampler2DArray => SAMPLER_2D_ARRAY,
            Ty::Sampler2DShadow => 0x8B62,
            Ty::SamplerCubeShadow => 0x8DC5,
            Ty::Sampler2DArrayShadow => 0x8DC4,
            // GL_INT_SAMPLER_* and GL_UNSIGNED_INT_SAMPLER_*.
            Ty::ISampler2D => 0x8DCA,
            Ty::ISampler3D => 0x8DCB,
            Ty::ISamplerCube => 0x8DCC,
            Ty::ISampler2DArray => 0x8DCF,
            Ty::USampler2D => 0x8DD2,
            Ty::USampler3D => 0x8DD3,
            Ty::USamplerCube => 0x8DD4,
            Ty::USampler2DArray => 0x8DD7,
        }
    }

    /// GLSL spelling; booleans live in the block as integers.
    pub(crate) fn glsl(self, in_block: bool) -> &'static str {
        match self {
            Ty::Float => "float",
            Ty::Vec2 => "vec2",
            Ty::Vec3 => "vec3",
            Ty::Vec4 => "vec4",
            Ty::Int => "int",
            Ty::IVec2 => "ivec2",
            Ty::IVec3 => "ivec3",
            Ty::IVec4 => "ivec4",
            Ty::UInt => "uint",
            Ty::UVec2 => "uvec2",
            Ty::UVec3 => "uvec3",
            Ty::UVec4 => "uvec4",
            Ty::Bool if in_block => "int",
            Ty::BVec2 if in_block => "ivec2",
            Ty::BVec3 if in_block => "ivec3",
            Ty::BVec4 if in_block => "ivec4",
            Ty::Bool => "bool",
            Ty::BVec2 => "bvec2",
            Ty::BVec3 => "bvec3",
            Ty::BVec4 => "bvec4",
            Ty::Mat2 => "mat2",
            Ty::Mat3 => "mat3",
            Ty::Mat4 => "mat4",
            Ty::Mat2x3 => "mat2x3",
            Ty::Mat2x4 => "mat2x4",
            Ty::Mat3x2 => "mat3x2",
            Ty::Mat3x4 => "mat3x4",
            Ty::Mat4x2 => "mat4x2",
            Ty::Mat4x3 => "mat4x3",
            Ty::Sampler2D | Ty::SamplerExternal | Ty::Sampler2DShadow => "texture2D",
            Ty::SamplerCube | Ty::SamplerCubeShadow => "textureCube",
            Ty::Sampler3D => "texture3D",
            Ty::Sampler2DArray | Ty::Sampler2DArrayShadow => "texture2DArray",
            Ty::ISampler2D => "itexture2D",
            Ty::ISampler3D => "itexture3D",
            // Integer cube maps are fetched as their six faces (`glsl::int_samplers`).
            Ty::ISamplerCube | Ty::ISampler2DArray => "itexture2DArray",
            Ty::USampler2D => "utexture2D",
            Ty::USampler3D => "utexture3D",
            Ty::USamplerCube | Ty::USampler2DArray => "utexture2DArray",
        }
    }

    /// Scalars per element (a matrix counts all its entries).
    pub fn components(self) -> usize {
        match self {
            Ty::Float
            | Ty::Int
            | Ty::UInt
            | Ty::Bool
            | Ty::Sampler2D
            | Ty::SamplerCube
            | Ty::SamplerExternal
            | Ty::Sampler3D
            | Ty::Sampler2DArray
            | Ty::Sampler2DShadow
            | Ty::SamplerCubeShadow
            | Ty::Sampler2DArrayShadow
            | Ty::ISampler2D
            | Ty::ISampler3D
            | Ty::ISamplerCube
            | Ty::ISampler2DArray
            | Ty::USampler2D
            | Ty::USampler3D
            | Ty::USamplerCube
            | Ty::USampler2DArray => 1,
            Ty::Vec2 | Ty::IVec2 | Ty::UVec2 | Ty::BVec2 => 2,
            Ty::Vec3 | Ty::IVec3 | Ty::UVec3 | Ty::BVec3 => 3,
            Ty::Vec4 | Ty::IVec4 | Ty::UVec4 | Ty::BVec4 | Ty::Mat2 => 4,
            Ty::Mat3 => 9,
            Ty::Mat4 => 16,
            Ty::Mat2x3 | Ty::Mat3x2 => 6,
            Ty::Mat2x4 | Ty::Mat4x2 => 8,
            Ty::Mat3x4 | Ty::Mat4x3 => 12,
        }
    }

    /// Matrix columns (0 for non-matrices).
    pub fn columns(self) -> usize {
        match self {
            Ty::Mat2 | Ty::Mat2x3 | Ty::Mat2x4 => 2,
            Ty::Mat3 | Ty::Mat3x2 | Ty::Mat3x4 => 3,
            Ty::Mat4 | Ty::Mat4x2 | Ty::Mat4x3 => 4,
            _ => 0,
        }
    }

    /// Matrix rows (0 for non-matrices).
    pub fn rows(self) -> usize {
        match self {
            Ty::Mat2 | Ty::Mat3x2 | Ty::Mat4x2 => 2,
            Ty::Mat3 | Ty::Mat2x3 | Ty::Mat4x3 => 3,
            Ty::Mat4 | Ty::Mat2x4 | Ty::Mat3x4 => 4,
            _ => 0,
        }
    }

    /// What a `glUniform*` call must match: float, int (and samplers), or bool (either).
    pub fn scalar(self) -> Scalar {
        match self {
            Ty::Int | Ty::IVec2 | Ty::IVec3 | Ty::IVec4 => Scalar::Int,
            Ty::UInt | Ty::UVec2 | Ty::UVec3 | Ty::UVec4 => Scalar::UInt,
            t if t.is_sampler() => Scalar::Int,
            Ty::Bool | Ty::BVec2 | Ty::BVec3 | Ty::BVec4 => Scalar::Bool,
            _ => Scalar::Float,
        }
    }

    /// Whether this is a sampler.
    pub fn is_sampler(self) -> bool {
        matches!(self, Ty::Sampler2D | Ty::SamplerCube | Ty::SamplerExternal | Ty::Sampler3D | Ty::Sampler2DArray)
            || self.is_shadow()
            || self.int_sampler().is_some()
    }

    /// Whether this is a shadow sampler, whose lookups compare (`rewrite`'s shadow helpers).
    pub fn is_shadow(self) -> bool {
        matches!(self, Ty::Sampler2DShadow | Ty::SamplerCubeShadow | Ty::Sampler2DArrayShadow)
    }

    /// Whether this is an integer sampler: `Some(signed)`.
    pub fn int_sampler(self) -> Option<bool> {
        match self {
            Ty::ISampler2D | Ty::ISampler3D | Ty::ISamplerCube | Ty::ISampler2DArray => Some(true),
            Ty::USampler2D | Ty::USampler3D | Ty::USamplerCube | Ty::USampler2DArray => Some(false),
            _ => None,
        }
    }

    /// The float sampler of the same dimensions: the sampler itself for every other.
    pub fn sampler_base(self) -> Ty {
        match self {
            Ty::ISampler2D | Ty::USampler2D => Ty::Sampler2D,
            Ty::ISampler3D | Ty::USampler3D => Ty::Sampler3D,
            Ty::ISamplerCube | Ty::USamplerCube => Ty::SamplerCube,
            Ty::ISampler2DArray | Ty::USampler2DArray => Ty::Sampler2DArray,
            t => t,
        }
    }

    /// std140 (size, alignment) of one element that is not in an array.
    pub(crate) fn std140(self) -> (u32, u32) {
        match self {
            Ty::Float | Ty::Int | Ty::UInt | Ty::Bool => (4, 4),
            Ty::Vec2 | Ty::IVec2 | Ty::UVec2 | Ty::BVec2 => (8, 8),
            Ty::Vec3 | Ty::IVec3 | Ty::UVec3 | Ty::BVec3 => (12, 16),
            Ty::Vec4 | Ty::IVec4 | Ty::UVec4 | Ty::BVec4 => (16, 16),
            t if t.is_sampler() => (0, 1),
            // Each column a vector padded to 16 bytes.
            t => (16 * t.columns() as u32, 16),
        }
    }
}

/// The scalar kind of a uniform.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    /// Float, vectors and matrices of float.
    Float,
    /// Int and sampler.
    Int,
    /// Unsigned int (GLSL ES 3.00).
    UInt,
    /// Bool (set with either float or int calls).
    Bool,
}

/// A global interface variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Var {
    /// Its name.
    pub name: String,
    /// Its type.
    pub ty: Ty,
    /// Array length, if an array.
    pub array: Option<u32>,
    /// `layout(location = N)` (GLSL ES 3.00 vertex inputs and fragment outputs).
    pub location: Option<u32>,
    /// Interpolated `flat` (GLSL ES 3.00 varyings): the provoking vertex's value.
    pub flat: bool,
}

/// A member of a uniform block, with its std140 place.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockMember {
    /// Its name (a structure's leaf: its access from the block, `s.x`, `a[1].m`).
    pub name: String,
    /// Its type.
    pub ty: Ty,
    /// Array length, if an array.
    pub array: Option<u32>,
    /// A matrix laid out row by row (`layout(row_major)`).
    pub row_major: bool,
    /// Byte offset in the block.
    pub offset: u32,
    /// Bytes between array elements (0 for a non-array).
    pub stride: u32,
}

/// A GLSL ES 3.00 uniform block, laid out by std140.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// The block's name (what `glGetUniformBlockIndex` takes; `B[k]` for an array's element).
    pub name: String,
    /// The instance name, if the block has one (its members are then `instance.member`).
    pub instance: Option<String>,
    /// Its index in an array of blocks (whose element `k` GL names `name[k]`).
    pub element: Option<u32>,
    /// Whether the stage's code uses it: an array's element only where indexed (a block of its
    /// own counts as used wherever declared).
    pub referenced: bool,
    /// Its members, in order (a member of structure type as its leaves, `s.x`, `a[1].m`).
    pub members: Vec<BlockMember>,
    /// Its members of structure types: each one's name, structure and array length.
    pub structs: Vec<(String, String, Option<u32>)>,
    /// Its data size in bytes (`GL_UNIFORM_BLOCK_DATA_SIZE`).
    pub size: u32,
}

impl Block {
    /// Its name without an array element's index (`B` of `B[k]`).
    pub fn base_name(&self) -> &str {
        match self.element {
            Some(k) => self.name.strip_suffix(&format!("[{k}]")).unwrap_or(&self.name),
            None => &self.name,
        }
    }
}

/// A shader's uniforms of structure types (`struct_uniforms`), each declared as one uniform
/// per leaf.
#[derive(Debug, Clone, Default)]
pub struct StructUniforms {
    /// The GL name of each leaf's uniform (`u[1].a`), by the uniform's name (`u__1__a`).
    pub names: HashMap<String, String>,
    /// Each structure uniform's type, as the other stage must declare it too.
    pub types: HashMap<String, String>,
}

/// A successfully compiled shader, kept for linking.
#[derive(Debug, Clone)]
pub struct Shader {
    /// The stage.
    pub stage: Stage,
    pub(crate) body: ast::TranslationUnit,
    /// `attribute` variables.
    pub attributes: Vec<Var>,
    /// `varying` variables (GLSL ES 3.00: vertex `out`s and fragment `in`s).
    pub varyings: Vec<Var>,
    /// GLSL ES 3.00 fragment `out`s, in declaration order.
    pub outputs: Vec<Var>,
    /// GLSL ES 3.00 uniform blocks, in declaration order.
    pub blocks: Vec<Block>,
    /// The language version: 100 or 300 (`#version 300 es`).
    pub version: u16,
    /// `uniform` variables (samplers included).
    pub uniforms: Vec<Var>,
    /// Whether it reads `gl_PointCoord` (fragment shaders).
    pub point_coord: bool,
    /// Whether it writes `gl_FragDepthEXT` (fragment shaders, `GL_EXT_frag_depth`).
    pub frag_depth: bool,
    /// Whether it reads `gl_InstanceIDEXT` (vertex shaders, `GL_EXT_draw_instanced`).
    pub instance_id: bool,
    /// Whether it reads `gl_VertexID` (vertex shaders, GLSL ES 3.00).
    pub vertex_id: bool,
    /// The generated functions standing in for built-ins naga lacks that it calls
    /// (`polyfill`).
    pub polyfills: std::collections::BTreeSet<&'static str>,
    /// Whether it uses `gl_FragData` (fragment shaders, `GL_EXT_draw_buffers`), or
    /// `gl_SecondaryFragDataEXT`.
    pub frag_data: bool,
    /// Whether it writes a second colour for dual-source blending (fragment shaders,
    /// `GL_EXT_blend_func_extended`).
    pub dual: bool,
    /// Whether it defines `main` (a program without one fails to link).
    pub has_main: bool,
    /// The 2D and 3D lookups it makes of its sampler uniforms, by (sampler, GLSL 450 function,
    /// whether 3D), each a call of a generated helper (`link::lookup_helpers`); `""` for a
    /// sampler parameter.
    pub lookups: std::collections::BTreeSet<(String, String, bool)>,
    /// Its uniforms of structure types, as the link needs them.
    pub structs: StructUniforms,
    /// The info log of a successful compile (warnings), empty if none.
    pub log: String,
    /// The source it was compiled from (what a program binary holds).
    pub source: String,
    /// What linking checks across stages.
    pub facts: Facts,
    /// Byte offset of each source line's start, to name the line of an error found later.
    pub(crate) line_starts: Vec<usize>,
}

impl Shader {
    /// The 1-based source line of byte `offset`.
    pub(crate) fn line_of(&self, offset: usize) -> u32 {
        self.line_starts.partition_point(|&s| s <= offset).max(1) as u32
    }
}

/// What the checks learnt that linking needs.
#[derive(Debug, Clone, Default)]
pub struct Facts {
    /// Precision of each float or int uniform.
    pub uniform_precisions: HashMap<String, ast::PrecisionQualifierData>,
    /// Precision of each varying.
    pub varying_precisions: HashMap<String, ast::PrecisionQualifierData>,
    /// Every variable name the shader's functions read or write.
    pub used: HashSet<String>,
    /// Built-in variables declared `invariant`.
    pub invariants: HashSet<String>,
}

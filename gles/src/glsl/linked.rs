//! A linked program's interface as the linker leaves it (uniform slots, attributes, samplers,
//! the translated stages), and the conventions every generated stage follows.

use crate::glsl::types::{Block, Scalar, Shader, Ty, Var};
use crate::limits::MAX_DRAW_BUFFERS;

/// A uniform's place in the program's block (or, for samplers, its binding).
#[derive(Debug, Clone)]
pub struct UniformSlot {
    /// The name as declared (a structure's leaf: the name of its generated uniform).
    pub name: String,
    /// The name GL reports (a structure's leaf: `u[1].a`).
    pub gl_name: String,
    /// Its type.
    pub ty: Ty,
    /// Array length (1 for non-arrays).
    pub len: u32,
    /// Whether declared as an array.
    pub is_array: bool,
    /// Byte offset of element 0 in the block.
    pub offset: u32,
    /// Bytes between array elements (std140).
    pub stride: u32,
    /// For samplers: index into the program's sampler list.
    pub sampler: Option<usize>,
}

/// A uniform block of a linked program.
#[derive(Debug, Clone)]
pub struct LinkedBlock {
    /// The block, laid out.
    pub block: Block,
    /// Its binding in the program's bind group.
    pub binding: u32,
    /// Whether the vertex stage declares it (`GL_UNIFORM_BLOCK_REFERENCED_BY_VERTEX_SHADER`).
    pub vertex: bool,
    /// Whether the fragment stage declares it.
    pub fragment: bool,
}

/// A linked program: naga modules and everything needed to feed them.
#[derive(Debug)]
pub struct Linked {
    /// Vertex stage module.
    pub vertex: naga::Module,
    /// Fragment stage module.
    pub fragment: naga::Module,
    /// Attributes with their locations.
    pub attributes: Vec<(Var, u32)>,
    /// Every uniform (samplers included), in declaration order.
    pub uniforms: Vec<UniformSlot>,
    /// Bytes of the uniform block (0 if none).
    pub block_size: u32,
    /// Sampler uniforms: (type, bind-group binding of the texture; the sampler and the border
    /// sampler follow).
    pub samplers: Vec<(Ty, u32)>,
    /// Per sampler: the block offset of its wrap flags, a `vec4` whose x and y are 1.0 where
    /// s and t wrap by `GL_MIRROR_CLAMP_TO_EDGE_EXT` and z where either wraps by
    /// `GL_CLAMP_TO_BORDER_EXT`, followed by its border colour (the draw writes both; see
    /// [`lookup_helpers`]).
    pub wrap_offsets: Vec<u32>,
    /// The vertex stage of `GL_POINTS` draws, as GLSL (parsed on first use by
    /// [`points_vertex`]): one instance per point, four vertices per instance, expanded to a
    /// square of `gl_PointSize` pixels with `gl_PointCoord` for the fragment stage.
    pub points_source: String,
    /// The vertex stage as GLSL, for its reversed-Z variants ([`Linked::reversed_vertex`]).
    pub vertex_source: String,
    /// The fragment stage's reversed-Z variant as GLSL, when it reads `gl_FragCoord` or
    /// writes `gl_FragDepthEXT` ([`Linked::reversed_fragment`]).
    pub reversed_fragment_source: Option<String>,
    /// The vertex input location of the points stage's `strata_point` parameter:
    /// (1 / viewport width, 1 / viewport height, 0, 0), constant over the draw.
    pub point_input: u32,
    /// Whether the fragment stage writes a second colour (`GL_EXT_blend_func_extended`): its
    /// one output is location 0's two blend sources.
    pub dual: bool,
    /// GLSL ES 3.00 uniform blocks, by block index.
    pub blocks: Vec<LinkedBlock>,
    /// GLSL ES 3.00 fragment outputs by name, with their locations (`glGetFragDataLocation`).
    pub outputs: Vec<(String, u32)>,
    /// What the fragment shader writes at each location (draw buffer).
    pub output_kinds: [OutputKind; crate::limits::MAX_DRAW_BUFFERS],
    /// Whether a varying reaches the fragment stage `flat`: its value is then the last
    /// vertex's of each primitive, as GL takes it (wgpu takes the first's).
    pub flat: bool,
    /// What transform feedback captures (`glTransformFeedbackVaryings` before the link).
    pub capture: Option<crate::glsl::capture::Capture>,
}

/// The vertex stage's `gl_VertexID` step, which an unrolled capture replaces.
pub(crate) const VERTEX_ID_STEP: &str = "    strata_VertexID = int(gl_VertexIndex);\n";

/// The points stage's first step after the shader's `main` and its copies: where a
/// capturing variant stores the vertex, before the point is expanded.
pub(crate) const POINT_SIZE_STEP: &str = "    float strata_size";

/// The vertex stage's last steps, Strata's conventions: y negated, clip z mapped to [0, 1]
/// (`variants::FLIP_Y` and `variants::FORWARD_Z`, which the stage's variants replace).
pub(crate) const CONVENTIONS: &str =
    "    gl_Position.y = -gl_Position.y;\n    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;\n";

/// The generated fragment `main`'s last step where the shader writes `gl_FragDepthEXT`
/// (`GL_EXT_frag_depth`): the value, clamped to [0, 1] as GL stores it, is the fragment's depth.
pub(crate) const FRAG_DEPTH_OUT: &str = "    gl_FragDepth = clamp(strata_FragDepth, 0.0, 1.0);\n";

/// The declarator suffix of a variable: `[n]` for an array of n, else nothing.
pub(crate) fn array_suffix(v: &Var) -> String {
    v.array.map_or(String::new(), |n| format!("[{n}]"))
}

/// What a fragment shader writes at one location: nothing, floats (to a normalized or float
/// colour buffer), or signed or unsigned integers (to an integer one).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// No output there.
    None,
    /// Floating-point colour.
    Float,
    /// Signed integers (`int`, `ivecN`).
    Int,
    /// Unsigned integers (`uint`, `uvecN`).
    UInt,
}

impl OutputKind {
    /// Whether a colour buffer of `format` takes what is written here: any buffer when
    /// nothing is, else a buffer of the same kind of values.
    pub fn fits(self, format: wgpu::TextureFormat) -> bool {
        use wgpu::TextureSampleType as T;
        matches!(
            (self, format.sample_type(None, None)),
            (OutputKind::None, _)
                | (OutputKind::Float, Some(T::Float { .. }))
                | (OutputKind::Int, Some(T::Sint))
                | (OutputKind::UInt, Some(T::Uint))
        )
    }
}

/// What the fragment shader `fs` writes at each location (see [`Linked::output_kinds`]):
/// GLSL ES 3.00's outputs at theirs (a lone one without a location at 0), GLSL ES 1.00's
/// colour floats at every location.
pub(super) fn output_kinds(fs: &Shader) -> [OutputKind; MAX_DRAW_BUFFERS] {
    if fs.version != 300 || fs.dual {
        return [OutputKind::Float; MAX_DRAW_BUFFERS];
    }
    let mut kinds = [OutputKind::None; MAX_DRAW_BUFFERS];
    for o in &fs.outputs {
        let kind = match o.ty.scalar() {
            Scalar::Int => OutputKind::Int,
            Scalar::UInt => OutputKind::UInt,
            _ => OutputKind::Float,
        };
        let loc = o.location.unwrap_or(0) as usize;
        for k in kinds.iter_mut().skip(loc).take(o.array.unwrap_or(1) as usize) {
            *k = kind;
        }
    }
    kinds
}

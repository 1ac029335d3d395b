//! GLSL ES 1.00 → Vulkan-flavoured GLSL 450 → naga.
//!
//! naga's GLSL front end accepts only GLSL 440+, so each ES shader is preprocessed and parsed
//! with glsl-lang (with `GL_ES` defined), its global interface is lifted out, and its AST is
//! rewritten: `gl_FragColor` and `gl_FragData` become variables that the generated `main`
//! copies to one output per draw buffer, the built-in constants become literals, `texture2D`-style
//! calls become `texture(sampler2D(t, s), …)` on split texture/sampler bindings, precision
//! qualifiers go, and `main` is renamed so that a generated `main` can apply Strata's
//! conventions (y negated, clip z mapped from [-1, 1] to [0, 1]). Linking then packs every loose
//! uniform of both stages into one std140 block at set 0, binding 0, assigns attribute and
//! varying locations, and hands the generated sources to naga to parse and validate.
//!
//! | module | step |
//! |---|---|
//! | `preprocess` | `#version` check, `GL_ES` defines, preprocessing and parsing |
//! | `interface` | lifting attributes, varyings and uniforms out of the AST; ES restrictions |
//! | `rewrite` | the AST rewrite to Vulkan-flavoured GLSL |
//! | `link` | the program-wide uniform block, locations, generated `main`s |
//! | `separate` | one-stage programs, and two programs' stages linked into one executable |
//! | `translate` | the generated code with its source lines; naga, errors at the shader's line |

mod checks;
mod consts;
mod interface;
mod link;
mod precision;
mod preprocess;
mod rewrite;
mod separate;
mod translate;
mod variants;
mod writes;

use glsl_lang::ast::{self, TypeSpecifierNonArrayData as T};

pub use link::{link, points_vertex, Linked, UniformSlot};
pub use separate::{fragment_uniform_name, interfaces_match, link_alone, rename_uniforms};
pub use variants::ClipZ;

use crate::enums as gl;

/// A shader stage.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Vertex shader.
    Vertex,
    /// Fragment shader.
    Fragment,
}

/// The GLSL ES 1.00 types an interface variable can have.
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
    Bool,
    BVec2,
    BVec3,
    BVec4,
    Mat2,
    Mat3,
    Mat4,
    Sampler2D,
    SamplerCube,
    /// `samplerExternalOES` (`GL_OES_EGL_image_external`), sampled as a 2D image.
    SamplerExternal,
    /// `sampler3D` (`GL_OES_texture_3D`).
    Sampler3D,
}

/// `GL_SAMPLER_EXTERNAL_OES`, the type `glGetActiveUniform` reports for `samplerExternalOES`.
const SAMPLER_EXTERNAL_OES: u32 = 0x8D66;

impl Ty {
    fn from_spec(t: &T) -> Option<Ty> {
        Some(match t {
            T::Float => Ty::Float,
            T::Vec2 => Ty::Vec2,
            T::Vec3 => Ty::Vec3,
            T::Vec4 => Ty::Vec4,
            T::Int => Ty::Int,
            T::IVec2 => Ty::IVec2,
            T::IVec3 => Ty::IVec3,
            T::IVec4 => Ty::IVec4,
            T::Bool => Ty::Bool,
            T::BVec2 => Ty::BVec2,
            T::BVec3 => Ty::BVec3,
            T::BVec4 => Ty::BVec4,
            T::Mat2 => Ty::Mat2,
            T::Mat3 => Ty::Mat3,
            T::Mat4 => Ty::Mat4,
            T::Sampler2D => Ty::Sampler2D,
            T::SamplerCube => Ty::SamplerCube,
            T::Sampler3D => Ty::Sampler3D,
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
            Ty::Bool => gl::BOOL,
            Ty::BVec2 => gl::BOOL_VEC2,
            Ty::BVec3 => gl::BOOL_VEC3,
            Ty::BVec4 => gl::BOOL_VEC4,
            Ty::Mat2 => gl::FLOAT_MAT2,
            Ty::Mat3 => gl::FLOAT_MAT3,
            Ty::Mat4 => gl::FLOAT_MAT4,
            Ty::Sampler2D => gl::SAMPLER_2D,
            Ty::SamplerCube => gl::SAMPLER_CUBE,
            Ty::SamplerExternal => SAMPLER_EXTERNAL_OES,
            Ty::Sampler3D => gl::SAMPLER_3D_OES,
        }
    }

    /// GLSL spelling; booleans live in the block as integers.
    fn glsl(self, in_block: bool) -> &'static str {
        match self {
            Ty::Float => "float",
            Ty::Vec2 => "vec2",
            Ty::Vec3 => "vec3",
            Ty::Vec4 => "vec4",
            Ty::Int => "int",
            Ty::IVec2 => "ivec2",
            Ty::IVec3 => "ivec3",
            Ty::IVec4 => "ivec4",
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
            Ty::Sampler2D | Ty::SamplerExternal => "texture2D",
            Ty::SamplerCube => "textureCube",
            Ty::Sampler3D => "texture3D",
        }
    }

    /// Scalars per element (a matrix counts all its entries).
    pub fn components(self) -> usize {
        match self {
            Ty::Float | Ty::Int | Ty::Bool | Ty::Sampler2D | Ty::SamplerCube | Ty::SamplerExternal | Ty::Sampler3D => 1,
            Ty::Vec2 | Ty::IVec2 | Ty::BVec2 => 2,
            Ty::Vec3 | Ty::IVec3 | Ty::BVec3 => 3,
            Ty::Vec4 | Ty::IVec4 | Ty::BVec4 | Ty::Mat2 => 4,
            Ty::Mat3 => 9,
            Ty::Mat4 => 16,
        }
    }

    /// Matrix columns (0 for non-matrices).
    pub fn columns(self) -> usize {
        match self {
            Ty::Mat2 => 2,
            Ty::Mat3 => 3,
            Ty::Mat4 => 4,
            _ => 0,
        }
    }

    /// What a `glUniform*` call must match: float, int (and samplers), or bool (either).
    pub fn scalar(self) -> Scalar {
        match self {
            Ty::Int | Ty::IVec2 | Ty::IVec3 | Ty::IVec4 => Scalar::Int,
            Ty::Sampler2D | Ty::SamplerCube | Ty::SamplerExternal | Ty::Sampler3D => Scalar::Int,
            Ty::Bool | Ty::BVec2 | Ty::BVec3 | Ty::BVec4 => Scalar::Bool,
            _ => Scalar::Float,
        }
    }

    /// Whether this is a sampler.
    pub fn is_sampler(self) -> bool {
        matches!(self, Ty::Sampler2D | Ty::SamplerCube | Ty::SamplerExternal | Ty::Sampler3D)
    }

    /// std140 (size, alignment) of one element that is not in an array.
    fn std140(self) -> (u32, u32) {
        match self {
            Ty::Float | Ty::Int | Ty::Bool => (4, 4),
            Ty::Vec2 | Ty::IVec2 | Ty::BVec2 => (8, 8),
            Ty::Vec3 | Ty::IVec3 | Ty::BVec3 => (12, 16),
            Ty::Vec4 | Ty::IVec4 | Ty::BVec4 => (16, 16),
            Ty::Mat2 => (32, 16),
            Ty::Mat3 => (48, 16),
            Ty::Mat4 => (64, 16),
            Ty::Sampler2D | Ty::SamplerCube | Ty::SamplerExternal | Ty::Sampler3D => (0, 1),
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
}

/// A successfully compiled shader, kept for linking.
#[derive(Debug, Clone)]
pub struct Shader {
    /// The stage.
    pub stage: Stage,
    body: ast::TranslationUnit,
    /// `attribute` variables.
    pub attributes: Vec<Var>,
    /// `varying` variables.
    pub varyings: Vec<Var>,
    /// `uniform` variables (samplers included).
    pub uniforms: Vec<Var>,
    /// Whether it reads `gl_PointCoord` (fragment shaders).
    pub point_coord: bool,
    /// Whether it writes `gl_FragDepthEXT` (fragment shaders, `GL_EXT_frag_depth`).
    pub frag_depth: bool,
    /// Whether it reads `gl_InstanceIDEXT` (vertex shaders, `GL_EXT_draw_instanced`).
    pub instance_id: bool,
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
    /// The info log of a successful compile (warnings), empty if none.
    pub log: String,
    /// The source it was compiled from (what a program binary holds).
    pub source: String,
    /// What linking checks across stages.
    pub facts: checks::Facts,
    /// Byte offset of each source line's start, to name the line of an error found later.
    line_starts: Vec<usize>,
}

impl Shader {
    /// The 1-based source line of byte `offset`.
    fn line_of(&self, offset: usize) -> u32 {
        self.line_starts.partition_point(|&s| s <= offset).max(1) as u32
    }
}

/// Compiles (parses and checks) a GLSL ES 1.00 shader. The error is the info log.
pub fn compile(stage: Stage, source: &str) -> Result<Shader, String> {
    // The parser and rewriter are third-party code fed client text: a panic there must become
    // a failed compile, never a dead session.
    // Type errors inside function bodies are found by naga: each stage is translated once
    // here, against a stand-in for the other stage, so that they fail the compile with a line.
    std::panic::catch_unwind(|| interface::compile_inner(stage, source).and_then(link::check_stage))
        .unwrap_or_else(|_| Err("0: internal error: the GLSL ES front end failed on this shader".into()))
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    const VS: &str =
        "attribute vec3 position; attribute vec2 uv; uniform mat4 mvp; uniform float k[3]; varying vec2 v_uv;
        void main() { v_uv = uv * k[1]; gl_Position = mvp * vec4(position, 1.0); }";
    const FS: &str = "#ifdef GL_ES\nprecision mediump float;\n#endif\nvarying vec2 v_uv; uniform sampler2D tex; uniform bool flip; uniform lowp vec4 tint;
        vec4 shade(vec2 c) { return texture2D(tex, c) * tint; }
        void main() { vec2 c = flip ? v_uv.yx : v_uv; gl_FragColor = shade(c); }";

    #[test]
    fn links_and_lays_out_std140() {
        let vs = compile(Stage::Vertex, VS).expect("vs");
        let fs = compile(Stage::Fragment, FS).expect("fs");
        let mut bind = HashMap::new();
        bind.insert("uv".to_string(), 0);
        let l = link(&vs, &fs, &bind, 16).expect("link");
        let find = |n: &str| l.uniforms.iter().find(|u| u.name == n).expect(n).clone();
        assert_eq!((find("mvp").offset, find("k").offset, find("k").stride), (0, 64, 16));
        assert_eq!(find("flip").offset, 112);
        assert_eq!(find("tint").offset, 128);
        // The sampler's wrap flags and border colour follow the uniforms.
        assert_eq!(l.wrap_offsets, vec![144]);
        assert_eq!(l.block_size, 176);
        assert_eq!(l.attributes.iter().find(|(a, _)| a.name == "uv").map(|x| x.1), Some(0));
        assert_eq!(l.attributes.iter().find(|(a, _)| a.name == "position").map(|x| x.1), Some(1));
        assert_eq!(l.samplers, vec![(Ty::Sampler2D, 1)]);
    }

    #[test]
    fn precision_only_qualifiers_are_dropped() {
        let vs = compile(Stage::Vertex, "attribute highp vec4 p; varying lowp vec4 c; void main() { highp float k = 1.0; c = p * k; gl_Position = p; }").expect("vs");
        let fs = compile(Stage::Fragment, "varying lowp vec4 c; mediump vec4 f(in lowp vec4 x, mediump float k) { return x * k; } void main() { gl_FragColor = f(c, 1.0); }").expect("fs");
        link(&vs, &fs, &HashMap::new(), 16).expect("link");
    }

    #[test]
    fn errors_become_info_logs() {
        assert!(compile(Stage::Vertex, "void main() { gl_Position = vec4(1.0) }").is_err());
        assert!(compile(Stage::Fragment, "attribute vec4 a; void main() {}").is_err());
        let no_main = compile(Stage::Vertex, "void notmain() { gl_Position = vec4(0.0); }").expect("compiles");
        let fs_ok = compile(Stage::Fragment, "void main() { gl_FragColor = vec4(0.0); }").expect("fs");
        let e = link(&no_main, &fs_ok, &HashMap::new(), 16).expect_err("no main");
        assert_eq!(e, "error: vertex shader lacks `main'");
        let vs = compile(Stage::Vertex, "varying vec2 a; void main() { gl_Position = vec4(0.0); }").expect("vs");
        let fs = compile(Stage::Fragment, "varying mediump vec3 b; void main() { gl_FragColor = vec4(b, 1.0); }")
            .expect("fs");
        let e = link(&vs, &fs, &HashMap::new(), 16).expect_err("unmatched varying");
        assert!(e.contains("'b'"), "{e}");
        let e = compile(
            Stage::Fragment,
            "precision mediump float;\nvoid main() {\n  float a = 1.0;\n  gl_FragColor =\n vec4(undefined_thing);\n}",
        )
        .expect_err("an unknown identifier");
        assert!(e.starts_with("0:4("), "the info log names the statement's line: {e}");
        assert!(e.contains("undefined_thing"), "{e}");
        let e = compile(Stage::Vertex, "attribute vec4 p;\nvoid main() {\n  vec3 v = p;\n  gl_Position = p;\n}")
            .expect_err("a vec4 assigned to a vec3");
        assert!(e.starts_with("0:3("), "the info log names the statement's line: {e}");
        assert!(e.contains("'main'"), "the shader's own names: {e}");
    }
}

#[cfg(test)]
mod conformance_tests;

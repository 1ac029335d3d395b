//! GLSL ES 1.00 → Vulkan-flavoured GLSL 450 → naga.
//!
//! naga's GLSL front end accepts only GLSL 440+, so each ES shader is preprocessed and parsed
//! with glsl-lang (with `GL_ES` defined), its global interface is lifted out, and its AST is
//! rewritten: `gl_FragColor`/`gl_FragData[0]` become an `out` variable, `texture2D`-style
//! calls become `texture(sampler2D(t, s), …)` on split texture/sampler bindings, precision
//! qualifiers go, and `main` is renamed so that a generated `main` can apply Strata's
//! conventions (y negated, clip z mapped from [-1, 1] to [0, 1]). Linking then packs every loose
//! uniform of both stages into one std140 block at set 0, binding 0, assigns attribute and
//! varying locations, and hands the generated sources to naga to parse and validate.

use std::collections::HashMap;
use std::fmt::Write as _;

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeQualifierSpecData, TypeSpecifierNonArrayData as T};
use glsl_lang::lexer::full::fs::PreprocessorExt;
use glsl_lang::parse::IntoParseBuilderExt;
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};
use glsl_lang_pp::processor::nodes::{Define, DefineObject};
use glsl_lang_pp::processor::ProcessorState;

use super::enums as gl;

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
}

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
            Ty::Sampler2D => "texture2D",
            Ty::SamplerCube => "textureCube",
        }
    }

    /// Scalars per element (a matrix counts all its entries).
    pub fn components(self) -> usize {
        match self {
            Ty::Float | Ty::Int | Ty::Bool | Ty::Sampler2D | Ty::SamplerCube => 1,
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
            Ty::Int | Ty::IVec2 | Ty::IVec3 | Ty::IVec4 | Ty::Sampler2D | Ty::SamplerCube => Scalar::Int,
            Ty::Bool | Ty::BVec2 | Ty::BVec3 | Ty::BVec4 => Scalar::Bool,
            _ => Scalar::Float,
        }
    }

    /// Whether this is a sampler.
    pub fn is_sampler(self) -> bool {
        matches!(self, Ty::Sampler2D | Ty::SamplerCube)
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
            Ty::Sampler2D | Ty::SamplerCube => (0, 1),
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
}

fn parse(stage: Stage, source: &str) -> Result<ast::TranslationUnit, String> {
    // `#version 100` is the only version ES 2.0 has; drop it (keeping line numbers) so the
    // parser uses its default grammar.
    let mut text = String::with_capacity(source.len());
    for line in source.lines() {
        if line.trim_start().starts_with("#version") {
            let v = line.trim_start().trim_start_matches("#version").trim();
            if !(v == "100" || v.starts_with("100 ")) {
                return Err(format!("0:1: '#version {v}' : GLSL ES 1.00 (version 100) is the only version supported"));
            }
            text.push('\n');
        } else {
            text.push_str(line);
            text.push('\n');
        }
    }
    let gl_es = "1".parse::<DefineObject>().map_err(|e| format!("internal: {e:?}"))?;
    let mut state = ProcessorState::builder().definition(Define::object("GL_ES".into(), gl_es.clone(), true));
    if stage == Stage::Fragment {
        // Fragment shaders get real f32 precision, so highp is supported (as on Mesa).
        state = state.definition(Define::object("GL_FRAGMENT_PRECISION_HIGH".into(), gl_es, true));
    }
    let state = state.finish();
    let mut pp = glsl_lang_pp::processor::fs::StdProcessor::new();
    let parsed = pp.open_source(&text, ".").with_state(state).builder::<ast::TranslationUnit>().parse();
    match parsed {
        Ok((tu, _, _)) => Ok(tu),
        Err(e) => Err(format!("0:{e}")),
    }
}

fn array_len(spec: Option<&ast::ArraySpecifier>) -> Result<Option<u32>, String> {
    let Some(spec) = spec else { return Ok(None) };
    match spec.dimensions.as_slice() {
        [d] => match &d.content {
            ast::ArraySpecifierDimensionData::ExplicitlySized(e) => match &e.content {
                ExprData::IntConst(n) if *n > 0 => Ok(Some(*n as u32)),
                _ => Err("array sizes of interface variables must be positive integer constants".into()),
            },
            ast::ArraySpecifierDimensionData::Unsized => Err("unsized arrays are not allowed".into()),
        },
        _ => Err("arrays of arrays are not allowed in GLSL ES 1.00".into()),
    }
}

enum Storage {
    Attribute,
    Varying,
    Uniform,
}

fn storage_of(q: Option<&ast::TypeQualifier>) -> Option<Storage> {
    q?.qualifiers.iter().find_map(|s| match &s.content {
        TypeQualifierSpecData::Storage(st) => match st.content {
            ast::StorageQualifierData::Attribute => Some(Storage::Attribute),
            ast::StorageQualifierData::Varying => Some(Storage::Varying),
            ast::StorageQualifierData::Uniform => Some(Storage::Uniform),
            _ => None,
        },
        _ => None,
    })
}

/// Compiles (parses and checks) a GLSL ES 1.00 shader. The error is the info log.
pub fn compile(stage: Stage, source: &str) -> Result<Shader, String> {
    // The parser and rewriter are third-party code fed client text: a panic there must become
    // a failed compile, never a dead session.
    std::panic::catch_unwind(|| compile_inner(stage, source))
        .unwrap_or_else(|_| Err("0: internal error: the GLSL ES front end failed on this shader".into()))
}

fn compile_inner(stage: Stage, source: &str) -> Result<Shader, String> {
    let tu = parse(stage, source)?;
    let mut shader = Shader {
        stage,
        body: ast::TranslationUnit(Vec::new()),
        attributes: vec![],
        varyings: vec![],
        uniforms: vec![],
    };
    let mut has_main = false;
    for decl in tu.0 {
        let list = match &decl.content {
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::Precision(..) => continue,
                ast::DeclarationData::InitDeclaratorList(list) => Some(list.clone()),
                _ => None,
            },
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                has_main |= f.prototype.name.0 == "main";
                None
            }
            _ => None,
        };
        let Some(list) = list else {
            shader.body.0.push(decl);
            continue;
        };
        let Some(storage) = storage_of(list.head.ty.qualifier.as_ref()) else {
            shader.body.0.push(decl);
            continue;
        };
        let ty = Ty::from_spec(&list.head.ty.ty.ty.content).ok_or_else(|| {
            format!("0: interface variables of type '{}' are not supported", type_name(&list.head.ty.ty))
        })?;
        let base_array = array_len(list.head.ty.ty.array_specifier.as_ref())?;
        let mut vars = Vec::new();
        if let Some(name) = &list.head.name {
            vars.push(Var {
                name: name.0.to_string(),
                ty,
                array: array_len(list.head.array_specifier.as_ref())?.or(base_array),
            });
        }
        for t in &list.tail {
            vars.push(Var {
                name: t.ident.ident.0.to_string(),
                ty,
                array: array_len(t.ident.array_spec.as_ref())?.or(base_array),
            });
        }
        if list.head.initializer.is_some() || list.tail.iter().any(|t| t.initializer.is_some()) {
            return Err("0: attribute, varying and uniform variables cannot be initialised".into());
        }
        match storage {
            Storage::Attribute => {
                if stage == Stage::Fragment {
                    return Err("0: 'attribute' is not allowed in a fragment shader".into());
                }
                if ty.scalar() != Scalar::Float || ty.columns() > 0 || vars.iter().any(|v| v.array.is_some()) {
                    return Err("0: attributes must be float, vec2, vec3 or vec4".into());
                }
                shader.attributes.extend(vars);
            }
            Storage::Varying => {
                if ty.scalar() != Scalar::Float || vars.iter().any(|v| v.array.is_some()) {
                    return Err("0: varyings must be non-array float vectors or matrices".into());
                }
                shader.varyings.extend(vars);
            }
            Storage::Uniform => {
                if ty.is_sampler() && vars.iter().any(|v| v.array.is_some()) {
                    return Err("0: sampler arrays are not supported".into());
                }
                shader.uniforms.extend(vars);
            }
        }
    }
    if !has_main {
        return Err("0: no function 'main' defined".into());
    }
    // Functions taking samplers: naga accepts no combined sampler parameters, so each becomes a
    // texture and a sampler parameter, and every call passes both halves.
    let mut sampler_fns: HashMap<String, Vec<bool>> = HashMap::new();
    let mut sampler_params: HashMap<String, Ty> = HashMap::new();
    for decl in &shader.body.0 {
        let proto = match &decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => &f.prototype,
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::FunctionPrototype(p) => p,
                _ => continue,
            },
            _ => continue,
        };
        let flags: Vec<bool> = proto
            .parameters
            .iter()
            .map(|p| match &p.content {
                ast::FunctionParameterDeclarationData::Named(_, d) => match Ty::from_spec(&d.ty.ty.content) {
                    Some(t) if t.is_sampler() => {
                        sampler_params.insert(d.ident.ident.0.to_string(), t);
                        true
                    }
                    _ => false,
                },
                ast::FunctionParameterDeclarationData::Unnamed(_, t) => {
                    Ty::from_spec(&t.ty.content).is_some_and(Ty::is_sampler)
                }
            })
            .collect();
        if flags.iter().any(|f| *f) {
            sampler_fns.insert(proto.name.0.to_string(), flags);
        }
    }
    let mut samplers: HashMap<String, Ty> =
        shader.uniforms.iter().filter(|u| u.ty.is_sampler()).map(|u| (u.name.clone(), u.ty)).collect();
    samplers.extend(sampler_params);
    let mut rewrite = Rewrite {
        sampler_fns,
        samplers,
        bools: shader
            .uniforms
            .iter()
            .filter(|u| u.ty.scalar() == Scalar::Bool)
            .map(|u| (u.name.clone(), u.ty))
            .collect(),
        mat2s: shader
            .uniforms
            .iter()
            .filter(|u| u.ty == Ty::Mat2)
            .map(|u| (u.name.clone(), u.array.is_some()))
            .collect(),
        error: None,
        stage,
    };
    shader.body.visit_mut(&mut rewrite);
    if let Some(e) = rewrite.error {
        return Err(e);
    }
    Ok(shader)
}

fn type_name(t: &ast::TypeSpecifier) -> String {
    let mut s = String::new();
    let _ = glsl_lang::transpiler::glsl::show_type_specifier(&mut s, t, &mut Default::default());
    s
}

/// The AST rewrite applied to every function body and remaining global.
struct Rewrite {
    /// Functions with sampler parameters: which positions are samplers.
    sampler_fns: HashMap<String, Vec<bool>>,
    samplers: HashMap<String, Ty>,
    /// `mat2` uniforms (naga cannot lay out `matCx2` in std140): stored as `vec4[2]` per matrix.
    mat2s: HashMap<String, bool>,
    bools: HashMap<String, Ty>,
    error: Option<String>,
    stage: Stage,
}

/// Removes precision qualifiers, dropping the qualifier altogether if nothing else remains
/// (an empty qualifier list is not valid GLSL, and the transpiler rejects it).
fn strip_precision(q: &mut Option<ast::TypeQualifier>) {
    if let Some(tq) = q {
        tq.qualifiers.retain(|s| !matches!(s.content, TypeQualifierSpecData::Precision(_)));
        if tq.qualifiers.is_empty() {
            *q = None;
        }
    }
}

fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

/// `mat2(strata_m2_NAME[i].xy, strata_m2_NAME[i + 1].xy)` where `i` is `2 * index` or 0.
fn mat2_of(name: &str, index: Option<&ast::Expr>) -> ast::Expr {
    let column = |k: i32| -> ast::Expr {
        let i: ast::Expr = match index {
            Some(idx) => {
                let twice: ast::Expr = ExprData::Binary(
                    ast::BinaryOpData::Mult.into(),
                    Box::new(ExprData::IntConst(2).into()),
                    Box::new(idx.clone()),
                )
                .into();
                ExprData::Binary(ast::BinaryOpData::Add.into(), Box::new(twice), Box::new(ExprData::IntConst(k).into()))
                    .into()
            }
            None => ExprData::IntConst(k).into(),
        };
        let elem: ast::Expr = ExprData::Bracket(Box::new(var(&format!("strata_m2_{name}"))), Box::new(i)).into();
        ExprData::Dot(Box::new(elem), ast::IdentifierData("xy".into()).into()).into()
    };
    ctor(T::Mat2, vec![column(0), column(1)])
}

fn ctor(ty: T, args: Vec<ast::Expr>) -> ast::Expr {
    let spec: ast::TypeSpecifier = ast::TypeSpecifierData { ty: ty.into(), array_specifier: None }.into();
    ExprData::FunCall(FunIdentifierData::TypeSpecifier(Box::new(spec)).into(), args).into()
}

impl VisitorMut for Rewrite {
    fn visit_full_specified_type(&mut self, t: &mut ast::FullySpecifiedType) -> Visit {
        strip_precision(&mut t.qualifier);
        Visit::Children
    }

    fn visit_function_parameter_declaration(&mut self, p: &mut ast::FunctionParameterDeclaration) -> Visit {
        match &mut p.content {
            ast::FunctionParameterDeclarationData::Named(q, _)
            | ast::FunctionParameterDeclarationData::Unnamed(q, _) => strip_precision(q),
        }
        Visit::Children
    }

    fn visit_function_prototype(&mut self, p: &mut ast::FunctionPrototype) -> Visit {
        if p.name.0 == "main" {
            p.name = ast::IdentifierData("strata_main".into()).into();
        }
        if self.sampler_fns.contains_key(p.name.0.as_str()) {
            let mut params = Vec::with_capacity(p.parameters.len() + 2);
            for param in std::mem::take(&mut p.parameters) {
                let split = match &param.content {
                    ast::FunctionParameterDeclarationData::Named(_, d) => Ty::from_spec(&d.ty.ty.content)
                        .filter(|t| t.is_sampler())
                        .map(|t| (t, d.ident.ident.0.to_string())),
                    _ => None,
                };
                match split {
                    Some((t, name)) => {
                        let tex = if t == Ty::SamplerCube { T::TextureCube } else { T::Texture2D };
                        for (ty, suffix) in [(tex, "__t"), (T::Sampler, "__s")] {
                            let spec: ast::TypeSpecifier =
                                ast::TypeSpecifierData { ty: ty.into(), array_specifier: None }.into();
                            let ident: ast::ArrayedIdentifier = ast::ArrayedIdentifierData {
                                ident: ast::IdentifierData(format!("{name}{suffix}").into()).into(),
                                array_spec: None,
                            }
                            .into();
                            let decl: ast::FunctionParameterDeclarator =
                                ast::FunctionParameterDeclaratorData { ty: spec, ident }.into();
                            params.push(ast::FunctionParameterDeclarationData::Named(None, decl).into());
                        }
                    }
                    None => params.push(param),
                }
            }
            p.parameters = params;
        }
        Visit::Children
    }

    fn visit_expr(&mut self, e: &mut ast::Expr) -> Visit {
        let replacement = match &mut e.content {
            ExprData::Variable(id) => {
                let name = id.0.as_str();
                if name == "gl_FragColor" && self.stage == Stage::Fragment {
                    Some(var("strata_FragColor"))
                } else if let Some(ty) = self.samplers.get(name) {
                    let t = if *ty == Ty::Sampler2D { T::Sampler2D } else { T::SamplerCube };
                    Some(ctor(t, vec![var(&format!("{name}__t")), var(&format!("{name}__s"))]))
                } else if self.mat2s.get(name) == Some(&false) {
                    Some(mat2_of(name, None))
                } else if let Some(ty) = self.bools.get(name) {
                    let t = match ty {
                        Ty::BVec2 => T::BVec2,
                        Ty::BVec3 => T::BVec3,
                        Ty::BVec4 => T::BVec4,
                        _ => T::Bool,
                    };
                    Some(ctor(t, vec![var(&format!("strata_b_{name}"))]))
                } else if name == "gl_FragData" {
                    self.error.get_or_insert_with(|| "0: gl_FragData may only be indexed with 0".into());
                    None
                } else {
                    None
                }
            }
            ExprData::Bracket(base, index) => match (&base.content, &index.content) {
                (ExprData::Variable(id), ExprData::IntConst(0)) if id.0 == "gl_FragData" => {
                    Some(var("strata_FragColor"))
                }
                (ExprData::Variable(id), _) if self.mat2s.get(id.0.as_str()) == Some(&true) => {
                    let mut idx = (**index).clone();
                    idx.visit_mut(self);
                    Some(mat2_of(id.0.as_str(), Some(&idx)))
                }
                _ => None,
            },
            ExprData::FunCall(fun, args) => {
                if let FunIdentifierData::Expr(f) = &mut fun.content {
                    if let ExprData::Variable(id) = &mut f.content {
                        if let Some(flags) = self.sampler_fns.get(id.0.as_str()) {
                            // Pass a sampler argument as its texture and sampler halves.
                            let mut expanded = Vec::with_capacity(args.len() + 2);
                            for (arg, is_sampler) in
                                std::mem::take(args).into_iter().zip(flags.iter().chain(std::iter::repeat(&false)))
                            {
                                match (&arg.content, is_sampler) {
                                    (ExprData::Variable(v), true) if self.samplers.contains_key(v.0.as_str()) => {
                                        expanded.push(var(&format!("{}__t", v.0)));
                                        expanded.push(var(&format!("{}__s", v.0)));
                                    }
                                    _ => expanded.push(arg),
                                }
                            }
                            *args = expanded;
                        }
                        // A vertex shader has no derivatives: ES defines its implicit-LOD
                        // lookups as level 0, so they become explicit-LOD lookups.
                        let vertex_implicit = self.stage == Stage::Vertex && args.len() == 2;
                        let renamed = match id.0.as_str() {
                            "texture2D" | "textureCube" if vertex_implicit => Some("textureLod"),
                            "texture2DProj" if vertex_implicit => Some("textureProjLod"),
                            "texture2D" | "textureCube" => Some("texture"),
                            "texture2DProj" => Some("textureProj"),
                            "texture2DLod" | "textureCubeLod" => Some("textureLod"),
                            "texture2DProjLod" => Some("textureProjLod"),
                            _ => None,
                        };
                        if let Some(r) = renamed {
                            if vertex_implicit && r.ends_with("Lod") {
                                args.push(ExprData::FloatConst(0.0).into());
                            }
                            *id = ast::IdentifierData(r.into()).into();
                        }
                    }
                }
                None
            }
            _ => None,
        };
        if let Some(r) = replacement {
            *e = r;
            return Visit::Parent;
        }
        Visit::Children
    }
}

/// A uniform's place in the program's block (or, for samplers, its binding).
#[derive(Debug, Clone)]
pub struct UniformSlot {
    /// The name as declared.
    pub name: String,
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
    /// Sampler uniforms: (type, bind-group binding of the texture; the sampler follows).
    pub samplers: Vec<(Ty, u32)>,
}

fn transpile(tu: &ast::TranslationUnit) -> Result<String, String> {
    let mut s = String::new();
    glsl_lang::transpiler::glsl::show_translation_unit(&mut s, tu, Default::default())
        .map_err(|e| format!("internal: transpiling failed: {e}"))?;
    Ok(s)
}

fn naga_module(stage: naga::ShaderStage, src: &str) -> Result<naga::Module, String> {
    let mut fe = naga::front::glsl::Frontend::default();
    let module = fe.parse(&naga::front::glsl::Options::from(stage), src).map_err(|e| e.emit_to_string(src))?;
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
        .validate(&module)
        .map_err(|e| e.emit_to_string(src))?;
    Ok(module)
}

/// Links a vertex and a fragment shader. `bindings` are `glBindAttribLocation` requests;
/// `max_attribs` bounds locations. The error is the program info log.
pub fn link(vs: &Shader, fs: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Linked, String> {
    std::panic::catch_unwind(|| link_inner(vs, fs, bindings, max_attribs))
        .unwrap_or_else(|_| Err("error: internal error: translating this program failed".into()))
}

fn link_inner(vs: &Shader, fs: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Linked, String> {
    // Uniforms: one program-wide namespace.
    let mut uniforms: Vec<UniformSlot> = Vec::new();
    let mut samplers = Vec::new();
    let mut offset = 0u32;
    for u in vs.uniforms.iter().chain(&fs.uniforms) {
        if let Some(prev) = uniforms.iter().find(|p| p.name == u.name) {
            if prev.ty != u.ty || prev.len != u.array.unwrap_or(1) {
                return Err(format!("error: uniform '{}' is declared with different types in the two stages", u.name));
            }
            continue;
        }
        let len = u.array.unwrap_or(1);
        let (size, align, stride, sampler) = if u.ty.is_sampler() {
            samplers.push((u.ty, 1 + 2 * samplers.len() as u32));
            (0, 1, 0, Some(samplers.len() - 1))
        } else {
            let (size, align) = u.ty.std140();
            if u.array.is_some() {
                let stride = size.div_ceil(16) * 16;
                (stride * len, 16, stride, None)
            } else {
                (size, align, size, None)
            }
        };
        offset = offset.div_ceil(align) * align;
        uniforms.push(UniformSlot {
            name: u.name.clone(),
            ty: u.ty,
            len,
            is_array: u.array.is_some(),
            offset,
            stride,
            sampler,
        });
        offset += size;
    }
    let block_size = offset.div_ceil(16) * 16;

    // Attributes: bound locations first, then the lowest free ones.
    let mut attributes: Vec<(Var, u32)> = Vec::new();
    let mut used = vec![false; max_attribs as usize];
    for a in &vs.attributes {
        if let Some(&loc) = bindings.get(&a.name) {
            if loc >= max_attribs {
                return Err(format!("error: attribute '{}' bound to location {loc} beyond the limit", a.name));
            }
            used[loc as usize] = true;
            attributes.push((a.clone(), loc));
        }
    }
    for a in &vs.attributes {
        if bindings.contains_key(&a.name) {
            continue;
        }
        let loc = used.iter().position(|u| !u).ok_or_else(|| "error: too many vertex attributes".to_string())?;
        used[loc] = true;
        attributes.push((a.clone(), loc as u32));
    }

    // Varyings: every fragment input must be a vertex output of the same type.
    for v in &fs.varyings {
        match vs.varyings.iter().find(|o| o.name == v.name) {
            Some(o) if o.ty == v.ty => {}
            Some(_) => return Err(format!("error: varying '{}' has different types in the two stages", v.name)),
            None => return Err(format!("error: fragment varying '{}' is not written by the vertex shader", v.name)),
        }
    }

    let mut common = String::from("#version 450\n");
    if block_size > 0 {
        common.push_str("layout(std140, set = 0, binding = 0) uniform StrataUniforms {\n");
        for u in uniforms.iter().filter(|u| !u.ty.is_sampler()) {
            if u.ty == Ty::Mat2 {
                let _ = writeln!(common, "    vec4 strata_m2_{}[{}];", u.name, 2 * u.len);
                continue;
            }
            let name = if u.ty.scalar() == Scalar::Bool { format!("strata_b_{}", u.name) } else { u.name.clone() };
            let arr = if u.is_array { format!("[{}]", u.len) } else { String::new() };
            let _ = writeln!(common, "    {} {name}{arr};", u.ty.glsl(true));
        }
        common.push_str("};\n");
    }
    for u in uniforms.iter().filter(|u| u.ty.is_sampler()) {
        let binding = samplers[u.sampler.unwrap_or(0)].1;
        let _ = writeln!(common, "layout(set = 0, binding = {binding}) uniform {} {}__t;", u.ty.glsl(true), u.name);
        let _ = writeln!(common, "layout(set = 0, binding = {}) uniform sampler {}__s;", binding + 1, u.name);
    }

    let mut vsrc = common.clone();
    for (a, loc) in &attributes {
        let _ = writeln!(vsrc, "layout(location = {loc}) in {} {};", a.ty.glsl(false), a.name);
    }
    // Varying locations: one per vector, one per column of a matrix. Matrices cannot cross
    // stages in naga, so a matrix varying is a private global in each stage, copied through
    // column vectors in the generated `main`s.
    let mut locations: HashMap<&str, u32> = HashMap::new();
    let mut next = 0u32;
    for v in &vs.varyings {
        locations.insert(v.name.as_str(), next);
        next += v.ty.columns().max(1) as u32;
    }
    let column_ty = |ty: Ty| match ty {
        Ty::Mat2 => "vec2",
        Ty::Mat3 => "vec3",
        _ => "vec4",
    };
    let mut vs_copy = String::new();
    for v in &vs.varyings {
        let loc = locations[v.name.as_str()];
        match v.ty.columns() {
            0 => {
                let _ = writeln!(vsrc, "layout(location = {loc}) out {} {};", v.ty.glsl(false), v.name);
            }
            cols => {
                let _ = writeln!(vsrc, "{} {};", v.ty.glsl(false), v.name);
                for c in 0..cols {
                    let _ = writeln!(
                        vsrc,
                        "layout(location = {}) out {} {}__c{c};",
                        loc + c as u32,
                        column_ty(v.ty),
                        v.name
                    );
                    let _ = writeln!(vs_copy, "    {}__c{c} = {}[{c}];", v.name, v.name);
                }
            }
        }
    }
    vsrc.push_str(&transpile(&vs.body)?);
    vsrc.push_str(&format!(
        "\nvoid main() {{\n    strata_main();\n{vs_copy}    gl_Position.y = -gl_Position.y;\n    gl_Position.z = (gl_Position.z + gl_Position.w) * 0.5;\n}}\n"
    ));

    let mut fsrc = common;
    let mut fs_copy = String::new();
    for v in &fs.varyings {
        let loc = locations.get(v.name.as_str()).copied().unwrap_or(0);
        match v.ty.columns() {
            0 => {
                let _ = writeln!(fsrc, "layout(location = {loc}) in {} {};", v.ty.glsl(false), v.name);
            }
            cols => {
                let _ = writeln!(fsrc, "{} {};", v.ty.glsl(false), v.name);
                let mut parts = Vec::new();
                for c in 0..cols {
                    let _ = writeln!(
                        fsrc,
                        "layout(location = {}) in {} {}__c{c};",
                        loc + c as u32,
                        column_ty(v.ty),
                        v.name
                    );
                    parts.push(format!("{}__c{c}", v.name));
                }
                let _ = writeln!(fs_copy, "    {} = {}({});", v.name, v.ty.glsl(false), parts.join(", "));
            }
        }
    }
    fsrc.push_str("layout(location = 0) out vec4 strata_FragColor;\n");
    fsrc.push_str(&transpile(&fs.body)?);
    fsrc.push_str(&format!("\nvoid main() {{\n{fs_copy}    strata_main();\n}}\n"));

    let vertex = naga_module(naga::ShaderStage::Vertex, &vsrc).map_err(|e| format!("vertex shader:\n{e}"))?;
    let fragment = naga_module(naga::ShaderStage::Fragment, &fsrc).map_err(|e| format!("fragment shader:\n{e}"))?;
    Ok(Linked { vertex, fragment, attributes, uniforms, block_size, samplers })
}

#[cfg(test)]
mod tests {
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
        assert_eq!(l.block_size, 144);
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
        assert!(compile(Stage::Vertex, "void notmain() {}").is_err());
        let vs = compile(Stage::Vertex, "varying vec2 a; void main() { gl_Position = vec4(0.0); }").expect("vs");
        let fs = compile(Stage::Fragment, "varying vec3 b; void main() { gl_FragColor = vec4(b, 1.0); }").expect("fs");
        let e = link(&vs, &fs, &HashMap::new(), 16).expect_err("unmatched varying");
        assert!(e.contains("'b'"), "{e}");
        let fs = compile(Stage::Fragment, "void main() { gl_FragColor = vec4(undefined_thing); }").expect("compiles");
        assert!(link(&vs, &fs, &HashMap::new(), 16).is_err(), "type errors surface at link");
    }
}

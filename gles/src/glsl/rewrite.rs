//! The AST rewrite from GLSL ES 1.00 to Vulkan-flavoured GLSL 450 that naga accepts: the
//! fragment output, split texture/sampler bindings, lookups renamed, precision dropped, `main`
//! renamed so that a generated `main` can wrap it, booleans and `mat2`s read from the block,
//! `gl_PointSize`/`gl_PointCoord` replaced by the variables of the point-quad expansion.

use std::collections::HashMap;

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeQualifierSpecData, TypeSpecifierNonArrayData as T};
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};

use crate::glsl::block_members::{ctor, two_rows};
use crate::glsl::int_samplers;
use crate::glsl::types::{Stage, Ty};
use crate::limits::MAX_DRAW_BUFFERS;

/// The AST rewrite applied to every function body and remaining global.
pub(super) struct Rewrite {
    /// Functions with sampler parameters: which positions are samplers.
    pub(super) sampler_fns: HashMap<String, Vec<bool>>,
    /// Sampler uniforms and parameters, by name (an array's elements as `NAME__K`).
    pub(super) samplers: HashMap<String, Ty>,
    /// The names of sampler parameters (the other samplers are uniforms).
    pub(super) sampler_params: std::collections::HashSet<String>,
    /// The 2D and 3D lookups made, by (sampler uniform, GLSL 450 function, whether 3D); `""`
    /// for a parameter's.
    pub(super) lookups: std::collections::BTreeSet<(String, String, bool)>,
    /// Sampler array uniforms: their lengths, by name.
    pub(super) sampler_arrays: HashMap<String, u32>,
    /// `matCx2` uniforms (naga cannot lay them out in std140): stored as `vec4[C]` per matrix,
    /// with their type; the flag says whether it is an array.
    pub(super) mat2s: HashMap<String, (Ty, bool)>,
    /// Boolean uniforms, stored as integers in the block, with their array lengths.
    pub(super) bools: HashMap<String, (Ty, Option<u32>)>,
    /// The first error found.
    pub(super) error: Option<String>,
    /// The stage rewritten.
    pub(super) stage: Stage,
    /// The language version: 100 or 300.
    pub(super) version: u16,
    /// Whether the (vertex) shader reads `gl_VertexID` (GLSL ES 3.00).
    pub(super) vertex_id: bool,
    /// The built-ins naga lacks that the shader calls, as the names of the generated functions
    /// that stand in for them (`polyfill`).
    pub(super) polyfills: std::collections::BTreeSet<&'static str>,
    /// Whether the (fragment) shader reads `gl_PointCoord`.
    pub(super) point_coord: bool,
    /// Whether the (fragment) shader writes `gl_FragDepthEXT`.
    pub(super) frag_depth: bool,
    /// Whether the (vertex) shader reads `gl_InstanceIDEXT`.
    pub(super) instance_id: bool,
    /// Whether the (fragment) shader uses `gl_FragColor`.
    pub(super) frag_color: bool,
    /// Whether the (fragment) shader uses `gl_FragData` (`GL_EXT_draw_buffers`).
    pub(super) frag_data: bool,
    /// Whether the (fragment) shader uses `gl_SecondaryFragColorEXT` (`GL_EXT_blend_func_extended`).
    pub(super) secondary_color: bool,
    /// Whether the (fragment) shader uses `gl_SecondaryFragDataEXT`.
    pub(super) secondary_data: bool,
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

/// `matCx2(strata_m2_NAME[i].xy, …, strata_m2_NAME[i + C - 1].xy)` where `i` is `C * index` or
/// 0, for a `matCx2` uniform of type `ty`.
fn mat2_of(name: &str, ty: Ty, index: Option<&ast::Expr>) -> ast::Expr {
    two_rows(var(&format!("strata_m2_{name}")), ty, index)
}

/// The boolean type of uniform type `ty`.
fn bool_type(ty: Ty) -> T {
    match ty {
        Ty::BVec2 => T::BVec2,
        Ty::BVec3 => T::BVec3,
        Ty::BVec4 => T::BVec4,
        _ => T::Bool,
    }
}

/// Boolean uniform `name` of type `ty` read from its integers in the block: `bvecN(strata_b_NAME)`,
/// or for an array of `len`, `bvecN[len](bvecN(strata_b_NAME[0]), …)`.
fn bool_of(name: &str, ty: Ty, len: Option<u32>) -> ast::Expr {
    let stored = var(&format!("strata_b_{name}"));
    let Some(len) = len else { return ctor(bool_type(ty), vec![stored]) };
    let elements = (0..len)
        .map(|k| {
            let at = ExprData::Bracket(Box::new(stored.clone()), Box::new(ExprData::IntConst(k as i32).into()));
            ctor(bool_type(ty), vec![at.into()])
        })
        .collect();
    let size: ast::Expr = ExprData::IntConst(len as i32).into();
    let dims = vec![ast::ArraySpecifierDimensionData::ExplicitlySized(Box::new(size)).into()];
    let spec = ast::TypeSpecifierData {
        ty: bool_type(ty).into(),
        array_specifier: Some(ast::ArraySpecifierData { dimensions: dims }.into()),
    };
    ExprData::FunCall(FunIdentifierData::TypeSpecifier(Box::new(spec.into())).into(), elements).into()
}

/// The name of element `k` of sampler array `name`: each element is a sampler of its own.
pub(super) fn sampler_element(name: &str, k: u32) -> String {
    format!("{name}__{k}")
}

/// The first argument of a call that indexes a sampler array: its position, the array's name
/// and length, and the index.
fn sampler_array_arg(arrays: &HashMap<String, u32>, args: &[ast::Expr]) -> Option<(usize, String, u32, ast::Expr)> {
    args.iter().enumerate().find_map(|(i, a)| match &a.content {
        ExprData::Bracket(base, index) => match &base.content {
            ExprData::Variable(id) => {
                arrays.get(id.0.as_str()).map(|&len| (i, id.0.to_string(), len, (**index).clone()))
            }
            _ => None,
        },
        _ => None,
    })
}

pub(super) use crate::glsl::hoist::{hoist_global_initializers, keep_sequence};

/// The parts a sampler is passed to a function as (naga takes no combined samplers): its
/// texture (`None`: 2D or cube, as the sampler), its sampler, its border sampler, its wrap
/// flags and border colour (`link::lookup_helpers`), its texture's swizzle
/// (`swizzle::SWIZZLE_FNS`) and its comparison (`shadow::SHADOW_FNS`).
const SAMPLER_PARTS: [(Option<T>, &str); 7] = [
    (None, "__t"),
    (Some(T::Sampler), "__s"),
    (Some(T::Sampler), "__b"),
    (Some(T::Vec4), "__w"),
    (Some(T::Vec4), "__c"),
    (Some(T::Vec4), "__z"),
    (Some(T::Vec4), "__d"),
];

impl Rewrite {
    /// Makes a 2D or 3D lookup (`id`, already the GLSL 450 function) a call of its generated
    /// helper, which applies the sampler's wrap flags and border colour:
    /// `NAME__FUNCTION(coordinate, …)` for a sampler uniform, `strata_p_FUNCTION(parts…,
    /// coordinate, …)` (`strata_p3_` for 3D) for a parameter.
    fn lookup_helper(&mut self, id: &mut ast::Identifier, args: &mut Vec<ast::Expr>) {
        let Some(ExprData::Variable(v)) = args.first().map(|a| &a.content) else { return };
        let sampler = v.0.to_string();
        // Cube maps and 2D arrays have no generated wraps (arrays' wraps are the sampler's).
        let Some(ty) =
            self.samplers.get(&sampler).copied().filter(|t| !matches!(t, Ty::SamplerCube | Ty::Sampler2DArray))
        else {
            return;
        };
        let three_d = ty == Ty::Sampler3D;
        let function = id.0.to_string();
        let name = if self.sampler_params.contains(&sampler) {
            let parts = SAMPLER_PARTS.iter().map(|(_, suffix)| var(&format!("{sampler}{suffix}")));
            args.splice(0..1, parts);
            self.lookups.insert((String::new(), function.clone(), three_d));
            format!("strata_p{}_{function}", if three_d { "3" } else { "" })
        } else {
            args.remove(0);
            self.lookups.insert((sampler.clone(), function.clone(), three_d));
            format!("{sampler}__{function}")
        };
        *id = ast::IdentifierData(name.into()).into();
    }
}

impl VisitorMut for Rewrite {
    fn visit_statement(&mut self, s: &mut ast::Statement) -> Visit {
        crate::glsl::polyfill::scope_bodies(s);
        Visit::Children
    }

    fn visit_full_specified_type(&mut self, t: &mut ast::FullySpecifiedType) -> Visit {
        strip_precision(&mut t.qualifier);
        Visit::Children
    }

    fn visit_struct_field_specifier(&mut self, f: &mut ast::StructFieldSpecifier) -> Visit {
        // GLSL ES 1.00 §4.1.8: members may carry precision qualifiers.
        strip_precision(&mut f.qualifier);
        Visit::Children
    }

    fn visit_initializer(&mut self, i: &mut ast::Initializer) -> Visit {
        if let ast::InitializerData::Simple(e) = &mut i.content {
            keep_sequence(e.as_mut());
        }
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
                        let tex = match t {
                            _ if t.int_sampler().is_some() => {
                                crate::glsl::int_samplers::texture_type(t).unwrap_or(T::Texture2D)
                            }
                            Ty::SamplerCube | Ty::SamplerCubeShadow => T::TextureCube,
                            Ty::Sampler3D => T::Texture3D,
                            Ty::Sampler2DArray | Ty::Sampler2DArrayShadow => T::Texture2DArray,
                            _ => T::Texture2D,
                        };
                        for (ty, suffix) in
                            SAMPLER_PARTS.iter().map(|(t, sfx)| (t.clone().unwrap_or_else(|| tex.clone()), *sfx))
                        {
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
        // A lookup on a sampler uniform or parameter, rearranged by its texture's swizzle once
        // rewritten: the sampler's name.
        let mut swizzled = None;
        let replacement = match &mut e.content {
            ExprData::Variable(id) => {
                let name = id.0.as_str();
                let es3 = self.version == 300;
                if es3 && matches!(name, "gl_FragColor" | "gl_FragData") {
                    // GLSL ES 3.00 declares its own outputs (Mesa's message).
                    self.error.get_or_insert(format!("0: `{name}' undeclared"));
                    None
                } else if es3 && name == "gl_FragDepth" && self.stage == Stage::Fragment {
                    // Clamped and written out by the generated `main` (`link`).
                    self.frag_depth = true;
                    Some(var("strata_FragDepth"))
                } else if es3 && name == "gl_InstanceID" && self.stage == Stage::Vertex {
                    self.instance_id = true;
                    Some(var("strata_InstanceID"))
                } else if es3 && name == "gl_VertexID" && self.stage == Stage::Vertex {
                    // Set by the generated `main` (`link`).
                    self.vertex_id = true;
                    Some(var("strata_VertexID"))
                } else if name == "gl_FragColor" && self.stage == Stage::Fragment {
                    self.frag_color = true;
                    Some(var("strata_FragColor"))
                } else if name == "gl_SecondaryFragColorEXT" && self.stage == Stage::Fragment {
                    // The second colour of dual-source blending, written out by the generated
                    // `main` (`link`).
                    self.secondary_color = true;
                    Some(var("strata_SecondaryFragColor"))
                } else if name == "gl_SecondaryFragDataEXT" && self.stage == Stage::Fragment {
                    self.secondary_data = true;
                    Some(var("strata_SecondaryFragData"))
                } else if name == "gl_FragData" && self.stage == Stage::Fragment {
                    // One colour per draw buffer, written out by the generated `main` (`link`).
                    self.frag_data = true;
                    Some(var("strata_FragData"))
                } else if let Some(v) = crate::glsl::consts::builtin(name)
                    .or_else(|| crate::glsl::consts::builtin_es3(name).filter(|_| self.version == 300))
                {
                    // The built-in constants (§7.4), which naga does not know; a negative one
                    // negated, so that a minus before it stays apart from its own.
                    let k: ast::Expr = ExprData::IntConst((v as i32).wrapping_abs()).into();
                    Some(if v < 0 { ExprData::Unary(ast::UnaryOpData::Minus.into(), Box::new(k)).into() } else { k })
                } else if name == "gl_PointSize" && self.stage == Stage::Vertex {
                    // Points are drawn as quads whose size the generated `main` reads from this.
                    Some(var("strata_PointSize"))
                } else if name == "gl_PointCoord" && self.stage == Stage::Fragment {
                    self.point_coord = true;
                    Some(var("strata_PointCoord"))
                } else if name == crate::glsl::checks::FRAG_DEPTH && self.stage == Stage::Fragment {
                    // Clamped and written out by the generated `main` (`link`).
                    self.frag_depth = true;
                    Some(var("strata_FragDepth"))
                } else if name == crate::glsl::checks::INSTANCE_ID && self.stage == Stage::Vertex {
                    // Set by the generated `main` (`link`).
                    self.instance_id = true;
                    Some(var("strata_InstanceID"))
                } else if let Some(ty) = self.samplers.get(name) {
                    // A shadow sampler reads its depth image as floats (`SHADOW_FNS` compares).
                    let t = match ty {
                        _ if ty.int_sampler().is_some() => {
                            crate::glsl::int_samplers::sampler_type(*ty).unwrap_or(T::Sampler2D)
                        }
                        Ty::SamplerCube | Ty::SamplerCubeShadow => T::SamplerCube,
                        Ty::Sampler3D => T::Sampler3D,
                        Ty::Sampler2DArray | Ty::Sampler2DArrayShadow => T::Sampler2DArray,
                        _ => T::Sampler2D,
                    };
                    Some(ctor(t, vec![var(&format!("{name}__t")), var(&format!("{name}__s"))]))
                } else if let Some(&(ty, false)) = self.mat2s.get(name) {
                    Some(mat2_of(name, ty, None))
                } else if let Some(&(ty, len)) = self.bools.get(name) {
                    Some(bool_of(name, ty, len))
                } else {
                    None
                }
            }
            ExprData::Bracket(base, index) => match (&base.content, &index.content) {
                (ExprData::Variable(id), ExprData::IntConst(k))
                    if id.0 == "gl_FragData" || id.0 == "gl_SecondaryFragDataEXT" =>
                {
                    let len = if id.0 == "gl_FragData" { MAX_DRAW_BUFFERS as i32 } else { 1 };
                    if *k < 0 || *k >= len {
                        self.error.get_or_insert(format!("0: array index must be < {len}"));
                    }
                    None
                }
                (ExprData::Variable(id), _) if self.bools.get(id.0.as_str()).is_some_and(|b| b.1.is_some()) => {
                    let mut idx = (**index).clone();
                    idx.visit_mut(self);
                    let ty = self.bools.get(id.0.as_str()).map_or(Ty::Bool, |b| b.0);
                    let element = ExprData::Bracket(Box::new(var(&format!("strata_b_{}", id.0))), Box::new(idx));
                    Some(ctor(bool_type(ty), vec![element.into()]))
                }
                (ExprData::Variable(id), _) if self.mat2s.get(id.0.as_str()).is_some_and(|m| m.1) => {
                    let mut idx = (**index).clone();
                    idx.visit_mut(self);
                    let ty = self.mat2s.get(id.0.as_str()).map_or(Ty::Mat2, |m| m.0);
                    Some(mat2_of(id.0.as_str(), ty, Some(&idx)))
                }
                _ => None,
            },
            ExprData::FunCall(fun, args) => {
                args.iter_mut().for_each(keep_sequence);
                crate::glsl::polyfill::fetch_offset(fun, args, &self.samplers);
                crate::glsl::polyfill::array_layer(fun, args, &self.samplers);
                // A sampler array element (GLSL ES 1.00 Appendix A: indexed by a constant or a
                // loop index) is one of the array's samplers: a constant index names it, any
                // other index selects the whole call over the elements.
                if let Some((at, name, len, index)) = sampler_array_arg(&self.sampler_arrays, args) {
                    if let ExprData::IntConst(k) = index.content {
                        if k < 0 || k as u32 >= len {
                            self.error.get_or_insert_with(|| {
                                format!("0: array index {k} out of range for sampler array '{name}'")
                            });
                            return Visit::Parent;
                        }
                        args[at] = var(&sampler_element(&name, k as u32));
                    } else {
                        let call_with = |k: u32| {
                            let mut c = ExprData::FunCall(fun.clone(), args.clone());
                            if let ExprData::FunCall(_, a) = &mut c {
                                a[at] = var(&sampler_element(&name, k));
                            }
                            ast::Expr::from(c)
                        };
                        let mut chain = call_with(len - 1);
                        for k in (0..len - 1).rev() {
                            let test: ast::Expr = ExprData::Binary(
                                ast::BinaryOpData::Equal.into(),
                                Box::new(index.clone()),
                                Box::new(ExprData::IntConst(k as i32).into()),
                            )
                            .into();
                            chain = ExprData::Ternary(Box::new(test), Box::new(call_with(k)), Box::new(chain)).into();
                        }
                        chain.visit_mut(self);
                        *e = chain;
                        return Visit::Parent;
                    }
                }
                if let FunIdentifierData::Expr(f) = &mut fun.content {
                    if let ExprData::Variable(id) = &mut f.content {
                        let int = match args.first().map(|a| &a.content) {
                            Some(ExprData::Variable(v)) if !self.sampler_fns.contains_key(id.0.as_str()) => self
                                .samplers
                                .get(v.0.as_str())
                                .filter(|t| t.int_sampler().is_some())
                                .map(|t| (v.0.to_string(), *t)),
                            _ => None,
                        };
                        if let Some((sampler, ty)) = int {
                            // An integer lookup (`int_samplers`): its other arguments rewritten,
                            // then the call replaced by its fetching helper's, or kept with its
                            // sampler rewritten (texelFetch, most size queries).
                            args.iter_mut().skip(1).for_each(|a| {
                                a.visit_mut(self);
                            });
                            let (function, fragment) = (id.0.to_string(), self.stage == Stage::Fragment);
                            let helper = int_samplers::lookup(&function, &sampler, ty, &args[1..], fragment);
                            if helper.is_none() {
                                if let Err(message) = int_samplers::kept(&function) {
                                    self.error.get_or_insert(message);
                                    return Visit::Parent;
                                }
                                args.iter_mut().take(1).for_each(|a| {
                                    a.visit_mut(self);
                                });
                            }
                            let call = helper.unwrap_or_else(|| std::mem::replace(e, ExprData::IntConst(0).into()));
                            *e = int_samplers::swizzled(&function, &sampler, call);
                            return Visit::Parent;
                        }
                        let shadow = match args.first().map(|a| &a.content) {
                            Some(ExprData::Variable(v))
                                if !self.sampler_fns.contains_key(id.0.as_str()) && id.0.as_str() != "textureSize" =>
                            {
                                self.samplers.get(v.0.as_str()).filter(|t| t.is_shadow()).map(|t| (v.0.to_string(), *t))
                            }
                            _ => None,
                        };
                        if let Some((sampler, ty)) = shadow {
                            // A shadow lookup: its other arguments rewritten, then the call
                            // replaced by its comparing helper's.
                            args.iter_mut().skip(1).for_each(|a| {
                                a.visit_mut(self);
                            });
                            let fragment = self.stage == Stage::Fragment;
                            if let Some(c) =
                                crate::glsl::shadow::lookup(id.0.as_str(), &sampler, ty, &args[1..], fragment)
                            {
                                *e = c;
                                return Visit::Parent;
                            }
                            self.error.get_or_insert_with(|| {
                                format!("0: no matching overload of `{}' for a shadow sampler", id.0)
                            });
                            return Visit::Parent;
                        }
                        if let Some(flags) = self.sampler_fns.get(id.0.as_str()) {
                            // Pass a sampler argument as its texture and sampler halves.
                            let mut expanded = Vec::with_capacity(args.len() + 2);
                            for (arg, is_sampler) in
                                std::mem::take(args).into_iter().zip(flags.iter().chain(std::iter::repeat(&false)))
                            {
                                match (&arg.content, is_sampler) {
                                    (ExprData::Variable(v), true) if self.samplers.contains_key(v.0.as_str()) => {
                                        for (_, suffix) in SAMPLER_PARTS {
                                            expanded.push(var(&format!("{}{suffix}", v.0)));
                                        }
                                    }
                                    _ => expanded.push(arg),
                                }
                            }
                            *args = expanded;
                        }
                        if let Some(ExprData::Variable(v)) = args.first().map(|a| &a.content) {
                            let built_in = !self.sampler_fns.contains_key(id.0.as_str());
                            if built_in
                                && crate::glsl::swizzle::returns_texels(id.0.as_str())
                                && self.samplers.contains_key(v.0.as_str())
                            {
                                swizzled = Some(v.0.to_string());
                            }
                        }
                        // A vertex shader has no derivatives: ES defines its implicit-LOD
                        // lookups as level 0, so they become explicit-LOD lookups.
                        let vertex_implicit = self.stage == Stage::Vertex && args.len() == 2;
                        let es3 = self.version == 300;
                        if let Some(stand_in) = crate::glsl::polyfill::stand_in(id.0.as_str(), es3) {
                            self.polyfills.insert(stand_in);
                            *id = ast::IdentifierData(stand_in.into()).into();
                        }
                        let renamed = match id.0.as_str() {
                            "texture2D" | "textureCube" | "texture3D" if vertex_implicit => Some("textureLod"),
                            "texture2DProj" | "texture3DProj" if vertex_implicit => Some("textureProjLod"),
                            // GLSL ES 3.00's overloaded lookups, whose 2D and 3D forms go through
                            // the same helpers.
                            "texture" if es3 && vertex_implicit => Some("textureLod"),
                            "textureProj" if es3 && vertex_implicit => Some("textureProjLod"),
                            "texture" | "textureProj" | "textureLod" | "textureProjLod" if es3 => {
                                Some(match id.0.as_str() {
                                    "texture" => "texture",
                                    "textureProj" => "textureProj",
                                    "textureLod" => "textureLod",
                                    _ => "textureProjLod",
                                })
                            }
                            "texture2D" | "textureCube" | "texture3D" => Some("texture"),
                            "texture2DProj" | "texture3DProj" => Some("textureProj"),
                            "texture2DLod" | "textureCubeLod" | "texture3DLod" => Some("textureLod"),
                            "texture2DProjLod" | "texture3DProjLod" => Some("textureProjLod"),
                            _ => None,
                        };
                        if let Some(r) = renamed {
                            if vertex_implicit && r.ends_with("Lod") {
                                args.push(ExprData::FloatConst(0.0).into());
                            }
                            *id = ast::IdentifierData(r.into()).into();
                            self.lookup_helper(id, args);
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
        if let Some(sampler) = swizzled {
            // The call's arguments are rewritten here, as its children would be, and the call
            // is wrapped: the wrapper is not visited again.
            if let ExprData::FunCall(_, args) = &mut e.content {
                args.iter_mut().for_each(|a| {
                    a.visit_mut(self);
                });
            }
            let call = std::mem::replace(e, ExprData::IntConst(0).into());
            let swizzle = FunIdentifierData::Expr(Box::new(var("strata_swizzle"))).into();
            *e = ExprData::FunCall(swizzle, vec![call, var(&format!("{sampler}__z"))]).into();
            return Visit::Parent;
        }
        Visit::Children
    }
}

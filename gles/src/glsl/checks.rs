//! GLSL ES 1.00 rules checked on the parsed shader before it is lifted and rewritten:
//! derivative functions (`GL_OES_standard_derivatives`), `gl_FragDepthEXT`
//! (`GL_EXT_frag_depth`), redeclarations (§4.2.7), struct
//! members (§4.1.8) and constant global initialisers (§4.3). Errors name the line, Mesa-style.

use std::collections::{HashMap, HashSet};

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeQualifierSpecData, TypeSpecifierNonArrayData as T};
use glsl_lang::visitor::{Host, Visit, Visitor};

use crate::glsl::precision;
use crate::glsl::precision::signature;
use crate::glsl::preprocess::{error_at, line_col, Parsed};
use crate::glsl::types::Facts;
use crate::glsl::types::Stage;

/// The derivative functions of `GL_OES_standard_derivatives`.
const DERIVATIVES: [&str; 3] = ["dFdx", "dFdy", "fwidth"];

/// The 3D lookups of `GL_OES_texture_3D`; the explicit-level ones only in vertex shaders.
const LOOKUPS_3D: [&str; 4] = ["texture3D", "texture3DProj", "texture3DLod", "texture3DProjLod"];

/// Checks `parsed` against the rules above; the error is the info log.
pub(super) fn check(stage: Stage, parsed: &Parsed) -> Result<Facts, String> {
    let at = |span: Option<ast::NodeSpan>, msg: &str| {
        let (line, col) = span.map_or((1, 1), |s| line_col(&parsed.text, usize::from(s.range().start())));
        error_at(line, col, msg)
    };
    let mut calls = Calls::default();
    parsed.tu.visit(&mut calls);
    for (name, span) in &calls.found {
        // Core in GLSL ES 3.00's fragment shaders.
        let derivatives = parsed.enabled.derivatives || parsed.version == 300;
        if DERIVATIVES.contains(&name.as_str()) && (stage == Stage::Vertex || !derivatives) {
            let why = if stage == Stage::Vertex {
                "is only available in fragment shaders"
            } else {
                "requires `#extension GL_OES_standard_derivatives : enable'"
            };
            return Err(at(*span, &format!("`{name}' {why}")));
        }
        // As on Mesa, a 3D lookup the shader has not enabled (or an explicit-level one in a
        // fragment shader) is no function at all.
        let lod = name.ends_with("Lod") && stage == Stage::Fragment;
        if LOOKUPS_3D.contains(&name.as_str()) && (!parsed.enabled.texture_3d || lod) {
            return Err(at(*span, &format!("no function with name '{name}'")));
        }
    }
    // `GL_EXT_frag_depth`'s output exists only in fragment shaders that enable it.
    if let Some(span) = calls.frag_depth {
        if stage == Stage::Vertex || !parsed.enabled.frag_depth {
            return Err(at(span, &format!("`{FRAG_DEPTH}' undeclared")));
        }
    }
    // `GL_EXT_draw_instanced`'s input exists only in vertex shaders that enable it.
    if let Some(span) = calls.instance_id {
        if stage == Stage::Fragment || !parsed.enabled.draw_instanced {
            return Err(at(span, &format!("`{INSTANCE_ID}' undeclared")));
        }
    }
    // `GL_EXT_blend_func_extended`'s outputs exist only in fragment shaders that enable it.
    if let Some((name, span)) = &calls.secondary {
        if stage == Stage::Vertex || !parsed.enabled.blend_func_extended {
            return Err(at(*span, &format!("`{name}' undeclared")));
        }
    }
    globals(&parsed.tu, parsed.version, &at)?;
    let mut loops = ForScopes::default();
    parsed.tu.visit(&mut loops);
    if let Some((span, name)) = loops.redeclared {
        return Err(at(span, &format!("`{name}' redeclared")));
    }
    crate::glsl::writes::check(stage, parsed.version, &parsed.tu, &at)?;
    crate::glsl::conversions::check(&parsed.tu, &at)?;
    // `sampler3D` is core in GLSL ES 3.00 (without a default precision, as with the extension).
    let texture_3d = parsed.enabled.texture_3d || parsed.version == 300;
    let precisions = precision::check(stage, &parsed.tu, texture_3d, parsed.version == 300, &at)?;
    let mut invariants = HashSet::new();
    for decl in &parsed.tu.0 {
        if let ast::ExternalDeclarationData::Declaration(d) = &decl.content {
            if let ast::DeclarationData::Invariant(id) = &d.content {
                if id.0 == "gl_FrontFacing" {
                    return Err(at(d.span, "`gl_FrontFacing' cannot be declared invariant"));
                }
                invariants.insert(id.0.to_string());
            }
        }
    }
    Ok(Facts {
        uniform_precisions: precisions.uniforms,
        varying_precisions: precisions.varyings,
        used: calls.variables,
        invariants,
    })
}

/// `GL_EXT_frag_depth`'s fragment depth output.
pub(super) const FRAG_DEPTH: &str = "gl_FragDepthEXT";
/// `GL_EXT_draw_instanced`'s instance number.
pub(super) const INSTANCE_ID: &str = "gl_InstanceIDEXT";
/// `GL_EXT_blend_func_extended`'s second colour outputs.
pub(super) const SECONDARY: [&str; 2] = ["gl_SecondaryFragColorEXT", "gl_SecondaryFragDataEXT"];

/// Every function called by name, with where; every variable named; the first uses of
/// [`FRAG_DEPTH`] and [`INSTANCE_ID`].
#[derive(Default)]
struct Calls {
    found: Vec<(String, Option<ast::NodeSpan>)>,
    variables: HashSet<String>,
    frag_depth: Option<Option<ast::NodeSpan>>,
    instance_id: Option<Option<ast::NodeSpan>>,
    secondary: Option<(String, Option<ast::NodeSpan>)>,
}

impl Visitor for Calls {
    fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
        if let ExprData::Variable(id) = &e.content {
            self.variables.insert(id.0.to_string());
            if id.0 == FRAG_DEPTH && self.frag_depth.is_none() {
                self.frag_depth = Some(e.span);
            }
            if id.0 == INSTANCE_ID && self.instance_id.is_none() {
                self.instance_id = Some(e.span);
            }
            if SECONDARY.contains(&id.0.as_str()) && self.secondary.is_none() {
                self.secondary = Some((id.0.to_string(), e.span));
            }
        }
        if let ExprData::FunCall(f, _) = &e.content {
            if let FunIdentifierData::Expr(callee) = &f.content {
                if let ExprData::Variable(id) = &callee.content {
                    self.found.push((id.0.to_string(), e.span));
                }
            }
        }
        Visit::Children
    }
}

/// GLSL ES §6.3: a `for` loop's body shares the scope of its init declaration, so the body's
/// own block may not declare a name the init declared (naga would take the block as a scope of
/// its own): the first such declaration.
#[derive(Default)]
struct ForScopes {
    redeclared: Option<(Option<ast::NodeSpan>, String)>,
}

/// The names a declaration list declares.
fn declared(d: &ast::Declaration) -> Vec<String> {
    match &d.content {
        ast::DeclarationData::InitDeclaratorList(list) => {
            let head = list.head.name.iter().map(|n| n.0.to_string());
            head.chain(list.tail.iter().map(|t| t.ident.ident.0.to_string())).collect()
        }
        _ => Vec::new(),
    }
}

impl Visitor for ForScopes {
    fn visit_iteration_statement(&mut self, it: &ast::IterationStatement) -> Visit {
        let ast::IterationStatementData::For(init, _, body) = &it.content else { return Visit::Children };
        let (ast::ForInitStatementData::Declaration(d), ast::StatementData::Compound(c)) =
            (&init.content, &body.content)
        else {
            return Visit::Children;
        };
        let names = declared(d);
        for st in &c.statement_list {
            if let ast::StatementData::Declaration(inner) = &st.content {
                if let Some(n) = declared(inner).into_iter().find(|n| names.contains(n)) {
                    self.redeclared.get_or_insert((st.span, n));
                }
            }
        }
        Visit::Children
    }
}

/// Whether a qualifier list declares a `const`.
pub(super) fn is_const(q: Option<&ast::TypeQualifier>) -> bool {
    q.is_some_and(|q| {
        q.qualifiers.iter().any(|s| matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Const))
    })
}

/// The first variable in `e` that is not a constant (a global declared `const`, or a
/// built-in constant), if any.
fn non_constant<'a>(e: &'a ast::Expr, consts: &HashSet<String>) -> Option<&'a ast::Expr> {
    struct Find<'c, 'e> {
        consts: &'c HashSet<String>,
        found: Option<&'e ast::Expr>,
    }
    let mut stack = vec![e];
    let mut f = Find { consts, found: None };
    while let Some(e) = stack.pop() {
        match &e.content {
            ExprData::Variable(id) if !f.consts.contains(id.0.as_str()) && !id.0.starts_with("gl_Max") => {
                f.found = Some(e);
                break;
            }
            ExprData::Unary(_, a) | ExprData::Dot(a, _) | ExprData::PostInc(a) | ExprData::PostDec(a) => stack.push(a),
            ExprData::Binary(_, a, b) | ExprData::Bracket(a, b) | ExprData::Comma(a, b) => {
                stack.push(a);
                stack.push(b);
            }
            ExprData::Assignment(a, _, b) => {
                stack.push(a);
                stack.push(b);
            }
            ExprData::Ternary(a, b, c) => {
                stack.push(a);
                stack.push(b);
                stack.push(c);
            }
            ExprData::FunCall(_, args) => stack.extend(args.iter()),
            _ => {}
        }
    }
    f.found
}

fn initializer_exprs(i: &ast::Initializer) -> Vec<&ast::Expr> {
    match &i.content {
        ast::InitializerData::Simple(e) => vec![e],
        ast::InitializerData::List(l) => l.iter().flat_map(initializer_exprs).collect(),
    }
}

/// Global-scope rules: redeclarations, struct members, constant initialisers.
fn globals(
    tu: &ast::TranslationUnit,
    version: u16,
    at: &dyn Fn(Option<ast::NodeSpan>, &str) -> String,
) -> Result<(), String> {
    let mut defined: HashSet<String> = HashSet::new();
    let mut prototyped: HashSet<String> = HashSet::new();
    let mut functions: HashSet<String> = HashSet::new();
    // Names of variables and structs at global scope.
    let mut names: HashMap<String, &'static str> = HashMap::new();
    let mut consts: HashSet<String> = HashSet::new();
    let struct_check = |s: &ast::StructSpecifier| -> Result<(), String> {
        for field in &s.fields {
            if field.identifiers.is_empty() {
                return Err(at(field.span, "anonymous structure members are not allowed"));
            }
            if matches!(field.ty.ty.content, T::Struct(_)) {
                return Err(at(field.span, "embedded structure definitions are not allowed"));
            }
        }
        Ok(())
    };
    for decl in &tu.0 {
        match &decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                let p = &f.prototype;
                let name = p.name.0.to_string();
                if names.contains_key(&name) {
                    return Err(at(p.span, &format!("`{name}' redeclared as a function")));
                }
                if !defined.insert(signature(p)) {
                    return Err(at(p.span, &format!("function `{name}' redefined")));
                }
                functions.insert(name);
            }
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::FunctionPrototype(p) => {
                    let name = p.name.0.to_string();
                    if names.contains_key(&name) {
                        return Err(at(p.span, &format!("`{name}' redeclared as a function")));
                    }
                    // GLSL ES 3.00 lets a function be declared again; 1.00 does not.
                    if !prototyped.insert(signature(p)) && version < 300 {
                        return Err(at(p.span, &format!("function `{name}' declared more than once")));
                    }
                    functions.insert(name);
                }
                ast::DeclarationData::InitDeclaratorList(list) => {
                    let head = &list.head;
                    if let T::Struct(s) = &head.ty.ty.ty.content {
                        struct_check(s)?;
                        if let Some(n) = &s.name {
                            let n = n.0.to_string();
                            if functions.contains(&n) || names.contains_key(&n) {
                                return Err(at(s.span, &format!("`{n}' redeclared")));
                            }
                            names.insert(n, "struct");
                        }
                    }
                    let constant = is_const(head.ty.qualifier.as_ref());
                    let mut declared: Vec<(String, Option<&ast::Initializer>, Option<ast::NodeSpan>)> = Vec::new();
                    if let Some(n) = &head.name {
                        declared.push((n.0.to_string(), head.initializer.as_ref(), head.span));
                    }
                    for t in &list.tail {
                        declared.push((t.ident.ident.0.to_string(), t.initializer.as_ref(), t.span));
                    }
                    for (n, init, span) in declared {
                        if let Some(init) = init {
                            for e in initializer_exprs(init) {
                                if let Some(bad) = non_constant(e, &consts) {
                                    let what = match &bad.content {
                                        ExprData::Variable(id) => id.0.to_string(),
                                        _ => String::new(),
                                    };
                                    return Err(at(
                                        bad.span.or(span),
                                        &format!("initializer of global variable uses non-constant `{what}'"),
                                    ));
                                }
                            }
                        }
                        if functions.contains(&n) || names.contains_key(&n) {
                            return Err(at(span, &format!("`{n}' redeclared")));
                        }
                        if constant {
                            consts.insert(n.clone());
                        }
                        names.insert(n, "variable");
                    }
                }
                _ => {}
            },
            _ => {}
        }
    }
    Ok(())
}

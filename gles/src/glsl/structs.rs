//! The structure types a shader declares (GLSL ES 1.00 §4.1.8), as uniforms and uniform block
//! members of structure type need them: each structure's members, the leaves a value of one
//! breaks into (`u.a`, `u.arr`, `u[1].inner.x`: one per member of a basic type or an array of
//! one, arrays of structures taken element by element, as GL names its active uniforms), and the
//! signature two stages' declarations of a structure must share (§4.2.6 of GLSL ES 3.00).

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use glsl_lang::ast::{self, ExprData, TypeSpecifierNonArrayData as T};
use glsl_lang::parse::DefaultParse;
use glsl_lang::transpiler::glsl::{show_type_specifier, FormattingState};
use glsl_lang::visitor::{Host, Visit, Visitor, VisitorMut};

use crate::glsl::consts::{array_len, fold, Val};
use crate::glsl::types::Ty;
use crate::limits::MAX_BLOCK;

/// A member's type.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum FieldTy {
    /// A basic type, with its spelling in the shader (a sampler's is needed to declare it).
    Basic(Ty, String),
    /// A structure, by name.
    Struct(String),
    /// A type uniforms cannot have here, spelt as in the shader.
    Other(String),
}

/// A member of a structure.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Field {
    /// Its name.
    pub(super) name: String,
    /// Its type.
    pub(super) ty: FieldTy,
    /// Its array length, if an array.
    pub(super) array: Option<u32>,
}

/// The shader's structures by name, each with its members in order.
pub(super) type Structs = HashMap<String, Vec<Field>>;

/// A leaf of a value of structure type: a member of a basic type (or an array of one).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Leaf {
    /// Its GL name, which is also its access from the root (`u[1].inner.x`).
    pub(super) name: String,
    /// Its type.
    pub(super) ty: Ty,
    /// Its type as the shader spells it.
    pub(super) spelling: String,
    /// Its array length, if an array.
    pub(super) array: Option<u32>,
}

/// The identifier a leaf (or any GL name of one) is declared as: `u[1].inner.x` is
/// `u__1__inner__x` (GLSL ES reserves names with two underscores in a row, so none of the
/// shader's own names is one).
pub(super) fn ident(name: &str) -> String {
    name.replace(['.', '['], "__").replace(']', "")
}

/// The type a member declaration has.
fn field_ty(t: &ast::TypeSpecifier) -> FieldTy {
    let mut spelling = String::new();
    let plain: ast::TypeSpecifier = ast::TypeSpecifierData { ty: t.ty.clone(), array_specifier: None }.into();
    let _ = show_type_specifier(&mut spelling, &plain, &mut FormattingState::default());
    match &t.ty.content {
        T::TypeName(n) => FieldTy::Struct(n.0.to_string()),
        T::Struct(s) => s.name.as_ref().map_or(FieldTy::Other(spelling), |n| FieldTy::Struct(n.0.to_string())),
        other => match Ty::from_spec(other) {
            Some(ty) => FieldTy::Basic(ty, spelling),
            None => FieldTy::Other(spelling),
        },
    }
}

/// The fields of a structure or block declaration.
pub(super) fn fields(decls: &[ast::StructFieldSpecifier], consts: &HashMap<String, Val>) -> Result<Vec<Field>, String> {
    let mut out = Vec::new();
    for f in decls {
        let ty = field_ty(&f.ty);
        for id in &f.identifiers {
            let spec = id.array_spec.as_ref().or(f.ty.array_specifier.as_ref());
            out.push(Field { name: id.ident.0.to_string(), ty: ty.clone(), array: array_len(spec, consts)? });
        }
    }
    Ok(out)
}

/// Every named structure `tu` declares.
pub(super) fn collect(tu: &ast::TranslationUnit, consts: &HashMap<String, Val>) -> Result<Structs, String> {
    struct Found<'c> {
        consts: &'c HashMap<String, Val>,
        structs: Structs,
        error: Option<String>,
    }
    impl Visitor for Found<'_> {
        fn visit_struct_specifier(&mut self, s: &ast::StructSpecifier) -> Visit {
            if let Some(n) = &s.name {
                match fields(&s.fields, self.consts) {
                    Ok(f) => {
                        self.structs.insert(n.0.to_string(), f);
                    }
                    Err(e) => {
                        self.error.get_or_insert(e);
                    }
                }
            }
            Visit::Children
        }
    }
    let mut found = Found { consts, structs: Structs::new(), error: None };
    tu.visit(&mut found);
    found.error.map_or(Ok(found.structs), Err)
}

/// The leaves of `name`, a value of structure `ty` (an array of `array` of them), in order.
pub(super) fn leaves(structs: &Structs, ty: &str, name: &str, array: Option<u32>) -> Result<Vec<Leaf>, String> {
    let mut out = Vec::new();
    for root in elements(name, array) {
        struct_leaves(structs, ty, &root, &mut out, 0)?;
    }
    Ok(out)
}

/// The most leaves one uniform may break into: each takes four bytes of the block at least.
const MAX_LEAVES: usize = (MAX_BLOCK / 4) as usize;

/// `name`, or its elements `name[k]` where an array.
pub(super) fn elements(name: &str, array: Option<u32>) -> Vec<String> {
    match array {
        Some(n) => (0..n).map(|k| format!("{name}[{k}]")).collect(),
        None => vec![name.to_string()],
    }
}

/// How deep structures may nest in one another (a structure cannot hold itself, but a
/// shader could declare a long chain).
pub(super) const MAX_DEPTH: usize = 16;

fn struct_leaves(structs: &Structs, ty: &str, at: &str, out: &mut Vec<Leaf>, depth: usize) -> Result<(), String> {
    let fields = structs.get(ty).filter(|_| depth < MAX_DEPTH).ok_or_else(|| format!("0: unknown structure `{ty}'"))?;
    for f in fields {
        let name = format!("{at}.{}", f.name);
        if out.len() > MAX_LEAVES {
            return Err(format!("error: the uniforms need more than the {MAX_BLOCK} bytes a uniform block can bind"));
        }
        match &f.ty {
            FieldTy::Basic(ty, spelling) => {
                out.push(Leaf { name, ty: *ty, spelling: spelling.clone(), array: f.array });
            }
            FieldTy::Struct(s) => {
                for e in elements(&name, f.array) {
                    struct_leaves(structs, s, &e, out, depth + 1)?;
                }
            }
            FieldTy::Other(t) => {
                return Err(format!("0: structure members of type '{t}' are not supported in uniforms"));
            }
        }
    }
    Ok(())
}

/// What two stages' declarations of structure `ty` must share: its name, and each member's
/// name, type and array length, down through the structures it holds.
pub(super) fn signature(structs: &Structs, ty: &str) -> String {
    let mut out = String::new();
    sign(structs, ty, &mut out, 0);
    out
}

fn sign(structs: &Structs, ty: &str, out: &mut String, depth: usize) {
    let _ = write!(out, "{ty}{{");
    for f in structs.get(ty).filter(|_| depth < MAX_DEPTH).into_iter().flatten() {
        match &f.ty {
            FieldTy::Basic(t, _) => {
                let _ = write!(out, "{t:?}");
            }
            FieldTy::Struct(s) => sign(structs, s, out, depth + 1),
            FieldTy::Other(t) => out.push_str(t),
        }
        let _ = write!(out, " {}{};", f.name, f.array.map_or(String::new(), |n| format!("[{n}]")));
    }
    out.push('}');
}

/// The name of the structure a declaration's type is, if one of `structs`.
pub(super) fn struct_name(t: &ast::TypeSpecifierNonArray, structs: &Structs) -> Option<String> {
    let name = match &t.content {
        T::TypeName(n) => n.0.to_string(),
        T::Struct(s) => s.name.as_ref()?.0.to_string(),
        _ => return None,
    };
    structs.contains_key(&name).then_some(name)
}

/// Whether a member of this type cannot be held by a structure in the translation: a sampler
/// (naga holds none in structures) or a matrix of two rows (whose std140 layout, which naga
/// gives every structure, it refuses).
pub(super) fn unheld(t: &T) -> bool {
    Ty::from_spec(t).is_some_and(|t| t.is_sampler() || t.rows() == 2)
        || crate::glsl::precision::ES3_SAMPLERS.contains(t)
}

/// Whether structure `ty` holds, at any depth, a member that [`unheld`] keeps out of it.
pub(super) fn holds_unheld(structs: &Structs, ty: &str) -> bool {
    fn walk(structs: &Structs, ty: &str, depth: usize) -> bool {
        structs.get(ty).filter(|_| depth < MAX_DEPTH).into_iter().flatten().any(|f| match &f.ty {
            FieldTy::Basic(t, _) => t.is_sampler() || t.rows() == 2,
            FieldTy::Struct(s) => walk(structs, s, depth + 1),
            FieldTy::Other(_) => true,
        })
    }
    walk(structs, ty, 0)
}

/// Drops from every structure declaration the members [`unheld`] keeps out (each is read from
/// its own uniform instead); a structure left with none keeps one unused member, as GLSL
/// needs one.
pub(super) struct DropUnheld;

impl VisitorMut for DropUnheld {
    fn visit_struct_specifier(&mut self, s: &mut ast::StructSpecifier) -> Visit {
        s.fields.retain(|f| !unheld(&f.ty.ty.content));
        if s.fields.is_empty() {
            let unused = ast::ArrayedIdentifierData {
                ident: ast::IdentifierData("strata_unused".into()).into(),
                array_spec: None,
            };
            let ty: ast::TypeSpecifier = ast::TypeSpecifierData { ty: T::Int.into(), array_specifier: None }.into();
            s.fields
                .push(ast::StructFieldSpecifierData { qualifier: None, ty, identifiers: vec![unused.into()] }.into());
        }
        Visit::Children
    }
}

/// The access `e` makes if it is a chain of members and elements from a variable: `u[1].tex`;
/// an index that is not constant reads `[0]`, and the flag says there was one.
fn access(e: &ast::Expr, consts: &HashMap<String, Val>) -> Option<(String, bool)> {
    match &e.content {
        ExprData::Variable(id) => Some((id.0.to_string(), false)),
        ExprData::Dot(base, field) => access(base, consts).map(|(p, d)| (format!("{p}.{}", field.0), d)),
        ExprData::Bracket(base, index) => {
            let (p, d) = access(base, consts)?;
            match fold(index, consts) {
                Some(Val::Int(k)) => Some((format!("{p}[{k}]"), d)),
                _ => Some((format!("{p}[0]"), true)),
            }
        }
        _ => None,
    }
}

/// Points each access of a leaf of a structure value (through constant indices) at what holds
/// that leaf, and finds the values used otherwise (whole, or through an index that is not
/// constant), which then need the whole structure.
pub(super) struct Paths<'c> {
    /// What each leaf's access (`u[1].a`, `b.s.x`) becomes.
    pub(super) leaves: HashMap<String, ast::Expr>,
    /// The accesses of the leaves that are samplers, which nothing else can stand for.
    pub(super) samplers: HashSet<String>,
    /// The accesses of the structure values (`u`, `b.s`).
    pub(super) roots: HashSet<String>,
    /// The roots used otherwise than through their leaves.
    pub(super) whole: HashSet<String>,
    /// The shader's constants, for indices.
    pub(super) consts: &'c HashMap<String, Val>,
    /// The first error found.
    pub(super) error: Option<String>,
    /// The names the function visited declares, which hide globals of theirs.
    pub(super) shadow: HashSet<String>,
}

/// The names a function declares (its parameters and locals), which hide the globals of the
/// same names in it (a local declared anywhere in the function counts throughout).
pub(super) fn locals(f: &ast::FunctionDefinition) -> HashSet<String> {
    struct Names(HashSet<String>);
    impl Visitor for Names {
        fn visit_function_parameter_declarator(&mut self, p: &ast::FunctionParameterDeclarator) -> Visit {
            self.0.insert(p.ident.ident.0.to_string());
            Visit::Children
        }
        fn visit_single_declaration(&mut self, d: &ast::SingleDeclaration) -> Visit {
            self.0.extend(d.name.iter().map(|n| n.0.to_string()));
            Visit::Children
        }
        fn visit_single_declaration_no_type(&mut self, d: &ast::SingleDeclarationNoType) -> Visit {
            self.0.insert(d.ident.ident.0.to_string());
            Visit::Children
        }
    }
    let mut names = Names(HashSet::new());
    f.visit(&mut names);
    names.0
}

impl VisitorMut for Paths<'_> {
    fn visit_external_declaration(&mut self, _: &mut ast::ExternalDeclaration) -> Visit {
        self.shadow.clear();
        Visit::Children
    }

    fn visit_function_definition(&mut self, f: &mut ast::FunctionDefinition) -> Visit {
        self.shadow = locals(f);
        Visit::Children
    }

    fn visit_expr(&mut self, e: &mut ast::Expr) -> Visit {
        if !matches!(e.content, ExprData::Variable(_) | ExprData::Dot(..) | ExprData::Bracket(..)) {
            return Visit::Children;
        }
        let Some((path, dynamic)) = access(e, self.consts) else { return Visit::Children };
        if path.split(['.', '[']).next().is_some_and(|root| self.shadow.contains(root)) {
            return Visit::Children;
        }
        if let Some(r) = self.leaves.get(&path) {
            if !dynamic {
                *e = r.clone();
                return Visit::Parent;
            }
            if self.samplers.contains(&path) {
                let msg = format!("0: the sampler `{path}' must be reached through constant indices");
                self.error.get_or_insert(msg);
                return Visit::Parent;
            }
        }
        if self.roots.contains(&path) {
            self.whole.insert(path);
        }
        Visit::Children
    }
}

/// Parses generated code.
pub(super) fn parse(text: &str) -> Result<Vec<ast::ExternalDeclaration>, String> {
    ast::TranslationUnit::parse(text)
        .map(|tu| tu.0)
        .map_err(|e| format!("0: internal error: generated code for a structure does not parse: {e}"))
}

/// Renames `tu`'s `main` to `renamed` and adds a `main` that runs `steps` and then it.
pub(super) fn wrap_main(tu: &mut ast::TranslationUnit, renamed: &str, steps: &str) -> Result<(), String> {
    for decl in &mut tu.0 {
        let proto = match &mut decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => &mut f.prototype,
            ast::ExternalDeclarationData::Declaration(d) => match &mut d.content {
                ast::DeclarationData::FunctionPrototype(p) => p,
                _ => continue,
            },
            _ => continue,
        };
        if proto.name.0 == "main" {
            proto.name = ast::IdentifierData(renamed.into()).into();
        }
    }
    tu.0.extend(parse(&format!("void main() {{\n{steps}    {renamed}();\n}}"))?);
    Ok(())
}

/// The statements copying leaf `leaf` (a uniform named by its identifier) into the private
/// global: an array element by element, as the uniform block lays arrays out otherwise.
pub(super) fn fill(out: &mut String, to: &str, from: &str, array: Option<u32>) {
    match array {
        Some(n) => (0..n).for_each(|k| {
            let _ = writeln!(out, "    {to}[{k}] = {from}[{k}];");
        }),
        None => {
            let _ = writeln!(out, "    {to} = {from};");
        }
    }
}

/// An identifier expression.
pub(super) fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

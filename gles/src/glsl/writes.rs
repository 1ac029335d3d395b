//! GLSL ES rules on expressions that the parser accepts: in GLSL ES 1.00 the reserved operators
//! (§5.1: `%`, `~`, `<<`, `>>`, `&`, `|`, `^` and their assignments) and assignment to a whole
//! array (§5.8), which GLSL ES 3.00 allows; in either, writes to read-only variables (§4.3.3 attributes, §4.3.4 uniforms, §4.3.5 varyings
//! in fragment shaders, constants), including passing them as `out`/`inout` arguments
//! (`conversions` checks basic types).
//!
//! Names are resolved per function: a parameter or a local of a name hides the global of that
//! name anywhere in the function (a simplification that can only accept more shaders).

use std::collections::{HashMap, HashSet};

use glsl_lang::ast::{
    self, AssignmentOpData as A, BinaryOpData as B, ExprData, FunIdentifierData, StorageQualifierData as S,
    TypeQualifierSpecData, UnaryOpData as U,
};
use glsl_lang::visitor::{Host, Visit, Visitor};

use crate::glsl::types::Stage;

/// Where an error is, as the info log writes it.
type At<'a> = &'a dyn Fn(Option<ast::NodeSpan>, &str) -> String;

/// The storage qualifiers of a qualifier list.
fn storages(q: Option<&ast::TypeQualifier>) -> Vec<S> {
    q.map(|q| {
        q.qualifiers
            .iter()
            .filter_map(|s| match &s.content {
                TypeQualifierSpecData::Storage(st) => Some(st.content.clone()),
                _ => None,
            })
            .collect()
    })
    .unwrap_or_default()
}

/// The variables a declaration list declares, with whether each is an array.
fn declared(list: &ast::InitDeclaratorList) -> Vec<(String, bool)> {
    let base = list.head.ty.ty.array_specifier.is_some();
    let mut v = Vec::new();
    if let Some(n) = &list.head.name {
        v.push((n.0.to_string(), base || list.head.array_specifier.is_some()));
    }
    for t in &list.tail {
        v.push((t.ident.ident.0.to_string(), base || t.ident.array_spec.is_some()));
    }
    v
}

/// The variable an l-value expression writes (through indexing and field selection).
fn root(e: &ast::Expr) -> Option<&ast::Expr> {
    match &e.content {
        ExprData::Variable(_) => Some(e),
        ExprData::Bracket(a, _) | ExprData::Dot(a, _) => root(a),
        _ => None,
    }
}

/// Checks every rule above on `tu`.
pub(super) fn check(stage: Stage, version: u16, tu: &ast::TranslationUnit, at: At<'_>) -> Result<(), String> {
    // Global read-only variables (with why) and global arrays.
    let mut read_only: HashMap<String, &'static str> = HashMap::new();
    let mut arrays: HashSet<String> = HashSet::new();
    // Per function name: for each overload, which parameters are `out` or `inout`.
    let mut outs: HashMap<String, Vec<Vec<bool>>> = HashMap::new();
    for decl in &tu.0 {
        match &decl.content {
            ast::ExternalDeclarationData::Declaration(d) => {
                if let ast::DeclarationData::InitDeclaratorList(list) = &d.content {
                    let st = storages(list.head.ty.qualifier.as_ref());
                    let why = if st.contains(&S::Attribute) {
                        Some("attribute")
                    } else if st.contains(&S::Uniform) {
                        Some("uniform")
                    } else if st.contains(&S::Varying) && stage == Stage::Fragment {
                        Some("varying")
                    } else if st.contains(&S::In) {
                        Some("input")
                    } else if st.contains(&S::Const) {
                        Some("constant")
                    } else {
                        None
                    };
                    for (n, is_array) in declared(list) {
                        if let Some(why) = why {
                            read_only.insert(n.clone(), why);
                        }
                        if is_array {
                            arrays.insert(n);
                        }
                    }
                }
            }
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                let p = &f.prototype;
                let o = p
                    .parameters
                    .iter()
                    .map(|param| {
                        let q = match &param.content {
                            ast::FunctionParameterDeclarationData::Named(q, _)
                            | ast::FunctionParameterDeclarationData::Unnamed(q, _) => q.as_ref(),
                        };
                        let st = storages(q);
                        st.contains(&S::Out) || st.contains(&S::InOut)
                    })
                    .collect();
                outs.entry(p.name.0.to_string()).or_default().push(o);
            }
            _ => {}
        }
    }
    for decl in &tu.0 {
        let ast::ExternalDeclarationData::FunctionDefinition(f) = &decl.content else { continue };
        let mut locals = Locals::default();
        for param in &f.prototype.parameters {
            if let ast::FunctionParameterDeclarationData::Named(_, d) = &param.content {
                let is_array = d.ty.array_specifier.is_some() || d.ident.array_spec.is_some();
                locals.names.insert(d.ident.ident.0.to_string());
                if is_array {
                    locals.arrays.insert(d.ident.ident.0.to_string());
                }
            }
        }
        f.statement.visit(&mut locals);
        let mut rules =
            Rules { read_only: &read_only, arrays: &arrays, outs: &outs, locals: &locals, error: None, version };
        f.statement.visit(&mut rules);
        if let Some((span, msg)) = rules.error {
            return Err(at(span, &msg));
        }
    }
    Ok(())
}

/// The parameters and locals of one function, and which of them are arrays.
#[derive(Default)]
struct Locals {
    names: HashSet<String>,
    arrays: HashSet<String>,
}

impl Visitor for Locals {
    fn visit_init_declarator_list(&mut self, list: &ast::InitDeclaratorList) -> Visit {
        let constant = storages(list.head.ty.qualifier.as_ref()).contains(&S::Const);
        for (n, is_array) in declared(list) {
            // A local constant stays read-only: it is not recorded as writable.
            if !constant {
                self.names.insert(n.clone());
            }
            if is_array {
                self.arrays.insert(n);
            }
        }
        Visit::Children
    }
}

/// The expression rules of one function body; the first error wins.
struct Rules<'a> {
    read_only: &'a HashMap<String, &'static str>,
    arrays: &'a HashSet<String>,
    outs: &'a HashMap<String, Vec<Vec<bool>>>,
    locals: &'a Locals,
    error: Option<(Option<ast::NodeSpan>, String)>,
    /// The language version: GLSL ES 3.00 has the operators and array assignment.
    version: u16,
}

impl Rules<'_> {
    /// Why the variable `e` writes cannot be written, if it cannot.
    fn unwritable(&self, e: &ast::Expr) -> Option<String> {
        let ExprData::Variable(id) = &root(e)?.content else { return None };
        let name = id.0.as_str();
        if self.locals.names.contains(name) {
            return None;
        }
        self.read_only.get(name).map(|why| format!("cannot write to read-only {why} `{name}'"))
    }

    /// Whether `e` names a whole array.
    fn is_array(&self, e: &ast::Expr) -> bool {
        let ExprData::Variable(id) = &e.content else { return false };
        let name = id.0.as_str();
        self.locals.arrays.contains(name) || (!self.locals.names.contains(name) && self.arrays.contains(name))
    }

    fn fail(&mut self, span: Option<ast::NodeSpan>, msg: String) -> Visit {
        self.error.get_or_insert((span, msg));
        Visit::Parent
    }
}

impl Visitor for Rules<'_> {
    fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
        if self.error.is_some() {
            return Visit::Parent;
        }
        match &e.content {
            ExprData::Binary(op, ..) if self.version == 100 && reserved_binary(&op.content).is_some() => {
                let text = reserved_binary(&op.content).unwrap_or_default();
                return self.fail(e.span, format!("operator `{text}' is reserved in GLSL ES 1.00"));
            }
            ExprData::Unary(op, _) if self.version == 100 && op.content == U::Complement => {
                return self.fail(e.span, "operator `~' is reserved in GLSL ES 1.00".into());
            }
            ExprData::Assignment(lhs, op, _) => {
                if let Some(text) = reserved_assignment(&op.content).filter(|_| self.version == 100) {
                    return self.fail(e.span, format!("operator `{text}' is reserved in GLSL ES 1.00"));
                }
                if let Some(why) = self.unwritable(lhs) {
                    return self.fail(e.span, why);
                }
                if self.version == 100 && self.is_array(lhs) {
                    return self.fail(e.span, "arrays cannot be the target of an assignment".into());
                }
            }
            ExprData::PostInc(a) | ExprData::PostDec(a) => {
                if let Some(why) = self.unwritable(a) {
                    return self.fail(e.span, why);
                }
            }
            ExprData::Unary(op, a) if matches!(op.content, U::Inc | U::Dec) => {
                if let Some(why) = self.unwritable(a) {
                    return self.fail(e.span, why);
                }
            }
            ExprData::FunCall(f, args) => {
                if let FunIdentifierData::Expr(callee) = &f.content {
                    if let ExprData::Variable(id) = &callee.content {
                        let overloads = self.outs.get(id.0.as_str()).map(Vec::as_slice).unwrap_or_default();
                        for o in overloads.iter().filter(|o| o.len() == args.len()) {
                            for (arg, _) in args.iter().zip(o).filter(|(_, &out)| out) {
                                if let Some(why) = self.unwritable(arg) {
                                    return self.fail(arg.span.or(e.span), format!("{why} (an `out' argument)"));
                                }
                            }
                        }
                    }
                }
            }
            _ => {}
        }
        Visit::Children
    }
}

/// The text of a reserved binary operator.
fn reserved_binary(op: &B) -> Option<&'static str> {
    Some(match op {
        B::Mod => "%",
        B::BitAnd => "&",
        B::BitOr => "|",
        B::BitXor => "^",
        B::LShift => "<<",
        B::RShift => ">>",
        _ => return None,
    })
}

/// The text of a reserved assignment operator.
fn reserved_assignment(op: &A) -> Option<&'static str> {
    Some(match op {
        A::Mod => "%=",
        A::LShift => "<<=",
        A::RShift => ">>=",
        A::And => "&=",
        A::Xor => "^=",
        A::Or => "|=",
        _ => return None,
    })
}

//! Global initialisers naga cannot evaluate at global scope, moved into `main`.

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeQualifierSpecData};
use glsl_lang::visitor::{Host, Visit};

/// `+(a, b)` for a sequence `(a, b)`: the transpiler writes a sequence without parentheses, which
/// in an argument or initializer would read as two; a unary plus makes it keep them.
pub(super) fn keep_sequence(e: &mut ast::Expr) {
    if matches!(e.content, ExprData::Comma(..)) {
        let seq = std::mem::replace(e, ExprData::IntConst(0).into());
        *e = ExprData::Unary(ast::UnaryOpData::Add.into(), Box::new(seq)).into();
    }
}

fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

/// Whether an expression calls a function (a constructor is no call) or reads one of `names`.
fn calls_function(e: &ast::Expr, names: &std::collections::HashSet<String>) -> bool {
    struct Finder<'a>(bool, &'a std::collections::HashSet<String>);
    impl glsl_lang::visitor::Visitor for Finder<'_> {
        fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
            match &e.content {
                ExprData::FunCall(f, _) => self.0 |= matches!(f.content, FunIdentifierData::Expr(_)),
                ExprData::Variable(v) => self.0 |= self.1.contains(v.0.as_str()),
                _ => {}
            }
            Visit::Children
        }
    }
    let mut f = Finder(false, names);
    e.visit(&mut f);
    f.0
}

/// Global initialisers that call functions (GLSL ES 1.00 §5.10 allows built-in calls in constant
/// expressions; naga evaluates none at global scope), or read a global whose initialiser moved,
/// become assignments at the start of `main`, before any of the shader's code runs; `const`
/// goes, as the compile already checked writes.
pub(super) fn hoist_global_initializers(tu: &mut ast::TranslationUnit) {
    let mut hoisted: Vec<ast::Statement> = Vec::new();
    let mut moved = std::collections::HashSet::new();
    for decl in &mut tu.0 {
        let ast::ExternalDeclarationData::Declaration(d) = &mut decl.content else { continue };
        let ast::DeclarationData::InitDeclaratorList(list) = &mut d.content else { continue };
        let mut take = |name: &str, init: &mut Option<ast::Initializer>| {
            let Some(ast::InitializerData::Simple(e)) = init.as_deref() else { return false };
            if !calls_function(e, &moved) {
                return false;
            }
            moved.insert(name.to_string());
            let mut value: ast::Expr = (**e).clone();
            keep_sequence(&mut value);
            let assign: ast::Expr =
                ExprData::Assignment(Box::new(var(name)), ast::AssignmentOpData::Equal.into(), Box::new(value)).into();
            hoisted.push(ast::StatementData::Expression(ast::ExprStatementData(Some(assign)).into()).into());
            *init = None;
            true
        };
        let mut any = false;
        if let Some(name) = list.head.name.clone() {
            any |= take(name.0.as_str(), &mut list.head.initializer);
        }
        for t in &mut list.tail {
            let name = t.ident.ident.0.to_string();
            any |= take(&name, &mut t.initializer);
        }
        if any {
            if let Some(q) = &mut list.head.ty.qualifier {
                q.qualifiers.retain(|s| {
                    !matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Const)
                });
                if q.qualifiers.is_empty() {
                    list.head.ty.qualifier = None;
                }
            }
        }
    }
    if hoisted.is_empty() {
        return;
    }
    for decl in &mut tu.0 {
        if let ast::ExternalDeclarationData::FunctionDefinition(f) = &mut decl.content {
            if f.prototype.name.0 == "main" || f.prototype.name.0 == "strata_main" {
                let body = &mut f.statement.statement_list;
                body.splice(0..0, hoisted.iter().cloned());
            }
        }
    }
}

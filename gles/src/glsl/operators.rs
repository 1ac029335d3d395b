//! Operators and constructors that naga's GLSL front end refuses or translates wrongly, rewritten
//! with their operands' shapes (`shapes`) before the rest of the rewrite:
//! - `==` and `!=` of arrays (GLSL ES 3.00 §5.9) call a generated function that compares the
//!   arrays element by element (each operand is evaluated once, as an argument);
//! - `%` and `%=` of a vector and a scalar (§5.9) make the scalar a vector;
//! - `-` of an unsigned integer becomes `0u - x`;
//! - a numeric constructor of one boolean value of another size (`int(bvec3)`, `ivec2(bool)`,
//!   `mat2(bool)`, §5.4.1) converts the boolean at its own size first.

use glsl_lang::ast::{
    self, AssignmentOpData as A, BinaryOpData as B, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T,
    UnaryOpData as U,
};

use crate::glsl::block_members::ctor;
use crate::glsl::preprocess::{error_at, line_col};
use crate::glsl::shapes::{matrix, size, vector, Scope, Shape};

/// The rewrite, one external declaration at a time.
struct Operators {
    scope: Scope,
    /// The generated comparisons: the shape compared and the function's name.
    equals: Vec<(Shape, String)>,
    /// The generated functions, each with the index of the declaration it goes before.
    generated: Vec<(usize, ast::ExternalDeclaration)>,
    /// The index of the declaration being rewritten.
    at: usize,
    error: Option<(Option<ast::NodeSpan>, String)>,
}

fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

fn binary(op: B, a: ast::Expr, b: ast::Expr) -> ast::Expr {
    ExprData::Binary(op.into(), Box::new(a), Box::new(b)).into()
}

fn index(a: ast::Expr, k: u32) -> ast::Expr {
    ExprData::Bracket(Box::new(a), Box::new(ExprData::IntConst(k as i32).into())).into()
}

/// `a && b && …` (`true` for none).
fn all(parts: Vec<ast::Expr>) -> ast::Expr {
    parts.into_iter().reduce(|a, b| binary(B::And, a, b)).unwrap_or_else(|| ExprData::BoolConst(true).into())
}

/// `bool NAME(T strata_x, T strata_y) { return …; }` for values of shape `s`, `equal` their
/// comparison.
fn equal_function(name: &str, s: &Shape, equal: ast::Expr) -> ast::ExternalDeclaration {
    let param = |p: &str| -> ast::FunctionParameterDeclaration {
        let spec = s.array.flatten().map(|n| {
            let size: ast::Expr = ExprData::IntConst(n as i32).into();
            let dims = vec![ast::ArraySpecifierDimensionData::ExplicitlySized(Box::new(size)).into()];
            ast::ArraySpecifierData { dimensions: dims }.into()
        });
        let ident = ast::ArrayedIdentifierData { ident: ast::IdentifierData(p.into()).into(), array_spec: spec };
        let ty = ast::TypeSpecifierData { ty: s.ty.clone().into(), array_specifier: None };
        let decl = ast::FunctionParameterDeclaratorData { ty: ty.into(), ident: ident.into() };
        ast::FunctionParameterDeclarationData::Named(None, decl.into()).into()
    };
    let ret = ast::JumpStatementData::Return(Some(Box::new(equal)));
    let body = ast::CompoundStatementData { statement_list: vec![ast::StatementData::Jump(ret.into()).into()] };
    let returns = ast::TypeSpecifierData { ty: T::Bool.into(), array_specifier: None };
    let prototype = ast::FunctionPrototypeData {
        ty: ast::FullySpecifiedTypeData { qualifier: None, ty: returns.into() }.into(),
        name: ast::IdentifierData(name.into()).into(),
        parameters: vec![param("strata_x"), param("strata_y")],
    };
    let f = ast::FunctionDefinitionData { prototype: prototype.into(), statement: body.into() };
    ast::ExternalDeclarationData::FunctionDefinition(f.into()).into()
}

impl Operators {
    fn fail(&mut self, span: Option<ast::NodeSpan>, msg: &str) {
        self.error.get_or_insert((span, msg.to_string()));
    }

    /// `x == y` for values of shape `s`, part by part (arrays by element, structures by member,
    /// matrices by column); `None` where a part's shape is unknown.
    fn parts(&self, s: &Shape, x: ast::Expr, y: ast::Expr) -> Option<ast::Expr> {
        if let Some(n) = s.array {
            let element = Shape::value(s.ty.clone());
            let each = (0..n?).map(|k| self.parts(&element, index(x.clone(), k), index(y.clone(), k)));
            return Some(all(each.collect::<Option<_>>()?));
        }
        let dot = |e: &ast::Expr, f: &str| -> ast::Expr {
            ExprData::Dot(Box::new(e.clone()), ast::IdentifierData(f.into()).into()).into()
        };
        Some(match (&s.ty, matrix(&s.ty)) {
            (T::TypeName(name), _) => {
                let fields = self.scope.fields(&name.0)?;
                all(fields.iter().map(|(f, fs)| self.parts(fs, dot(&x, f), dot(&y, f))).collect::<Option<_>>()?)
            }
            (_, Some((columns, _))) => all((0..u32::from(columns))
                .map(|c| binary(B::Equal, index(x.clone(), c), index(y.clone(), c)))
                .collect()),
            _ => binary(B::Equal, x, y),
        })
    }

    /// The name of the function comparing two values of shape `s` (an array or a structure).
    fn equal(&mut self, s: &Shape) -> Option<String> {
        if let Some((_, name)) = self.equals.iter().find(|(t, _)| t == s) {
            return Some(name.clone());
        }
        let name = format!("strata_equal{}", self.equals.len());
        let parts = self.parts(s, var("strata_x"), var("strata_y"))?;
        self.equals.push((s.clone(), name.clone()));
        self.generated.push((self.at, equal_function(&name, s, parts)));
        Some(name)
    }

    /// Rewrites `e`, its operands first.
    fn expr(&mut self, e: &mut ast::Expr) {
        match &mut e.content {
            ExprData::Unary(_, a) | ExprData::PostInc(a) | ExprData::PostDec(a) | ExprData::Dot(a, _) => self.expr(a),
            ExprData::Binary(_, a, b)
            | ExprData::Comma(a, b)
            | ExprData::Assignment(a, _, b)
            | ExprData::Bracket(a, b) => {
                self.expr(a);
                self.expr(b);
            }
            ExprData::Ternary(c, a, b) => {
                self.expr(c);
                self.expr(a);
                self.expr(b);
            }
            ExprData::FunCall(f, args) => {
                if let FunIdentifierData::Expr(callee) = &mut f.content {
                    self.expr(callee);
                }
                args.iter_mut().for_each(|a| self.expr(a));
            }
            _ => {}
        }
        let span = e.span;
        let replacement = match &mut e.content {
            ExprData::Binary(op, a, b) if matches!(op.content, B::Equal | B::NonEqual) => {
                let (sa, sb) = (self.scope.of(a), self.scope.of(b));
                let aggregate = |s: &&Shape| s.array.is_some() || matches!(s.ty, T::TypeName(_));
                let known = [&sa, &sb].into_iter().flatten().filter(aggregate).cloned();
                let Some(s) = known.max_by_key(|s| s.array != Some(None)) else { return };
                let Some(name) = self.equal(&s) else {
                    let msg = "comparison of arrays or structures of this type is not supported (sizes must be \
                               integer literals, structures declared outside functions)";
                    return self.fail(span, msg);
                };
                let call = FunIdentifierData::Expr(Box::new(var(&name))).into();
                let placeholder = || Box::new(ast::Expr::from(ExprData::IntConst(0)));
                let args = vec![*std::mem::replace(a, placeholder()), *std::mem::replace(b, placeholder())];
                let c: ast::Expr = ExprData::FunCall(call, args).into();
                Some(match op.content {
                    B::Equal => c,
                    _ => ExprData::Unary(U::Not.into(), Box::new(c)).into(),
                })
            }
            ExprData::Binary(op, a, b) if op.content == B::Mod => {
                self.splat(a, b);
                None
            }
            ExprData::Assignment(a, op, b) if op.content == A::Mod => {
                if let Some(s) = self.scope.of(a).filter(|s| s.size().is_some_and(|n| n > 1)) {
                    if self.scope.of(b).and_then(|s| s.size()) == Some(1) {
                        **b = ctor(s.ty, vec![std::mem::replace(b, ExprData::IntConst(0).into())]);
                    }
                }
                None
            }
            ExprData::Unary(op, a) if op.content == U::Minus => {
                let unsigned = self.scope.of(a).and_then(|s| s.scalar()) == Some(T::UInt);
                unsigned.then(|| {
                    let x = std::mem::replace(&mut **a, ExprData::IntConst(0).into());
                    binary(B::Sub, ExprData::UIntConst(0).into(), x)
                })
            }
            ExprData::FunCall(f, args) if args.len() == 1 => {
                let FunIdentifierData::TypeSpecifier(ts) = &f.content else { return };
                let Some(target) = crate::glsl::shapes::scalar(&ts.ty).filter(|_| ts.array_specifier.is_none()) else {
                    return;
                };
                let Some(from) = self.scope.of(&args[0]) else { return };
                let n = from.size();
                if target != T::Bool && from.scalar() == Some(T::Bool) && n != size(&ts.ty) {
                    if let Some(via) = n.and_then(|n| vector(&target, n)) {
                        args[0] = ctor(via, vec![std::mem::replace(&mut args[0], ExprData::IntConst(0).into())]);
                    }
                }
                None
            }
            _ => None,
        };
        if let Some(r) = replacement {
            *e = r;
        }
    }

    /// Makes the scalar operand of `a % b` a vector when the other is one.
    fn splat(&mut self, a: &mut ast::Expr, b: &mut ast::Expr) {
        let (sa, sb) = (self.scope.of(a), self.scope.of(b));
        let (Some(na), Some(nb)) = (sa.as_ref().and_then(Shape::size), sb.as_ref().and_then(Shape::size)) else {
            return;
        };
        let (scalar, to) = match (na, nb) {
            (1, n) if n > 1 => (a, sb),
            (n, 1) if n > 1 => (b, sa),
            _ => return,
        };
        if let Some(to) = to {
            *scalar = ctor(to.ty, vec![std::mem::replace(scalar, ExprData::IntConst(0).into())]);
        }
    }
}

impl Operators {
    /// Rewrites a statement's expressions, with the names it declares in scope.
    fn statement(&mut self, st: &mut ast::Statement) {
        use ast::StatementData as S;
        match &mut st.content {
            S::Declaration(d) => self.declaration(d),
            S::Expression(e) => e.0.iter_mut().for_each(|e| self.expr(e)),
            S::Selection(sel) => {
                self.expr(&mut sel.cond);
                match &mut sel.rest.content {
                    ast::SelectionRestStatementData::Statement(a) => self.scoped(a),
                    ast::SelectionRestStatementData::Else(a, b) => {
                        self.scoped(a);
                        self.scoped(b);
                    }
                }
            }
            S::Switch(sw) => {
                self.expr(&mut sw.head);
                self.scope.push();
                sw.body.iter_mut().for_each(|s| self.statement(s));
                self.scope.pop();
            }
            S::CaseLabel(c) => {
                if let ast::CaseLabelData::Case(e) = &mut c.content {
                    self.expr(e);
                }
            }
            S::Iteration(it) => {
                self.scope.push();
                match &mut it.content {
                    ast::IterationStatementData::While(c, body) => {
                        self.condition(c);
                        self.scoped(body);
                    }
                    ast::IterationStatementData::DoWhile(body, e) => {
                        self.scoped(body);
                        self.expr(e);
                    }
                    ast::IterationStatementData::For(init, rest, body) => {
                        match &mut init.content {
                            ast::ForInitStatementData::Expression(e) => e.iter_mut().for_each(|e| self.expr(e)),
                            ast::ForInitStatementData::Declaration(d) => self.declaration(d),
                        }
                        if let Some(c) = &mut rest.condition {
                            self.condition(c);
                        }
                        rest.post_expr.iter_mut().for_each(|e| self.expr(e));
                        self.scoped(body);
                    }
                }
                self.scope.pop();
            }
            S::Jump(j) => {
                if let ast::JumpStatementData::Return(Some(e)) = &mut j.content {
                    self.expr(e);
                }
            }
            S::Compound(c) => {
                self.scope.push();
                c.statement_list.iter_mut().for_each(|s| self.statement(s));
                self.scope.pop();
            }
        }
    }

    /// A statement in a scope of its own.
    fn scoped(&mut self, st: &mut ast::Statement) {
        self.scope.push();
        self.statement(st);
        self.scope.pop();
    }

    fn condition(&mut self, c: &mut ast::Condition) {
        match &mut c.content {
            ast::ConditionData::Expr(e) => self.expr(e),
            ast::ConditionData::Assignment(ty, name, init) => {
                self.initializer(init);
                self.scope.declare(&name.0, Scope::declared(&ty.ty, None));
            }
        }
    }

    fn initializer(&mut self, init: &mut ast::Initializer) {
        match &mut init.content {
            ast::InitializerData::Simple(e) => self.expr(e),
            ast::InitializerData::List(list) => list.iter_mut().for_each(|i| self.initializer(i)),
        }
    }

    /// Rewrites a declaration's initialisers, then declares its names (each initialiser sees
    /// the names before it).
    fn declaration(&mut self, d: &mut ast::Declaration) {
        if let ast::DeclarationData::InitDeclaratorList(list) = &mut d.content {
            list.head.initializer.iter_mut().for_each(|i| self.initializer(i));
            list.tail.iter_mut().flat_map(|t| t.initializer.iter_mut()).for_each(|i| self.initializer(i));
            self.scope.declare_list(list);
        }
    }
}

/// Rewrites the operators and constructors above in `tu` (`text`: the parsed text, for the
/// lines of errors).
pub(super) fn rewrite(tu: &mut ast::TranslationUnit, text: &str) -> Result<(), String> {
    let mut ops = Operators { scope: Scope::new(tu), equals: vec![], generated: vec![], at: 0, error: None };
    for (i, decl) in tu.0.iter_mut().enumerate() {
        ops.at = i;
        match &mut decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => {
                ops.scope.enter(f);
                f.statement.statement_list.iter_mut().for_each(|s| ops.statement(s));
                ops.scope.leave();
            }
            ast::ExternalDeclarationData::Declaration(d) => ops.declaration(d),
            ast::ExternalDeclarationData::Preprocessor(_) => {}
        }
        if let Some((span, msg)) = ops.error.take() {
            let (line, col) = span.map_or((1, 1), |s| line_col(text, usize::from(s.range().start())));
            return Err(error_at(line, col, &msg));
        }
    }
    for (i, f) in ops.generated.into_iter().rev() {
        tu.0.insert(i, f);
    }
    Ok(())
}

//! GLSL ES has no implicit conversions (1.00 and 3.00 §4.1.10): the operands of an arithmetic,
//! bitwise or relational operator, the two sides of an assignment, a declaration and its
//! initialiser, the branches of `?:` and a function's return value and type must share a basic
//! type (float, int, uint or bool). naga's GLSL front end, whose language is GLSL 4.x, converts
//! silently, so the shader is checked before it is translated.
//!
//! Types are inferred only where they are certain: literals, declared variables (a name
//! declared with two basic types in one function, or there and globally, is left unknown),
//! structure and block members, constructors, swizzles, indexing, `length()`, user functions
//! whose overloads all return one type, and operators. Whatever is unknown (the built-in
//! functions among them) is never an error.

use std::collections::HashMap;

use glsl_lang::ast::{
    self, AssignmentOpData as A, BinaryOpData as B, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T,
    UnaryOpData as U,
};
use glsl_lang::visitor::{Host, Visit, Visitor};

/// Where an error is, as the info log writes it.
type At<'a> = &'a dyn Fn(Option<ast::NodeSpan>, &str) -> String;

/// A basic type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Basic {
    Float,
    Int,
    UInt,
    Bool,
}

impl Basic {
    fn name(self) -> &'static str {
        match self {
            Basic::Float => "float",
            Basic::Int => "int",
            Basic::UInt => "uint",
            Basic::Bool => "bool",
        }
    }
}

/// What is known of an expression's or a variable's type.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Ty {
    /// A scalar, vector or matrix of a basic type (`array`: an array of them).
    Value { basic: Basic, array: bool },
    /// A structure (or a block's instance), by name.
    Struct { name: String, array: bool },
}

impl Ty {
    fn basic(&self) -> Option<Basic> {
        match self {
            Ty::Value { basic, array: false } => Some(*basic),
            _ => None,
        }
    }

    /// The type of one element of an array, or of a component (column) of a vector (matrix).
    fn indexed(&self) -> Option<Ty> {
        Some(match self {
            Ty::Value { basic, .. } => Ty::Value { basic: *basic, array: false },
            Ty::Struct { name, array: true } => Ty::Struct { name: name.clone(), array: false },
            Ty::Struct { array: false, .. } => return None,
        })
    }
}

/// The type a type specifier names (`array`: declared as an array), if it is one of the above.
fn of_spec(t: &T, array: bool) -> Option<Ty> {
    let basic = match t {
        T::Float | T::Vec2 | T::Vec3 | T::Vec4 => Basic::Float,
        T::Mat2 | T::Mat3 | T::Mat4 | T::Mat22 | T::Mat23 | T::Mat24 => Basic::Float,
        T::Mat32 | T::Mat33 | T::Mat34 | T::Mat42 | T::Mat43 | T::Mat44 => Basic::Float,
        T::Int | T::IVec2 | T::IVec3 | T::IVec4 => Basic::Int,
        T::UInt | T::UVec2 | T::UVec3 | T::UVec4 => Basic::UInt,
        T::Bool | T::BVec2 | T::BVec3 | T::BVec4 => Basic::Bool,
        T::TypeName(n) => return Some(Ty::Struct { name: n.0.to_string(), array }),
        T::Struct(s) => return s.name.as_ref().map(|n| Ty::Struct { name: n.0.to_string(), array }),
        _ => return None,
    };
    Some(Ty::Value { basic, array })
}

/// The built-in variables and constants with a certain type.
fn builtin(name: &str) -> Option<Ty> {
    let basic = match name {
        "gl_Position" | "gl_FragCoord" | "gl_FragColor" | "gl_PointSize" | "gl_PointCoord" | "gl_FragDepth" => {
            Basic::Float
        }
        "gl_FragData" => return Some(Ty::Value { basic: Basic::Float, array: true }),
        "gl_VertexID" | "gl_InstanceID" => Basic::Int,
        "gl_FrontFacing" => Basic::Bool,
        n if n.starts_with("gl_Max") || n.starts_with("gl_Min") => Basic::Int,
        _ => return None,
    };
    Some(Ty::Value { basic, array: false })
}

/// Names with their types where certain: `None` where declared with different types.
#[derive(Default, Clone)]
struct Names(HashMap<String, Option<Ty>>);

impl Names {
    fn declare(&mut self, name: &str, ty: Option<Ty>) {
        self.0.entry(name.to_string()).and_modify(|t| *t = if *t == ty { ty.clone() } else { None }).or_insert(ty);
    }
}

/// The declarations a list makes, with their types.
fn declared(list: &ast::InitDeclaratorList) -> Vec<(String, Option<Ty>)> {
    let ty = &list.head.ty.ty;
    let base = ty.array_specifier.is_some();
    let mut v = Vec::new();
    if let Some(n) = &list.head.name {
        v.push((n.0.to_string(), of_spec(&ty.ty.content, base || list.head.array_specifier.is_some())));
    }
    for t in &list.tail {
        v.push((t.ident.ident.0.to_string(), of_spec(&ty.ty.content, base || t.ident.array_spec.is_some())));
    }
    v
}

/// The members of structures and blocks, by structure (block) name.
type Members = HashMap<String, Option<Names>>;

/// Collects structures, blocks and the variables of one scope: the globals, or one function's
/// parameters and locals (`params`).
#[derive(Default)]
struct Collect {
    members: Members,
    names: Names,
    params: bool,
}

impl Collect {
    fn fields(fields: &[ast::StructFieldSpecifier]) -> Names {
        let mut names = Names::default();
        for f in fields {
            for id in &f.identifiers {
                let array = f.ty.array_specifier.is_some() || id.array_spec.is_some();
                names.declare(&id.ident.0, of_spec(&f.ty.ty, array));
            }
        }
        names
    }

    fn structure(&mut self, name: &str, fields: Names) {
        self.members
            .entry(name.to_string())
            .and_modify(|m| {
                if m.as_ref().map(|n| &n.0) != Some(&fields.0) {
                    *m = None;
                }
            })
            .or_insert(Some(fields));
    }
}

impl Visitor for Collect {
    fn visit_struct_specifier(&mut self, s: &ast::StructSpecifier) -> Visit {
        if let Some(n) = &s.name {
            let fields = Collect::fields(&s.fields);
            self.structure(&n.0, fields);
        }
        Visit::Children
    }

    fn visit_block(&mut self, b: &ast::Block) -> Visit {
        let fields = Collect::fields(&b.fields);
        match &b.identifier {
            Some(id) => {
                self.structure(&b.name.0, fields);
                let ty = Ty::Struct { name: b.name.0.to_string(), array: id.array_spec.is_some() };
                self.names.declare(&id.ident.0, Some(ty));
            }
            None => {
                for (n, t) in fields.0 {
                    self.names.declare(&n, t);
                }
            }
        }
        Visit::Parent
    }

    fn visit_init_declarator_list(&mut self, list: &ast::InitDeclaratorList) -> Visit {
        for (n, t) in declared(list) {
            self.names.declare(&n, t);
        }
        Visit::Children
    }

    fn visit_function_parameter_declarator(&mut self, d: &ast::FunctionParameterDeclarator) -> Visit {
        let array = d.ty.array_specifier.is_some() || d.ident.array_spec.is_some();
        self.names.declare(&d.ident.ident.0, of_spec(&d.ty.ty, array));
        Visit::Children
    }

    // A function's own names are collected per function.
    fn visit_function_definition(&mut self, _: &ast::FunctionDefinition) -> Visit {
        Visit::Parent
    }

    fn visit_function_prototype(&mut self, _: &ast::FunctionPrototype) -> Visit {
        if self.params {
            Visit::Children
        } else {
            Visit::Parent
        }
    }
}

/// Checks one function's expressions against the rules above.
struct Check<'a> {
    names: &'a Names,
    members: &'a Members,
    /// Each user function's return type, where all its overloads agree.
    functions: &'a HashMap<String, Option<Ty>>,
    /// The function's return type.
    returns: Option<Ty>,
    function: String,
    error: Option<(Option<ast::NodeSpan>, String)>,
}

impl Check<'_> {
    fn fail(&mut self, span: Option<ast::NodeSpan>, msg: String) {
        self.error.get_or_insert((span, msg));
    }

    /// The type of `e`, checking it on the way.
    fn ty(&mut self, e: &ast::Expr) -> Option<Ty> {
        let value = |basic| Some(Ty::Value { basic, array: false });
        match &e.content {
            ExprData::IntConst(_) => value(Basic::Int),
            ExprData::UIntConst(_) => value(Basic::UInt),
            ExprData::FloatConst(_) => value(Basic::Float),
            ExprData::BoolConst(_) => value(Basic::Bool),
            ExprData::DoubleConst(_) => None,
            ExprData::Variable(id) => match self.names.0.get(id.0.as_str()) {
                Some(t) => t.clone(),
                None => builtin(&id.0),
            },
            ExprData::Unary(op, a) => {
                let t = self.ty(a);
                match op.content {
                    U::Not => value(Basic::Bool),
                    _ => t,
                }
            }
            ExprData::PostInc(a) | ExprData::PostDec(a) => self.ty(a),
            ExprData::Comma(a, b) => {
                self.ty(a);
                self.ty(b)
            }
            ExprData::Binary(op, a, b) => {
                let (ta, tb) = (self.ty(a), self.ty(b));
                let (ba, bb) = (ta.as_ref().and_then(Ty::basic), tb.as_ref().and_then(Ty::basic));
                let what = match op.content {
                    B::Add | B::Sub | B::Mult | B::Div | B::Mod => Some("arithmetic"),
                    B::BitAnd | B::BitOr | B::BitXor => Some("bitwise"),
                    B::Lt | B::Gt | B::Lte | B::Gte | B::Equal | B::NonEqual => Some("relational"),
                    _ => None,
                };
                if let (Some(what), Some(x), Some(y)) = (what, ba, bb) {
                    if x != y {
                        self.fail(e.span, format!("could not implicitly convert operands to {what} operator"));
                    }
                }
                match op.content {
                    B::Lt | B::Gt | B::Lte | B::Gte | B::Equal | B::NonEqual | B::Or | B::Xor | B::And => {
                        value(Basic::Bool)
                    }
                    B::LShift | B::RShift => ta.filter(|t| t.basic().is_some()),
                    _ => ba.or(bb).and_then(value),
                }
            }
            ExprData::Ternary(c, a, b) => {
                self.ty(c);
                let (ta, tb) = (self.ty(a), self.ty(b));
                if let (Some(x), Some(y)) = (&ta, &tb) {
                    if x != y {
                        self.fail(e.span, "second and third operands of ?: operator must have the same type".into());
                    }
                }
                ta.or(tb)
            }
            ExprData::Assignment(lhs, op, rhs) => {
                let (tl, tr) = (self.ty(lhs), self.ty(rhs));
                let shift = matches!(op.content, A::LShift | A::RShift);
                if let (false, Some(x), Some(y)) =
                    (shift, tl.as_ref().and_then(Ty::basic), tr.as_ref().and_then(Ty::basic))
                {
                    if x != y {
                        let msg =
                            format!("value of type {} cannot be assigned to variable of type {}", y.name(), x.name());
                        self.fail(e.span, msg);
                    }
                }
                tl
            }
            ExprData::Bracket(a, i) => {
                self.ty(i);
                self.ty(a)?.indexed()
            }
            ExprData::Dot(a, field) => match self.ty(a)? {
                Ty::Struct { name, array: false } => {
                    self.members.get(&name)?.as_ref()?.0.get(field.0.as_str())?.clone()
                }
                // A swizzle keeps the basic type.
                Ty::Value { basic, array: false } => value(basic),
                _ => None,
            },
            ExprData::FunCall(f, args) => {
                for a in args {
                    self.ty(a);
                }
                match &f.content {
                    FunIdentifierData::TypeSpecifier(ts) => of_spec(&ts.ty, ts.array_specifier.is_some()),
                    FunIdentifierData::Expr(callee) => match &callee.content {
                        ExprData::Dot(base, m) if m.0 == "length" && args.is_empty() => {
                            self.ty(base);
                            value(Basic::Int)
                        }
                        ExprData::Variable(name) => self.functions.get(name.0.as_str()).cloned().flatten(),
                        _ => None,
                    },
                }
            }
        }
    }
}

impl Visitor for Check<'_> {
    fn visit_expr(&mut self, e: &ast::Expr) -> Visit {
        self.ty(e);
        Visit::Parent
    }

    fn visit_init_declarator_list(&mut self, list: &ast::InitDeclaratorList) -> Visit {
        let ty = &list.head.ty.ty;
        let base = ty.array_specifier.is_some();
        let inits = std::iter::once((list.head.initializer.as_ref(), list.head.array_specifier.is_some()))
            .chain(list.tail.iter().map(|t| (t.initializer.as_ref(), t.ident.array_spec.is_some())));
        for (init, array) in inits {
            let Some(ast::InitializerData::Simple(e)) = init.map(|i| &i.content) else { continue };
            let want = of_spec(&ty.ty.content, base || array).as_ref().and_then(Ty::basic);
            let got = self.ty(e).as_ref().and_then(Ty::basic);
            if let (Some(want), Some(got)) = (want, got) {
                if want != got {
                    let msg = format!(
                        "cannot initialise a `{}' with a `{}' (no implicit conversions)",
                        want.name(),
                        got.name()
                    );
                    self.fail(e.span, msg);
                }
            }
        }
        Visit::Parent
    }

    fn visit_jump_statement(&mut self, j: &ast::JumpStatement) -> Visit {
        if let ast::JumpStatementData::Return(Some(e)) = &j.content {
            let got = self.ty(e).as_ref().and_then(Ty::basic);
            if let (Some(want), Some(got)) = (self.returns.as_ref().and_then(Ty::basic), got) {
                if want != got {
                    let msg = format!(
                        "`return' with wrong type {}, in function `{}' returning {}",
                        got.name(),
                        self.function,
                        want.name()
                    );
                    self.fail(j.span, msg);
                }
            }
        }
        Visit::Parent
    }
}

/// Checks `tu` against the rules above.
pub(super) fn check(tu: &ast::TranslationUnit, at: At<'_>) -> Result<(), String> {
    let mut globals = Collect::default();
    tu.visit(&mut globals);
    let mut functions: HashMap<String, Option<Ty>> = HashMap::new();
    for decl in &tu.0 {
        let p = match &decl.content {
            ast::ExternalDeclarationData::FunctionDefinition(f) => &f.prototype,
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::FunctionPrototype(p) => p,
                _ => continue,
            },
            _ => continue,
        };
        let ty = of_spec(&p.ty.ty.ty, p.ty.ty.array_specifier.is_some());
        functions
            .entry(p.name.0.to_string())
            .and_modify(|t| *t = if *t == ty { ty.clone() } else { None })
            .or_insert(ty);
    }
    // Global initialisers.
    let mut check = Check {
        names: &globals.names,
        members: &globals.members,
        functions: &functions,
        returns: None,
        function: String::new(),
        error: None,
    };
    for decl in &tu.0 {
        if let ast::ExternalDeclarationData::Declaration(d) = &decl.content {
            d.visit(&mut check);
        }
    }
    if let Some((span, msg)) = check.error {
        return Err(at(span, &msg));
    }
    for decl in &tu.0 {
        let ast::ExternalDeclarationData::FunctionDefinition(f) = &decl.content else { continue };
        let mut local = Collect { members: globals.members.clone(), names: Names::default(), params: true };
        f.prototype.visit(&mut local);
        f.statement.visit(&mut local);
        // A local name hides a global one; declared with another type, it is unknown.
        let mut names = globals.names.clone();
        for (n, t) in local.names.0 {
            match names.0.get(&n) {
                Some(g) if *g != t => names.0.insert(n, None),
                _ => names.0.insert(n, t),
            };
        }
        let returns = of_spec(&f.prototype.ty.ty.ty, f.prototype.ty.ty.array_specifier.is_some());
        let mut check = Check {
            names: &names,
            members: &local.members,
            functions: &functions,
            returns,
            function: f.prototype.name.0.to_string(),
            error: None,
        };
        f.statement.visit(&mut check);
        if let Some((span, msg)) = check.error {
            return Err(at(span, &msg));
        }
    }
    Ok(())
}

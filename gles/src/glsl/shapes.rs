//! The shapes of expressions (basic type, vector size, matrix dimensions, structure, array
//! length) where they are certain, for the rewrites that depend on them (`operators`): literals,
//! declared variables and parameters (a name declared with two types in one function, or there
//! and globally, is left unknown), structure and block members, constructors, swizzles,
//! indexing, user functions whose overloads all return one type, the built-in functions whose
//! result follows from their arguments, and operators.

use std::collections::HashMap;

use glsl_lang::ast::{
    self, BinaryOpData as B, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T, UnaryOpData as U,
};
use glsl_lang::visitor::{Host, Visit, Visitor};

/// An expression's type: one element's and, for an array, its length.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Shape {
    /// The type of the value (of each element of an array).
    pub(super) ty: T,
    /// `None`: no array; `Some(None)`: an array whose length is no literal.
    pub(super) array: Option<Option<u32>>,
}

impl Shape {
    /// A value (no array) of type `ty`.
    pub(super) fn value(ty: T) -> Shape {
        Shape { ty, array: None }
    }

    /// The scalar type of a scalar, vector or matrix value (no array).
    pub(super) fn scalar(&self) -> Option<T> {
        self.array.is_none().then(|| scalar(&self.ty)).flatten()
    }

    /// The component count of a scalar (1) or vector value (no array).
    pub(super) fn size(&self) -> Option<u8> {
        self.array.is_none().then(|| size(&self.ty)).flatten()
    }
}

/// The scalar type of a scalar, vector or matrix type.
pub(super) fn scalar(t: &T) -> Option<T> {
    Some(match t {
        T::Float | T::Vec2 | T::Vec3 | T::Vec4 => T::Float,
        T::Int | T::IVec2 | T::IVec3 | T::IVec4 => T::Int,
        T::UInt | T::UVec2 | T::UVec3 | T::UVec4 => T::UInt,
        T::Bool | T::BVec2 | T::BVec3 | T::BVec4 => T::Bool,
        _ => return matrix(t).map(|_| T::Float),
    })
}

/// The component count of a scalar (1) or vector type.
pub(super) fn size(t: &T) -> Option<u8> {
    Some(match t {
        T::Float | T::Int | T::UInt | T::Bool => 1,
        T::Vec2 | T::IVec2 | T::UVec2 | T::BVec2 => 2,
        T::Vec3 | T::IVec3 | T::UVec3 | T::BVec3 => 3,
        T::Vec4 | T::IVec4 | T::UVec4 | T::BVec4 => 4,
        _ => return None,
    })
}

/// The scalar (`n` = 1) or vector type of `n` components of scalar type `s`.
pub(super) fn vector(s: &T, n: u8) -> Option<T> {
    Some(match (s, n) {
        (_, 1) => s.clone(),
        (T::Float, 2) => T::Vec2,
        (T::Float, 3) => T::Vec3,
        (T::Float, 4) => T::Vec4,
        (T::Int, 2) => T::IVec2,
        (T::Int, 3) => T::IVec3,
        (T::Int, 4) => T::IVec4,
        (T::UInt, 2) => T::UVec2,
        (T::UInt, 3) => T::UVec3,
        (T::UInt, 4) => T::UVec4,
        (T::Bool, 2) => T::BVec2,
        (T::Bool, 3) => T::BVec3,
        (T::Bool, 4) => T::BVec4,
        _ => return None,
    })
}

/// The columns and rows of a matrix type.
pub(super) fn matrix(t: &T) -> Option<(u8, u8)> {
    Some(match t {
        T::Mat2 | T::Mat22 => (2, 2),
        T::Mat3 | T::Mat33 => (3, 3),
        T::Mat4 | T::Mat44 => (4, 4),
        T::Mat23 => (2, 3),
        T::Mat24 => (2, 4),
        T::Mat32 => (3, 2),
        T::Mat34 => (3, 4),
        T::Mat42 => (4, 2),
        T::Mat43 => (4, 3),
        _ => return None,
    })
}

/// The matrix type of `columns` columns and `rows` rows.
fn mat(columns: u8, rows: u8) -> Option<T> {
    Some(match (columns, rows) {
        (2, 2) => T::Mat2,
        (3, 3) => T::Mat3,
        (4, 4) => T::Mat4,
        (2, 3) => T::Mat23,
        (2, 4) => T::Mat24,
        (3, 2) => T::Mat32,
        (3, 4) => T::Mat34,
        (4, 2) => T::Mat42,
        (4, 3) => T::Mat43,
        _ => return None,
    })
}

/// The length an array specifier of one dimension gives: `Some(None)` if it is no literal.
fn length(spec: Option<&ast::ArraySpecifier>) -> Option<Option<u32>> {
    let spec = spec?;
    Some(match spec.dimensions.as_slice() {
        [d] => match &d.content {
            ast::ArraySpecifierDimensionData::ExplicitlySized(e) => match e.content {
                ExprData::IntConst(n) if n > 0 => Some(n as u32),
                ExprData::UIntConst(n) if n > 0 => Some(n),
                _ => None,
            },
            ast::ArraySpecifierDimensionData::Unsized => None,
        },
        _ => None,
    })
}

/// The shape a declaration gives, with the array specifiers of its type and of its name.
fn declared(t: &ast::TypeSpecifier, name_spec: Option<&ast::ArraySpecifier>) -> Option<Shape> {
    let ty = match &t.ty.content {
        T::Struct(s) => T::TypeName(s.name.clone()?),
        T::TypeName(_) => t.ty.content.clone(),
        other => {
            scalar(other)?;
            other.clone()
        }
    };
    if t.array_specifier.is_some() && name_spec.is_some() {
        return None;
    }
    Some(Shape { ty, array: length(t.array_specifier.as_ref().or(name_spec)) })
}

/// Names with their shapes where certain (`None` where declared with different types), and
/// the order they were first declared in.
#[derive(Default, Clone)]
pub(super) struct Names(HashMap<String, Option<Shape>>, Vec<String>);

impl Names {
    fn declare(&mut self, name: &str, shape: Option<Shape>) {
        if !self.0.contains_key(name) {
            self.1.push(name.to_string());
        }
        self.0
            .entry(name.to_string())
            .and_modify(|t| *t = if *t == shape { shape.clone() } else { None })
            .or_insert(shape);
    }
}

/// Collects structures, blocks and the names of one scope: the globals, or one function's
/// parameters and locals.
#[derive(Default)]
struct Collect {
    members: HashMap<String, Option<Names>>,
    names: Names,
    /// Whether a function's own names are collected (else the globals).
    local: bool,
}

impl Collect {
    fn fields(fields: &[ast::StructFieldSpecifier]) -> Names {
        let mut names = Names::default();
        for f in fields {
            for id in &f.identifiers {
                names.declare(&id.ident.0, declared(&f.ty, id.array_spec.as_ref()));
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
                let ty = T::TypeName(ast::TypeNameData(b.name.0.clone()).into());
                self.names.declare(&id.ident.0, Some(Shape { ty, array: length(id.array_spec.as_ref()) }));
            }
            None => fields.0.into_iter().for_each(|(n, t)| self.names.declare(&n, t)),
        }
        Visit::Parent
    }

    fn visit_init_declarator_list(&mut self, list: &ast::InitDeclaratorList) -> Visit {
        let ty = &list.head.ty.ty;
        if let Some(n) = &list.head.name {
            self.names.declare(&n.0, declared(ty, list.head.array_specifier.as_ref()));
        }
        for t in &list.tail {
            self.names.declare(&t.ident.ident.0, declared(ty, t.ident.array_spec.as_ref()));
        }
        Visit::Children
    }

    fn visit_function_parameter_declarator(&mut self, d: &ast::FunctionParameterDeclarator) -> Visit {
        self.names.declare(&d.ident.ident.0, declared(&d.ty, d.ident.array_spec.as_ref()));
        Visit::Children
    }

    fn visit_function_definition(&mut self, _: &ast::FunctionDefinition) -> Visit {
        if self.local {
            Visit::Children
        } else {
            Visit::Parent
        }
    }

    fn visit_function_prototype(&mut self, _: &ast::FunctionPrototype) -> Visit {
        if self.local {
            Visit::Children
        } else {
            Visit::Parent
        }
    }
}

/// The built-in variables with a certain shape.
fn builtin(name: &str) -> Option<Shape> {
    Some(Shape::value(match name {
        "gl_Position" | "gl_FragCoord" | "gl_FragColor" => T::Vec4,
        "gl_PointCoord" => T::Vec2,
        "gl_PointSize" | "gl_FragDepth" => T::Float,
        "gl_VertexID" | "gl_InstanceID" => T::Int,
        "gl_FrontFacing" => T::Bool,
        n if n.starts_with("gl_Max") || n.starts_with("gl_Min") => T::Int,
        _ => return None,
    }))
}

/// The shapes of a translation unit's names: its globals, structures and functions.
pub(super) struct Scope {
    members: HashMap<String, Option<Names>>,
    /// The structures declared outside functions.
    global_structs: HashMap<String, Option<Names>>,
    globals: Names,
    /// Each user function's return shape, where all its overloads agree.
    functions: HashMap<String, Option<Shape>>,
    /// The names declared in the function being looked at, innermost scope last (none outside
    /// functions).
    frames: Vec<HashMap<String, Option<Shape>>>,
}

impl Scope {
    /// The globals, structures and functions of `tu`.
    pub(super) fn new(tu: &ast::TranslationUnit) -> Scope {
        let mut globals = Collect::default();
        tu.visit(&mut globals);
        let mut functions: HashMap<String, Option<Shape>> = HashMap::new();
        for decl in &tu.0 {
            let p = match &decl.content {
                ast::ExternalDeclarationData::FunctionDefinition(f) => &f.prototype,
                ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                    ast::DeclarationData::FunctionPrototype(p) => p,
                    _ => continue,
                },
                _ => continue,
            };
            let shape = declared(&p.ty.ty, None);
            functions
                .entry(p.name.0.to_string())
                .and_modify(|t| *t = if *t == shape { shape.clone() } else { None })
                .or_insert(shape);
        }
        Scope {
            global_structs: globals.members.clone(),
            members: globals.members,
            globals: globals.names,
            functions,
            frames: Vec::new(),
        }
    }

    /// Looks at function `f` next, its parameters declared (its structures are known
    /// throughout).
    pub(super) fn enter(&mut self, f: &ast::FunctionDefinition) {
        let mut local = Collect { local: true, ..Collect::default() };
        f.visit(&mut local);
        for (name, fields) in local.members {
            self.members.insert(name, fields);
        }
        self.frames = vec![HashMap::new()];
        for p in &f.prototype.parameters {
            if let ast::FunctionParameterDeclarationData::Named(_, d) = &p.content {
                self.declare(&d.ident.ident.0, declared(&d.ty, d.ident.array_spec.as_ref()));
            }
        }
    }

    /// Looks at the globals next (outside any function).
    pub(super) fn leave(&mut self) {
        self.frames.clear();
    }

    /// Opens a scope (a compound statement, a loop).
    pub(super) fn push(&mut self) {
        self.frames.push(HashMap::new());
    }

    /// Closes the innermost scope.
    pub(super) fn pop(&mut self) {
        self.frames.pop();
    }

    /// Declares `name` in the innermost scope.
    pub(super) fn declare(&mut self, name: &str, shape: Option<Shape>) {
        match self.frames.last_mut() {
            Some(frame) => {
                frame.insert(name.to_string(), shape);
            }
            None => self.globals.declare(name, shape),
        }
    }

    /// Declares the names of `list`.
    pub(super) fn declare_list(&mut self, list: &ast::InitDeclaratorList) {
        let ty = &list.head.ty.ty;
        if let Some(n) = &list.head.name {
            self.declare(&n.0, declared(ty, list.head.array_specifier.as_ref()));
        }
        for t in &list.tail {
            self.declare(&t.ident.ident.0, declared(ty, t.ident.array_spec.as_ref()));
        }
    }

    /// The shape of a declaration's type `ty` with a name's array specifier `spec`.
    pub(super) fn declared(ty: &ast::TypeSpecifier, spec: Option<&ast::ArraySpecifier>) -> Option<Shape> {
        declared(ty, spec)
    }

    /// The members of global structure `name`, in order, if all their shapes are certain.
    pub(super) fn fields(&self, name: &str) -> Option<Vec<(String, Shape)>> {
        let names = self.global_structs.get(name)?.as_ref()?;
        names.1.iter().map(|n| Some((n.clone(), names.0.get(n)?.clone()?))).collect()
    }

    /// The shape of `e`, if certain.
    pub(super) fn of(&self, e: &ast::Expr) -> Option<Shape> {
        let value = |t| Some(Shape::value(t));
        match &e.content {
            ExprData::IntConst(_) => value(T::Int),
            ExprData::UIntConst(_) => value(T::UInt),
            ExprData::FloatConst(_) => value(T::Float),
            ExprData::BoolConst(_) => value(T::Bool),
            ExprData::DoubleConst(_) => None,
            ExprData::Variable(id) => {
                let name = id.0.as_str();
                match self.frames.iter().rev().find_map(|f| f.get(name)).or_else(|| self.globals.0.get(name)) {
                    Some(t) => t.clone(),
                    None => builtin(name),
                }
            }
            ExprData::Unary(op, a) => match op.content {
                U::Not => value(T::Bool),
                _ => self.of(a),
            },
            ExprData::PostInc(a) | ExprData::PostDec(a) => self.of(a),
            ExprData::Comma(_, b) => self.of(b),
            ExprData::Assignment(a, _, _) => self.of(a),
            ExprData::Ternary(_, a, b) => self.of(a).or_else(|| self.of(b)),
            ExprData::Binary(op, a, b) => self.binary(&op.content, a, b),
            ExprData::Bracket(a, _) => {
                let s = self.of(a)?;
                match s.array {
                    Some(_) => value(s.ty),
                    None => match matrix(&s.ty) {
                        Some((_, rows)) => value(vector(&T::Float, rows)?),
                        None => value(scalar(&s.ty).filter(|_| size(&s.ty).is_some_and(|n| n > 1))?),
                    },
                }
            }
            ExprData::Dot(a, field) => {
                let s = self.of(a)?;
                match (&s.ty, s.array) {
                    (T::TypeName(n), None) => {
                        self.members.get(n.0.as_str())?.as_ref()?.0.get(field.0.as_str())?.clone()
                    }
                    (t, None) => value(vector(&scalar(t).filter(|_| size(t).is_some())?, field.0.len() as u8)?),
                    _ => None,
                }
            }
            ExprData::FunCall(f, args) => match &f.content {
                FunIdentifierData::TypeSpecifier(ts) => {
                    let mut s = declared(ts, None)?;
                    if s.array == Some(None)
                        && matches!(ts.array_specifier.as_ref().map(|a| a.dimensions.as_slice()), Some([d]) if matches!(d.content, ast::ArraySpecifierDimensionData::Unsized))
                    {
                        s.array = Some(Some(args.len() as u32));
                    }
                    Some(s)
                }
                FunIdentifierData::Expr(callee) => match &callee.content {
                    ExprData::Dot(_, m) if m.0 == "length" && args.is_empty() => value(T::Int),
                    ExprData::Variable(name) => match self.functions.get(name.0.as_str()) {
                        Some(s) => s.clone(),
                        None => self.built_in(&name.0, args),
                    },
                    _ => None,
                },
            },
        }
    }

    fn binary(&self, op: &B, a: &ast::Expr, b: &ast::Expr) -> Option<Shape> {
        if matches!(op, B::Lt | B::Gt | B::Lte | B::Gte | B::Equal | B::NonEqual | B::Or | B::Xor | B::And) {
            return Some(Shape::value(T::Bool));
        }
        let (sa, sb) = (self.of(a)?, self.of(b));
        if matches!(op, B::LShift | B::RShift) {
            return Some(sa);
        }
        let sb = sb?;
        if sa.array.is_some() || sb.array.is_some() {
            return None;
        }
        if *op == B::Mult {
            match (matrix(&sa.ty), matrix(&sb.ty), size(&sa.ty), size(&sb.ty)) {
                (Some((_, r)), Some((k, _)), _, _) => return Some(Shape::value(mat(k, r)?)),
                (Some((_, r)), None, _, Some(n)) if n > 1 => return Some(Shape::value(vector(&T::Float, r)?)),
                (None, Some((c, _)), Some(n), _) if n > 1 => return Some(Shape::value(vector(&T::Float, c)?)),
                _ => {}
            }
        }
        // A scalar with a vector or matrix is the vector or matrix.
        Some(if size(&sa.ty) == Some(1) { sb } else { sa })
    }

    /// The shape of built-in function `name`'s result with these arguments.
    fn built_in(&self, name: &str, args: &[ast::Expr]) -> Option<Shape> {
        let arg = |k: usize| args.get(k).and_then(|a| self.of(a)).filter(|s| s.array.is_none());
        let sized = |s: T| Some(Shape::value(vector(&s, arg(0)?.size()?)?));
        match name {
            "step" | "smoothstep" => arg(args.len().checked_sub(1)?),
            "length" | "distance" | "dot" | "determinant" => Some(Shape::value(T::Float)),
            "cross" => Some(Shape::value(T::Vec3)),
            "any" | "all" => Some(Shape::value(T::Bool)),
            "lessThan" | "lessThanEqual" | "greaterThan" | "greaterThanEqual" | "equal" | "notEqual" | "isnan"
            | "isinf" => sized(T::Bool),
            "floatBitsToInt" => sized(T::Int),
            "floatBitsToUint" => sized(T::UInt),
            "intBitsToFloat" | "uintBitsToFloat" => sized(T::Float),
            "packSnorm2x16" | "packUnorm2x16" | "packHalf2x16" => Some(Shape::value(T::UInt)),
            "unpackSnorm2x16" | "unpackUnorm2x16" | "unpackHalf2x16" => Some(Shape::value(T::Vec2)),
            "transpose" => {
                let (c, r) = matrix(&arg(0)?.ty)?;
                Some(Shape::value(mat(r, c)?))
            }
            "outerProduct" => Some(Shape::value(mat(arg(1)?.size()?, arg(0)?.size()?)?)),
            "radians" | "degrees" | "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "sinh" | "cosh" | "tanh"
            | "asinh" | "acosh" | "atanh" | "pow" | "exp" | "log" | "exp2" | "log2" | "sqrt" | "inversesqrt"
            | "abs" | "sign" | "floor" | "trunc" | "round" | "roundEven" | "ceil" | "fract" | "mod" | "modf"
            | "min" | "max" | "clamp" | "mix" | "normalize" | "faceforward" | "reflect" | "refract" | "dFdx"
            | "dFdy" | "fwidth" | "not" | "inverse" | "matrixCompMult" => arg(0),
            _ => None,
        }
    }
}

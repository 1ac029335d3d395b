//! Uniform block members that naga cannot read by std140 as they are declared (the trap ANGLE's
//! `OutputUniformBlocks` also works around): booleans, stored as ints; matrices of two rows,
//! whose columns std140 places 16 bytes apart, stored as one `vec4` per column; and row-major
//! matrices, stored as their column-major transpose. The block declares each member as it is
//! stored ([`declaration`]), and every read of one in the shader's code becomes the value it
//! stands for ([`rewrite`]): `bool(m)`, `mat3x2(m[0].xy, m[1].xy, m[2].xy)`, `transpose(m)`.

use std::collections::{HashMap, HashSet};

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T};
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};

use crate::glsl::structs::ident;
use crate::glsl::types::{Block, BlockMember, Scalar, Ty};

/// The column-major matrix holding the same numbers as `ty` read row by row.
fn transposed(ty: Ty) -> Ty {
    match ty {
        Ty::Mat2x3 => Ty::Mat3x2,
        Ty::Mat3x2 => Ty::Mat2x3,
        Ty::Mat2x4 => Ty::Mat4x2,
        Ty::Mat4x2 => Ty::Mat2x4,
        Ty::Mat3x4 => Ty::Mat4x3,
        Ty::Mat4x3 => Ty::Mat3x4,
        t => t,
    }
}

/// The matrix type a member is stored as: its own, or its transpose where row-major (lift
/// marks only matrices so).
pub(super) fn storage(m: &BlockMember) -> Ty {
    if m.row_major {
        transposed(m.ty)
    } else {
        m.ty
    }
}

/// How a member is stored, where not as declared: its stored name.
fn stored_name(m: &BlockMember) -> Option<String> {
    let s = storage(m);
    let name = ident(&m.name);
    if m.ty.scalar() == Scalar::Bool {
        Some(format!("strata_b_{name}"))
    } else if s.rows() == 2 {
        Some(format!("strata_m2_{name}"))
    } else if m.row_major {
        Some(format!("strata_t_{name}"))
    } else {
        None
    }
}

/// The line declaring `m` in its block, as it is stored.
pub(super) fn declaration(m: &BlockMember) -> String {
    let s = storage(m);
    let len = m.array.unwrap_or(1);
    let array = m.array.map_or(String::new(), |n| format!("[{n}]"));
    match stored_name(m) {
        // std140 places each of a matrix's columns (of an array: each matrix's) 16 bytes on.
        Some(name) if s.rows() == 2 && m.ty.scalar() != Scalar::Bool => {
            format!("vec4 {name}[{}];", s.columns() as u32 * len)
        }
        Some(name) => format!("{} {name}{array};", s.glsl(true)),
        None => format!("{} {}{array};", m.ty.glsl(true), ident(&m.name)),
    }
}

/// The type specifier of a matrix or boolean type, for a constructor.
fn spec(ty: Ty) -> T {
    match ty {
        Ty::Mat2 => T::Mat2,
        Ty::Mat3 => T::Mat3,
        Ty::Mat4 => T::Mat4,
        Ty::Mat2x3 => T::Mat23,
        Ty::Mat2x4 => T::Mat24,
        Ty::Mat3x2 => T::Mat32,
        Ty::Mat3x4 => T::Mat34,
        Ty::Mat4x2 => T::Mat42,
        Ty::Mat4x3 => T::Mat43,
        Ty::BVec2 => T::BVec2,
        Ty::BVec3 => T::BVec3,
        Ty::BVec4 => T::BVec4,
        _ => T::Bool,
    }
}

/// A constructor call of type `ty`.
pub(super) fn ctor(ty: T, args: Vec<ast::Expr>) -> ast::Expr {
    let spec: ast::TypeSpecifier = ast::TypeSpecifierData { ty: ty.into(), array_specifier: None }.into();
    ExprData::FunCall(FunIdentifierData::TypeSpecifier(Box::new(spec)).into(), args).into()
}

fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

fn call(f: FunIdentifierData, args: Vec<ast::Expr>) -> ast::Expr {
    ExprData::FunCall(f.into(), args).into()
}

fn binary(op: ast::BinaryOpData, a: ast::Expr, b: ast::Expr) -> ast::Expr {
    ExprData::Binary(op.into(), Box::new(a), Box::new(b)).into()
}

/// `ty(columns[i].xy, …, columns[i + C - 1].xy)`, `i` being `C * index` (or 0): a `matCx2` read
/// from the `vec4` per column it is stored as.
pub(super) fn two_rows(columns: ast::Expr, ty: Ty, index: Option<&ast::Expr>) -> ast::Expr {
    let c = ty.columns() as i32;
    let column = |k: i32| -> ast::Expr {
        let i = match index {
            Some(idx) => binary(
                ast::BinaryOpData::Add,
                binary(ast::BinaryOpData::Mult, ExprData::IntConst(c).into(), idx.clone()),
                ExprData::IntConst(k).into(),
            ),
            None => ExprData::IntConst(k).into(),
        };
        let elem: ast::Expr = ExprData::Bracket(Box::new(columns.clone()), Box::new(i)).into();
        ExprData::Dot(Box::new(elem), ast::IdentifierData("xy".into()).into()).into()
    };
    ctor(spec(ty), (0..c).map(column).collect())
}

/// The value of `m` (element `index` of an array) read from `stored`, what it is stored as.
fn value(m: &BlockMember, stored: ast::Expr, index: Option<&ast::Expr>) -> ast::Expr {
    let s = storage(m);
    let element = |e: ast::Expr| match index {
        Some(i) => ExprData::Bracket(Box::new(e), Box::new(i.clone())).into(),
        None => e,
    };
    if m.ty.scalar() == Scalar::Bool {
        return ctor(spec(m.ty), vec![element(stored)]);
    }
    let read = if s.rows() == 2 { two_rows(stored, s, index) } else { element(stored) };
    if m.row_major {
        call(FunIdentifierData::Expr(Box::new(var("transpose"))), vec![read])
    } else {
        read
    }
}

/// Where a member stored otherwise is read from: bare (a block without an instance name) or
/// through its block's instance.
#[derive(Clone)]
struct Special {
    member: BlockMember,
    stored: String,
}

/// Rewrites the reads of `blocks`' specially stored members in `body`.
pub(super) fn rewrite(body: &mut ast::TranslationUnit, blocks: &[Block]) -> Result<(), String> {
    let mut bare = HashMap::new();
    let mut through: HashMap<(String, String), Special> = HashMap::new();
    for b in blocks {
        for m in &b.members {
            let Some(stored) = stored_name(m) else { continue };
            let special = Special { member: m.clone(), stored };
            match &b.instance {
                Some(i) => through.insert((i.clone(), ident(&m.name)), special),
                None => bare.insert(ident(&m.name), special),
            };
        }
    }
    if bare.is_empty() && through.is_empty() {
        return Ok(());
    }
    let mut r = Reads { bare, through, error: None, shadow: HashSet::new() };
    body.visit_mut(&mut r);
    r.error.map_or(Ok(()), Err)
}

struct Reads {
    bare: HashMap<String, Special>,
    through: HashMap<(String, String), Special>,
    error: Option<String>,
    /// The names the function visited declares, which hide the block's members of theirs.
    shadow: HashSet<String>,
}

impl Reads {
    /// The member `e` names, with the expression of its storage.
    fn special(&self, e: &ast::Expr) -> Option<(Special, ast::Expr)> {
        match &e.content {
            ExprData::Variable(id) if self.shadow.contains(id.0.as_str()) => None,
            ExprData::Variable(id) => self.bare.get(id.0.as_str()).map(|s| (s.clone(), var(&s.stored))),
            ExprData::Dot(base, field) => match &base.content {
                ExprData::Variable(inst) if self.shadow.contains(inst.0.as_str()) => None,
                ExprData::Variable(inst) => {
                    let s = self.through.get(&(inst.0.to_string(), field.0.to_string()))?;
                    let stored = ExprData::Dot(base.clone(), ast::IdentifierData(s.stored.as_str().into()).into());
                    Some((s.clone(), stored.into()))
                }
                _ => None,
            },
            _ => None,
        }
    }
}

impl VisitorMut for Reads {
    fn visit_external_declaration(&mut self, _: &mut ast::ExternalDeclaration) -> Visit {
        self.shadow.clear();
        Visit::Children
    }

    fn visit_function_definition(&mut self, f: &mut ast::FunctionDefinition) -> Visit {
        self.shadow = crate::glsl::structs::locals(f);
        Visit::Children
    }

    fn visit_expr(&mut self, e: &mut ast::Expr) -> Visit {
        if let ExprData::Bracket(base, index) = &mut e.content {
            if let Some((s, stored)) = self.special(base).filter(|(s, _)| s.member.array.is_some()) {
                index.visit_mut(self);
                let index = (**index).clone();
                *e = value(&s.member, stored, Some(&index));
                return Visit::Parent;
            }
        }
        if let Some((s, stored)) = self.special(e) {
            if s.member.array.is_some() {
                let msg = format!("0: the uniform block member array `{}' may only be read by element", s.member.name);
                self.error.get_or_insert(msg);
                return Visit::Parent;
            }
            *e = value(&s.member, stored, None);
            return Visit::Parent;
        }
        Visit::Children
    }
}

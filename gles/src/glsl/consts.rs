//! Constant folding of integral constant expressions (GLSL ES 1.00 §4.3.3), as array sizes
//! need: literals, `const` globals, the built-in constants (with the values Strata reports
//! through `glGetIntegerv`), arithmetic, comparisons, logic, `?:` and the comma operator; and
//! the array lengths of declarations, which are such expressions.

use std::collections::HashMap;

use glsl_lang::ast::{self, BinaryOpData as B, ExprData, UnaryOpData as U};

use crate::limits::{MAX_ATTRIBS, MAX_DRAW_BUFFERS, MAX_STAGE_UNITS, MAX_UNITS};

/// A folded constant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Val {
    /// An `int`.
    Int(i64),
    /// A `bool`.
    Bool(bool),
    /// A `float`.
    Float(f64),
}

/// The built-in constants of GLSL ES 1.00 §7.4, as Strata reports the matching limits.
pub(super) fn builtin(name: &str) -> Option<i64> {
    Some(match name {
        "gl_MaxVertexAttribs" => MAX_ATTRIBS as i64,
        "gl_MaxVertexUniformVectors" | "gl_MaxFragmentUniformVectors" => 256,
        "gl_MaxVaryingVectors" => 15,
        "gl_MaxVertexTextureImageUnits" | "gl_MaxTextureImageUnits" => MAX_STAGE_UNITS as i64,
        "gl_MaxCombinedTextureImageUnits" => MAX_UNITS as i64,
        "gl_MaxDrawBuffers" => MAX_DRAW_BUFFERS as i64,
        "gl_MaxDualSourceDrawBuffersEXT" => 1,
        _ => return None,
    })
}

/// The built-in constants GLSL ES 3.00 §7.3 adds to those of 1.00 (the specification's
/// minimums, which Strata's limits meet: texel offsets are WGSL's −8…7).
const ES3_CONSTANTS: [(&str, i64); 4] = [
    ("gl_MaxVertexOutputVectors", 16),
    ("gl_MaxFragmentInputVectors", 15),
    ("gl_MinProgramTexelOffset", -8),
    ("gl_MaxProgramTexelOffset", 7),
];

/// One of [`ES3_CONSTANTS`] by name.
pub(super) fn builtin_es3(name: &str) -> Option<i64> {
    ES3_CONSTANTS.iter().find(|(n, _)| *n == name).map(|(_, v)| *v)
}

/// The constants a shader of `version` starts with: GLSL ES 3.00's own built-in ones.
pub(super) fn seeded(version: u16) -> HashMap<String, Val> {
    match version {
        300 => ES3_CONSTANTS.iter().map(|(n, v)| (n.to_string(), Val::Int(*v))).collect(),
        _ => HashMap::new(),
    }
}

/// Folds `e`; `None` if it is not a constant expression this folder understands.
pub(super) fn fold(e: &ast::Expr, consts: &HashMap<String, Val>) -> Option<Val> {
    Some(match &e.content {
        ExprData::IntConst(n) => Val::Int(i64::from(*n)),
        ExprData::UIntConst(n) => Val::Int(i64::from(*n)),
        ExprData::BoolConst(b) => Val::Bool(*b),
        ExprData::FloatConst(f) => Val::Float(f64::from(*f)),
        ExprData::Variable(id) => match consts.get(id.0.as_str()) {
            Some(v) => *v,
            None => Val::Int(builtin(id.0.as_str())?),
        },
        ExprData::Comma(a, b) => {
            fold(a, consts)?;
            fold(b, consts)?
        }
        ExprData::Ternary(c, a, b) => match fold(c, consts)? {
            Val::Bool(true) => fold(a, consts)?,
            Val::Bool(false) => fold(b, consts)?,
            _ => return None,
        },
        ExprData::Unary(op, a) => match (&op.content, fold(a, consts)?) {
            (U::Minus, Val::Int(n)) => Val::Int(n.checked_neg()?),
            (U::Minus, Val::Float(f)) => Val::Float(-f),
            (U::Add, v) => v,
            (U::Not, Val::Bool(b)) => Val::Bool(!b),
            _ => return None,
        },
        ExprData::Binary(op, a, b) => binary(&op.content, fold(a, consts)?, fold(b, consts)?)?,
        // An array's `length()`, where the array's size is known (`NAME.length()` in `consts`).
        ExprData::FunCall(f, args) if args.is_empty() => match &f.content {
            ast::FunIdentifierData::Expr(callee) => match &callee.content {
                ExprData::Dot(base, field) if field.0 == "length" => match &base.content {
                    ExprData::Variable(id) => *consts.get(&format!("{}.length()", id.0))?,
                    _ => return None,
                },
                _ => return None,
            },
            _ => return None,
        },
        _ => return None,
    })
}

fn binary(op: &B, a: Val, b: Val) -> Option<Val> {
    Some(match (a, b) {
        (Val::Int(x), Val::Int(y)) => match op {
            B::Add => Val::Int(x.checked_add(y)?),
            B::Sub => Val::Int(x.checked_sub(y)?),
            B::Mult => Val::Int(x.checked_mul(y)?),
            B::Div => Val::Int(x.checked_div(y)?),
            B::Equal => Val::Bool(x == y),
            B::NonEqual => Val::Bool(x != y),
            B::Lt => Val::Bool(x < y),
            B::Gt => Val::Bool(x > y),
            B::Lte => Val::Bool(x <= y),
            B::Gte => Val::Bool(x >= y),
            _ => return None,
        },
        (Val::Float(x), Val::Float(y)) => match op {
            B::Add => Val::Float(x + y),
            B::Sub => Val::Float(x - y),
            B::Mult => Val::Float(x * y),
            B::Div => Val::Float(x / y),
            B::Equal => Val::Bool(x == y),
            B::NonEqual => Val::Bool(x != y),
            B::Lt => Val::Bool(x < y),
            B::Gt => Val::Bool(x > y),
            B::Lte => Val::Bool(x <= y),
            B::Gte => Val::Bool(x >= y),
            _ => return None,
        },
        (Val::Bool(x), Val::Bool(y)) => match op {
            B::And => Val::Bool(x && y),
            B::Or => Val::Bool(x || y),
            B::Xor => Val::Bool(x ^ y),
            B::Equal => Val::Bool(x == y),
            B::NonEqual => Val::Bool(x != y),
            _ => return None,
        },
        _ => return None,
    })
}

/// The length of an interface variable's array specifier, `None` if it is no array.
pub(super) fn array_len(
    spec: Option<&ast::ArraySpecifier>,
    consts: &HashMap<String, Val>,
) -> Result<Option<u32>, String> {
    let Some(spec) = spec else { return Ok(None) };
    match spec.dimensions.as_slice() {
        [d] => match &d.content {
            ast::ArraySpecifierDimensionData::ExplicitlySized(e) => match fold(e, consts) {
                // Uniform arrays are bounded by the block at link (with a log naming them),
                // varyings below; the size only has to be a positive int.
                Some(Val::Int(n)) if n > 0 && n <= i64::from(i32::MAX) => Ok(Some(n as u32)),
                Some(Val::Int(_)) => Err("0: array size must be greater than zero".into()),
                _ => Err("0: array size must be a constant valued expression".into()),
            },
            ast::ArraySpecifierDimensionData::Unsized => Err("unsized arrays are not allowed".into()),
        },
        _ => Err("arrays of arrays are not allowed in GLSL ES 1.00".into()),
    }
}

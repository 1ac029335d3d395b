//! Built-in functions naga's GLSL front end lacks, each replaced by a generated function of the
//! same overloads that computes what the specification defines: `modf` (GLSL ES 3.00 §8.3) and
//! `matrixCompMult` (GLSL ES 1.00 §8.5, and for every matrix shape in 3.00 §8.6); and
//! `texelFetchOffset`, whose offset naga drops, as `texelFetch` of the offset coordinate.

use std::fmt::Write as _;

/// The name of the generated function that stands in for built-in `name`, if naga lacks it
/// (`es3`: the shader is GLSL ES 3.00, which has `modf`).
pub(super) fn stand_in(name: &str, es3: bool) -> Option<&'static str> {
    match name {
        "modf" if es3 => Some("strata_modf"),
        "matrixCompMult" => Some("strata_matrixCompMult"),
        _ => None,
    }
}

/// The definitions of the stand-ins named in `used`.
pub(super) fn definitions(used: &std::collections::BTreeSet<&'static str>) -> String {
    let mut out = String::new();
    if used.contains("strata_modf") {
        // The integer part goes out, the fractional part comes back, each with x's sign.
        for ty in ["float", "vec2", "vec3", "vec4"] {
            let _ = writeln!(out, "{ty} strata_modf({ty} x, out {ty} i) {{ i = trunc(x); return x - i; }}");
        }
    }
    if used.contains("strata_matrixCompMult") {
        for columns in 2..=4 {
            for rows in 2..=4 {
                let ty = if columns == rows { format!("mat{columns}") } else { format!("mat{columns}x{rows}") };
                let products: Vec<String> = (0..columns).map(|c| format!("a[{c}] * b[{c}]")).collect();
                let _ = writeln!(
                    out,
                    "{ty} strata_matrixCompMult({ty} a, {ty} b) {{ return {ty}({}); }}",
                    products.join(", ")
                );
            }
        }
    }
    out
}

/// Makes a call of `texelFetchOffset(sampler, P, lod, offset)` one of `texelFetch(sampler,
/// P + offset, lod)` (a 2D array's offset has no layer part): naga's front end drops the
/// offset. `samplers` gives the sampler's type.
pub(super) fn fetch_offset(
    fun: &mut glsl_lang::ast::FunIdentifier,
    args: &mut Vec<glsl_lang::ast::Expr>,
    samplers: &std::collections::HashMap<String, crate::glsl::types::Ty>,
) {
    use glsl_lang::ast::{self, ExprData, FunIdentifierData};
    let FunIdentifierData::Expr(f) = &mut fun.content else { return };
    let ExprData::Variable(id) = &mut f.content else { return };
    if id.0 != "texelFetchOffset" || args.len() != 4 {
        return;
    }
    let array = match &args[0].content {
        ExprData::Variable(v) => {
            samplers.get(v.0.as_str()).is_some_and(|t| t.sampler_base() == crate::glsl::types::Ty::Sampler2DArray)
        }
        _ => false,
    };
    let Some(offset) = args.pop() else { return };
    let offset = match array {
        true => crate::glsl::block_members::ctor(
            ast::TypeSpecifierNonArrayData::IVec3,
            vec![offset, ExprData::IntConst(0).into()],
        ),
        false => offset,
    };
    let coordinate = std::mem::replace(&mut args[1], ExprData::IntConst(0).into());
    args[1] = ExprData::Binary(ast::BinaryOpData::Add.into(), Box::new(coordinate), Box::new(offset)).into();
    *id = ast::IdentifierData("texelFetch".into()).into();
}

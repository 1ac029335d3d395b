//! Built-in functions naga's GLSL front end lacks, each replaced by a generated function of the
//! same overloads that computes what the specification defines: `modf` (GLSL ES 3.00 §8.3),
//! `matrixCompMult` (GLSL ES 1.00 §8.5, and for every matrix shape in 3.00 §8.6) and
//! `outerProduct` (3.00 §8.6: naga gives a non-square product the transposed shape), and the
//! geometric functions of scalars (§8.4: `dot`, `normalize`, `faceforward`, `reflect` and
//! `refract` of `float`s, which naga takes only as vectors); and `texelFetchOffset`, whose
//! offset naga drops, as `texelFetch` of the offset coordinate.

use std::fmt::Write as _;

/// The name of the generated function that stands in for built-in `name`, if naga lacks it
/// (`es3`: the shader is GLSL ES 3.00, which has `modf`).
pub(super) fn stand_in(name: &str, es3: bool) -> Option<&'static str> {
    match name {
        "modf" if es3 => Some("strata_modf"),
        "matrixCompMult" => Some("strata_matrixCompMult"),
        "outerProduct" if es3 => Some("strata_outerProduct"),
        "dot" => Some("strata_dot"),
        "normalize" => Some("strata_normalize"),
        "faceforward" => Some("strata_faceforward"),
        "reflect" => Some("strata_reflect"),
        "refract" => Some("strata_refract"),
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
    // The scalar forms, as §8.4 defines them with dot(x, y) = x * y; the vector forms forward.
    let geometric = [
        ("strata_dot", "float", "a, {t} b", "a * b", "dot(a, b)"),
        ("strata_normalize", "{t}", "a", "sign(a)", "normalize(a)"),
        ("strata_faceforward", "{t}", "n, {t} i, {t} r", "r * i < 0.0 ? n : -n", "faceforward(n, i, r)"),
        ("strata_reflect", "{t}", "i, {t} n", "i - 2.0 * n * i * n", "reflect(i, n)"),
        (
            "strata_refract",
            "{t}",
            "i, {t} n, float e",
            "1.0 - e * e * (1.0 - n * i * n * i) < 0.0 ? 0.0 : e * i - (e * n * i + sqrt(1.0 - e * e * (1.0 - n * i * n * i))) * n",
            "refract(i, n, e)",
        ),
    ];
    for (name, returns, params, scalar, vector) in geometric {
        if used.contains(name) {
            for t in ["float", "vec2", "vec3", "vec4"] {
                let body = if t == "float" { scalar } else { vector };
                let (returns, params) = (returns.replace("{t}", t), params.replace("{t}", t));
                let _ = writeln!(out, "{returns} {name}({t} {params}) {{ return {body}; }}");
            }
        }
    }
    if used.contains("strata_outerProduct") {
        // Column `k` of `c` times `r`'s transpose is `c` scaled by `r[k]`.
        for columns in 2..=4 {
            for rows in 2..=4 {
                let ty = if columns == rows { format!("mat{columns}") } else { format!("mat{columns}x{rows}") };
                let scaled: Vec<String> = (0..columns).map(|k| format!("c * r[{k}]")).collect();
                let _ = writeln!(
                    out,
                    "{ty} strata_outerProduct(vec{rows} c, vec{columns} r) {{ return {ty}({}); }}",
                    scaled.join(", ")
                );
            }
        }
    }
    out
}

/// Makes the layer of a lookup on a float 2D array (`texture`, `textureLod`, `textureGrad` and
/// their offset forms) the one GL chooses, `floor(layer + 0.5)` (`strata_layer`, in
/// `link::WRAP_FNS`): naga makes the layer an integer by truncation. `samplers` gives the
/// sampler's type.
pub(super) fn array_layer(
    fun: &glsl_lang::ast::FunIdentifier,
    args: &mut [glsl_lang::ast::Expr],
    samplers: &std::collections::HashMap<String, crate::glsl::types::Ty>,
) {
    use glsl_lang::ast::{ExprData, FunIdentifierData};
    let FunIdentifierData::Expr(f) = &fun.content else { return };
    let ExprData::Variable(id) = &f.content else { return };
    let lookup = matches!(
        id.0.as_str(),
        "texture" | "textureOffset" | "textureLod" | "textureLodOffset" | "textureGrad" | "textureGradOffset"
    );
    let array = match args.first().map(|a| &a.content) {
        Some(ExprData::Variable(v)) => samplers.get(v.0.as_str()) == Some(&crate::glsl::types::Ty::Sampler2DArray),
        _ => false,
    };
    if !lookup || !array || args.len() < 2 {
        return;
    }
    let coordinate = std::mem::replace(&mut args[1], ExprData::IntConst(0).into());
    let name = ExprData::Variable(glsl_lang::ast::IdentifierData("strata_layer".into()).into());
    let call = FunIdentifierData::Expr(Box::new(name.into()));
    args[1] = ExprData::FunCall(call.into(), vec![coordinate]).into();
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

/// Gives the body of an `if`, `else`, `while`, `do` or `for` that is a declaration its own
/// block: what it declares is scoped to it (GLSL ES 3.00 §6.3), which a bare declaration
/// printed after the condition would not be.
pub(super) fn scope_bodies(s: &mut glsl_lang::ast::Statement) {
    use glsl_lang::ast::{self, IterationStatementData as I, SelectionRestStatementData as R, StatementData as S};
    let wrap = |b: &mut Box<ast::Statement>| {
        if matches!(b.content, S::Declaration(_)) {
            let inner = std::mem::replace(&mut **b, S::Expression(ast::ExprStatementData(None).into()).into());
            **b = S::Compound(ast::CompoundStatementData { statement_list: vec![inner] }.into()).into();
        }
    };
    match &mut s.content {
        S::Selection(sel) => match &mut sel.rest.content {
            R::Statement(b) => wrap(b),
            R::Else(a, b) => {
                wrap(a);
                wrap(b);
            }
        },
        S::Iteration(it) => match &mut it.content {
            I::While(_, b) | I::DoWhile(b, _) | I::For(_, _, b) => wrap(b),
        },
        _ => {}
    }
}

//! Built-in functions naga's GLSL front end lacks, each replaced by a generated function of the
//! same overloads that computes what the specification defines: `modf` (GLSL ES 3.00 §8.3),
//! `matrixCompMult` (GLSL ES 1.00 §8.5, and for every matrix shape in 3.00 §8.6) and
//! `outerProduct` (3.00 §8.6: naga gives a non-square product the transposed shape), and the
//! geometric functions of scalars (§8.4: `dot`, `normalize`, `faceforward`, `reflect` and
//! `refract` of `float`s, which naga takes only as vectors).

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

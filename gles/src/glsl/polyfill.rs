//! Built-in functions naga's GLSL front end lacks, each replaced by a generated function of the
//! same overloads that computes what the specification defines: `modf` (GLSL ES 3.00 §8.3) and
//! `matrixCompMult` (GLSL ES 1.00 §8.5, and for every matrix shape in 3.00 §8.6).

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

//! Expressions whose translation depends on their operands' shapes (`operators`, `shapes`), the
//! stand-ins of `polyfill`, and the generated text around operators.

use std::collections::HashMap;

use super::*;

/// A GLSL ES 3.00 fragment shader whose `main` runs `body` (with an `int k` uniform and an
/// output `o`), after `globals`.
fn fs(globals: &str, body: &str) -> String {
    format!(
        "#version 300 es\nprecision highp float;\nprecision highp int;\nuniform int k;\nout vec4 o;\n{globals}\nvoid main() {{\n{body}\n}}"
    )
}

fn compiles(globals: &str, body: &str) {
    let src = fs(globals, body);
    if let Err(e) = compile(Stage::Fragment, &src) {
        panic!("{e}\n{src}");
    }
}

#[test]
fn arrays_and_structures_compare() {
    compiles(
        "struct S { int a; vec2 b; bvec3 c; };\nstruct N { S s; mat3 m; float f[2]; };",
        "int x[3] = int[3](k, 2, 3); int y[3] = x; vec2 v[2]; mat2 m[2]; mat2 n[2]; S s[2]; S t[2]; N a; N b;
        int z = 0;
        bool r = x == y && !(x != int[3](z++, 2, 3)) && v == vec2[2](vec2(1.0), vec2(k));
        r = r && m != n && s == t && s[0] != t[1] && a == b && a.s != b.s;
        { float x = 1.0; r = r && x == 1.0; }
        o = vec4(r);",
    );
    // Each distinct type compared gets one function, placed before its first use.
    compiles(
        "int f(int a[2], int b[2]) { return a == b ? 1 : 0; }",
        "int p[2]; int q[2]; o = vec4(f(p, q), p == q, 0, 1);",
    );
}

#[test]
fn arrays_of_unknown_size_are_refused_with_the_line() {
    let src = fs("const int N = 2;", "int a[N];\nint b[N];\no = vec4(a == b);");
    let e = compile(Stage::Fragment, &src).expect_err("no literal size");
    assert!(e.starts_with("0:10("), "{e}");
    assert!(e.contains("not supported"), "{e}");
}

#[test]
fn vector_and_scalar_operands_mix() {
    compiles(
        "",
        "ivec4 v = ivec4(k); uvec3 u = uvec3(k); ivec2 w = ivec2(k);
        v = v % k; v = k % v; v %= 3; u = u % 5u; u = 7u % u; u %= 2u; w = (w << 2) & 0xff | k ^ w;
        v <<= 1; v >>= k; v &= k; v |= 1; v ^= k; u = u << 1u; u >>= 2;
        o = vec4(v) + vec4(u, 1.0) + vec4(w, 0, 0);",
    );
}

#[test]
fn unsigned_values_negate() {
    compiles(
        "",
        "uint u = uint(k); uvec2 w = uvec2(u); u = -u; w = -w + -uvec2(1u); o = vec4(float(u), vec2(w), 1.0);",
    );
}

#[test]
fn booleans_convert_to_numbers_of_any_size() {
    compiles(
        "",
        "bvec3 b = bvec3(k); bool c = k > 1; int i = int(b); ivec2 i2 = ivec2(c); mat2 m = mat2(c);
        mat3x4 n = mat3x4(b.x); uvec2 u = uvec2(b); float f = float(bvec2(b)); uint w = uint(bvec4(c));
        o = vec4(float(i), vec2(i2), f) + m[0].xyxy + n[1] + vec4(u, w, 1);",
    );
}

#[test]
fn outer_products_have_the_specified_shape() {
    compiles("", "mat4x3 m = outerProduct(vec3(1.0), vec4(2.0)); mat2x4 n = outerProduct(vec4(1.0), vec2(k)); o = vec4(m[3], n[1][3]);");
    // Mesa's shape: as many rows as the first vector has components.
    let wrong = fs("", "mat3x4 m = outerProduct(vec3(1.0), vec4(2.0)); o = m[0];");
    assert!(compile(Stage::Fragment, &wrong).is_err());
}

#[test]
fn geometric_functions_take_scalars() {
    compiles(
        "",
        "float x = float(k); o = vec4(dot(x, x), normalize(x), reflect(x, 1.0), refract(x, 1.0, 0.5));
        o += vec4(faceforward(x, x, x), dot(vec2(x), vec2(1.0)), normalize(vec3(x)).x, reflect(vec4(x), vec4(1.0)).y);",
    );
}

#[test]
fn negative_operands_keep_their_minus() {
    compiles(
        "const float a = (float(-5.25)) - -5.5;\nint c = int(-4 - -4);",
        "int d = k - -4; o = vec4(a, float(d) - -a, float(c), float(-gl_MinProgramTexelOffset));",
    );
}

#[test]
fn constants_made_of_hoisted_constants_are_hoisted_too() {
    compiles("const float d = sin(0.5) + 1.0;\nconst vec4 b = vec4(d);\nconst vec4 e = b * 2.0;", "o = e;");
}

#[test]
fn boolean_uniform_arrays_read_by_element_and_whole() {
    let vs = compile(Stage::Vertex, "#version 300 es\nin vec4 p;\nvoid main() { gl_Position = p; }").expect("vs");
    let f = fs(
        "uniform bvec4 flags[3];\nuniform bool bits[2];\nfloat same(bvec4 a, bvec4 b) { return a == b ? 1.0 : 0.0; }",
        "o = vec4(same(flags[0], bvec4(true)), same(flags[k], bvec4(false)), float(bits[1]), float(bits == bool[2](true, false)));",
    );
    let fs = compile(Stage::Fragment, &f).expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    assert!(l.uniforms.iter().any(|u| u.name == "flags"));
}

//! GLSL ES 1.00 rules: error cases with their info logs, and what must compile and link.

use std::collections::HashMap;

use crate::glsl::{compile, link};

use crate::glsl::types::{Stage, Ty};

fn frag_err(src: &str) -> String {
    compile(Stage::Fragment, src).expect_err("must not compile")
}

fn vert_err(src: &str) -> String {
    compile(Stage::Vertex, src).expect_err("must not compile")
}

#[test]
fn derivatives_need_the_extension_and_a_fragment_shader() {
    let fs = "#version 100\n#extension GL_OES_standard_derivatives : enable\nprecision mediump float;\nvarying vec2 x;\nvoid main() { gl_FragColor = vec4(dFdx(x), dFdy(x.x), fwidth(x.y)); }";
    let f = compile(Stage::Fragment, fs).expect("fragment derivatives");
    let v = compile(
        Stage::Vertex,
        "attribute vec2 p; varying vec2 x; void main() { x = p; gl_Position = vec4(p, 0.0, 1.0); }",
    )
    .expect("vs");
    link(&v, &f, &HashMap::new(), 16).expect("derivatives link");
    assert_eq!(
        frag_err(
            "precision mediump float;\nvarying vec2 x;\nvoid main() {\n  gl_FragColor = vec4(dFdx(x), 0.0, 0.0);\n}"
        ),
        "0:4(23): error: `dFdx' requires `#extension GL_OES_standard_derivatives : enable'"
    );
    assert_eq!(
        vert_err("#extension GL_OES_standard_derivatives : require\nattribute vec2 x;\nvoid main() { gl_Position = fwidth(x).xyxy; }"),
        "0:3(29): error: `fwidth' is only available in fragment shaders"
    );
}

#[test]
fn extension_directives_follow_section_3_4() {
    let macro_test = "#version 100\n#extension GL_OES_standard_derivatives : require\n#if GL_OES_standard_derivatives != 1\n#error no\n#endif\nvoid main() { gl_Position = vec4(0.0); }";
    compile(Stage::Vertex, macro_test).expect("macro defined to 1 in vertex shaders");
    assert_eq!(
        vert_err("void main() {}\n#extension GL_FOO_bar : require\n"),
        "0:2(1): error: extension `GL_FOO_bar' unsupported in vertex shader"
    );
    let warned = compile(Stage::Fragment, "#extension GL_FOO_bar : enable\nvoid main() { gl_FragColor = vec4(0.0); }")
        .expect("enable of an unsupported extension only warns");
    assert_eq!(warned.log, "0:1(1): warning: extension `GL_FOO_bar' unsupported in fragment shader");
    assert!(vert_err("#extension all : enable\nvoid main() {}").contains("cannot enable all extensions"));
    compile(Stage::Vertex, "#extension all : warn\nvoid main() { gl_Position = vec4(0.0); }").expect("all : warn");
    // Only offered extensions are defined as macros.
    compile(
        Stage::Vertex,
        "#ifdef GL_OES_texture_buffer\n#error defined\n#endif\nvoid main() { gl_Position = vec4(0.0); }",
    )
    .expect("an extension Strata does not offer is not defined");
}

#[test]
fn frag_depth_needs_the_extension_and_a_fragment_shader() {
    let fs = "#extension GL_EXT_frag_depth : enable\nprecision mediump float;\nvarying float d;\nvoid main() {\n  gl_FragColor = vec4(1.0);\n  gl_FragDepthEXT = d * 0.5;\n}";
    let f = compile(Stage::Fragment, fs).expect("fragment depth");
    assert!(f.frag_depth);
    let v = compile(Stage::Vertex, "attribute float p; varying float d; void main() { d = p; gl_Position = vec4(p); }")
        .expect("vs");
    link(&v, &f, &HashMap::new(), 16).expect("frag depth links");
    assert_eq!(
        frag_err("precision mediump float;\nvoid main() {\n  gl_FragDepthEXT = 0.5;\n}"),
        "0:3(3): error: `gl_FragDepthEXT' undeclared"
    );
    assert!(vert_err("#extension GL_EXT_frag_depth : enable\nvoid main() {\n  gl_FragDepthEXT = 0.5;\n}")
        .contains("`gl_FragDepthEXT' undeclared"));
}

#[test]
fn version_macro_is_100() {
    compile(
        Stage::Fragment,
        "#version 100\n#if __VERSION__ != 100\n#error wrong\n#endif\nvoid main() { gl_FragColor = vec4(0.0); }",
    )
    .expect("__VERSION__ is 100");
}

#[test]
fn missing_main_is_a_link_error() {
    let vs = compile(Stage::Vertex, "void main() { gl_Position = vec4(0.0); }").expect("vs");
    let fs = compile(Stage::Fragment, "precision mediump float; float foo() { return 0.0; }")
        .expect("compiles without main");
    assert_eq!(link(&vs, &fs, &HashMap::new(), 16).expect_err("no main"), "error: fragment shader lacks `main'");
}

#[test]
fn global_initialisers_must_be_constant() {
    assert_eq!(
        vert_err("uniform float uf;\nfloat g = uf;\nvoid main() { gl_Position = vec4(g); }"),
        "0:2(11): error: initializer of global variable uses non-constant `uf'"
    );
    assert!(vert_err("float a = 1.0;\nfloat b = a;\nvoid main() { gl_Position = vec4(b); }").starts_with("0:2("));
    compile(Stage::Vertex, "const float a = 1.0;\nfloat b = a * 2.0;\nvoid main() { gl_Position = vec4(b); }")
        .expect("const initialiser");
}

#[test]
fn redeclarations_and_struct_members() {
    assert!(vert_err("int f(int a) { return a; }\nint f(int a) { return a; }\nvoid main() {}").starts_with("0:2("));
    assert!(vert_err("int f(int a);\nint f(int a);\nvoid main() {}").contains("declared more than once"));
    assert!(vert_err("int f(int a);\nstruct f { int x; };\nvoid main() {}").contains("`f' redeclared"));
    assert!(vert_err("int x;\nint x;\nvoid main() {}").starts_with("0:2("));
    assert!(vert_err("struct S { int x; };\nstruct T { S; int y; };\nvoid main() {}").contains("anonymous"));
    assert!(vert_err("struct S { struct T { int a; } t; int b; };\nvoid main() {}").contains("embedded"));
    compile(
        Stage::Vertex,
        "int f(int a);\nint f(float a);\nint f(int a) { return a; }\nvoid main() { gl_Position = vec4(float(f(1))); }",
    )
    .expect("overloads and a prototype before the definition");
}

#[test]
fn array_sizes_are_folded() {
    let vs = compile(
        Stage::Vertex,
        "const int N = 3;\nuniform float a[(1, 2)];\nuniform float b[N + 1];\nuniform float c[gl_MaxDrawBuffers >= 1 ? 2 : -1];\nvoid main() { gl_Position = vec4(a[0] + b[3] + c[1]); }",
    )
    .expect("folded sizes");
    let lens: Vec<_> = vs.uniforms.iter().map(|u| u.array).collect();
    assert_eq!(lens, vec![Some(2), Some(4), Some(2)]);
    assert!(vert_err("uniform float a[gl_MaxDrawBuffers > 8 ? 1 : -1];\nvoid main() {}").contains("greater than zero"));
}

#[test]
fn float_array_varyings_link() {
    let vs = compile(
        Stage::Vertex,
        "attribute vec4 p; varying mediump float f[4]; varying mat2 m[2];\nvoid main() { gl_Position = p; f[0] = 0.0; f[1] = 1.0; f[2] = 0.0; f[3] = 1.0; m[0] = mat2(1.0); m[1] = mat2(2.0); }",
    )
    .expect("vs");
    let fs = compile(
        Stage::Fragment,
        "precision mediump float; varying float f[4]; varying mat2 m[2];\nvoid main() { gl_FragColor = vec4(f[0], f[1], f[2], f[3]) * m[1][0][0]; }",
    )
    .expect("fs");
    link(&vs, &fs, &HashMap::new(), 16).expect("array varyings link");
    let fs3 = compile(
        Stage::Fragment,
        "precision mediump float; varying float f[3];\nvoid main() { gl_FragColor = vec4(f[0]); }",
    )
    .expect("fs");
    assert!(link(&vs, &fs3, &HashMap::new(), 16).is_err(), "array lengths must match");
}

#[test]
fn reserved_operators_array_assignment_and_read_only_writes_fail() {
    let e = frag_err("precision mediump float;\nint f() {\n  return 15 % 4;\n}\nvoid main() {}");
    assert!(e.starts_with("0:3(10): error: operator") && e.contains("reserved"), "{e}");
    assert!(frag_err("precision mediump float;\nvoid f() { int a = 1; a <<= 2; }").contains("reserved"));
    assert!(frag_err("precision mediump float;\nint f(int a) { return ~a; }").contains("reserved"));
    assert_eq!(
        vert_err("void f(float x[2])\n{\n  float y[2];\n  y = x;\n}"),
        "0:4(3): error: arrays cannot be the target of an assignment"
    );
    assert_eq!(
        vert_err("attribute float x;\nfloat f() {\n\tx = 0.0;\n\treturn x;\n}"),
        "0:3(2): error: cannot write to read-only attribute `x'"
    );
    assert_eq!(
        frag_err("precision mediump float;\nvarying float x;\nvoid f(out float y) { y = 0.0; }\nvoid g() { f(x); }"),
        "0:4(14): error: cannot write to read-only varying `x' (an `out' argument)"
    );
    assert!(frag_err("precision mediump float;\nuniform float u;\nvoid g() { u++; }").contains("uniform `u'"));
    assert_eq!(
        vert_err("vec2 f() {\n  const float x = 1;\n  return vec2(x, 0.0);\n}"),
        "0:2(19): error: cannot initialise a `float' with a `int' (no implicit conversions)"
    );
    // What stays legal: a local hiding a global, writing a varying in the vertex shader,
    // indexing into an array, an `in` argument, and the same name as a parameter.
    compile(
        Stage::Vertex,
        "attribute float x; varying float v[2]; float a[2];\nvoid f(in float y) {}\nvoid main() { float x = 1.0; x = 2.0; v[0] = x; a[1] = 3.0; f(x); gl_Position = vec4(x); }",
    )
    .expect("legal writes");
    compile(Stage::Fragment, "precision mediump float;\nvarying float x;\nvoid f(float x) { x = 1.0; }\nvoid main() { gl_FragColor = vec4(x); }")
        .expect("a parameter hides the varying");
}

#[test]
fn sampler_arrays_are_one_binding_per_element() {
    let fs = compile(
        Stage::Fragment,
        "uniform sampler2D array[2];\nvoid main() { highp vec4 c = texture2D(array[1], vec2(0.0)); for (int i = 0; i < 2; i++) { c += texture2D(array[i], vec2(0.0)); } gl_FragColor = c; }",
    )
    .expect("sampler arrays compile");
    let vs = compile(Stage::Vertex, "void main() { gl_Position = vec4(0.0); }").expect("vs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("sampler arrays link");
    // Each element: a texture, a sampler and a border sampler.
    assert_eq!(l.samplers, vec![(Ty::Sampler2D, 1), (Ty::Sampler2D, 4)]);
    let u = l.uniforms.iter().find(|u| u.name == "array").expect("the array is one uniform");
    assert_eq!((u.len, u.is_array, u.sampler), (2, true, Some(0)));
    compile(Stage::Fragment, "uniform sampler2D a[2];\nvoid main() { gl_FragColor = texture2D(a[2], vec2(0.0)); }")
        .expect_err("a constant index past the end");
}

#[test]
fn sequences_struct_precision_and_called_global_initializers_translate() {
    let vs = "const float cf = 2.0;\nfloat g = (cf, 3.0);\nconst float c = cos((1.0, 2.0));\nvoid main() { gl_Position = vec4(g, c, max((1.0, cf), 0.0), 1.0); }";
    let vs = compile(Stage::Vertex, vs).expect("sequences in initializers and arguments, cos in a const");
    let fs = compile(Stage::Fragment, "struct s { lowp float a; };\nvoid main() { gl_FragColor = vec4(0); }")
        .expect("a precision on a struct member");
    link(&vs, &fs, &HashMap::new(), 16).expect("link");
}

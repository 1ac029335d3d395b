//! Uniforms of structure types and uniform block members of structure types: what compiles,
//! links, and the names GL gives their leaves (GLSL ES 3.00 §4.3.7, ES 3.0 §2.12.6).

use std::collections::HashMap;

use super::*;

const VS: &str = "#version 300 es
in vec4 p;
struct Inner { float x; bool b[2]; mat2 m; };
struct S { vec4 a; float arr[3]; Inner inner; sampler2D tex; };
uniform S u;
uniform S v[2];
out vec4 c;
void main() {
    c = u.a + vec4(u.arr[1] + u.inner.x + v[1].inner.m[1][0], 0.0, 0.0, 0.0) + texture(v[1].tex, vec2(0.5));
    if (u.inner.b[1]) c += texture(u.tex, vec2(0.0));
    gl_Position = p;
}";

const FS: &str = "#version 300 es
precision mediump float;
struct Inner { float x; bool b[2]; mat2 m; };
struct S { vec4 a; float arr[3]; Inner inner; sampler2D tex; };
uniform S u;
in vec4 c;
out vec4 o;
void main() { o = c * u.a; }";

#[test]
fn structure_uniforms_link_leaf_by_leaf() {
    let vs = compile(Stage::Vertex, VS).expect("vs");
    let fs = compile(Stage::Fragment, FS).expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let names: Vec<&str> = l.uniforms.iter().map(|u| u.gl_name.as_str()).collect();
    assert!(names.contains(&"u.arr") && names.contains(&"v[1].inner.m") && names.contains(&"v[0].tex"), "{names:?}");
    let tex = l.uniforms.iter().find(|u| u.gl_name == "u.tex").expect("u.tex");
    assert!(tex.ty.is_sampler());
}

#[test]
fn structures_must_match_across_stages() {
    let vs = compile(Stage::Vertex, VS).expect("vs");
    let other = FS.replace("struct S { vec4 a;", "struct S { vec4 z;").replace("u.a", "u.z");
    let fs = compile(Stage::Fragment, &other).expect("fs");
    link(&vs, &fs, &HashMap::new(), 16).expect_err("different members");
}

#[test]
fn es1_structure_uniforms() {
    let vs = compile(
        Stage::Vertex,
        "attribute vec4 p; struct S { vec3 a; float k[2]; }; uniform S s[2]; varying vec4 c;
         void main() { c = vec4(s[1].a, s[0].k[1]); gl_Position = p; }",
    )
    .expect("vs");
    let fs = compile(
        Stage::Fragment,
        "precision mediump float; uniform struct T { sampler2D t; lowp vec4 w; } t; varying vec4 c;
         void main() { gl_FragColor = c * texture2D(t.t, c.xy) + t.w; }",
    )
    .expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let names: Vec<&str> = l.uniforms.iter().map(|u| u.gl_name.as_str()).collect();
    assert_eq!(names, ["s[0].a", "s[0].k", "s[1].a", "s[1].k", "t.t", "t.w"]);
}

#[test]
fn whole_structures_are_filled_from_their_leaves() {
    let vs = compile(
        Stage::Vertex,
        "attribute vec4 p; struct S { vec3 a; float k[2]; }; uniform S s[2]; uniform int i; varying vec4 c;
         float f(S x) { return x.k[1]; }
         void main() { c = vec4(s[i].a, f(s[0])); gl_Position = p; }",
    )
    .expect("vs");
    let fs = compile(Stage::Fragment, "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }")
        .expect("fs");
    link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let e = compile(
        Stage::Vertex,
        "attribute vec4 p; struct S { mat2 m; }; uniform S s[2]; uniform int i;
         void main() { gl_Position = p * s[i].m[0][0]; }",
    )
    .expect_err("a matrix of two rows, indexed by a variable");
    assert!(e.contains("not supported yet"), "{e}");
}

/// A vertex shader with blocks holding structures (dEQP-GLES3's `ubo.multi_nested_struct`).
const BLOCKS_VS: &str = "#version 300 es
in highp vec4 a_position;
out mediump float v_result;
struct S { lowp mat3 a; mediump ivec2 b[4]; highp vec4 c; };
struct T { mediump uint a; S b; bvec4 c; };
layout(std140) uniform BlockA { highp float a; S b; lowp uvec3 c; } blockA;
layout(std140, row_major) uniform BlockB { mediump mat2 m; T t; bvec4 c; bool d; };
void main() {
    gl_Position = a_position;
    float r = blockA.a + blockA.b.a[1][2] + float(blockA.b.b[3].y) + blockA.b.c.w;
    r += m[1][0] + t.b.a[0][1] + float(t.b.b[2].x) + (t.c.y ? 1.0 : 0.0) + (c.x ? 1.0 : 0.0) + (d ? 1.0 : 0.0);
    v_result = r;
}";

#[test]
fn block_structures_are_laid_out_leaf_by_leaf() {
    let vs = compile(Stage::Vertex, BLOCKS_VS).expect("vs");
    let fs = compile(
        Stage::Fragment,
        "#version 300 es\nprecision mediump float; in float v_result; out vec4 o; void main() { o = vec4(v_result); }",
    )
    .expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let a = &l.blocks[0].block;
    let at = |n: &str| a.members.iter().find(|m| m.name == n).map(|m| (m.offset, m.stride)).expect(n);
    // ES 3.0 §2.12.6.4: the structure starts at a vec4 boundary, as does what follows it.
    assert_eq!([at("a"), at("b.a"), at("b.b"), at("b.c"), at("c")], [(0, 0), (16, 0), (64, 16), (128, 0), (144, 0)]);
    assert_eq!(a.size, 160);
    let b = &l.blocks[1].block;
    let row = |n: &str| b.members.iter().find(|m| m.name == n).map(|m| (m.offset, m.row_major)).expect(n);
    assert_eq!(
        [row("m"), row("t.a"), row("t.b.a"), row("t.b.c"), row("t.c"), row("c"), row("d")],
        [(0, true), (32, false), (48, true), (160, false), (176, false), (192, false), (208, false)]
    );
}

#[test]
fn blocks_without_instance_names_declare_their_members() {
    let vs = |blocks: &str| {
        compile(Stage::Vertex, &format!("#version 300 es\n{blocks}\nvoid main() {{ gl_Position = v; }}"))
    };
    vs("uniform A { vec4 v; }; uniform B { vec4 w; } b;").expect("`v' is declared by A");
    vs("uniform A { vec4 v; }; uniform B { vec4 v; };").expect_err("`v' declared twice");
    vs("uniform A { vec4 w; } a; uniform A { vec4 v; };").expect_err("`A' declared twice");
}

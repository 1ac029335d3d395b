//! GLSL ES 3.00: what must compile and link, and the errors Mesa gives.

use std::collections::HashMap;

use super::*;

const VS: &str = "#version 300 es
layout(location = 2) in vec4 position;
in vec2 uv;
out vec2 v_uv;
flat out int v_id;
out float buffer;
void main() {
    uint u = uint(gl_VertexID) * 3u;
    v_id = int(u % 7u) + gl_InstanceID;
    buffer = float(u >> 1);
    v_uv = uv;
    gl_Position = position;
}";

const FS: &str = "#version 300 es
precision mediump float;
in vec2 v_uv;
flat in int v_id;
in float buffer;
uniform sampler2D tex;
uniform samplerCube cube;
layout(location = 1) out vec4 second;
layout(location = 0) out vec4 color;
void main() {
    ivec2 size = textureSize(tex, 0);
    vec4 t = texture(tex, v_uv) + textureLod(tex, v_uv, 1.0) + texelFetch(tex, ivec2(1), 0);
    t += texture(cube, vec3(v_uv, 1.0)) + textureProj(tex, vec3(v_uv, 2.0));
    color = t * float(size.x + (v_id & 3)) + vec4(trunc(buffer), round(buffer), floatBitsToInt(1.0), 0.0);
    second = vec4(transpose(mat2(1.0, 2.0, 3.0, 4.0))[0], determinant(mat2(2.0)), inverse(mat2(2.0))[0][0]);
}";

#[test]
fn a_300_es_program_compiles_and_links() {
    let vs = compile(Stage::Vertex, VS).expect("vs");
    let fs = compile(Stage::Fragment, FS).expect("fs");
    assert_eq!(vs.version, 300);
    let l = link(&vs, &fs, &HashMap::from([("position".to_string(), 0)]), 16).expect("link");
    // The shader's location wins over a binding; the other input takes the lowest free one.
    let loc = |n: &str| l.attributes.iter().find(|(a, _)| a.name == n).map(|x| x.1);
    assert_eq!((loc("position"), loc("uv")), (Some(2), Some(0)));
    // ES 3.00 allows no aliasing: a binding onto the shader's location fails the link.
    let e = link(&vs, &fs, &HashMap::from([("uv".to_string(), 2)]), 16).expect_err("aliased");
    assert!(e.contains("location 2"), "{e}");
}

#[test]
fn es3_errors_are_mesa_s() {
    let fs = |body: &str| compile(Stage::Fragment, &format!("#version 300 es\nprecision mediump float;\n{body}"));
    let e = fs("in vec4 c; void main() { gl_FragColor = c; }").expect_err("no gl_FragColor in 3.00");
    assert!(e.contains("`gl_FragColor' undeclared"), "{e}");
    let e = compile(Stage::Vertex, "#version 300 es\nattribute vec4 p; void main() { gl_Position = p; }")
        .expect_err("attribute is reserved");
    assert!(e.contains("reserved word `attribute'"), "{e}");
    let e = fs("in int k; out vec4 o; void main() { o = vec4(k); }").expect_err("integer inputs are flat");
    assert!(e.contains("flat"), "{e}");
    let vs =
        compile(Stage::Vertex, "#version 300 es\nin vec4 p; out vec2 uv; void main() { uv = p.xy; gl_Position = p; }")
            .expect("vs");
    let two = fs("out vec4 a; out vec4 b; void main() { a = vec4(1.0); b = a; }").expect("compiles");
    let e = link(&vs, &two, &HashMap::new(), 16).expect_err("two outputs need locations");
    assert!(e.contains("location"), "{e}");
    let same =
        fs("layout(location = 0) out vec4 a; layout(location = 0) out vec4 b; void main() { a = vec4(1.0); b = a; }")
            .expect("compiles");
    assert!(link(&vs, &same, &HashMap::new(), 16).is_err(), "outputs share a location");
    let v = compile(Stage::Vertex, "#version 300 es\nin vec4 p; out vec4 c; void main() { c = p; gl_Position = p; }")
        .expect("vs");
    let f = fs("flat in vec4 c; out vec4 o; void main() { o = c; }").expect("fs");
    let e = link(&v, &f, &HashMap::new(), 16).expect_err("interpolation must match");
    assert!(e.contains("interpolation"), "{e}");
    assert!(compile(Stage::Vertex, "#version 310 es\nvoid main() {}").is_err());
}

/// Every GLSL ES 3.00 built-in function compiles (each one Mesa compiles), those naga lacks
/// through their stand-ins; what they compute is compared with Mesa by `tests/gles3_oracle.rs`.
#[test]
fn es3_built_ins_compile() {
    let exprs = [
        "vec4(modf(1.5, f))",
        "vec4(packSnorm2x16(vec2(0.5)))",
        "vec4(unpackUnorm2x16(7u), 0.0, 0.0)",
        "vec4(float(isinf(f)))",
        "vec4(matrixCompMult(mat2x3(1.0), mat2x3(2.0))[0], 0.0)",
        "vec4(lessThan(uvec2(1u), uvec2(2u)), 0.0, 0.0)",
        "vec4(abs(-3), sign(-2), min(3u, 4u), clamp(5u, 1u, 3u))",
        "vec4(mix(vec2(0.0), vec2(1.0), bvec2(true)), 0.0, 0.0)",
        "vec4(trunc(f), round(f), roundEven(f), sinh(f))",
        "vec4(cosh(f), tanh(f), asinh(f), acosh(2.0))",
        "vec4(atanh(0.5))",
        "vec4(floatBitsToUint(f), uintBitsToFloat(3u), 0.0, 0.0)",
        "textureProjOffset(t, vec3(0.5), ivec2(1))",
        "textureLodOffset(t, vec2(0.5), 0.0, ivec2(1))",
        "textureProjLodOffset(t, vec3(0.5), 0.0, ivec2(1))",
        "textureGradOffset(t, vec2(0.5), vec2(0.1), vec2(0.1), ivec2(1))",
        "textureProjGrad(t, vec3(0.5), vec2(0.1), vec2(0.1))",
        "textureProjGradOffset(t, vec4(0.5), vec2(0.1), vec2(0.1), ivec2(1))",
        "texelFetchOffset(t, ivec2(0), 0, ivec2(1))",
        "vec4(ivec4(1) / ivec4(2) + ivec4(3) % 2)",
        "vec4(uvec3(1u) << 2u, 0.0)",
        "vec4(mat3x2(1.0) * vec3(1.0), 0.0, 0.0)",
        "vec4(outerProduct(vec2(1.0), vec3(1.0))[0], 0.0, 0.0)",
        "vec4(transpose(mat4x2(1.0))[0], 0.0, 0.0)",
        "vec4(modf(vec2(1.5), v2), 0.0, 0.0)",
        "vec4(dFdx(f), fwidth(f), dFdy(f), 0.0)",
        "vec4(bvec4(true))",
        "vec4(ivec4(1))",
        "vec4(1, 2u, true, 0.5)",
    ];
    let mut bad = Vec::new();
    for e in exprs {
        let src = format!("#version 300 es\nprecision mediump float;\nuniform sampler2D t;\nout vec4 o;\nvoid main() {{ float f = 0.5; vec2 v2; o = {e}; }}");
        if let Err(err) = compile(Stage::Fragment, &src) {
            bad.push(format!("{e}: {err}"));
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn sampler3d_is_core_in_300_es() {
    let fs = |precision: &str| {
        compile(
            Stage::Fragment,
            &format!(
                "#version 300 es\nprecision mediump float; {precision} uniform sampler3D s; in vec2 uv; out vec4 o;\n\
                 void main() {{ o = texture(s, vec3(uv, 0.5)); }}"
            ),
        )
    };
    fs("precision lowp sampler3D;").expect("a default precision for sampler3D");
    let e = fs("").expect_err("sampler3D has no default precision");
    assert!(e.contains("sampler3D"), "{e}");
}

/// GLSL ES 3.00's shadow, array and integer samplers take precision qualifiers and default
/// precision statements, and have no default precision of their own (§4.5.4); each is
/// sampled.
#[test]
fn es3_sampler_types_take_precision() {
    let fs = |decl: &str, body: &str| {
        compile(
            Stage::Fragment,
            &format!("#version 300 es\nprecision mediump float;\n{decl}\nout vec4 o;\nvoid main() {{ {body} }}"),
        )
    };
    for t in ["sampler2DShadow", "samplerCubeShadow", "sampler2DArray", "isampler3D", "usampler2DArray"] {
        fs(&format!("uniform highp {t} s;"), "o = vec4(1.0);").unwrap_or_else(|e| panic!("{t}: {e}"));
        fs(&format!("precision lowp {t}; uniform {t} s;"), "o = vec4(1.0);").unwrap_or_else(|e| panic!("{t}: {e}"));
        let e = fs(&format!("uniform {t} s;"), "o = vec4(1.0);").expect_err("no default precision");
        assert!(e.contains(&format!("type `{t}'")), "{t}: {e}");
        let sampled = fs(&format!("uniform highp {t} s;"), "o = vec4(float(textureSize(s, 0).x));");
        sampled.unwrap_or_else(|e| panic!("{t} is sampled: {e}"));
    }
    // GLSL ES 1.00 knows none of them.
    let e = compile(Stage::Fragment, "precision mediump float; precision lowp sampler2DArray; void main() {}")
        .expect_err("ES 1.00");
    assert!(e.contains("default precision statements apply only"), "{e}");
}

/// GLSL ES 3.00's own built-in constants fold in array sizes and as values; GLSL ES 1.00 has
/// none of them; texture units are ES 3.0's minimums: 16 a stage, 32 combined.
#[test]
fn es3_built_in_constants() {
    let vs = |version: &str, body: &str| compile(Stage::Vertex, &format!("{version}\n{body}"));
    let body = "uniform float a[gl_MaxProgramTexelOffset - gl_MinProgramTexelOffset];
        uniform float b[gl_MaxVertexOutputVectors + gl_MaxFragmentInputVectors];
        uniform float c[gl_MaxCombinedTextureImageUnits - gl_MaxTextureImageUnits];
        void main() { float d[gl_MaxVertexTextureImageUnits]; d[0] = 1.0;
            gl_Position = vec4(a[14] + b[30] + c[15] + d[0] + float(gl_MaxProgramTexelOffset)); }";
    let v = vs("#version 300 es", body).expect("3.00");
    let lens: Vec<_> = v.uniforms.iter().map(|u| u.array).collect();
    assert_eq!(lens, [Some(15), Some(31), Some(16)]);
    let e = vs("", "uniform float a[gl_MaxProgramTexelOffset];\nvoid main() {}").expect_err("1.00");
    assert!(e.contains("constant valued"), "{e}");
    assert!(vs("", "void main() { gl_Position = vec4(float(gl_MaxVertexOutputVectors)); }").is_err(), "1.00");
}

/// A name after `.` is a member even where a structure of that name is declared (a block's
/// instance name scopes its members, §4.3.7).
#[test]
fn a_member_may_share_a_structure_s_name() {
    let vs = compile(
        Stage::Vertex,
        "#version 300 es
        uniform Data { mat4 mvp; float k; } camera;
        struct mvp { mat4 m; };
        struct k { float f; };
        in vec4 p;
        void main() { mvp x = mvp(camera.mvp); k y = k(camera.k); gl_Position = x.m * p * y.f; }",
    )
    .expect("compiles");
    assert_eq!(vs.blocks[0].members.iter().map(|m| m.name.as_str()).collect::<Vec<_>>(), ["mvp", "k"]);
}

/// An array of blocks is one block per element, `B[k]`, referenced by a stage only where it
/// indexes it; indices must be constant and within the array.
#[test]
fn arrays_of_uniform_blocks() {
    let vs = compile(
        Stage::Vertex,
        "#version 300 es
        const int N = 3;
        uniform Light { vec4 color; } lights[N];
        void main() { gl_Position = lights[0].color + lights[N - 1].color; }",
    )
    .expect("vs");
    let fs = compile(
        Stage::Fragment,
        "#version 300 es
        precision mediump float;
        uniform Light { vec4 color; } lights[3];
        out vec4 o;
        void main() { o = lights[1].color; }",
    )
    .expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let blocks: Vec<(&str, bool, bool)> =
        l.blocks.iter().map(|b| (b.block.name.as_str(), b.vertex, b.fragment)).collect();
    assert_eq!(blocks, [("Light[0]", true, false), ("Light[1]", false, true), ("Light[2]", true, false)]);
    let vs = |body: &str| {
        compile(Stage::Vertex, &format!("#version 300 es\nuniform B {{ vec4 v; }} b[2];\nuniform int k;\n{body}"))
    };
    let e = vs("void main() { gl_Position = b[k].v; }").expect_err("not constant");
    assert!(e.contains("constant integral expression"), "{e}");
    let e = vs("void main() { gl_Position = b[2].v; }").expect_err("past the end");
    assert!(e.contains("out of bounds"), "{e}");
    let e = vs("void main() { gl_Position = b.length() > 1 ? vec4(1.0) : vec4(0.0); }").expect_err("whole array");
    assert!(e.contains("may only be indexed"), "{e}");
}

/// No implicit conversions (§4.1.10), in either version; what is certain is checked, the rest
/// (built-in functions, shadowed names) left alone.
#[test]
fn no_implicit_conversions() {
    let vs = |version: &str, body: &str| {
        compile(
            Stage::Vertex,
            &format!(
                "{version}\nuniform vec4 a[7];\nuniform int i;\nstruct S {{ float f; int n; }};\n\
                 int twice(int x) {{ return 2 * x; }}\n{body}"
            ),
        )
    };
    let refused = [
        ("#version 300 es", "void main() { gl_Position = vec4(a[i].x + a.length()); }", "arithmetic"),
        ("#version 300 es", "void main() { gl_Position = vec4(uint(a[i].x) + a.length()); }", "arithmetic"),
        ("", "void main() { S s = S(1.0, i); gl_Position = vec4(s.f * s.n); }", "arithmetic"),
        ("", "void main() { float f; f = twice(i); gl_Position = vec4(f); }", "cannot be assigned"),
        ("", "void main() { gl_Position = vec4(i < 1.0 ? 1.0 : 0.0); }", "relational"),
        ("", "void main() { gl_Position = vec4(i > 0 ? 1.0 : 0); }", "?:"),
        ("", "float f() { return i; }\nvoid main() { gl_Position = vec4(f()); }", "`return' with wrong type int"),
        ("", "void main() { float x = a[0].y + 1.0; int y = twice(1) + x; gl_Position = vec4(y); }", "arithmetic"),
        ("#version 300 es", "void main() { uint u = 1u; u = u & i; gl_Position = vec4(u); }", "bitwise"),
    ];
    for (version, body, want) in refused {
        let e = vs(version, body).expect_err(body);
        assert!(e.contains(want), "{body}: {e}");
    }
    let accepted = [
        ("#version 300 es", "void main() { uint u = 3u << i; int n = i >> 1u; gl_Position = vec4(float(u) + float(n)); }"),
        ("", "void main() { float i = 1.0; gl_Position = vec4(i * 2.0); }"),
        ("", "void main() { gl_Position = vec4(max(i, 1) + 1.0); }"),
        ("", "void main() { S s = S(1.0, i); vec3 v = a[0].xyz * s.f; gl_Position = vec4(v.x, v.yz, float(twice(s.n))); }"),
        ("", "void main() { bool b = a[0].x > 0.0 && i == 2; gl_Position = vec4(b ? 1.0 : 0.0); }"),
    ];
    for (version, body) in accepted {
        vs(version, body).unwrap_or_else(|e| panic!("{body}: {e}"));
    }
}

#[test]
fn uniform_blocks_link_with_std140_offsets() {
    let vs = compile(
        Stage::Vertex,
        "#version 300 es
        layout(std140) uniform Transform { mat4 mvp; vec3 tint; float k[3]; } xf;
        layout(shared) uniform Common { vec2 scale; int mode; };
        in vec4 p; out vec3 c;
        void main() { c = xf.tint * xf.k[2] * float(mode); gl_Position = xf.mvp * p * scale.x; }",
    )
    .expect("vs");
    let fs = compile(
        Stage::Fragment,
        "#version 300 es
        precision mediump float;
        uniform Common { vec2 scale; int mode; };
        uniform Light { uvec4 flags; mat3x4 m; } light;
        in vec3 c; out vec4 o;
        void main() { o = vec4(c * scale.y, float(light.flags.x)) * light.m[0]; }",
    )
    .expect("fs");
    let l = link(&vs, &fs, &HashMap::new(), 16).expect("link");
    let names: Vec<(&str, u32, bool, bool)> =
        l.blocks.iter().map(|b| (b.block.name.as_str(), b.block.size, b.vertex, b.fragment)).collect();
    assert_eq!(names, [("Transform", 128, true, false), ("Common", 16, true, true), ("Light", 64, false, true)]);
    let offsets: Vec<(u32, u32)> = l.blocks[0].block.members.iter().map(|m| (m.offset, m.stride)).collect();
    assert_eq!(offsets, [(0, 0), (64, 0), (80, 16)]);
    let differ = compile(
        Stage::Fragment,
        "#version 300 es
        precision mediump float; uniform Common { vec2 scale; uint mode; }; out vec4 o;
        void main() { o = vec4(scale, 0.0, 1.0); }",
    )
    .expect("fs");
    let e = link(&vs, &differ, &HashMap::new(), 16).expect_err("declared differently");
    assert!(e.contains("Common"), "{e}");
}

/// Every shadow lookup of GLSL ES 3.00 compiles, links and validates (as compared helpers).
#[test]
fn shadow_lookups_link() {
    let vs =
        compile(Stage::Vertex, "#version 300 es\nin vec4 p; out vec2 uv; void main() { uv = p.xy; gl_Position = p; }")
            .expect("vs");
    let fs = compile(
        Stage::Fragment,
        "#version 300 es
        precision highp float;
        uniform highp sampler2DShadow s; uniform highp sampler2DArrayShadow a;
        uniform highp samplerCubeShadow c;
        uniform highp int mode; uniform float ref;
        in vec2 uv;
        out vec4 o;
        float look(highp sampler2DShadow t) { return texture(t, vec3(uv, ref)); }
        void main() {
            float r = texture(s, vec3(uv, ref)) + textureLod(s, vec3(uv, ref), 0.0)
                + textureGrad(s, vec3(uv, ref), dFdx(uv), dFdy(uv)) + textureProj(s, vec4(uv, ref, 2.0))
                + textureOffset(s, vec3(uv, ref), ivec2(1, 0)) + textureProjLod(s, vec4(uv, ref, 4.0), 0.0)
                + textureLodOffset(s, vec3(uv, ref), 0.0, ivec2(-1, 1)) + texture(s, vec3(uv, ref), 1.0)
                + texture(a, vec4(uv, 1.0, ref)) + textureGrad(a, vec4(uv, 0.0, ref), dFdx(uv), dFdy(uv))
                + texture(c, vec4(1.0, uv, ref)) + look(s);
            o = vec4(r, float(textureSize(s, 0).x), 0.0, 1.0);
        }",
    )
    .expect("fs");
    link(&vs, &fs, &HashMap::new(), 16).expect("link");
}

/// Integer literals of 32 significant bits are their bit patterns (the parser takes only values
/// up to 2³¹ − 1, so they are respelled); digits beside a '.' are floats', left alone.
#[test]
fn literals_of_32_bits() {
    let fs = |body: &str| {
        compile(
            Stage::Fragment,
            &format!("#version 300 es\nprecision highp float;\nout vec4 o;\nvoid main() {{ {body} }}"),
        )
    };
    fs("int a = int(0xFFFFFFFF) + 0x80000000 + 4294967295 + 020000000000; o = vec4(float(a));").expect("ints");
    fs("float f = 0.2147483648 + 2147483648.0 + 4294967296.5; o = vec4(f);").expect("floats");
    fs("int b = 4294967296; o = vec4(float(b));").expect_err("33 bits");
}

/// Every kind of integer lookup becomes GLSL that naga takes: each lookup form on each integer
/// sampler type (the helpers of `int_samplers`), linked.
#[test]
fn integer_sampler_lookups_compile_and_link() {
    let vs = compile(
        Stage::Vertex,
        "#version 300 es
layout(location = 0) in vec2 pos;
out vec2 uv;
void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }",
    )
    .expect("vs");
    for (decl, expr) in [
        ("uniform highp usampler2D s;", "texture(s, p)"),
        ("uniform highp usampler2D s;", "textureProj(s, vec3(p, 1.0) * 2.0)"),
        ("uniform highp usampler2D s;", "uvec4(textureSize(s, 1), textureSize(s, 0))"),
        ("uniform highp usampler2D s;", "texelFetch(s, ivec2(uv * 4.0), 1)"),
        ("uniform highp isampler3D s;", "texture(s, vec3(p, p.x * 2.0))"),
        ("uniform highp isamplerCube s;", "texture(s, vec3(p, 1.0))"),
        ("uniform highp usampler2DArray s;", "texture(s, vec3(p, 0.0))"),
        ("uniform highp isampler2D s;", "textureGradOffset(s, p, vec2(1.0), vec2(0.5), ivec2(1))"),
        ("uniform highp isampler2D s;", "textureProjLod(s, vec4(p, 0.0, 2.0), 1.0)"),
        ("uniform highp usampler3D s;", "textureProjGrad(s, vec4(p, 0.0, 2.0), vec3(1.0), vec3(0.0))"),
        (
            "uniform highp usamplerCube s;",
            "textureGrad(s, vec3(p, 1.0), vec3(1.0), vec3(0.0)) + uvec4(textureSize(s, 0), 0, 0)",
        ),
        ("uniform highp isampler2DArray s;", "textureLodOffset(s, vec3(p, 1.0), 1.0, ivec2(-1))"),
    ] {
        let src = format!(
            "#version 300 es
precision highp float;
precision highp int;
{decl}
in vec2 uv;
out vec4 o;
void main() {{ vec2 p = uv * 3.0 - 1.0; vec4 v = vec4({expr}); o = v; }}"
        );
        let fs = compile(Stage::Fragment, &src).map_err(|e| format!("{expr}: {e}")).expect("fs");
        link(&vs, &fs, &HashMap::new(), 16).map_err(|e| format!("{expr}: {e}")).expect("link");
    }
}

/// GLSL ES 3.00 §6.3 scopes, as Mesa compiles them: a block's declaration hides an outer one,
/// a body of one declaration is its own scope, a function may be declared twice, and a `for`
/// body may not declare again what its init declared.
#[test]
fn statement_scopes() {
    let fs = |body: &str| {
        compile(Stage::Fragment, &format!("#version 300 es\nprecision mediump float;\nout vec4 o;\n{body}"))
    };
    fs("void main() { int a = 1; { int a = 2; } o = vec4(a); }").expect("a block hides a local");
    fs("int a = 1; void main() { if (true) int a = 42; o = vec4(a); }").expect("an if body declares");
    fs("int f(int x);\nint f(int);\nint f(int x) { return x; }\nvoid main() { o = vec4(f(1)); }")
        .expect("a function declared twice");
    let e = fs("void main() { for (int i = 0; i < 2; i++) { int i = 3; o = vec4(i); } }")
        .expect_err("the for body shares the init's scope");
    assert!(e.contains("`i' redeclared"), "{e}");
}

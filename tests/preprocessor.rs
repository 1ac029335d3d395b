//! Conditional compilation in GLSL ES 1.00 shaders, against Mesa: macros in `#if` expand where
//! the `#if` stands (a macro may name one defined only later in the text), and the directives
//! of a skipped section are ignored, `#extension` included (GLSL ES 1.00 §3.4, as in C99's
//! preprocessing). Shader generators that build every variant from one source depend on both.
//! For each shader, Mesa's compile status is the oracle and Strata's front end must agree.

mod support;

use strata_client::{Calls, ClientError};
use strata_gles::glsl;
use strata_protocol::Text;
use support::mesa::MesaGl;

/// A fragment shader body that needs nothing from any extension.
const BODY: &str = "precision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); }\n";

/// Vertex shaders (name, source) whose extension directives decide whether they compile.
fn vertex_cases() -> Vec<(&'static str, String)> {
    let instance = "attribute vec4 p;\nvoid main() { gl_Position = p + vec4(float(gl_InstanceIDEXT)); }\n";
    vec![
        ("GL_EXT_draw_instanced enabled", format!("#extension GL_EXT_draw_instanced : enable\n{instance}")),
        ("GL_EXT_draw_instanced required", format!("#extension GL_EXT_draw_instanced : require\n{instance}")),
        ("GL_EXT_draw_instanced never enabled", instance.to_string()),
        (
            "GL_EXT_draw_instanced enabled, then disabled",
            format!(
                "#extension GL_EXT_draw_instanced : enable\n#extension GL_EXT_draw_instanced : disable\n{instance}"
            ),
        ),
        (
            "GL_EXT_draw_instanced's macro in a vertex shader",
            "#ifndef GL_EXT_draw_instanced\n#error no macro\n#endif\nvoid main() { gl_Position = vec4(0.0); }\n".into(),
        ),
    ]
}

/// Shaders (name, fragment source) whose preprocessing decides whether they compile.
fn cases() -> Vec<(&'static str, String)> {
    let derivatives =
        "precision mediump float;\nvarying vec2 v;\nvoid main() { gl_FragColor = vec4(dFdx(v), 0.0, 1.0); }\n";
    let frag_depth = "precision mediump float;\nvoid main() { gl_FragColor = vec4(1.0); gl_FragDepthEXT = 0.25; }\n";
    vec![
        (
            // A compositor's shader generator: the variant macro is defined before the names it
            // expands to, and the external-image section is skipped for the solid variant.
            "variant macro defined before its value",
            format!(
                "#define VARIANT VARIANT_SOLID\n#define VARIANT_SOLID 7\n#define VARIANT_EXTERNAL 8\n\
                 #if VARIANT == VARIANT_EXTERNAL\n#extension GL_FOO_external_image : require\n#endif\n{BODY}"
            ),
        ),
        (
            "the same variant selected: the extension is required",
            format!(
                "#define VARIANT VARIANT_EXTERNAL\n#define VARIANT_SOLID 7\n#define VARIANT_EXTERNAL 8\n\
                 #if VARIANT == VARIANT_EXTERNAL\n#extension GL_FOO_external_image : require\n#endif\n{BODY}"
            ),
        ),
        ("#if 0 around an unknown required extension", format!("#if 0\n#extension GL_FOO_bar : require\n#endif\n{BODY}")),
        ("#if 1 around an unknown required extension", format!("#if 1\n#extension GL_FOO_bar : require\n#endif\n{BODY}")),
        (
            "#ifdef of an undefined macro, #else taken",
            format!("#ifdef NOT_DEFINED\n#extension GL_FOO_bar : require\n#else\n#define X 1\n#endif\n{BODY}"),
        ),
        (
            "#ifndef of a defined macro",
            format!("#define SEEN\n#ifndef SEEN\n#extension GL_FOO_bar : require\n#endif\n{BODY}"),
        ),
        (
            "#elif chain: the taken branch enables derivatives",
            format!(
                "#define A B\n#define B 2\n#if A == 1\n#extension GL_FOO_bar : require\n#elif A == 2\n\
                 #extension GL_OES_standard_derivatives : enable\n#else\n#extension GL_FOO_baz : require\n#endif\n{derivatives}"
            ),
        ),
        (
            "derivatives enabled only in a skipped section",
            format!("#if 0\n#extension GL_OES_standard_derivatives : enable\n#endif\n{derivatives}"),
        ),
        (
            "a function-like macro in #if",
            format!("#define PLUS1(x) ((x) + 1)\n#if PLUS1(1) != 2\n#extension GL_FOO_bar : require\n#endif\n{BODY}"),
        ),
        (
            "defined() with && and !",
            format!("#if defined(GL_ES) && !defined(NOPE)\n#else\n#extension GL_FOO_bar : require\n#endif\n{BODY}"),
        ),
        (
            "malformed directives in a skipped section",
            format!("#if 0\n#extension garbage\n#frobnicate now\n#line x y\n#error not reached\n#endif\n{BODY}"),
        ),
        (
            "a nested skipped #if with a bad expression",
            format!("#if 0\n#if 1 +\n#extension GL_FOO_bar : require\n#endif\n#endif\n{BODY}"),
        ),
        (
            "#undef makes a later section skipped",
            format!("#define ON 1\n#undef ON\n#if defined(ON)\n#extension GL_FOO_bar : require\n#endif\n{BODY}"),
        ),
        ("an #error in a taken section", format!("#if 1\n#error taken\n#endif\n{BODY}")),
        ("GL_EXT_frag_depth enabled", format!("#extension GL_EXT_frag_depth : enable\n{frag_depth}")),
        (
            "GL_EXT_frag_depth enabled only in a skipped section",
            format!("#ifndef GL_ES\n#extension GL_EXT_frag_depth : enable\n#endif\n{frag_depth}"),
        ),
        ("GL_EXT_frag_depth never enabled", frag_depth.to_string()),
        (
            "GL_EXT_frag_depth's macro",
            format!("#ifndef GL_EXT_frag_depth\n#error no macro\n#endif\n{BODY}"),
        ),
        (
            "GL_EXT_draw_instanced's instance number in a fragment shader",
            "#extension GL_EXT_draw_instanced : enable\nprecision mediump float;\n\
             void main() { gl_FragColor = vec4(float(gl_InstanceIDEXT)); }\n"
                .into(),
        ),
        (
            "GL_EXT_draw_instanced's macro in a fragment shader",
            format!("#ifndef GL_EXT_draw_instanced\n#error no macro\n#endif\n{BODY}"),
        ),
    ]
}

/// Whether Mesa compiles `source` as a shader of `stage`, with its info log.
fn mesa_compiles(gl: &mut MesaGl, stage: glsl::Stage, name: u32, source: &str) -> Result<(bool, String), ClientError> {
    gl.glCreateShader(if stage == glsl::Stage::Vertex { 0x8B31 } else { 0x8B30 }, name)?;
    gl.glShaderSource(name, Text::borrowed(source))?;
    gl.glCompileShader(name)?;
    Ok((gl.glGetShaderiv(name, 0x8B81)? != 0, gl.glGetShaderInfoLog(name)?))
}

#[test]
fn conditional_sections_and_their_directives_match_mesa() {
    let Some(mut mesa) = MesaGl::open_or_skip(16, 16) else { return };
    let mut outcomes = [0usize; 2];
    let mut disagreements = Vec::new();
    let staged = cases().into_iter().map(|(n, s)| (n, glsl::Stage::Fragment, s));
    let staged = staged.chain(vertex_cases().into_iter().map(|(n, s)| (n, glsl::Stage::Vertex, s)));
    for (i, (name, stage, source)) in staged.enumerate() {
        let (native, log) = mesa_compiles(&mut mesa, stage, 100 + i as u32, &source).expect("Mesa");
        let ours = glsl::compile(stage, &source);
        eprintln!("{name}: Mesa {native}, Strata {}", ours.is_ok());
        outcomes[usize::from(native)] += 1;
        if ours.is_ok() != native {
            let said = ours.err().unwrap_or_default();
            disagreements.push(format!("{name}: Mesa compiles: {native} ({log:?}); Strata: {said:?}"));
        }
    }
    assert!(disagreements.is_empty(), "Strata's preprocessing differs from Mesa's:\n{}", disagreements.join("\n"));
    // The cases must exercise both outcomes, or they would not tell anything apart.
    assert!(outcomes.iter().all(|&n| n >= 3), "cases Mesa refuses and compiles: {outcomes:?}");
}

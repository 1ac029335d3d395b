//! GLSL ES 1.00 → Vulkan-flavoured GLSL 450 → naga.
//!
//! naga's GLSL front end accepts only GLSL 440+, so each ES shader is preprocessed and parsed
//! with glsl-lang (with `GL_ES` defined), its global interface is lifted out, and its AST is
//! rewritten: `gl_FragColor` and `gl_FragData` become variables that the generated `main`
//! copies to one output per draw buffer, the built-in constants become literals, `texture2D`-style
//! calls become `texture(sampler2D(t, s), …)` on split texture/sampler bindings, precision
//! qualifiers go, and `main` is renamed so that a generated `main` can apply Strata's
//! conventions (y negated, clip z mapped from [-1, 1] to [0, 1]). Linking then packs every loose
//! uniform of both stages into one std140 block at set 0, binding 0, assigns attribute and
//! varying locations, and hands the generated sources to naga to parse and validate.
//!
//! | module | step |
//! |---|---|
//! | `preprocess` | `#version` check, `GL_ES` defines, preprocessing and parsing |
//! | `interface` | lifting attributes, varyings and uniforms out of the AST; ES restrictions |
//! | `blocks` | GLSL ES 3.00 uniform blocks: lifted, laid out by std140, declared again |
//! | `rewrite` | the AST rewrite to Vulkan-flavoured GLSL |
//! | `link` | the program-wide uniform block, locations, generated `main`s |
//! | `polyfill` | generated functions for the built-ins naga lacks |
//! | `separate` | one-stage programs, and two programs' stages linked into one executable |
//! | `translate` | the generated code with its source lines; naga, errors at the shader's line |

mod attributes;
mod block_arrays;
mod block_members;
mod block_structs;
pub mod blocks;
pub mod capture;
mod checks;
mod consts;
mod conversions;
mod es3_rules;
mod fields;
mod hoist;
mod int_samplers;
mod interface;
mod link;
pub mod linked;
mod operators;
mod polyfill;
mod precision;
mod preprocess;
mod rewrite;
mod separate;
mod shadow;
mod shapes;
mod sized_arrays;
mod struct_uniforms;
mod struct_varyings;
mod structs;
mod swizzle;
mod translate;
pub mod types;
mod variants;
mod writes;

pub use link::{link, points_vertex};
pub use linked::{Linked, OutputKind, UniformSlot};
pub use separate::{fragment_uniform_name, interfaces_match, link_alone, rename_uniforms};
pub use types::{Block, BlockMember, Scalar, Shader, Stage, StructUniforms, Ty, Var};
pub use variants::ClipZ;

/// Compiles (parses and checks) a GLSL ES 1.00 shader. The error is the info log.
pub fn compile(stage: Stage, source: &str) -> Result<Shader, String> {
    // The parser and rewriter are third-party code fed client text: a panic there must become
    // a failed compile, never a dead session.
    // Type errors inside function bodies are found by naga: each stage is translated once
    // here, against a stand-in for the other stage, so that they fail the compile with a line.
    std::panic::catch_unwind(|| {
        interface::compile_inner(stage, source).and_then(|s| match separate::stand_in(&s) {
            Ok(other) => link::check_stage(s, &other),
            Err(_) => Ok(s),
        })
    })
    .unwrap_or_else(|_| Err("0: internal error: the GLSL ES front end failed on this shader".into()))
}

#[cfg(test)]
mod conformance_tests;
#[cfg(test)]
mod es3_tests;
#[cfg(test)]
mod operators_tests;
#[cfg(test)]
mod struct_tests;

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    const VS: &str =
        "attribute vec3 position; attribute vec2 uv; uniform mat4 mvp; uniform float k[3]; varying vec2 v_uv;
        void main() { v_uv = uv * k[1]; gl_Position = mvp * vec4(position, 1.0); }";
    const FS: &str = "#ifdef GL_ES\nprecision mediump float;\n#endif\nvarying vec2 v_uv; uniform sampler2D tex; uniform bool flip; uniform lowp vec4 tint;
        vec4 shade(vec2 c) { return texture2D(tex, c) * tint; }
        void main() { vec2 c = flip ? v_uv.yx : v_uv; gl_FragColor = shade(c); }";

    #[test]
    fn links_and_lays_out_std140() {
        let vs = compile(Stage::Vertex, VS).expect("vs");
        let fs = compile(Stage::Fragment, FS).expect("fs");
        let mut bind = HashMap::new();
        bind.insert("uv".to_string(), 0);
        let l = link(&vs, &fs, &bind, 16).expect("link");
        let find = |n: &str| l.uniforms.iter().find(|u| u.name == n).expect(n).clone();
        assert_eq!((find("mvp").offset, find("k").offset, find("k").stride), (0, 64, 16));
        assert_eq!(find("flip").offset, 112);
        assert_eq!(find("tint").offset, 128);
        // The sampler's wrap flags, border colour, swizzle and comparison follow the uniforms.
        assert_eq!(l.wrap_offsets, vec![144]);
        assert_eq!(l.block_size, 208);
        assert_eq!(l.attributes.iter().find(|(a, _)| a.name == "uv").map(|x| x.1), Some(0));
        assert_eq!(l.attributes.iter().find(|(a, _)| a.name == "position").map(|x| x.1), Some(1));
        assert_eq!(l.samplers, vec![(Ty::Sampler2D, 1)]);
    }

    #[test]
    fn precision_only_qualifiers_are_dropped() {
        let vs = compile(Stage::Vertex, "attribute highp vec4 p; varying lowp vec4 c; void main() { highp float k = 1.0; c = p * k; gl_Position = p; }").expect("vs");
        let fs = compile(Stage::Fragment, "varying lowp vec4 c; mediump vec4 f(in lowp vec4 x, mediump float k) { return x * k; } void main() { gl_FragColor = f(c, 1.0); }").expect("fs");
        link(&vs, &fs, &HashMap::new(), 16).expect("link");
    }

    #[test]
    fn errors_become_info_logs() {
        assert!(compile(Stage::Vertex, "void main() { gl_Position = vec4(1.0) }").is_err());
        assert!(compile(Stage::Fragment, "attribute vec4 a; void main() {}").is_err());
        let no_main = compile(Stage::Vertex, "void notmain() { gl_Position = vec4(0.0); }").expect("compiles");
        let fs_ok = compile(Stage::Fragment, "void main() { gl_FragColor = vec4(0.0); }").expect("fs");
        let e = link(&no_main, &fs_ok, &HashMap::new(), 16).expect_err("no main");
        assert_eq!(e, "error: vertex shader lacks `main'");
        let vs = compile(Stage::Vertex, "varying vec2 a; void main() { gl_Position = vec4(0.0); }").expect("vs");
        let fs = compile(Stage::Fragment, "varying mediump vec3 b; void main() { gl_FragColor = vec4(b, 1.0); }")
            .expect("fs");
        let e = link(&vs, &fs, &HashMap::new(), 16).expect_err("unmatched varying");
        assert!(e.contains("'b'"), "{e}");
        let e = compile(
            Stage::Fragment,
            "precision mediump float;\nvoid main() {\n  float a = 1.0;\n  gl_FragColor =\n vec4(undefined_thing);\n}",
        )
        .expect_err("an unknown identifier");
        assert!(e.starts_with("0:4("), "the info log names the statement's line: {e}");
        assert!(e.contains("undefined_thing"), "{e}");
        let e = compile(Stage::Vertex, "attribute vec4 p;\nvoid main() {\n  vec3 v = p;\n  gl_Position = p;\n}")
            .expect_err("a vec4 assigned to a vec3");
        assert!(e.starts_with("0:3("), "the info log names the statement's line: {e}");
        assert!(e.contains("'main'"), "the shader's own names: {e}");
    }
}

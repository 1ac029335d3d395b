//! `GL_EXT_separate_shader_objects` in the translator: the stand-in a one-stage program is
//! linked against, the interface two programs' stages must share to draw together, and the
//! renaming that keeps two programs' uniforms apart when their stages are linked into one
//! executable.

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use glsl_lang::ast::{self, ExprData};
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};

use crate::glsl::Linked;

use crate::glsl::types::{Shader, Stage};

/// The prefix a fragment stage's uniform gets where the vertex stage of another program
/// declares one of the same name.
const FRAGMENT_PREFIX: &str = "strata_fs_";

/// The other stage of a one-stage program: it declares the varyings `s` reads (a fragment
/// shader's) and nothing else, and writes a constant (white fragments, as Mesa draws where a
/// pipeline has no fragment stage).
pub(super) fn stand_in(s: &Shader) -> Result<Shader, String> {
    let source = match s.stage {
        Stage::Vertex => "void main() { gl_FragColor = vec4(1.0); }".to_string(),
        Stage::Fragment => {
            let mut src = String::new();
            for v in &s.varyings {
                let _ =
                    writeln!(src, "varying {} {}{};", v.ty.glsl(false), v.name, crate::glsl::linked::array_suffix(v));
            }
            for (frag, vert) in [("gl_FragCoord", "gl_Position"), ("gl_PointCoord", "gl_PointSize")] {
                if s.facts.invariants.contains(frag) {
                    let _ = writeln!(src, "invariant {vert};");
                }
            }
            src.push_str("void main() { gl_Position = vec4(0.0); }");
            src
        }
    };
    let other = if s.stage == Stage::Vertex { Stage::Fragment } else { Stage::Vertex };
    crate::glsl::interface::compile_inner(other, &source)
}

/// Links a one-stage (separable) program: `s` against its stand-in. The error is the info log.
pub fn link_alone(s: &Shader, bindings: &HashMap<String, u32>, max_attribs: u32) -> Result<Linked, String> {
    let other = stand_in(s).map_err(|e| format!("error: internal error: the stand-in stage failed: {e}"))?;
    let (vs, fs) = if s.stage == Stage::Vertex { (s, &other) } else { (&other, s) };
    crate::glsl::link(vs, fs, bindings, max_attribs)
}

/// Whether a vertex stage feeds a fragment stage of another program: every varying the
/// fragment stage reads is written with the same type and precision (as Mesa matches them).
pub fn interfaces_match(vs: &Shader, fs: &Shader) -> bool {
    fs.varyings.iter().all(|v| {
        vs.varyings.iter().any(|o| {
            o.name == v.name
                && o.ty == v.ty
                && o.array == v.array
                && vs.facts.varying_precisions.get(&o.name) == fs.facts.varying_precisions.get(&v.name)
        })
    })
}

/// The name a fragment uniform `name` has in an executable whose vertex stage declares
/// `taken` (itself where they differ).
pub fn fragment_uniform_name(name: &str, taken: &HashSet<String>) -> String {
    if taken.contains(name) {
        format!("{FRAGMENT_PREFIX}{name}")
    } else {
        name.to_string()
    }
}

/// Fragment shader `fs` with each uniform the vertex stage also declares (`taken`) renamed
/// by [`fragment_uniform_name`], with the names the rewrite derived from it (the block's
/// `strata_b_`/`strata_m2_` forms, a sampler's `__` parts).
pub fn rename_uniforms(fs: &Shader, taken: &HashSet<String>) -> Shader {
    let clashes: HashSet<String> =
        fs.uniforms.iter().filter(|u| taken.contains(&u.name)).map(|u| u.name.clone()).collect();
    let mut out = fs.clone();
    if clashes.is_empty() {
        return out;
    }
    out.body.visit_mut(&mut Rename { clashes: &clashes });
    for u in &mut out.uniforms {
        u.name = fragment_uniform_name(&u.name, &clashes);
    }
    let names = std::mem::take(&mut out.structs.names);
    out.structs.names = names.into_iter().map(|(k, v)| (fragment_uniform_name(&k, &clashes), v)).collect();
    let facts = &mut out.facts;
    facts.uniform_precisions =
        facts.uniform_precisions.drain().map(|(k, v)| (fragment_uniform_name(&k, &clashes), v)).collect();
    facts.used = facts.used.drain().map(|k| fragment_uniform_name(&k, &clashes)).collect();
    out
}

/// Renames the identifiers of clashing uniforms, leaving field selections and struct members.
struct Rename<'a> {
    clashes: &'a HashSet<String>,
}

impl Rename<'_> {
    /// The new spelling of `id`, if it is a clashing uniform or a name derived from one.
    fn renamed(&self, id: &str) -> Option<String> {
        for derived in ["strata_b_", "strata_m2_"] {
            if let Some(base) = id.strip_prefix(derived) {
                if self.clashes.contains(base) {
                    return Some(format!("{derived}{FRAGMENT_PREFIX}{base}"));
                }
            }
        }
        // GLSL ES reserves `__`: a name with it is one the rewrite made from a sampler's (or a
        // structure's leaf, `u__a`, itself a uniform whose sampler parts follow).
        let derived = id.match_indices("__").any(|(at, _)| self.clashes.contains(&id[..at]));
        (self.clashes.contains(id) || derived).then(|| format!("{FRAGMENT_PREFIX}{id}"))
    }
}

impl VisitorMut for Rename<'_> {
    fn visit_identifier(&mut self, id: &mut ast::Identifier) -> Visit {
        if let Some(new) = self.renamed(id.0.as_str()) {
            id.content.0 = new.into();
        }
        Visit::Children
    }

    fn visit_expr(&mut self, e: &mut ast::Expr) -> Visit {
        if let ExprData::Dot(base, _) = &mut e.content {
            base.visit_mut(self);
            return Visit::Parent;
        }
        Visit::Children
    }

    fn visit_struct_field_specifier(&mut self, _: &mut ast::StructFieldSpecifier) -> Visit {
        Visit::Parent
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::glsl::{compile, link};

    #[test]
    fn clashing_uniforms_stay_apart() {
        let vs = compile(Stage::Vertex, "attribute vec4 p; uniform vec4 k; uniform bool b; varying vec4 c; void main() { c = b ? k : -k; gl_Position = p; }")
            .expect("vs");
        let fs = compile(
            Stage::Fragment,
            "precision mediump float; varying highp vec4 c; uniform vec4 k; uniform bool b; uniform mat2 m; uniform sampler2D s[2];\n\
             struct S { float k; }; void main() { S x = S(1.0); vec4 t = texture2D(s[1], c.xy); gl_FragColor = (b ? c + k : c) * x.k + t + vec4(m[0], 0.0, 0.0); }",
        )
        .expect("fs");
        let taken: HashSet<String> = vs.uniforms.iter().map(|u| u.name.clone()).collect();
        let renamed = rename_uniforms(&fs, &taken);
        let l = link(&vs, &renamed, &HashMap::new(), 16).expect("link");
        let names: Vec<&str> = l.uniforms.iter().map(|u| u.name.as_str()).collect();
        assert_eq!(names, ["k", "b", "strata_fs_k", "strata_fs_b", "m", "s"]);
        assert!(interfaces_match(&vs, &fs));
        let lowp = compile(Stage::Fragment, "varying lowp vec4 c; void main() { gl_FragColor = c; }").expect("fs");
        assert!(!interfaces_match(&vs, &lowp), "precisions differ");
    }

    #[test]
    fn the_directive_and_macro() {
        let src = "#extension GL_EXT_separate_shader_objects : require\n#ifndef GL_EXT_separate_shader_objects\n#error no macro\n#endif\n\
                   precision mediump float; void main() { gl_FragColor = vec4(float(GL_EXT_separate_shader_objects)); }";
        compile(Stage::Fragment, src).expect("the directive is accepted and the macro defined");
    }
}

//! Uniforms of structure types (GLSL ES 1.00 §4.1.8, §4.3.4): `uniform S u;`, arrays of them,
//! structures within them. GL makes each leaf an active uniform of its own (`u.a`, `u.arr[0]`,
//! `u[1].inner.x`), and so does the translation: each becomes a plain uniform (`u__a`, named
//! by [`structs::ident`]), and each access of a leaf through constant indices reads it. Where
//! the shader uses `u` otherwise (whole, or through an index that is not constant), a private
//! global of the structure stands for it, which a generated `main` fills from the leaves
//! before the shader's own `main` (renamed) runs. naga holds no samplers in structures, nor
//! matrices of two rows (it gives every structure std140's layout, which it refuses for them):
//! such members leave the structure, and a uniform holding one must be used member by member.

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;

use glsl_lang::ast::{self, TypeQualifierSpecData};
use glsl_lang::visitor::HostMut;

use crate::glsl::consts::array_len;
use crate::glsl::structs::{self, fill, ident, parse, var, wrap_main, Paths, Structs};
use crate::glsl::types::StructUniforms;

/// What the shader's own `main` is renamed to.
const RENAMED_MAIN: &str = "strata_uniform_main";

/// Whether a declaration's qualifiers make it a `uniform`.
fn is_uniform(q: Option<&ast::TypeQualifier>) -> bool {
    q.is_some_and(|q| {
        q.qualifiers.iter().any(|s| {
            matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Uniform)
        })
    })
}

/// Flattens the structure uniforms of `tu` (of language `version`): what the link needs of
/// them, and the shader's structures as declared.
pub(super) fn flatten(tu: &mut ast::TranslationUnit, version: u16) -> Result<(StructUniforms, Structs), String> {
    let consts = crate::glsl::block_arrays::global_ints(tu, version);
    let structs = structs::collect(tu, &consts)?;
    let mut info = StructUniforms::default();
    if structs.is_empty() {
        return Ok((info, structs));
    }
    let mut out = Vec::with_capacity(tu.0.len());
    let mut paths = Paths {
        leaves: HashMap::new(),
        samplers: HashSet::new(),
        roots: HashSet::new(),
        whole: HashSet::new(),
        consts: &consts,
        error: None,
        shadow: HashSet::new(),
    };
    // Each structure uniform's type, and the steps filling it from its leaves.
    let mut fills: HashMap<String, (String, String)> = HashMap::new();
    for decl in std::mem::take(&mut tu.0) {
        let flattened = match &decl.content {
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::InitDeclaratorList(list) if is_uniform(list.head.ty.qualifier.as_ref()) => {
                    structs::struct_name(&list.head.ty.ty.ty, &structs).map(|s| (list, s))
                }
                _ => None,
            },
            _ => None,
        };
        let Some((list, sname)) = flattened else {
            out.push(decl);
            continue;
        };
        if list.head.initializer.is_some() || list.tail.iter().any(|t| t.initializer.is_some()) {
            return Err("0: attribute, varying and uniform variables cannot be initialised".into());
        }
        let base = list.head.ty.ty.array_specifier.as_ref();
        let mut declared: Vec<(String, Option<&ast::ArraySpecifier>)> = Vec::new();
        if let Some(n) = &list.head.name {
            declared.push((n.0.to_string(), list.head.array_specifier.as_ref().or(base)));
        }
        declared.extend(list.tail.iter().map(|t| (t.ident.ident.0.to_string(), t.ident.array_spec.as_ref().or(base))));
        let mut text = String::new();
        for (name, spec) in declared {
            let array = array_len(spec, &consts)?;
            info.types.insert(name.clone(), structs::signature(&structs, &sname));
            let mut steps = String::new();
            for leaf in structs::leaves(&structs, &sname, &name, array)? {
                let id = ident(&leaf.name);
                let dims = leaf.array.map_or(String::new(), |n| format!("[{n}]"));
                let _ = writeln!(text, "uniform {} {id}{dims};", leaf.spelling);
                if leaf.ty.is_sampler() {
                    paths.samplers.insert(leaf.name.clone());
                } else {
                    fill(&mut steps, &leaf.name, &id, leaf.array);
                }
                paths.leaves.insert(leaf.name.clone(), var(&id));
                info.names.insert(id, leaf.name);
            }
            paths.roots.insert(name.clone());
            fills.insert(name, (sname.clone(), steps));
        }
        // The private global (with the structure, where declared here), unqualified: what the
        // shader's code reads where it uses the whole structure.
        let mut private = decl.clone();
        if let ast::ExternalDeclarationData::Declaration(d) = &mut private.content {
            if let ast::DeclarationData::InitDeclaratorList(l) = &mut d.content {
                l.head.ty.qualifier = None;
            }
        }
        out.push(private);
        out.extend(parse(&text)?);
    }
    tu.0 = out;
    tu.visit_mut(&mut structs::DropUnheld);
    if info.names.is_empty() {
        return Ok((info, structs));
    }
    tu.visit_mut(&mut paths);
    if let Some(e) = paths.error {
        return Err(e);
    }
    let mut whole: Vec<&String> = paths.whole.iter().collect();
    whole.sort();
    let mut steps = String::new();
    for name in whole {
        let Some((sname, fill)) = fills.get(name) else { continue };
        if structs::holds_unheld(&structs, sname) {
            return Err(format!(
                "0: the uniform `{name}' holds samplers or matrices of two rows, and is used other than member by member through constant indices: not supported yet"
            ));
        }
        steps.push_str(fill);
    }
    if !steps.is_empty() {
        wrap_main(tu, RENAMED_MAIN, &steps)?;
    }
    Ok((info, structs))
}

/// The names under which a structure uniform of either stage appears in the other as
/// something else: a link error (§4.2.6 of GLSL ES 3.00: the same name, the same type).
pub(super) fn check_link(vs: &crate::glsl::types::Shader, fs: &crate::glsl::types::Shader) -> Result<(), String> {
    for (a, b) in [(vs, fs), (fs, vs)] {
        for (name, sig) in &a.structs.types {
            let differs = match b.structs.types.get(name) {
                Some(other) => other != sig,
                None => b.uniforms.iter().any(|u| &u.name == name),
            };
            if differs {
                return Err(format!("error: uniform `{name}' is declared with different types in the two stages"));
            }
        }
    }
    Ok(())
}

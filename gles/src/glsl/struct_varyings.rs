//! GLSL ES 3.00 varyings of structure types (§4.3.4, §4.3.6): `out S s;` in a vertex shader,
//! `in S s;` in a fragment shader. naga has no structures between stages, so each becomes a
//! private global of the structure, which the shader's code reads and writes as it is, and one
//! varying per member (`s__a` for `s.a`, with the declaration's qualifiers), which the stages
//! match by name; a generated `main` copies the members in before the shader's own `main`
//! (renamed) runs, or out after it. Arrays of structures, and structures within them, are
//! refused.

use std::collections::HashMap;
use std::fmt::Write as _;

use glsl_lang::ast::{self, TypeSpecifierNonArrayData as T};
use glsl_lang::parse::DefaultParse;
use glsl_lang::transpiler::glsl::{show_array_spec, show_type_qualifier, show_type_specifier, FormattingState};

use crate::glsl::types::Stage;

/// What the shader's own `main` is renamed to.
const RENAMED_MAIN: &str = "strata_struct_main";

/// A member of a structure: its name, and its declaration's type with an array size if any.
type Member = (String, String);

/// The members of structure `s`, or why it cannot be a varying.
fn members(s: &ast::StructSpecifier) -> Result<Vec<Member>, String> {
    let mut out = Vec::new();
    for f in &s.fields {
        if matches!(f.ty.ty.content, T::Struct(_) | T::TypeName(_)) {
            return Err("0: structure varyings holding structures are not supported yet".into());
        }
        let mut ty = String::new();
        let _ = show_type_specifier(&mut ty, &f.ty, &mut FormattingState::default());
        for id in &f.identifiers {
            let mut arr = String::new();
            if let Some(a) = &id.array_spec {
                let _ = show_array_spec(&mut arr, a, &mut FormattingState::default());
            }
            out.push((id.ident.0.to_string(), format!("{ty}|{arr}")));
        }
    }
    Ok(out)
}

/// Whether a qualifier list makes a varying of `stage` (`in` of a fragment shader, `out` of a
/// vertex shader).
fn is_varying(q: Option<&ast::TypeQualifier>, stage: Stage) -> bool {
    let want = if stage == Stage::Fragment { ast::StorageQualifierData::In } else { ast::StorageQualifierData::Out };
    q.is_some_and(|q| {
        q.qualifiers.iter().any(|s| matches!(&s.content, ast::TypeQualifierSpecData::Storage(st) if st.content == want))
    })
}

/// Parses generated declarations.
fn parse(text: &str) -> Result<Vec<ast::ExternalDeclaration>, String> {
    ast::TranslationUnit::parse(text)
        .map(|tu| tu.0)
        .map_err(|e| format!("0: internal error: a generated structure varying does not parse: {e}"))
}

/// Flattens the structure varyings of `tu`, a GLSL ES 3.00 shader of `stage`.
pub(super) fn flatten(stage: Stage, tu: &mut ast::TranslationUnit) -> Result<(), String> {
    let mut structs: HashMap<String, Vec<Member>> = HashMap::new();
    let mut out = Vec::with_capacity(tu.0.len());
    // (the member's varying, the member as the private global's)
    let mut copies: Vec<(String, String)> = Vec::new();
    for decl in std::mem::take(&mut tu.0) {
        let ast::ExternalDeclarationData::Declaration(d) = &decl.content else {
            out.push(decl);
            continue;
        };
        let ast::DeclarationData::InitDeclaratorList(list) = &d.content else {
            out.push(decl);
            continue;
        };
        let head = &list.head;
        let fields = match &head.ty.ty.ty.content {
            T::Struct(s) => {
                let m = members(s);
                if let (Some(n), Ok(m)) = (&s.name, &m) {
                    structs.insert(n.0.to_string(), m.clone());
                }
                Some(m)
            }
            T::TypeName(n) => structs.get(n.0.as_str()).cloned().map(Ok),
            _ => None,
        };
        let qualifier = head.ty.qualifier.as_ref();
        let (Some(fields), true) = (fields, is_varying(qualifier, stage)) else {
            out.push(decl);
            continue;
        };
        let fields = fields?;
        if head.array_specifier.is_some()
            || head.ty.ty.array_specifier.is_some()
            || list.tail.iter().any(|t| t.ident.array_spec.is_some())
        {
            return Err("0: arrays of structure varyings are not supported yet".into());
        }
        let mut q = String::new();
        if let Some(q0) = qualifier {
            let _ = show_type_qualifier(&mut q, q0, &mut FormattingState::default());
        }
        let names: Vec<String> = head
            .name
            .iter()
            .map(|n| n.0.to_string())
            .chain(list.tail.iter().map(|t| t.ident.ident.0.to_string()))
            .collect();
        // The private global (and the structure, where declared here), without the qualifiers.
        let mut private = list.clone();
        private.head.ty.qualifier = None;
        let mut private_decl = decl.clone();
        if let ast::ExternalDeclarationData::Declaration(pd) = &mut private_decl.content {
            pd.content = ast::DeclarationData::InitDeclaratorList(private);
        }
        out.push(private_decl);
        let mut text = String::new();
        for name in &names {
            for (member, ty) in &fields {
                let (ty, arr) = ty.split_once('|').unwrap_or((ty, ""));
                let _ = writeln!(text, "{q} {ty} {name}__{member}{arr};");
                copies.push((format!("{name}__{member}"), format!("{name}.{member}")));
            }
        }
        out.extend(parse(&text)?);
    }
    tu.0 = out;
    if copies.is_empty() {
        return Ok(());
    }
    for decl in &mut tu.0 {
        if let ast::ExternalDeclarationData::FunctionDefinition(f) = &mut decl.content {
            if f.prototype.name.0 == "main" {
                f.prototype.name = ast::IdentifierData(RENAMED_MAIN.into()).into();
            }
        }
    }
    let steps: String = copies
        .iter()
        .map(|(v, p)| if stage == Stage::Fragment { format!("{p} = {v}; ") } else { format!("{v} = {p}; ") })
        .collect();
    let main = if stage == Stage::Fragment {
        format!("void main() {{ {steps}{RENAMED_MAIN}(); }}")
    } else {
        format!("void main() {{ {RENAMED_MAIN}(); {steps}}}")
    };
    tu.0.extend(parse(&main)?);
    Ok(())
}

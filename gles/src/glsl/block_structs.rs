//! Uniform block members of structure types (GLSL ES 3.00 §4.3.7): `uniform B { S s; S a[2]; }`.
//! GL lists each leaf as an active uniform of the block (`B.s.x`, `B.a[1].m`) at its std140
//! offset (ES 3.0 §2.12.6.4: a structure is aligned to a `vec4`, and so is what follows it), so
//! `blocks` lays the block out leaf by leaf: each leaf is a member of its own (`s__x`, named by
//! [`structs::ident`]) at its offset, padded to it where the structure's rounding leaves a gap.
//! Each access of a leaf through constant indices reads that member; where the shader uses a
//! structure otherwise (whole, or through an index that is not constant), a private global of
//! it (`b__s` for `b.s`, or `s` in a block without an instance name) stands for it, filled from
//! the leaves by a generated `main` before the shader's own runs.

use std::collections::{HashMap, HashSet};

use glsl_lang::ast::{self, ExprData, TypeSpecifierNonArrayData as T};
use glsl_lang::visitor::HostMut;

use crate::glsl::consts::Val;
use crate::glsl::structs::{self, fill, ident, var, wrap_main, Paths, Structs};
use crate::glsl::types::Block;

/// What the shader's own `main` is renamed to.
const RENAMED_MAIN: &str = "strata_block_main";

/// The private global that stands for structure member `member` of `block`.
fn private_name(block: &Block, member: &str) -> String {
    match &block.instance {
        Some(i) => format!("{i}__{member}"),
        None => member.to_string(),
    }
}

/// The declarations of the private globals of `block`'s structure members.
pub(super) fn privates(block: &Block) -> Vec<ast::ExternalDeclaration> {
    let mut out = Vec::new();
    for (member, ty, array) in &block.structs {
        let spec = ast::TypeSpecifierData {
            ty: T::TypeName(ast::TypeNameData(ty.as_str().into()).into()).into(),
            array_specifier: None,
        };
        let dims = array.map(|n| {
            let e: ast::Expr = ExprData::IntConst(n as i32).into();
            ast::ArraySpecifierData {
                dimensions: vec![ast::ArraySpecifierDimensionData::ExplicitlySized(Box::new(e)).into()],
            }
            .into()
        });
        let head = ast::SingleDeclarationData {
            ty: ast::FullySpecifiedTypeData { qualifier: None, ty: spec.into() }.into(),
            name: Some(ast::IdentifierData(private_name(block, member).into()).into()),
            array_specifier: dims,
            initializer: None,
        };
        let list = ast::InitDeclaratorListData { head: head.into(), tail: Vec::new() };
        let decl = ast::DeclarationData::InitDeclaratorList(list.into());
        out.push(ast::ExternalDeclarationData::Declaration(decl.into()).into());
    }
    out
}

/// Points the accesses of `blocks`' structure members in `body` at their leaves, and fills the
/// private globals of those used otherwise.
pub(super) fn rewrite(
    body: &mut ast::TranslationUnit,
    blocks: &[Block],
    structs: &Structs,
    consts: &HashMap<String, Val>,
) -> Result<(), String> {
    let mut paths = Paths {
        leaves: HashMap::new(),
        samplers: HashSet::new(),
        roots: HashSet::new(),
        whole: HashSet::new(),
        consts,
        error: None,
        shadow: HashSet::new(),
    };
    // The structure type and filling steps of each root, by its access.
    let mut fills: HashMap<String, (String, String)> = HashMap::new();
    for b in blocks.iter().filter(|b| !b.structs.is_empty()) {
        let through = |name: &str| match &b.instance {
            Some(i) => format!("{i}.{name}"),
            None => name.to_string(),
        };
        let read = |name: &str| -> ast::Expr {
            match &b.instance {
                Some(i) => ExprData::Dot(Box::new(var(i)), ast::IdentifierData(ident(name).into()).into()).into(),
                None => var(&ident(name)),
            }
        };
        for (member, ty, _) in &b.structs {
            let private = private_name(b, member);
            let mut steps = String::new();
            let prefix = format!("{member}.");
            let prefix_element = format!("{member}[");
            for m in b.members.iter().filter(|m| m.name.starts_with(&prefix) || m.name.starts_with(&prefix_element)) {
                paths.leaves.insert(through(&m.name), read(&m.name));
                let to = format!("{private}{}", &m.name[member.len()..]);
                fill(&mut steps, &to, &through(&ident(&m.name)), m.array);
            }
            paths.roots.insert(through(member));
            fills.insert(through(member), (ty.clone(), steps));
        }
    }
    if paths.roots.is_empty() {
        return Ok(());
    }
    body.visit_mut(&mut paths);
    if let Some(e) = paths.error {
        return Err(e);
    }
    let mut whole: Vec<&String> = paths.whole.iter().collect();
    whole.sort();
    let mut steps = String::new();
    for root in whole {
        let Some((ty, fill)) = fills.get(root) else { continue };
        if structs::holds_unheld(structs, ty) {
            return Err(format!(
                "0: the uniform block member `{root}' holds matrices of two rows, and is used other than member by member through constant indices: not supported yet"
            ));
        }
        steps.push_str(fill);
    }
    if !steps.is_empty() {
        wrap_main(body, RENAMED_MAIN, &steps)?;
    }
    Ok(())
}

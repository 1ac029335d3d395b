//! GLSL ES 3.00 arrays of uniform blocks (§4.3.7): `uniform B { … } b[N];` declares N blocks,
//! which GL names `B[0]` … `B[N-1]` and binds one by one. An index into such an array must be
//! a constant integral expression (§4.3.7), so each element becomes a block of its own before
//! the blocks are lifted (`B__k`, instance `b__k`: names with two underscores in a row, which
//! GLSL ES reserves) and each `b[k]` names its element's instance.

use std::collections::HashMap;

use glsl_lang::ast::{self, ExprData, TypeQualifierSpecData};
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};

use crate::glsl::blocks::{element_name, Element, Elements, MAX_COMBINED_UNIFORM_BLOCKS};
use crate::glsl::consts::{fold, Val};

/// An identifier node.
fn ident(name: &str) -> ast::Identifier {
    ast::IdentifierData::from(name).into()
}

/// The values of the shader's global constants that fold, by name (with the built-in ones).
pub(super) fn global_ints(tu: &ast::TranslationUnit, version: u16) -> HashMap<String, Val> {
    let mut consts = crate::glsl::consts::seeded(version);
    for decl in &tu.0 {
        let ast::ExternalDeclarationData::Declaration(d) = &decl.content else { continue };
        let ast::DeclarationData::InitDeclaratorList(list) = &d.content else { continue };
        if !crate::glsl::checks::is_const(list.head.ty.qualifier.as_ref()) {
            continue;
        }
        let named = list.head.name.as_ref().map(|n| (n, list.head.initializer.as_ref()));
        for (name, init) in named.into_iter().chain(list.tail.iter().map(|t| (&t.ident.ident, t.initializer.as_ref())))
        {
            if let Some(ast::InitializerData::Simple(e)) = init.map(|i| &i.content) {
                if let Some(v) = fold(e, &consts) {
                    consts.insert(name.0.to_string(), v);
                }
            }
        }
    }
    consts
}

/// Splits every array of uniform blocks of `tu` into its elements and points each indexed use
/// at its element; what it made, for naming the blocks as GL does.
pub(super) fn split(tu: &mut ast::TranslationUnit, version: u16) -> Result<Elements, String> {
    let consts = global_ints(tu, version);
    let mut elements = Elements::new();
    // Each array's block name and length, by instance name.
    let mut arrays: HashMap<String, (String, u32)> = HashMap::new();
    let mut out = Vec::with_capacity(tu.0.len());
    for decl in std::mem::take(&mut tu.0) {
        let arrayed = match &decl.content {
            ast::ExternalDeclarationData::Declaration(d) => match &d.content {
                ast::DeclarationData::Block(b) if is_uniform(b) => {
                    b.identifier.as_ref().filter(|id| id.array_spec.is_some()).map(|id| (b, id))
                }
                _ => None,
            },
            _ => None,
        };
        let Some((b, id)) = arrayed else {
            out.push(decl);
            continue;
        };
        let len = match crate::glsl::consts::array_len(id.array_spec.as_ref(), &consts) {
            Ok(Some(n)) if n as usize <= MAX_COMBINED_UNIFORM_BLOCKS => n,
            Ok(_) => {
                return Err(format!(
                    "error: the array of uniform blocks `{}' has more than {MAX_COMBINED_UNIFORM_BLOCKS} elements",
                    b.name.0
                ))
            }
            Err(e) if e.contains("unsized") => {
                return Err(format!("0: the array of uniform blocks `{}' must have a size", b.name.0))
            }
            Err(e) => return Err(e),
        };
        let instance = id.ident.0.to_string();
        for k in 0..len {
            let mut element = b.clone();
            element.name = ident(&element_name(&b.name.0, k));
            element.identifier =
                Some(ast::ArrayedIdentifierData { ident: ident(&element_name(&instance, k)), array_spec: None }.into());
            let element_of = Element { base: b.name.0.to_string(), index: k, referenced: false };
            elements.insert(element_name(&b.name.0, k), element_of);
            let mut d = decl.clone();
            if let ast::ExternalDeclarationData::Declaration(dd) = &mut d.content {
                dd.content = ast::DeclarationData::Block(element);
            }
            out.push(d);
        }
        arrays.insert(instance, (b.name.0.to_string(), len));
    }
    tu.0 = out;
    if arrays.is_empty() {
        return Ok(elements);
    }
    let mut indexing = Indexing { arrays, consts, error: None, indexed: Vec::new() };
    tu.visit_mut(&mut indexing);
    if let Some(e) = indexing.error {
        return Err(e);
    }
    for name in indexing.indexed {
        if let Some(e) = elements.get_mut(&name) {
            e.referenced = true;
        }
    }
    Ok(elements)
}

/// Points each `b[k]` of an array of blocks at its element, checking `k`.
struct Indexing {
    /// Each array's block name and length, by instance name.
    arrays: HashMap<String, (String, u32)>,
    consts: HashMap<String, Val>,
    error: Option<String>,
    /// The element blocks indexed (`B__k`).
    indexed: Vec<String>,
}

impl VisitorMut for Indexing {
    fn visit_expr(&mut self, e: &mut ast::Expr) -> Visit {
        let element = match &e.content {
            ExprData::Bracket(base, index) => match &base.content {
                ExprData::Variable(id) => match self.arrays.get(id.0.as_str()) {
                    Some((block, len)) => match fold(index, &self.consts) {
                        Some(Val::Int(k)) if (0..i64::from(*len)).contains(&k) => {
                            self.indexed.push(element_name(block, k as u32));
                            Some(element_name(&id.0, k as u32))
                        }
                        Some(Val::Int(k)) => {
                            let msg =
                                format!("0: index {k} is out of bounds of the array of uniform blocks `{}'", id.0);
                            self.error.get_or_insert(msg);
                            return Visit::Parent;
                        }
                        _ => {
                            let msg = format!(
                                "0: the array of uniform blocks `{}' must be indexed by a constant integral expression",
                                id.0
                            );
                            self.error.get_or_insert(msg);
                            return Visit::Parent;
                        }
                    },
                    None => None,
                },
                _ => None,
            },
            // A whole array of blocks is no value.
            ExprData::Variable(id) if self.arrays.contains_key(id.0.as_str()) => {
                let msg = format!("0: the array of uniform blocks `{}' may only be indexed", id.0);
                self.error.get_or_insert(msg);
                return Visit::Parent;
            }
            _ => None,
        };
        match element {
            Some(name) => {
                e.content = ExprData::Variable(ident(&name));
                Visit::Parent
            }
            None => Visit::Children,
        }
    }
}

/// Whether a block declaration is a `uniform` block.
fn is_uniform(b: &ast::Block) -> bool {
    b.qualifier.qualifiers.iter().any(|s| {
        matches!(&s.content, TypeQualifierSpecData::Storage(st) if st.content == ast::StorageQualifierData::Uniform)
    })
}

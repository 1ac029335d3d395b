//! GLSL ES 3.00 arrays declared without a size and sized by their initializer (§4.1.9):
//! `float x[] = float[2](…)`, `float y[] = float[](a, b, c)`, `float b[] = a` take the size
//! of the constructor, its arguments, or the array they copy. naga has no such declarations,
//! so each gets its size written out, in the declaration and in an unsized constructor, before
//! the shader is translated.

use std::collections::HashMap;

use glsl_lang::ast::{self, ArraySpecifierDimensionData as Dim, ExprData};
use glsl_lang::visitor::{HostMut, Visit, VisitorMut};

/// The sizes of the arrays declared so far, by name (later declarations of a name win).
#[derive(Default)]
struct Sizes(HashMap<String, u32>);

/// An explicit size of one dimension.
fn sized(n: u32) -> ast::ArraySpecifier {
    let e: ast::Expr = ExprData::IntConst(n as i32).into();
    ast::ArraySpecifierData { dimensions: vec![Dim::ExplicitlySized(Box::new(e)).into()] }.into()
}

/// Whether `spec` is one unsized dimension.
fn no_size(spec: Option<&ast::ArraySpecifier>) -> bool {
    spec.is_some_and(|s| matches!(s.dimensions.as_slice(), [d] if matches!(d.content, Dim::Unsized)))
}

/// The size of a one-dimension explicit specifier that is an integer literal.
fn literal(spec: Option<&ast::ArraySpecifier>) -> Option<u32> {
    match spec?.dimensions.as_slice() {
        [d] => match &d.content {
            Dim::ExplicitlySized(e) => match e.content {
                ExprData::IntConst(n) => u32::try_from(n).ok(),
                ExprData::UIntConst(n) => Some(n),
                _ => None,
            },
            Dim::Unsized => None,
        },
        _ => None,
    }
}

impl Sizes {
    /// The size `init` gives an unsized array; an unsized array constructor in it gets its size.
    fn of(&self, init: &mut ast::Initializer) -> Option<u32> {
        let ast::InitializerData::Simple(e) = &mut init.content else { return None };
        match &mut e.content {
            ExprData::FunCall(f, args) => {
                let ast::FunIdentifierData::TypeSpecifier(ts) = &mut f.content else { return None };
                if no_size(ts.array_specifier.as_ref()) {
                    let n = args.len() as u32;
                    ts.array_specifier = Some(sized(n));
                    return Some(n);
                }
                literal(ts.array_specifier.as_ref())
            }
            ExprData::Variable(id) => self.0.get(id.0.as_str()).copied(),
            _ => None,
        }
    }
}

impl VisitorMut for Sizes {
    fn visit_init_declarator_list(&mut self, list: &mut ast::InitDeclaratorList) -> Visit {
        let head = &mut list.head;
        if let Some(name) = head.name.as_ref().map(|n| n.0.to_string()) {
            let on_name = no_size(head.array_specifier.as_ref());
            let on_type = no_size(head.ty.ty.array_specifier.as_ref());
            if let (true, Some(init)) = (on_name || on_type, head.initializer.as_mut()) {
                if let Some(n) = self.of(init) {
                    if on_name {
                        head.array_specifier = Some(sized(n));
                    } else {
                        head.ty.ty.array_specifier = Some(sized(n));
                    }
                }
            }
            let n = literal(head.array_specifier.as_ref()).or(literal(head.ty.ty.array_specifier.as_ref()));
            if let Some(n) = n {
                self.0.insert(name, n);
            }
        }
        for t in &mut list.tail {
            if let (true, Some(init)) = (no_size(t.ident.array_spec.as_ref()), t.initializer.as_mut()) {
                if let Some(n) = self.of(init) {
                    t.ident.array_spec = Some(sized(n));
                }
            }
            if let Some(n) = literal(t.ident.array_spec.as_ref()) {
                self.0.insert(t.ident.ident.0.to_string(), n);
            }
        }
        Visit::Children
    }
}

/// Writes out the sizes of `tu`'s arrays sized by their initializers.
pub(super) fn size(tu: &mut ast::TranslationUnit) {
    tu.visit_mut(&mut Sizes::default());
}

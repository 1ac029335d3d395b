//! The file-level import graph of one crate: an edge A -> B for every path written in A that
//! resolves to an item defined in B.

use std::collections::{BTreeMap, BTreeSet, HashSet};
use std::path::{Path, PathBuf};

use syn::visit::{self, Visit};
use syn::{Attribute, Item};

use crate::error::ArchError;
use crate::modules::{flatten_use, is_reexport, is_test_only, Binding, FileId, ModId, ModuleTree, UseLeaf};
use crate::resolve::{Res, Resolver, Want};
use crate::scan::token_paths;

/// An edge between two files, with the names that caused it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The file whose paths name the items.
    pub from: PathBuf,
    /// The file that defines them.
    pub to: PathBuf,
    /// The names, sorted.
    pub names: Vec<String>,
}

/// The import graph of one crate; paths are relative to the crate root's directory.
#[derive(Clone, Debug, Default)]
pub struct FileGraph {
    /// Every file of the crate compiled outside tests, in module-tree order.
    pub files: Vec<PathBuf>,
    /// Every edge, sorted by file pair.
    pub edges: Vec<Edge>,
}

/// The import graph of the crate whose root file is `root` (`src/lib.rs` or `src/main.rs`).
pub fn crate_graph(root: &Path) -> Result<FileGraph, ArchError> {
    let tree = ModuleTree::build(root)?;
    let resolver = Resolver::new(&tree);
    let mut edges: BTreeMap<(FileId, FileId), BTreeSet<String>> = BTreeMap::new();
    for (id, file) in tree.files.iter().enumerate() {
        let mut v = EdgeVisitor {
            tree: &tree,
            resolver: &resolver,
            file: id,
            module: file.top,
            scopes: Vec::new(),
            locals: Vec::new(),
            block_depth: 0,
            edges: &mut edges,
        };
        for item in &file.ast.items {
            v.visit_item(item);
        }
    }
    let files: Vec<PathBuf> = tree.files.iter().map(|f| f.rel.clone()).collect();
    let edges = edges
        .into_iter()
        .map(|((from, to), names)| Edge {
            from: files[from].clone(),
            to: files[to].clone(),
            names: names.into_iter().collect(),
        })
        .collect();
    Ok(FileGraph { files, edges })
}

/// The `use` leaves of one block: they shadow the module's names inside it.
#[derive(Default)]
struct LocalScope {
    /// Bound names and the paths they stand for.
    named: Vec<(String, Vec<String>)>,
    /// Glob imports' module paths.
    globs: Vec<Vec<String>>,
}

/// Walks one file's syntax tree, resolving every path and recording edges.
struct EdgeVisitor<'a> {
    /// The crate's module tree.
    tree: &'a ModuleTree,
    /// Path resolution over the tree.
    resolver: &'a Resolver<'a>,
    /// The file being walked.
    file: FileId,
    /// The module whose items are being walked (inline modules change it).
    module: ModId,
    /// `use` declarations of the enclosing blocks, innermost last.
    scopes: Vec<LocalScope>,
    /// The lower-case names bound by patterns in each enclosing function, innermost last.
    locals: Vec<HashSet<String>>,
    /// How many blocks enclose the current item (0 at module level).
    block_depth: usize,
    /// The edges found so far, over every file.
    edges: &'a mut BTreeMap<(FileId, FileId), BTreeSet<String>>,
}

/// The attributes of an item.
fn item_attrs(item: &Item) -> &[Attribute] {
    match item {
        Item::Const(i) => &i.attrs,
        Item::Enum(i) => &i.attrs,
        Item::ExternCrate(i) => &i.attrs,
        Item::Fn(i) => &i.attrs,
        Item::ForeignMod(i) => &i.attrs,
        Item::Impl(i) => &i.attrs,
        Item::Macro(i) => &i.attrs,
        Item::Mod(i) => &i.attrs,
        Item::Static(i) => &i.attrs,
        Item::Struct(i) => &i.attrs,
        Item::Trait(i) => &i.attrs,
        Item::TraitAlias(i) => &i.attrs,
        Item::Type(i) => &i.attrs,
        Item::Union(i) => &i.attrs,
        Item::Use(i) => &i.attrs,
        _ => &[],
    }
}

/// Collects the names that patterns bind (parameters, `let`, closures, arms), skipping
/// upper-case ones, which are constants, unit structs or variants matched by name.
#[derive(Default)]
struct Binders(HashSet<String>);

impl<'ast> Visit<'ast> for Binders {
    fn visit_pat_ident(&mut self, pat: &'ast syn::PatIdent) {
        let name = pat.ident.to_string();
        if name.starts_with(|c: char| c.is_lowercase() || c == '_') {
            self.0.insert(name);
        }
        visit::visit_pat_ident(self, pat);
    }

    fn visit_item(&mut self, _item: &'ast Item) {}
}

/// The segments of a path, as strings.
fn segments(path: &syn::Path) -> Vec<String> {
    path.segments.iter().map(|s| s.ident.to_string()).collect()
}

impl EdgeVisitor<'_> {
    /// Resolves `segs` in the current context, using the `use` declarations of the innermost
    /// `limit` enclosing blocks before the module's names.
    fn resolve(&self, segs: &[String], last: Want, macro_path: bool, limit: usize) -> Option<Res> {
        let first = segs.first()?;
        let keyword = matches!(first.as_str(), "crate" | "$crate" | "self" | "super" | "Self");
        if !keyword {
            for depth in (0..limit.min(self.scopes.len())).rev() {
                let scope = &self.scopes[depth];
                if let Some((_, path)) = scope.named.iter().rev().find(|(n, _)| n == first) {
                    let mut expanded = path.clone();
                    expanded.extend_from_slice(&segs[1..]);
                    return self.resolve(&expanded, last, macro_path, depth);
                }
                let want = if segs.len() == 1 { last } else { Want::Module };
                for glob in &scope.globs {
                    if let Some(Res::Module(g)) = self.resolve(glob, Want::Module, false, depth) {
                        if let Some(start) = self.resolver.lookup(g, first, want) {
                            return self.resolver.walk(start, &segs[1..], last);
                        }
                    }
                }
            }
        }
        self.resolver.resolve(self.module, segs, last, macro_path)
    }

    /// Records the edge a resolution makes from the current file, under `name`.
    fn add_edge(&mut self, res: &Res, name: String) {
        let Some(target) = self.resolver.res_file(res) else { return };
        if target != self.file {
            self.edges.entry((self.file, target)).or_default().insert(name);
        }
    }

    /// Resolves a path written in the file and records its edge. A lone segment naming a
    /// module is a local variable of the same name, not a path (modules are not values).
    fn record(&mut self, segs: &[String], macro_path: bool) {
        if let Some(res) = self.resolve(segs, Want::Any, macro_path, usize::MAX) {
            if segs.len() == 1 && matches!(res, Res::Module(_)) {
                return;
            }
            let name = self.resolver.res_name(&res);
            self.add_edge(&res, name);
        }
    }

    /// Records the edges of one `use` declaration (its leaves resolved outside its own block).
    fn record_use(&mut self, tree: &syn::UseTree) {
        let limit = self.scopes.len().saturating_sub(1);
        for leaf in flatten_use(tree) {
            match leaf {
                UseLeaf::Named { path, .. } => {
                    if let Some(res) = self.resolve(&path, Want::Any, false, limit) {
                        let name = self.resolver.res_name(&res);
                        self.add_edge(&res, name);
                    }
                }
                UseLeaf::Glob { prefix } => {
                    if let Some(res) = self.resolve(&prefix, Want::Module, false, limit) {
                        let name = format!("{}::*", prefix.last().map_or("", String::as_str));
                        self.add_edge(&res, name);
                    }
                }
            }
        }
    }

    /// Walks a function's signature and body with the names its patterns bind as locals.
    fn in_function(&mut self, sig: &syn::Signature, body: Option<&syn::Block>) {
        let mut binders = Binders::default();
        binders.visit_signature(sig);
        if let Some(body) = body {
            binders.visit_block(body);
        }
        self.locals.push(binders.0);
        self.visit_signature(sig);
        if let Some(body) = body {
            self.visit_block(body);
        }
        self.locals.pop();
    }

    /// Whether a lone name is a local binding of an enclosing function.
    fn is_local(&self, path: &syn::Path) -> bool {
        path.segments.len() == 1
            && path.get_ident().is_some_and(|id| {
                let name = id.to_string();
                self.locals.iter().any(|l| l.contains(&name))
            })
    }

    /// Records a path with an optional qualified self (`<T as Trait>::f`): only the trait part
    /// is a path to resolve.
    fn record_qualified(&mut self, qself: Option<&syn::QSelf>, path: &syn::Path) {
        match qself {
            None => {
                if path.leading_colon.is_none() {
                    self.record(&segments(path), false);
                }
            }
            Some(q) => {
                self.visit_type(&q.ty);
                if q.position > 0 && path.leading_colon.is_none() {
                    let segs = segments(path);
                    self.record(&segs[..q.position.min(segs.len())], false);
                }
            }
        }
    }
}

impl<'ast> Visit<'ast> for EdgeVisitor<'_> {
    fn visit_item(&mut self, item: &'ast Item) {
        if !is_test_only(item_attrs(item)) {
            visit::visit_item(self, item);
        }
    }

    fn visit_item_mod(&mut self, item: &'ast syn::ItemMod) {
        let Some((_, items)) = &item.content else { return };
        let name = item.ident.to_string();
        let child = self.tree.modules[self.module].bindings.get(&name).and_then(|bs| {
            bs.iter().find_map(|b| match b {
                Binding::Module(m) if self.tree.modules[*m].file == self.file => Some(*m),
                _ => None,
            })
        });
        match child {
            Some(child) if self.block_depth == 0 => {
                let outer = std::mem::replace(&mut self.module, child);
                for item in items {
                    self.visit_item(item);
                }
                self.module = outer;
            }
            _ => items.iter().for_each(|i| self.visit_item(i)),
        }
    }

    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        if item.leading_colon.is_some() || (self.block_depth == 0 && is_reexport(&item.vis)) {
            return;
        }
        self.record_use(&item.tree);
    }

    fn visit_block(&mut self, block: &'ast syn::Block) {
        let mut scope = LocalScope::default();
        for stmt in &block.stmts {
            if let syn::Stmt::Item(Item::Use(u)) = stmt {
                if u.leading_colon.is_some() || is_test_only(&u.attrs) {
                    continue;
                }
                for leaf in flatten_use(&u.tree) {
                    match leaf {
                        UseLeaf::Named { name: Some(name), path } => scope.named.push((name, path)),
                        UseLeaf::Named { name: None, .. } => {}
                        UseLeaf::Glob { prefix } => scope.globs.push(prefix),
                    }
                }
            }
        }
        self.scopes.push(scope);
        self.block_depth += 1;
        visit::visit_block(self, block);
        self.block_depth -= 1;
        self.scopes.pop();
    }

    fn visit_impl_item(&mut self, item: &'ast syn::ImplItem) {
        let attrs = match item {
            syn::ImplItem::Const(i) => &i.attrs,
            syn::ImplItem::Fn(i) => &i.attrs,
            syn::ImplItem::Type(i) => &i.attrs,
            syn::ImplItem::Macro(i) => &i.attrs,
            _ => return visit::visit_impl_item(self, item),
        };
        if !is_test_only(attrs) {
            visit::visit_impl_item(self, item);
        }
    }

    fn visit_trait_item(&mut self, item: &'ast syn::TraitItem) {
        let attrs = match item {
            syn::TraitItem::Const(i) => &i.attrs,
            syn::TraitItem::Fn(i) => &i.attrs,
            syn::TraitItem::Type(i) => &i.attrs,
            syn::TraitItem::Macro(i) => &i.attrs,
            _ => return visit::visit_trait_item(self, item),
        };
        if !is_test_only(attrs) {
            visit::visit_trait_item(self, item);
        }
    }

    fn visit_field(&mut self, field: &'ast syn::Field) {
        if !is_test_only(&field.attrs) {
            visit::visit_field(self, field);
        }
    }

    fn visit_variant(&mut self, variant: &'ast syn::Variant) {
        if !is_test_only(&variant.attrs) {
            visit::visit_variant(self, variant);
        }
    }

    fn visit_arm(&mut self, arm: &'ast syn::Arm) {
        if !is_test_only(&arm.attrs) {
            visit::visit_arm(self, arm);
        }
    }

    fn visit_local(&mut self, local: &'ast syn::Local) {
        if !is_test_only(&local.attrs) {
            visit::visit_local(self, local);
        }
    }

    fn visit_stmt_macro(&mut self, mac: &'ast syn::StmtMacro) {
        if !is_test_only(&mac.attrs) {
            visit::visit_stmt_macro(self, mac);
        }
    }

    fn visit_visibility(&mut self, _vis: &'ast syn::Visibility) {}

    fn visit_attribute(&mut self, _attr: &'ast Attribute) {}

    fn visit_path(&mut self, path: &'ast syn::Path) {
        self.record_qualified(None, path);
        visit::visit_path(self, path);
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        self.in_function(&f.sig, Some(&f.block));
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.in_function(&f.sig, Some(&f.block));
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        self.in_function(&f.sig, f.default.as_ref());
    }

    fn visit_expr_path(&mut self, expr: &'ast syn::ExprPath) {
        if expr.qself.is_some() || !self.is_local(&expr.path) {
            self.record_qualified(expr.qself.as_ref(), &expr.path);
        }
        visit::visit_path(self, &expr.path);
    }

    fn visit_type_path(&mut self, ty: &'ast syn::TypePath) {
        self.record_qualified(ty.qself.as_ref(), &ty.path);
        visit::visit_path(self, &ty.path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        if mac.path.leading_colon.is_none() {
            self.record(&segments(&mac.path), true);
        }
        for path in token_paths(mac.tokens.clone()) {
            self.record(&path, false);
        }
    }
}

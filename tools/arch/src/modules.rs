//! The module tree of one crate: which file holds each module, and the names each module
//! defines, imports and re-exports.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use syn::{Attribute, Item, UseTree, Visibility};

use crate::error::{read_to_string, ArchError};

/// Index of a module in [`ModuleTree::modules`].
pub(crate) type ModId = usize;
/// Index of a file in [`ModuleTree::files`].
pub(crate) type FileId = usize;
/// Index of an import in [`ModuleTree::imports`].
pub(crate) type ImportId = usize;

/// What a name in a module stands for.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Binding {
    /// A child module (file or inline).
    Module(ModId),
    /// An item defined in the module, held by this file.
    Item(FileId),
    /// A `use` declaration; resolved on demand.
    Import(ImportId),
}

/// One leaf of a `use` tree.
#[derive(Clone, Debug)]
pub(crate) enum UseLeaf {
    /// `a::b::C` or `a::b::C as D`: the bound name (`None` for `as _`) and the full path.
    Named {
        /// The name the declaration binds, if any.
        name: Option<String>,
        /// The path it names.
        path: Vec<String>,
    },
    /// `a::b::*`: the path of the module whose names are imported.
    Glob {
        /// The module's path.
        prefix: Vec<String>,
    },
}

/// A `use` declaration's leaf, as the module tree keeps it.
#[derive(Clone, Debug)]
pub(crate) struct Import {
    /// The module the declaration is written in; its path is resolved there.
    pub module: ModId,
    /// The path it names (for a glob: the module whose names it imports).
    pub path: Vec<String>,
}

/// A module: its place in the tree, its file and its names.
#[derive(Debug)]
pub(crate) struct Module {
    /// The module's own name (`crate` for the root).
    pub name: String,
    /// The enclosing module; `None` for the crate root.
    pub parent: Option<ModId>,
    /// The file holding the module's items.
    pub file: FileId,
    /// Every name the module defines or imports, in each namespace it has.
    pub bindings: HashMap<String, Vec<Binding>>,
    /// Glob imports (`use x::*`), in order.
    pub globs: Vec<ImportId>,
    /// `macro_rules!` macros in textual scope: inherited ones first, then the module's own.
    pub macros: Vec<(String, FileId)>,
}

/// A parsed source file of the crate.
pub(crate) struct ParsedFile {
    /// The path relative to the crate root's directory.
    pub rel: PathBuf,
    /// The syntax tree.
    pub ast: syn::File,
    /// The module whose top level the file is.
    pub top: ModId,
}

/// The module tree of one crate, built from its root file by following `mod` declarations.
pub(crate) struct ModuleTree {
    /// Every file of the crate that is compiled outside tests.
    pub files: Vec<ParsedFile>,
    /// Every module; the root is module 0.
    pub modules: Vec<Module>,
    /// Every `use` leaf of every module.
    pub imports: Vec<Import>,
}

/// Where `mod name;` declarations in the current context look for their files.
struct DirCtx {
    /// The directory of the source file.
    file_dir: PathBuf,
    /// The directory that `mod name;` looks in.
    child_dir: PathBuf,
    /// How many inline `mod x { }` blocks enclose the current items.
    inline_depth: usize,
}

/// Whether an item is compiled only for tests (`#[cfg(test)]` or `#[cfg(all(test, ..))]`).
pub(crate) fn is_test_only(attrs: &[Attribute]) -> bool {
    attrs.iter().any(|attr| attr.path().is_ident("cfg") && attr.parse_args::<syn::Meta>().is_ok_and(|m| needs_test(&m)))
}

/// Whether a `cfg` predicate can hold only when `test` does.
fn needs_test(meta: &syn::Meta) -> bool {
    match meta {
        syn::Meta::Path(p) => p.is_ident("test"),
        syn::Meta::List(list) if list.path.is_ident("all") => list
            .parse_args_with(syn::punctuated::Punctuated::<syn::Meta, syn::Token![,]>::parse_terminated)
            .is_ok_and(|parts| parts.iter().any(needs_test)),
        _ => false,
    }
}

/// The string of a `#[path = "..."]` attribute, if any.
fn path_attr(attrs: &[Attribute]) -> Option<String> {
    attrs.iter().find(|a| a.path().is_ident("path")).and_then(|a| match &a.meta {
        syn::Meta::NameValue(nv) => match &nv.value {
            syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) => Some(s.value()),
            _ => None,
        },
        _ => None,
    })
}

/// Whether the attributes include `#[name]`.
fn has_attr(attrs: &[Attribute], name: &str) -> bool {
    attrs.iter().any(|a| a.path().is_ident(name))
}

/// Whether a `use` with this visibility is a re-export (`pub use`, `pub(crate) use`).
pub(crate) fn is_reexport(vis: &Visibility) -> bool {
    match vis {
        Visibility::Public(_) => true,
        Visibility::Restricted(r) => r.path.is_ident("crate"),
        Visibility::Inherited => false,
    }
}

/// The leaves of a `use` tree, with their full paths.
pub(crate) fn flatten_use(tree: &UseTree) -> Vec<UseLeaf> {
    let mut leaves = Vec::new();
    flatten_into(tree, &mut Vec::new(), &mut leaves);
    leaves
}

/// Collects the leaves below `tree`, `prefix` being the path above it.
fn flatten_into(tree: &UseTree, prefix: &mut Vec<String>, leaves: &mut Vec<UseLeaf>) {
    match tree {
        UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            flatten_into(&p.tree, prefix, leaves);
            prefix.pop();
        }
        UseTree::Name(n) => leaves.push(named_leaf(prefix, &n.ident, Some(n.ident.to_string()))),
        UseTree::Rename(r) => {
            let name = (r.rename != "_").then(|| r.rename.to_string());
            leaves.push(named_leaf(prefix, &r.ident, name));
        }
        UseTree::Glob(_) => leaves.push(UseLeaf::Glob { prefix: prefix.clone() }),
        UseTree::Group(g) => g.items.iter().for_each(|t| flatten_into(t, prefix, leaves)),
    }
}

/// A named leaf: `self` names the prefix itself (`use a::b::{self}` binds `b`).
fn named_leaf(prefix: &[String], ident: &syn::Ident, name: Option<String>) -> UseLeaf {
    if ident == "self" && !prefix.is_empty() {
        let bound = if name.as_deref() == Some("self") { prefix.last().cloned() } else { name };
        UseLeaf::Named { name: bound, path: prefix.to_vec() }
    } else {
        let mut path = prefix.to_vec();
        path.push(ident.to_string());
        UseLeaf::Named { name, path }
    }
}

/// Parses one file.
pub(crate) fn parse_file(path: &Path) -> Result<syn::File, ArchError> {
    let text = read_to_string(path)?;
    syn::parse_file(&text).map_err(|source| ArchError::Parse { path: path.to_path_buf(), source })
}

impl ModuleTree {
    /// Builds the tree of the crate whose root file is `root` (`lib.rs` or `main.rs`).
    pub(crate) fn build(root: &Path) -> Result<Self, ArchError> {
        let base = root.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut tree = ModuleTree { files: Vec::new(), modules: Vec::new(), imports: Vec::new() };
        let ast = parse_file(root)?;
        let rel = root.strip_prefix(&base).map(Path::to_path_buf).unwrap_or_else(|_| root.to_path_buf());
        tree.modules.push(Module {
            name: "crate".to_string(),
            parent: None,
            file: 0,
            bindings: HashMap::new(),
            globs: Vec::new(),
            macros: Vec::new(),
        });
        tree.files.push(ParsedFile { rel, ast, top: 0 });
        let ctx = DirCtx { file_dir: base.clone(), child_dir: base.clone(), inline_depth: 0 };
        let mut loaded = vec![root.to_path_buf()];
        let items = std::mem::take(&mut tree.files[0].ast.items);
        let result = tree.add_items(0, 0, &items, &ctx, &base, &mut loaded);
        tree.files[0].ast.items = items;
        result.map(|()| tree)
    }

    /// Adds a binding to module `m`.
    fn bind(&mut self, m: ModId, name: String, binding: Binding) {
        self.modules[m].bindings.entry(name).or_default().push(binding);
    }

    /// Records the names of `items` (held by `file`) in module `m`, loading child modules.
    fn add_items(
        &mut self,
        m: ModId,
        file: FileId,
        items: &[Item],
        ctx: &DirCtx,
        base: &Path,
        loaded: &mut Vec<PathBuf>,
    ) -> Result<(), ArchError> {
        for item in items {
            let (attrs, ident) = match item {
                Item::Fn(i) => (&i.attrs, Some(&i.sig.ident)),
                Item::Struct(i) => (&i.attrs, Some(&i.ident)),
                Item::Enum(i) => (&i.attrs, Some(&i.ident)),
                Item::Union(i) => (&i.attrs, Some(&i.ident)),
                Item::Trait(i) => (&i.attrs, Some(&i.ident)),
                Item::TraitAlias(i) => (&i.attrs, Some(&i.ident)),
                Item::Type(i) => (&i.attrs, Some(&i.ident)),
                Item::Const(i) => (&i.attrs, Some(&i.ident)),
                Item::Static(i) => (&i.attrs, Some(&i.ident)),
                Item::Mod(i) => {
                    if !is_test_only(&i.attrs) {
                        self.add_module(m, file, i, ctx, base, loaded)?;
                    }
                    continue;
                }
                Item::Use(u) => {
                    if !is_test_only(&u.attrs) {
                        self.add_use(m, &u.tree);
                    }
                    continue;
                }
                Item::Macro(i) => {
                    if !is_test_only(&i.attrs) && i.mac.path.is_ident("macro_rules") {
                        if let Some(name) = &i.ident {
                            let name = name.to_string();
                            self.modules[m].macros.push((name.clone(), file));
                            if has_attr(&i.attrs, "macro_export") {
                                self.bind(0, name.clone(), Binding::Item(file));
                            }
                            self.bind(m, name, Binding::Item(file));
                        }
                    }
                    continue;
                }
                Item::ForeignMod(f) => {
                    if !is_test_only(&f.attrs) {
                        for fi in &f.items {
                            let ident = match fi {
                                syn::ForeignItem::Fn(f) => Some(&f.sig.ident),
                                syn::ForeignItem::Static(s) => Some(&s.ident),
                                syn::ForeignItem::Type(t) => Some(&t.ident),
                                _ => None,
                            };
                            if let Some(ident) = ident {
                                self.bind(m, ident.to_string(), Binding::Item(file));
                            }
                        }
                    }
                    continue;
                }
                _ => continue,
            };
            if let Some(ident) = ident {
                if !is_test_only(attrs) && ident != "_" {
                    self.bind(m, ident.to_string(), Binding::Item(file));
                }
            }
        }
        Ok(())
    }

    /// Records the leaves of a `use` tree declared in module `m`.
    fn add_use(&mut self, m: ModId, tree: &UseTree) {
        for leaf in flatten_use(tree) {
            match leaf {
                UseLeaf::Named { name, path } => {
                    self.imports.push(Import { module: m, path });
                    if let Some(name) = name {
                        let id = self.imports.len() - 1;
                        self.bind(m, name, Binding::Import(id));
                    }
                }
                UseLeaf::Glob { prefix } => {
                    self.imports.push(Import { module: m, path: prefix });
                    let id = self.imports.len() - 1;
                    self.modules[m].globs.push(id);
                }
            }
        }
    }

    /// Adds the module declared by `item` in module `m` (held by `file`), loading its file.
    fn add_module(
        &mut self,
        m: ModId,
        file: FileId,
        item: &syn::ItemMod,
        ctx: &DirCtx,
        base: &Path,
        loaded: &mut Vec<PathBuf>,
    ) -> Result<(), ArchError> {
        let name = item.ident.to_string();
        let inherited = self.modules[m].macros.clone();
        let path_attr = path_attr(&item.attrs);
        let child = self.modules.len();
        if let Some((_, items)) = &item.content {
            self.modules.push(Module {
                name: name.clone(),
                parent: Some(m),
                file,
                bindings: HashMap::new(),
                globs: Vec::new(),
                macros: inherited.clone(),
            });
            self.bind(m, name.clone(), Binding::Module(child));
            let child_dir = match &path_attr {
                Some(p) if ctx.inline_depth == 0 => ctx.file_dir.join(p),
                Some(p) => ctx.child_dir.join(p),
                None => ctx.child_dir.join(&name),
            };
            let inner = DirCtx { file_dir: ctx.file_dir.clone(), child_dir, inline_depth: ctx.inline_depth + 1 };
            self.add_items(child, file, items, &inner, base, loaded)?;
        } else {
            let candidates = match &path_attr {
                Some(p) if ctx.inline_depth == 0 => vec![ctx.file_dir.join(p)],
                Some(p) => vec![ctx.child_dir.join(p)],
                None => vec![ctx.child_dir.join(format!("{name}.rs")), ctx.child_dir.join(&name).join("mod.rs")],
            };
            let Some(path) = candidates.iter().find(|p| p.is_file()).cloned() else {
                let declared_in = base.join(&self.files[file].rel);
                let looked_for = candidates.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ");
                return Err(ArchError::ModuleNotFound { name, declared_in, looked_for });
            };
            if loaded.contains(&path) {
                return Ok(());
            }
            loaded.push(path.clone());
            let mut ast = parse_file(&path)?;
            let new_file = self.files.len();
            self.modules.push(Module {
                name: name.clone(),
                parent: Some(m),
                file: new_file,
                bindings: HashMap::new(),
                globs: Vec::new(),
                macros: inherited.clone(),
            });
            self.bind(m, name, Binding::Module(child));
            let items = std::mem::take(&mut ast.items);
            let rel = path.strip_prefix(base).map(Path::to_path_buf).unwrap_or_else(|_| path.clone());
            self.files.push(ParsedFile { rel, ast, top: child });
            let file_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
            let is_mod_rs = path_attr.is_some() || path.file_name().is_some_and(|f| f == "mod.rs");
            let child_dir = if is_mod_rs {
                file_dir.clone()
            } else {
                file_dir.join(path.file_stem().map(PathBuf::from).unwrap_or_default())
            };
            let inner = DirCtx { file_dir, child_dir, inline_depth: 0 };
            let result = self.add_items(child, new_file, &items, &inner, base, loaded);
            self.files[new_file].ast.items = items;
            result?;
        }
        if has_attr(&item.attrs, "macro_use") {
            let own: Vec<_> = self.modules[child].macros[inherited.len()..].to_vec();
            self.modules[m].macros.extend(own);
        }
        Ok(())
    }
}

//! The walk of `docs/architecture.md`: numbered steps naming a file and a function, from the
//! application's call to the client's image and on to the output.

use std::collections::{BTreeSet, HashMap, HashSet};
use std::path::Path;

use syn::visit::{self, Visit};

use crate::modules::is_test_only;

/// How the walk section starts.
pub const SECTION_PREFIX: &str = "## The walk of";

/// The distinct files of the walk.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WalkCounts {
    /// Distinct files to the client's image (the first subsection).
    pub image: usize,
    /// Distinct files to the output (both subsections together).
    pub output: usize,
}

/// What the walk gets wrong, and the counts computed from its steps.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WalkCheck {
    /// Each problem, in document order.
    pub problems: Vec<String>,
    /// The counts, when the section exists.
    pub counts: Option<WalkCounts>,
}

/// The function a step names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StepFn {
    /// `name`: any function or method of that name.
    Plain(String),
    /// `Type::name`: a method of `Type` (inherent or trait impl) or a trait's default method.
    Method(String, String),
    /// `name!`: a `macro_rules!` macro.
    Macro(String),
}

/// One numbered step: its line, file and function token.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// The line number in the document (1-based).
    pub line: usize,
    /// The file, relative to the repository root.
    pub file: String,
    /// The function token as written, if the step has one.
    pub function: Option<String>,
}

/// Whether `s` is a Rust identifier.
fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_alphabetic() || c == '_') && chars.all(|c| c.is_alphanumeric() || c == '_')
}

/// Parses a function token: `name`, `Type::name` or `name!`.
pub fn parse_fn(token: &str) -> Option<StepFn> {
    if let Some(name) = token.strip_suffix('!') {
        return is_ident(name).then(|| StepFn::Macro(name.to_string()));
    }
    match token.split_once("::") {
        Some((ty, name)) => (is_ident(ty) && is_ident(name)).then(|| StepFn::Method(ty.to_string(), name.to_string())),
        None => is_ident(token).then(|| StepFn::Plain(token.to_string())),
    }
}

/// Whether a line is a numbered list item (`^\d+\. `).
fn is_numbered(line: &str) -> bool {
    let digits = line.len() - line.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    digits > 0 && line[digits..].starts_with(". ")
}

/// The step on a numbered line: the first backticked token ending in `.rs` and the next one.
pub fn parse_step(line_no: usize, line: &str) -> Option<Step> {
    let tokens: Vec<&str> = line.split('`').skip(1).step_by(2).collect();
    let at = tokens.iter().position(|t| t.ends_with(".rs"))?;
    Some(Step { line: line_no, file: tokens[at].to_string(), function: tokens.get(at + 1).map(|t| t.to_string()) })
}

/// The functions, methods and macros a file defines.
#[derive(Default)]
struct Defs {
    /// Free functions (at any depth).
    fns: HashSet<String>,
    /// Methods by the last segment of their impl's self type.
    methods: HashSet<(String, String)>,
    /// Trait methods with a default body, by trait.
    defaults: HashSet<(String, String)>,
    /// `macro_rules!` macros.
    macros: HashSet<String>,
}

/// The last path segment of a type (`&mut Foo<T>` -> `Foo`).
fn type_name(ty: &syn::Type) -> Option<String> {
    match ty {
        syn::Type::Path(p) => p.path.segments.last().map(|s| s.ident.to_string()),
        syn::Type::Reference(r) => type_name(&r.elem),
        syn::Type::Paren(p) => type_name(&p.elem),
        syn::Type::Group(g) => type_name(&g.elem),
        _ => None,
    }
}

impl<'ast> Visit<'ast> for Defs {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let test_only = match item {
            syn::Item::Mod(m) => is_test_only(&m.attrs),
            syn::Item::Fn(f) => is_test_only(&f.attrs),
            syn::Item::Impl(i) => is_test_only(&i.attrs),
            _ => false,
        };
        if !test_only {
            visit::visit_item(self, item);
        }
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        self.fns.insert(f.sig.ident.to_string());
        visit::visit_item_fn(self, f);
    }

    fn visit_item_impl(&mut self, imp: &'ast syn::ItemImpl) {
        if let Some(ty) = type_name(&imp.self_ty) {
            for item in &imp.items {
                if let syn::ImplItem::Fn(f) = item {
                    self.methods.insert((ty.clone(), f.sig.ident.to_string()));
                }
            }
        }
        visit::visit_item_impl(self, imp);
    }

    fn visit_item_trait(&mut self, tr: &'ast syn::ItemTrait) {
        for item in &tr.items {
            if let syn::TraitItem::Fn(f) = item {
                if f.default.is_some() {
                    self.defaults.insert((tr.ident.to_string(), f.sig.ident.to_string()));
                }
            }
        }
        visit::visit_item_trait(self, tr);
    }

    fn visit_item_macro(&mut self, m: &'ast syn::ItemMacro) {
        if m.mac.path.is_ident("macro_rules") {
            if let Some(ident) = &m.ident {
                self.macros.insert(ident.to_string());
            }
        }
    }
}

impl Defs {
    /// Whether the file defines the function a step names.
    fn defines(&self, f: &StepFn) -> bool {
        match f {
            StepFn::Plain(name) => {
                self.fns.contains(name) || self.methods.iter().chain(&self.defaults).any(|(_, n)| n == name)
            }
            StepFn::Method(ty, name) => {
                let key = (ty.clone(), name.clone());
                self.methods.contains(&key) || self.defaults.contains(&key)
            }
            StepFn::Macro(name) => self.macros.contains(name),
        }
    }
}

/// The definitions of a file, parsed once; `Err` says why the file cannot be checked.
fn defs_of<'c>(
    repo_root: &Path,
    file: &str,
    cache: &'c mut HashMap<String, Result<Defs, String>>,
) -> &'c Result<Defs, String> {
    cache.entry(file.to_string()).or_insert_with(|| {
        let path = repo_root.join(file);
        if !path.is_file() {
            return Err("no such file".to_string());
        }
        let text = std::fs::read_to_string(&path).map_err(|e| format!("cannot read: {e}"))?;
        let ast = syn::parse_file(&text).map_err(|e| format!("cannot parse: {e}"))?;
        let mut defs = Defs::default();
        defs.visit_file(&ast);
        Ok(defs)
    })
}

/// Parses the counts line: `Distinct files: N to the client's image, M to the output.`
pub fn parse_counts(line: &str) -> Option<WalkCounts> {
    let rest = line.trim().strip_prefix("Distinct files: ")?;
    let (image, rest) = rest.split_once(" to the client's image, ")?;
    let output = rest.strip_suffix(" to the output.")?;
    Some(WalkCounts { image: image.trim().parse().ok()?, output: output.trim().parse().ok()? })
}

/// Checks the walk section of `doc` against the files under `repo_root`.
pub fn check_walk(repo_root: &Path, doc: &str) -> WalkCheck {
    let lines: Vec<&str> = doc.lines().collect();
    let Some(start) = lines.iter().position(|l| l.starts_with(SECTION_PREFIX)) else {
        return WalkCheck {
            problems: vec![format!("no section whose heading starts with `{SECTION_PREFIX}`")],
            counts: None,
        };
    };
    let end = lines[start + 1..].iter().position(|l| l.starts_with("## ")).map_or(lines.len(), |i| start + 1 + i);
    let mut problems = Vec::new();
    let headings: Vec<usize> = (start + 1..end).filter(|&i| lines[i].starts_with("### ")).collect();
    if headings.len() != 2 {
        problems.push(format!("the walk has {} `### ` subsections, not two", headings.len()));
    }
    let image = headings.iter().copied().find(|&i| lines[i].contains("client's image"));
    let output = headings.iter().copied().find(|&i| Some(i) != image && lines[i].contains("output"));
    if image.is_none() {
        problems.push("no `### ` subsection about the client's image".to_string());
    }
    if output.is_none() {
        problems.push("no `### ` subsection about the output".to_string());
    }
    let subsection_end = |h: usize| headings.iter().copied().find(|&i| i > h).unwrap_or(end);
    let mut cache = HashMap::new();
    let mut files_of = |heading: Option<usize>, problems: &mut Vec<String>| -> BTreeSet<String> {
        let mut files = BTreeSet::new();
        let Some(h) = heading else { return files };
        for (i, line) in lines.iter().enumerate().take(subsection_end(h)).skip(h + 1) {
            if !is_numbered(line) {
                continue;
            }
            let line_no = i + 1;
            let Some(step) = parse_step(line_no, line) else {
                problems.push(format!("line {line_no}: the step names no `.rs` file"));
                continue;
            };
            files.insert(step.file.clone());
            check_step(repo_root, &step, &mut cache, problems);
        }
        files
    };
    let image_files = files_of(image, &mut problems);
    let output_files = files_of(output, &mut problems);
    let counts = WalkCounts { image: image_files.len(), output: image_files.union(&output_files).count() };
    let stated: Vec<&str> =
        lines[start..end].iter().copied().filter(|l| l.trim().starts_with("Distinct files:")).collect();
    match stated.as_slice() {
        [] => problems.push(format!(
            "no line `Distinct files: {} to the client's image, {} to the output.`",
            counts.image, counts.output
        )),
        [line] => match parse_counts(line) {
            Some(c) if c == counts => {}
            Some(c) => problems.push(format!(
                "the walk says {} files to the client's image and {} to the output; its steps name {} and {}",
                c.image, c.output, counts.image, counts.output
            )),
            None => problems.push(format!("cannot read the counts line `{}`", line.trim())),
        },
        _ => problems.push("more than one `Distinct files:` line".to_string()),
    }
    WalkCheck { problems, counts: Some(counts) }
}

/// Checks that a step's file exists and defines its function.
fn check_step(
    repo_root: &Path,
    step: &Step,
    cache: &mut HashMap<String, Result<Defs, String>>,
    problems: &mut Vec<String>,
) {
    let line = step.line;
    let Some(token) = &step.function else {
        problems.push(format!("line {line}: the step names no function after `{}`", step.file));
        return;
    };
    let Some(function) = parse_fn(token) else {
        problems.push(format!("line {line}: `{token}` is not a function name (`name`, `Type::name` or `name!`)"));
        return;
    };
    match defs_of(repo_root, &step.file, cache) {
        Err(why) => problems.push(format!("line {line}: `{}`: {why}", step.file)),
        Ok(defs) if !defs.defines(&function) => {
            problems.push(format!("line {line}: `{}` defines no `{token}`", step.file));
        }
        Ok(_) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::{is_numbered, parse_counts, parse_fn, parse_step, StepFn, WalkCounts};

    #[test]
    fn tokens_and_lines() {
        assert_eq!(parse_fn("draw"), Some(StepFn::Plain("draw".into())));
        assert_eq!(parse_fn("Gpu::is_lost"), Some(StepFn::Method("Gpu".into(), "is_lost".into())));
        assert_eq!(parse_fn("entry_points!"), Some(StepFn::Macro("entry_points".into())));
        assert_eq!(parse_fn("current()"), None);
        assert!(is_numbered("12. `a.rs` — `f`"));
        assert!(!is_numbered(" 1. x") && !is_numbered("1.x") && !is_numbered("- 1. x"));
        let step = parse_step(3, "4. `x` then `a/b.rs` — `Foo::bar`: more `c.rs`").expect("a step");
        assert_eq!((step.file.as_str(), step.function.as_deref()), ("a/b.rs", Some("Foo::bar")));
        assert_eq!(
            parse_counts("Distinct files: 29 to the client's image, 45 to the output."),
            Some(WalkCounts { image: 29, output: 45 })
        );
        assert_eq!(parse_counts("Distinct files: 29 to the image, 45 to the output."), None);
    }
}

//! Import circles of small synthetic crates, one rule at a time.

mod common;

use common::{edge_lines, TempTree};
use strata_arch::{crate_graph, find_circles};

/// The circles of the crate rooted at `src/lib.rs` in `tree`, each as its sorted file list.
fn circles(tree: &TempTree) -> Vec<Vec<String>> {
    let graph = crate_graph(&tree.path("src/lib.rs")).expect("the crate parses");
    find_circles(&graph).iter().map(|c| c.files.iter().map(|f| f.display().to_string()).collect()).collect()
}

#[test]
fn a_two_file_circle_is_found_with_its_names() {
    let tree = TempTree::with(
        "two",
        &[
            ("src/lib.rs", "mod a;\nmod b;\n"),
            ("src/a.rs", "use crate::b::B;\npub struct A;\npub fn make() -> B { B }\n"),
            ("src/b.rs", "pub struct B;\npub fn make() -> crate::a::A { crate::a::A }\n"),
        ],
    );
    assert_eq!(circles(&tree), [["a.rs", "b.rs"]]);
    let graph = crate_graph(&tree.path("src/lib.rs")).expect("the crate parses");
    let circle = &find_circles(&graph)[0];
    let edges: Vec<String> = circle
        .edges
        .iter()
        .map(|e| format!("{} -> {}: {}", e.from.display(), e.to.display(), e.names.join(", ")))
        .collect();
    assert_eq!(edges, ["a.rs -> b.rs: B", "b.rs -> a.rs: A"]);
}

#[test]
fn a_chain_is_not_a_circle() {
    let tree = TempTree::with(
        "chain",
        &[
            ("src/lib.rs", "mod a;\nmod b;\nmod c;\n"),
            ("src/a.rs", "use crate::b::B;\npub fn f(_: B) {}\n"),
            ("src/b.rs", "pub struct B(pub crate::c::C);\n"),
            ("src/c.rs", "pub struct C;\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["a.rs -> b.rs: B", "b.rs -> c.rs: C"]);
    assert!(circles(&tree).is_empty());
}

#[test]
fn a_reexport_is_followed_to_the_defining_file() {
    // The facade re-exports both children; `a.rs` imports its sibling through the facade.
    let tree = TempTree::with(
        "facade",
        &[
            ("src/lib.rs", "mod shapes;\npub use shapes::{A, B};\n"),
            ("src/shapes/mod.rs", "mod a;\nmod b;\npub use a::A;\npub(crate) use b::B;\n"),
            ("src/shapes/a.rs", "use super::B;\npub struct A(pub B);\n"),
            ("src/shapes/b.rs", "pub struct B;\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["shapes/a.rs -> shapes/b.rs: B"]);
    assert!(circles(&tree).is_empty());
}

#[test]
fn a_reexported_name_used_in_the_facade_is_an_edge() {
    let tree = TempTree::with(
        "facade-use",
        &[
            ("src/lib.rs", "mod a;\npub use a::A;\npub fn make() -> A { A }\npub struct Top;\n"),
            ("src/a.rs", "pub struct A;\npub fn top() -> crate::Top { crate::Top }\n"),
        ],
    );
    assert_eq!(circles(&tree), [["a.rs", "lib.rs"]]);
}

#[test]
fn a_glob_import_of_the_parent_is_an_edge() {
    let tree = TempTree::with(
        "glob",
        &[
            ("src/lib.rs", "mod child;\npub fn top() { child::f() }\n"),
            ("src/child.rs", "use super::*;\npub fn f() {}\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["lib.rs -> child.rs: f", "child.rs -> lib.rs: super::*"]);
    assert_eq!(circles(&tree), [["child.rs", "lib.rs"]]);
}

#[test]
fn test_only_code_is_ignored() {
    let tree = TempTree::with(
        "tests",
        &[
            ("src/lib.rs", "mod a;\nmod b;\n#[cfg(test)]\nfn only_in_tests() { a::A::new(); }\n"),
            (
                "src/a.rs",
                "pub struct A;\nimpl A { pub fn new() -> Self { A } }\n\
                 #[cfg(test)]\nmod tests {\n    use crate::b::B;\n    #[test]\n    fn t() { let _ = B; }\n}\n\
                 #[cfg(test)]\nmod a_tests;\n",
            ),
            ("src/a_tests.rs", "use crate::b::B;\n"),
            ("src/b.rs", "use crate::a::A;\npub struct B;\npub fn make() -> A { A::new() }\n"),
        ],
    );
    let graph = crate_graph(&tree.path("src/lib.rs")).expect("the crate parses");
    let files: Vec<String> = graph.files.iter().map(|f| f.display().to_string()).collect();
    assert_eq!(files, ["lib.rs", "a.rs", "b.rs"]);
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["b.rs -> a.rs: A"]);
    assert!(circles(&tree).is_empty());
}

#[test]
fn a_path_inside_a_macro_invocation_is_an_edge() {
    let tree = TempTree::with(
        "macro",
        &[
            ("src/lib.rs", "mod a;\nmod b;\n"),
            ("src/a.rs", "pub fn show() -> String { format!(\"{}\", crate::b::X) }\n"),
            ("src/b.rs", "pub const X: u32 = 1;\npub fn f() -> String { crate::a::show() }\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["a.rs -> b.rs: X", "b.rs -> a.rs: show"]);
    assert_eq!(circles(&tree), [["a.rs", "b.rs"]]);
}

#[test]
fn a_macro_path_is_an_edge() {
    let tree = TempTree::with(
        "macro-path",
        &[
            ("src/lib.rs", "mod gen;\nmacro_rules! make { () => {}; }\npub(crate) use make;\n"),
            ("src/gen.rs", "crate::make!();\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["gen.rs -> lib.rs: make"]);
}

#[test]
fn an_alias_is_expanded_to_what_it_names() {
    let tree = TempTree::with(
        "alias",
        &[
            ("src/lib.rs", "mod a;\nmod shapes;\n"),
            ("src/shapes/mod.rs", "pub mod circle;\npub mod square;\n"),
            ("src/shapes/circle.rs", "pub fn area() -> f32 { 1.0 }\n"),
            ("src/shapes/square.rs", "pub fn side() -> f32 { 1.0 }\n"),
            (
                "src/a.rs",
                "use crate::shapes;\nuse crate::shapes::square as sq;\n\
                 pub fn f() -> f32 { shapes::circle::area() + sq::side() }\n",
            ),
        ],
    );
    assert_eq!(
        edge_lines(&tree.path("src/lib.rs")),
        ["a.rs -> shapes/mod.rs: shapes", "a.rs -> shapes/circle.rs: area", "a.rs -> shapes/square.rs: side, square"]
    );
}

#[test]
fn enum_variants_and_methods_count_as_their_type() {
    let tree = TempTree::with(
        "variants",
        &[
            ("src/lib.rs", "mod a;\nmod b;\n"),
            ("src/a.rs", "pub enum Mode { On }\npub struct S;\nimpl S { pub fn new() -> S { S } }\n"),
            ("src/b.rs", "pub fn f() { let _ = crate::a::Mode::On; let _ = crate::a::S::new(); }\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["b.rs -> a.rs: Mode, S"]);
}

#[test]
fn a_name_no_file_defines_goes_to_the_modules_file() {
    let tree = TempTree::with(
        "generated",
        &[
            ("src/lib.rs", "mod a;\nmod b;\n"),
            ("src/a.rs", "macro_rules! gen { () => { pub fn made() {} }; }\ngen!();\n"),
            ("src/b.rs", "pub fn f() { crate::a::made() }\n"),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["b.rs -> a.rs: made"]);
}

#[test]
fn paths_into_other_crates_and_local_variables_are_not_edges() {
    let tree = TempTree::with(
        "external",
        &[
            ("src/lib.rs", "mod a;\nmod b;\npub use a::size;\npub use std::fmt::Write;\n"),
            ("src/a.rs", "pub fn size() -> usize { 1 }\n"),
            (
                "src/b.rs",
                "use super::*;\nuse std::collections::HashMap;\n\
                 pub fn f(size: usize) -> usize { let m: HashMap<u8, u8> = HashMap::new(); size + m.len() }\n",
            ),
        ],
    );
    assert_eq!(edge_lines(&tree.path("src/lib.rs")), ["b.rs -> lib.rs: super::*"]);
}

#[test]
fn inline_modules_and_path_attributes_are_part_of_the_tree() {
    let tree = TempTree::with(
        "inline",
        &[
            ("src/lib.rs", "mod outer {\n    pub mod inner;\n}\n#[path = \"elsewhere/x.rs\"]\nmod x;\n"),
            ("src/outer/inner.rs", "pub fn g() { crate::x::h() }\n"),
            ("src/elsewhere/x.rs", "pub fn h() {}\npub fn k() { crate::outer::inner::g() }\n"),
        ],
    );
    assert_eq!(circles(&tree), [["elsewhere/x.rs", "outer/inner.rs"]]);
}

#[test]
fn a_binary_root_is_its_own_crate_and_paths_into_the_library_are_ignored() {
    let tree = TempTree::with(
        "bin",
        &[
            ("src/lib.rs", "pub mod cli;\npub fn start() {}\npub fn both() { cli::run() }\n"),
            ("src/cli.rs", "pub fn run() { crate::start() }\n"),
            ("src/main.rs", "mod cli2;\nfn main() { strata_lib::cli::run(); cli2::go(); }\npub fn shared() {}\n"),
            ("src/cli2.rs", "use strata_lib::start;\npub fn go() { start(); crate::shared() }\n"),
        ],
    );
    let crates = strata_arch::circles_in(&tree.root).expect("two crates");
    let found: Vec<(strata_arch::CrateKind, usize)> = crates.iter().map(|c| (c.kind, c.circles.len())).collect();
    assert_eq!(found, [(strata_arch::CrateKind::Lib, 1), (strata_arch::CrateKind::Bin, 1)]);
    assert_eq!(edge_lines(&tree.path("src/main.rs")), ["main.rs -> cli2.rs: go", "cli2.rs -> main.rs: shared"]);
}

//! The module table, the walk and file lengths, on a small synthetic repository.

mod common;

use common::TempTree;
use strata_arch::{check, Report, WalkCounts};

/// The architecture document of the synthetic repository; `steps` replaces the walk's body.
fn doc(rows: &str, walk: &str) -> String {
    format!(
        "# Architecture\n\n## Layers\n\n| crate | depends on |\n|---|---|\n| `alpha` | (no workspace crate) |\n\n\
         ## Modules\n\n| File | Purpose |\n|---|---|\n{rows}\n## The walk of one call\n\n{walk}\n## After\n\n\
         1. `alpha/src/nowhere.rs` — `ignored`: outside the walk.\n"
    )
}

/// The rows of a complete module table.
const ROWS: &str = "| `alpha/src/lib.rs` | Crate root. |\n\
| `alpha/src/draw.rs` | Drawing. |\n\
| `alpha/src/out.rs` | Output. |\n\
| `alpha/src/main.rs` | The binary. |\n\
| `alpha/src/cli.rs` | Its commands. |\n\
| `alpha/tests/smoke.rs` | A test outside `src/`. |\n";

/// A walk whose steps all name functions that exist.
const WALK: &str = "### (a) To the client's image\n\n\
1. `alpha/src/draw.rs` — `draw`: a free function.\n\
2. `alpha/src/draw.rs` — `Pass::run`: an inherent method.\n\
3. `alpha/src/draw.rs` — `make!`: a macro.\n\
\n### (b) To the output\n\n\
4. `alpha/src/out.rs` — `Present::present`: a trait's default method.\n\
5. `alpha/src/out.rs` — `Screen::show`: a trait method implemented for a type.\n\
6. `alpha/src/lib.rs` — `start`: back at the root (see `alpha/src/draw.rs`).\n\
\nDistinct files: 1 to the client's image, 3 to the output.\n";

/// A repository that passes every check.
fn clean_repo(label: &str) -> TempTree {
    TempTree::with(
        label,
        &[
            ("Cargo.toml", "[workspace]\nmembers = [\"alpha\"]\n"),
            ("alpha/Cargo.toml", "[package]\nname = \"alpha\"\nversion = \"0.1.0\"\n"),
            ("alpha/src/lib.rs", "pub mod draw;\npub mod out;\npub fn start() { draw::draw() }\n"),
            (
                "alpha/src/draw.rs",
                "pub struct Pass;\nimpl Pass {\n    pub fn run(&self) {}\n}\npub fn draw() {}\n\
                 macro_rules! make {\n    () => {};\n}\n",
            ),
            (
                "alpha/src/out.rs",
                "pub trait Present {\n    fn present(&self) {}\n    fn later(&self);\n}\npub struct Screen;\n\
                 impl Present for Screen {\n    fn later(&self) {}\n}\npub trait Show {\n    fn show(&self);\n}\n\
                 impl Show for Screen {\n    fn show(&self) {}\n}\n",
            ),
            ("alpha/src/main.rs", "mod cli;\nfn main() {\n    cli::run();\n}\n"),
            ("alpha/src/cli.rs", "use alpha::draw::Pass;\npub fn run() {\n    Pass.run();\n}\n"),
            ("alpha/tests/smoke.rs", "#[test]\nfn smoke() {}\n"),
            ("docs/architecture.md", &doc(ROWS, WALK)),
        ],
    )
}

/// Runs the check, printing the report.
fn report(tree: &TempTree) -> Report {
    let report = check(&tree.root).expect("the repository can be checked");
    println!("{report}");
    report
}

#[test]
fn a_clean_repository_has_no_problems() {
    let tree = clean_repo("clean");
    let report = report(&tree);
    assert!(!report.has_problems());
    assert_eq!(report.walk.counts, Some(WalkCounts { image: 1, output: 3 }));
    assert_eq!(report.crates.len(), 2);
}

#[test]
fn a_source_file_without_a_row_is_reported() {
    let tree = clean_repo("missing");
    tree.write("alpha/src/extra/deep.rs", "pub fn f() {}\n");
    let report = report(&tree);
    let missing: Vec<String> = report.table.missing.iter().map(|p| p.display().to_string()).collect();
    assert_eq!(missing, ["alpha/src/extra/deep.rs"]);
    assert!(report.table.stale.is_empty());
    assert_eq!(report.problem_count(), 1);
}

#[test]
fn a_row_naming_no_file_is_reported() {
    let tree = clean_repo("stale");
    tree.write("docs/architecture.md", &doc(&format!("{ROWS}| `alpha/src/gone.rs` | Removed. |\n"), WALK));
    let report = report(&tree);
    assert_eq!(report.table.stale, ["alpha/src/gone.rs"]);
    assert!(report.table.missing.is_empty());
    assert_eq!(report.problem_count(), 1);
}

#[test]
fn a_walk_step_naming_a_missing_function_is_reported() {
    let tree = clean_repo("walk-fn");
    let walk = WALK
        .replace("`Pass::run`", "`Pass::fly`")
        .replace("`Screen::show`", "`Screen::later`")
        .replace("`make!`", "`draw!`");
    tree.write("docs/architecture.md", &doc(ROWS, &walk));
    let report = report(&tree);
    assert_eq!(report.walk.problems.len(), 2, "{:?}", report.walk.problems);
    assert!(report.walk.problems[0].contains("`alpha/src/draw.rs` defines no `Pass::fly`"));
    assert!(report.walk.problems[1].contains("`alpha/src/draw.rs` defines no `draw!`"));
}

#[test]
fn a_walk_step_naming_a_missing_file_is_reported() {
    let tree = clean_repo("walk-file");
    tree.write(
        "docs/architecture.md",
        &doc(ROWS, &WALK.replace("`alpha/src/lib.rs` — `start`", "`alpha/src/gone.rs` — `start`")),
    );
    let report = report(&tree);
    assert_eq!(report.walk.problems.len(), 1, "{:?}", report.walk.problems);
    assert!(report.walk.problems[0].contains("`alpha/src/gone.rs`: no such file"));
}

#[test]
fn a_wrong_count_of_distinct_files_is_reported() {
    let tree = clean_repo("walk-count");
    let walk = WALK.replace("1 to the client's image", "2 to the client's image");
    tree.write("docs/architecture.md", &doc(ROWS, &walk));
    let report = report(&tree);
    assert_eq!(
        report.walk.problems,
        ["the walk says 2 files to the client's image and 3 to the output; its steps name 1 and 3"]
    );
    assert_eq!(report.walk.counts, Some(WalkCounts { image: 1, output: 3 }));
}

#[test]
fn a_walk_without_its_sections_or_counts_is_reported() {
    let tree = clean_repo("walk-shape");
    tree.write(
        "docs/architecture.md",
        &doc(ROWS, "### (a) To the client's image\n\n1. `alpha/src/draw.rs` — `draw`.\n"),
    );
    let report = report(&tree);
    assert_eq!(report.walk.problems.len(), 3, "{:?}", report.walk.problems);
    assert!(report.walk.problems[0].contains("not two"));
    assert!(report.walk.problems[1].contains("about the output"));
    assert!(report.walk.problems[2].contains("no line `Distinct files: 1 to the client's image, 1 to the output.`"));
    tree.write("docs/architecture.md", "# Architecture\n");
    let report = check(&tree.root).expect("the repository can be checked");
    assert!(report.walk.problems.iter().any(|p| p.contains("## The walk of")));
    assert_eq!(report.walk.counts, None);
}

#[test]
fn a_dependency_the_layers_table_does_not_state_is_reported() {
    let tree = clean_repo("layers");
    // A second member, which alpha now depends on; the table still says alpha depends on
    // nothing, and names no `beta`.
    tree.write("Cargo.toml", "[workspace]\nmembers = [\"alpha\", \"beta\"]\n");
    tree.write("beta/Cargo.toml", "[package]\nname = \"beta\"\nversion = \"0.1.0\"\n");
    tree.write("beta/src/lib.rs", "pub fn b() {}\n");
    tree.write(
        "alpha/Cargo.toml",
        "[package]\nname = \"alpha\"\nversion = \"0.1.0\"\n\n[dependencies]\nbeta = { path = \"../beta\" }\n\n\
         [dev-dependencies]\ngamma = \"1\"\n",
    );
    let report = report(&tree);
    assert_eq!(
        report.layers.problems,
        [
            "`alpha` depends on beta but the layers table says no workspace crate",
            "`beta` has no row in the layers table"
        ]
    );
    tree.write("docs/architecture.md", "# Architecture\n");
    let report = check(&tree.root).expect("the repository can be checked");
    assert_eq!(report.layers.problems, ["no `## Layers` table with a `depends on` column"]);
}

#[test]
fn a_file_over_600_lines_is_reported() {
    let tree = clean_repo("long");
    let fill = |n: usize| {
        format!("pub struct Pass;\nimpl Pass {{\n    pub fn run(&self) {{}}\n}}\npub fn draw() {{}}\nmacro_rules! make {{\n    () => {{}};\n}}\n{}", "//\n".repeat(n - 8))
    };
    tree.write("alpha/src/draw.rs", &fill(600));
    assert!(!report(&tree).has_problems());
    tree.write("alpha/src/draw.rs", &fill(601));
    let report = report(&tree);
    let long: Vec<(String, usize)> =
        report.long_files.iter().map(|l| (l.path.display().to_string(), l.lines)).collect();
    assert_eq!(long, [("alpha/src/draw.rs".to_string(), 601)]);
    assert_eq!(report.problem_count(), 1);
}

#[test]
fn circles_are_problems_of_the_check() {
    let tree = clean_repo("circle");
    tree.write("alpha/src/out.rs", "pub fn show() { crate::draw::draw() }\n");
    tree.write("alpha/src/draw.rs", "pub struct Pass;\nimpl Pass {\n    pub fn run(&self) {}\n}\npub fn draw() { crate::out::show() }\nmacro_rules! make {\n    () => {};\n}\n");
    let report = report(&tree);
    assert_eq!(report.circle_count(), 1);
    let text = report.to_string();
    assert!(text.contains("circle 1 of 2 files: draw.rs, out.rs"), "{text}");
    assert!(text.contains("draw.rs -> out.rs: show"), "{text}");
}

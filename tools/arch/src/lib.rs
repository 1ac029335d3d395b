//! Checks of the workspace's structure: import circles between the files of each crate, the
//! layers table (the crate graph), the module table and the walk of `docs/architecture.md`,
//! and the length of source files.
#![warn(missing_docs)]

pub mod circles;
pub mod doc;
mod error;
pub mod graph;
pub mod layers;
mod modules;
pub mod report;
mod resolve;
mod scan;
pub mod walk;
pub mod workspace;

use std::path::{Path, PathBuf};

pub use circles::{find_circles, Circle};
pub use doc::TableCheck;
pub use error::ArchError;
pub use graph::{crate_graph, Edge, FileGraph};
pub use layers::LayerCheck;
pub use report::{CrateCircles, LongFile, Report, MAX_LINES};
pub use walk::{WalkCheck, WalkCounts};
pub use workspace::{CrateKind, CrateRoot, Member};

/// The architecture document, relative to the repository root.
pub const ARCHITECTURE_DOC: &str = "docs/architecture.md";

/// Runs every check on the repository at `repo_root`.
pub fn check(repo_root: &Path) -> Result<Report, ArchError> {
    let members = workspace::members(repo_root)?;
    let mut crates = Vec::new();
    let mut sources = Vec::new();
    for member in &members {
        for root in &member.crates {
            crates.push(crate_circles(repo_root, &member.name, root)?);
        }
        for file in workspace::rust_files(&repo_root.join(&member.dir).join("src"))? {
            sources.push(file.strip_prefix(repo_root).map(Path::to_path_buf).unwrap_or(file));
        }
    }
    let doc = error::read_to_string(&repo_root.join(ARCHITECTURE_DOC))?;
    Ok(Report {
        crates,
        table: doc::check_table(repo_root, &doc, &sources),
        layers: layers::check_layers(&doc, &members),
        walk: walk::check_walk(repo_root, &doc),
        long_files: long_files(repo_root, &sources)?,
    })
}

/// The circles of one crate; `name` labels it, and its base is shown relative to `repo_root`.
pub fn crate_circles(repo_root: &Path, name: &str, root: &CrateRoot) -> Result<CrateCircles, ArchError> {
    let graph = crate_graph(&root.root)?;
    let dir = root.root.parent().unwrap_or(Path::new(""));
    Ok(CrateCircles {
        name: name.to_string(),
        kind: root.kind,
        base: dir.strip_prefix(repo_root).unwrap_or(dir).to_path_buf(),
        circles: find_circles(&graph),
    })
}

/// The circles of the crates in a directory (a `src` directory or a package directory).
pub fn circles_in(dir: &Path) -> Result<Vec<CrateCircles>, ArchError> {
    workspace::crates_in(dir)?.iter().map(|root| crate_circles(Path::new(""), "", root)).collect()
}

/// The number of lines of a text.
pub fn line_count(text: &str) -> usize {
    text.lines().count()
}

/// The files of `files` (relative to `repo_root`) longer than [`MAX_LINES`].
pub fn long_files(repo_root: &Path, files: &[PathBuf]) -> Result<Vec<LongFile>, ArchError> {
    let mut long = Vec::new();
    for file in files {
        let lines = line_count(&error::read_to_string(&repo_root.join(file))?);
        if lines > MAX_LINES {
            long.push(LongFile { path: file.clone(), lines });
        }
    }
    Ok(long)
}

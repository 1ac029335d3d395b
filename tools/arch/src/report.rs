//! The outcome of a check and its readable form.

use std::fmt;
use std::path::PathBuf;

use crate::circles::Circle;
use crate::doc::TableCheck;
use crate::layers::LayerCheck;
use crate::walk::WalkCheck;
use crate::workspace::{slash_path, CrateKind};

/// The most lines a source file may have.
pub const MAX_LINES: usize = 600;

/// The import circles of one crate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CrateCircles {
    /// The package name; empty for a directory given on the command line.
    pub name: String,
    /// Library or binary.
    pub kind: CrateKind,
    /// The crate root's directory; the circles' paths are relative to it.
    pub base: PathBuf,
    /// The circles, largest first.
    pub circles: Vec<Circle>,
}

/// A source file longer than the limit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LongFile {
    /// The file, relative to the repository root.
    pub path: PathBuf,
    /// Its number of lines.
    pub lines: usize,
}

/// Everything `check` found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Report {
    /// The import circles of every crate (crates without circles included).
    pub crates: Vec<CrateCircles>,
    /// The module table's missing and stale rows.
    pub table: TableCheck,
    /// Where the layers table and the manifests disagree.
    pub layers: LayerCheck,
    /// The walk's problems and counts.
    pub walk: WalkCheck,
    /// Source files over the line limit.
    pub long_files: Vec<LongFile>,
}

impl Report {
    /// The number of circles over all crates.
    pub fn circle_count(&self) -> usize {
        self.crates.iter().map(|c| c.circles.len()).sum()
    }

    /// The number of problems: circles, rows, walk problems and long files.
    pub fn problem_count(&self) -> usize {
        self.circle_count()
            + self.table.missing.len()
            + self.table.stale.len()
            + self.layers.problems.len()
            + self.walk.problems.len()
            + self.long_files.len()
    }

    /// Whether anything is wrong.
    pub fn has_problems(&self) -> bool {
        self.problem_count() > 0
    }
}

/// The label of a crate: its directory, package and kind.
fn crate_label(c: &CrateCircles) -> String {
    let kind = match c.kind {
        CrateKind::Lib => "lib",
        CrateKind::Bin => "bin",
    };
    if c.name.is_empty() {
        format!("{} ({kind})", slash_path(&c.base))
    } else {
        format!("{} ({}, {kind})", slash_path(&c.base), c.name)
    }
}

/// Writes one crate's circles, each with its files and the edges inside it.
pub fn write_circles(f: &mut impl fmt::Write, c: &CrateCircles) -> fmt::Result {
    let label = crate_label(c);
    match c.circles.len() {
        0 => return writeln!(f, "  {label}: no circles"),
        1 => writeln!(f, "  {label}: 1 circle")?,
        n => writeln!(f, "  {label}: {n} circles")?,
    }
    for (i, circle) in c.circles.iter().enumerate() {
        let files: Vec<String> = circle.files.iter().map(|p| slash_path(p)).collect();
        writeln!(f, "    circle {} of {} files: {}", i + 1, files.len(), files.join(", "))?;
        for e in &circle.edges {
            writeln!(f, "      {} -> {}: {}", slash_path(&e.from), slash_path(&e.to), e.names.join(", "))?;
        }
    }
    Ok(())
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Import circles: {}", self.circle_count())?;
        for c in &self.crates {
            write_circles(f, c)?;
        }
        writeln!(f, "Module table: {} missing rows, {} stale rows", self.table.missing.len(), self.table.stale.len())?;
        for m in &self.table.missing {
            writeln!(f, "  missing row: {}", slash_path(m))?;
        }
        for s in &self.table.stale {
            writeln!(f, "  stale row (no such file): {s}")?;
        }
        writeln!(f, "Layers: {} problems", self.layers.problems.len())?;
        for p in &self.layers.problems {
            writeln!(f, "  {p}")?;
        }
        match self.walk.counts {
            Some(c) => writeln!(
                f,
                "Walk: {} problems; distinct files: {} to the client's image, {} to the output",
                self.walk.problems.len(),
                c.image,
                c.output
            )?,
            None => writeln!(f, "Walk: {} problems", self.walk.problems.len())?,
        }
        for p in &self.walk.problems {
            writeln!(f, "  {p}")?;
        }
        writeln!(f, "Long files (over {} lines): {}", MAX_LINES, self.long_files.len())?;
        for l in &self.long_files {
            writeln!(f, "  {}: {} lines", slash_path(&l.path), l.lines)?;
        }
        writeln!(f, "Problems: {}", self.problem_count())
    }
}

//! The module table of `docs/architecture.md`: one row per source file, and no row for a file
//! that does not exist.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::workspace::slash_path;

/// What the module table gets wrong.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TableCheck {
    /// Source files under a member's `src/` without a row, relative to the repository root.
    pub missing: Vec<PathBuf>,
    /// Rows naming a file that does not exist, as written.
    pub stale: Vec<String>,
}

/// The file a table line documents: its first cell is a backticked path ending in `.rs`.
pub fn row_file(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix('|')?;
    let cell = rest.split('|').next()?.trim();
    let path = cell.strip_prefix('`')?.strip_suffix('`')?;
    (path.ends_with(".rs") && !path.contains('`')).then_some(path)
}

/// Every file the module table documents, in document order.
pub fn table_rows(doc: &str) -> Vec<&str> {
    doc.lines().filter_map(row_file).collect()
}

/// Checks the module table of `doc` against `sources` (source files under members' `src/`,
/// relative to `repo_root`) and against the files on disk.
pub fn check_table(repo_root: &Path, doc: &str, sources: &[PathBuf]) -> TableCheck {
    let rows = table_rows(doc);
    let documented: BTreeSet<&str> = rows.iter().copied().collect();
    let missing = sources.iter().filter(|s| !documented.contains(slash_path(s).as_str())).cloned().collect();
    let mut seen = BTreeSet::new();
    let stale =
        rows.into_iter().filter(|r| !repo_root.join(r).is_file() && seen.insert(*r)).map(str::to_string).collect();
    TableCheck { missing, stale }
}

#[cfg(test)]
mod tests {
    use super::row_file;

    #[test]
    fn rows_are_backticked_rust_paths_in_the_first_cell() {
        assert_eq!(row_file("| `server/src/main.rs` | The daemon. |"), Some("server/src/main.rs"));
        assert_eq!(row_file("  |`a.rs`|x|"), Some("a.rs"));
        assert_eq!(row_file("| File | Purpose |"), None);
        assert_eq!(row_file("| `shaders/x.wgsl` | a shader |"), None);
        assert_eq!(row_file("| x | `a.rs` |"), None);
        assert_eq!(row_file("`a.rs` | x"), None);
    }
}

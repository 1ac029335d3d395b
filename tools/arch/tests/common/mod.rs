//! Synthetic crates and repositories written to a fresh directory under the system's
//! temporary directory, removed when dropped.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A directory of files for one test.
pub struct TempTree {
    /// The directory.
    pub root: PathBuf,
}

/// Counts trees made by this process, so each gets its own directory.
static NEXT: AtomicUsize = AtomicUsize::new(0);

impl TempTree {
    /// A new empty directory named after `label`.
    pub fn new(label: &str) -> Self {
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let root = std::env::temp_dir().join(format!("strata-arch-{label}-{}-{n}", std::process::id()));
        if root.exists() {
            std::fs::remove_dir_all(&root).expect("removing a stale test directory");
        }
        std::fs::create_dir_all(&root).expect("creating the test directory");
        TempTree { root }
    }

    /// A new directory holding `files` (path, contents).
    pub fn with(label: &str, files: &[(&str, &str)]) -> Self {
        let tree = TempTree::new(label);
        for (path, text) in files {
            tree.write(path, text);
        }
        tree
    }

    /// Writes one file, creating its directories.
    pub fn write(&self, path: &str, text: &str) {
        let path = self.root.join(path);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).expect("creating a directory");
        }
        std::fs::write(&path, text).expect("writing a file");
    }

    /// A path inside the tree.
    #[allow(dead_code)]
    pub fn path(&self, rel: &str) -> PathBuf {
        self.root.join(rel)
    }
}

impl Drop for TempTree {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.root);
    }
}

/// The edges of a crate graph as `from -> to: names` lines.
#[allow(dead_code)]
pub fn edge_lines(root: &Path) -> Vec<String> {
    let graph = strata_arch::crate_graph(root).expect("the crate parses");
    graph.edges.iter().map(|e| format!("{} -> {}: {}", e.from.display(), e.to.display(), e.names.join(", "))).collect()
}

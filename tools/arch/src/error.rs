//! The errors that stop a check before it can report: unreadable or unparsable files.

use std::path::PathBuf;

/// Why a check could not run to its end.
#[derive(Debug, thiserror::Error)]
pub enum ArchError {
    /// A file or directory could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file or directory.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A Rust source file is not valid Rust.
    #[error("cannot parse {path}: {source}")]
    Parse {
        /// The source file.
        path: PathBuf,
        /// The parser's error.
        source: syn::Error,
    },
    /// A `Cargo.toml` is not valid TOML or lacks what the check needs.
    #[error("{path}: {message}")]
    Manifest {
        /// The manifest.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// A `mod name;` declaration whose file exists nowhere it may be.
    #[error("module `{name}` declared in {declared_in} has no file (looked for {looked_for})")]
    ModuleNotFound {
        /// The module's name.
        name: String,
        /// The file holding the declaration.
        declared_in: PathBuf,
        /// The candidate paths, comma separated.
        looked_for: String,
    },
    /// A directory given as a crate holds neither `lib.rs` nor `main.rs`.
    #[error("no crate root (lib.rs or main.rs) in {0}")]
    NoCrateRoot(PathBuf),
}

/// Reads a file to a string, naming the file in the error.
pub(crate) fn read_to_string(path: &std::path::Path) -> Result<String, ArchError> {
    std::fs::read_to_string(path).map_err(|source| ArchError::Read { path: path.to_path_buf(), source })
}

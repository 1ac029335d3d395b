//! The workspace: its member packages, their crates' root files and their source files.

use std::path::{Path, PathBuf};

use crate::error::{read_to_string, ArchError};

/// Whether a crate is a package's library or one of its binaries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CrateKind {
    /// The library (`src/lib.rs`).
    Lib,
    /// A binary (`src/main.rs` or a `[[bin]]` path); its `crate::` is the binary.
    Bin,
}

/// One crate to check, by its root file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CrateRoot {
    /// Library or binary.
    pub kind: CrateKind,
    /// The root file (`lib.rs`, `main.rs`); file paths in its graph are relative to its directory.
    pub root: PathBuf,
}

/// A workspace member package.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Member {
    /// The package's directory, relative to the repository root.
    pub dir: PathBuf,
    /// The package's name.
    pub name: String,
    /// Its crates: the library first, then the binaries.
    pub crates: Vec<CrateRoot>,
    /// The packages its `[dependencies]` name (build and development dependencies left out).
    pub dependencies: Vec<String>,
}

/// Parses a manifest into a TOML table.
fn manifest(path: &Path) -> Result<toml::Table, ArchError> {
    read_to_string(path)?
        .parse::<toml::Table>()
        .map_err(|e| ArchError::Manifest { path: path.to_path_buf(), message: e.to_string() })
}

/// The `[workspace] members` of the repository's root `Cargo.toml`, with their crates.
pub fn members(repo_root: &Path) -> Result<Vec<Member>, ArchError> {
    let path = repo_root.join("Cargo.toml");
    let table = manifest(&path)?;
    let listed = table
        .get("workspace")
        .and_then(|w| w.get("members"))
        .and_then(|m| m.as_array())
        .ok_or_else(|| ArchError::Manifest { path: path.clone(), message: "no [workspace] members".to_string() })?;
    let mut dirs = Vec::new();
    for entry in listed {
        let Some(entry) = entry.as_str() else {
            return Err(ArchError::Manifest { path, message: format!("member {entry} is not a string") });
        };
        match entry.strip_suffix("/*") {
            Some(parent) => {
                let mut found: Vec<PathBuf> = list_dir(&repo_root.join(parent))?
                    .into_iter()
                    .filter(|p| p.join("Cargo.toml").is_file())
                    .filter_map(|p| p.strip_prefix(repo_root).ok().map(Path::to_path_buf))
                    .collect();
                found.sort();
                dirs.extend(found);
            }
            None => dirs.push(PathBuf::from(entry)),
        }
    }
    dirs.into_iter().map(|dir| member(repo_root, dir)).collect()
}

/// A member package: its name and crate roots from its manifest and `src/`.
fn member(repo_root: &Path, dir: PathBuf) -> Result<Member, ArchError> {
    let pkg_dir = repo_root.join(&dir);
    let path = pkg_dir.join("Cargo.toml");
    let table = manifest(&path)?;
    let name = table
        .get("package")
        .and_then(|p| p.get("name"))
        .and_then(|n| n.as_str())
        .ok_or_else(|| ArchError::Manifest { path: path.clone(), message: "no package name".to_string() })?
        .to_string();
    let mut crates = Vec::new();
    let lib = table.get("lib").and_then(|l| l.get("path")).and_then(|p| p.as_str()).unwrap_or("src/lib.rs");
    if pkg_dir.join(lib).is_file() {
        crates.push(CrateRoot { kind: CrateKind::Lib, root: pkg_dir.join(lib) });
    }
    let mut bins: Vec<PathBuf> = Vec::new();
    for bin in table.get("bin").and_then(|b| b.as_array()).into_iter().flatten() {
        let bin_path = match bin.get("path").and_then(|p| p.as_str()) {
            Some(p) => p.to_string(),
            None => match bin.get("name").and_then(|n| n.as_str()) {
                Some(n) if n != name => format!("src/bin/{n}.rs"),
                _ => "src/main.rs".to_string(),
            },
        };
        bins.push(pkg_dir.join(bin_path));
    }
    bins.push(pkg_dir.join("src/main.rs"));
    for bin in bins {
        let known = crates.iter().any(|c| c.root == bin);
        if bin.is_file() && !known {
            crates.push(CrateRoot { kind: CrateKind::Bin, root: bin });
        }
    }
    let dependencies = table
        .get("dependencies")
        .and_then(|d| d.as_table())
        .map(|d| {
            d.iter()
                .map(|(key, spec)| {
                    let renamed = spec.get("package").and_then(|p| p.as_str());
                    renamed.unwrap_or(key).to_string()
                })
                .collect()
        })
        .unwrap_or_default();
    Ok(Member { dir, name, crates, dependencies })
}

/// The crates of a directory given on the command line: a `src` directory or a package
/// directory holding one (`lib.rs` and/or `main.rs`).
pub fn crates_in(dir: &Path) -> Result<Vec<CrateRoot>, ArchError> {
    let src = if dir.join("src").is_dir() { dir.join("src") } else { dir.to_path_buf() };
    let mut crates = Vec::new();
    if src.join("lib.rs").is_file() {
        crates.push(CrateRoot { kind: CrateKind::Lib, root: src.join("lib.rs") });
    }
    if src.join("main.rs").is_file() {
        crates.push(CrateRoot { kind: CrateKind::Bin, root: src.join("main.rs") });
    }
    if crates.is_empty() {
        return Err(ArchError::NoCrateRoot(dir.to_path_buf()));
    }
    Ok(crates)
}

/// The entries of a directory, sorted.
fn list_dir(dir: &Path) -> Result<Vec<PathBuf>, ArchError> {
    let read_err = |source| ArchError::Read { path: dir.to_path_buf(), source };
    let mut entries = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_err)? {
        entries.push(entry.map_err(read_err)?.path());
    }
    entries.sort();
    Ok(entries)
}

/// Every `.rs` file under `dir`, recursively, sorted; empty if `dir` does not exist.
pub fn rust_files(dir: &Path) -> Result<Vec<PathBuf>, ArchError> {
    let mut files = Vec::new();
    if dir.is_dir() {
        collect_rust_files(dir, &mut files)?;
    }
    files.sort();
    Ok(files)
}

/// Adds the `.rs` files under `dir` to `files`.
fn collect_rust_files(dir: &Path, files: &mut Vec<PathBuf>) -> Result<(), ArchError> {
    for path in list_dir(dir)? {
        if path.is_dir() {
            collect_rust_files(&path, files)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    Ok(())
}

/// A path as the document writes it: relative, with `/` separators.
pub fn slash_path(path: &Path) -> String {
    path.components().map(|c| c.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/")
}

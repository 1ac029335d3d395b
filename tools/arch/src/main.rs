//! `strata-arch`: checks the workspace's structure and prints what is wrong.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use strata_arch::workspace::{crates_in, slash_path};

/// Checks the workspace's structure: import circles, the module table and the walk of
/// docs/architecture.md, and file lengths.
#[derive(Parser)]
#[command(name = "strata-arch", version)]
struct Cli {
    /// What to do.
    #[command(subcommand)]
    command: Command,
}

/// The subcommands.
#[derive(Subcommand)]
enum Command {
    /// Runs every check on the repository; exits 1 if anything is wrong.
    Check {
        /// The repository root (default: the nearest directory upwards with a workspace Cargo.toml).
        #[arg(long)]
        repo: Option<PathBuf>,
    },
    /// Prints the import circles of the crates in the given directories; exits 1 if any.
    Circles {
        /// Crate `src` directories (or package directories holding `src`).
        #[arg(required = true)]
        dirs: Vec<PathBuf>,
    },
    /// Prints every edge of the import graph of the crates in a directory.
    Graph {
        /// A crate `src` directory (or a package directory holding `src`).
        dir: PathBuf,
    },
}

/// The nearest directory from the current one upwards whose `Cargo.toml` has `[workspace]`.
fn find_repo() -> Result<PathBuf> {
    let cwd = std::env::current_dir().context("reading the current directory")?;
    for dir in cwd.ancestors() {
        let manifest = dir.join("Cargo.toml");
        if let Ok(text) = std::fs::read_to_string(&manifest) {
            if text.lines().any(|l| l.trim() == "[workspace]") {
                return Ok(dir.to_path_buf());
            }
        }
    }
    bail!("no workspace Cargo.toml in {} or above; pass --repo", cwd.display())
}

/// Writes `text` to standard output; a closed pipe (`| head`) ends the output quietly.
fn emit(text: &str) -> Result<()> {
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other.context("writing to standard output"),
    }
}

/// Runs `check` and prints the report.
fn check(repo: Option<PathBuf>) -> Result<ExitCode> {
    let repo = match repo {
        Some(r) => r,
        None => find_repo()?,
    };
    let report = strata_arch::check(&repo).with_context(|| format!("checking {}", repo.display()))?;
    emit(&report.to_string())?;
    Ok(if report.has_problems() { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}

/// Prints the circles of each directory's crates.
fn circles(dirs: &[PathBuf]) -> Result<ExitCode> {
    let mut any = false;
    let mut text = String::new();
    for dir in dirs {
        for c in strata_arch::circles_in(dir).with_context(|| format!("reading {}", dir.display()))? {
            any |= !c.circles.is_empty();
            strata_arch::report::write_circles(&mut text, &c)?;
        }
    }
    emit(&text)?;
    Ok(if any { ExitCode::FAILURE } else { ExitCode::SUCCESS })
}

/// Prints every edge of a directory's crates.
fn graph(dir: &Path) -> Result<ExitCode> {
    let mut text = String::new();
    for root in crates_in(dir)? {
        let g = strata_arch::crate_graph(&root.root).with_context(|| format!("reading {}", root.root.display()))?;
        text += &format!("# {} ({} files, {} edges)\n", root.root.display(), g.files.len(), g.edges.len());
        for e in &g.edges {
            text += &format!("{} -> {}: {}\n", slash_path(&e.from), slash_path(&e.to), e.names.join(", "));
        }
    }
    emit(&text)?;
    Ok(ExitCode::SUCCESS)
}

fn main() -> Result<ExitCode> {
    match Cli::parse().command {
        Command::Check { repo } => check(repo),
        Command::Circles { dirs } => circles(&dirs),
        Command::Graph { dir } => graph(&dir),
    }
}

//! The fuzz targets under `fuzz/` (a cargo-fuzz project) build, replay a sample of their
//! checked-in corpora and fuzz a few seconds each without a crash, panic, hang or runaway
//! allocation. Long runs, over whole corpora, are `cargo +nightly fuzz run TARGET` by hand
//! (docs/fuzzing.md); this keeps the targets compiling against the code they fuzz.

mod support;

use std::path::Path;
use std::process::{Command, Output};
use std::time::Instant;

use support::TempDir;

/// Each target and how many seconds it fuzzes after replaying its sample.
const TARGETS: &[(&str, u32)] = &[("ring_reader", 2), ("ring_race", 2), ("decoder", 2), ("glsl", 4), ("executor", 6)];
/// Corpus files replayed per target: the unoptimised build takes about 0.1 s for a shader or
/// an executor input, and a whole corpus has thousands.
const SAMPLE: usize = 64;

/// Copies the first `SAMPLE` files (by name, which is a content hash) of `corpus` into `dir`.
fn sample(corpus: &Path, dir: &Path) {
    let mut names: Vec<_> = std::fs::read_dir(corpus)
        .unwrap_or_else(|e| panic!("{}: {e}", corpus.display()))
        .map(|e| e.expect("corpus entry").path())
        .collect();
    names.sort();
    for src in names.iter().take(SAMPLE) {
        std::fs::copy(src, dir.join(src.file_name().expect("a file name"))).expect("copy a corpus file");
    }
}

/// `cargo [+nightly] fuzz ARGS` in the repository root, with the variables of the `cargo test`
/// that runs this removed, so that the fuzz project builds in its own target directory with
/// its own flags. Without a sanitizer nothing needs nightly, so the default toolchain serves
/// where nightly is not installed.
fn cargo_fuzz(root: &Path, nightly: bool, args: &[&str]) -> Output {
    let mut cmd = Command::new("cargo");
    if nightly {
        cmd.arg("+nightly");
    }
    cmd.arg("fuzz")
        .args(args)
        .current_dir(root)
        .env_remove("CARGO")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET_DIR")
        .env_remove("RUSTFLAGS")
        .env_remove("RUSTUP_TOOLCHAIN")
        .output()
        .expect("run cargo fuzz")
}

/// Whether `cargo +nightly` runs, i.e. the nightly toolchain is installed.
fn nightly_installed() -> bool {
    Command::new("cargo")
        .args(["+nightly", "--version"])
        .env_remove("RUSTUP_TOOLCHAIN")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The last `n` lines of a run's output, for a failure message.
fn tail(out: &Output, n: usize) -> String {
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let lines: Vec<&str> = text.lines().collect();
    lines[lines.len().saturating_sub(n)..].join("\n")
}

#[test]
fn fuzz_targets_run_clean() {
    if !support::nothing_missing(if support::which("cargo-fuzz").is_some() { &[] } else { &["cargo-fuzz"] }) {
        return;
    }
    let nightly = nightly_installed();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("the repository root");
    let start = Instant::now();
    // Unoptimised and without a sanitizer: the build dominates this test, and a few seconds
    // of fuzzing need no speed.
    let out = cargo_fuzz(root, nightly, &["build", "--dev", "--sanitizer", "none"]);
    assert!(out.status.success(), "cargo fuzz build failed:\n{}", tail(&out, 40));
    eprintln!("fuzz targets built in {:.0?}", start.elapsed());
    for &(target, seconds) in TARGETS {
        let started = Instant::now();
        // New inputs and any crash go to a scratch directory; the checked-in corpus is only read.
        let scratch = TempDir::new(&format!("fuzz-{target}"));
        let scratch_dir = scratch.0.to_str().expect("a UTF-8 temporary directory");
        let seeds = TempDir::new(&format!("fuzz-{target}-sample"));
        sample(&root.join("fuzz/corpus").join(target), &seeds.0);
        let corpus = seeds.0.to_str().expect("a UTF-8 temporary directory");
        let max_time = format!("-max_total_time={seconds}");
        let artifacts = format!("-artifact_prefix={scratch_dir}/");
        let out = cargo_fuzz(
            root,
            nightly,
            &[
                "run",
                "--dev",
                "--sanitizer",
                "none",
                target,
                scratch_dir,
                corpus,
                "--",
                &max_time,
                "-rss_limit_mb=2048",
                "-timeout=10",
                &artifacts,
            ],
        );
        assert!(out.status.success(), "fuzz target {target} failed ({}):\n{}", out.status, tail(&out, 60));
        let summary = tail(&out, 3);
        eprintln!("{target}: {:.0?}; {}", started.elapsed(), summary.replace('\n', "; "));
    }
}

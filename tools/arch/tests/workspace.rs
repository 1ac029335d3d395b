//! The real repository passes every check: no import circles, a complete and current module
//! table, a walk whose steps name real functions and whose counts match, no long files.

use std::path::Path;

#[test]
fn the_repository_has_no_structural_problems() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let started = std::time::Instant::now();
    let report = strata_arch::check(&repo).expect("the repository can be checked");
    let elapsed = started.elapsed();
    assert!(!report.has_problems(), "{report}");
    assert!(elapsed.as_secs() < 5, "the check took {elapsed:?}");
}

//! The executor against Mesa: every program below is written once against `Calls` and rendered
//! twice, through `stratad` (wgpu on lavapipe) and through the system's Mesa GLES2 (llvmpipe).
//! The two images must agree within the tolerance stated beside each program; the default is
//! at most 1/255 per channel on at least 99.9 % of pixels. On failure the actual, expected and
//! difference images are written under `target/oracle-failures/`.

mod programs;
mod support;

use programs::harness::{judge, render, strata_context};
use programs::{H, W};
use strata_client::{Calls, ClientError};
use support::mesa::MesaGl;
use support::Daemon;

#[test]
fn executor_matches_mesa() {
    matches_mesa("oracle", &[]);
}

/// Mesa's GLES2 is loaded into this process, and its contexts must not be used from two
/// test threads at once.
static MESA: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Renders every program through a daemon started with `daemon_args` and through Mesa, and
/// fails listing every program whose images differ.
fn matches_mesa(tag: &str, daemon_args: &[&str]) {
    let _one_at_a_time = MESA.lock().unwrap_or_else(|e| e.into_inner());
    let cases = programs::all();
    assert!(cases.len() >= 30, "the suite must have at least 30 programs");
    let cases = support::only(cases, |c| c.name);
    // Mesa held to ES 2.0, as Strata's contexts are (before its first context in this process).
    std::env::set_var("MESA_GLES_VERSION_OVERRIDE", "2.0");
    let mut mesa_probe = match MesaGl::open(W, H) {
        Ok(m) => m,
        Err(e) if std::env::var_os("STRATA_REQUIRE_ORACLES").is_none() => {
            eprintln!("SKIPPED: Mesa GLES2 unavailable ({e}); install libegl-mesa0 libgles2 to run the oracle suite");
            return;
        }
        Err(e) => panic!("Mesa GLES2 unavailable ({e}) and STRATA_REQUIRE_ORACLES is set"),
    };
    eprintln!("reference: {}", mesa_probe.renderer);
    let _ = mesa_probe.glFinish();
    drop(mesa_probe);
    let daemon = Daemon::start(tag, daemon_args);
    let out_dir =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target").join(format!("{tag}-failures"));
    let mut failures = Vec::new();
    for case in &cases {
        let expected = MesaGl::open(W, H).map_err(ClientError::Unsupported).and_then(|mut m| render(&mut m, case));
        let actual = strata_context(&daemon.socket, case.name).and_then(|mut c| render(&mut c, case));
        match (actual, expected) {
            (Ok(a), Ok(e)) => failures.extend(judge(case, &a, &e, &out_dir)),
            (Err(e), _) => failures.push(format!("{}: through stratad: {e}", case.name)),
            (_, Err(e)) => failures.push(format!("{}: through Mesa: {e}", case.name)),
        }
    }
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")), "daemon panicked");
    let warnings: Vec<String> =
        daemon.log_text().lines().filter(|l| !l.contains(" INFO ")).map(str::to_string).collect();
    assert!(
        failures.is_empty(),
        "{} of {} programs differ from Mesa:\n{}\ndaemon warnings:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n"),
        warnings.join("\n")
    );
}

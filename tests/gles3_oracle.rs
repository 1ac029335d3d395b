//! OpenGL ES 3.0 against Mesa held to ES 3.0 (`MESA_GLES_VERSION_OVERRIDE=3.0`, asserted from
//! its `GL_VERSION`): the version queries and errors of an ES 3.0 context, and every program of
//! `programs::es3` rendered in an ES 3.0 context through `stratad --es3` and through Mesa, the
//! images compared as `gles_oracle.rs` compares them. Mesa reads the override once per process,
//! so ES 3.0 has a test binary of its own.

mod programs;
mod support;

use programs::harness::{judge, render};
use programs::{H, W};
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use support::mesa::MesaGl;
use support::Daemon;

/// Mesa's contexts must not be used from two test threads at once.
static MESA: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// `GL_MAJOR_VERSION`, `GL_MINOR_VERSION`, `GL_NUM_EXTENSIONS`, `GL_EXTENSIONS`, `GL_VERSION`.
const MAJOR_VERSION: u32 = 0x821B;
const MINOR_VERSION: u32 = 0x821C;
const NUM_EXTENSIONS: u32 = 0x821D;
const EXTENSIONS: u32 = 0x1F03;
const VERSION: u32 = 0x1F02;
const SHADING_LANGUAGE_VERSION: u32 = 0x8B8C;

/// Mesa held to ES 3.0 with an ES 3.0 context, or `None` where the test skips (oracles not
/// required and Mesa missing).
fn mesa_es3() -> Option<MesaGl> {
    std::env::set_var("MESA_GLES_VERSION_OVERRIDE", "3.0");
    match MesaGl::open_version(W, H, 3) {
        Ok(mut m) => {
            let version = m.glGetString(VERSION).ok().flatten().unwrap_or_default();
            assert!(version.starts_with("OpenGL ES 3.0 "), "Mesa must be held to ES 3.0: {version}");
            Some(m)
        }
        Err(e) if !support::oracles_required() => {
            eprintln!("SKIPPED: Mesa ES 3.0 unavailable ({e})");
            None
        }
        Err(e) => panic!("Mesa ES 3.0 unavailable ({e}) and STRATA_REQUIRE_ORACLES is set"),
    }
}

/// An ES 3.0 context on a pbuffer through the daemon at `socket`.
fn strata_es3(socket: &std::path::Path, name: &str) -> Result<Connection, ClientError> {
    let opts = ConnectOptions { socket: socket.to_path_buf(), name: name.into(), ..ConnectOptions::default() };
    let mut c = Connection::connect(&opts)?;
    strata_client::setup::egl_context_es3(
        &mut c,
        24,
        8,
        strata_client::setup::SurfaceKind::Pbuffer { width: W, height: H },
    )?;
    Ok(c)
}

/// What a context answers about its version: (major, minor), the strings' version parts,
/// whether `glGetStringi` lists exactly `GL_EXTENSIONS` (`GL_NUM_EXTENSIONS` of them), and
/// `glGetStringi`'s answers and errors past the end and for another name.
fn version_answers(gl: &mut dyn Calls<Error = ClientError>) -> Result<Vec<String>, ClientError> {
    let int = |gl: &mut dyn Calls<Error = ClientError>, p| -> Result<i32, ClientError> {
        Ok(gl.glGetIntegerv(p)?.first().copied().unwrap_or(-1))
    };
    let mut out = Vec::new();
    out.push(format!("major {} minor {}", int(gl, MAJOR_VERSION)?, int(gl, MINOR_VERSION)?));
    let version = gl.glGetString(VERSION)?.unwrap_or_default();
    out.push(format!("version {}", version.split(' ').take(3).collect::<Vec<_>>().join(" ")));
    out.push(format!("language {}", gl.glGetString(SHADING_LANGUAGE_VERSION)?.unwrap_or_default()));
    let count = int(gl, NUM_EXTENSIONS)?;
    let listed = gl.glGetString(EXTENSIONS)?.unwrap_or_default();
    let mut by_index = Vec::new();
    for i in 0..count.max(0) as u32 {
        by_index.push(gl.glGetStringi(EXTENSIONS, i)?.unwrap_or_default());
    }
    // The same extensions, each once; the order is each implementation's (Mesa sorts one list
    // by name and the other by year).
    let mut whole: Vec<&str> = listed.split_whitespace().collect();
    whole.sort_unstable();
    by_index.sort_unstable();
    out.push(format!("stringi lists GL_EXTENSIONS: {}", by_index == whole));
    out.push(format!("error {:#x}", gl.glGetError()?));
    let past = gl.glGetStringi(EXTENSIONS, count as u32)?;
    out.push(format!("past the end {past:?} error {:#x}", gl.glGetError()?));
    let other = gl.glGetStringi(VERSION, 0)?;
    out.push(format!("another name {other:?} error {:#x}", gl.glGetError()?));
    Ok(out)
}

#[test]
fn an_es3_context_answers_its_version_as_mesa_does() {
    let _one_at_a_time = MESA.lock().unwrap_or_else(|e| e.into_inner());
    let Some(mut mesa) = mesa_es3() else { return };
    let expected = version_answers(&mut mesa).expect("Mesa");
    let daemon = Daemon::start("es3-version", &["--es3"]);
    let mut c = strata_es3(&daemon.socket, "es3-version").expect("an ES 3.0 context");
    let actual = version_answers(&mut c).expect("Strata");
    // The extension lists are each implementation's own; everything else is the same.
    assert_eq!(actual, expected);
    // Without --es3, version 3 is refused as Mesa held to ES 2.0 refuses it.
    let plain = Daemon::start("es3-refused", &[]);
    match strata_es3(&plain.socket, "es3-refused") {
        Err(e) => assert!(e.to_string().contains("0x3009"), "EGL_BAD_MATCH: {e}"),
        Ok(_) => panic!("an ES 3.0 context from a daemon that does not offer ES 3.0"),
    }
}

#[test]
fn es3_programs_match_mesa() {
    let _one_at_a_time = MESA.lock().unwrap_or_else(|e| e.into_inner());
    let cases = support::only(programs::es3::all(), |c| c.name);
    let Some(probe) = mesa_es3() else { return };
    eprintln!("reference: {}", probe.renderer);
    drop(probe);
    let daemon = Daemon::start("es3-oracle", &["--es3"]);
    let out_dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/es3-oracle-failures");
    let mut failures = Vec::new();
    for case in &cases {
        let expected =
            MesaGl::open_version(W, H, 3).map_err(ClientError::Unsupported).and_then(|mut m| render(&mut m, case));
        let actual = strata_es3(&daemon.socket, case.name).and_then(|mut c| render(&mut c, case));
        match (actual, expected) {
            (Ok(a), Ok(e)) => failures.extend(judge(case, &a, &e, &out_dir)),
            (Err(e), _) => failures.push(format!("{}: through stratad: {e}", case.name)),
            (_, Err(e)) => failures.push(format!("{}: through Mesa: {e}", case.name)),
        }
    }
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")), "daemon panicked");
    assert!(
        failures.is_empty(),
        "{} of {} ES 3.0 programs differ from Mesa:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

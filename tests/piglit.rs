//! piglit, the OpenGL conformance suite, as the oracle for Strata's GLES 2.0 and GLSL ES 1.00:
//! piglit's GLES 2.0 selection (read from piglit's own metadata, `piglit/selection.rs`) runs
//! natively on Mesa (llvmpipe) held to ES 2.0 (`MESA_GLES_VERSION_OVERRIDE=2.0`: Mesa then
//! creates only ES 2.0 contexts, with only the extensions an ES 2.0 context has) and through
//! `stratad` with the drop-in libEGL/libGLESv2, each under its own Xvfb. Every test that passes
//! natively must pass through Strata, unless `tests/piglit/exceptions.txt` excuses it.
//! Entries that pass through Strata again are stale and fail the test too, so the file stays
//! honest.
//!
//! Results stay under `target/piglit/{native,strata}` (piglit's `results.json`, the daemon's
//! log) and the verdict is written to `target/strata-tests/piglit.txt`.

#[path = "piglit/selection.rs"]
mod selection;
mod support;
#[path = "piglit/verdict.rs"]
mod verdict;

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::{Daemon, TempDir, Xvfb};
use verdict::{Run, Verdict};

/// Where Debian's piglit keeps its test profiles.
const TESTS: &str = "/usr/lib/x86_64-linux-gnu/piglit/tests";
/// Where it keeps its test programs.
const BIN: &str = "/usr/lib/x86_64-linux-gnu/piglit/bin";
/// The profiles the selection is drawn from.
const PROFILES: &[&str] = &["opengl.xml.gz", "shader.xml.gz", "glslparser.xml.gz"];
/// What the native side's version string must start with: Mesa held to ES 2.0.
const NATIVE_VERSION: &str = "OpenGL ES 2.0";
/// piglit kills a test that runs longer than this and records `timeout`.
const PER_TEST_TIMEOUT_S: u32 = 60;
/// A whole run that takes longer than this is killed and fails the test.
const RUN_DEADLINE: Duration = Duration::from_secs(900);
/// Mesa held to ES 2.0 passes about 190 tests of the selection; far fewer means the oracle
/// itself is broken.
const NATIVE_PASS_FLOOR: usize = 160;

/// Whether piglit, wflinfo and Xvfb are installed; if not, the test skips with the reason,
/// unless `STRATA_REQUIRE_ORACLES=1` (CI), where it fails.
fn oracles_present() -> bool {
    let mut missing: Vec<&str> =
        ["piglit", "wflinfo", "Xvfb"].into_iter().filter(|p| support::which(p).is_none()).collect();
    if !Path::new(TESTS).join(PROFILES[0]).is_file() {
        missing.push(TESTS);
    }
    support::nothing_missing(&missing)
}

/// The workspace's target directory (where cargo put `stratad`).
fn target_dir() -> PathBuf {
    PathBuf::from(support::stratad()).parent().and_then(Path::parent).expect("target dir").to_path_buf()
}

/// The checked-in exceptions file.
fn exceptions_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/piglit/exceptions.txt")
}

/// One side of the comparison: the environment its programs run in.
struct Side {
    name: &'static str,
    display: String,
    /// Extra variables; everything that could route GL elsewhere is removed first.
    env: Vec<(&'static str, PathBuf)>,
}

impl Side {
    fn command(&self, program: &str) -> Command {
        let mut cmd = Command::new(program);
        for var in ["LD_LIBRARY_PATH", "LD_PRELOAD", "STRATA_SOCKET", "STRATA_WINDOW", "STRATA_CHECK_ERRORS"] {
            cmd.env_remove(var);
        }
        // No Mesa override of the caller's may reach either side (`MESA_GL_VERSION_OVERRIDE`,
        // `MESA_EXTENSION_OVERRIDE`, …): each side sets what it needs below.
        for (var, _) in std::env::vars_os() {
            if var.to_string_lossy().starts_with("MESA_") {
                cmd.env_remove(var);
            }
        }
        cmd.env("DISPLAY", &self.display).env("PIGLIT_PLATFORM", "x11_egl").env("PIGLIT_COMPRESSION", "none");
        cmd.envs(self.env.iter().map(|(k, v)| (k, v.as_os_str())));
        cmd
    }

    /// The renderer and version string wflinfo reports for an ES 2 context on this side.
    fn renderer(&self) -> (String, String) {
        let out = self.command("wflinfo").args(["-p", "x11_egl", "-a", "gles2"]).output().expect("run wflinfo");
        let text = String::from_utf8_lossy(&out.stdout);
        let line = |key: &str| text.lines().find_map(|l| l.strip_prefix(key)).unwrap_or("?").trim().to_string();
        let renderer = line("OpenGL renderer string:");
        let version = line("OpenGL version string:");
        eprintln!("{}: wflinfo: {renderer}, {version}", self.name);
        assert!(
            out.status.success(),
            "{}: wflinfo failed: {}{}",
            self.name,
            text,
            String::from_utf8_lossy(&out.stderr)
        );
        (renderer, version)
    }

    /// Runs the tests of `profile` into `results` and reads them back, with the wall time.
    fn run_piglit(&self, profile: &Path, results: &Path) -> (Run, Duration) {
        let _ = std::fs::remove_dir_all(results);
        std::fs::create_dir_all(results).expect("results dir");
        let log = results.with_extension("log");
        let mut cmd = self.command("piglit");
        cmd.args(["run", "-o", "-l", "dummy", "-p", "x11_egl", "--timeout", &PER_TEST_TIMEOUT_S.to_string()]);
        cmd.arg(profile).arg(results);
        let file = std::fs::File::create(&log).expect("piglit log");
        cmd.stdin(Stdio::null()).stdout(file.try_clone().expect("log")).stderr(file);
        // Its own process group, so that a deadline takes piglit's tests down with it.
        cmd.process_group(0);
        let start = Instant::now();
        let mut child = cmd.spawn().expect("spawn piglit");
        let status = loop {
            if let Some(s) = child.try_wait().expect("try_wait") {
                break s;
            }
            if start.elapsed() > RUN_DEADLINE {
                // SAFETY: kill(2) on the process group of our own child.
                unsafe { libc::kill(-(child.id() as i32), libc::SIGKILL) };
                let _ = child.wait();
                panic!("{}: piglit ran past {RUN_DEADLINE:?}; log: {}", self.name, log.display());
            }
            std::thread::sleep(Duration::from_millis(100));
        };
        let elapsed = start.elapsed();
        let text = std::fs::read_to_string(&log).unwrap_or_default();
        assert!(status.success(), "{}: piglit run failed ({status}):\n{text}", self.name);
        let run = verdict::load_run(results).unwrap_or_else(|e| panic!("{}: {e}\npiglit said:\n{text}", self.name));
        (run, elapsed)
    }
}

/// The summary written to `target/strata-tests/piglit.txt`.
fn summary(native: (&Run, Duration), strata: (&Run, Duration), v: &Verdict, rerun: &str) -> String {
    let mut s = String::new();
    let mut line = |l: String| {
        s.push_str(&l);
        s.push('\n');
    };
    line(format!(
        "piglit selection: the tests of {} on GLES 2.0 and GLSL ES 1.00, by piglit's metadata (tests/piglit/selection.rs); native side held to {NATIVE_VERSION}",
        PROFILES.join(" ")
    ));
    line(format!("native (Mesa):   {} in {:.1}s", verdict::counts_line(native.0), native.1.as_secs_f64()));
    line(format!("through stratad: {} in {:.1}s", verdict::counts_line(strata.0), strata.1.as_secs_f64()));
    let native_passes = native.0.values().filter(|o| o.result == "pass").count();
    let both = native.0.iter().filter(|(n, o)| o.result == "pass" && strata.0[*n].result == "pass").count();
    line(format!(
        "of {native_passes} native passes: {both} pass through stratad, {} excused, {} regressions",
        v.excused,
        v.regressions.len()
    ));
    line(String::new());
    line(format!("To re-run one test by hand through stratad:\n  {rerun} <command below>\n"));
    if !v.regressions.is_empty() {
        line(format!("Pass natively, not through stratad ({}):", v.regressions.len()));
        for name in &v.regressions {
            let o = &strata.0[name];
            line(format!("  {name}: {} — {}", o.result, verdict::key_line(o)));
            line(format!("      {}", o.command));
        }
        line(String::new());
    }
    for (title, list) in [
        ("Stale exceptions: they pass through stratad now; remove them", &v.stale),
        ("Unknown exceptions: not a test of the selection", &v.unknown),
        ("Exceptions that do not pass natively either (harmless)", &v.unused),
    ] {
        if !list.is_empty() {
            line(format!("{title} ({}):", list.len()));
            for e in list {
                line(format!("  exceptions.txt:{}: {}", e.line, e.name));
            }
            line(String::new());
        }
    }
    s
}

#[test]
fn piglit_passes_through_stratad_wherever_it_passes_on_mesa() {
    let exceptions_text = std::fs::read_to_string(exceptions_path()).expect("read tests/piglit/exceptions.txt");
    let exceptions = verdict::parse_exceptions(&exceptions_text).expect("tests/piglit/exceptions.txt");
    if !oracles_present() {
        return;
    }
    let out_dir = target_dir().join("piglit");
    std::fs::create_dir_all(&out_dir).expect("target/piglit");

    // The oracle: Mesa's own libraries (LIBGL_ALWAYS_SOFTWARE keeps it on llvmpipe where a GPU
    // exists), nothing of Strata's on the library path.
    let selected = selection::select(Path::new(TESTS), Path::new(BIN), PROFILES).expect("piglit's profiles");
    let list = out_dir.join("gles2.xml.gz");
    selection::write_profile(&list, &selected).expect("write the selection's profile");
    eprintln!("selection: {} tests of piglit's GLES 2.0 build and GLSL ES 1.00 ({})", selected.len(), list.display());
    let x_native = Xvfb::start(1024, 768).expect("Xvfb");
    let native = Side {
        name: "native",
        display: x_native.display.clone(),
        env: vec![("LIBGL_ALWAYS_SOFTWARE", "1".into()), ("MESA_GLES_VERSION_OVERRIDE", "2.0".into())],
    };
    let (renderer, version) = native.renderer();
    assert!(
        renderer.contains("llvmpipe") && !renderer.contains("Strata"),
        "the native run must use Mesa's llvmpipe, but wflinfo reports {renderer:?}"
    );
    assert!(
        version.starts_with(NATIVE_VERSION),
        "the native side must be held to ES 2.0, but wflinfo reports {version:?}"
    );
    let (native_run, native_time) = native.run_piglit(&list, &out_dir.join("native"));
    eprintln!("native (Mesa):   {} in {:.1}s", verdict::counts_line(&native_run), native_time.as_secs_f64());
    let native_passes = native_run.values().filter(|o| o.result == "pass").count();
    assert!(
        native_passes >= NATIVE_PASS_FLOOR,
        "Mesa passes only {native_passes} tests (expected about 190): the oracle is broken; see {}",
        out_dir.join("native.log").display()
    );

    // Through Strata: its own X server, daemon, socket, and the drop-in libraries.
    let x_strata = Xvfb::start(1024, 768).expect("Xvfb");
    let tmp = TempDir::new("piglit");
    let shim = support::shim_dir(&tmp);
    let daemon = Daemon::start("piglit", &["--output", "headless:main=640x480"]);
    // piglit's GLES utility library (built with GLX) resolves extension entry points with
    // libGL's glXGetProcAddressARB, whose stubs call nothing without a GLX context. The
    // drop-in answers that query too, and is preloaded so that its answer comes first.
    let strata = Side {
        name: "strata",
        display: x_strata.display.clone(),
        env: vec![
            ("LD_LIBRARY_PATH", shim.clone()),
            ("LD_PRELOAD", shim.join("libEGL.so.1")),
            ("STRATA_SOCKET", daemon.socket.clone()),
        ],
    };
    let (renderer, _) = strata.renderer();
    assert!(renderer.starts_with("Strata"), "the run through stratad reaches {renderer:?} instead");
    let (strata_run, strata_time) = strata.run_piglit(&list, &out_dir.join("strata"));
    eprintln!("through stratad: {} in {:.1}s", verdict::counts_line(&strata_run), strata_time.as_secs_f64());
    let _ = std::fs::write(out_dir.join("stratad.log"), daemon.log_text());
    assert_eq!(
        native_run.keys().collect::<Vec<_>>(),
        strata_run.keys().collect::<Vec<_>>(),
        "both runs must hold the same tests"
    );

    let v = verdict::judge(&native_run, &strata_run, &exceptions);
    let rerun = "stratad serve --socket /tmp/s.sock & Xvfb :9 -noreset & DISPLAY=:9 PIGLIT_PLATFORM=x11_egl \
                 PIGLIT_SOURCE_DIR=/usr/lib/x86_64-linux-gnu/piglit LD_LIBRARY_PATH=$(tools/build-shim) \
                 LD_PRELOAD=target/strata-gl/libEGL.so.1 STRATA_SOCKET=/tmp/s.sock";
    let text = summary((&native_run, native_time), (&strata_run, strata_time), &v, rerun);
    let report_dir = target_dir().join("strata-tests");
    std::fs::create_dir_all(&report_dir).expect("target/strata-tests");
    let report = report_dir.join("piglit.txt");
    std::fs::write(&report, &text).expect("write the summary");
    eprintln!("{} native passes excused by exceptions.txt; summary in {}", v.excused, report.display());
    assert!(v.ok(), "piglit through stratad falls short of Mesa (full results in {}):\n{text}", out_dir.display());
}

/// The checked-in exceptions file parses, and excuses nothing that is in scope.
#[test]
fn exceptions_file_is_well_formed() {
    let text = std::fs::read_to_string(exceptions_path()).expect("read tests/piglit/exceptions.txt");
    let list = verdict::parse_exceptions(&text).unwrap_or_else(|e| panic!("tests/piglit/exceptions.txt: {e}"));
    assert!(!list.is_empty());
}

/// The selection holds piglit's GLES 2 tests and no other: known members of each kind are in,
/// the GLES 3, GLES 1 and desktop builds' tests are out.
#[test]
fn the_selection_is_piglits_gles2_build_and_glsl_es_1_00() {
    if !oracles_present() {
        return;
    }
    let selected = selection::select(Path::new(TESTS), Path::new(BIN), PROFILES).expect("piglit's profiles");
    let names: std::collections::HashSet<&str> = selected.iter().map(|t| t.name.as_str()).collect();
    for inside in [
        // C tests of the GLES 2 build, with and without the suffix.
        "spec@!opengl es 2.0@invalid-es3-queries_gles2",
        "spec@glsl-es-1.00@linker@glsl-fface-invariant",
        "spec@oes_texture_float@oes_texture_float",
        // shader_runner and glslparsertest with API gles2 and GLSL ES 1.00.
        "spec@oes_standard_derivatives@compiler@fwidth-vec4.frag",
    ] {
        assert!(names.contains(inside), "{inside} is missing from the selection");
    }
    for outside in [
        // GLES 3 build, GLES 1 build, desktop GL, GLSL ES 3.00.
        "spec@oes_texture_view@formats",
        "spec@oes_compressed_etc1_rgb8_texture@basic",
        "shaders@glsl-bindattriblocation",
        "spec@oes_standard_derivatives@preprocessor@enabled-es.comp",
    ] {
        assert!(!names.contains(outside), "{outside} is in the selection");
    }
    assert!(selected.iter().all(|t| t.xml.starts_with("<Test ") && t.xml.ends_with("</Test>")));
}

//! piglit, the OpenGL conformance suite, as the oracle for Strata's GLES 2.0 and GLSL ES 1.00:
//! piglit's GLES 2.0 selection runs natively on Mesa (llvmpipe) and through `stratad` with the
//! drop-in libEGL/libGLESv2, each under its own Xvfb, and every test that passes natively must
//! pass through Strata, unless `tests/piglit/exceptions.txt` excuses it (it needs an ES 3.x or
//! desktop GL context, or an extension Strata does not offer). Entries that pass through Strata
//! again are stale and fail the test too, so the file stays honest.
//!
//! Results stay under `target/piglit/{native,strata}` (piglit's `results.json`, the daemon's
//! log) and the verdict is written to `target/strata-tests/piglit.txt`.

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
/// The profiles the selection is drawn from.
const PROFILES: &[&str] = &["opengl.xml.gz", "shader.xml.gz", "glslparser.xml.gz"];
/// `-t` filters: GLES 2.0, GLSL ES 1.00 and the ES extensions.
const INCLUDE: &[&str] = &["glsl-es-1.00", "opengl es 2.0", "_gles2", "gles2$", "oes_", "ext_frag_depth"];
/// `-x` filter: everything ES 3.
const EXCLUDE: &str = "gles3|gles-3|es 3|glsl-es-3";
/// piglit kills a test that runs longer than this and records `timeout`.
const PER_TEST_TIMEOUT_S: u32 = 60;
/// A whole run that takes longer than this is killed and fails the test.
const RUN_DEADLINE: Duration = Duration::from_secs(900);
/// Mesa passes about 300 tests of the selection; far fewer means the oracle itself is broken.
const NATIVE_PASS_FLOOR: usize = 250;

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
        cmd.env("DISPLAY", &self.display).env("PIGLIT_PLATFORM", "x11_egl").env("PIGLIT_COMPRESSION", "none");
        cmd.envs(self.env.iter().map(|(k, v)| (k, v.as_os_str())));
        cmd
    }

    /// The renderer wflinfo reports for an ES 2 context on this side.
    fn renderer(&self) -> String {
        let out = self.command("wflinfo").args(["-p", "x11_egl", "-a", "gles2"]).output().expect("run wflinfo");
        let text = String::from_utf8_lossy(&out.stdout);
        let line = |key: &str| text.lines().find_map(|l| l.strip_prefix(key)).unwrap_or("?").trim().to_string();
        let renderer = line("OpenGL renderer string:");
        eprintln!("{}: wflinfo: {renderer}, {}", self.name, line("OpenGL version string:"));
        assert!(
            out.status.success(),
            "{}: wflinfo failed: {}{}",
            self.name,
            text,
            String::from_utf8_lossy(&out.stderr)
        );
        renderer
    }

    /// Runs the selection into `results` and reads it back, with the wall time.
    fn run_piglit(&self, results: &Path) -> (Run, Duration) {
        let _ = std::fs::remove_dir_all(results);
        std::fs::create_dir_all(results).expect("results dir");
        let log = results.with_extension("log");
        let mut cmd = self.command("piglit");
        cmd.args(["run", "-o", "-l", "dummy", "-p", "x11_egl", "--timeout", &PER_TEST_TIMEOUT_S.to_string()]);
        for t in INCLUDE {
            cmd.args(["-t", t]);
        }
        cmd.args(["-x", EXCLUDE]);
        cmd.args(PROFILES.iter().map(|p| Path::new(TESTS).join(p))).arg(results);
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
    line(format!("piglit selection: -t {} -x '{EXCLUDE}' {}", INCLUDE.join(" -t "), PROFILES.join(" ")));
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
    let x_native = Xvfb::start(1024, 768).expect("Xvfb");
    let native =
        Side { name: "native", display: x_native.display.clone(), env: vec![("LIBGL_ALWAYS_SOFTWARE", "1".into())] };
    let renderer = native.renderer();
    assert!(
        renderer.contains("llvmpipe") && !renderer.contains("Strata"),
        "the native run must use Mesa's llvmpipe, but wflinfo reports {renderer:?}"
    );
    let (native_run, native_time) = native.run_piglit(&out_dir.join("native"));
    eprintln!("native (Mesa):   {} in {:.1}s", verdict::counts_line(&native_run), native_time.as_secs_f64());
    let native_passes = native_run.values().filter(|o| o.result == "pass").count();
    assert!(
        native_passes >= NATIVE_PASS_FLOOR,
        "Mesa passes only {native_passes} tests (expected about 300): the oracle is broken; see {}",
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
    let renderer = strata.renderer();
    assert!(renderer.starts_with("Strata"), "the run through stratad reaches {renderer:?} instead");
    let (strata_run, strata_time) = strata.run_piglit(&out_dir.join("strata"));
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

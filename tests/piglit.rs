//! piglit, the OpenGL conformance suite, as the oracle for Strata's GLES 2.0 and GLSL ES 1.00:
//! piglit's GLES 2.0 selection (read from piglit's own metadata, `piglit/selection.rs`) runs
//! natively on Mesa (llvmpipe) held to ES 2.0 (`MESA_GLES_VERSION_OVERRIDE=2.0`: Mesa then
//! creates only ES 2.0 contexts, with only the extensions an ES 2.0 context has) and through
//! `stratad` with the drop-in libEGL/libGLESv2, each under its own Xvfb. Every test that passes
//! natively must pass through Strata, unless `tests/piglit/exceptions.txt` excuses it.
//! Entries that pass through Strata again are stale and fail the test too, so the file stays
//! honest.
//!
//! The same for ES 3.0: piglit's GLES 3.0 selection in the areas ES 3.0's language and buffer
//! and draw side cover, natively on Mesa held to ES 3.0 and through `stratad --es3`, with
//! `tests/piglit/exceptions_es3.txt`; at least 95 % of the native passes must pass through
//! Strata, and each that does not needs its entry there.
//!
//! Results stay under `target/piglit/{native,strata}` (`…-es3` for ES 3.0: piglit's
//! `results.json`, the daemon's log) and the verdict is written to
//! `target/strata-tests/piglit.txt` (`piglit-es3.txt`).

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
/// piglit kills a test that runs longer than this and records `timeout`.
const PER_TEST_TIMEOUT_S: u32 = 60;
/// A whole run that takes longer than this is killed and fails the test.
const RUN_DEADLINE: Duration = Duration::from_secs(900);
/// One comparison: a selection, the version both sides are held to, and its exceptions.
struct Oracle {
    /// What the selection takes.
    api: &'static selection::Api,
    /// What its files and report are called (`gles2`, `gles3`).
    label: &'static str,
    /// The version Mesa is held to (`MESA_GLES_VERSION_OVERRIDE`), which its version string
    /// must then start with after "OpenGL ES ".
    version: &'static str,
    /// What wflinfo asks for (`gles2`, `gles3`).
    wflinfo_api: &'static str,
    /// The daemon's options beyond the output.
    daemon_args: &'static [&'static str],
    /// The exceptions file, under `tests/piglit`, and the excuses it may give.
    exceptions: &'static str,
    excuses: &'static [&'static str],
    /// Where the results go, under `target/piglit`, beside `native` and `strata`: "" or `-es3`.
    suffix: &'static str,
    /// Fewer native passes than this means the oracle itself is broken.
    native_floor: usize,
    /// The share of the native passes that must pass through Strata, excused or not (ES 3.0:
    /// 95 %); `None` where the exceptions alone bound what may fail.
    min_share: Option<f64>,
}

/// piglit's GLES 2.0 selection: Mesa held to ES 2.0 passes about 190 of its tests.
const ES2: Oracle = Oracle {
    api: &selection::GLES2,
    label: "gles2",
    version: "2.0",
    wflinfo_api: "gles2",
    daemon_args: &[],
    exceptions: "exceptions.txt",
    excuses: verdict::EXCUSES,
    suffix: "",
    native_floor: 160,
    min_share: None,
};

/// piglit's GLES 3.0 selection in the first part's areas: Mesa held to ES 3.0 passes about 150.
const ES3: Oracle = Oracle {
    api: &selection::GLES3,
    label: "gles3",
    version: "3.0",
    wflinfo_api: "gles3",
    daemon_args: &["--es3", "--es3-for-es2"],
    exceptions: "exceptions_es3.txt",
    excuses: verdict::EXCUSES_ES3,
    suffix: "-es3",
    native_floor: 120,
    min_share: Some(0.95),
};

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

/// A checked-in exceptions file.
fn exceptions_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/piglit").join(name)
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

    /// The renderer and version string wflinfo reports for a context of `api` on this side.
    fn renderer(&self, api: &str) -> (String, String) {
        let out = self.command("wflinfo").args(["-p", "x11_egl", "-a", api]).output().expect("run wflinfo");
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

/// The summary written to `target/strata-tests/piglit.txt` (`piglit-es3.txt`).
fn summary(o: &Oracle, native: (&Run, Duration), strata: (&Run, Duration), v: &Verdict, rerun: &str) -> String {
    let mut s = String::new();
    let mut line = |l: String| {
        s.push_str(&l);
        s.push('\n');
    };
    line(format!(
        "piglit selection: the tests of {} of piglit's {} build, by its metadata (tests/piglit/selection.rs); native side held to OpenGL ES {}",
        PROFILES.join(" "),
        o.label,
        o.version
    ));
    line(format!("native (Mesa):   {} in {:.1}s", verdict::counts_line(native.0), native.1.as_secs_f64()));
    line(format!("through stratad: {} in {:.1}s", verdict::counts_line(strata.0), strata.1.as_secs_f64()));
    let (both, native_passes) = verdict::shared_passes(native.0, strata.0);
    line(format!(
        "of {native_passes} native passes: {both} pass through stratad ({:.1} %), {} excused, {} regressions",
        100.0 * both as f64 / native_passes.max(1) as f64,
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
                line(format!("  {}:{}: {}", o.exceptions, e.line, e.name));
            }
            line(String::new());
        }
    }
    s
}

#[test]
fn piglit_passes_through_stratad_wherever_it_passes_on_mesa() {
    compare(&ES2);
}

#[test]
fn piglit_es3_passes_through_stratad_as_on_mesa() {
    compare(&ES3);
}

/// Runs `o`'s selection natively and through `stratad`, and judges the two.
fn compare(o: &Oracle) {
    let exceptions_text = std::fs::read_to_string(exceptions_path(o.exceptions)).expect("read the exceptions");
    let exceptions = verdict::parse_exceptions_with(&exceptions_text, o.excuses).expect("the exceptions file");
    if !oracles_present() {
        return;
    }
    let out_dir = target_dir().join("piglit");
    std::fs::create_dir_all(&out_dir).expect("target/piglit");

    // The oracle: Mesa's own libraries (LIBGL_ALWAYS_SOFTWARE keeps it on llvmpipe where a GPU
    // exists), nothing of Strata's on the library path.
    let selected = selection::select(Path::new(TESTS), Path::new(BIN), PROFILES, o.api).expect("piglit's profiles");
    let list = out_dir.join(format!("{}.xml.gz", o.label));
    selection::write_profile(&list, &selected).expect("write the selection's profile");
    eprintln!("selection: {} tests of piglit's {} build ({})", selected.len(), o.label, list.display());
    let x_native = Xvfb::start(1024, 768).expect("Xvfb");
    let native = Side {
        name: "native",
        display: x_native.display.clone(),
        env: vec![("LIBGL_ALWAYS_SOFTWARE", "1".into()), ("MESA_GLES_VERSION_OVERRIDE", o.version.into())],
    };
    let (renderer, version) = native.renderer(o.wflinfo_api);
    assert!(
        renderer.contains("llvmpipe") && !renderer.contains("Strata"),
        "the native run must use Mesa's llvmpipe, but wflinfo reports {renderer:?}"
    );
    assert!(
        version.starts_with(&format!("OpenGL ES {}", o.version)),
        "the native side must be held to ES {}, but wflinfo reports {version:?}",
        o.version
    );
    let (native_run, native_time) = native.run_piglit(&list, &out_dir.join(format!("native{}", o.suffix)));
    eprintln!("native (Mesa):   {} in {:.1}s", verdict::counts_line(&native_run), native_time.as_secs_f64());
    let native_passes = native_run.values().filter(|o| o.result == "pass").count();
    assert!(
        native_passes >= o.native_floor,
        "Mesa passes only {native_passes} tests: the oracle is broken; see {}",
        out_dir.join(format!("native{}.log", o.suffix)).display()
    );

    // Through Strata: its own X server, daemon, socket, and the drop-in libraries.
    let x_strata = Xvfb::start(1024, 768).expect("Xvfb");
    let tmp = TempDir::new("piglit");
    let shim = support::shim_dir(&tmp);
    let mut args = vec!["--output", "headless:main=640x480"];
    args.extend(o.daemon_args);
    let daemon = Daemon::start("piglit", &args);
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
    let (renderer, _) = strata.renderer(o.wflinfo_api);
    assert!(renderer.starts_with("Strata"), "the run through stratad reaches {renderer:?} instead");
    let (strata_run, strata_time) = strata.run_piglit(&list, &out_dir.join(format!("strata{}", o.suffix)));
    eprintln!("through stratad: {} in {:.1}s", verdict::counts_line(&strata_run), strata_time.as_secs_f64());
    let _ = std::fs::write(out_dir.join(format!("stratad{}.log", o.suffix)), daemon.log_text());
    assert_eq!(
        native_run.keys().collect::<Vec<_>>(),
        strata_run.keys().collect::<Vec<_>>(),
        "both runs must hold the same tests"
    );

    let v = verdict::judge(&native_run, &strata_run, &exceptions);
    let rerun = "stratad serve --socket /tmp/s.sock & Xvfb :9 -noreset & DISPLAY=:9 PIGLIT_PLATFORM=x11_egl \
                 PIGLIT_SOURCE_DIR=/usr/lib/x86_64-linux-gnu/piglit LD_LIBRARY_PATH=$(tools/build-shim) \
                 LD_PRELOAD=target/strata-gl/libEGL.so.1 STRATA_SOCKET=/tmp/s.sock";
    let text = summary(o, (&native_run, native_time), (&strata_run, strata_time), &v, rerun);
    let report_dir = target_dir().join("strata-tests");
    std::fs::create_dir_all(&report_dir).expect("target/strata-tests");
    let report = report_dir.join(format!("piglit{}.txt", o.suffix));
    std::fs::write(&report, &text).expect("write the summary");
    eprintln!("{} native passes excused by {}; summary in {}", v.excused, o.exceptions, report.display());
    assert!(v.ok(), "piglit through stratad falls short of Mesa (full results in {}):\n{text}", out_dir.display());
    if let Some(min) = o.min_share {
        let (both, native_passes) = verdict::shared_passes(&native_run, &strata_run);
        assert!(
            both as f64 >= min * native_passes as f64,
            "{both} of {native_passes} native passes pass through stratad, under {:.0} %:\n{text}",
            100.0 * min
        );
    }
}

/// The checked-in exceptions files parse.
#[test]
fn exceptions_files_are_well_formed() {
    for o in [&ES2, &ES3] {
        let name = o.exceptions;
        let text = std::fs::read_to_string(exceptions_path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let list =
            verdict::parse_exceptions_with(&text, o.excuses).unwrap_or_else(|e| panic!("tests/piglit/{name}: {e}"));
        assert!(!list.is_empty(), "{name} lists nothing");
    }
}

/// The selection holds piglit's GLES 2 tests and no other: known members of each kind are in,
/// the GLES 3, GLES 1 and desktop builds' tests are out.
#[test]
fn the_selection_is_piglits_gles2_build_and_glsl_es_1_00() {
    if !oracles_present() {
        return;
    }
    let selected =
        selection::select(Path::new(TESTS), Path::new(BIN), PROFILES, &selection::GLES2).expect("piglit's profiles");
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

/// The GLES 3.0 selection holds piglit's GLES 3 build and GLSL ES 3.00 in its areas, and no
/// other: known members of each kind are in, image tests and other builds' tests are out.
#[test]
fn the_es3_selection_is_piglits_gles3_build_in_its_areas() {
    if !oracles_present() {
        return;
    }
    let selected =
        selection::select(Path::new(TESTS), Path::new(BIN), PROFILES, &selection::GLES3).expect("piglit's profiles");
    let names: std::collections::HashSet<&str> = selected.iter().map(|t| t.name.as_str()).collect();
    for inside in [
        // C tests of the GLES 3 build, a glslparsertest and a compiler test with version 3.00.
        "spec@!opengl es 3.0@gl_vertexid used with gldrawarrays",
        "spec@arb_transform_feedback2@change objects while paused (gles3)",
        "spec@glsl-es-3.00@compiler@undefined-macro.vert",
        "spec@glsl-es-3.00@compiler@flat_interpolation@flat-struct-int.frag",
        // The image side's tests, and NV_read_depth's in ES 3.0.
        "spec@!opengl es 3.0@texture-immutable-levels",
        "spec@!opengl es 3.0@ext_texture_array-compressed_gles3 teximage",
        "spec@!opengl es 3.0@oes_compressed_etc2_texture-miptree_gles3 r11",
        "spec@nv_read_depth@read_depth_gles3",
    ] {
        assert!(names.contains(inside), "{inside} is missing from the selection");
    }
    for outside in [
        // Extensions beyond ES 3.0, the GLES 2 build, GLSL ES 1.00.
        "spec@oes_texture_view@formats",
        "spec@arb_blend_func_extended@arb_blend_func_extended-fbo-extended-blend_gles3",
        "spec@!opengl es 2.0@invalid-es3-queries_gles2",
        "spec@glsl-es-1.00@linker@glsl-fface-invariant",
    ] {
        assert!(!names.contains(outside), "{outside} is in the selection");
    }
}

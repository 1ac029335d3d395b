//! apitrace through the drop-in libEGL/libGLESv2, as graphics developers use it: a short
//! glmark2-es2 run is traced with `apitrace trace --api egl` while it renders through `stratad`,
//! `apitrace dump` shows its calls, and `eglretrace` replays the trace twice with snapshots of
//! selected frames (`-s DIR -S CALLS`): natively on Mesa (the oracle) and through the drop-in
//! libraries against the daemon. The two replays' snapshots must agree pixel by pixel within
//! the tolerance stated for each scene.
//!
//! A piglit program is traced the same way: piglit's programs link glvnd's `libGL.so.1`, whose
//! `gl*` stubs apitrace's `dlsym(RTLD_NEXT, ...)` finds before the drop-in library's functions,
//! so its `glGetString(GL_VERSION)` inside the traced `eglMakeCurrent` must reach the daemon
//! through glvnd's dispatch (`client-shim/capi/src/glvnd.rs`). The program must pass under the
//! tracer, and the replays of its draws must agree.
//!
//! Debian's eglretrace picks its window system through waffle, whose default is GLX; both
//! replays use waffle's EGL-on-X11 platform (`WAFFLE_PLATFORM=x11_egl`), the one that loads
//! libEGL/libGLESv2. The replayer creates 32x32 windows and grows them to the traced size
//! before it draws, so the replay through Strata also checks that window surfaces follow their
//! X window's size.

mod support;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Duration;

use support::{Daemon, TempDir, Xvfb};

/// How close two snapshots must be: at most `max_diff` per channel on at least `min_fraction`
/// of the pixels (the kind of tolerance `tests/gles_oracle.rs` states per program).
#[derive(Debug, Clone, Copy)]
struct Tol {
    max_diff: u8,
    min_fraction: f64,
}

/// Rounding of the last bit.
const EXACT: Tol = Tol { max_diff: 1, min_fraction: 0.999 };
/// Transcendentals: `pow` of a specular term in mediump differs in its last bits between the
/// two shader compilers, which a high shininess magnifies on a few highlight pixels; and a
/// blur that samples a render target with linear filtering rounds each tap on its own.
const MATH: Tol = Tol { max_diff: 3, min_fraction: 0.995 };

/// The traced glmark2 scenes (each gets its own context), and the tolerance of their frames.
/// Together they draw with client-side arrays and buffer objects, sample mipmapped textures,
/// render to textures, map buffers (`GL_OES_mapbuffer`) and blend.
const SCENES: &[(&str, Tol)] = &[
    ("build:use-vbo=false", EXACT),
    ("texture:texture-filter=mipmap", EXACT),
    ("shading:shading=blinn-phong-inf", MATH),
    ("effect2d:kernel=0,1,0;1,-4,1;0,1,0;", EXACT),
    ("buffer:update-fraction=0.5:update-dispersion=0.9:columns=40:update-method=map:interleave=false", EXACT),
    ("desktop:windows=2:effect=blur:blur-radius=3:passes=1:separable=true", MATH),
];

/// Each scene's run time: a few frames, at least one.
const SCENE_SECONDS: &str = "0.1";
/// glmark2's window size, which the replays grow their windows to.
const SIZE: &str = "160x120";

/// Whether the programs this test drives are installed; if not, the test skips with the
/// reason, unless `STRATA_REQUIRE_ORACLES` is set, where it fails.
fn programs_present() -> bool {
    let missing: Vec<&str> =
        ["apitrace", "eglretrace", "glmark2-es2", "Xvfb"].into_iter().filter(|p| support::which(p).is_none()).collect();
    support::nothing_missing(&missing)
}

/// Runs a program to completion, killing it after `deadline`; returns its output and whether
/// it timed out.
fn run(mut cmd: Command, deadline: Duration) -> (Output, bool) {
    let child = cmd.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().expect("spawn");
    support::wait_with_deadline(child, deadline)
}

fn text(o: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr))
}

/// A command with the X display set and no Strata or waffle settings inherited.
fn command(program: &str, display: &str) -> Command {
    let mut cmd = Command::new(program);
    cmd.env("DISPLAY", display)
        .env_remove("LD_LIBRARY_PATH")
        .env_remove("LD_PRELOAD")
        .env_remove("STRATA_SOCKET")
        .env_remove("STRATA_WINDOW")
        .env_remove("WAFFLE_PLATFORM");
    cmd
}

/// Points a command at the drop-in libraries in `shim` and the daemon at `socket`.
fn through_strata(cmd: &mut Command, shim: &Path, socket: &Path) {
    cmd.env("LD_LIBRARY_PATH", shim).env("STRATA_SOCKET", socket);
}

/// The call numbers of each scene's frames (`eglSwapBuffers`), from `apitrace dump`: a scene
/// starts where a context is made current. glmark2's first context, which only reads the GL
/// strings, draws no frame and is left out.
fn frames_by_scene(dump: &str) -> Vec<Vec<u64>> {
    let mut scenes: Vec<Vec<u64>> = Vec::new();
    for line in dump.lines() {
        let Some((no, call)) = line.split_once(' ') else { continue };
        let Ok(no) = no.parse::<u64>() else { continue };
        if call.starts_with("eglMakeCurrent(") && !call.contains("ctx = NULL") {
            scenes.push(Vec::new());
        } else if call.starts_with("eglSwapBuffers(") {
            if let Some(s) = scenes.last_mut() {
                s.push(no);
            }
        }
    }
    scenes.retain(|frames| !frames.is_empty());
    scenes
}

/// Replays `trace` with eglretrace on waffle's EGL-on-X11 platform, snapshotting `calls` into
/// `dir`.
fn replay(mut cmd: Command, trace: &Path, dir: &Path, calls: &str) -> Output {
    std::fs::create_dir_all(dir).expect("snapshot dir");
    let mut prefix = dir.as_os_str().to_owned();
    prefix.push("/");
    cmd.env("WAFFLE_PLATFORM", "x11_egl").arg("-s").arg(prefix).arg("-S").arg(calls).arg(trace);
    let (out, timed_out) = run(cmd, Duration::from_secs(120));
    assert!(!timed_out, "eglretrace timed out:\n{}", text(&out));
    out
}

/// Compares two snapshots; `None` when they agree within `tol`, else why not.
fn compare(actual: &image::RgbImage, expected: &image::RgbImage, tol: Tol) -> Option<String> {
    if actual.dimensions() != expected.dimensions() {
        return Some(format!("size {:?}, expected {:?}", actual.dimensions(), expected.dimensions()));
    }
    let (mut bad, mut worst) = (0usize, 0u8);
    for (a, e) in actual.pixels().zip(expected.pixels()) {
        let d = a.0.iter().zip(e.0).map(|(x, y)| x.abs_diff(y)).max().unwrap_or(0);
        worst = worst.max(d);
        if d > tol.max_diff {
            bad += 1;
        }
    }
    let pixels = (actual.width() * actual.height()).max(1) as usize;
    let ok = 1.0 - bad as f64 / pixels as f64;
    (ok < tol.min_fraction).then(|| {
        format!(
            "{bad} of {pixels} pixels differ by more than {} (worst {worst}); {:.2}% within, {:.2}% required",
            tol.max_diff,
            ok * 100.0,
            tol.min_fraction * 100.0
        )
    })
}

fn load(path: &Path) -> Result<image::RgbImage, String> {
    image::open(path).map(|i| i.to_rgb8()).map_err(|e| format!("{}: {e}", path.display()))
}

#[test]
fn apitrace_traces_and_replays_glmark2_through_stratad() {
    if !programs_present() {
        return;
    }
    let x = Xvfb::start(640, 480).expect("Xvfb");
    let tmp = TempDir::new("apitrace");
    let shim = support::shim_dir(&tmp);
    // A small output and a high refresh: replays swap with interval 1, paced by the output.
    let daemon = Daemon::start("apitrace", &["--output", "headless:main=320x240", "--refresh-hz", "1000"]);

    // Trace glmark2-es2 rendering through the daemon.
    let trace = tmp.0.join("glmark2.trace");
    let mut cmd = command("apitrace", &x.display);
    cmd.args(["trace", "--api", "egl", "-o"]).arg(&trace).args(["glmark2-es2", "-s", SIZE]);
    for (scene, _) in SCENES {
        cmd.arg("-b").arg(format!("{scene}:duration={SCENE_SECONDS}"));
    }
    through_strata(&mut cmd, &shim, &daemon.socket);
    let (out, timed_out) = run(cmd, Duration::from_secs(120));
    let traced = text(&out);
    assert!(
        !timed_out && out.status.success() && traced.contains("glmark2 Score"),
        "glmark2-es2 under apitrace failed (exit {:?}, timed out: {timed_out}):\n{traced}\nstratad log:\n{}",
        out.status,
        daemon.log_text()
    );
    assert!(trace.metadata().is_ok_and(|m| m.len() > 0), "no trace written:\n{traced}");

    // The trace holds the GL calls, and the strings the daemon answered (`--verbose` shows
    // queries such as glGetString too).
    let mut cmd = command("apitrace", &x.display);
    cmd.args(["dump", "--verbose", "--color=never"]).arg(&trace);
    let (out, _) = run(cmd, Duration::from_secs(60));
    let dump = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "apitrace dump failed:\n{}", text(&out));
    for call in [
        "eglCreateWindowSurface(",
        "eglMakeCurrent(",
        "glCompileShader(",
        "glUseProgram(",
        "glTexImage2D(",
        "glBindFramebuffer(",
        "glMapBufferOES(",
        "glDrawArrays(",
        "eglSwapBuffers(",
    ] {
        assert!(dump.contains(call), "apitrace dump shows no {call}...)");
    }
    assert!(dump.contains("GL_RENDERER) = \"Strata on "), "the trace was not recorded through stratad");

    // Each scene's first and last frame.
    let scenes = frames_by_scene(&dump);
    assert_eq!(scenes.len(), SCENES.len(), "one context with frames per scene expected");
    let mut selected: BTreeMap<u64, (&str, Tol)> = BTreeMap::new();
    for (frames, &(scene, tol)) in scenes.iter().zip(SCENES) {
        let (Some(first), Some(last)) = (frames.first(), frames.last()) else {
            panic!("{scene}: no frame in the trace");
        };
        selected.insert(*first, (scene, tol));
        selected.insert(*last, (scene, tol));
    }
    let calls = selected.keys().map(u64::to_string).collect::<Vec<_>>().join(",");

    // The oracle: Mesa replays the trace natively.
    let native_dir = tmp.0.join("native");
    let out = replay(command("eglretrace", &x.display), &trace, &native_dir, &calls);
    assert!(
        out.status.success(),
        "Mesa cannot replay the trace here, so it cannot serve as the oracle:\n{}",
        text(&out)
    );

    // The same replay through the drop-in libraries and the daemon.
    let strata_dir = tmp.0.join("strata");
    let mut cmd = command("eglretrace", &x.display);
    through_strata(&mut cmd, &shim, &daemon.socket);
    let out = replay(cmd, &trace, &strata_dir, &calls);
    assert!(
        out.status.success(),
        "eglretrace through stratad failed:\n{}\nstratad log:\n{}",
        text(&out),
        daemon.log_text()
    );

    let failures_dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/apitrace-failures");
    let mut failures = Vec::new();
    for (call, (scene, tol)) in &selected {
        let name = format!("{call:010}.png");
        let expected = load(&native_dir.join(&name)).expect("Mesa's snapshot");
        // A frame of one colour would let a replay that draws nothing pass.
        assert!(
            expected.pixels().any(|p| p != expected.get_pixel(0, 0)),
            "{scene}: Mesa's snapshot of call {call} is a single colour"
        );
        let why = match load(&strata_dir.join(&name)) {
            Ok(actual) => compare(&actual, &expected, *tol),
            Err(e) => Some(format!("no snapshot through stratad ({e})")),
        };
        match why {
            None => eprintln!("ok   {scene}: frame ending at call {call}"),
            Some(why) => {
                let _ = std::fs::create_dir_all(&failures_dir);
                let _ = std::fs::copy(native_dir.join(&name), failures_dir.join(format!("{call}-expected.png")));
                let _ = std::fs::copy(strata_dir.join(&name), failures_dir.join(format!("{call}-actual.png")));
                failures.push(format!("{scene}, frame ending at call {call}: {why}"));
            }
        }
    }
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")), "stratad panicked:\n{}", daemon.log_text());
    assert!(
        failures.is_empty(),
        "{} of {} snapshots through stratad differ from Mesa's (images in {}):\n{}",
        failures.len(),
        selected.len(),
        failures_dir.display(),
        failures.join("\n")
    );
    drop(x);
}

/// A piglit program that draws through waffle and probes its pixels, and passes through Strata.
const PIGLIT_PROGRAM: &str = "/usr/lib/x86_64-linux-gnu/piglit/bin/draw-vertices-half-float_gles2";

#[test]
fn apitrace_traces_and_replays_a_piglit_program_through_stratad() {
    if !programs_present() {
        return;
    }
    if !support::nothing_missing(if Path::new(PIGLIT_PROGRAM).is_file() { &[] } else { &[PIGLIT_PROGRAM] }) {
        return;
    }
    let x = Xvfb::start(640, 480).expect("Xvfb");
    let tmp = TempDir::new("apitrace-piglit");
    let shim = support::shim_dir(&tmp);
    let daemon = Daemon::start("apitrace-piglit", &["--output", "headless:main=320x240", "--refresh-hz", "1000"]);

    let trace = tmp.0.join("piglit.trace");
    let mut cmd = command("apitrace", &x.display);
    cmd.args(["trace", "--api", "egl", "-o"])
        .arg(&trace)
        .args([PIGLIT_PROGRAM, "-auto", "-fbo"])
        .env("PIGLIT_PLATFORM", "x11_egl")
        .env("PIGLIT_SOURCE_DIR", "/usr/lib/x86_64-linux-gnu/piglit");
    through_strata(&mut cmd, &shim, &daemon.socket);
    let (out, timed_out) = run(cmd, Duration::from_secs(120));
    let traced = text(&out);
    assert!(
        !timed_out && out.status.success() && traced.contains(r#"PIGLIT: {"result": "pass" }"#),
        "the piglit program under apitrace failed (exit {:?}, timed out: {timed_out}):\n{traced}\nstratad log:\n{}",
        out.status,
        daemon.log_text()
    );
    assert!(!traced.contains("got null GL_VERSION"), "apitrace's own GL calls did not reach stratad:\n{traced}");

    let mut cmd = command("apitrace", &x.display);
    cmd.args(["dump", "--verbose", "--color=never"]).arg(&trace);
    let (out, _) = run(cmd, Duration::from_secs(60));
    let dump = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "apitrace dump failed:\n{}", text(&out));
    assert!(dump.contains("GL_VERSION) = \"OpenGL ES 2.0 Strata"), "the trace was not recorded through stratad");
    let draws = dump.lines().filter(|l| l.split_once(' ').is_some_and(|(_, c)| c.starts_with("glDraw"))).count();
    assert!(draws > 0, "the trace holds no draw");

    // A snapshot after every draw (piglit's automatic mode never swaps; with `-fbo` it draws
    // into a framebuffer object, whose size the trace records, unlike the window's, which a
    // replay without swaps never learns), natively on Mesa (the oracle) and through the
    // drop-in libraries.
    let native_dir = tmp.0.join("native");
    let out = replay(command("eglretrace", &x.display), &trace, &native_dir, "*/draw");
    assert!(out.status.success(), "Mesa cannot replay the piglit trace:\n{}", text(&out));
    let strata_dir = tmp.0.join("strata");
    let mut cmd = command("eglretrace", &x.display);
    through_strata(&mut cmd, &shim, &daemon.socket);
    let out = replay(cmd, &trace, &strata_dir, "*/draw");
    assert!(out.status.success(), "eglretrace through stratad failed:\n{}", text(&out));

    let mut names: Vec<_> = std::fs::read_dir(&native_dir)
        .expect("native snapshots")
        .filter_map(|e| e.ok().map(|e| e.file_name()))
        .collect();
    names.sort();
    assert!(names.len() >= draws, "{} native snapshots for {draws} draws", names.len());
    let last = load(&native_dir.join(names.last().expect("a snapshot"))).expect("Mesa's snapshot");
    assert!(last.pixels().any(|p| p != last.get_pixel(0, 0)), "Mesa's last snapshot is a single colour");
    let failures: Vec<String> = names
        .iter()
        .filter_map(|n| {
            let expected = load(&native_dir.join(n)).expect("Mesa's snapshot");
            let why = match load(&strata_dir.join(n)) {
                Ok(actual) => compare(&actual, &expected, EXACT),
                Err(e) => Some(format!("no snapshot through stratad ({e})")),
            };
            why.map(|w| format!("{}: {w}", n.to_string_lossy()))
        })
        .collect();
    assert!(daemon.log_text().lines().all(|l| !l.contains("panicked")), "stratad panicked:\n{}", daemon.log_text());
    assert!(failures.is_empty(), "snapshots through stratad differ from Mesa's:\n{}", failures.join("\n"));
    drop(x);
}

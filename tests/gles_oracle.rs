//! The executor against Mesa: every program below is written once against `Calls` and rendered
//! twice, through `stratad` (wgpu on lavapipe) and through the system's Mesa GLES2 (llvmpipe).
//! The two images must agree within the tolerance stated beside each program; the default is
//! at most 1/255 per channel on at least 99.9 % of pixels. On failure the actual, expected and
//! difference images are written under `target/oracle-failures/`.

mod programs;
mod support;

use programs::{Case, Names, H, W};
use strata_client::{Calls, ClientError, ConnectOptions, Connection};
use support::mesa::MesaGl;
use support::Daemon;

const EGL_NONE: i32 = 0x3038;

/// Sets up a W×H RGBA8 D24S8 pbuffer with a current ES2 context through Strata's EGL.
fn strata_context(socket: &std::path::Path, name: &str) -> Result<Connection, ClientError> {
    let opts = ConnectOptions { socket: socket.to_path_buf(), name: name.into(), ..ConnectOptions::default() };
    let mut c = Connection::connect(&opts)?;
    let d = c.eglGetDisplay(0)?;
    c.eglInitialize(d)?.map_err(|e| ClientError::Unsupported(format!("eglInitialize: {e:#x}")))?;
    let attribs = [0x3033, 1, 0x3040, 4, 0x3024, 8, 0x3023, 8, 0x3022, 8, 0x3021, 8, 0x3025, 24, 0x3026, 8, EGL_NONE];
    let configs = c
        .eglChooseConfig(d, strata_protocol::Slice::new(&attribs), 1)?
        .map_err(|e| ClientError::Unsupported(format!("eglChooseConfig: {e:#x}")))?;
    let config = *configs.first().ok_or_else(|| ClientError::Unsupported("no config".into()))?;
    let s = c
        .eglCreatePbufferSurface(d, config, strata_protocol::Slice::new(&[0x3057, W, 0x3056, H, EGL_NONE]))?
        .map_err(|e| ClientError::Unsupported(format!("eglCreatePbufferSurface: {e:#x}")))?;
    let ctx = c
        .eglCreateContext(d, config, 0, strata_protocol::Slice::new(&[0x3098, 2, EGL_NONE]))?
        .map_err(|e| ClientError::Unsupported(format!("eglCreateContext: {e:#x}")))?;
    c.eglMakeCurrent(d, s, s, ctx)?.map_err(|e| ClientError::Unsupported(format!("eglMakeCurrent: {e:#x}")))?;
    Ok(c)
}

fn render(gl: &mut dyn Calls<Error = ClientError>, case: &Case) -> Result<Vec<u8>, ClientError> {
    let mut names = Names::default();
    // EGL leaves a new pbuffer's contents undefined: start every program from cleared buffers
    // (with the default clear values, so no state changes).
    gl.glClear(0x4000 | 0x0100 | 0x0400)?;
    (case.run)(gl, &mut names)?;
    let e = gl.glGetError()?;
    if e != 0 && !case.expects_error {
        return Err(ClientError::Unsupported(format!("GL error {e:#x} after the program")));
    }
    Ok(gl.glReadPixels(0, 0, W, H, 0x1908, 0x1401)?.0)
}

fn save(path: &std::path::Path, px: &[u8]) {
    // Rows arrive bottom-up (GL order); flip for viewing.
    let mut flipped = Vec::with_capacity(px.len());
    for row in px.chunks(W as usize * 4).rev() {
        flipped.extend_from_slice(row);
    }
    if let Some(img) = image::RgbaImage::from_raw(W as u32, H as u32, flipped) {
        let _ = img.save(path);
    }
}

/// Compares two images; returns a description of the mismatch, if any.
fn compare(case: &Case, actual: &[u8], expected: &[u8]) -> Option<String> {
    if actual.len() != expected.len() {
        return Some(format!("sizes differ: {} vs {}", actual.len(), expected.len()));
    }
    let pixels = actual.len() / 4;
    let mut bad = 0usize;
    let mut worst = 0u8;
    for (a, e) in actual.chunks(4).zip(expected.chunks(4)) {
        let d = a.iter().zip(e).map(|(x, y)| x.abs_diff(*y)).max().unwrap_or(0);
        worst = worst.max(d);
        if d > case.tol.max_diff {
            bad += 1;
        }
    }
    let ok_fraction = 1.0 - bad as f64 / pixels as f64;
    (ok_fraction < case.tol.min_fraction).then(|| {
        format!(
            "{bad} of {pixels} pixels differ by more than {} (worst {worst}); {:.3}% within tolerance, {:.3}% required",
            case.tol.max_diff,
            ok_fraction * 100.0,
            case.tol.min_fraction * 100.0
        )
    })
}

#[test]
fn executor_matches_mesa() {
    let cases = programs::all();
    assert!(cases.len() >= 30, "the suite must have at least 30 programs");
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
    let daemon = Daemon::start("oracle", &[]);
    let out_dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/oracle-failures");
    let mut failures = Vec::new();
    for case in &cases {
        let expected = MesaGl::open(W, H).map_err(ClientError::Unsupported).and_then(|mut m| render(&mut m, case));
        let actual = strata_context(&daemon.socket, case.name).and_then(|mut c| render(&mut c, case));
        match (actual, expected) {
            (Ok(a), Ok(e)) => {
                if let Some(why) = compare(case, &a, &e) {
                    let _ = std::fs::create_dir_all(&out_dir);
                    save(&out_dir.join(format!("{}-actual.png", case.name)), &a);
                    save(&out_dir.join(format!("{}-expected.png", case.name)), &e);
                    let diff: Vec<u8> = a
                        .chunks(4)
                        .zip(e.chunks(4))
                        .flat_map(|(x, y)| {
                            let d = x.iter().zip(y).map(|(p, q)| p.abs_diff(*q)).max().unwrap_or(0);
                            [d.saturating_mul(8), 0, 0, 255]
                        })
                        .collect();
                    save(&out_dir.join(format!("{}-diff.png", case.name)), &diff);
                    failures.push(format!("{}: {why}", case.name));
                } else {
                    eprintln!("ok   {}", case.name);
                    if std::env::var_os("STRATA_ORACLE_DUMP").is_some() {
                        let _ = std::fs::create_dir_all(&out_dir);
                        save(&out_dir.join(format!("{}-ok.png", case.name)), &a);
                    }
                }
            }
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

//! Running a program on both backends and comparing the images.

use strata_client::{Calls, ClientError, ConnectOptions, Connection};

use super::{Case, Names, H, W};

/// Sets up a W×H RGBA8 D24S8 pbuffer with a current ES2 context through Strata's EGL.
pub fn strata_context(socket: &std::path::Path, name: &str) -> Result<Connection, ClientError> {
    let opts = ConnectOptions { socket: socket.to_path_buf(), name: name.into(), ..ConnectOptions::default() };
    let mut c = Connection::connect(&opts)?;
    strata_client::setup::egl_context(
        &mut c,
        24,
        8,
        strata_client::setup::SurfaceKind::Pbuffer { width: W, height: H },
    )?;
    Ok(c)
}

pub fn render(gl: &mut dyn Calls<Error = ClientError>, case: &Case) -> Result<Vec<u8>, ClientError> {
    render_with(gl, case, &mut Names::default())
}

/// Like `render`, allocating object names from `names`.
pub fn render_with(
    gl: &mut dyn Calls<Error = ClientError>,
    case: &Case,
    names: &mut Names,
) -> Result<Vec<u8>, ClientError> {
    let names = &mut *names;
    // EGL leaves a new pbuffer's contents undefined: start every program from cleared buffers
    // (with the default clear values, so no state changes).
    gl.glClear(0x4000 | 0x0100 | 0x0400)?;
    (case.run)(gl, names)?;
    let e = gl.glGetError()?;
    if e != 0 && !case.expects_error {
        return Err(ClientError::Unsupported(format!("GL error {e:#x} after the program")));
    }
    Ok(gl.glReadPixels(0, 0, W, H, 0x1908, 0x1401)?.0)
}

pub fn save(path: &std::path::Path, px: &[u8]) {
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
pub fn compare(case: &Case, actual: &[u8], expected: &[u8]) -> Option<String> {
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

/// Compares a program's image through Strata (`actual`) with Mesa's: the failure's line, with
/// the two images and their difference saved under `out_dir`; on success `None`, the image
/// saved too where `STRATA_ORACLE_DUMP` asks.
pub fn judge(case: &Case, actual: &[u8], expected: &[u8], out_dir: &std::path::Path) -> Option<String> {
    let Some(why) = compare(case, actual, expected) else {
        eprintln!("ok   {}", case.name);
        if std::env::var_os("STRATA_ORACLE_DUMP").is_some() {
            let _ = std::fs::create_dir_all(out_dir);
            save(&out_dir.join(format!("{}-ok.png", case.name)), actual);
        }
        return None;
    };
    let _ = std::fs::create_dir_all(out_dir);
    save(&out_dir.join(format!("{}-actual.png", case.name)), actual);
    save(&out_dir.join(format!("{}-expected.png", case.name)), expected);
    let diff: Vec<u8> = actual
        .chunks(4)
        .zip(expected.chunks(4))
        .flat_map(|(x, y)| {
            let d = x.iter().zip(y).map(|(p, q)| p.abs_diff(*q)).max().unwrap_or(0);
            [d.saturating_mul(8), 0, 0, 255]
        })
        .collect();
    save(&out_dir.join(format!("{}-diff.png", case.name)), &diff);
    Some(format!("{}: {why}", case.name))
}

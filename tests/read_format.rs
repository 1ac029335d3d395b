//! `glReadPixels` against Mesa: every format and type pair below, at two pack alignments, must
//! raise the error Mesa raises on an ES 2.0 context, or return the same bytes: RGBA, and with
//! `GL_EXT_read_format_bgra` BGRA bytes and the two reversed 16-bit BGRA packings.

mod programs;
mod support;

use programs::harness::strata_context;
use programs::*;
use strata_client::ClientError;
use support::mesa::MesaGl;
use support::Daemon;

const FORMATS: &[u32] = &[0x1908, 0x80E1, 0x1907, 0x1906];
/// UNSIGNED_BYTE, the two reversed packings, 565, 4444, FLOAT.
const TYPES: &[u32] = &[0x1401, 0x8365, 0x8366, 0x8363, 0x8033, 0x1406];

/// A gradient quad over a cleared background, so that every component varies.
fn scene(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    gl.glClearColor(0.2, 0.4, 0.6, 0.8)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS_COLOR, FS_VARY, &["pos", "col"])?;
    vertex_quad(gl, n, [-0.8, -0.8, 0.8, 0.8], |x, y| {
        [x, y, 0.0, (x + 1.0) / 2.0, (y + 1.0) / 2.0, 1.0 - (x + 1.0) / 2.0, 0.3 + y * 0.3]
    })
}

/// For each alignment, format and type: the error, and the bytes read where there is none.
fn reads(gl: Gl<'_>) -> Result<Vec<(u32, Vec<u8>)>, ClientError> {
    scene(gl, &mut Names::default())?;
    while gl.glGetError()? != 0 {}
    let mut out = Vec::new();
    for align in [1, 4] {
        gl.glPixelStorei(0x0D05, align)?;
        for &format in FORMATS {
            for &ty in TYPES {
                let bytes = gl.glReadPixels(5, 9, 37, 23, format, ty)?.0;
                let e = gl.glGetError()?;
                out.push((e, if e == 0 { bytes } else { Vec::new() }));
            }
        }
    }
    Ok(out)
}

#[test]
fn read_pixels_answers_as_mesa_answers() {
    let Some(mut mesa) = MesaGl::open_or_skip(W, H) else { return };
    let want = reads(&mut mesa).expect("Mesa");
    let daemon = Daemon::start("read-format", &[]);
    let mut strata = strata_context(&daemon.socket, "read-format").expect("context");
    let got = reads(&mut strata).expect("Strata");
    let pairs = [1, 4].iter().flat_map(|a| FORMATS.iter().flat_map(move |f| TYPES.iter().map(move |t| (*a, *f, *t))));
    let mut differ = Vec::new();
    let mut read = 0;
    for ((a, f, t), (g, w)) in pairs.zip(got.iter().zip(&want)) {
        read += usize::from(w.0 == 0);
        if g.0 != w.0 {
            differ.push(format!("align {a}, format {f:#x}, type {t:#x}: Mesa error {:#x}, Strata {:#x}", w.0, g.0));
        } else if g.1 != w.1 {
            let at = g.1.iter().zip(&w.1).position(|(x, y)| x != y);
            differ.push(format!(
                "align {a}, format {f:#x}, type {t:#x}: {} bytes against Mesa's {}, first difference at {at:?}",
                g.1.len(),
                w.1.len()
            ));
        }
    }
    assert!(differ.is_empty(), "glReadPixels differs from Mesa:\n{}", differ.join("\n"));
    assert!(read >= 8, "only {read} reads succeeded on Mesa");
}

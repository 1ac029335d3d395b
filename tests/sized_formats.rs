//! `GL_OES_required_internalformat` against Mesa: `glTexImage2D` with each sized internal
//! format and every format and type pair Strata offers, and `glCopyTexImage2D` into each, must
//! raise exactly the error Mesa raises on an ES 2.0 context (none where the pair fits the
//! format), and a texture uploaded with a sized internal format must sample as the unsized one
//! does.

mod programs;
mod support;

use programs::harness::strata_context;
use programs::*;
use strata_client::ClientError;
use strata_protocol::{Blob, Slice};
use support::mesa::MesaGl;
use support::Daemon;

/// The sized internal formats the extension names (and two it does not: 32-bit depth without
/// `GL_OES_depth32`, RGB10_A2 without `GL_EXT_texture_type_2_10_10_10_REV`).
const SIZED: &[u32] =
    &[0x803C, 0x8040, 0x8043, 0x8045, 0x8051, 0x8D62, 0x8058, 0x8057, 0x8056, 0x81A5, 0x81A6, 0x88F0, 0x81A7, 0x8059];
/// The formats and types Strata takes.
const FORMATS: &[u32] = &[0x1906, 0x1909, 0x190A, 0x1907, 0x1908, 0x80E1, 0x1902, 0x84F9];
const TYPES: &[u32] = &[0x1401, 0x8363, 0x8033, 0x8034, 0x1403, 0x1405, 0x84FA, 0x1406, 0x8D61];

/// The error each (internal, format, type) upload of a 1×1 image raises, in order.
fn errors(gl: Gl<'_>, n: &mut Names) -> Result<Vec<u32>, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    while gl.glGetError()? != 0 {}
    let mut out = Vec::new();
    for &internal in SIZED {
        for &format in FORMATS {
            for &ty in TYPES {
                gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 1, 1, 0, format, ty, None)?;
                out.push(gl.glGetError()?);
            }
        }
    }
    // glCopyTexImage2D from the RGBA framebuffer, into each sized format and the unsized ones.
    for &internal in SIZED.iter().chain(&[0x1906, 0x1907, 0x1908, 0x1909, 0x190A, 0x1902, 0x84F9]) {
        gl.glCopyTexImage2D(TEXTURE_2D, 0, internal, 0, 0, 2, 2, 0)?;
        out.push(gl.glGetError()?);
    }
    Ok(out)
}

/// A luminance-alpha texture uploaded as LUMINANCE8_ALPHA8 and a 565 one as RGB565, sampled.
fn sized_upload_samples_as_unsized(gl: Gl<'_>, n: &mut Names) -> Result<(), ClientError> {
    let la: Vec<u8> = (0..16u8).flat_map(|i| [i * 16, 255 - i * 16]).collect();
    let t = texture(gl, n, 4, 4, LUMINANCE_ALPHA, UNSIGNED_BYTE, &la, NEAREST, CLAMP_TO_EDGE)?;
    gl.glTexImage2D(TEXTURE_2D, 0, 0x8045, 4, 4, 0, LUMINANCE_ALPHA, UNSIGNED_BYTE, Some(Blob::borrowed(&la)))?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glViewport(0, 0, W / 2, H)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    let rgb: Vec<u8> = (0..16u16).flat_map(|i| (i * 4099).to_ne_bytes()).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, 0x8D62, 4, 4, 0, RGB, 0x8363, Some(Blob::borrowed(&rgb)))?;
    gl.glViewport(W / 2, 0, W / 2, H)?;
    textured_quad(gl, n, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)
}

#[test]
fn sized_internal_formats_are_taken_as_mesa_takes_them() {
    let Some(mut mesa) = MesaGl::open_or_skip(W, H) else { return };
    let want = errors(&mut mesa, &mut Names::default()).expect("Mesa");
    let daemon = Daemon::start("sized-formats", &[]);
    let mut strata = strata_context(&daemon.socket, "sized-formats").expect("context");
    let got = errors(&mut strata, &mut Names::default()).expect("Strata");
    let mut differ = Vec::new();
    let mut fits = 0;
    let uploads = SIZED.iter().flat_map(|i| FORMATS.iter().flat_map(move |f| TYPES.iter().map(move |t| (*i, *f, *t))));
    let copies = SIZED.iter().chain(&[0x1906, 0x1907, 0x1908, 0x1909, 0x190A, 0x1902, 0x84F9]).map(|i| (*i, 0, 0));
    for ((i, f, t), (g, w)) in uploads.chain(copies).zip(got.iter().zip(&want)) {
        fits += usize::from(*w == 0);
        let call = if f == 0 { "glCopyTexImage2D".to_string() } else { format!("format {f:#x}, type {t:#x}") };
        if g != w {
            differ.push(format!("internal {i:#x}, {call}: Mesa {w:#x}, Strata {g:#x}"));
        }
    }
    assert_eq!(got.len(), want.len());
    assert!(differ.is_empty(), "{} uploads differ from Mesa's:\n{}", differ.len(), differ.join("\n"));
    assert!(fits >= 15, "only {fits} uploads fit: the table tells nothing apart");
}

#[test]
fn a_sized_upload_samples_as_the_unsized_one() {
    let case = Case { name: "sized_upload", run: sized_upload_samples_as_unsized, tol: DEFAULT, expects_error: false };
    let Some(mut mesa) = MesaGl::open_or_skip(W, H) else { return };
    let expected = programs::harness::render(&mut mesa, &case).expect("Mesa");
    let daemon = Daemon::start("sized-upload", &[]);
    let mut strata = strata_context(&daemon.socket, "sized-upload").expect("context");
    let actual = programs::harness::render(&mut strata, &case).expect("Strata");
    assert!(programs::harness::compare(&case, &actual, &expected).is_none(), "the sized uploads sample differently");
}

//! Multisample renderbuffers: a 4-sample RGBA8 colour buffer with a 4-sample depth buffer,
//! cleared, drawn into (triangles whose slanted edges are antialiased, a depth test between two
//! of them, a quad at half sample coverage, one at half alpha to coverage), resolved by `glBlitFramebuffer` into a texture's
//! framebuffer and that shown in the window; the queries (`GL_MAX_SAMPLES`, `GL_SAMPLES`,
//! `GL_SAMPLE_BUFFERS`, `GL_RENDERBUFFER_SAMPLES`, `glGetInternalformativ`) and the errors
//! (reads and copies from a multisample framebuffer, a moved resolve, a multisample draw
//! framebuffer, a resolve into another format, integer formats with samples, mixed sample
//! counts) as marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const READ_FRAMEBUFFER: u32 = 0x8CA8;
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const RGBA8: u32 = 0x8058;
const RGBA8UI: u32 = 0x8D7C;
const DEPTH_COMPONENT24: u32 = 0x81A6;
const MAX_SAMPLES: u32 = 0x8D57;
const SAMPLES: u32 = 0x80A9;
const SAMPLE_BUFFERS: u32 = 0x80A8;
const NUM_SAMPLE_COUNTS: u32 = 0x9380;
const RENDERBUFFER_SAMPLES: u32 = 0x8CAB;
const SAMPLE_COVERAGE: u32 = 0x80A0;
const SAMPLE_ALPHA_TO_COVERAGE: u32 = 0x809E;
const RGBA4: u32 = 0x8056;
const DEPTH_TEST_CAP: u32 = 0x0B71;

/// A new `w`×`h` renderbuffer of `format` with `samples` samples, left bound; its name.
fn renderbuffer(gl: Gl<'_>, n: &mut Names, samples: i32, format: u32, (w, h): (i32, i32)) -> Result<u32, ClientError> {
    let rb = n.next();
    gl.glGenRenderbuffers(Slice::new(&[rb]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorageMultisample(RENDERBUFFER, samples, format, w, h)?;
    Ok(rb)
}

/// Draws triangles `xyz` (clip space) in colour `c` through the bound colour program `p`.
fn triangles(gl: Gl<'_>, n: &mut Names, p: u32, xyz: &[f32], c: [f32; 4]) -> R {
    color(gl, p, c)?;
    draw_positions(gl, n, xyz, TRIANGLES)
}

/// The multisample program.
pub fn multisample(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let first = |v: Vec<i32>| v.first().copied().unwrap_or(-1) as u32;
    marks.push(first(gl.glGetIntegerv(MAX_SAMPLES)?));
    marks.push(first(gl.glGetInternalformativ(RENDERBUFFER, RGBA8, SAMPLES, 16)?));
    marks.push(first(gl.glGetInternalformativ(RENDERBUFFER, RGBA8, NUM_SAMPLE_COUNTS, 16)?));
    marks.push(first(gl.glGetInternalformativ(RENDERBUFFER, DEPTH_COMPONENT24, NUM_SAMPLE_COUNTS, 16)?));
    marks.push(first(gl.glGetInternalformativ(RENDERBUFFER, RGBA8UI, NUM_SAMPLE_COUNTS, 16)?));
    gl.glGetInternalformativ(TEXTURE_2D, RGBA8, SAMPLES, 16)?;
    marks.push(gl.glGetError()?);

    // The multisample framebuffer: 4-sample colour and depth.
    let size = (W, H - 8);
    let color_rb = renderbuffer(gl, n, 4, RGBA8, size)?;
    marks.push(first(vec![gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_SAMPLES)?]));
    let depth_rb = renderbuffer(gl, n, 4, DEPTH_COMPONENT24, size)?;
    let ms = n.next();
    gl.glGenFramebuffers(Slice::new(&[ms]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, ms)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, color_rb)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, depth_rb)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(first(gl.glGetIntegerv(SAMPLES)?));
    marks.push(first(gl.glGetIntegerv(SAMPLE_BUFFERS)?));
    gl.glViewport(0, 0, size.0, size.1)?;
    gl.glClearColor(0.2, 0.3, 0.4, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT)?;

    // A green triangle in front, a red one behind it reaching past it, a blue sliver whose
    // long edges are nearly horizontal, and a quad at half coverage.
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glEnable(DEPTH_TEST_CAP)?;
    triangles(gl, n, p, &[-0.9, -0.9, 0.0, 0.3, -0.7, 0.0, -0.5, 0.8, 0.0], [0.0, 1.0, 0.0, 1.0])?;
    triangles(gl, n, p, &[-0.8, 0.1, 0.5, 0.9, -0.2, 0.5, 0.7, 0.9, 0.5], [1.0, 0.0, 0.0, 1.0])?;
    triangles(gl, n, p, &[-1.0, -0.2, -0.5, 1.0, -0.35, -0.5, 1.0, -0.1, -0.5], [0.0, 0.2, 1.0, 1.0])?;
    gl.glDisable(DEPTH_TEST_CAP)?;
    gl.glEnable(SAMPLE_COVERAGE)?;
    gl.glSampleCoverage(0.5, false)?;
    triangles(gl, n, p, &quad(0.4, -0.95, 0.95, -0.5, 0.0), [1.0, 1.0, 1.0, 1.0])?;
    gl.glDisable(SAMPLE_COVERAGE)?;
    gl.glEnable(SAMPLE_ALPHA_TO_COVERAGE)?;
    triangles(gl, n, p, &quad(-0.95, 0.5, -0.6, 0.95, 0.0), [1.0, 1.0, 0.0, 0.5])?;
    gl.glDisable(SAMPLE_ALPHA_TO_COVERAGE)?;

    // Reads and copies refused.
    let scratch = n.next();
    gl.glGenTextures(Slice::new(&[scratch]))?;
    gl.glBindTexture(TEXTURE_2D, scratch)?;
    gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?;
    marks.push(gl.glGetError()?);
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);

    // The resolve, into a texture's framebuffer.
    let (resolved, tex) = (n.next(), n.next());
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, size.0, size.1, 0, RGBA, UNSIGNED_BYTE, None)?;
    gl.glGenFramebuffers(Slice::new(&[resolved]))?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, resolved)?;
    gl.glFramebufferTexture2D(DRAW_FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, tex, 0)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, ms)?;
    // A moved rectangle, and a multisample draw framebuffer, are refused.
    gl.glBlitFramebuffer(0, 0, 8, 8, 1, 0, 9, 8, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, ms)?;
    gl.glBlitFramebuffer(0, 0, 8, 8, 0, 0, 8, 8, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, resolved)?;
    gl.glBlitFramebuffer(0, 0, size.0, size.1, 0, 0, size.0, size.1, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    // Into a buffer of another internal format: refused.
    let other = renderbuffer(gl, n, 0, RGBA4, size)?;
    let other_fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[other_fb]))?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, other_fb)?;
    gl.glFramebufferRenderbuffer(DRAW_FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, other)?;
    gl.glBlitFramebuffer(0, 0, size.0, size.1, 0, 0, size.0, size.1, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    // Shown in the window, one to one.
    gl.glBindFramebuffer(READ_FRAMEBUFFER, resolved)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, size.0, size.1, 0, 0, size.0, size.1, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);

    // Integer formats take no samples; counts beyond the most are refused.
    renderbuffer(gl, n, 4, RGBA8UI, (4, 4))?;
    marks.push(gl.glGetError()?);
    renderbuffer(gl, n, 8, RGBA8, (4, 4))?;
    marks.push(gl.glGetError()?);
    renderbuffer(gl, n, -1, RGBA8, (4, 4))?;
    marks.push(gl.glGetError()?);
    let one = renderbuffer(gl, n, 1, RGBA8, (4, 4))?;
    marks.push(first(vec![gl.glGetRenderbufferParameteriv(RENDERBUFFER, RENDERBUFFER_SAMPLES)?]));
    // Mixed sample counts: a multisample colour buffer with a single-sample depth buffer.
    let single_depth = renderbuffer(gl, n, 0, DEPTH_COMPONENT24, (4, 4))?;
    let mixed = n.next();
    gl.glGenFramebuffers(Slice::new(&[mixed]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, mixed)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, one)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, single_depth)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

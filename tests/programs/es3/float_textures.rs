//! ES 3.0's sized float formats in `glTexImage2D`: the half-float formats from `GL_HALF_FLOAT`
//! and `GL_FLOAT` data, the 32-bit ones from `GL_FLOAT` data, each channel count, values beyond
//! [0, 1] kept, half-float images filtered linearly and rendered to (cleared and drawn beyond
//! 1), sub-images by the format's table; and the pairings the table refuses, as colours and
//! marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const HALF_FLOAT: u32 = 0x140B;
const RED: u32 = 0x1903;
const RG: u32 = 0x8227;
const RGBA16F: i32 = 0x881A;
const RGB16F: i32 = 0x881B;
const RG16F: i32 = 0x822F;
const R16F: i32 = 0x822D;
const RGBA32F: i32 = 0x8814;
const RGB32F: i32 = 0x8815;
const RG32F: i32 = 0x8230;
const R32F: i32 = 0x822E;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform sampler2D s; uniform vec2 uv; uniform float scale;
    out vec4 o;
    void main() { o = texture(s, uv) * scale; }";
const FS_BRIGHT: &str = "#version 300 es
    precision highp float;
    out vec4 o;
    void main() { o = vec4(2.5, 0.25, 3.0, 1.5); }";

/// Half floats' bytes.
fn halves(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| half::f16::from_f32(*x).to_bits().to_ne_bytes()).collect()
}

/// A new 2D texture bound on unit 0, filtered by `filter`, holding `w`×1 texels of `data` in
/// `internal` from `format` and `ty`.
#[allow(clippy::too_many_arguments)]
fn float_texture(
    gl: Gl<'_>,
    n: &mut Names,
    internal: i32,
    w: i32,
    format: u32,
    ty: u32,
    data: &[u8],
    filter: i32,
) -> R {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, filter)?;
    gl.glTexImage2D(TEXTURE_2D, 0, internal, w, 1, 0, format, ty, Some(Blob::borrowed(data)))
}

/// The float texture program.
pub fn float_textures(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let (uv, scale) =
        (gl.glGetUniformLocation(p, Text::borrowed("uv"))?, gl.glGetUniformLocation(p, Text::borrowed("scale"))?);
    // Draws cell `k` (8 across, 8×8 pixels each) reading the bound texture at (`u`, 0.5).
    let cell = |gl: Gl<'_>, n: &mut Names, k: usize, u: f32, s: f32| -> R {
        gl.glUniform2f(uv, u, 0.5)?;
        gl.glUniform1f(scale, s)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    };
    gl.glActiveTexture(TEXTURE0)?;
    let mut marks = Vec::new();

    // Each format, values beyond [0, 1] scaled back into it by the shader.
    let wide = [2.0, 0.5, 0.25, 4.0, 1.0, 3.0, 0.5, 2.0];
    float_texture(gl, n, RGBA16F, 2, RGBA, HALF_FLOAT, &halves(&wide), NEAREST)?;
    cell(gl, n, 0, 0.25, 0.25)?;
    cell(gl, n, 1, 0.75, 0.25)?;
    // Linear filtering between the two texels.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    cell(gl, n, 2, 0.5, 0.25)?;
    // Float data replacing a texel of the half-float image.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 1, 1, RGBA, FLOAT, Blob::borrowed(&f32s(&[0.5, 1.5, 3.5, 2.5])))?;
    cell(gl, n, 14, 0.75, 0.25)?;
    let cases: [(i32, u32, u32, Vec<u8>, usize); 7] = [
        (RGBA16F, RGBA, FLOAT, f32s(&wide[..4]), 3),
        (RGB16F, RGB, FLOAT, f32s(&[3.0, 1.5, 0.5]), 4),
        (RG16F, RG, HALF_FLOAT, halves(&[0.75, 2.0]), 5),
        (R16F, RED, FLOAT, f32s(&[1.25]), 6),
        (RGBA32F, RGBA, FLOAT, f32s(&[0.5, 3.5, 1.0, 2.0]), 7),
        (RGB32F, RGB, FLOAT, f32s(&[2.25, 0.5, 1.75]), 8),
        (RG32F, RG, FLOAT, f32s(&[1.5, 3.25]), 9),
    ];
    for (internal, format, ty, data, k) in cases {
        float_texture(gl, n, internal, 1, format, ty, &data, NEAREST)?;
        cell(gl, n, k, 0.5, 0.25)?;
    }
    // A 32-bit red image, then a texel of it replaced.
    float_texture(gl, n, R32F, 2, RED, FLOAT, &f32s(&[0.5, 1.0]), NEAREST)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 0, 1, 1, RED, FLOAT, Blob::borrowed(&f32s(&[3.0])))?;
    cell(gl, n, 10, 0.25, 0.5)?;
    cell(gl, n, 11, 0.75, 0.25)?;
    // Half-float data replacing a texel of a 32-bit image is refused.
    gl.glTexSubImage2D(TEXTURE_2D, 0, 0, 0, 1, 1, RED, HALF_FLOAT, Blob::borrowed(&halves(&[0.5])))?;
    marks.push(gl.glGetError()?);

    // A half-float image rendered to: cleared beyond 1 in one half, drawn beyond 1 in the other.
    let target = n.next();
    gl.glGenTextures(Slice::new(&[target]))?;
    gl.glBindTexture(TEXTURE_2D, target)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA16F, 2, 1, 0, RGBA, HALF_FLOAT, None)?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, target, 0)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 2, 1)?;
    gl.glClearColor(3.0, 0.5, 1.5, 2.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glViewport(1, 0, 1, 1)?;
    program(gl, n, VS, FS_BRIGHT, &[])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)?;
    gl.glUseProgram(p)?;
    cell(gl, n, 12, 0.25, 0.25)?;
    cell(gl, n, 13, 0.75, 0.25)?;

    // The pairings ES 3.0's table refuses, and an unknown type.
    let refused: [(i32, u32, u32); 4] =
        [(RGBA16F, RGBA, UNSIGNED_BYTE), (RGBA32F, RGBA, HALF_FLOAT), (R32F, RGBA, FLOAT), (RGBA16F, RGBA, 0x1234)];
    for (internal, format, ty) in refused {
        gl.glTexImage2D(TEXTURE_2D, 0, internal, 1, 1, 0, format, ty, None)?;
        marks.push(gl.glGetError()?);
    }
    mark_all(gl, &marks)
}

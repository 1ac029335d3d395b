//! Programs for texture formats and the texture-side extensions: float and half-float
//! textures (`OES_texture_float`, `OES_texture_half_float` and their `_linear` variants),
//! BGRA uploads (`EXT_texture_format_BGRA8888`), unpack sub-rectangles
//! (`EXT_unpack_subimage`), depth-stencil textures
//! (`OES_packed_depth_stencil` with `OES_depth_texture`), non-power-of-two textures
//! (`OES_texture_npot`), and 8-bit, 24-bit depth and packed depth-stencil renderbuffers
//! (`OES_rgb8_rgba8`, `OES_depth24`, `OES_packed_depth_stencil`).

use half::f16;

use super::multi_draw::mark_all;
use super::*;

const BGRA_EXT: u32 = 0x80E1;
const DEPTH_STENCIL_OES: u32 = 0x84F9;
const UNSIGNED_INT_24_8_OES: u32 = 0x84FA;
const UNPACK_ROW_LENGTH: u32 = 0x0CF2;
const UNPACK_SKIP_ROWS: u32 = 0x0CF3;
const UNPACK_SKIP_PIXELS: u32 = 0x0CF4;
const STENCIL_ATTACHMENT: u32 = 0x8D20;
const RGBA8_OES: u32 = 0x8058;
const RGB8_OES: u32 = 0x8051;
const DEPTH_COMPONENT24_OES: u32 = 0x81A6;
const DEPTH24_STENCIL8_OES: u32 = 0x88F0;
const FRAMEBUFFER_COMPLETE: u32 = 0x8CD5;

/// A texture sampled, scaled and biased into [0, 1] (float textures hold any value).
const FS_SCALED: &str = "precision highp float; uniform highp sampler2D s; uniform vec2 sb; varying vec2 t;
    void main() { gl_FragColor = texture2D(s, t) * sb.x + sb.y; }";

/// Shows the red channel of a depth texture, and its fraction ×16 to make small errors visible.
const FS_DEPTH_RED: &str = "precision highp float; uniform highp sampler2D s; varying vec2 t;
    void main() { float d = texture2D(s, t).r; gl_FragColor = vec4(d, fract(d * 16.0), 0.0, 1.0); }";

/// A new 2D texture on unit 0 with the given filters and clamped edges.
pub(super) fn new_texture(gl: Gl<'_>, n: &mut Names, min: i32, mag: i32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, min)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, mag)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_S, CLAMP_TO_EDGE)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, CLAMP_TO_EDGE)?;
    Ok(t)
}

/// Uses the scale-and-bias program.
fn scaled_program(gl: Gl<'_>, n: &mut Names, scale: f32, bias: f32) -> R {
    let p = program(gl, n, VS_TEX, FS_SCALED, &["pos", "uv"])?;
    let loc = gl.glGetUniformLocation(p, Text::borrowed("sb"))?;
    gl.glUniform2f(loc, scale, bias)
}

/// Draws the bound texture over the viewport rectangle `[x, y, w, h]`.
pub(super) fn blit(gl: Gl<'_>, n: &mut Names, r: [i32; 4]) -> R {
    gl.glViewport(r[0], r[1], r[2], r[3])?;
    textured_quad(gl, n, 0.0, 1.0)
}

/// `v` as `FLOAT` or `HALF_FLOAT_OES` texel data.
pub(super) fn float_data(v: &[f32], ty: u32) -> Vec<u8> {
    if ty == FLOAT {
        f32s(v)
    } else {
        v.iter().flat_map(|x| f16::from_f32(*x).to_bits().to_ne_bytes()).collect()
    }
}

fn has_extension(gl: Gl<'_>, name: &str) -> Result<bool, ClientError> {
    Ok(gl.glGetString(0x1F03)?.unwrap_or_default().split(' ').any(|e| e == name))
}

fn float_texture_formats(gl: Gl<'_>, n: &mut Names) -> R {
    // piglit's oes_texture_float scheme: values in [-1000, 1000] shown as v / 2000 + 0.5.
    scaled_program(gl, n, 1.0 / 2000.0, 0.5)?;
    let formats = [(RGBA, 4), (RGB, 3), (LUMINANCE, 1), (ALPHA, 1), (LUMINANCE_ALPHA, 2)];
    for (row, ty) in [FLOAT, HALF_FLOAT_OES].into_iter().enumerate() {
        for (i, (format, comps)) in formats.into_iter().enumerate() {
            new_texture(gl, n, NEAREST, NEAREST)?;
            let v: Vec<f32> = (0..4 * comps).map(|k| ((k * 373 + i * 151 + row * 97) % 2000) as f32 - 999.75).collect();
            let data = float_data(&v, ty);
            gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 2, 2, 0, format, ty, Some(Blob::borrowed(&data)))?;
            blit(gl, n, [i as i32 * 12 + 2, row as i32 * 32, 12, 32])?;
        }
    }
    Ok(())
}

fn float_texture_linear(gl: Gl<'_>, n: &mut Names) -> R {
    scaled_program(gl, n, 1.0 / 1000.0, 0.3)?;
    let v: Vec<f32> = (0..64).map(|k| ((k * 211 + (k / 4) * 97) % 700) as f32 - 100.5).collect();
    // RGBA32F is filtered only where OES_texture_float_linear is offered.
    let linear = if has_extension(gl, "GL_OES_texture_float_linear")? { LINEAR } else { NEAREST };
    new_texture(gl, n, linear, linear)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, FLOAT, Some(Blob::borrowed(&float_data(&v, FLOAT))))?;
    blit(gl, n, [0, 0, 32, 64])?;
    // Half floats are filtered (`GL_OES_texture_half_float_linear`).
    new_texture(gl, n, LINEAR, LINEAR)?;
    let half = float_data(&v, HALF_FLOAT_OES);
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 4, 4, 0, RGB, HALF_FLOAT_OES, Some(Blob::borrowed(&half[..96])))?;
    blit(gl, n, [32, 0, 32, 64])
}

fn float_texture_mipmaps(gl: Gl<'_>, n: &mut Names) -> R {
    scaled_program(gl, n, 0.25, 0.0)?;
    // Explicit half-float levels of distinct colours, each drawn at its own size.
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    for level in 0..5 {
        let size = 16 >> level;
        let c = [level as f32 * 0.75, 4.0 - level as f32 * 0.5, (level % 2) as f32 * 3.0, 4.0];
        let v: Vec<f32> = (0..size * size).flat_map(|_| c).collect();
        let data = float_data(&v, HALF_FLOAT_OES);
        gl.glTexImage2D(
            TEXTURE_2D,
            level,
            RGBA as i32,
            size,
            size,
            0,
            RGBA,
            HALF_FLOAT_OES,
            Some(Blob::borrowed(&data)),
        )?;
    }
    let mut x = 0;
    for level in 0..5 {
        let size = 16 >> level;
        blit(gl, n, [x, 0, size, size])?;
        x += size + 2;
    }
    // Generated half-float levels of 2×2 checker blocks (exact averages).
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    let v: Vec<f32> = (0..64)
        .flat_map(|i| if ((i % 8) / 2 + (i / 16)) % 2 == 0 { [4.0, 0.5, 1.0, 4.0] } else { [0.0, 3.5, 2.0, 1.0] })
        .collect();
    let data = float_data(&v, HALF_FLOAT_OES);
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 8, 8, 0, RGBA, HALF_FLOAT_OES, Some(Blob::borrowed(&data)))?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    let mut x = 0;
    for level in 0..4 {
        let size = 8 >> level;
        blit(gl, n, [x, 32, size, size])?;
        x += size + 2;
    }
    Ok(())
}

fn bgra_texture(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    new_texture(gl, n, NEAREST, NEAREST)?;
    let px = pattern(4, 4);
    gl.glTexImage2D(TEXTURE_2D, 0, BGRA_EXT as i32, 4, 4, 0, BGRA_EXT, UNSIGNED_BYTE, Some(Blob::borrowed(&px)))?;
    let sub = [10u8, 200, 30, 255, 250, 20, 90, 128, 0, 0, 255, 255, 60, 60, 60, 60];
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 2, 2, 2, BGRA_EXT, UNSIGNED_BYTE, Blob::borrowed(&sub))?;
    blit(gl, n, [0, 0, W, H])
}

fn unpack_subimage(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    // A 4×3 texture cut out of an 8×6 image at (3, 2).
    new_texture(gl, n, NEAREST, NEAREST)?;
    let src = pattern(8, 6);
    gl.glPixelStorei(UNPACK_ROW_LENGTH, 8)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 2)?;
    gl.glPixelStorei(UNPACK_SKIP_PIXELS, 3)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 3, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&src)))?;
    blit(gl, n, [0, 0, 32, 64])?;
    // RGB rows of 5 pixels padded to 2 bytes; a 2×2 sub-image from (1, 1) of them.
    new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 2)?;
    gl.glPixelStorei(UNPACK_ROW_LENGTH, 0)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 0)?;
    gl.glPixelStorei(UNPACK_SKIP_PIXELS, 0)?;
    let rgb: Vec<u8> = (0..4 * 16).map(|i| (i * 37 % 256) as u8).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 5, 4, 0, RGB, UNSIGNED_BYTE, Some(Blob::borrowed(&rgb)))?;
    gl.glPixelStorei(UNPACK_ROW_LENGTH, 5)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 1)?;
    gl.glPixelStorei(UNPACK_SKIP_PIXELS, 1)?;
    let other: Vec<u8> = (0..4 * 16).map(|i| (255 - i * 11 % 256) as u8).collect();
    gl.glTexSubImage2D(TEXTURE_2D, 0, 2, 1, 2, 2, RGB, UNSIGNED_BYTE, Blob::borrowed(&other))?;
    gl.glPixelStorei(UNPACK_ROW_LENGTH, 0)?;
    gl.glPixelStorei(UNPACK_SKIP_ROWS, 0)?;
    gl.glPixelStorei(UNPACK_SKIP_PIXELS, 0)?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 4)?;
    blit(gl, n, [32, 0, 32, 64])
}

/// A framebuffer object with `color` (a texture) and a depth-stencil texture at both the depth
/// and stencil attachments; fails if it is not complete.
fn ds_framebuffer(gl: Gl<'_>, n: &mut Names, color: u32, ds: u32) -> Result<u32, ClientError> {
    let fb = n.next();
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, color, 0)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, ds, 0)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, STENCIL_ATTACHMENT, TEXTURE_2D, ds, 0)?;
    if gl.glCheckFramebufferStatus(FRAMEBUFFER)? != FRAMEBUFFER_COMPLETE {
        return Err(ClientError::Unsupported("depth-stencil texture framebuffer incomplete".into()));
    }
    Ok(fb)
}

fn depth_stencil_texture(gl: Gl<'_>, n: &mut Names) -> R {
    // Render into a colour texture with a depth-stencil texture: a stencil mask, then depth-
    // tested quads inside it.
    let target = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 32, 32, 0, RGBA, UNSIGNED_BYTE, None)?;
    let ds = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        DEPTH_STENCIL_OES as i32,
        32,
        32,
        0,
        DEPTH_STENCIL_OES,
        UNSIGNED_INT_24_8_OES,
        None,
    )?;
    ds_framebuffer(gl, n, target, ds)?;
    gl.glViewport(0, 0, 32, 32)?;
    gl.glClearColor(0.1, 0.1, 0.3, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glEnable(STENCIL_TEST)?;
    gl.glStencilFunc(0x0207, 1, 0xFF)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E01)?;
    color(gl, p, [0.2, 0.2, 0.2, 1.0])?;
    draw_positions(gl, n, &[-0.9, -0.9, 0.0, 0.9, -0.6, 0.0, -0.2, 0.9, 0.0], TRIANGLES)?;
    gl.glStencilFunc(0x0202, 1, 0xFF)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E00)?;
    gl.glEnable(DEPTH_TEST)?;
    color(gl, p, [1.0, 0.5, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.5, 0.5, 0.4), TRIANGLES)?;
    color(gl, p, [0.0, 0.8, 0.4, 1.0])?;
    draw_positions(gl, n, &[-1.0, 1.0, -0.5, 1.0, 1.0, 0.9, 1.0, -1.0, 0.2], TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)?;
    gl.glDisable(STENCIL_TEST)?;
    // Uploaded depths and stencil values: the stencil test passes where the low byte is 1.
    let target2 = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 16, 16, 0, RGBA, UNSIGNED_BYTE, None)?;
    let ds2 = new_texture(gl, n, NEAREST, NEAREST)?;
    let values: Vec<u8> = (0..256u32)
        .flat_map(|i| {
            let depth = (i * 65_793) & 0xFF_FFFF;
            ((depth << 8) | u32::from((i % 16) / 4 % 2 != (i / 64) % 2)).to_ne_bytes()
        })
        .collect();
    let (f, t) = (DEPTH_STENCIL_OES, UNSIGNED_INT_24_8_OES);
    gl.glTexImage2D(TEXTURE_2D, 0, f as i32, 16, 16, 0, f, t, Some(Blob::borrowed(&values)))?;
    ds_framebuffer(gl, n, target2, ds2)?;
    gl.glViewport(0, 0, 16, 16)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glEnable(STENCIL_TEST)?;
    gl.glStencilFunc(0x0202, 1, 0xFF)?;
    color(gl, p, [1.0, 1.0, 0.0, 1.0])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glDisable(STENCIL_TEST)?;
    // Show the colour results and both textures' depths.
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, target)?;
    blit(gl, n, [0, 0, 32, 32])?;
    gl.glBindTexture(TEXTURE_2D, target2)?;
    blit(gl, n, [32, 0, 32, 32])?;
    program(gl, n, VS_TEX, FS_DEPTH_RED, &["pos", "uv"])?;
    gl.glBindTexture(TEXTURE_2D, ds)?;
    blit(gl, n, [0, 32, 32, 32])?;
    gl.glBindTexture(TEXTURE_2D, ds2)?;
    blit(gl, n, [32, 32, 32, 32])
}

fn npot_textures(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    // OES_texture_npot: non-power-of-two sizes with linear filtering and clamped edges…
    new_texture(gl, n, LINEAR, LINEAR)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 13, 7, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&pattern(13, 7))))?;
    blit(gl, n, [0, 0, 32, 32])?;
    // …and, which ES 2.0 alone forbids, repeat wrapping and mipmaps.
    new_texture(gl, n, NEAREST_MIPMAP_NEAREST, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_S, REPEAT)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, MIRRORED_REPEAT)?;
    for (level, (w, h)) in [(10, 6), (5, 3), (2, 1), (1, 1)].into_iter().enumerate() {
        let px: Vec<u8> = pattern(w, h).iter().map(|&b| b.wrapping_add(level as u8 * 60)).collect();
        gl.glTexImage2D(
            TEXTURE_2D,
            level as i32,
            RGBA as i32,
            w,
            h,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&px)),
        )?;
    }
    gl.glViewport(32, 0, 32, 32)?;
    textured_quad(gl, n, -1.0, 2.0)?;
    // Level 1 (5×3) drawn at its size, repeated twice each way.
    gl.glViewport(0, 40, 10, 6)?;
    textured_quad(gl, n, 0.0, 2.0)
}

/// Two overlapping quads whose depths differ by less than 16 bits resolve.
fn close_depths(gl: Gl<'_>, n: &mut Names) -> R {
    gl.glEnable(DEPTH_TEST)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    color(gl, p, [0.9, 0.3, 0.1, 1.0])?;
    draw_positions(gl, n, &quad(-0.8, -0.8, 0.6, 0.6, 0.50001), TRIANGLES)?;
    color(gl, p, [0.1, 0.6, 0.9, 0.5])?;
    draw_positions(gl, n, &quad(-0.6, -0.6, 0.8, 0.8, 0.50000), TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)
}

/// A framebuffer object of `color` and `depth` renderbuffers (`depth` also at the stencil
/// attachment if `stencil`), left bound so that the program's image is read from it.
fn renderbuffer_target(gl: Gl<'_>, n: &mut Names, color: u32, depth: u32, stencil: bool) -> R {
    let (fb, c, d) = (n.next(), n.next(), n.next());
    gl.glBindRenderbuffer(RENDERBUFFER, c)?;
    gl.glRenderbufferStorage(RENDERBUFFER, color, W, H)?;
    gl.glBindRenderbuffer(RENDERBUFFER, d)?;
    gl.glRenderbufferStorage(RENDERBUFFER, depth, W, H)?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, c)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, DEPTH_ATTACHMENT, RENDERBUFFER, d)?;
    if stencil {
        gl.glFramebufferRenderbuffer(FRAMEBUFFER, STENCIL_ATTACHMENT, RENDERBUFFER, d)?;
    }
    if gl.glCheckFramebufferStatus(FRAMEBUFFER)? != FRAMEBUFFER_COMPLETE {
        return Err(ClientError::Unsupported("renderbuffer framebuffer incomplete".into()));
    }
    gl.glClearColor(0.2, 0.3, 0.1, 0.6)?;
    gl.glClearStencil(0)?;
    gl.glClear(COLOR_BUFFER_BIT | DEPTH_BUFFER_BIT | STENCIL_BUFFER_BIT)
}

fn renderbuffer_rgba8_depth24(gl: Gl<'_>, n: &mut Names) -> R {
    renderbuffer_target(gl, n, RGBA8_OES, DEPTH_COMPONENT24_OES, false)?;
    close_depths(gl, n)
}

fn renderbuffer_rgb8_depth24_stencil8(gl: Gl<'_>, n: &mut Names) -> R {
    renderbuffer_target(gl, n, RGB8_OES, DEPTH24_STENCIL8_OES, true)?;
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glEnable(STENCIL_TEST)?;
    gl.glStencilFunc(0x0207, 3, 0xFF)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E01)?;
    color(gl, p, [0.4, 0.4, 0.4, 1.0])?;
    draw_positions(gl, n, &[-1.0, -1.0, 0.0, 1.0, -0.5, 0.0, 0.0, 1.0, 0.0], TRIANGLES)?;
    gl.glStencilFunc(0x0205, 3, 0xFF)?;
    gl.glStencilOp(0x1E00, 0x1E00, 0x1E00)?;
    close_depths(gl, n)?;
    gl.glDisable(STENCIL_TEST)
}

/// RGB images read alpha as 1, however they were filled: without data, by rendering, or by a
/// copy from a framebuffer with alpha.
fn rgb_alpha_is_one(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS_POS, FS_COLOR, &["pos"])?;
    gl.glClearColor(0.5, 0.25, 0.75, 0.3)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    color(gl, p, [0.9, 0.6, 0.1, 0.6])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 0.2, 0.0), TRIANGLES)?;
    let copied = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGB, 0, 0, 32, 32, 0)?;
    let blank = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 16, 16, 0, RGB, UNSIGNED_BYTE, None)?;
    let rendered = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGB as i32, 16, 16, 0, RGB, UNSIGNED_BYTE, None)?;
    let fb = n.next();
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, rendered, 0)?;
    gl.glViewport(0, 0, 16, 16)?;
    gl.glClearColor(0.1, 0.2, 0.3, 0.2)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    // Blending with the destination's alpha (1) as the factor.
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(0x0304, 0)?;
    draw_positions(gl, n, &quad(-0.5, -0.5, 1.0, 1.0, 0.0), TRIANGLES)?;
    gl.glDisable(BLEND)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    let fs = "precision mediump float; uniform sampler2D s; varying vec2 t;
        void main() { vec4 c = texture2D(s, t); gl_FragColor = vec4(c.a, c.rg, 1.0); }";
    program(gl, n, VS_TEX, fs, &["pos", "uv"])?;
    for (i, tex) in [copied, blank, rendered].into_iter().enumerate() {
        gl.glBindTexture(TEXTURE_2D, tex)?;
        blit(gl, n, [i as i32 * 21, 0, 20, 64])?;
    }
    Ok(())
}

/// Texture 0, the default texture of each target: it takes images, sub-images, copies and
/// parameters as any texture does and is sampled where bound (a 2D image nearest then linear,
/// a cube face), each context's own; its queries answer what was set, as colours and marks.
fn default_texture(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(
        gl,
        n,
        VS_TEX,
        "precision mediump float; uniform sampler2D s; varying vec2 t;
        void main() { gl_FragColor = texture2D(s, t); }",
        &["pos", "uv"],
    )?;
    let _ = p;
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_2D, 0)?;
    let texels: Vec<u8> = (0..16u8).flat_map(|i| [i * 16, 255 - i * 16, 64, 255]).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&texels)))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    gl.glTexSubImage2D(TEXTURE_2D, 0, 1, 1, 1, 1, RGBA, UNSIGNED_BYTE, Blob::borrowed(&[255, 255, 0, 255]))?;
    let mut marks = vec![gl.glGetError()?];
    blit(gl, n, [0, 0, 32, 32])?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_MAG_FILTER)?.first().copied().unwrap_or(0) as u32);
    blit(gl, n, [32, 0, 32, 32])?;
    // A copy into it, and a named texture bound over it and away again.
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 0, 0, 40, 8, 2, 2)?;
    marks.push(gl.glGetError()?);
    let named = new_texture(gl, n, NEAREST, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 1, 1, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&[0, 0, 255, 255])))?;
    blit(gl, n, [0, 32, 16, 16])?;
    gl.glBindTexture(TEXTURE_2D, 0)?;
    blit(gl, n, [16, 32, 16, 16])?;
    let _ = named;
    mark_all(gl, &marks)
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    let c = |name, run, tol| Case { name, run, tol, expects_error: false };
    // Depth shown as fract(16·d): Mesa's 24-bit unorm depth against wgpu's depth formats may
    // round the last bit of that channel either way (as for the other depth-texture programs).
    let depth_tol = Tol { max_diff: 2, min_fraction: 0.999 };
    vec![
        c("float_texture_formats", float_texture_formats, DEFAULT),
        c("float_texture_linear", float_texture_linear, DEFAULT),
        c("float_texture_mipmaps", float_texture_mipmaps, DEFAULT),
        c("bgra_texture", bgra_texture, DEFAULT),
        c("unpack_subimage", unpack_subimage, DEFAULT),
        c("depth_stencil_texture", depth_stencil_texture, depth_tol),
        c("npot_textures", npot_textures, DEFAULT),
        c("renderbuffer_rgba8_depth24", renderbuffer_rgba8_depth24, DEFAULT),
        c("renderbuffer_rgb8_depth24_stencil8", renderbuffer_rgb8_depth24_stencil8, DEFAULT),
        c("rgb_alpha_is_one", rgb_alpha_is_one, DEFAULT),
        c("default_texture", default_texture, DEFAULT),
    ]
}

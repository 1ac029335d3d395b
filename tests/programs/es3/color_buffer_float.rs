//! ES 3.0's float and 10-bit colour buffers (`GL_EXT_color_buffer_float`, and `RGB10_A2`,
//! which ES 3.0 makes renderable): renderbuffers of the 16- and 32-bit float formats, the
//! packed `R11F_G11F_B10F` and `RGB10_A2`, each cleared with values beyond [0, 1] (negative
//! ones too), drawn into, blended into and cleared in part by `glClearBufferfv`, then read as
//! `GL_RGBA`/`GL_FLOAT`, in the buffer's implementation read format and as bytes, with their
//! completeness, component type, sizes and read format; textures of these formats (2D, a 3D
//! slice, a 2D array layer, immutable and not) drawn into and sampled into the window, and
//! the unsized and other float images that are not renderable; blits from float to 8-bit and
//! 8-bit to float buffers (scaled, linear), into the 10-bit one from the window, and the
//! integer-to-float blit refused; copies between float buffers and images; one clear of an
//! 8-bit and a 32-bit float buffer at once; the extension string; all as marks and colours.

use super::super::multi_draw::mark_all;
use super::super::*;

const RED: u32 = 0x1903;
const RG: u32 = 0x8227;
const HALF_FLOAT: u32 = 0x140B;
const R16F: u32 = 0x822D;
const RG16F: u32 = 0x822F;
const RGBA16F: u32 = 0x881A;
const R32F: u32 = 0x822E;
const RG32F: u32 = 0x8230;
const RGBA32F: u32 = 0x8814;
const RGB32F: u32 = 0x8815;
const R11F_G11F_B10F: u32 = 0x8C3A;
const RGB9_E5: u32 = 0x8C3D;
const RGB10_A2: u32 = 0x8059;
const RGBA8: u32 = 0x8058;
const RGBA8UI: u32 = 0x8D7C;
const UNSIGNED_INT_2_10_10_10_REV: u32 = 0x8368;
const UNSIGNED_INT_10F_11F_11F_REV: u32 = 0x8C3B;
const TEXTURE_3D: u32 = 0x806F;
const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const COLOR: u32 = 0x1800;
const ONE: u32 = 1;
const READ_FRAMEBUFFER: u32 = 0x8CA8;
const DRAW_FRAMEBUFFER: u32 = 0x8CA9;
const IMPLEMENTATION_COLOR_READ_TYPE: u32 = 0x8B9A;
const IMPLEMENTATION_COLOR_READ_FORMAT: u32 = 0x8B9B;
const COMPONENT_TYPE: u32 = 0x8211;
const RED_SIZE: u32 = 0x8212;
const GREEN_SIZE: u32 = 0x8213;
const BLUE_SIZE: u32 = 0x8214;
const ALPHA_SIZE: u32 = 0x8215;
const EXTENSIONS: u32 = 0x1F03;

/// The clear colour: beyond [0, 1] both ways.
const CLEAR: [f32; 4] = [-2.5, 3.25, 0.5, -0.75];
/// The drawn colour.
const DRAWN: [f32; 4] = [1.5, -0.5, 0.25, 2.0];
/// The colour `glClearBufferfv` clears one pixel to.
const CLEARED: [f32; 4] = [-1.25, 0.375, 8.0, 0.125];

/// A GLSL ES 3.00 colour program: the `color` uniform at output 0.
const VS: &str = "#version 300 es
in vec4 pos;
void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
precision highp float;
uniform vec4 color;
out vec4 o;
void main() { o = color; }";
/// A gradient across the window's pixels, from -2 to 2 in red, 1 to -1 in green, and fixed
/// blue and alpha beyond 1.
const FS_GRADIENT: &str = "#version 300 es
precision highp float;
uniform vec2 size;
out vec4 o;
void main() {
    vec2 f = gl_FragCoord.xy / size;
    o = vec4(f.x * 4.0 - 2.0, 1.0 - 2.0 * f.y, 1.5, 1.25);
}";
/// Two outputs: an 8-bit and a float buffer.
const FS_TWO: &str = "#version 300 es
precision highp float;
layout(location = 0) out vec4 a;
layout(location = 1) out vec4 b;
void main() { a = vec4(0.25, 1.5, -1.0, 0.5); b = vec4(0.25, 1.5, -1.0, 0.5); }";
/// Shows a texture's values v as v / 4 + 0.5.
const FS_SCALED: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { gl_FragColor = texture2D(s, t) * 0.25 + 0.5; }";

/// A float as a mark: its value in 256ths (the mark keeps the low 16 bits).
fn f(v: f32) -> u32 {
    (v * 256.0).round() as i32 as u32
}

/// The floats of `bytes` (native order).
fn floats(bytes: &[u8]) -> Vec<f32> {
    bytes.chunks_exact(4).map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]])).collect()
}

/// The first four bytes of `bytes` (fewer padded with zeros) as two marks, low half first.
fn word(marks: &mut Vec<u32>, bytes: &[u8]) {
    let mut b = [0u8; 4];
    let n = bytes.len().min(4);
    b[..n].copy_from_slice(&bytes[..n]);
    let v = u32::from_ne_bytes(b);
    marks.extend([v & 0xFFFF, v >> 16]);
}

/// A new framebuffer, bound.
fn framebuffer(gl: Gl<'_>, n: &mut Names) -> Result<u32, ClientError> {
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    Ok(fb)
}

/// A new `w`×`h` renderbuffer of `format` at colour attachment `slot` of the bound framebuffer.
fn renderbuffer(gl: Gl<'_>, n: &mut Names, format: u32, (w, h): (i32, i32), slot: u32) -> Result<u32, ClientError> {
    let rb = n.next();
    gl.glGenRenderbuffers(Slice::new(&[rb]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, rb)?;
    gl.glRenderbufferStorage(RENDERBUFFER, format, w, h)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0 + slot, RENDERBUFFER, rb)?;
    Ok(rb)
}

/// A new 2D texture with nearest filters, bound.
fn texture_2d(gl: Gl<'_>, n: &mut Names) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// Marks the bound framebuffer's status, colour attachment 0's component type and sizes (red
/// and green, blue and alpha, a byte each), and the implementation read format and type.
fn attachment_state(gl: Gl<'_>, marks: &mut Vec<u32>) -> R {
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    marks.push(gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, COMPONENT_TYPE)? as u32);
    let size = |gl: Gl<'_>, p| gl.glGetFramebufferAttachmentParameteriv(FRAMEBUFFER, COLOR_ATTACHMENT0, p);
    let (r, g) = (size(gl, RED_SIZE)?, size(gl, GREEN_SIZE)?);
    let (b, a) = (size(gl, BLUE_SIZE)?, size(gl, ALPHA_SIZE)?);
    marks.push((r | g << 8) as u32);
    marks.push((b | a << 8) as u32);
    for pname in [IMPLEMENTATION_COLOR_READ_FORMAT, IMPLEMENTATION_COLOR_READ_TYPE] {
        marks.push(gl.glGetIntegerv(pname)?.first().copied().unwrap_or(-7) as u32);
    }
    marks.push(gl.glGetError()?);
    Ok(())
}

/// Fills the bound 4×4 framebuffer: cleared to [`CLEAR`], [`DRAWN`] drawn over the left half,
/// blended (one, one) over the bottom right quarter, and pixel (3, 3) cleared to [`CLEARED`]
/// by `glClearBufferfv`: (0, 0) then holds the drawn colour, (2, 0) their sum, (2, 3) the
/// clear colour.
fn fill(gl: Gl<'_>, n: &mut Names, p: u32) -> R {
    gl.glViewport(0, 0, 4, 4)?;
    gl.glClearColor(CLEAR[0], CLEAR[1], CLEAR[2], CLEAR[3])?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    gl.glUseProgram(p)?;
    color(gl, p, DRAWN)?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 1.0, 0.0), TRIANGLES)?;
    gl.glEnable(BLEND)?;
    gl.glBlendFunc(ONE, ONE)?;
    draw_positions(gl, n, &quad(0.0, -1.0, 1.0, 0.0, 0.0), TRIANGLES)?;
    gl.glDisable(BLEND)?;
    gl.glEnable(SCISSOR_TEST)?;
    gl.glScissor(3, 3, 1, 1)?;
    gl.glClearBufferfv(COLOR, 0, Slice::new(&CLEARED))?;
    gl.glDisable(SCISSOR_TEST)
}

/// The colour buffer formats: renderbuffers of each, filled, read back.
fn renderbuffers(gl: Gl<'_>, n: &mut Names, p: u32, marks: &mut Vec<u32>) -> R {
    for format in [R16F, RG16F, RGBA16F, R32F, RG32F, RGBA32F, R11F_G11F_B10F, RGB10_A2] {
        framebuffer(gl, n)?;
        renderbuffer(gl, n, format, (4, 4), 0)?;
        attachment_state(gl, marks)?;
        fill(gl, n, p)?;
        if format == RGB10_A2 {
            // Normalized: read as bytes and as its own packed texels (the clear and the sum).
            for (x, y) in [(0, 0), (2, 0), (2, 3), (3, 3)] {
                let px = gl.glReadPixels(x, y, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
                marks.push(px.get(..2).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
                marks.push(px.get(2..4).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
            }
            let px = gl.glReadPixels(2, 0, 1, 1, RGBA, UNSIGNED_INT_2_10_10_10_REV)?.0;
            word(marks, &px);
            // Floats are no format of a normalized buffer.
            gl.glReadPixels(0, 0, 1, 1, RGBA, FLOAT)?;
            marks.push(gl.glGetError()?);
            continue;
        }
        // The sum and the glClearBufferfv pixel, every channel as floats (absent ones 0 and 1).
        let all = floats(&gl.glReadPixels(0, 0, 4, 4, RGBA, FLOAT)?.0);
        for at in [2, 15] {
            marks.extend(all.get(at * 4..at * 4 + 4).unwrap_or(&[9.0; 4]).iter().map(|v| f(*v)));
        }
        marks.push(gl.glGetError()?);
        // The drawn and the cleared pixel in the implementation read format.
        let read = |gl: Gl<'_>, p| gl.glGetIntegerv(p).map(|v| v.first().copied().unwrap_or(0) as u32);
        let (rf, rt) = (read(gl, IMPLEMENTATION_COLOR_READ_FORMAT)?, read(gl, IMPLEMENTATION_COLOR_READ_TYPE)?);
        for x in [0, 2] {
            let px = gl.glReadPixels(x, if x == 0 { 0 } else { 3 }, 1, 1, rf, rt)?.0;
            word(marks, &px);
        }
        // Bytes are no format of a float buffer.
        gl.glReadPixels(0, 0, 1, 1, RGBA, UNSIGNED_BYTE)?;
        marks.push(gl.glGetError()?);
    }
    Ok(())
}

/// Float textures drawn into and shown: each image gets the gradient, and is sampled scaled
/// into cell `cell` of the window's bottom rows (8×8 cells, 8 a row).
fn textures(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    let gradient = program(gl, n, VS, FS_GRADIENT, &["pos"])?;
    let size = gl.glGetUniformLocation(gradient, Text::borrowed("size"))?;
    gl.glUniform2f(size, 8.0, 8.0)?;
    let show = program(gl, n, VS_TEX, FS_SCALED, &["pos", "uv"])?;
    let mut cell = 0;
    let mut shown = |gl: Gl<'_>, n: &mut Names, t: u32| -> R {
        gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
        gl.glUseProgram(show)?;
        gl.glBindTexture(TEXTURE_2D, t)?;
        gl.glViewport(cell % 8 * 8, cell / 8 * 8, 8, 8)?;
        cell += 1;
        textured_quad(gl, n, 0.0, 1.0)
    };
    // 2D images: sized from float or half data, immutable, packed, 10-bit.
    let images: [(u32, u32, u32, bool); 7] = [
        (R16F, RED, FLOAT, false),
        (RG32F, RG, FLOAT, false),
        (RGBA32F, RGBA, FLOAT, false),
        (RGBA16F, RGBA, HALF_FLOAT, false),
        (R11F_G11F_B10F, RGB, FLOAT, false),
        (RGBA32F, RGBA, FLOAT, true),
        (RGB10_A2, RGBA, UNSIGNED_INT_2_10_10_10_REV, true),
    ];
    for (internal, format, ty, immutable) in images {
        let t = texture_2d(gl, n)?;
        if immutable {
            gl.glTexStorage2D(TEXTURE_2D, 1, internal, 8, 8)?;
        } else {
            gl.glTexImage2D(TEXTURE_2D, 0, internal as i32, 8, 8, 0, format, ty, None)?;
        }
        framebuffer(gl, n)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        gl.glViewport(0, 0, 8, 8)?;
        gl.glUseProgram(gradient)?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
        if internal == RGBA16F {
            // Half floats blend: the gradient added again over the top half.
            gl.glEnable(BLEND)?;
            gl.glBlendFunc(ONE, ONE)?;
            draw_positions(gl, n, &quad(-1.0, 0.0, 1.0, 1.0, 0.0), TRIANGLES)?;
            gl.glDisable(BLEND)?;
        }
        shown(gl, n, t)?;
    }
    // A 3D slice and a 2D array layer, drawn into and read as floats.
    for target in [TEXTURE_3D, TEXTURE_2D_ARRAY] {
        let t = n.next();
        gl.glGenTextures(Slice::new(&[t]))?;
        gl.glBindTexture(target, t)?;
        gl.glTexStorage3D(target, 1, if target == TEXTURE_3D { RG32F } else { RGBA16F }, 8, 8, 3)?;
        framebuffer(gl, n)?;
        gl.glFramebufferTextureLayer(FRAMEBUFFER, COLOR_ATTACHMENT0, t, 0, 1)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
        gl.glViewport(0, 0, 8, 8)?;
        gl.glUseProgram(gradient)?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)?;
        let px = floats(&gl.glReadPixels(6, 1, 1, 1, RGBA, FLOAT)?.0);
        marks.extend(px.iter().map(|v| f(*v)));
    }
    // Not renderable: unsized RGBA and RGB floats and RGB32F (unsupported), luminance floats
    // and shared-exponent images (incomplete); unsized RED floats are.
    let others: [(i32, u32, u32); 6] = [
        (RGBA as i32, RGBA, FLOAT),
        (RGB32F as i32, RGB, FLOAT),
        (LUMINANCE as i32, LUMINANCE, FLOAT),
        (RGB9_E5 as i32, RGB, FLOAT),
        (RED as i32, RED, FLOAT),
        (RGBA as i32, RGBA, HALF_FLOAT_OES),
    ];
    for (internal, format, ty) in others {
        let t = texture_2d(gl, n)?;
        gl.glTexImage2D(TEXTURE_2D, 0, internal, 4, 4, 0, format, ty, None)?;
        framebuffer(gl, n)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
        marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    }
    // An immutable 32-bit float texture's attachment state.
    let t = texture_2d(gl, n)?;
    gl.glTexStorage2D(TEXTURE_2D, 1, RG32F, 4, 4)?;
    framebuffer(gl, n)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
    attachment_state(gl, marks)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)
}

/// Blits between float, 8-bit and 10-bit buffers, and the one refused.
fn blits(gl: Gl<'_>, n: &mut Names, p: u32, marks: &mut Vec<u32>) -> R {
    // A 32-bit float buffer, filled, into an 8-bit one (clamped) of the same size.
    let float = framebuffer(gl, n)?;
    renderbuffer(gl, n, RGBA32F, (4, 4), 0)?;
    fill(gl, n, p)?;
    let bytes = framebuffer(gl, n)?;
    renderbuffer(gl, n, RGBA8, (4, 4), 0)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, float)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 0, 0, 4, 4, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, bytes)?;
    for (x, y) in [(0, 0), (2, 0), (3, 3)] {
        let px = gl.glReadPixels(x, y, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
        marks.push(px.get(..2).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
        marks.push(px.get(2..4).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
    }
    // The 8-bit one, magnified with a linear filter into a half-float and a 32-bit float
    // buffer (8×8), read as floats.
    for format in [RGBA16F, RGBA32F] {
        let wide = framebuffer(gl, n)?;
        renderbuffer(gl, n, format, (8, 8), 0)?;
        gl.glBindFramebuffer(READ_FRAMEBUFFER, bytes)?;
        gl.glBlitFramebuffer(0, 0, 4, 4, 0, 0, 8, 8, COLOR_BUFFER_BIT, LINEAR as u32)?;
        marks.push(gl.glGetError()?);
        gl.glBindFramebuffer(READ_FRAMEBUFFER, wide)?;
        for (x, y) in [(3, 1), (5, 6)] {
            let px = floats(&gl.glReadPixels(x, y, 1, 1, RGBA, FLOAT)?.0);
            marks.extend(px.iter().map(|v| f(*v)));
        }
    }
    // The float one, minified with a linear filter, into the window's bottom right corner.
    gl.glBindFramebuffer(READ_FRAMEBUFFER, float)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 56, 16, 64, 24, COLOR_BUFFER_BIT, LINEAR as u32)?;
    marks.push(gl.glGetError()?);
    // The window's bottom left (the textures shown) into a 10-bit buffer, halved, linear.
    let ten = framebuffer(gl, n)?;
    renderbuffer(gl, n, RGB10_A2, (8, 8), 0)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, 0)?;
    gl.glBlitFramebuffer(0, 0, 16, 16, 0, 0, 8, 8, COLOR_BUFFER_BIT, LINEAR as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(READ_FRAMEBUFFER, ten)?;
    for (x, y) in [(1, 1), (6, 2)] {
        word(marks, &gl.glReadPixels(x, y, 1, 1, RGBA, UNSIGNED_INT_2_10_10_10_REV)?.0);
    }
    // Integers into floats: refused.
    let ints = framebuffer(gl, n)?;
    renderbuffer(gl, n, RGBA8UI, (4, 4), 0)?;
    gl.glBindFramebuffer(READ_FRAMEBUFFER, ints)?;
    gl.glBindFramebuffer(DRAW_FRAMEBUFFER, float)?;
    gl.glBlitFramebuffer(0, 0, 4, 4, 0, 0, 4, 4, COLOR_BUFFER_BIT, NEAREST as u32)?;
    marks.push(gl.glGetError()?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)
}

/// Copies from float buffers into float images, and the ones refused.
fn copies(gl: Gl<'_>, n: &mut Names, p: u32, marks: &mut Vec<u32>) -> R {
    let float = framebuffer(gl, n)?;
    renderbuffer(gl, n, RGBA32F, (4, 4), 0)?;
    fill(gl, n, p)?;
    // A new R32F image from it (red only), read back through a framebuffer.
    let red = texture_2d(gl, n)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, R32F, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    // A new RGBA8 one and a half-float one are refused.
    texture_2d(gl, n)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA8, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA16F, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    // A half-float image, a part copied into it.
    let half = texture_2d(gl, n)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA16F as i32, 4, 4, 0, RGBA, HALF_FLOAT, None)?;
    gl.glCopyTexSubImage2D(TEXTURE_2D, 0, 1, 1, 1, 0, 2, 2)?;
    marks.push(gl.glGetError()?);
    // From the R32F buffer a new RGBA32F image is refused (it lacks green, blue and alpha).
    framebuffer(gl, n)?;
    renderbuffer(gl, n, R32F, (4, 4), 0)?;
    texture_2d(gl, n)?;
    gl.glCopyTexImage2D(TEXTURE_2D, 0, RGBA32F, 0, 0, 4, 4, 0)?;
    marks.push(gl.glGetError()?);
    // The copies, read.
    for (t, at) in [(red, [2, 0]), (half, [1, 1]), (half, [2, 2]), (half, [0, 0])] {
        framebuffer(gl, n)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0, TEXTURE_2D, t, 0)?;
        let px = floats(&gl.glReadPixels(at[0], at[1], 1, 1, RGBA, FLOAT)?.0);
        marks.extend(px.iter().map(|v| f(*v)));
    }
    let _ = float;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)
}

/// An 8-bit and a 32-bit float buffer cleared at once (the 8-bit one clamps) and drawn by two
/// outputs.
fn two_buffers(gl: Gl<'_>, n: &mut Names, marks: &mut Vec<u32>) -> R {
    framebuffer(gl, n)?;
    renderbuffer(gl, n, RGBA8, (4, 4), 0)?;
    renderbuffer(gl, n, RGBA32F, (4, 4), 1)?;
    gl.glDrawBuffersEXT(Slice::new(&[COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1]))?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glViewport(0, 0, 4, 4)?;
    gl.glClearColor(-1.0, 2.0, 0.5, 1.0)?;
    gl.glClear(COLOR_BUFFER_BIT)?;
    program(gl, n, VS, FS_TWO, &["pos"])?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 1.0, 0.0), TRIANGLES)?;
    for x in [0, 3] {
        gl.glReadBufferNV(COLOR_ATTACHMENT0)?;
        let px = gl.glReadPixels(x, 0, 1, 1, RGBA, UNSIGNED_BYTE)?.0;
        marks.push(px.get(..2).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
        marks.push(px.get(2..4).map_or(0, |b| u32::from(b[0]) | u32::from(b[1]) << 8));
        gl.glReadBufferNV(COLOR_ATTACHMENT0 + 1)?;
        let px = floats(&gl.glReadPixels(x, 0, 1, 1, RGBA, FLOAT)?.0);
        marks.extend(px.iter().map(|v| f(*v)));
    }
    marks.push(gl.glGetError()?);
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glViewport(0, 0, W, H)
}

/// The float colour buffer program: the extension, each format's renderbuffer, and two
/// buffers at once.
pub fn color_buffer_float(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    let extensions = gl.glGetString(EXTENSIONS)?.unwrap_or_default();
    marks.push(u32::from(extensions.split_whitespace().any(|e| e == "GL_EXT_color_buffer_float")));
    let p = program(gl, n, VS, FS, &["pos"])?;
    renderbuffers(gl, n, p, &mut marks)?;
    two_buffers(gl, n, &mut marks)?;
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

/// The float images program: textures drawn into and shown, blits and copies.
pub fn color_buffer_float_images(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    textures(gl, n, &mut marks)?;
    let p = program(gl, n, VS, FS, &["pos"])?;
    blits(gl, n, p, &mut marks)?;
    copies(gl, n, p, &mut marks)?;
    gl.glClearColor(0.0, 0.0, 0.0, 1.0)?;
    gl.glViewport(0, 0, W, H)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

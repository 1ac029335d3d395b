//! `GL_EXT_texture_border_clamp` / `GL_OES_texture_border_clamp`: a 4×4 texture drawn with
//! coordinates from -0.75 to 1.75, so that the border colour surrounds it: on s, t and both
//! with other wraps on the other axis, nearest, linear and minified through mipmaps; the
//! border as each format shows it (RGB, luminance, luminance-alpha, alpha, red, a float
//! image's unclamped border, a clamped one); projective lookups, a sampler parameter and a
//! vertex-stage lookup; the colour set from integers and read back both ways, and the errors,
//! marked as colours.

use super::multi_draw::mark_all;
use super::textures::{float_data, new_texture};
use super::*;

const CLAMP_TO_BORDER: i32 = 0x812D;
const BORDER_COLOR: u32 = 0x1004;
const REPEAT: i32 = 0x2901;
const MIRRORED_REPEAT: i32 = 0x8370;
const LINEAR_MIPMAP_LINEAR: i32 = 0x2703;
const RED_EXT: u32 = 0x1903;

/// Texel (x, y) of the 4×4 image.
fn texel(x: usize, y: usize) -> [u8; 4] {
    [(x * 80 + 10) as u8, (y * 80 + 10) as u8, ((x + y) * 30 + 20) as u8, (255 - x * 40) as u8]
}

/// Defines the 4×4 image (and its mipmaps) on the bound texture in `format`.
fn image(gl: Gl<'_>, format: u32) -> R {
    let comps = match format {
        RGBA => 4,
        RGB => 3,
        LUMINANCE_ALPHA => 2,
        _ => 1,
    };
    let data: Vec<u8> = (0..16).flat_map(|i| texel(i % 4, i / 4)[..comps].to_vec()).collect();
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    gl.glTexImage2D(TEXTURE_2D, 0, format as i32, 4, 4, 0, format, UNSIGNED_BYTE, Some(Blob::borrowed(&data)))?;
    gl.glGenerateMipmap(TEXTURE_2D)
}

/// Sets the bound texture's wraps.
fn wrap(gl: Gl<'_>, s: i32, t: i32) -> R {
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_S, s)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, t)
}

/// Sets the bound texture's border colour.
fn border(gl: Gl<'_>, c: [f32; 4]) -> R {
    gl.glTexParameterfv(TEXTURE_2D, BORDER_COLOR, Slice::new(&c))
}

/// Draws the bound texture into the 12×12 square at (`x`, `y`), coordinates -0.75 to 1.75.
fn square(gl: Gl<'_>, n: &mut Names, x: i32, y: i32) -> R {
    gl.glViewport(x, y, 12, 12)?;
    textured_quad(gl, n, -0.75, 1.75)
}

/// Projective lookups through a vec3 and a vec4 coordinate whose projections are exactly the
/// coordinate.
const FS_PROJ: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    void main() { vec4 a = texture2DProj(s, vec3(t * 2.0, 2.0)); vec4 b = texture2DProj(s, vec4(t * -0.5, 0.3, -0.5));
                  gl_FragColor = t.x + t.y > 1.0 ? a : b; }";
/// A lookup through a function's sampler parameter.
const FS_PARAM: &str = "precision highp float; uniform sampler2D s; varying vec2 t;
    vec4 look(sampler2D x, vec2 c) { return texture2D(x, c); }
    void main() { gl_FragColor = look(s, t); }";
/// A vertex-stage lookup at each corner, interpolated.
const VS_LOOKUP: &str = "attribute vec4 pos; attribute vec2 uv; uniform sampler2D s; varying vec4 c;
    void main() { c = texture2DLod(s, uv, 0.0); gl_Position = pos; }";
const FS_VARYING: &str = "precision mediump float; varying vec4 c; void main() { gl_FragColor = c; }";

fn border_clamp(gl: Gl<'_>, n: &mut Names) -> R {
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    let mut marks = Vec::new();
    let tex = new_texture(gl, n, NEAREST, NEAREST)?;
    image(gl, RGBA)?;
    border(gl, [0.2, 0.4, 0.6, 0.8])?;
    let mut cell = 0;
    let mut next = || {
        let c = cell;
        cell += 1;
        ((c % 5) * 12, (c / 5) * 12)
    };
    for filter in [NEAREST, LINEAR] {
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, filter)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, filter)?;
        for (s, t) in [
            (CLAMP_TO_BORDER, CLAMP_TO_BORDER),
            (CLAMP_TO_BORDER, CLAMP_TO_EDGE),
            (REPEAT, CLAMP_TO_BORDER),
            (CLAMP_TO_BORDER, MIRRORED_REPEAT),
        ] {
            wrap(gl, s, t)?;
            let (x, y) = next();
            square(gl, n, x, y)?;
        }
    }
    // Minified through mipmaps.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, LINEAR_MIPMAP_LINEAR)?;
    wrap(gl, CLAMP_TO_BORDER, CLAMP_TO_BORDER)?;
    let (x, y) = next();
    gl.glViewport(x, y, 5, 5)?;
    textured_quad(gl, n, -0.75, 1.75)?;
    // The border as each format shows it; out of range, clamped by a normalised image.
    for (format, colour) in [
        (RGB, [0.9, 0.1, 0.5, 0.3]),
        (LUMINANCE, [0.7, 0.1, 0.2, 0.3]),
        (LUMINANCE_ALPHA, [0.3, 0.9, 0.9, 0.6]),
        (ALPHA, [0.9, 0.9, 0.9, 0.4]),
        (RED_EXT, [0.6, 0.5, 0.4, 0.3]),
        (RGBA, [1.5, -0.5, 0.5, 2.0]),
    ] {
        new_texture(gl, n, LINEAR, LINEAR)?;
        image(gl, format)?;
        wrap(gl, CLAMP_TO_BORDER, CLAMP_TO_BORDER)?;
        border(gl, colour)?;
        let (x, y) = next();
        square(gl, n, x, y)?;
    }
    // A float image's border is not clamped: shown scaled by a quarter.
    let p = program(gl, n, VS_TEX, "precision highp float; uniform sampler2D s; varying vec2 t; void main() { gl_FragColor = texture2D(s, t) * 0.25; }", &["pos", "uv"])?;
    let _ = p;
    new_texture(gl, n, NEAREST, NEAREST)?;
    let v: Vec<f32> = (0..64).map(|i| (i % 7) as f32 * 0.5).collect();
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 4, 4, 0, RGBA, FLOAT, Some(Blob::borrowed(&float_data(&v, FLOAT))))?;
    wrap(gl, CLAMP_TO_BORDER, CLAMP_TO_BORDER)?;
    border(gl, [2.0, 3.0, 0.5, 4.0])?;
    let (x, y) = next();
    square(gl, n, x, y)?;
    // Projective lookups, a sampler parameter and a vertex lookup of the first texture.
    gl.glBindTexture(TEXTURE_2D, tex)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, LINEAR)?;
    for (vs, fs) in [(VS_TEX, FS_PROJ), (VS_TEX, FS_PARAM), (VS_LOOKUP, FS_VARYING)] {
        program(gl, n, vs, fs, &["pos", "uv"])?;
        let (x, y) = next();
        square(gl, n, x, y)?;
    }
    // The colour: set from integers, read back as floats and integers.
    gl.glViewport(0, 0, W, H)?;
    gl.glTexParameteriv(TEXTURE_2D, BORDER_COLOR, Slice::new(&[0x7fff_ffff, 0, 0x3fff_ffff, -0x7fff_ffff]))?;
    marks.push(gl.glGetError()?);
    for v in gl.glGetTexParameterfv(TEXTURE_2D, BORDER_COLOR)? {
        marks.push((v * 1000.0 + 2000.0) as u32);
    }
    for v in gl.glGetTexParameteriv(TEXTURE_2D, BORDER_COLOR)? {
        marks.push((v >> 16) as u32);
    }
    marks.push(gl.glGetTexParameteriv(TEXTURE_2D, TEXTURE_WRAP_S)?.first().copied().unwrap_or(-7) as u32);
    // Errors: a scalar border, and an external texture's wrap.
    gl.glTexParameterf(TEXTURE_2D, BORDER_COLOR, 0.5)?;
    marks.push(gl.glGetError()?);
    gl.glBindTexture(0x8D65, n.next())?;
    gl.glTexParameteri(0x8D65, TEXTURE_WRAP_S, CLAMP_TO_BORDER)?;
    marks.push(gl.glGetError()?);
    program(gl, n, VS_TEX, FS_TEX, &["pos", "uv"])?;
    mark_all(gl, &marks)
}

/// Every program of this file, with its tolerance.
pub fn all() -> Vec<Case> {
    vec![Case {
        name: "border_clamp",
        run: border_clamp,
        tol: Tol { max_diff: 2, min_fraction: 0.999 },
        expects_error: false,
    }]
}

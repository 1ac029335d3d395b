//! ES 3.0's texture swizzles (`GL_TEXTURE_SWIZZLE_R`…`_A`): a texel of four distinct
//! channels read through swizzles of channels, zero and one, by every kind of lookup
//! (`texture`, `textureLod`, `texelFetch`, `textureProj`, `textureOffset`, a lookup in a
//! function taking the sampler, a vertex shader's lookup), on 2D textures, cube maps and 2D
//! arrays, with a sampler object bound (the swizzle stays the texture's); a luminance texture
//! swizzled; the queries and the values refused, as colours and marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const SWIZZLE_R: u32 = 0x8E42;
const GREEN: u32 = 0x1904;
const BLUE: u32 = 0x1905;
const RED: u32 = 0x1903;
const ZERO: u32 = 0;
const ONE: u32 = 1;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    uniform highp sampler2D s;
    uniform int mode;
    out vec4 fromVertex;
    void main() {
        gl_Position = pos;
        fromVertex = mode == 5 ? textureLod(s, vec2(0.5), 0.0) : vec4(0.0);
    }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2D s; uniform highp samplerCube c; uniform highp sampler2DArray a;
    uniform highp int mode;
    in vec4 fromVertex;
    out vec4 o;
    vec4 through(highp sampler2D t) { return texture(t, vec2(0.5)); }
    void main() {
        if (mode == 0) o = texture(s, vec2(0.5));
        else if (mode == 1) o = textureLod(s, vec2(0.5), 0.0);
        else if (mode == 2) o = texelFetch(s, ivec2(1, 1), 0);
        else if (mode == 3) o = textureProj(s, vec3(1.0, 1.0, 2.0));
        else if (mode == 4) o = through(s);
        else if (mode == 5) o = fromVertex;
        else if (mode == 6) o = texture(c, vec3(1.0, 0.2, 0.1));
        else if (mode == 7) o = texture(a, vec3(0.5, 0.5, 1.0));
        else o = textureOffset(s, vec2(0.25), ivec2(1, 1));
    }";

/// Every texel of the 2×2 images: four distinct channels.
const TEXEL: [u8; 4] = [200, 120, 40, 160];

/// A new texture of `target` bound on `unit` (0 2D, 1 cube, 2 array), nearest-filtered.
fn new_texture(gl: Gl<'_>, n: &mut Names, target: u32, unit: u32) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glActiveTexture(TEXTURE0 + unit)?;
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(target, t)?;
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(target, TEXTURE_MAG_FILTER, NEAREST)?;
    Ok(t)
}

/// Sets the four swizzles of the texture bound to `target`.
fn swizzle(gl: Gl<'_>, target: u32, sources: [u32; 4]) -> R {
    for (i, s) in sources.into_iter().enumerate() {
        gl.glTexParameteri(target, SWIZZLE_R + i as u32, s as i32)?;
    }
    Ok(())
}

/// The first value of a query's answer, or 1 where there is none.
fn first(v: Vec<i32>) -> u32 {
    v.first().map_or(1, |&x| x as u32)
}

/// The swizzle program.
pub fn swizzles(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let mode = gl.glGetUniformLocation(p, Text::borrowed("mode"))?;
    for (name, unit) in [("s", 0), ("c", 1), ("a", 2)] {
        let l = gl.glGetUniformLocation(p, Text::borrowed(name))?;
        gl.glUniform1i(l, unit)?;
    }
    let mut k = 0;
    let mut cell = |gl: Gl<'_>, n: &mut Names, m: i32| -> R {
        gl.glUniform1i(mode, m)?;
        let (x0, y0) = (-1.0 + (k % 8) as f32 * 0.25, -1.0 + (k / 8) as f32 * 0.25);
        k += 1;
        draw_positions(gl, n, &quad(x0, y0, x0 + 0.25, y0 + 0.25, 0.0), TRIANGLES)
    };
    let mut marks = Vec::new();
    let image = TEXEL.repeat(4);

    let cube = new_texture(gl, n, TEXTURE_CUBE_MAP, 1)?;
    for face in 0..6 {
        let target = TEXTURE_CUBE_MAP_POSITIVE_X + face;
        gl.glTexImage2D(target, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&image)))?;
    }
    new_texture(gl, n, TEXTURE_2D_ARRAY, 2)?;
    let layers = TEXEL.repeat(8);
    gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, RGBA, 2, 2, 2, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&layers)))?;
    let flat = new_texture(gl, n, TEXTURE_2D, 0)?;
    gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, 2, 2, 0, RGBA, UNSIGNED_BYTE, Some(Blob::borrowed(&image)))?;

    // The identity, then three swizzles, each read by every lookup.
    let sources =
        [[RED, GREEN, BLUE, ALPHA], [BLUE, GREEN, RED, ALPHA], [ZERO, ONE, RED, GREEN], [ALPHA, ALPHA, ALPHA, ONE]];
    for s in sources {
        gl.glActiveTexture(TEXTURE0)?;
        swizzle(gl, TEXTURE_2D, s)?;
        gl.glActiveTexture(TEXTURE0 + 1)?;
        swizzle(gl, TEXTURE_CUBE_MAP, [s[3], s[2], s[1], s[0]])?;
        gl.glActiveTexture(TEXTURE0 + 2)?;
        swizzle(gl, TEXTURE_2D_ARRAY, [s[1], s[0], s[3], s[2]])?;
        for m in 0..9 {
            cell(gl, n, m)?;
        }
    }

    // A sampler object bound to unit 0 changes nothing of the swizzle.
    gl.glActiveTexture(TEXTURE0)?;
    let sampler = n.next();
    gl.glGenSamplers(Slice::new(&[sampler]))?;
    gl.glSamplerParameteri(sampler, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glBindSampler(0, sampler)?;
    cell(gl, n, 0)?;
    gl.glBindSampler(0, 0)?;

    // A luminance texture: (L, L, L, 1) before the swizzle.
    new_texture(gl, n, TEXTURE_2D, 0)?;
    gl.glTexImage2D(TEXTURE_2D, 0, LUMINANCE as i32, 1, 1, 0, LUMINANCE, UNSIGNED_BYTE, Some(Blob::borrowed(&[90])))?;
    swizzle(gl, TEXTURE_2D, [ALPHA, ZERO, RED, GREEN])?;
    cell(gl, n, 0)?;

    // The queries, the values refused, and texture 0.
    gl.glBindTexture(TEXTURE_2D, flat)?;
    for i in 0..4 {
        marks.push(first(gl.glGetTexParameteriv(TEXTURE_2D, SWIZZLE_R + i)?));
    }
    for bad in [RGBA as i32, 0x1902, -1, 2] {
        gl.glTexParameteri(TEXTURE_2D, SWIZZLE_R, bad)?;
        marks.push(gl.glGetError()?);
    }
    gl.glTexParameterf(TEXTURE_2D, SWIZZLE_R + 1, 0.5)?;
    marks.push(gl.glGetError()?);
    marks.push(first(gl.glGetTexParameteriv(TEXTURE_2D, SWIZZLE_R + 1)?));
    gl.glBindTexture(TEXTURE_2D, 0)?;
    marks.push(first(gl.glGetTexParameteriv(TEXTURE_2D, SWIZZLE_R + 2)?));
    marks.push(gl.glGetError()?);
    let _ = cube;
    mark_all(gl, &marks)
}

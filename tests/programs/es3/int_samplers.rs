//! GLSL ES 3.00's integer samplers, each image shown as colours: a mipmapped `R8UI` 2D image
//! (the level the nearest mipmap filter picks, repeat and mirrored repeat beyond the edges,
//! offsets, projection, explicit levels, gradients, `texelFetch`, `textureSize`, a swizzle),
//! an `RGBA16I` 3D image, an `RG32UI` 2D array, an `R8I` cube map, an incomplete image (a
//! linear filter), a lookup in the vertex stage, a sampler passed to a function, and the
//! sampler types `glGetActiveUniform` reports.

use super::super::multi_draw::mark_all;
use super::super::*;
use super::language::{screen, VS_SCREEN};

const RED_INTEGER: u32 = 0x8D94;
const RG_INTEGER: u32 = 0x8228;
const RGBA_INTEGER: u32 = 0x8D99;
const R8UI: u32 = 0x8232;
const R8I: u32 = 0x8231;
const RG32UI: u32 = 0x823C;
const RGBA16I: u32 = 0x8D88;
const TEXTURE_3D: u32 = 0x806F;
const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const TEXTURE_WRAP_R: u32 = 0x8072;
const TEXTURE_SWIZZLE_R: u32 = 0x8E42;
const TEXTURE_MAX_LOD: u32 = 0x813B;
const GREEN: i32 = 0x1904;

/// Nearest filters (and a nearest mipmap filter where `mips`) on the texture bound to `target`.
fn nearest(gl: Gl<'_>, target: u32, mips: bool) -> R {
    let min = if mips { NEAREST_MIPMAP_NEAREST } else { NEAREST };
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, min)?;
    gl.glTexParameteri(target, TEXTURE_MAG_FILTER, NEAREST)
}

/// Points program `p`'s sampler `s` at texture unit `u`.
fn unit(gl: Gl<'_>, p: u32, u: i32) -> R {
    let at = gl.glGetUniformLocation(p, Text::borrowed("s"))?;
    gl.glUniform1i(at, u)
}

/// A new texture's name.
fn tex(gl: Gl<'_>, n: &mut Names) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glGenTextures(Slice::new(&[t]))?;
    Ok(t)
}

/// A quad of the screen at cell `i` of an 8×4 grid, filled from the bottom left.
fn cell(gl: Gl<'_>, i: i32) -> R {
    gl.glViewport(i % 8 * W / 8, i / 8 * H / 4, W / 8, H / 4)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

/// A fragment shader showing `expr` (an integer vector lookup on `decl`'s sampler `s`, with
/// `uv` over [-1, 2]) as colours: each component divided by `scale`, negative ones shown as
/// their magnitude in the other half of the range.
fn show(decl: &str, expr: &str, scale: f32) -> String {
    format!(
        "#version 300 es
        precision highp float;
        precision highp int;
        {decl}
        in vec2 uv;
        out vec4 o;
        void main() {{
            vec2 p = uv * 3.0 - 1.0;
            vec4 v = vec4({expr});
            o = vec4(mix(v / {scale:.1}, 0.5 - v / {scale:.1}, lessThan(v, vec4(0.0))).rgb, 1.0);
        }}"
    )
}

/// The integer samplers program.
pub fn int_samplers(gl: Gl<'_>, n: &mut Names) -> R {
    let mut marks = Vec::new();
    // Rows of one-byte texels are not padded.
    gl.glPixelStorei(UNPACK_ALIGNMENT, 1)?;
    // R8UI 2D, 8×8 with levels 4×4, 2×2 and 1×1: texel (x, y) of level l is 10x + 30y + 50l + 1.
    let t2 = tex(gl, n)?;
    gl.glBindTexture(TEXTURE_2D, t2)?;
    for level in 0..4 {
        let size = 8 >> level;
        let data: Vec<u8> =
            (0..size * size).map(|i| ((i % size) * 10 + (i / size) * 30 + 50 * level + 1) as u8).collect();
        gl.glTexImage2D(
            TEXTURE_2D,
            level,
            R8UI as i32,
            size,
            size,
            0,
            RED_INTEGER,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&data)),
        )?;
    }
    nearest(gl, TEXTURE_2D, true)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_WRAP_T, MIRRORED_REPEAT)?;
    let u2 = "uniform highp usampler2D s;";
    let lookups = [
        ("texture(s, p)", 255.0),
        ("texture(s, p * 0.25, 1.5)", 255.0),
        ("textureLod(s, p, 1.0)", 255.0),
        ("textureLod(s, p, 2.6)", 255.0),
        ("textureOffset(s, p, ivec2(2, -1))", 255.0),
        ("textureProj(s, vec3(p, 1.0) * 2.0)", 255.0),
        ("textureProj(s, vec4(p, 5.0, 0.5))", 255.0),
        ("textureGrad(s, p, vec2(0.5, 0.0), vec2(0.0, 0.1))", 255.0),
        ("texelFetch(s, ivec2(uv * 4.0), 1)", 255.0),
        ("uvec4(textureSize(s, 1), textureSize(s, 0))", 16.0),
        ("textureLodOffset(s, p, 0.0, ivec2(-3, 1))", 255.0),
    ];
    for (i, (expr, scale)) in lookups.iter().enumerate() {
        screen(gl, n, VS_SCREEN, &show(u2, expr, *scale))?;
        cell(gl, i as i32)?;
    }
    // A swizzle of integer texels, and a level-of-detail clamp.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_SWIZZLE_R + 1, GREEN + 2)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_SWIZZLE_R + 3, GREEN - 1)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 1.0)?;
    screen(gl, n, VS_SCREEN, &show(u2, "textureLod(s, p, 3.0)", 255.0))?;
    cell(gl, 11)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 1000.0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_SWIZZLE_R + 1, GREEN)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_SWIZZLE_R + 3, RGBA as i32 - 0x1908 + 0x1906)?;

    // RGBA16I 3D, 4×4×2, clamped in r: components ±(100 x, 100 y, 100 z, 7).
    let t3 = tex(gl, n)?;
    gl.glActiveTexture(TEXTURE0 + 1)?;
    gl.glBindTexture(TEXTURE_3D, t3)?;
    let mut data = Vec::new();
    for i in 0..32i16 {
        let (x, y, z) = (i % 4, (i / 4) % 4, i / 16);
        for v in [100 * x + 20, -(100 * y + 30), 100 * z + 40, 7] {
            data.extend(v.to_ne_bytes());
        }
    }
    gl.glTexImage3DOES(TEXTURE_3D, 0, RGBA16I, 4, 4, 2, 0, RGBA_INTEGER, SHORT, Some(Blob::borrowed(&data)))?;
    nearest(gl, TEXTURE_3D, false)?;
    gl.glTexParameteri(TEXTURE_3D, TEXTURE_WRAP_R, CLAMP_TO_EDGE)?;
    let i3 = "uniform highp isampler3D s;";
    for (k, expr) in ["texture(s, vec3(p, p.x * 2.0))", "textureProj(s, vec4(p, 0.7, 1.0))"].iter().enumerate() {
        let p = screen(gl, n, VS_SCREEN, &show(i3, expr, 700.0))?;
        unit(gl, p, 1)?;
        cell(gl, 12 + k as i32)?;
    }

    // RG32UI 2D array, 2×2×3: (layer * 1000 + x * 100, y * 50 + 1).
    let ta = tex(gl, n)?;
    gl.glActiveTexture(TEXTURE0 + 2)?;
    gl.glBindTexture(TEXTURE_2D_ARRAY, ta)?;
    let data: Vec<u8> = (0..12u32)
        .flat_map(|i| [(i / 4) * 1000 + (i % 2) * 100, ((i / 2) % 2) * 50 + 1])
        .flat_map(u32::to_ne_bytes)
        .collect();
    gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, RG32UI, 2, 2, 3, 0, RG_INTEGER, UNSIGNED_INT, Some(Blob::borrowed(&data)))?;
    nearest(gl, TEXTURE_2D_ARRAY, false)?;
    let p =
        screen(gl, n, VS_SCREEN, &show("uniform highp usampler2DArray s;", "texture(s, vec3(p, uv.x * 3.0))", 2100.0))?;
    unit(gl, p, 2)?;
    cell(gl, 14)?;
    // texelFetchOffset (whose offset naga's front end drops) on the array and the 2D image.
    let fetch = "texelFetchOffset(s, ivec3(ivec2(uv * 2.0) - ivec2(1, 0), 2), 0, ivec2(1, 0))";
    let p = screen(gl, n, VS_SCREEN, &show("uniform highp usampler2DArray s;", fetch, 2100.0))?;
    unit(gl, p, 2)?;
    cell(gl, 20)?;
    let fetch = "texelFetchOffset(s, ivec2(uv * 4.0) + ivec2(0, 2), 1, ivec2(-1, -2))";
    screen(gl, n, VS_SCREEN, &show(u2, fetch, 255.0))?;
    cell(gl, 21)?;

    // R8I cube, 2×2 faces: face f's texel (x, y) is (f * 20 + x * 5 + y) negated on odd faces.
    let tc = tex(gl, n)?;
    gl.glActiveTexture(TEXTURE0 + 3)?;
    gl.glBindTexture(TEXTURE_CUBE_MAP, tc)?;
    for f in 0..6i32 {
        let data: Vec<u8> = (0..4)
            .map(|i| ((f * 20 + (i % 2) * 5 + i / 2 + 1) * if f % 2 == 1 { -1 } else { 1 }) as i8 as u8)
            .collect();
        let target = TEXTURE_CUBE_MAP_POSITIVE_X + f as u32;
        gl.glTexImage2D(target, 0, R8I as i32, 2, 2, 0, RED_INTEGER, BYTE, Some(Blob::borrowed(&data)))?;
    }
    nearest(gl, TEXTURE_CUBE_MAP, false)?;
    let cube = "uniform highp isamplerCube s;";
    let p = screen(
        gl,
        n,
        VS_SCREEN,
        &show(cube, "texture(s, vec3(p.x - 0.5, 0.6 - p.y, 0.4)) + ivec4(textureSize(s, 0), 0, 0)", 128.0),
    )?;
    unit(gl, p, 3)?;
    cell(gl, 15)?;

    // Unit 4: an integer image incomplete while a filter is linear (reading (0, 0, 0, 1)),
    // then complete; read through a function's sampler parameter.
    let ti = tex(gl, n)?;
    gl.glActiveTexture(TEXTURE0 + 4)?;
    gl.glBindTexture(TEXTURE_2D, ti)?;
    gl.glTexImage2D(TEXTURE_2D, 0, R8UI as i32, 1, 1, 0, RED_INTEGER, UNSIGNED_BYTE, Some(Blob::borrowed(&[200])))?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    let via = "uniform highp usampler2D s;
        highp uvec4 look(highp usampler2D t, vec2 q) { return texture(t, q) + uvec4(0u, 0u, 10u, 0u); }";
    let p = screen(gl, n, VS_SCREEN, &show(via, "look(s, p)", 255.0))?;
    unit(gl, p, 4)?;
    cell(gl, 16)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    cell(gl, 17)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    cell(gl, 18)?;

    // A vertex stage lookup (level 0): the unsigned 2D image at the quad's corner.
    let vs = "#version 300 es
        layout(location = 0) in vec2 pos;
        uniform highp usampler2D s;
        flat out highp uvec4 v;
        void main() { v = texture(s, pos * 0.4 + 0.5); gl_Position = vec4(pos, 0.0, 1.0); }";
    let fs = "#version 300 es
        precision highp float;
        flat in highp uvec4 v;
        out vec4 o;
        void main() { o = vec4(vec3(v.rgb) / 255.0, 1.0); }";
    let p = screen(gl, n, vs, fs)?;
    unit(gl, p, 0)?;
    cell(gl, 19)?;

    // The sampler types as glGetActiveUniform reports them.
    let typed = [
        (u2, "texture(s, p)"),
        (i3, "texture(s, vec3(p, 0.0))"),
        (cube, "texture(s, vec3(p, 1.0))"),
        ("uniform highp usampler2DArray s;", "texture(s, vec3(p, 0.0))"),
        ("uniform highp isampler2D s;", "texture(s, p)"),
    ];
    for (decl, expr) in typed {
        let p = screen(gl, n, VS_SCREEN, &show(decl, expr, 1.0))?;
        marks.push(gl.glGetActiveUniform(p, 0)?.map_or(0, |u| u.ty));
    }
    gl.glViewport(0, 0, W, H)?;
    gl.glActiveTexture(TEXTURE0)?;
    gl.glPixelStorei(UNPACK_ALIGNMENT, 4)?;
    marks.push(gl.glGetError()?);
    mark_all(gl, &marks)
}

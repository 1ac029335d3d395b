//! ES 3.0's mipmapped depth textures: levels given one by one (`glTexImage2D`,
//! `glTexImage3D`) or allocated at once (`glTexStorage2D`) and written by sub-images, each
//! level its own depth; read by shadow lookups whose level of detail (given, or from
//! gradients) chooses a level (nearest mipmap filters) or weighs two (linear), within the base
//! and max level and the `MIN_LOD`/`MAX_LOD` clamps, on 2D images, 2D arrays and cube maps;
//! read plainly as depth by a `sampler2D`; and a level above 0 as a framebuffer's depth, drawn
//! into and then compared. Colours, and the framebuffer's status as marks.

use super::super::multi_draw::mark_all;
use super::super::*;

const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const DEPTH_COMPONENT: u32 = 0x1902;
const DEPTH_COMPONENT16: u32 = 0x81A5;
const DEPTH_COMPONENT32F: u32 = 0x8CAC;
const COMPARE_MODE: u32 = 0x884C;
const COMPARE_REF_TO_TEXTURE: i32 = 0x884E;
const LEQUAL: i32 = 0x0203;
const TEXTURE_MIN_LOD: u32 = 0x813A;
const TEXTURE_MAX_LOD: u32 = 0x813B;
const TEXTURE_BASE_LEVEL: u32 = 0x813C;
const TEXTURE_MAX_LEVEL: u32 = 0x813D;
const NEAREST_MIPMAP_NEAREST: i32 = 0x2700;
const LINEAR_MIPMAP_NEAREST: i32 = 0x2701;
const NEAREST_MIPMAP_LINEAR: i32 = 0x2702;
const LINEAR_MIPMAP_LINEAR: i32 = 0x2703;
const RGBA8: u32 = 0x8058;
const ALWAYS: u32 = 0x0207;
const NONE: i32 = 0;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2DShadow s; uniform highp sampler2DArrayShadow a;
    uniform highp samplerCubeShadow c; uniform highp sampler2D plain;
    uniform highp int mode; uniform float lod; uniform float ref;
    out vec4 o;
    float look() {
        vec2 uv = vec2(0.3, 0.6);
        // A gradient of 2^lod texels of the 8-texel base level per pixel.
        vec2 g = vec2(exp2(lod) / 8.0, 0.0);
        if (mode == 0) return textureLod(s, vec3(uv, ref), lod);
        if (mode == 1) return textureGrad(s, vec3(uv, ref), g, g.yx);
        if (mode == 2) return textureGrad(a, vec4(uv, 1.0, ref), g, g.yx);
        if (mode == 3) return textureGrad(c, vec4(1.0, 0.2, -0.3, ref), vec3(0.0, g.x * 2.0, 0.0), vec3(0.0, 0.0, g.x * 2.0));
        if (mode == 4) return textureLod(plain, uv, lod).r;
        return textureProjLod(s, vec4(uv * 2.0, ref * 2.0, 2.0), lod);
    }
    void main() { float v = look(); o = vec4(v, fract(v * 4.0), 0.25, 1.0); }";

/// The depth of level `l` of every image here.
fn level_depth(l: i32) -> f32 {
    0.1 + 0.2 * l as f32
}

/// A depth texture of `target` on `unit`, comparing by `LEQUAL`, minified by `min` (magnified
/// nearest).
fn depth_texture(gl: Gl<'_>, n: &mut Names, target: u32, unit: u32, min: i32) -> Result<u32, ClientError> {
    let t = super::shadow::depth_texture(gl, n, target, unit, LEQUAL, NEAREST)?;
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, min)?;
    Ok(t)
}

/// `count` texels of depth `d`.
fn filled(d: f32, count: i32) -> Vec<u8> {
    f32s(&vec![d; count as usize])
}

/// The mipmapped depth program.
pub fn depth_mipmaps(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    for (name, unit) in [("s", 0), ("a", 1), ("c", 2), ("plain", 3)] {
        let l = gl.glGetUniformLocation(p, Text::borrowed(name))?;
        gl.glUniform1i(l, unit)?;
    }
    let [mode, lod, reference] = ["mode", "lod", "ref"].map(|name| gl.glGetUniformLocation(p, Text::borrowed(name)));
    let (mode, lod, reference) = (mode?, lod?, reference?);
    let mut k = 0;
    let mut tile = |gl: Gl<'_>, n: &mut Names, m: i32, l: f32, r: f32| -> R {
        gl.glUniform1i(mode, m)?;
        gl.glUniform1f(lod, l)?;
        gl.glUniform1f(reference, r)?;
        gl.glViewport(k % 16 * 4, k / 16 * 4, 4, 4)?;
        k += 1;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)
    };

    // A 2D image of four levels (8×8 to 1×1) given one by one, a 2D array of three layers
    // by glTexImage3D per level, and a cube map level by level and face by face.
    depth_texture(gl, n, TEXTURE_2D_ARRAY, 1, NEAREST_MIPMAP_NEAREST)?;
    for l in 0..4 {
        let s = 8 >> l;
        let data = filled(level_depth(l), s * s * 3);
        let fmt = DEPTH_COMPONENT32F;
        gl.glTexImage3DOES(TEXTURE_2D_ARRAY, l, fmt, s, s, 3, 0, DEPTH_COMPONENT, FLOAT, Some(Blob::borrowed(&data)))?;
    }
    depth_texture(gl, n, TEXTURE_CUBE_MAP, 2, NEAREST_MIPMAP_NEAREST)?;
    for l in 0..4 {
        let s = 8 >> l;
        let data = filled(level_depth(l), s * s);
        for face in 0..6 {
            let f = DEPTH_COMPONENT32F as i32;
            let target = TEXTURE_CUBE_MAP_POSITIVE_X + face;
            gl.glTexImage2D(target, l, f, s, s, 0, DEPTH_COMPONENT, FLOAT, Some(Blob::borrowed(&data)))?;
        }
    }
    let t = depth_texture(gl, n, TEXTURE_2D, 0, NEAREST_MIPMAP_NEAREST)?;
    for l in 0..4 {
        let s = 8 >> l;
        let data = filled(level_depth(l), s * s);
        let f = DEPTH_COMPONENT32F as i32;
        gl.glTexImage2D(TEXTURE_2D, l, f, s, s, 0, DEPTH_COMPONENT, FLOAT, Some(Blob::borrowed(&data)))?;
    }
    // The same image read plainly.
    gl.glActiveTexture(TEXTURE0 + 3)?;
    gl.glBindTexture(TEXTURE_2D, t)?;

    // Each filter at levels of detail below, at, between and beyond the levels; references
    // between the levels' depths tell which level was read (and mixtures, how much of each).
    let lods = [0.0, 0.4, 0.6, 1.0, 1.5, 2.25, 3.0, 5.0];
    for min in [NEAREST_MIPMAP_NEAREST, LINEAR_MIPMAP_NEAREST, NEAREST_MIPMAP_LINEAR, LINEAR_MIPMAP_LINEAR] {
        for (unit, target) in [(0, TEXTURE_2D), (1, TEXTURE_2D_ARRAY), (2, TEXTURE_CUBE_MAP)] {
            gl.glActiveTexture(TEXTURE0 + unit)?;
            gl.glTexParameteri(target, TEXTURE_MIN_FILTER, min)?;
        }
        for m in [0, 1, 2, 3] {
            for l in lods {
                tile(gl, n, m, l, 0.4)?;
            }
        }
    }
    gl.glActiveTexture(TEXTURE0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST_MIPMAP_NEAREST)?;
    for r in [0.2, 0.6] {
        for l in [0.0, 1.0, 2.0] {
            tile(gl, n, 5, l, r)?;
        }
    }
    // Plain depth reads of each level (comparison off).
    gl.glActiveTexture(TEXTURE0 + 3)?;
    gl.glTexParameteri(TEXTURE_2D, COMPARE_MODE, NONE)?;
    for l in [0.0, 1.0, 2.0, 3.0] {
        tile(gl, n, 4, l, 0.0)?;
    }
    gl.glTexParameteri(TEXTURE_2D, COMPARE_MODE, COMPARE_REF_TO_TEXTURE)?;
    // Base and max level, then the level-of-detail clamps.
    gl.glActiveTexture(TEXTURE0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 1)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 2)?;
    for l in [0.0, 1.0, 3.0] {
        tile(gl, n, 0, l, 0.4)?;
    }
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_BASE_LEVEL, 0)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAX_LEVEL, 1000)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MIN_LOD, 1.6)?;
    gl.glTexParameterf(TEXTURE_2D, TEXTURE_MAX_LOD, 2.2)?;
    for l in [0.0, 2.0, 4.0] {
        tile(gl, n, 0, l, 0.4)?;
    }
    // Within the clamps, two levels weighed.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST_MIPMAP_LINEAR)?;
    for l in [0.0, 1.8, 4.0] {
        tile(gl, n, 0, l, 0.4)?;
    }

    // Immutable storage of four DEPTH_COMPONENT16 levels, written level by level.
    let t16 = depth_texture(gl, n, TEXTURE_2D, 0, NEAREST_MIPMAP_NEAREST)?;
    gl.glTexStorage2D(TEXTURE_2D, 4, DEPTH_COMPONENT16, 8, 8)?;
    for l in 0..4 {
        let s = 8 >> l;
        let v = (f64::from(level_depth(3 - l)) * 65535.0).round() as u16;
        let data: Vec<u8> = vec![v; (s * s) as usize].iter().flat_map(|x| x.to_ne_bytes()).collect();
        gl.glTexSubImage2D(TEXTURE_2D, l, 0, 0, s, s, DEPTH_COMPONENT, UNSIGNED_SHORT, Blob::borrowed(&data))?;
    }
    for l in [0.0, 1.0, 2.0, 3.0] {
        tile(gl, n, 0, l, 0.4)?;
    }

    // Level 1 of the immutable image as a framebuffer's depth: a quad at depth 0.75 drawn into
    // its left half, then every level compared again.
    let (fb, colour) = (n.next(), n.next());
    gl.glGenRenderbuffers(Slice::new(&[colour]))?;
    gl.glBindRenderbuffer(RENDERBUFFER, colour)?;
    gl.glRenderbufferStorage(RENDERBUFFER, RGBA8, 4, 4)?;
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    gl.glFramebufferRenderbuffer(FRAMEBUFFER, COLOR_ATTACHMENT0, RENDERBUFFER, colour)?;
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, t16, 1)?;
    let mut marks = vec![gl.glCheckFramebufferStatus(FRAMEBUFFER)?];
    gl.glViewport(0, 0, 4, 4)?;
    gl.glEnable(DEPTH_TEST)?;
    gl.glDepthFunc(ALWAYS)?;
    let flat = program(
        gl,
        n,
        VS,
        "#version 300 es\nprecision mediump float; out vec4 o; void main() { o = vec4(1.0); }",
        &[],
    )?;
    draw_positions(gl, n, &quad(-1.0, -1.0, 0.0, 1.0, 0.5), TRIANGLES)?;
    gl.glDisable(DEPTH_TEST)?;
    // Level 4, which the image lacks: incomplete.
    gl.glFramebufferTexture2D(FRAMEBUFFER, DEPTH_ATTACHMENT, TEXTURE_2D, t16, 4)?;
    marks.push(gl.glCheckFramebufferStatus(FRAMEBUFFER)?);
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    gl.glDeleteProgram(flat)?;
    gl.glUseProgram(p)?;
    for l in [0.0, 1.0, 2.0] {
        tile(gl, n, 0, l, 0.4)?;
        tile(gl, n, 0, l, 0.6)?;
    }
    marks.push(gl.glGetError()?);
    gl.glViewport(0, 0, W, H)?;
    mark_all(gl, &marks)
}

//! ES 3.0's shadow lookups: a 4×4 depth image of distinct depths compared with a reference by
//! every comparison function, nearest and linear (the comparisons filtered; a cube's only
//! nearest), through
//! `texture`, `textureLod`, `textureGrad`, `textureProj`, `textureOffset` and their
//! combinations on `sampler2DShadow`, `sampler2DArrayShadow` (a 2D array of depth images,
//! specified whole and in part) and `samplerCubeShadow`, the
//! comparison set on the texture or by a sampler object over it, a fixed-point depth image's
//! reference clamped; as colours.

use super::super::*;

const TEXTURE_2D_ARRAY: u32 = 0x8C1A;
const DEPTH_COMPONENT: u32 = 0x1902;
const DEPTH_COMPONENT32F: u32 = 0x8CAC;
const DEPTH_COMPONENT24: u32 = 0x81A6;
const COMPARE_MODE: u32 = 0x884C;
const COMPARE_FUNC: u32 = 0x884D;
const COMPARE_REF_TO_TEXTURE: i32 = 0x884E;
const NEVER: u32 = 0x0200;
const LEQUAL: i32 = 0x0203;
const GREATER: i32 = 0x0204;

const VS: &str = "#version 300 es
    layout(location = 0) in vec4 pos;
    void main() { gl_Position = pos; }";
const FS: &str = "#version 300 es
    precision highp float;
    uniform highp sampler2DShadow s; uniform highp sampler2DArrayShadow a;
    uniform highp samplerCubeShadow c;
    uniform highp int mode; uniform vec4 area; uniform float ref;
    out vec4 o;
    float look(vec2 uv) {
        if (mode == 0) return texture(s, vec3(uv, ref));
        if (mode == 1) return textureLod(s, vec3(uv, ref), 0.0);
        if (mode == 2) return textureGrad(s, vec3(uv, ref), dFdx(uv), dFdy(uv));
        if (mode == 3) return textureProj(s, vec4(uv * 2.0, ref * 2.0, 2.0));
        if (mode == 4) return textureOffset(s, vec3(uv, ref), ivec2(1, 0));
        if (mode == 5) return textureProjLod(s, vec4(uv * 4.0, ref * 4.0, 4.0), 0.0);
        if (mode == 6) return textureLodOffset(s, vec3(uv, ref), 0.0, ivec2(-1, 1));
        if (mode == 7) return texture(s, vec3(uv, ref), 1.0);
        if (mode == 8) return texture(a, vec4(uv, 0.6, ref));
        if (mode == 9) return textureGrad(a, vec4(uv, 0.0, ref), dFdx(uv), dFdy(uv));
        if (mode == 11) return textureLod(s, vec3(uv, ref), 1.0);
        if (mode == 12) return textureGradOffset(a, vec4(uv, 2.0, ref), dFdx(uv), dFdy(uv), ivec2(1, -1));
        return texture(c, vec4(1.0, uv.y * 2.0 - 1.0, uv.x * 2.0 - 1.0, ref));
    }
    void main() {
        o = vec4(look((gl_FragCoord.xy - area.xy) / area.zw), 0.25, 0.0, 1.0);
    }";

/// The uniforms' locations: mode, area, ref.
struct Draw([i32; 3]);

impl Draw {
    /// Draws `mode`'s lookup with reference `r` over the 8×8 tile `k` (8 across).
    fn tile(&self, gl: Gl<'_>, n: &mut Names, k: i32, mode: i32, r: f32) -> R {
        self.area(gl, n, [k % 8 * 8, k / 8 * 8, 8], mode, r)
    }

    /// Draws `mode`'s lookup with reference `r` over the square of `size` pixels at (`x`, `y`).
    fn area(&self, gl: Gl<'_>, n: &mut Names, [x, y, size]: [i32; 3], mode: i32, r: f32) -> R {
        let [m, area, reference] = self.0;
        gl.glUniform1i(m, mode)?;
        gl.glUniform4f(area, x as f32, y as f32, size as f32, size as f32)?;
        gl.glUniform1f(reference, r)?;
        gl.glViewport(x, y, size, size)?;
        draw_positions(gl, n, &quad(-1.0, -1.0, 1.0, 1.0, 0.0), TRIANGLES)
    }
}

/// The depths of the 4×4 image: each texel its own, (x + 4y + 0.5) / 16.
fn depths() -> Vec<f32> {
    (0..16).map(|i| (i as f32 + 0.5) / 16.0).collect()
}

/// A new depth texture of `target` on `unit`, comparing by `func`, filtered by `filter`.
pub(super) fn depth_texture(
    gl: Gl<'_>,
    n: &mut Names,
    target: u32,
    unit: u32,
    func: i32,
    filter: i32,
) -> Result<u32, ClientError> {
    let t = n.next();
    gl.glActiveTexture(TEXTURE0 + unit)?;
    gl.glGenTextures(Slice::new(&[t]))?;
    gl.glBindTexture(target, t)?;
    gl.glTexParameteri(target, TEXTURE_MIN_FILTER, filter)?;
    gl.glTexParameteri(target, TEXTURE_MAG_FILTER, filter)?;
    gl.glTexParameteri(target, TEXTURE_WRAP_S, CLAMP_TO_EDGE)?;
    gl.glTexParameteri(target, TEXTURE_WRAP_T, CLAMP_TO_EDGE)?;
    gl.glTexParameteri(target, COMPARE_MODE, COMPARE_REF_TO_TEXTURE)?;
    gl.glTexParameteri(target, COMPARE_FUNC, func)?;
    Ok(t)
}

/// The shadow program.
pub fn shadow(gl: Gl<'_>, n: &mut Names) -> R {
    let p = program(gl, n, VS, FS, &[])?;
    let mut locs = [0; 3];
    for (l, name) in locs.iter_mut().zip(["mode", "area", "ref"]) {
        *l = gl.glGetUniformLocation(p, Text::borrowed(name))?;
    }
    let draw = Draw(locs);
    for (name, unit) in [("s", 0), ("a", 1), ("c", 2)] {
        let l = gl.glGetUniformLocation(p, Text::borrowed(name))?;
        gl.glUniform1i(l, unit)?;
    }
    let image = f32s(&depths());
    let blob = || Some(Blob::borrowed(&image));

    // The array (layer 1 the image, layer 0 its reverse, layer 2 half of each), and the cube
    // (every face the image).
    depth_texture(gl, n, TEXTURE_2D_ARRAY, 1, LEQUAL, NEAREST)?;
    let mut layers = depths();
    layers.reverse();
    layers.extend(depths());
    layers.extend(depths().iter().map(|d| d * 0.5));
    let layers = f32s(&layers);
    let array = Some(Blob::borrowed(&layers));
    gl.glTexImage3DOES(TEXTURE_2D_ARRAY, 0, DEPTH_COMPONENT32F, 4, 4, 3, 0, DEPTH_COMPONENT, FLOAT, array)?;
    // Layer 2 rewritten in part: its top half the reverse.
    let top = f32s(&depths()[..8]);
    gl.glTexSubImage3DOES(TEXTURE_2D_ARRAY, 0, 0, 2, 2, 4, 2, 1, DEPTH_COMPONENT, FLOAT, Blob::borrowed(&top))?;
    depth_texture(gl, n, TEXTURE_CUBE_MAP, 2, LEQUAL, NEAREST)?;
    for face in 0..6 {
        gl.glTexImage2D(
            TEXTURE_CUBE_MAP_POSITIVE_X + face,
            0,
            DEPTH_COMPONENT32F as i32,
            4,
            4,
            0,
            DEPTH_COMPONENT,
            FLOAT,
            blob(),
        )?;
    }

    // Every lookup, nearest then linear, with references between the depths.
    let t = depth_texture(gl, n, TEXTURE_2D, 0, LEQUAL, NEAREST)?;
    gl.glTexImage2D(TEXTURE_2D, 0, DEPTH_COMPONENT32F as i32, 4, 4, 0, DEPTH_COMPONENT, FLOAT, blob())?;
    let mut k = 0;
    for filter in [NEAREST, LINEAR] {
        for (unit, target) in [(0, TEXTURE_2D), (1, TEXTURE_2D_ARRAY), (2, TEXTURE_CUBE_MAP)] {
            gl.glActiveTexture(TEXTURE0 + unit)?;
            gl.glTexParameteri(target, TEXTURE_MIN_FILTER, filter)?;
            gl.glTexParameteri(target, TEXTURE_MAG_FILTER, filter)?;
        }
        for mode in [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12] {
            // A cube's comparisons are not filtered (the nearest texel's is taken).
            if mode == 10 && filter == LINEAR {
                continue;
            }
            draw.tile(gl, n, k, mode, 0.4)?;
            k += 1;
        }
        draw.tile(gl, n, k, 1, 0.75)?;
        k += 1;
    }

    // Every function, nearest.
    gl.glActiveTexture(TEXTURE0)?;
    gl.glBindTexture(TEXTURE_2D, t)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
    for (i, func) in (NEVER..NEVER + 8).enumerate() {
        gl.glTexParameteri(TEXTURE_2D, COMPARE_FUNC, func as i32)?;
        // 0.53125 is a depth of the image exactly: the functions of equality tell (in 16×16
        // squares, 4×4 pixels a texel).
        draw.area(gl, n, [i as i32 % 4 * 16, 32 + i as i32 / 4 * 16, 16], 1, 0.53125)?;
    }
    gl.glTexParameteri(TEXTURE_2D, COMPARE_FUNC, LEQUAL)?;
    // Magnified (level 0) linearly, minified (level 1) nearest.
    gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, LINEAR)?;
    draw.tile(gl, n, k, 1, 0.4)?;
    draw.tile(gl, n, k + 1, 11, 0.4)?;
    k += 2;

    // A sampler object's comparison over the texture's.
    let sampler = n.next();
    gl.glGenSamplers(Slice::new(&[sampler]))?;
    gl.glSamplerParameteri(sampler, COMPARE_MODE, COMPARE_REF_TO_TEXTURE)?;
    gl.glSamplerParameteri(sampler, COMPARE_FUNC, GREATER)?;
    gl.glSamplerParameteri(sampler, TEXTURE_MIN_FILTER, LINEAR)?;
    gl.glSamplerParameteri(sampler, TEXTURE_MAG_FILTER, LINEAR)?;
    gl.glBindSampler(0, sampler)?;
    draw.tile(gl, n, k, 0, 0.3)?;
    k += 1;
    gl.glBindSampler(0, 0)?;

    // A 24-bit fixed-point depth image: references outside [0, 1] are clamped.
    depth_texture(gl, n, TEXTURE_2D, 0, LEQUAL, NEAREST)?;
    let ints: Vec<u32> = depths().iter().map(|d| (f64::from(*d) * f64::from(u32::MAX)) as u32).collect();
    let ints: Vec<u8> = ints.iter().flat_map(|v| v.to_ne_bytes()).collect();
    gl.glTexImage2D(
        TEXTURE_2D,
        0,
        DEPTH_COMPONENT24 as i32,
        4,
        4,
        0,
        DEPTH_COMPONENT,
        UNSIGNED_INT,
        Some(Blob::borrowed(&ints)),
    )?;
    for r in [-0.5, 1.5, 0.5] {
        draw.tile(gl, n, k, 1, r)?;
        k += 1;
    }
    gl.glViewport(0, 0, W, H)?;
    Ok(())
}

//! The GLSL ES 3.00 language: `in`/`out` with `layout(location)`, integer and unsigned types
//! and operators, the new built-in functions, the overloaded lookups, `gl_VertexID` and
//! `gl_InstanceID`, fragment outputs at locations, and `gl_FragDepth`.

use super::super::*;

/// A full-screen strip (two triangles) of xy positions.
const SCREEN: [f32; 8] = [-1.0, -1.0, 1.0, -1.0, -1.0, 1.0, 1.0, 1.0];

/// A program over the whole screen: `vs`'s input `pos` at location 0.
pub(super) fn screen(gl: Gl<'_>, n: &mut Names, vs: &str, fs: &str) -> Result<u32, ClientError> {
    let p = program(gl, n, vs, fs, &[])?;
    buffer(gl, n, ARRAY_BUFFER, &f32s(&SCREEN))?;
    attrib(gl, 0, 2, FLOAT, false, 0, 0)?;
    Ok(p)
}

/// The vertex stage of [`screen`]'s programs.
pub(super) const VS_SCREEN: &str = "#version 300 es
layout(location = 0) in vec2 pos;
out vec2 uv;
void main() { uv = pos * 0.5 + 0.5; gl_Position = vec4(pos, 0.0, 1.0); }";

/// Inputs placed by `layout(location)` (no binding), a colour and a position crossing to the
/// fragment stage, `buffer` as a name, and an output without a location.
pub fn interface(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "#version 300 es
        layout(location = 3) in vec3 col;
        layout(location = 1) in vec2 pos;
        out vec3 v_col;
        out vec2 buffer;
        void main() { v_col = col; buffer = pos; gl_Position = vec4(pos, 0.0, 1.0); }";
    let fs = "#version 300 es
        precision mediump float;
        in vec3 v_col;
        in vec2 buffer;
        out vec4 frag;
        void main() { frag = vec4(v_col * (0.75 + 0.25 * buffer.x), 1.0); }";
    program(gl, n, vs, fs, &[])?;
    let v: [f32; 15] = [-0.9, -0.9, 1.0, 0.2, 0.1, 0.9, -0.8, 0.1, 1.0, 0.3, -0.2, 0.9, 0.2, 0.4, 1.0];
    buffer(gl, n, ARRAY_BUFFER, &f32s(&v))?;
    attrib(gl, 1, 2, FLOAT, false, 20, 0)?;
    attrib(gl, 3, 3, FLOAT, false, 20, 8)?;
    gl.glDrawArrays(TRIANGLES, 0, 3)
}

/// Integer and unsigned arithmetic, shifts, bitwise operators, `%` and conversions on each
/// pixel's coordinates: exact, so the images agree to the bit.
pub fn integers(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "#version 300 es
        precision highp float;
        precision highp int;
        in vec2 uv;
        out vec4 frag;
        void main() {
            ivec2 p = ivec2(gl_FragCoord.xy);
            uint h = uint(p.x) * 2654435761u + uint(p.y) * 40503u;
            h ^= h >> 13;
            h = (h * 0x5bd1e995u) ^ (h >> 15);
            int m = (p.x * 7 + p.y) % 11;
            int s = ~p.y & 0x3f | (p.x << 2) & 0xc0;
            uvec2 v = uvec2(p) / 3u;
            // Literals of 32 significant bits are their bit patterns: -1, INT_MIN, -2 (in
            // decimal and in octal).
            int w = (int(0xFFFFFFFF) << (p.x & 7)) ^ (0x80000000 >> (p.y & 7)) ^ (4294967294 * p.x)
                ^ (037777777776 * (p.y & 3));
            frag = vec4(float(h & 255u) / 255.0, float(m * 23) / 255.0, float(s ^ ((w & 15) << 4)) / 255.0,
                        float((v.x ^ v.y ^ uint(w >> 26)) & 15u) / 15.0);
        }";
    screen(gl, n, VS_SCREEN, fs)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

/// GLSL ES 3.00's new built-ins, each in a band of the screen.
pub fn builtins(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "#version 300 es
        precision highp float;
        precision highp int;
        in vec2 uv;
        out vec4 frag;
        void main() {
            float x = uv.x * 8.0 - 4.0;
            int band = int(uv.y * 8.0);
            vec4 c = vec4(0.0, 0.0, 0.0, 1.0);
            if (band == 0) {
                c.rgb = vec3(trunc(x) / 8.0 + 0.5, roundEven(x * 1.3) / 12.0 + 0.5, sign(x) * 0.25 + 0.5);
            } else if (band == 1) {
                float whole;
                float f = modf(x * 1.7, whole);
                c.rgb = vec3(f * 0.5 + 0.5, whole / 14.0 + 0.5, fract(x));
            } else if (band == 2) {
                int b = floatBitsToInt(x);
                uint u = floatBitsToUint(uv.x);
                c.rgb = vec3(float((b >> 20) & 255) / 255.0, float((u >> 16) & 255u) / 255.0,
                             intBitsToFloat(floatBitsToInt(uv.x)));
            } else if (band == 3) {
                uint halves = packHalf2x16(vec2(uv.x, 1.0 - uv.x));
                vec2 back = unpackHalf2x16(halves);
                uint n16 = packUnorm2x16(vec2(uv.x, 0.25));
                c.rgb = vec3(back.y, float(n16 & 0xffffu) / 65535.0, unpackSnorm2x16(packSnorm2x16(vec2(x / 4.0))).x * 0.5 + 0.5);
            } else if (band == 4) {
                mat3 o = outerProduct(vec3(uv.x, 0.5, 1.0), vec3(0.5, uv.x, 0.25));
                mat2 t = transpose(mat2(uv.x, 0.2, 0.7, 0.1));
                c.rgb = vec3(o[1][0], o[2][1], t[1][0]);
            } else if (band == 5) {
                mat2 m = mat2(2.0 + uv.x, 1.0, 0.5, 3.0);
                mat2 i = inverse(m);
                c.rgb = vec3(determinant(m) / 10.0, i[0][0], (inverse(mat3(2.0)) * vec3(uv.x)).x);
            } else if (band == 6) {
                ivec3 k = clamp(ivec3(int(x * 10.0), -3, 9), ivec3(-20), ivec3(20));
                uvec2 m = max(uvec2(uint(uv.x * 100.0), 40u), uvec2(50u));
                c.rgb = vec3(float(k.x + 40) / 80.0, float(min(k.y, k.z) + 3) / 12.0, float(m.x) / 100.0);
            } else {
                bvec3 pick = bvec3(x > 0.0, x < -1.0, abs(x) < 2.0);
                c.rgb = mix(vec3(0.1, 0.2, 0.3), vec3(0.9, 0.8, 0.7), pick) * (isnan(x) ? 0.0 : 1.0);
            }
            frag = c;
        }";
    screen(gl, n, VS_SCREEN, fs)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

/// An 8×8 pattern with mipmaps at unit 0 and a cube map at unit 1, read by `texture`,
/// `textureLod`, `texelFetch`, `textureSize`, `textureProj`, `textureOffset` and `textureGrad`,
/// each in a quarter or a band.
pub fn lookups(gl: Gl<'_>, n: &mut Names) -> R {
    texture(gl, n, 8, 8, RGBA, UNSIGNED_BYTE, &pattern(8, 8), NEAREST_MIPMAP_NEAREST, REPEAT)?;
    gl.glGenerateMipmap(TEXTURE_2D)?;
    let cube = n.next();
    gl.glGenTextures(Slice::new(&[cube]))?;
    gl.glActiveTexture(TEXTURE0 + 1)?;
    gl.glBindTexture(TEXTURE_CUBE_MAP, cube)?;
    for face in 0..6u32 {
        let px: Vec<u8> = (0..16).flat_map(|k| [face as u8 * 40, k as u8 * 16, 200 - face as u8 * 30, 255]).collect();
        gl.glTexImage2D(
            TEXTURE_CUBE_MAP_POSITIVE_X + face,
            0,
            RGBA as i32,
            4,
            4,
            0,
            RGBA,
            UNSIGNED_BYTE,
            Some(Blob::borrowed(&px)),
        )?;
    }
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MIN_FILTER, NEAREST)?;
    gl.glTexParameteri(TEXTURE_CUBE_MAP, TEXTURE_MAG_FILTER, NEAREST)?;
    let fs = "#version 300 es
        precision mediump float;
        uniform sampler2D tex;
        uniform samplerCube cube;
        in vec2 uv;
        out vec4 frag;
        void main() {
            ivec2 size = textureSize(tex, 0);
            ivec2 half_size = textureSize(tex, 1);
            vec2 q = uv * 2.0;
            int band = int(uv.y * 4.0);
            if (uv.x < 0.25) {
                frag = texture(tex, q);
            } else if (uv.x < 0.5) {
                frag = textureLod(tex, q, float(band) * 0.9);
            } else if (uv.x < 0.75) {
                frag = texelFetch(tex, ivec2(uv * vec2(size)) % (size >> band), band) * 0.5
                     + vec4(float(half_size.x) / 8.0, float(size.y) / 16.0, 0.0, 0.5);
            } else if (band == 0) {
                frag = textureProj(tex, vec3(q, 2.0));
            } else if (band == 1) {
                frag = textureOffset(tex, q, ivec2(1, -2));
            } else if (band == 2) {
                frag = textureGrad(tex, q, vec2(0.3, 0.0), vec2(0.0, 0.3));
            } else {
                frag = texture(cube, vec3(q.x - 1.0, 1.0, q.y * 4.0 - 7.0));
            }
        }";
    let p = screen(gl, n, VS_SCREEN, fs)?;
    let at = gl.glGetUniformLocation(p, Text::borrowed("cube"))?;
    gl.glUniform1i(at, 1)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

/// `gl_VertexID` picks each vertex's position from a constant array (no inputs at all) in a
/// draw starting at vertex 3; `gl_InstanceID` places each of three instances.
pub fn vertex_ids(gl: Gl<'_>, n: &mut Names) -> R {
    let vs = "#version 300 es
        const vec2 corners[7] = vec2[7](vec2(9.0), vec2(9.0), vec2(9.0),
            vec2(-0.9, -0.9), vec2(-0.3, -0.9), vec2(-0.9, -0.3), vec2(-0.3, -0.2));
        out vec4 c;
        void main() {
            vec2 at = corners[gl_VertexID] + vec2(float(gl_InstanceID) * 0.6, float(gl_InstanceID) * 0.3);
            c = vec4(float(gl_VertexID - 3) / 3.0, float(gl_InstanceID) / 2.0, 0.5, 1.0);
            gl_Position = vec4(at, 0.0, 1.0);
        }";
    let fs = "#version 300 es
        precision mediump float;
        in vec4 c;
        out vec4 frag;
        void main() { frag = c; }";
    program(gl, n, vs, fs, &[])?;
    gl.glDrawArraysInstancedEXT(TRIANGLE_STRIP, 3, 4, 3)
}

/// Two outputs at locations 1 and 0 into two textures of a framebuffer, which are then
/// shown side by side.
pub fn outputs(gl: Gl<'_>, n: &mut Names) -> R {
    let textures = [n.next(), n.next()];
    gl.glGenTextures(Slice::new(&textures))?;
    let fb = n.next();
    gl.glGenFramebuffers(Slice::new(&[fb]))?;
    gl.glBindFramebuffer(FRAMEBUFFER, fb)?;
    for (k, &t) in textures.iter().enumerate() {
        gl.glBindTexture(TEXTURE_2D, t)?;
        gl.glTexImage2D(TEXTURE_2D, 0, RGBA as i32, W / 2, H, 0, RGBA, UNSIGNED_BYTE, None)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MIN_FILTER, NEAREST)?;
        gl.glTexParameteri(TEXTURE_2D, TEXTURE_MAG_FILTER, NEAREST)?;
        gl.glFramebufferTexture2D(FRAMEBUFFER, COLOR_ATTACHMENT0 + k as u32, TEXTURE_2D, t, 0)?;
    }
    gl.glDrawBuffersEXT(Slice::new(&[COLOR_ATTACHMENT0, COLOR_ATTACHMENT0 + 1]))?;
    gl.glViewport(0, H / 2, W / 2, H / 2)?;
    let fs = "#version 300 es
        precision mediump float;
        in vec2 uv;
        layout(location = 1) out vec4 second;
        layout(location = 0) out vec4 first;
        void main() {
            first = vec4(uv, 0.25, 1.0);
            second = vec4(1.0 - uv.y, 0.5, uv.x, 1.0);
        }";
    screen(gl, n, VS_SCREEN, fs)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    // An array of outputs: element i at location i (a lone array without a location at 0).
    gl.glViewport(0, 0, W / 2, H / 2)?;
    let array = "#version 300 es
        precision mediump float;
        in vec2 uv;
        out vec3 o[2];
        void main() {
            o[0] = vec3(uv.y, 0.75, uv.x);
            o[1] = vec3(0.125, uv.x, 1.0 - uv.y);
        }";
    let p = screen(gl, n, VS_SCREEN, array)?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    gl.glBindFramebuffer(FRAMEBUFFER, 0)?;
    let mut marks = Vec::new();
    for name in ["o", "o[0]", "o[1]", "o[2]"] {
        marks.push(gl.glGetFragDataLocation(p, Text::borrowed(name))? as u32 & 0xFFFF);
    }
    let show = "#version 300 es
        precision mediump float;
        uniform sampler2D tex;
        in vec2 uv;
        out vec4 frag;
        // The alpha of a vec3 output is undefined (ES 3.0 §4.2.1): shown as 1.
        void main() { frag = vec4(texture(tex, uv).rgb, 1.0); }";
    screen(gl, n, VS_SCREEN, show)?;
    for (k, &t) in textures.iter().enumerate() {
        gl.glViewport(k as i32 * W / 2, 0, W / 2, H)?;
        gl.glBindTexture(TEXTURE_2D, t)?;
        gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    }
    gl.glViewport(0, 0, W, H)?;
    super::super::multi_draw::mark_all(gl, &marks)
}

/// `gl_FragDepth` (core in GLSL ES 3.00) decides which of two crossing quads is in front.
pub fn frag_depth(gl: Gl<'_>, n: &mut Names) -> R {
    let fs = "#version 300 es
        precision highp float;
        uniform vec4 color;
        uniform float slope;
        in vec2 uv;
        out vec4 frag;
        void main() { gl_FragDepth = 0.5 + slope * (uv.x - 0.5); frag = color; }";
    let p = screen(gl, n, VS_SCREEN, fs)?;
    gl.glEnable(DEPTH_TEST)?;
    let slope = gl.glGetUniformLocation(p, Text::borrowed("slope"))?;
    for (s, c) in [(0.8, [1.0, 0.4, 0.0, 1.0]), (-0.8, [0.0, 0.4, 1.0, 1.0])] {
        gl.glUniform1f(slope, s)?;
        color(gl, p, c)?;
        gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)?;
    }
    gl.glDisable(DEPTH_TEST)
}

//! GLSL ES 3.00 expressions whose operands' shapes decide their meaning: `==` and `!=` of
//! arrays and structures, `%` of a vector and a scalar, shifts and bitwise operators of mixed
//! operands, negated unsigned integers, numeric constructors of booleans of another size,
//! non-square `outerProduct`, the geometric functions of scalars, boolean uniform arrays, and
//! a subtraction of a negative literal, and blocks and bodies that declare a name again (their
//! own scopes). Each lights one cell of a 4×4 grid.

use super::super::*;

const FS: &str = "#version 300 es
    precision highp float;
    precision highp int;
    uniform int k;
    uniform bvec4 flags[2];
    uniform bool bits[3];
    in vec2 uv;
    out vec4 frag;
    struct S { int a; vec2 b; bvec2 c; };
    const float minus = (float(-5.25)) - -5.5;
    const float hoisted = sin(0.5) + 1.0;
    const vec2 twice = vec2(hoisted) * 2.0;
    float same(bvec4 a, bvec4 b) { return a == b ? 1.0 : 0.0; }
    float same1(bool a, bool b) { return a == b ? 1.0 : 0.0; }
    int[3] triple(int x) { return int[3](x, x + 1, x + 2); }
    void main() {
        int cell = int(uv.x * 4.0) + 4 * int(uv.y * 4.0);
        vec4 c = vec4(0.0, 0.0, 0.0, 1.0);
        float fk = float(k);
        if (cell == 0) {
            int x[3] = int[3](k, 2, 3);
            int y[3] = int[3](7, 2, 3);
            vec2 v[2] = vec2[2](vec2(fk, 1.0), vec2(0.5));
            c.rgb = vec3(x == y, x != y, v == vec2[2](vec2(7.0, 1.0), vec2(0.5)));
            c.a = float(x == int[3](7, 2, 4)) * 0.5 + 0.25;
        } else if (cell == 1) {
            int z = 0;
            bool t = triple(z++) == int[3](0, 1, 2);
            mat2 m[2] = mat2[2](mat2(fk), mat2(1.0));
            mat2 n[2] = mat2[2](mat2(7.0), mat2(1.0));
            mat3 o[1] = mat3[1](mat3(fk));
            o[0][2][1] = 0.5;
            c.rgb = vec3(t, float(z) / 2.0, float(m == n) * 0.5 + float(o == mat3[1](mat3(fk))) * 0.25);
        } else if (cell == 2) {
            S s = S(k, vec2(1.0, fk), bvec2(true, k > 3));
            S u = S(7, vec2(1.0, 7.0), bvec2(true));
            S w[2] = S[2](s, u);
            S q[2] = S[2](u, S(7, vec2(1.0, 7.0), bvec2(true, false)));
            c.rgb = vec3(s == u, s != u, w == q) * vec3(1.0, 0.5, 0.75) + vec3(0.0, 0.0, float(w[0] == q[0]) * 0.25);
            S r = S(7, vec2(1.0, 7.0), bvec2(true, false));
            c.a = float(r != u) * 0.5 + 0.5;
        } else if (cell == 3) {
            ivec4 a = ivec4(k, k + 5, 2 * k, 100);
            ivec4 r = a % 3;
            ivec4 q = 50 % a;
            a %= 4;
            c = vec4(r.xyz, 0) / 4.0 + vec4(q.xyz, 0) / 64.0 + vec4(a) / 16.0;
        } else if (cell == 4) {
            uvec3 u = uvec3(k, 9, 200);
            uvec3 r = u % 5u;
            uvec3 q = 1000u % u;
            u %= 6u;
            c.rgb = vec3(r) / 8.0 + vec3(q & 63u) / 256.0 + vec3(u) / 32.0;
        } else if (cell == 5) {
            ivec3 a = ivec3(k, 3 * k, 100 - k);
            ivec3 s = (a << 2) & 0xfc | 1;
            ivec3 t = (a >> 1) ^ k;
            ivec3 b = k & a | (k ^ a);
            a <<= 1;
            a |= k;
            a ^= 3;
            a >>= 1;
            c.rgb = vec3(s & 255) / 255.0 * 0.5 + vec3(t & 31) / 64.0 + vec3(b & 15) / 128.0 + vec3(a & 7) / 64.0;
        } else if (cell == 6) {
            uvec2 u = uvec2(k, 300);
            u = (u << 3u) | uint(k);
            u >>= 2;
            u = u ^ 5u & u;
            c.rg = vec2(u & 255u) / 255.0;
        } else if (cell == 7) {
            bvec3 b = bvec3(k > 3, k > 9, true);
            bool e = k == 7;
            int i = int(b);
            ivec2 i2 = ivec2(e);
            uvec2 u2 = uvec2(b);
            float f = float(bvec2(b.yx));
            mat2 m = mat2(e);
            mat3x4 m34 = mat3x4(b.y);
            c = vec4(float(i), float(i2.y) * 0.5, float(u2.y) + f * 0.5 + m[1][1] * 0.25, 0.5 + m[0][1] + m34[2][2] * 0.25);
        } else if (cell == 8) {
            mat4x3 m = outerProduct(vec3(0.1, 0.2, fk / 10.0), vec4(1.0, 0.5, 0.25, uv.x));
            c = vec4(m[0], m[3].z);
        } else if (cell == 9) {
            mat2x4 a = outerProduct(vec4(0.1, 0.2, 0.3, 0.4), vec2(fk / 8.0, uv.y));
            mat3x2 b = outerProduct(vec2(0.25, fk / 10.0), vec3(0.5, 1.0, uv.x));
            c = vec4(a[1].xw, b[2]);
        } else if (cell == 10) {
            uint u = uint(k);
            u = -u;
            uvec2 w = -uvec2(3u, u);
            c.rgb = vec3(u & 15u, w & 15u) * 16.0 / 255.0;
        } else if (cell == 11) {
            c = vec4(same(flags[0], bvec4(true, false, true, false)), same(flags[k - 6], bvec4(false, false, true, true)),
                     same1(bits[1], false) * 0.5 + float(bits == bool[3](true, false, true)) * 0.25,
                     float(flags[1].z) * 0.75);
        } else if (cell == 12) {
            float x = fk / 10.0 - 0.5;
            c = vec4(dot(x, 2.0) + 0.5, normalize(x) * 0.5 + 0.5, reflect(x, 1.0) + 0.5, faceforward(1.0, x, 1.0));
        } else if (cell == 13) {
            float x = fk / 10.0 - 0.5;
            c = vec4(refract(x, 1.0, 0.5) + 0.5, refract(0.1, -1.0, 2.0), 0.5, 1.0);
        } else if (cell == 14) {
            int d = k - -4;
            c = vec4(minus, float(d) / 16.0 - -0.25, float(-gl_MinProgramTexelOffset >= 8), twice.x / 4.0);
        } else if (cell == 15) {
            int a = k;
            { int a = 2; a++; c.b = float(a) / 8.0; }
            if (k > 0) int a = 42;
            else int a = 43;
            int b = 1;
            while (b < 3) int a = b++;
            c.rg = vec2(float(a) / 16.0, float(b) / 4.0);
        } else {
            c = vec4(uv, 0.5, 1.0);
        }
        frag = c;
    }";

/// Sets the uniforms and draws the grid.
pub fn expressions(gl: Gl<'_>, n: &mut Names) -> R {
    let p = super::language::screen(gl, n, super::language::VS_SCREEN, FS)?;
    let at = |gl: Gl<'_>, name: &str| gl.glGetUniformLocation(p, Text::borrowed(name));
    let k = at(gl, "k")?;
    gl.glUniform1i(k, 7)?;
    let flags = at(gl, "flags")?;
    gl.glUniform4iv(flags, Slice::new(&[1, 0, 1, 0, 0, 0, 1, 1]))?;
    let bits = at(gl, "bits")?;
    gl.glUniform1iv(bits, Slice::new(&[1, 0, 1]))?;
    gl.glDrawArrays(TRIANGLE_STRIP, 0, 4)
}

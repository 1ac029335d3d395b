//! GLSL ES 3.00's shadow samplers (`sampler2DShadow`, `sampler2DArrayShadow`,
//! `samplerCubeShadow`), compared in the shader: naga refuses a depth reference with an
//! explicit level or gradients, and a comparison sampler could not serve the lookups that take
//! them. A shadow sampler binds its depth image as unfilterable floats with a nearest sampler;
//! each lookup becomes a call of a helper that fetches the texel (2D and arrays: the four
//! texels a linear filter covers, each compared, then weighed bilinearly, as GL filters
//! comparisons) and compares it with the reference by the sampler's function, read from the
//! uniform block beside the wrap flags (`NAME__d`: function, filters, clamp, compare mode).
//! The level of detail (implicit from derivatives, given, or from gradients), clamped by
//! `MIN_LOD` and `MAX_LOD`, chooses between the magnification and minification filters and,
//! with a mipmap filter, the level (nearest) or the two levels whose comparisons are weighed
//! (linear), from `NAME__c`: the clamps, the last level past the base, and the mipmap filter
//! (0 none, 1 nearest, 2 linear).

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T};

use crate::glsl::block_members::ctor;
use crate::glsl::types::Ty;

/// The helpers both stages may call (in the common part of the program's sources).
pub(super) const SHADOW_FNS: &str = "float strata_cmp(float r, float d, vec4 k) {
    float q = k.z > 0.5 ? clamp(r, 0.0, 1.0) : r;
    int f = int(k.x + 0.5);
    bool p = f == 2 ? q < d : f == 3 ? q == d : f == 4 ? q <= d : f == 5 ? q > d : f == 6 ? q != d : f == 7 ? q >= d : f == 8;
    return p ? 1.0 : 0.0;
}
float strata_pcf(float r, vec4 k, vec2 w, float a, float b, float c, float d) {
    return mix(mix(strata_cmp(r, a, k), strata_cmp(r, b, k), w.x), mix(strata_cmp(r, c, k), strata_cmp(r, d, k), w.x), w.y);
}
bool strata_linear(vec4 k, float lod) {
    return (lod > 0.0 ? floor(k.y * 0.5) : mod(k.y, 2.0)) > 0.5;
}
vec3 strata_shadow_levels(vec4 c, float lod) {
    float l = clamp(lod, c.x, c.y);
    if (c.w < 0.5 || !(l > 0.0)) { return vec3(0.0, 0.0, 0.0); }
    if (c.w < 1.5) { float n = min(floor(l + 0.5), c.z); return vec3(n, n, 0.0); }
    float a = min(floor(l), c.z);
    return vec3(a, min(a + 1.0, c.z), fract(l));
}
float strata_shadow2(texture2D t, sampler s, vec4 k, vec3 p, vec2 off, bool lin, float lv) {
    vec2 size = vec2(textureSize(sampler2D(t, s), int(lv)));
    vec2 uv = p.xy + off / size;
    float d = textureLod(sampler2D(t, s), uv, lv).r;
    if (k.w < 0.5) { return d; }
    if (!lin) { return strata_cmp(p.z, d, k); }
    vec2 f = uv * size - 0.5;
    vec2 i = floor(f);
    vec2 c = (i + 0.5) / size;
    vec2 e = 1.0 / size;
    return strata_pcf(p.z, k, f - i, textureLod(sampler2D(t, s), c, lv).r,
        textureLod(sampler2D(t, s), c + vec2(e.x, 0.0), lv).r,
        textureLod(sampler2D(t, s), c + vec2(0.0, e.y), lv).r, textureLod(sampler2D(t, s), c + e, lv).r);
}
float strata_shadowL(texture2D t, sampler s, vec4 k, vec4 c, vec3 p, vec2 off, float lod) {
    bool lin = strata_linear(k, clamp(lod, c.x, c.y));
    vec3 l = strata_shadow_levels(c, lod);
    float a = strata_shadow2(t, s, k, p, off, lin, l.x);
    return l.z > 0.0 ? mix(a, strata_shadow2(t, s, k, p, off, lin, l.y), l.z) : a;
}
float strata_shadowLP(texture2D t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, float lod) {
    return strata_shadowL(t, s, k, c, p.xyz / p.w, off, lod);
}
float strata_shadowG(texture2D t, sampler s, vec4 k, vec4 c, vec3 p, vec2 off, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(sampler2D(t, s), 0));
    return strata_shadowL(t, s, k, c, p, off, log2(max(length(dx * size), length(dy * size))));
}
float strata_shadowGP(texture2D t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, vec2 dx, vec2 dy) {
    return strata_shadowG(t, s, k, c, p.xyz / p.w, off, dx, dy);
}
float strata_shadowA2(texture2DArray t, sampler s, vec4 k, vec4 p, vec2 off, bool lin, float lv) {
    ivec3 n = textureSize(sampler2DArray(t, s), int(lv));
    vec2 size = vec2(n.xy);
    float layer = clamp(floor(p.z + 0.5), 0.0, float(n.z - 1));
    vec2 uv = p.xy + off / size;
    float d = textureLod(sampler2DArray(t, s), vec3(uv, layer), lv).r;
    if (k.w < 0.5) { return d; }
    if (!lin) { return strata_cmp(p.w, d, k); }
    vec2 f = uv * size - 0.5;
    vec2 i = floor(f);
    vec2 c = (i + 0.5) / size;
    vec2 e = 1.0 / size;
    return strata_pcf(p.w, k, f - i, textureLod(sampler2DArray(t, s), vec3(c, layer), lv).r,
        textureLod(sampler2DArray(t, s), vec3(c + vec2(e.x, 0.0), layer), lv).r,
        textureLod(sampler2DArray(t, s), vec3(c + vec2(0.0, e.y), layer), lv).r,
        textureLod(sampler2DArray(t, s), vec3(c + e, layer), lv).r);
}
float strata_shadowA(texture2DArray t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, float lod) {
    bool lin = strata_linear(k, clamp(lod, c.x, c.y));
    vec3 l = strata_shadow_levels(c, lod);
    float a = strata_shadowA2(t, s, k, p, off, lin, l.x);
    return l.z > 0.0 ? mix(a, strata_shadowA2(t, s, k, p, off, lin, l.y), l.z) : a;
}
float strata_shadowAG(texture2DArray t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(sampler2DArray(t, s), 0).xy);
    return strata_shadowA(t, s, k, c, p, off, log2(max(length(dx * size), length(dy * size))));
}
vec3 strata_cube_axes(vec3 r, vec3 v) {
    vec3 a = abs(r);
    if (a.x >= a.y && a.x >= a.z) { return r.x > 0.0 ? vec3(-v.z, -v.y, v.x) : vec3(v.z, -v.y, -v.x); }
    if (a.y >= a.z) { return r.y > 0.0 ? vec3(v.x, v.z, v.y) : vec3(v.x, -v.z, -v.y); }
    return r.z > 0.0 ? vec3(v.x, -v.y, v.z) : vec3(-v.x, -v.y, -v.z);
}
vec3 strata_cube_face(vec3 r) {
    vec3 a = abs(r);
    float f = a.x >= a.y && a.x >= a.z ? (r.x > 0.0 ? 0.0 : 1.0) : a.y >= a.z ? (r.y > 0.0 ? 2.0 : 3.0) : (r.z > 0.0 ? 4.0 : 5.0);
    vec3 q = strata_cube_axes(r, r);
    return vec3(0.5 * (q.xy / q.z + 1.0), f);
}
float strata_cube_lod(textureCube t, sampler s, vec3 r, vec3 dx, vec3 dy) {
    vec3 q = strata_cube_axes(r, r);
    vec3 ex = strata_cube_axes(r, dx);
    vec3 ey = strata_cube_axes(r, dy);
    vec2 sx = 0.5 * (ex.xy * q.z - q.xy * ex.z) / (q.z * q.z);
    vec2 sy = 0.5 * (ey.xy * q.z - q.xy * ey.z) / (q.z * q.z);
    return log2(float(textureSize(samplerCube(t, s), 0).x) * max(length(sx), length(sy)));
}
vec3 strata_cube_dir(float face, vec2 st) {
    vec2 q = st * 2.0 - 1.0;
    int f = int(face + 0.5);
    return f == 0 ? vec3(1.0, -q.y, -q.x) : f == 1 ? vec3(-1.0, -q.y, q.x) : f == 2 ? vec3(q.x, 1.0, q.y)
        : f == 3 ? vec3(q.x, -1.0, -q.y) : f == 4 ? vec3(q.x, -q.y, 1.0) : vec3(-q.x, -q.y, -1.0);
}
float strata_cube_cmp(textureCube t, sampler s, vec4 k, float r, float face, vec2 st, float e, float lv) {
    vec2 c = clamp(st, 0.5 * e, 1.0 - 0.5 * e);
    if (c.x != st.x && c.y != st.y) {
        return (strata_cmp(r, textureLod(samplerCube(t, s), strata_cube_dir(face, c), lv).r, k)
            + strata_cmp(r, textureLod(samplerCube(t, s), strata_cube_dir(face, vec2(st.x, c.y)), lv).r, k)
            + strata_cmp(r, textureLod(samplerCube(t, s), strata_cube_dir(face, vec2(c.x, st.y)), lv).r, k)) / 3.0;
    }
    return strata_cmp(r, textureLod(samplerCube(t, s), strata_cube_dir(face, st), lv).r, k);
}
float strata_shadowC2(textureCube t, sampler s, vec4 k, vec4 p, bool lin, float lv) {
    float d = textureLod(samplerCube(t, s), p.xyz, lv).r;
    if (k.w < 0.5) { return d; }
    if (!lin) { return strata_cmp(p.w, d, k); }
    vec3 f = strata_cube_face(p.xyz);
    float size = float(textureSize(samplerCube(t, s), int(lv)).x);
    vec2 g = f.xy * size - 0.5;
    vec2 i = floor(g);
    vec2 c = (i + 0.5) / size;
    float e = 1.0 / size;
    vec2 w = g - i;
    return mix(mix(strata_cube_cmp(t, s, k, p.w, f.z, c, e, lv), strata_cube_cmp(t, s, k, p.w, f.z, c + vec2(e, 0.0), e, lv), w.x),
        mix(strata_cube_cmp(t, s, k, p.w, f.z, c + vec2(0.0, e), e, lv), strata_cube_cmp(t, s, k, p.w, f.z, c + vec2(e, e), e, lv), w.x), w.y);
}
float strata_shadowC(textureCube t, sampler s, vec4 k, vec4 c, vec4 p, float lod) {
    bool lin = strata_linear(k, clamp(lod, c.x, c.y));
    vec3 l = strata_shadow_levels(c, lod);
    float a = strata_shadowC2(t, s, k, p, lin, l.x);
    return l.z > 0.0 ? mix(a, strata_shadowC2(t, s, k, p, lin, l.y), l.z) : a;
}
float strata_shadowCG(textureCube t, sampler s, vec4 k, vec4 c, vec4 p, vec3 dx, vec3 dy) {
    return strata_shadowC(t, s, k, c, p, strata_cube_lod(t, s, p.xyz, dx, dy));
}
";

/// The helpers of implicit levels of detail, which take derivatives: the fragment stage's
/// only (a vertex stage's implicit lookups read level 0).
pub(super) const SHADOW_IMPLICIT_FNS: &str =
    "float strata_shadowI(texture2D t, sampler s, vec4 k, vec4 c, vec3 p, vec2 off, float bias) {
    vec2 size = vec2(textureSize(sampler2D(t, s), 0));
    return strata_shadowL(t, s, k, c, p, off, log2(max(length(dFdx(p.xy * size)), length(dFdy(p.xy * size)))) + bias);
}
float strata_shadowIP(texture2D t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, float bias) {
    return strata_shadowI(t, s, k, c, p.xyz / p.w, off, bias);
}
float strata_shadowAI(texture2DArray t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, float bias) {
    vec2 size = vec2(textureSize(sampler2DArray(t, s), 0).xy);
    return strata_shadowA(t, s, k, c, p, off, log2(max(length(dFdx(p.xy * size)), length(dFdy(p.xy * size)))) + bias);
}
float strata_shadowCI(textureCube t, sampler s, vec4 k, vec4 c, vec4 p, vec2 off, float bias) {
    return strata_shadowC(t, s, k, c, p, strata_cube_lod(t, s, p.xyz, dFdx(p.xyz), dFdy(p.xyz)) + bias);
}
";

/// A variable reference.
fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

/// `name(args…)`.
fn call(name: &str, args: Vec<ast::Expr>) -> ast::Expr {
    ExprData::FunCall(FunIdentifierData::Expr(Box::new(var(name))).into(), args).into()
}

/// A float literal.
fn float(v: f32) -> ast::Expr {
    ExprData::FloatConst(v).into()
}

/// The call a lookup `function` on shadow sampler `sampler` of type `ty` becomes, given the
/// lookup's arguments after the sampler (`args`), in the fragment stage or not (`fragment`):
/// `None` for a function the sampler does not take (left for naga to refuse).
pub(super) fn lookup(function: &str, sampler: &str, ty: Ty, args: &[ast::Expr], fragment: bool) -> Option<ast::Expr> {
    let parts = || {
        [
            var(&format!("{sampler}__t")),
            var(&format!("{sampler}__s")),
            var(&format!("{sampler}__d")),
            var(&format!("{sampler}__c")),
        ]
    };
    let vec2 = |e: &ast::Expr| ctor(T::Vec2, vec![e.clone()]);
    let zero = || vec2(&float(0.0));
    let with = |name: &str, rest: Vec<ast::Expr>| Some(call(name, parts().into_iter().chain(rest).collect()));
    let a = |i: usize| args.get(i).cloned();
    // An implicit lookup: its bias (or none); in a vertex stage, level 0.
    let implicit = |name: &str, lod_name: &str, p: ast::Expr, off: ast::Expr, bias: Option<ast::Expr>| {
        if fragment {
            with(name, vec![p, off, bias.unwrap_or_else(|| float(0.0))])
        } else {
            with(lod_name, vec![p, off, float(0.0)])
        }
    };
    match ty {
        Ty::Sampler2DShadow => match (function, args.len()) {
            ("texture", 1 | 2) => implicit("strata_shadowI", "strata_shadowL", a(0)?, zero(), a(1)),
            ("textureProj", 1 | 2) => implicit("strata_shadowIP", "strata_shadowLP", a(0)?, zero(), a(1)),
            ("textureOffset", 2 | 3) => implicit("strata_shadowI", "strata_shadowL", a(0)?, vec2(&a(1)?), a(2)),
            ("textureProjOffset", 2 | 3) => implicit("strata_shadowIP", "strata_shadowLP", a(0)?, vec2(&a(1)?), a(2)),
            ("textureLod", 2) => with("strata_shadowL", vec![a(0)?, zero(), a(1)?]),
            ("textureLodOffset", 3) => with("strata_shadowL", vec![a(0)?, vec2(&a(2)?), a(1)?]),
            ("textureProjLod", 2) => with("strata_shadowLP", vec![a(0)?, zero(), a(1)?]),
            ("textureProjLodOffset", 3) => with("strata_shadowLP", vec![a(0)?, vec2(&a(2)?), a(1)?]),
            ("textureGrad", 3) => with("strata_shadowG", vec![a(0)?, zero(), a(1)?, a(2)?]),
            ("textureGradOffset", 4) => with("strata_shadowG", vec![a(0)?, vec2(&a(3)?), a(1)?, a(2)?]),
            ("textureProjGrad", 3) => with("strata_shadowGP", vec![a(0)?, zero(), a(1)?, a(2)?]),
            ("textureProjGradOffset", 4) => with("strata_shadowGP", vec![a(0)?, vec2(&a(3)?), a(1)?, a(2)?]),
            _ => None,
        },
        Ty::Sampler2DArrayShadow => match (function, args.len()) {
            ("texture", 1) => implicit("strata_shadowAI", "strata_shadowA", a(0)?, zero(), None),
            ("textureGrad", 3) => with("strata_shadowAG", vec![a(0)?, zero(), a(1)?, a(2)?]),
            ("textureGradOffset", 4) => with("strata_shadowAG", vec![a(0)?, vec2(&a(3)?), a(1)?, a(2)?]),
            _ => None,
        },
        Ty::SamplerCubeShadow => match (function, args.len()) {
            ("texture", 1 | 2) => {
                if fragment {
                    with("strata_shadowCI", vec![a(0)?, zero(), a(1).unwrap_or_else(|| float(0.0))])
                } else {
                    with("strata_shadowC", vec![a(0)?, float(0.0)])
                }
            }
            ("textureGrad", 3) => with("strata_shadowCG", vec![a(0)?, a(1)?, a(2)?]),
            _ => None,
        },
        _ => None,
    }
}

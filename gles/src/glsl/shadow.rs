//! GLSL ES 3.00's shadow samplers (`sampler2DShadow`, `sampler2DArrayShadow`,
//! `samplerCubeShadow`), compared in the shader: naga refuses a depth reference with an
//! explicit level or gradients, and a comparison sampler could not serve the lookups that take
//! them. A shadow sampler binds its depth image as unfilterable floats with a nearest sampler;
//! each lookup becomes a call of a helper that fetches the texel (2D and arrays: the four
//! texels a linear filter covers, each compared, then weighed bilinearly, as GL filters
//! comparisons) and compares it with the reference by the sampler's function, read from the
//! uniform block beside the wrap flags (`NAME__d`: function, filters, clamp, compare mode).
//! The level of detail (implicit from derivatives, given, or from gradients) only chooses
//! between the magnification and minification filters: depth images have one level.

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
float strata_shadowL(texture2D t, sampler s, vec4 k, vec3 p, vec2 off, float lod) {
    vec2 size = vec2(textureSize(sampler2D(t, s), 0));
    vec2 uv = p.xy + off / size;
    float d = textureLod(sampler2D(t, s), uv, 0.0).r;
    if (k.w < 0.5) { return d; }
    if (!strata_linear(k, lod)) { return strata_cmp(p.z, d, k); }
    vec2 f = uv * size - 0.5;
    vec2 i = floor(f);
    vec2 c = (i + 0.5) / size;
    vec2 e = 1.0 / size;
    return strata_pcf(p.z, k, f - i, textureLod(sampler2D(t, s), c, 0.0).r,
        textureLod(sampler2D(t, s), c + vec2(e.x, 0.0), 0.0).r,
        textureLod(sampler2D(t, s), c + vec2(0.0, e.y), 0.0).r, textureLod(sampler2D(t, s), c + e, 0.0).r);
}
float strata_shadowLP(texture2D t, sampler s, vec4 k, vec4 p, vec2 off, float lod) {
    return strata_shadowL(t, s, k, p.xyz / p.w, off, lod);
}
float strata_shadowG(texture2D t, sampler s, vec4 k, vec3 p, vec2 off, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(sampler2D(t, s), 0));
    return strata_shadowL(t, s, k, p, off, log2(max(length(dx * size), length(dy * size))));
}
float strata_shadowGP(texture2D t, sampler s, vec4 k, vec4 p, vec2 off, vec2 dx, vec2 dy) {
    return strata_shadowG(t, s, k, p.xyz / p.w, off, dx, dy);
}
float strata_shadowA(texture2DArray t, sampler s, vec4 k, vec4 p, vec2 off, float lod) {
    ivec3 n = textureSize(sampler2DArray(t, s), 0);
    vec2 size = vec2(n.xy);
    float layer = clamp(floor(p.z + 0.5), 0.0, float(n.z - 1));
    vec2 uv = p.xy + off / size;
    float d = textureLod(sampler2DArray(t, s), vec3(uv, layer), 0.0).r;
    if (k.w < 0.5) { return d; }
    if (!strata_linear(k, lod)) { return strata_cmp(p.w, d, k); }
    vec2 f = uv * size - 0.5;
    vec2 i = floor(f);
    vec2 c = (i + 0.5) / size;
    vec2 e = 1.0 / size;
    return strata_pcf(p.w, k, f - i, textureLod(sampler2DArray(t, s), vec3(c, layer), 0.0).r,
        textureLod(sampler2DArray(t, s), vec3(c + vec2(e.x, 0.0), layer), 0.0).r,
        textureLod(sampler2DArray(t, s), vec3(c + vec2(0.0, e.y), layer), 0.0).r,
        textureLod(sampler2DArray(t, s), vec3(c + e, layer), 0.0).r);
}
float strata_shadowAG(texture2DArray t, sampler s, vec4 k, vec4 p, vec2 off, vec2 dx, vec2 dy) {
    vec2 size = vec2(textureSize(sampler2DArray(t, s), 0).xy);
    return strata_shadowA(t, s, k, p, off, log2(max(length(dx * size), length(dy * size))));
}
float strata_shadowC(textureCube t, sampler s, vec4 k, vec4 p) {
    float d = textureLod(samplerCube(t, s), p.xyz, 0.0).r;
    return k.w < 0.5 ? d : strata_cmp(p.w, d, k);
}
";

/// The helpers of implicit levels of detail, which take derivatives: the fragment stage's
/// only (a vertex stage's implicit lookups read level 0).
pub(super) const SHADOW_IMPLICIT_FNS: &str =
    "float strata_shadowI(texture2D t, sampler s, vec4 k, vec3 p, vec2 off, float bias) {
    vec2 size = vec2(textureSize(sampler2D(t, s), 0));
    return strata_shadowL(t, s, k, p, off, log2(max(length(dFdx(p.xy * size)), length(dFdy(p.xy * size)))) + bias);
}
float strata_shadowIP(texture2D t, sampler s, vec4 k, vec4 p, vec2 off, float bias) {
    return strata_shadowI(t, s, k, p.xyz / p.w, off, bias);
}
float strata_shadowAI(texture2DArray t, sampler s, vec4 k, vec4 p, vec2 off, float bias) {
    vec2 size = vec2(textureSize(sampler2DArray(t, s), 0).xy);
    return strata_shadowA(t, s, k, p, off, log2(max(length(dFdx(p.xy * size)), length(dFdy(p.xy * size)))) + bias);
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
    let parts = || [var(&format!("{sampler}__t")), var(&format!("{sampler}__s")), var(&format!("{sampler}__d"))];
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
            ("texture", 1 | 2) | ("textureGrad", 3) => with("strata_shadowC", vec![a(0)?]),
            _ => None,
        },
        _ => None,
    }
}

//! GLSL ES 3.00's integer samplers (`isampler2D`, `usampler3D`, `isamplerCube`,
//! `usampler2DArray` …). naga samples no integer image, and integer images are never filtered
//! (a linear filter leaves them incomplete), so every lookup becomes a call of a helper that
//! fetches the one texel GL's nearest filter picks: it chooses the level from the level of
//! detail (implicit from derivatives, given, or from gradients; clamped by `MIN_LOD` and
//! `MAX_LOD`; the base level alone without a mipmap filter), wraps the texel's coordinates by
//! the sampler's modes and reads it with `texelFetch`. Cube maps are bound as the 2D array of
//! their faces, the face chosen as GL chooses it. The wraps and levels come from the uniform
//! block beside the sampler (`NAME__d`: wrap s, t and r, levels; `NAME__c`: the level clamps).
//! `texelFetch` and `textureSize` need no helper.

use glsl_lang::ast::{self, ExprData, FunIdentifierData, TypeSpecifierNonArrayData as T};

use crate::glsl::block_members::ctor;
use crate::glsl::types::Ty;

/// The helpers both stages may call, for signed (`$` = `i`) and unsigned (`u`) images.
const TEMPLATE: &str = "$vec4 strata_$2L($texture2D t, sampler s, vec4 k, vec4 c, vec2 p, ivec2 off, float lod) {
    int l = strata_ilevel(k, c, lod);
    ivec2 n = textureSize($sampler2D(t, s), l);
    ivec2 i = ivec2(floor(p * vec2(n))) + off;
    return texelFetch($sampler2D(t, s), ivec2(strata_iwrap(i.x, n.x, k.x), strata_iwrap(i.y, n.y, k.y)), l);
}
$vec4 strata_$2LP($texture2D t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, float lod) {
    return strata_$2L(t, s, k, c, p.xy / p.z, off, lod);
}
$vec4 strata_$2LP($texture2D t, sampler s, vec4 k, vec4 c, vec4 p, ivec2 off, float lod) {
    return strata_$2L(t, s, k, c, p.xy / p.w, off, lod);
}
$vec4 strata_$2G($texture2D t, sampler s, vec4 k, vec4 c, vec2 p, ivec2 off, vec2 dx, vec2 dy) {
    vec2 n = vec2(textureSize($sampler2D(t, s), 0));
    return strata_$2L(t, s, k, c, p, off, log2(max(length(dx * n), length(dy * n))));
}
$vec4 strata_$2GP($texture2D t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, vec2 dx, vec2 dy) {
    return strata_$2G(t, s, k, c, p.xy / p.z, off, dx, dy);
}
$vec4 strata_$2GP($texture2D t, sampler s, vec4 k, vec4 c, vec4 p, ivec2 off, vec2 dx, vec2 dy) {
    return strata_$2G(t, s, k, c, p.xy / p.w, off, dx, dy);
}
$vec4 strata_$3L($texture3D t, sampler s, vec4 k, vec4 c, vec3 p, ivec3 off, float lod) {
    int l = strata_ilevel(k, c, lod);
    ivec3 n = textureSize($sampler3D(t, s), l);
    ivec3 i = ivec3(floor(p * vec3(n))) + off;
    ivec3 w = ivec3(strata_iwrap(i.x, n.x, k.x), strata_iwrap(i.y, n.y, k.y), strata_iwrap(i.z, n.z, k.z));
    return texelFetch($sampler3D(t, s), w, l);
}
$vec4 strata_$3LP($texture3D t, sampler s, vec4 k, vec4 c, vec4 p, ivec3 off, float lod) {
    return strata_$3L(t, s, k, c, p.xyz / p.w, off, lod);
}
$vec4 strata_$3G($texture3D t, sampler s, vec4 k, vec4 c, vec3 p, ivec3 off, vec3 dx, vec3 dy) {
    vec3 n = vec3(textureSize($sampler3D(t, s), 0));
    return strata_$3L(t, s, k, c, p, off, log2(max(length(dx * n), length(dy * n))));
}
$vec4 strata_$3GP($texture3D t, sampler s, vec4 k, vec4 c, vec4 p, ivec3 off, vec3 dx, vec3 dy) {
    return strata_$3G(t, s, k, c, p.xyz / p.w, off, dx, dy);
}
$vec4 strata_$AL($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, float lod) {
    int l = strata_ilevel(k, c, lod);
    ivec3 n = textureSize($sampler2DArray(t, s), l);
    ivec2 i = ivec2(floor(p.xy * vec2(n.xy))) + off;
    int layer = clamp(int(floor(p.z + 0.5)), 0, n.z - 1);
    return texelFetch($sampler2DArray(t, s), ivec3(strata_iwrap(i.x, n.x, k.x), strata_iwrap(i.y, n.y, k.y), layer), l);
}
$vec4 strata_$AG($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, vec2 dx, vec2 dy) {
    vec2 n = vec2(textureSize($sampler2DArray(t, s), 0).xy);
    return strata_$AL(t, s, k, c, p, off, log2(max(length(dx * n), length(dy * n))));
}
$vec4 strata_$CL($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 r, float lod) {
    int l = strata_ilevel(k, c, lod);
    vec3 f = strata_cube_st(r);
    ivec2 n = textureSize($sampler2DArray(t, s), l).xy;
    ivec2 i = clamp(ivec2(floor(f.xy * vec2(n))), ivec2(0), n - 1);
    return texelFetch($sampler2DArray(t, s), ivec3(i, int(f.z)), l);
}
$vec4 strata_$CG($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 r, vec3 dx, vec3 dy) {
    vec2 n = vec2(textureSize($sampler2DArray(t, s), 0).xy);
    vec2 st = strata_cube_st(r).xy;
    vec2 a = (strata_cube_st(r + dx).xy - st) * n;
    vec2 b = (strata_cube_st(r + dy).xy - st) * n;
    return strata_$CL(t, s, k, c, r, log2(max(length(a), length(b))));
}
";

/// The helpers of implicit levels of detail, which take derivatives: the fragment stage's
/// only (a vertex stage's implicit lookups read level 0).
const IMPLICIT_TEMPLATE: &str =
    "$vec4 strata_$2I($texture2D t, sampler s, vec4 k, vec4 c, vec2 p, ivec2 off, float bias) {
    vec2 q = p * vec2(textureSize($sampler2D(t, s), 0));
    return strata_$2L(t, s, k, c, p, off, log2(max(length(dFdx(q)), length(dFdy(q)))) + bias);
}
$vec4 strata_$2IP($texture2D t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, float bias) {
    return strata_$2I(t, s, k, c, p.xy / p.z, off, bias);
}
$vec4 strata_$2IP($texture2D t, sampler s, vec4 k, vec4 c, vec4 p, ivec2 off, float bias) {
    return strata_$2I(t, s, k, c, p.xy / p.w, off, bias);
}
$vec4 strata_$3I($texture3D t, sampler s, vec4 k, vec4 c, vec3 p, ivec3 off, float bias) {
    vec3 q = p * vec3(textureSize($sampler3D(t, s), 0));
    return strata_$3L(t, s, k, c, p, off, log2(max(length(dFdx(q)), length(dFdy(q)))) + bias);
}
$vec4 strata_$3IP($texture3D t, sampler s, vec4 k, vec4 c, vec4 p, ivec3 off, float bias) {
    return strata_$3I(t, s, k, c, p.xyz / p.w, off, bias);
}
$vec4 strata_$AI($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 p, ivec2 off, float bias) {
    vec2 q = p.xy * vec2(textureSize($sampler2DArray(t, s), 0).xy);
    return strata_$AL(t, s, k, c, p, off, log2(max(length(dFdx(q)), length(dFdy(q)))) + bias);
}
$vec4 strata_$CI($texture2DArray t, sampler s, vec4 k, vec4 c, vec3 r, float bias) {
    vec2 q = strata_cube_st(r).xy * vec2(textureSize($sampler2DArray(t, s), 0).xy);
    return strata_$CL(t, s, k, c, r, log2(max(length(dFdx(q)), length(dFdy(q)))) + bias);
}
";

/// What every integer helper uses: the swizzle of integer texels (`swizzle::SWIZZLE_FNS`'s
/// overloads), the wraps (0 repeat, 1 clamp to the edge, 2 mirrored
/// repeat, 3 mirror once then clamp), the level a level of detail picks with a nearest mipmap
/// filter (ES 3.0 §3.8.10), and a cube map's face and coordinates (§3.8.7, table 3.21).
const COMMON: &str = "int strata_iwrap(int c, int n, float m) {
    if (m < 0.5) { int r = c - (c / n) * n; return r < 0 ? r + n : r; }
    if (m < 1.5) { return clamp(c, 0, n - 1); }
    if (m > 2.5) { return clamp(c < 0 ? -1 - c : c, 0, n - 1); }
    int p = c - (c / (2 * n)) * (2 * n);
    p = p < 0 ? p + 2 * n : p;
    return p < n ? p : 2 * n - 1 - p;
}
int strata_ilevel(vec4 k, vec4 c, float lod) {
    float l = clamp(lod, c.x, c.y);
    if (k.w < 0.5 || !(l > 0.5)) { return 0; }
    return min(int(ceil(l + 0.5)) - 1, int(k.w) - 1);
}
int strata_ipick(ivec4 v, float i) {
    return i < 2.5 ? (i < 1.5 ? v.x : v.y) : i < 4.5 ? (i < 3.5 ? v.z : v.w) : (i < 5.5 ? 0 : 1);
}
ivec4 strata_swizzle(ivec4 v, vec4 z) {
    if (z.x == 0.0) { return v; }
    return ivec4(strata_ipick(v, z.x), strata_ipick(v, z.y), strata_ipick(v, z.z), strata_ipick(v, z.w));
}
uint strata_upick(uvec4 v, float i) {
    return i < 2.5 ? (i < 1.5 ? v.x : v.y) : i < 4.5 ? (i < 3.5 ? v.z : v.w) : (i < 5.5 ? 0u : 1u);
}
uvec4 strata_swizzle(uvec4 v, vec4 z) {
    if (z.x == 0.0) { return v; }
    return uvec4(strata_upick(v, z.x), strata_upick(v, z.y), strata_upick(v, z.z), strata_upick(v, z.w));
}
vec3 strata_cube_st(vec3 r) {
    vec3 a = abs(r);
    float sc; float tc; float ma; float face;
    if (a.x >= a.y && a.x >= a.z) {
        face = r.x >= 0.0 ? 0.0 : 1.0; ma = a.x; sc = r.x >= 0.0 ? -r.z : r.z; tc = -r.y;
    } else if (a.y >= a.z) {
        face = r.y >= 0.0 ? 2.0 : 3.0; ma = a.y; sc = r.x; tc = r.y >= 0.0 ? r.z : -r.z;
    } else {
        face = r.z >= 0.0 ? 4.0 : 5.0; ma = a.z; sc = r.z >= 0.0 ? r.x : -r.x; tc = -r.y;
    }
    return vec3((sc / ma + 1.0) * 0.5, (tc / ma + 1.0) * 0.5, face);
}
";

/// The helpers both stages of a program with integer samplers may call.
pub(super) fn helpers() -> String {
    format!("{COMMON}{}{}", TEMPLATE.replace('$', "i"), TEMPLATE.replace('$', "u"))
}

/// The fragment stage's helpers of implicit levels of detail.
pub(super) fn implicit_helpers() -> String {
    format!("{}{}", IMPLICIT_TEMPLATE.replace('$', "i"), IMPLICIT_TEMPLATE.replace('$', "u"))
}

/// The combined sampler type an integer sampler `ty` is read through: its own, but a cube
/// map's faces as a 2D array.
pub(super) fn sampler_type(ty: Ty) -> Option<T> {
    Some(match ty {
        Ty::ISampler2D => T::ISampler2D,
        Ty::ISampler3D => T::ISampler3D,
        Ty::ISamplerCube | Ty::ISampler2DArray => T::ISampler2DArray,
        Ty::USampler2D => T::USampler2D,
        Ty::USampler3D => T::USampler3D,
        Ty::USamplerCube | Ty::USampler2DArray => T::USampler2DArray,
        _ => return None,
    })
}

/// The texture type an integer sampler `ty`'s image binds as.
pub(super) fn texture_type(ty: Ty) -> Option<T> {
    Some(match ty {
        Ty::ISampler2D => T::ITexture2D,
        Ty::ISampler3D => T::ITexture3D,
        Ty::ISamplerCube | Ty::ISampler2DArray => T::ITexture2DArray,
        // glsl-lang has no unsigned texture types: they are named.
        Ty::USampler2D => named("utexture2D"),
        Ty::USampler3D => named("utexture3D"),
        Ty::USamplerCube | Ty::USampler2DArray => named("utexture2DArray"),
        _ => return None,
    })
}

/// Whether an integer lookup `function` that has no helper stays as it is (`texelFetch`,
/// `texelFetchOffset`, `textureSize`), or the compile error for a lookup the sampler does not
/// take.
pub(super) fn kept(function: &str) -> Result<(), String> {
    if crate::glsl::swizzle::returns_texels(function) && !function.starts_with("texelFetch") {
        Err(format!("0: no matching overload of `{function}' for an integer sampler"))
    } else {
        Ok(())
    }
}

/// `call`, a lookup `function` on integer sampler `sampler`, wrapped in the texture's swizzle
/// when it returns texels.
pub(super) fn swizzled(function: &str, sampler: &str, call: ast::Expr) -> ast::Expr {
    if !crate::glsl::swizzle::returns_texels(function) {
        return call;
    }
    let swizzle = FunIdentifierData::Expr(Box::new(var("strata_swizzle"))).into();
    ExprData::FunCall(swizzle, vec![call, var(&format!("{sampler}__z"))]).into()
}

/// A type given by its name.
fn named(name: &str) -> T {
    T::TypeName(ast::TypeNameData(name.into()).into())
}

/// A variable reference.
fn var(name: &str) -> ast::Expr {
    ExprData::Variable(ast::IdentifierData(name.into()).into()).into()
}

/// `name(args…)`.
fn call(name: &str, args: Vec<ast::Expr>) -> ast::Expr {
    ExprData::FunCall(FunIdentifierData::Expr(Box::new(var(name))).into(), args).into()
}

/// The call a lookup `function` on integer sampler `sampler` of type `ty` becomes, given the
/// lookup's arguments after the sampler (`args`, already rewritten), in the fragment stage or
/// not (`fragment`): `None` for a function that needs no helper (`texelFetch`, and
/// `textureSize` but of a cube map) or that the sampler does not take (left for naga to
/// refuse).
pub(super) fn lookup(function: &str, sampler: &str, ty: Ty, args: &[ast::Expr], fragment: bool) -> Option<ast::Expr> {
    let signed = ty.int_sampler()?;
    let g = if signed { "i" } else { "u" };
    let parts = || {
        [
            var(&format!("{sampler}__t")),
            var(&format!("{sampler}__s")),
            var(&format!("{sampler}__d")),
            var(&format!("{sampler}__c")),
        ]
    };
    let with = |name: &str, rest: Vec<ast::Expr>| {
        Some(call(&format!("strata_{g}{name}"), parts().into_iter().chain(rest).collect()))
    };
    let a = |i: usize| args.get(i).cloned();
    let zero = |t: T| ctor(t, vec![ExprData::IntConst(0).into()]);
    let float = |v: f32| -> ast::Expr { ExprData::FloatConst(v).into() };
    let dim = match ty.sampler_base() {
        Ty::Sampler2D => "2",
        Ty::Sampler3D => "3",
        Ty::Sampler2DArray => "A",
        _ => "C",
    };
    if function == "textureSize" {
        // A cube map's faces are a 2D array: its size is the array's width and height.
        return (dim == "C").then(|| {
            let c = ctor(sampler_type(ty)?, vec![var(&format!("{sampler}__t")), var(&format!("{sampler}__s"))]);
            let size = call("textureSize", vec![c, a(0)?]);
            Some(ExprData::Dot(Box::new(size), ast::IdentifierData("xy".into()).into()).into())
        })?;
    }
    let cube = dim == "C";
    let off_ty = if dim == "3" { T::IVec3 } else { T::IVec2 };
    // An implicit lookup: the fragment stage's helper with its bias, else level 0's.
    let implicit = |p: ast::Expr, suffix: &str, off: Option<ast::Expr>, bias: Option<ast::Expr>| {
        let mut rest = vec![p];
        if dim != "C" {
            rest.push(off.unwrap_or_else(|| zero(off_ty.clone())));
        }
        if fragment {
            rest.push(bias.unwrap_or_else(|| float(0.0)));
            with(&format!("{dim}I{suffix}"), rest)
        } else {
            rest.push(float(0.0));
            with(&format!("{dim}L{suffix}"), rest)
        }
    };
    // Projective forms (2D: a vec3 or vec4 coordinate, told apart by overloads; 3D: vec4).
    let projective = matches!(dim, "2" | "3");
    match (function, args.len()) {
        ("texture", 1 | 2) => implicit(a(0)?, "", None, a(1)),
        ("textureOffset", 2 | 3) if !cube => implicit(a(0)?, "", a(1), a(2)),
        ("textureProj", 1 | 2) if projective => implicit(a(0)?, "P", None, a(1)),
        ("textureProjOffset", 2 | 3) if projective => implicit(a(0)?, "P", a(1), a(2)),
        ("textureLod", 2) if cube => with("CL", vec![a(0)?, a(1)?]),
        ("textureLod", 2) => with(&format!("{dim}L"), vec![a(0)?, zero(off_ty), a(1)?]),
        ("textureLodOffset", 3) if !cube => with(&format!("{dim}L"), vec![a(0)?, a(2)?, a(1)?]),
        ("textureProjLod", 2) if projective => with(&format!("{dim}LP"), vec![a(0)?, zero(off_ty), a(1)?]),
        ("textureProjLodOffset", 3) if projective => with(&format!("{dim}LP"), vec![a(0)?, a(2)?, a(1)?]),
        ("textureGrad", 3) if cube => with("CG", vec![a(0)?, a(1)?, a(2)?]),
        ("textureGrad", 3) => with(&format!("{dim}G"), vec![a(0)?, zero(off_ty), a(1)?, a(2)?]),
        ("textureGradOffset", 4) if !cube => with(&format!("{dim}G"), vec![a(0)?, a(3)?, a(1)?, a(2)?]),
        ("textureProjGrad", 3) if projective => with(&format!("{dim}GP"), vec![a(0)?, zero(off_ty), a(1)?, a(2)?]),
        ("textureProjGradOffset", 4) if projective => with(&format!("{dim}GP"), vec![a(0)?, a(3)?, a(1)?, a(2)?]),
        _ => None,
    }
}

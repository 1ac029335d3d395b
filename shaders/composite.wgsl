// The compositor's pass (§4.5–4.6), drawn over rectangles ("cells") of the output that every
// surface of the pass covers entirely: per fragment the nearest of the pass's surfaces (and of
// an earlier pass's result), lit in a group's last pass, then laid on the background or blended
// over what lies beneath.
//
// A naga_oil module: everything a pass does, as functions. Each pass shape's shader is composed
// at run time (server/src/compositor/shader.rs): Rust writes, from the pass's description of
// its inputs (server/src/compositor/inputs.rs), the bindings and a short `fs` that imports this
// module and calls `first` or `intermediate`, then `nearer` once per further surface (each
// surface's textures passed as arguments: WGSL cannot index textures without binding arrays),
// then `finish`. The shape's flags are shader defs (set when the pass has the property):
//   SELECT        several candidates: the depth select runs (otherwise one surface, fetched once),
//                 comparing eye-space depths (fn eye);
//   INTERMEDIATE  an earlier pass's result is a candidate;
//   LAST          the group's last pass, which writes the output (else an intermediate);
//   LIT           uniform Phong lighting; FROM_DEPTH: normals reconstructed from depth;
//   DEPTH         the surfaces' depth images are bound;
//   BASE          the cell's farthest group: laid on the background in the shader, no blending;
//   COPY          the 2D compositor: the texel as it is (no opacity);
//   MAP           the lighting factor is read from a light map (one surface, per-surface normal);
//   FACTOR        the pass that draws a light map;
//   SCALED        some surface's source region is scaled to its rectangle (integer location
//                 and bilinear filtering; shapes without it fetch each pixel's own texel);
// and SURFACES is the number of surfaces (the length of a draw's array of `Surf`).

#define_import_path strata::composite

// The lighting and the background, at the start of the uniform buffer.
struct Params {
    light_pos: vec4<f32>,
    // w: the depth-normal scale.
    light_color: vec4<f32>,
    view_pos: vec4<f32>,
    // ambient, shininess, output width, output height.
    misc: vec4<f32>,
    // Premultiplied.
    background: vec4<f32>,
};
// rect: x, y (output pixels, from the top), width, height: where the surface shows; src: the
// part of its image shown there, x, y (from the image's top), width, height; normal: xyz unit
// (or zero), w > 0.5 when the surface has a depth image; proj: its declared projection (kind:
// 0 orthographic, 1 perspective; near; far; reversed: 0 or 1), [0, 0, 1, 0] when undeclared;
// img: the image's width and height, the opacity, unused.
struct Surf { rect: vec4<i32>, src: vec4<i32>, normal: vec4<f32>, proj: vec4<f32>, img: vec4<f32>, };
// A draw's uniform block. origin.xy: the render target's origin in output pixels; origin.zw:
// the intermediate's.
struct Draw { origin: vec4<i32>, surf: array<Surf, #{SURFACES}>, };

// The nearest candidate so far: eye depth, colour (straight alpha), normal.
struct Best { d: f32, c: vec4<f32>, n: vec3<f32>, };

#ifdef LAST
// The output (or the light map).
struct Out { @location(0) color: vec4<f32>, };
#else
// An intermediate: the selected colour, and its eye depth and normal.
struct Out { @location(0) color: vec4<f32>, @location(1) geom: vec4<f32>, };
#endif

// One cell per instance: corner `v` of its rectangle `r` in clip space (x0, y0, x1, y1), drawn
// as a strip.
fn corner(v: u32, r: vec4<f32>) -> vec4<f32> {
    return vec4<f32>(select(r.x, r.z, (v & 1u) != 0u), select(r.y, r.w, (v & 2u) != 0u), 0.0, 1.0);
}

// The output pixel of fragment position `pos` in a target whose origin is `origin.xy`.
fn pixel(pos: vec4<f32>, origin: vec4<i32>) -> vec2<i32> {
    return vec2<i32>(floor(pos.xy)) + origin.xy;
}

// `a / b` rounded down (b > 0); WGSL's `/` rounds towards zero.
fn fdiv(a: i32, b: i32) -> i32 {
    let q = a / b;
    return select(q, q - 1, a % b != 0 && a < 0);
}

// The image row of row `y` counted from the image's top: the images are in GL row order,
// bottom row first.
fn row(s: Surf, y: i32) -> i32 {
    return i32(s.img.y) - 1 - y;
}

// Where output pixel `px` lies in surface `s`'s images: the source texel whose area holds the
// pixel's centre, the rectangle mapped onto the source region. In integers, so that it is
// exact: x = src.x + floor((2 (px - rect.x) + 1) src.w / (2 rect.w)); with equal sizes, the
// pixel's own texel.
fn at(s: Surf, px: vec2<i32>) -> vec2<i32> {
    let l = px - s.rect.xy;
    var t = s.src.xy + l;
#ifdef SCALED
    // At scale 1 the formula gives `l` itself; only shapes with a scaled surface carry it.
    if (any(s.src.zw != s.rect.zw)) {
        t = s.src.xy + vec2<i32>(fdiv((2 * l.x + 1) * s.src.z, 2 * s.rect.z), fdiv((2 * l.y + 1) * s.src.w, 2 * s.rect.w));
    }
#endif
    return vec2<i32>(t.x, row(s, t.y));
}

// Surface `s`'s colour at output pixel `px` (`sp` in its images, `at(s, px)`): its texel
// where the source region has the rectangle's size; scaled (SCALED shapes only), the bilinear
// blend of the four source texels around the pixel's centre (texel centres at half-integers,
// clamped to the source region), as a filtering sampler would give it. The weights come from
// integers too: u = src.x + ((2 l + 1) src.w - rect.w) / (2 rect.w) in texel-centre units.
fn colour(s: Surf, px: vec2<i32>, sp: vec2<i32>, color: texture_2d<f32>) -> vec4<f32> {
#ifdef SCALED
    if (any(s.src.zw != s.rect.zw)) {
        let l = px - s.rect.xy;
        let n = (2 * l + vec2<i32>(1)) * s.src.zw - s.rect.zw;
        let d = 2 * s.rect.zw;
        let t0 = vec2<i32>(fdiv(n.x, d.x), fdiv(n.y, d.y));
        let f = vec2<f32>(n - t0 * d) / vec2<f32>(d);
        let lo = s.src.xy;
        let hi = s.src.xy + s.src.zw - vec2<i32>(1);
        let a = clamp(s.src.xy + t0, lo, hi);
        let b = clamp(s.src.xy + t0 + vec2<i32>(1), lo, hi);
        let c00 = textureLoad(color, vec2<i32>(a.x, row(s, a.y)), 0);
        let c10 = textureLoad(color, vec2<i32>(b.x, row(s, a.y)), 0);
        let c01 = textureLoad(color, vec2<i32>(a.x, row(s, b.y)), 0);
        let c11 = textureLoad(color, vec2<i32>(b.x, row(s, b.y)), 0);
        return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
    }
#endif
    return textureLoad(color, sp, 0);
}

#ifdef DEPTH
// A depth texel as the compositor reads it, under projection `p` (a Surf's proj): NaN as the far
// plane's window depth (1, or 0 when reversed), then clamped to [0, 1] (so -inf reads 0 and
// +inf 1). NaN is found by its bits: WGSL lets a compiler assume floats are never NaN.
fn texel(v: f32, p: vec4<f32>) -> f32 {
    let nan = (bitcast<u32>(v) & 0x7fffffffu) > 0x7f800000u;
    return clamp(select(v, select(1.0, 0.0, p.w > 0.5), nan), 0.0, 1.0);
}
#endif

#ifdef SELECT
// The eye-space depth of window depth `d` under projection `p` (a Surf's proj), by which the
// select compares surfaces whose projections differ: `d` read as a texel (NaN at the far
// plane, clamped to [0, 1]) and flipped when reversed, then orthographic n + d (f - n),
// perspective n f / (f - d (f - n)), or n / (1 - d) with f infinite. Undeclared
// ([0, 0, 1, 0]) gives back `d` itself, exactly: 0 + d (1 - 0).
fn eye(d_in: f32, p: vec4<f32>) -> f32 {
    let d = texel(d_in, p);
    // Far at +inf (tested by its bits, so that no float optimisation can assume it away); the
    // far plane itself is +inf, not left to a division by zero.
    let infinite = bitcast<u32>(p.z) == 0x7f800000u;
    if (p.w > 0.5) {
        // Reversed: from d itself, not from 1 - d, which would throw away the precision that
        // float depth has near 0 (the far plane).
        if (p.x < 0.5) { return p.z - d * (p.z - p.y); }
        if (infinite) { return select(p.y / d, p.z, d <= 0.0); }
        return p.y * p.z / (p.y + d * (p.z - p.y));
    }
    if (p.x < 0.5) { return p.y + d * (p.z - p.y); }
    if (infinite) { return select(p.y / (1.0 - d), p.z, d >= 1.0); }
    return p.y * p.z / (p.z - d * (p.z - p.y));
}

// Surface `s`'s eye depth at `sp` (in its images); without a depth image it lies at its far
// plane (1 undeclared).
fn eye_at(s: Surf, sp: vec2<i32>, depth: texture_depth_2d) -> f32 {
    var d: f32 = s.proj.z;
    if (s.normal.w > 0.5) { d = eye(textureLoad(depth, sp, 0), s.proj); }
    return d;
}
#endif

#ifdef FROM_DEPTH
// The normal at `p` of `depth` (read as texels under projection `pr`; its size `size`) by
// central differences (one-sided at edges), its slopes scaled by `scale`.
fn dn(depth: texture_depth_2d, pr: vec4<f32>, scale: f32, p: vec2<i32>, size: vec2<i32>) -> vec3<f32> {
    let x0 = max(p.x - 1, 0); let x1 = min(p.x + 1, size.x - 1);
    let y0 = max(p.y - 1, 0); let y1 = min(p.y + 1, size.y - 1);
    var dzdx = 0.0; var dzdy = 0.0;
    if (x1 > x0) { dzdx = (texel(textureLoad(depth, vec2<i32>(x1, p.y), 0), pr) - texel(textureLoad(depth, vec2<i32>(x0, p.y), 0), pr)) / f32(x1 - x0); }
    if (y1 > y0) { dzdy = (texel(textureLoad(depth, vec2<i32>(p.x, y1), 0), pr) - texel(textureLoad(depth, vec2<i32>(p.x, y0), 0), pr)) / f32(y1 - y0); }
    return normalize(vec3<f32>(-dzdx * scale, -dzdy * scale, 1.0));
}
#endif

#ifdef LIT
// The Phong factor ambient + diffuse + specular of a fragment on the plane z = 0 with normal `n`
// (a unit vector, or zero: no direction, ambient only). Shininess 0 makes specular 1, as
// x^0 = 1 for every x (WGSL leaves pow(0, 0) undefined).
fn factor(prm: Params, n: vec3<f32>, frag_px: vec2<f32>) -> f32 {
    if (all(n == vec3<f32>(0.0))) { return prm.misc.x; }
    let frag = vec3<f32>(frag_px.x / prm.misc.z * 2.0 - 1.0, 1.0 - frag_px.y / prm.misc.w * 2.0, 0.0);
    let ld = normalize(prm.light_pos.xyz - frag);
    let vd = normalize(prm.view_pos.xyz - frag);
    let diffuse = max(dot(n, ld), 0.0);
    let r = reflect(-ld, n);
    let base = max(dot(vd, r), 0.0);
    var specular = 1.0;
    if (prm.misc.y != 0.0) { specular = pow(base, prm.misc.y); }
    return prm.misc.x + diffuse + specular;
}
// Lit colour: factor · light colour · colour.
fn light(prm: Params, c: vec3<f32>, f: f32) -> vec3<f32> {
    return clamp(c * f * prm.light_color.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
}
#endif

#ifdef FACTOR
// A light map's texel at `px`: the factor for the normal of the draw's surface `s`.
fn light_map(prm: Params, s: Surf, px: vec2<i32>) -> Out {
    return Out(vec4<f32>(factor(prm, s.normal.xyz, vec2<f32>(px) + 0.5), 0.0, 0.0, 0.0));
}
#else
// Surface `s` taken as the candidate at output pixel `px` (`sp` in its images) with eye depth
// `d`: its colour, its alpha times its opacity, and its normal (from its depth, or its own).
fn take(
    prm: Params,
    s: Surf,
    px: vec2<i32>,
    sp: vec2<i32>,
    d: f32,
    color: texture_2d<f32>,
#ifdef DEPTH
    depth: texture_depth_2d,
#endif
) -> Best {
    var b: Best;
    b.d = d;
    b.c = colour(s, px, sp, color);
#ifndef COPY
    b.c.a = b.c.a * s.img.z;
#endif
#ifdef FROM_DEPTH
    b.n = vec3<f32>(0.0, 0.0, 1.0);
    if (s.normal.w > 0.5) { b.n = dn(depth, s.proj, prm.light_color.w, sp, vec2<i32>(s.img.xy)); }
#else
    b.n = s.normal.xyz;
#endif
    return b;
}

// The pass's first candidate, surface `s` at output pixel `px`, taken unconditionally (so no
// "far" initial value bounds eye depth); without the select, the pass's one surface.
fn first(
    prm: Params,
    s: Surf,
    px: vec2<i32>,
    color: texture_2d<f32>,
#ifdef DEPTH
    depth: texture_depth_2d,
#endif
) -> Best {
    let sp = at(s, px);
#ifdef SELECT
    return take(prm, s, px, sp, eye_at(s, sp, depth), color, depth);
#else ifdef DEPTH
    return take(prm, s, px, sp, 0.0, color, depth);
#else
    return take(prm, s, px, sp, 0.0, color);
#endif
}
#endif

#ifdef INTERMEDIATE
// An earlier pass's result at output pixel `px` as the first candidate: its colour, eye depth
// and normal; the intermediate's origin is `origin.zw`.
fn intermediate(origin: vec4<i32>, px: vec2<i32>, icolor: texture_2d<f32>, igeom: texture_2d<f32>) -> Best {
    let ip = px - origin.zw;
    let g = textureLoad(igeom, ip, 0);
    return Best(g.x, textureLoad(icolor, ip, 0), g.yzw);
}
#endif

#ifdef SELECT
// The nearer of candidate `b` and surface `s` at output pixel `px`; `<=`: on equal depth the
// later surface in stacking order wins.
fn nearer(
    b: Best,
    prm: Params,
    s: Surf,
    px: vec2<i32>,
    color: texture_2d<f32>,
    depth: texture_depth_2d,
) -> Best {
    let sp = at(s, px);
    let d = eye_at(s, sp, depth);
    if (d <= b.d) { return take(prm, s, px, sp, d, color, depth); }
    return b;
}
#endif

#ifndef FACTOR
// What the pass writes at output pixel `px` for the selected candidate `b`: an intermediate
// (colour, eye depth and normal), or the output's colour: as it is (the 2D copy), else lit
// (the factor from the light map `lmap`, or computed) and premultiplied, on the background
// where the pass is the cell's farthest group.
fn finish(
    b: Best,
    prm: Params,
    px: vec2<i32>,
#ifdef MAP
    lmap: texture_2d<f32>,
#endif
) -> Out {
#ifndef LAST
    return Out(b.c, vec4<f32>(b.d, b.n));
#else ifdef COPY
    return Out(b.c);
#else
#ifdef MAP
    let rgb = light(prm, b.c.rgb, textureLoad(lmap, px, 0).x);
#else ifdef LIT
    let rgb = light(prm, b.c.rgb, factor(prm, b.n, vec2<f32>(px) + 0.5));
#else
    let rgb = b.c.rgb;
#endif
#ifdef BASE
    let under = 1.0 - b.c.a;
    return Out(vec4<f32>(rgb * b.c.a + prm.background.rgb * under, b.c.a + prm.background.a * under));
#else
    return Out(vec4<f32>(rgb * b.c.a, b.c.a));
#endif
#endif
}
#endif

// The compositor's pass (§4.5–4.6), drawn over rectangles ("cells") of the output that every
// surface of the pass covers entirely: per fragment the nearest of the pass's surfaces (and of
// an earlier pass's result), lit in a group's last pass, then laid on the background or blended
// over what lies beneath.
//
// A template, specialised per pass shape at run time (server/src/compositor/shader.rs):
//   //#each surface ... //#end   repeats a block for every surface of the pass, with {{i}},
//                                {{color_binding}} and {{depth_binding}} filled in;
//   //#if NAME ... //#end         keeps a block when the pass has the property NAME, and
//   //#if !NAME ... //#end        when it lacks it:
//     select        several candidates: the depth select runs (otherwise one surface, fetched once),
//                   comparing eye-space depths (fn eye);
//     intermediate  an earlier pass's result is a candidate;
//     last          the group's last pass, which writes the output (else an intermediate);
//     lit           uniform Phong lighting; from_depth: normals reconstructed from depth;
//     depth         the surfaces' depth images are bound;
//     base          the cell's farthest group: laid on the background in the shader, no blending;
//     copy          the 2D compositor: the texel as it is;
//     map           the lighting factor is read from a light map (one surface, per-surface normal);
//     factor        the pass that draws a light map;
//     first         (inside //#each) the pass's first candidate, taken unconditionally;
//   {{N}} is the number of surfaces, {{icolor_binding}}, {{igeom_binding}} the intermediate's.

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
// rect: x, y (output pixels, from the top), width, height; normal: xyz unit (or zero), w > 0.5
// when the surface has a depth image; proj: its declared projection (kind: 0 orthographic,
// 1 perspective; near; far; reversed: 0 or 1), [0, 0, 1, 0] when undeclared.
struct Surf { rect: vec4<i32>, normal: vec4<f32>, proj: vec4<f32>, };
// origin.xy: the render target's origin in output pixels; origin.zw: the intermediate's.
struct Draw { origin: vec4<i32>, surf: array<Surf, {{N}}>, };
@group(0) @binding(0) var<uniform> P: Params;
@group(0) @binding(1) var<uniform> D: Draw;
//#each surface
@group(0) @binding({{color_binding}}) var color{{i}}: texture_2d<f32>;
//#if depth
@group(0) @binding({{depth_binding}}) var depth{{i}}: texture_depth_2d;
//#end
//#end
//#if map
@group(0) @binding({{icolor_binding}}) var lmap: texture_2d<f32>;
//#end
//#if intermediate
@group(0) @binding({{icolor_binding}}) var icolor: texture_2d<f32>;
@group(0) @binding({{igeom_binding}}) var igeom: texture_2d<f32>;
//#end

// One cell per instance: `r` is its rectangle in clip space (x0, y0, x1, y1), drawn as a strip.
@vertex fn vs(@builtin(vertex_index) v: u32, @location(0) r: vec4<f32>) -> @builtin(position) vec4<f32> {
    return vec4<f32>(select(r.x, r.z, (v & 1u) != 0u), select(r.y, r.w, (v & 2u) != 0u), 0.0, 1.0);
}

//#if depth
// A depth texel as the compositor reads it, under projection `p` (a Surf's proj): NaN as the far
// plane's window depth (1, or 0 when reversed), then clamped to [0, 1] (so -inf reads 0 and
// +inf 1). NaN is found by its bits: WGSL lets a compiler assume floats are never NaN.
fn texel(v: f32, p: vec4<f32>) -> f32 {
    let nan = (bitcast<u32>(v) & 0x7fffffffu) > 0x7f800000u;
    return clamp(select(v, select(1.0, 0.0, p.w > 0.5), nan), 0.0, 1.0);
}
//#end

//#if select
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
//#end

//#if from_depth
//#each surface
// Surface {{i}}'s normal at p from its depth (read as texels) by central differences
// (one-sided at edges).
fn dn{{i}}(p: vec2<i32>, size: vec2<i32>) -> vec3<f32> {
    let x0 = max(p.x - 1, 0); let x1 = min(p.x + 1, size.x - 1);
    let y0 = max(p.y - 1, 0); let y1 = min(p.y + 1, size.y - 1);
    var dzdx = 0.0; var dzdy = 0.0;
    let pr = D.surf[{{i}}].proj;
    if (x1 > x0) { dzdx = (texel(textureLoad(depth{{i}}, vec2<i32>(x1, p.y), 0), pr) - texel(textureLoad(depth{{i}}, vec2<i32>(x0, p.y), 0), pr)) / f32(x1 - x0); }
    if (y1 > y0) { dzdy = (texel(textureLoad(depth{{i}}, vec2<i32>(p.x, y1), 0), pr) - texel(textureLoad(depth{{i}}, vec2<i32>(p.x, y0), 0), pr)) / f32(y1 - y0); }
    return normalize(vec3<f32>(-dzdx * P.light_color.w, -dzdy * P.light_color.w, 1.0));
}
//#end
//#end

//#if lit
// The Phong factor ambient + diffuse + specular of a fragment on the plane z = 0 with normal `n`
// (a unit vector, or zero: no direction, ambient only). Shininess 0 makes specular 1, as
// x^0 = 1 for every x (WGSL leaves pow(0, 0) undefined).
fn factor(n: vec3<f32>, frag_px: vec2<f32>) -> f32 {
    if (all(n == vec3<f32>(0.0))) { return P.misc.x; }
    let frag = vec3<f32>(frag_px.x / P.misc.z * 2.0 - 1.0, 1.0 - frag_px.y / P.misc.w * 2.0, 0.0);
    let ld = normalize(P.light_pos.xyz - frag);
    let vd = normalize(P.view_pos.xyz - frag);
    let diffuse = max(dot(n, ld), 0.0);
    let r = reflect(-ld, n);
    let base = max(dot(vd, r), 0.0);
    var specular = 1.0;
    if (P.misc.y != 0.0) { specular = pow(base, P.misc.y); }
    return P.misc.x + diffuse + specular;
}
// Lit colour: factor · light colour · colour.
fn light(c: vec3<f32>, f: f32) -> vec3<f32> {
    return clamp(c * f * P.light_color.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
}
//#end
//#if factor
// A light map: the factor of every pixel for the normal of the draw's surface.
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let px = vec2<i32>(floor(pos.xy)) + D.origin.xy;
    return vec4<f32>(factor(D.surf[0].normal.xyz, vec2<f32>(px) + 0.5), 0.0, 0.0, 0.0);
}
//#end
//#if !factor
//#if last
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
//#end
//#if !last
struct Out { @location(0) color: vec4<f32>, @location(1) geom: vec4<f32>, };
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> Out {
//#end
    let px = vec2<i32>(floor(pos.xy)) + D.origin.xy;
//#if select
    // The nearest candidate so far (eye depth, colour, normal): the intermediate's, else the
    // first surface's taken unconditionally, so no "far" initial value bounds eye depth.
    var best_d: f32;
    var best_c: vec4<f32>;
    var best_n = vec3<f32>(0.0, 0.0, 1.0);
//#if intermediate
    let ip = px - D.origin.zw;
    let g = textureLoad(igeom, ip, 0);
    best_d = g.x;
    best_c = textureLoad(icolor, ip, 0);
    best_n = g.yzw;
//#end
//#each surface
    {
        let r = D.surf[{{i}}].rect;
        // Surface images are in GL row order: bottom row first.
        let sp = vec2<i32>(px.x - r.x, r.y + r.w - 1 - px.y);
        // Eye depth; without a depth image the surface lies at its far plane (1 undeclared).
        var d: f32 = D.surf[{{i}}].proj.z;
        if (D.surf[{{i}}].normal.w > 0.5) { d = eye(textureLoad(depth{{i}}, sp, 0), D.surf[{{i}}].proj); }
//#if first
        {
//#end
//#if !first
        // `<=`: on equal depth the later surface in stacking order wins.
        if (d <= best_d) {
//#end
            best_d = d;
            best_c = textureLoad(color{{i}}, sp, 0);
//#if from_depth
            if (D.surf[{{i}}].normal.w > 0.5) { best_n = dn{{i}}(sp, r.zw); } else { best_n = vec3<f32>(0.0, 0.0, 1.0); }
//#end
//#if !from_depth
            best_n = D.surf[{{i}}].normal.xyz;
//#end
        }
    }
//#end
//#end
//#if !select
//#each surface
    let r = D.surf[{{i}}].rect;
    let sp = vec2<i32>(px.x - r.x, r.y + r.w - 1 - px.y);
    let best_c = textureLoad(color{{i}}, sp, 0);
//#if from_depth
    var best_n = vec3<f32>(0.0, 0.0, 1.0);
    if (D.surf[{{i}}].normal.w > 0.5) { best_n = dn{{i}}(sp, r.zw); }
//#end
//#if !from_depth
    let best_n = D.surf[{{i}}].normal.xyz;
//#end
//#end
//#end
//#if last
//#if copy
    return best_c;
//#end
//#if !copy
//#if map
    let rgb = light(best_c.rgb, textureLoad(lmap, px, 0).x);
//#end
//#if !map
//#if lit
    let rgb = light(best_c.rgb, factor(best_n, vec2<f32>(px) + 0.5));
//#end
//#end
//#if !lit
    let rgb = best_c.rgb;
//#end
//#if base
    let under = 1.0 - best_c.a;
    return vec4<f32>(rgb * best_c.a + P.background.rgb * under, best_c.a + P.background.a * under);
//#end
//#if !base
    return vec4<f32>(rgb * best_c.a, best_c.a);
//#end
//#end
//#end
//#if !last
    var o: Out;
    o.color = best_c;
    o.geom = vec4<f32>(best_d, best_n);
    return o;
//#end
}
//#end

// The compositor's pass (§4.5–4.6): per output fragment, the nearest of this pass's surfaces
// (and of an earlier pass's result), lit in a group's last pass.
//
// A template, specialised per pass shape at run time (server/src/compositor/mod.rs):
//   //#each surface ... //#end   repeats a block for every surface of the pass, with {{i}},
//                                {{color_binding}} and {{depth_binding}} filled in;
//   //#if NAME ... //#end         keeps a block when the pass has the property NAME, and
//   //#if !NAME ... //#end        when it lacks it: intermediate (an earlier pass's result is an
//                                input), last (the group's last pass, which writes the output),
//                                lit, from_depth (normals reconstructed from depth);
//   {{N}} is the number of surfaces, {{EMPTY}} the intermediate's "no fragment" depth, and
//   {{icolor_binding}}, {{igeom_binding}} the intermediate's bindings.

struct Surf { rect: vec4<f32>, normal: vec4<f32>, };
struct Params { light_pos: vec4<f32>, light_color: vec4<f32>, view_pos: vec4<f32>, misc: vec4<f32>, surf: array<Surf, {{N}}>, };
@group(0) @binding(0) var<uniform> P: Params;
//#each surface
@group(0) @binding({{color_binding}}) var color{{i}}: texture_2d<f32>;
@group(0) @binding({{depth_binding}}) var depth{{i}}: texture_depth_2d;
//#end
//#if intermediate
@group(0) @binding({{icolor_binding}}) var icolor: texture_2d<f32>;
@group(0) @binding({{igeom_binding}}) var igeom: texture_2d<f32>;
//#end

@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

//#if from_depth
//#each surface
// Surface {{i}}'s normal at p from its depth by central differences (one-sided at edges).
fn dn{{i}}(p: vec2<i32>, size: vec2<i32>) -> vec3<f32> {
    let x0 = max(p.x - 1, 0); let x1 = min(p.x + 1, size.x - 1);
    let y0 = max(p.y - 1, 0); let y1 = min(p.y + 1, size.y - 1);
    var dzdx = 0.0; var dzdy = 0.0;
    if (x1 > x0) { dzdx = (textureLoad(depth{{i}}, vec2<i32>(x1, p.y), 0) - textureLoad(depth{{i}}, vec2<i32>(x0, p.y), 0)) / f32(x1 - x0); }
    if (y1 > y0) { dzdy = (textureLoad(depth{{i}}, vec2<i32>(p.x, y1), 0) - textureLoad(depth{{i}}, vec2<i32>(p.x, y0), 0)) / f32(y1 - y0); }
    return normalize(vec3<f32>(-dzdx * P.light_color.w, -dzdy * P.light_color.w, 1.0));
}
//#end
//#end

//#if last
//#if lit
// Phong: (ambient + diffuse + specular) · light colour · colour, the fragment on the plane z = 0.
fn light(c: vec3<f32>, n_raw: vec3<f32>, frag_px: vec2<f32>) -> vec3<f32> {
    var n = vec3<f32>(0.0);
    if (length(n_raw) > 0.0) { n = normalize(n_raw); }
    let frag = vec3<f32>(frag_px.x / P.misc.z * 2.0 - 1.0, 1.0 - frag_px.y / P.misc.w * 2.0, 0.0);
    let ld = normalize(P.light_pos.xyz - frag);
    let vd = normalize(P.view_pos.xyz - frag);
    let diffuse = max(dot(n, ld), 0.0);
    let r = reflect(-ld, n);
    let base = max(dot(vd, r), 0.0);
    var specular = 1.0;
    if (P.misc.y != 0.0) { specular = pow(base, P.misc.y); }
    let f = P.misc.x + diffuse + specular;
    return clamp(c * f * P.light_color.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
}
//#end
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
//#end
//#if !last
struct Out { @location(0) color: vec4<f32>, @location(1) geom: vec4<f32>, };
@fragment fn fs(@builtin(position) pos: vec4<f32>) -> Out {
//#end
    let px = vec2<i32>(floor(pos.xy));
    var best_d: f32 = {{EMPTY}};
    var best_c = vec4<f32>(0.0);
    var best_n = vec3<f32>(0.0, 0.0, 1.0);
    var found = false;
//#if intermediate
    let g = textureLoad(igeom, px, 0);
    if (g.x < 2.0) { best_d = g.x; best_c = textureLoad(icolor, px, 0); best_n = g.yzw; found = true; }
//#end
//#each surface
    {
        let r = P.surf[{{i}}].rect;
        let l = vec2<i32>(px.x - i32(r.x), px.y - i32(r.y));
        let size = vec2<i32>(i32(r.z), i32(r.w));
        if (l.x >= 0 && l.y >= 0 && l.x < size.x && l.y < size.y) {
            // Surface images are in GL row order: bottom row first.
            let sp = vec2<i32>(l.x, size.y - 1 - l.y);
            let has_depth = P.surf[{{i}}].normal.w > 0.5;
            var d: f32 = 1.0;
            if (has_depth) { d = textureLoad(depth{{i}}, sp, 0); }
            // `<=`: on equal depth the later surface in stacking order wins.
            if (d <= best_d) {
                best_d = d;
                best_c = textureLoad(color{{i}}, sp, 0);
//#if from_depth
                if (has_depth) { best_n = dn{{i}}(sp, size); } else { best_n = vec3<f32>(0.0, 0.0, 1.0); }
//#end
//#if !from_depth
                best_n = P.surf[{{i}}].normal.xyz;
//#end
                found = true;
            }
        }
    }
//#end
    if (!found) { discard; }
//#if last
//#if lit
    let rgb = light(best_c.rgb, best_n, pos.xy);
//#end
//#if !lit
    let rgb = best_c.rgb;
//#end
    return vec4<f32>(rgb * best_c.a, best_c.a);
//#end
//#if !last
    var o: Out;
    o.color = best_c;
    o.geom = vec4<f32>(best_d, best_n);
    return o;
//#end
}

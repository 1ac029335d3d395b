// The background of the compositor's cells that no surface covers: one premultiplied colour,
// written over each cell (one instance per cell, its clip-space rectangle in `r`).
struct Params {
    light_pos: vec4<f32>,
    light_color: vec4<f32>,
    view_pos: vec4<f32>,
    misc: vec4<f32>,
    background: vec4<f32>,
};
@group(0) @binding(0) var<uniform> P: Params;
@vertex fn vs(@builtin(vertex_index) v: u32, @location(0) r: vec4<f32>) -> @builtin(position) vec4<f32> {
    return vec4<f32>(select(r.x, r.z, (v & 1u) != 0u), select(r.y, r.w, (v & 2u) != 0u), 0.0, 1.0);
}
@fragment fn fs() -> @location(0) vec4<f32> {
    return P.background;
}

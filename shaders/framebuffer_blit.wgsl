// glBlitFramebuffer's colour copy: each destination pixel samples the source at the point its
// centre maps to (the rectangles' corners in the order given, so flips fall out), with the
// nearest or linear sampler, clamped to the edge.
struct Params {
    // Destination corner 0, and source texels per destination pixel along x and y.
    dst0: vec2<f32>,
    scale: vec2<f32>,
    // Source corner 0, and one over the source image's size.
    src0: vec2<f32>,
    inv_size: vec2<f32>,
};

@group(0) @binding(0) var src: texture_2d<f32>;
@group(0) @binding(1) var smp: sampler;
@group(0) @binding(2) var<uniform> p: Params;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
    let s = p.src0 + (pos.xy - p.dst0) * p.scale;
    return textureSampleLevel(src, smp, s * p.inv_size, 0.0);
}

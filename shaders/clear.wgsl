// glClear with a scissor or partial write masks: a full-screen triangle whose colour, depth
// and stencil writes are governed by the pipeline's masks, the scissor and the reference.
struct ClearParams {
    color: vec4<f32>,
    depth: f32,
};

@group(0) @binding(0) var<uniform> params: ClearParams;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, params.depth, 1.0);
}

@fragment
fn fs() -> @location(0) vec4<f32> {
    return params.color;
}

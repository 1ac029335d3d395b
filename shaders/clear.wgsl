// glClear with a scissor or partial write masks: a full-screen triangle whose colour, depth
// and stencil writes are governed by the pipeline's masks, the scissor and the reference.
// Each colour slot (draw buffer) gets its own colour: the clear colour as its image stores it.
struct ClearParams {
    colors: array<vec4<f32>, 8>,
    depth: f32,
};

@group(0) @binding(0) var<uniform> params: ClearParams;

struct Out {
    @location(0) c0: vec4<f32>,
    @location(1) c1: vec4<f32>,
    @location(2) c2: vec4<f32>,
    @location(3) c3: vec4<f32>,
    @location(4) c4: vec4<f32>,
    @location(5) c5: vec4<f32>,
    @location(6) c6: vec4<f32>,
    @location(7) c7: vec4<f32>,
};

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, params.depth, 1.0);
}

@fragment
fn fs() -> Out {
    let c = params.colors;
    return Out(c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]);
}

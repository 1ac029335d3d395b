// A frame copied through host memory (drivers that cannot share images between devices): any
// depth format is read as a 32-bit float into a colour image, which can be copied to a buffer
// (wgpu cannot copy Depth24Plus images out).
@group(0) @binding(0) var src: texture_depth_2d;

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(textureLoad(src, vec2<i32>(p.xy), 0), 0.0, 0.0, 1.0);
}

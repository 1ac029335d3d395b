// glGenerateMipmap of a 3D image (GL_OES_texture_3D): each slice of a level is the 2x2x2 box
// filter of the level above, taken with one trilinear sample at the shared corner of the eight
// source texels. The instance is the slice drawn.
@group(0) @binding(0) var src: texture_3d<f32>;
@group(0) @binding(1) var smp: sampler;

struct VsOut {
    @builtin(position) pos: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) @interpolate(flat) slice: u32,
};

@vertex
fn vs(@builtin(vertex_index) i: u32, @builtin(instance_index) slice: u32) -> VsOut {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    var out: VsOut;
    out.pos = vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
    out.uv = vec2<f32>(uv.x, 1.0 - uv.y);
    out.slice = slice;
    return out;
}

@fragment
fn fs(in: VsOut) -> @location(0) vec4<f32> {
    let slices = max(textureDimensions(src).z / 2u, 1u);
    let r = (f32(in.slice) + 0.5) / f32(slices);
    return textureSampleLevel(src, smp, vec3<f32>(in.uv, r), 0.0);
}
